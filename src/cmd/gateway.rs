//! `vpx-efis gateway`: the XFSp bridge with no terminal UI, for a box that only bridges.
//!
//! Link → model (every received packet applied, every connection event noted) →
//! gateway → UDP, and commands from the network back to the unit. One line per notable
//! event (the model's event log: connection, faults, every network command) goes to
//! standard error. Without `--port` the built-in virtual VP-X runs over an in-process
//! pipe. Runs until SIGINT, SIGTERM or SIGHUP (Ctrl-C, Ctrl-Break or a closed console
//! on Windows), then stops any motor it was running and exits 128 + the signal's number.

use std::io::Write;
use std::net::Ipv4Addr;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::Context;
use clap::Args;
use crossbeam_channel::{select, unbounded};

use crate::app::queries::QueryPacer;
use crate::app::{StopGate, Terminated};
use crate::audit::Origin;
use crate::cmd::common::{PortArgs, XfspArgs};
use crate::control::MotorStreamer;
use crate::exchange::Rereader;
use crate::link::{Connector, Link, LinkEvent, PortAddr, RxItem, port_connector};
use crate::model::{LogEntry, LogLevel, Model, Source};
use crate::protocol::message::Packet;
use crate::sim::SimHandle;
use crate::xfsp::gateway::{Gateway, GatewayConfig};
use crate::xfsp::net::{Target, XfspNet};

/// The longest the loop sleeps, so a stop request is noticed promptly.
const MAX_WAIT: Duration = Duration::from_millis(100);

/// Everything the bridge needs, independent of the command line (tests build it).
#[derive(Debug, Clone)]
pub struct BridgeOptions {
    /// A serial path or TCP bridge, or `None` for the built-in virtual VP-X.
    pub port: Option<PortAddr>,
    pub baud: u32,
    pub scenario: String,
    pub target: Target,
    pub iface: Ipv4Addr,
    pub gateway: GatewayConfig,
    pub record: Option<PathBuf>,
    /// The audit log's folder ([`crate::audit`]): every command sent to the unit.
    pub audit: Option<PathBuf>,
}

impl BridgeOptions {
    pub fn from_args(args: &GatewayArgs) -> anyhow::Result<BridgeOptions> {
        // The bridge is always on the network: no --xfsp means the default group.
        let mut xfsp = crate::app::XfspOptions::from(args.xfsp.clone());
        xfsp.xfsp
            .get_or_insert_with(|| crate::xfsp::net::DEFAULT_TARGET.to_string());
        let (target, iface, gateway) =
            crate::app::xfsp_setup(&xfsp)?.ok_or_else(|| anyhow::anyhow!("no XFSp target"))?;
        Ok(BridgeOptions {
            port: args.port.port.clone(),
            baud: args.port.baud,
            scenario: args.port.scenario.clone(),
            target,
            iface,
            gateway,
            record: args.record.clone(),
            audit: crate::check::report::default_dir(),
        })
    }
}

#[derive(Debug, Args)]
pub struct GatewayArgs {
    #[command(flatten)]
    pub port: PortArgs,
    #[command(flatten)]
    pub xfsp: XfspArgs,
    /// Record every serial byte to a capture file.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
}

pub fn run(args: GatewayArgs) -> anyhow::Result<()> {
    let opts = BridgeOptions::from_args(&args)?;
    // SIGINT, SIGTERM, and SIGHUP (a dropped ssh session) stop the bridge and its motor
    // streams cleanly, then the process exits 128 + n.
    let stop = crate::app::stop_flag("gateway-stop", |_| {})?;
    run_bridge(&opts, &stop.raised, |line| {
        eprintln!("vpx-efis gateway: {line}")
    })?;
    match stop.by() {
        Some(t) => Err(Terminated(t).into()),
        None => Ok(()),
    }
}

/// Runs the bridge until `stop` is set. `say` gets one line per notable event.
pub fn run_bridge(
    opts: &BridgeOptions,
    stop: &AtomicBool,
    mut say: impl FnMut(&str),
) -> anyhow::Result<()> {
    let start = Instant::now();
    let (connector, source, _sim): (Connector, Source, Option<SimHandle>) = match &opts.port {
        Some(p) => (
            port_connector(p, opts.baud),
            Source::Serial {
                path: p.to_string(),
            },
            None,
        ),
        None => {
            let (source, connector, handle) = crate::app::builtin_sim(&opts.scenario)?;
            (connector, source, Some(handle))
        }
    };
    // The app's recorder: flushed by its own thread at least once a second while the
    // link is idle, and offsets kept in order across the reader and writer threads.
    let mut capture = match &opts.record {
        Some(path) => {
            let r = crate::app::Recorder::create(path)?;
            r.start(start)
                .with_context(|| format!("cannot write the capture file {}", path.display()))?;
            Some(r)
        }
        None => None,
    };
    let net = XfspNet::open(&opts.target, opts.iface)
        .with_context(|| format!("cannot open XFSp {} on {}", opts.target, opts.iface))?;
    say(&format!(
        "XFSp {} from {}, source id {:#06x}, {:?}, {}{}",
        opts.target,
        net.local_addr()
            .map_or_else(|_| "?".to_string(), |a| a.to_string()),
        opts.gateway.source_id,
        opts.gateway.cert,
        opts.gateway.control.describe(),
        match &source {
            Source::Simulated { scenario } => format!(", SIMULATED VP-X ({scenario})"),
            Source::Serial { path } => format!(", VP-X on {path}"),
            Source::Replay { file } => format!(", replay {file}"),
        }
    ));

    let (ev_tx, ev_rx) = unbounded();
    let link = Link::start(connector, move |e| {
        let _ = ev_tx.send(e);
    });
    let unit = link.handle();
    // As on the page: a panic anywhere sends the stop messages first, and unwinding
    // out of this function sends them again before the link closes.
    // Everything the loop sends goes through the gate, which the hook's stop closes
    // to moves, so a resend decided before a panic cannot follow its stop.
    let audit = match &opts.audit {
        Some(dir) => Some(
            crate::audit::Audit::start(dir.clone())
                .context("cannot start the audit log's thread")?
                .0,
        ),
        None => None,
    };
    let gate = Arc::new(StopGate::with_audit(unit.clone(), audit.clone()));
    let hook_gate = gate.clone();
    crate::app::set_emergency_stop(move || {
        hook_gate.emergency_stop();
        std::thread::sleep(Duration::from_millis(50));
    });
    crate::app::install_panic_hook();
    let _stop_on_unwind = StopOnDrop(unit.clone());
    let mut model = Model::new(source);
    let mut gw = Gateway::new(opts.gateway.clone(), start);
    let mut printed: Option<LogEntry> = None;
    // The bridge asks for names and specs at every connect, as the page does, so the
    // network sees the circuits' real labels and breakers. Its command numbers start
    // high so they rarely meet the gateway's own motor-stream numbers.
    let mut asking = Asking::default();
    let mut cnt: u8 = 0x80;
    let mut net_error_said = false;

    while !stop.load(Ordering::SeqCst) && !crate::app::panicked() {
        let now = Instant::now();
        let deadline = asking
            .next_deadline(&model, now)
            .map_or(gw.next_deadline(), |d| d.min(gw.next_deadline()));
        let wait = deadline.saturating_duration_since(now).min(MAX_WAIT);
        let mut to_unit: Vec<Packet> = Vec::new();
        let mut events = Vec::new();
        select! {
            recv(ev_rx) -> e => if let Ok(e) = e { events.push(e) },
            recv(net.incoming()) -> d => if let Ok(d) = d {
                to_unit.extend(gw.receive(&d.bytes, &mut model, d.at));
            },
            default(wait) => {},
        }
        events.extend(ev_rx.try_iter());
        for e in events {
            match &e {
                LinkEvent::Connected { .. } => {
                    // A run cut off by a pulled cable is told to stop first (ahead of
                    // everything this pass queues).
                    gate.send(Origin::Page, MotorStreamer::emergency_stop_packets());
                    asking.connected(Instant::now());
                }
                LinkEvent::Disconnected { .. } | LinkEvent::OpenFailed { .. } => asking.link_down(),
                _ => {}
            }
            apply(&mut model, &mut gw, &mut capture, e, &mut to_unit);
        }
        to_unit.extend(asking.due(&model, Instant::now(), || {
            cnt = cnt.wrapping_add(1) | 0x80;
            cnt
        }));
        while let Ok(d) = net.incoming().try_recv() {
            to_unit.extend(gw.receive(&d.bytes, &mut model, d.at));
        }
        let step = gw.tick(&mut model, Instant::now());
        to_unit.extend(step.to_unit);
        gate.send(Origin::Xfsp, to_unit);
        match net.send_all(&step.datagrams) {
            Err(e) if !net_error_said => {
                say(&format!("cannot send on XFSp: {e}"));
                net_error_said = true;
            }
            Ok(()) if !step.datagrams.is_empty() => net_error_said = false,
            _ => {}
        }
        if let Some(why) = audit.as_ref().and_then(crate::audit::Audit::take_problem) {
            say(&why);
        }
        print_new_events(&model, &mut printed, &mut say);
    }

    let now = Instant::now();
    // Its own stops on the way out, whoever ran the motor.
    gate.send(Origin::Page, gw.shutdown(&mut model, now));
    print_new_events(&model, &mut printed, &mut say);
    let s = gw.stats();
    say(&format!(
        "stopped: {} datagrams sent, received {} fresh, {} duplicate, {} out of order, {} malformed; {} commands taken, {} refused, {} refused as not allowed ({})",
        s.datagrams_built,
        s.rx.fresh,
        s.rx.duplicate,
        s.rx.out_of_order,
        s.rx.malformed,
        s.commands_taken,
        s.commands_refused,
        s.commands_not_allowed,
        opts.gateway.control.describe()
    ));
    // Writes whatever is queued (the stop messages) before the threads end.
    link.shutdown();
    crate::app::clear_emergency_stop();
    if let Some(c) = capture.as_mut() {
        c.flush();
    }
    Ok(())
}

fn apply(
    model: &mut Model,
    gw: &mut Gateway,
    capture: &mut Option<crate::app::Recorder>,
    e: LinkEvent,
    to_unit: &mut Vec<Packet>,
) {
    let now = Instant::now();
    match e {
        LinkEvent::Rx {
            at, item, stats, ..
        } => {
            model.note_decoder(stats);
            match item {
                RxItem::Packet(p) => model.apply_packet(at, &p),
                RxItem::Malformed(_) => model.note_malformed(),
                _ => {}
            }
        }
        LinkEvent::Connected { port } => model.note_connected(now, port),
        LinkEvent::Disconnected { reason } | LinkEvent::OpenFailed { reason } => {
            model.note_link_lost(now, reason)
        }
        LinkEvent::Tx {
            at,
            packet: Some(p),
            ..
        } => model.note_sent(at, &p),
        LinkEvent::Tx { .. } => {}
        LinkEvent::WriteError { at, reason } => {
            model.note_write_error(at, reason);
            to_unit.extend(gw.on_link_error(model, at));
        }
        LinkEvent::Bytes { at, dir, bytes } => {
            if let Some(c) = capture.as_mut()
                && let Err(e) = c.record(at, dir, &bytes)
            {
                model.note_write_error(at, format!("capture file: {e}"));
                *capture = None;
            }
        }
    }
}

/// What the bridge asks the unit, as the page does: the connect-time queries and the
/// minute's refresh ([`QueryPacer`]), and, from a few seconds after a connect, again
/// for every setting the connect-time queries did not bring ([`Rereader`]), rather
/// than leaving the network without labels and breakers until the minute is up.
#[derive(Default)]
struct Asking {
    pacer: QueryPacer,
    rereader: Rereader,
}

impl Asking {
    fn connected(&mut self, now: Instant) {
        self.pacer.start(now);
        self.rereader.connected(now);
    }

    fn link_down(&mut self) {
        self.pacer.stop();
        self.rereader.link_down();
    }

    fn next_deadline(&self, model: &Model, now: Instant) -> Option<Instant> {
        [
            self.pacer.next_deadline(),
            self.rereader.next_deadline(model, now),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    fn due(
        &mut self,
        model: &Model,
        now: Instant,
        mut next_cnt: impl FnMut() -> u8,
    ) -> Vec<Packet> {
        let mut out = self.pacer.due(now, model, &mut next_cnt);
        for q in self.rereader.due(model, now) {
            out.push(Packet::request(next_cnt(), q));
        }
        out
    }
}

/// Sends the stop messages when dropped: the bridge's drop guard for an unwinding
/// panic, declared after the link so it runs while the link can still write.
struct StopOnDrop(crate::link::LinkHandle);

impl Drop for StopOnDrop {
    fn drop(&mut self) {
        for p in MotorStreamer::emergency_stop_packets() {
            let _ = self.0.send(p);
        }
    }
}

/// Says each model log entry once, in order.
fn print_new_events(model: &Model, printed: &mut Option<LogEntry>, say: &mut impl FnMut(&str)) {
    let from = printed
        .as_ref()
        .and_then(|last| model.events.iter().rposition(|e| e == last))
        .map_or(0, |i| i + 1);
    for e in model.events.iter().skip(from) {
        say(&format!("{}{}", prefix(e.level), e.text));
    }
    if let Some(last) = model.events.back() {
        *printed = Some(last.clone());
    }
    let _ = std::io::stderr().flush();
}

/// Alerts stand out in a log file; plain information needs no word.
fn prefix(level: LogLevel) -> &'static str {
    match level {
        LogLevel::Info => "",
        LogLevel::Warning => "warning: ",
        LogLevel::Alert => "ALERT: ",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit that answered none of the connect-time queries (noise on the line, a
    /// unit still booting) is asked again a few seconds later, not a minute later.
    #[test]
    fn settings_lost_at_connect_are_asked_again_within_seconds() {
        let t0 = Instant::now();
        let model = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        let mut asking = Asking::default();
        asking.connected(t0);
        let mut cnt = 0u8;
        let mut next = || {
            cnt = cnt.wrapping_add(1);
            cnt
        };
        // The connect-time queries go out over the first second or so.
        let mut t = t0;
        while t < t0 + Duration::from_secs(2) {
            asking.due(&model, t, &mut next);
            t += Duration::from_millis(10);
        }
        let grace = t0 + crate::exchange::CONNECT_GRACE;
        let deadline = asking.next_deadline(&model, t).expect("something to ask");
        assert!(deadline <= grace, "next ask at +{:?}", deadline - t0);
        let again = asking.due(&model, grace, &mut next);
        assert!(!again.is_empty(), "nothing asked again at the grace's end");
    }
}

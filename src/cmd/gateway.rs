//! `vpx-efis gateway`: the XFSp bridge with no terminal UI, for a box that only bridges.
//!
//! The app with no screen ([`App`]): link → model (every received packet applied,
//! every connection event noted) → gateway → UDP, and commands from the network back
//! to the unit through the app's stop gate. One line per notable
//! event (the model's event log: connection, faults, every network command) goes to
//! standard error. Without `--port` the built-in virtual VP-X runs over an in-process
//! pipe. Runs until SIGINT, SIGTERM or SIGHUP (Ctrl-C, Ctrl-Break or a closed console
//! on Windows), then stops any motor it was running and exits 128 + the signal's number.

use std::io::Write;
use std::net::Ipv4Addr;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use clap::Args;

use crate::app::{App, AppOptions, Recorder, Terminated};
use crate::cmd::common::LinkArgs;
use crate::link::{Connector, PortAddr, port_connector};
use crate::model::{LogEntry, LogLevel, Model, Source};
use crate::sim::SimHandle;
use crate::xfsp::gateway::GatewayConfig;
use crate::xfsp::net::Target;

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
    /// The logbook, and the aircraft ([`crate::logbook`]): every command sent to the
    /// unit.
    pub logbook: Option<crate::logbook::Target>,
}

impl BridgeOptions {
    pub fn from_args(args: &GatewayArgs) -> anyhow::Result<BridgeOptions> {
        // The bridge is always on the network: no --xfsp means the default group.
        let mut xfsp = crate::app::XfspOptions::from(args.link.xfsp.clone());
        xfsp.xfsp
            .get_or_insert_with(|| crate::xfsp::net::DEFAULT_TARGET.to_string());
        let (target, iface, gateway) =
            crate::app::xfsp_setup(&xfsp)?.ok_or_else(|| anyhow::anyhow!("no XFSp target"))?;
        Ok(BridgeOptions {
            port: args.link.port.port.clone(),
            baud: args.link.port.baud,
            scenario: args.link.port.scenario.clone(),
            target,
            iface,
            gateway,
            record: args.link.record.clone(),
            logbook: crate::logbook::target(),
        })
    }
}

#[derive(Debug, Args)]
pub struct GatewayArgs {
    #[command(flatten)]
    pub link: LinkArgs,
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
///
/// The bridge is the app with no screen: the same link sink and model, the same loop
/// ([`App::serve_until`]), the same queries at connect and re-read after a loss of
/// communication, the same stop gate, panic path and audit log as the page.
pub fn run_bridge(
    opts: &BridgeOptions,
    stop: &AtomicBool,
    mut say: impl FnMut(&str),
) -> anyhow::Result<()> {
    let (connector, source, sim): (Connector, Source, Option<SimHandle>) = match &opts.port {
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
    // A path that cannot be written fails here, before the port is opened.
    let recorder = opts.record.as_deref().map(Recorder::create).transpose()?;
    let unit = match &source {
        Source::Simulated { scenario } => format!(", SIMULATED VP-X ({scenario})"),
        Source::Serial { path } => format!(", VP-X on {path}"),
        Source::Replay { file } => format!(", replay {file}"),
    };
    let options = AppOptions {
        logbook: opts.logbook.clone(),
        ..AppOptions::default()
    };
    let mut app = match recorder {
        Some(r) => App::recording(source, connector, options, r),
        None => App::new(source, connector, options),
    };
    app.enable_xfsp(&opts.target, opts.iface, opts.gateway.clone())?;
    say(&format!(
        "XFSp {} from {}, source id {:#06x}, {:?}, {}{unit}",
        opts.target,
        app.xfsp_local_addr()
            .map_or_else(|| "?".to_string(), |a| a.to_string()),
        opts.gateway.source_id,
        opts.gateway.cert,
        opts.gateway.control.describe(),
    ));
    // As on the page: a panic anywhere sends every motor's stop through the app's
    // gate first (audited), and nothing queued after it moves a motor.
    crate::app::install_panic_hook();
    app.arm_emergency_stop();
    let mut printed: Option<LogEntry> = None;
    app.serve_until(stop, MAX_WAIT, |app| {
        print_new_events(&app.model(), &mut printed, &mut say)
    });
    // Its own stops on the way out, whoever ran the motor, written before the link
    // closes.
    let stats = app.xfsp_stats().unwrap_or_default();
    app.shutdown();
    crate::app::clear_emergency_stop();
    if let Some(sim) = sim {
        sim.stop();
    }
    let s = stats;
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
    Ok(())
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

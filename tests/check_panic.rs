//! Panic safety of the headless check (`vpx-efis check`), in a process of its own: the
//! panic hook is global, and a panic here must not stop the motors of other tests.
//!
//! The check runs on a thread of its own against the virtual VP-X on a real
//! pseudo-terminal, with a tap recording every byte it puts on the wire. The panic is
//! the check's own: its output, which it flushes after every pass of its loop, panics
//! once told to, while the check is running a motor. Nothing in the program is there
//! for the test.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::io::Write;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crossbeam_channel::unbounded;
use vpx_efis::app::{HeadlessCheck, run_headless_with};
use vpx_efis::check::state::Step;
use vpx_efis::check::{Options, Timing};
use vpx_efis::link;
use vpx_efis::protocol::message::Message;
use vpx_efis::protocol::{Decoder, Event as DecEvent, Packet};
use vpx_efis::sim::{self, SimOptions};

mod page_rig;
use page_rig::{Tap, Wire};

/// The check's standard output, which panics at its next flush once `armed`.
struct Output {
    armed: Arc<AtomicBool>,
    panicked_at: Arc<std::sync::Mutex<Option<Instant>>>,
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        if self.armed.load(Ordering::SeqCst) {
            *self.panicked_at.lock().unwrap() = Some(Instant::now());
            panic!("simulated crash in the headless check's loop");
        }
        Ok(())
    }
}

/// Every flap and trim move on the wire from entry `from`, with when it went and
/// whether it runs the motor (`on`).
fn moves(wire: &Wire, from: usize) -> Vec<(Instant, &'static str, bool)> {
    let wire = wire.lock().unwrap();
    let mut dec = Decoder::new();
    let mut out = Vec::new();
    for (at, bytes) in &wire[from..] {
        dec.push(bytes, |e| {
            if let DecEvent::Frame(f) = e
                && let Ok(p) = Packet::parse(&f)
            {
                match p.message {
                    Message::TrimMove(m) => out.push((*at, "trim", m.on)),
                    Message::FlapMove(m) => out.push((*at, "flaps", m.on)),
                    _ => {}
                }
            }
        });
    }
    out
}

/// A panic in the check's own loop while it runs a motor: the hook's stop goes out
/// through the app's one stop gate (at once, for every motor), nothing moves a motor
/// after it, the unit stops by that message (not by starving), and the audit log has
/// the stop as the panic's.
#[test]
fn a_panic_in_the_headless_check_mid_run_stops_the_motor_through_the_gate_audited() {
    let (sim_side, check_side) = link::duplex_pipe(Duration::from_millis(20));
    let sim = sim::spawn(
        SimOptions::new(sim::load_scenario("demo").unwrap()),
        Box::new(sim_side.reader),
        Box::new(sim_side.writer),
    );
    let wire: Wire = Arc::default();
    let to_sim = Arc::new(std::sync::Mutex::new(check_side.writer));
    let from_sim = Arc::new(std::sync::Mutex::new(check_side.reader));
    let tap = Tap::start(to_sim, from_sim, wire.clone());
    let dir = tempfile::tempdir().unwrap();
    let reports = dir.path().join("reports");
    // The audit log is the logbook's; this one, not the one beside the config file.
    let logbook = dir.path().join("logbook.sqlite");
    vpx_efis::logbook::set_target(Some(vpx_efis::logbook::Target {
        path: logbook.clone(),
        aircraft: None,
    }));
    let h = HeadlessCheck {
        port: Some(tap.slave_path.parse().unwrap()),
        baud: 57_600,
        scenario: "demo".into(),
        options: Options {
            // The motors alone, each run long enough to panic in the middle of it.
            skip: vec![Step::Switches, Step::Circuits, Step::Loads],
            yes: true,
            loads_file: Some(dir.path().join("loads.toml")),
            timing: Timing {
                motor_run: Duration::from_secs(3),
                ..Timing::default()
            },
            ..Options::default()
        },
        report: Some(reports.clone()),
    };
    let armed = Arc::new(AtomicBool::new(false));
    let panicked_at = Arc::new(std::sync::Mutex::new(None));
    let check = {
        let out = Output {
            armed: armed.clone(),
            panicked_at: panicked_at.clone(),
        };
        std::thread::spawn(move || {
            let (_typed, lines) = unbounded();
            let (_signal, terminations) = unbounded();
            let mut out = out;
            run_headless_with(h, &lines, &terminations, &mut out)
        })
    };

    // A run under way for 300 ms (a few resends in, well before its end), not the
    // short probe the check makes first near an endpoint.
    let running = |s: &sim::SimStats| s.flap_running || s.pitch_trim_running;
    let end = Instant::now() + Duration::from_secs(30);
    let mut since: Option<Instant> = None;
    while since.is_none_or(|t| t.elapsed() < Duration::from_millis(300)) {
        assert!(Instant::now() < end, "the check never ran a motor");
        if check.is_finished() {
            panic!("the check ended before running a motor: {:?}", check.join());
        }
        since = match (running(&sim.stats()), since) {
            (true, None) => Some(Instant::now()),
            (true, s) => s,
            (false, _) => None,
        };
        std::thread::sleep(Duration::from_millis(10));
    }
    let from = wire.lock().unwrap().len();
    armed.store(true, Ordering::SeqCst);
    let joined = check.join();
    assert!(joined.is_err(), "the check's loop did not panic");
    assert!(vpx_efis::app::panicked());
    let panicked = panicked_at.lock().unwrap().expect("panicked in the flush");
    std::thread::sleep(Duration::from_millis(600));
    vpx_efis::app::clear_emergency_stop();

    let after = moves(&wire, from);
    let first_stop = after
        .iter()
        .position(|(at, _, on)| !on && *at >= panicked)
        .unwrap_or_else(|| panic!("no stop on the wire after the panic: {after:?}"));
    let (at, _, _) = after[first_stop];
    assert!(
        at.saturating_duration_since(panicked) < Duration::from_millis(200),
        "the stop came {:?} after the panic",
        at.saturating_duration_since(panicked)
    );
    // The hook's stop is of every motor at once: flaps, pitch and roll trim.
    let stops: Vec<&str> = after[first_stop..]
        .iter()
        .take(3)
        .map(|(_, m, _)| *m)
        .collect();
    assert_eq!(stops, ["flaps", "trim", "trim"], "{after:?}");
    assert!(
        after[first_stop..].iter().all(|(_, _, on)| !on),
        "a move went out after the panic's stop: {after:?}"
    );
    let s = sim.stats();
    assert!(!s.flap_running && !s.pitch_trim_running, "still running");
    assert_eq!(
        (s.flap_starvations, s.pitch_trim_starvations),
        (0, 0),
        "stopped by the message, not by starving"
    );

    // The audit log has the hook's stops, said as the panic's, and sent.
    let text = vpx_efis::logbook::jsonl::all_audit_lines(&logbook)
        .expect("an audit log")
        .join("\n");
    let panic_stops: Vec<&str> = text
        .lines()
        .filter(|l| l.contains(r#""origin":"panic""#))
        .collect();
    assert_eq!(panic_stops.len(), 3, "{text}");
    assert!(
        panic_stops
            .iter()
            .all(|l| l.contains(r#""result":"sent""#) && l.contains("MOVE")),
        "{text}"
    );
    tap.unplug();
    sim.stop();
}

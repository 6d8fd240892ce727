//! SIGTERM and SIGHUP during a trim run, against the real `vpx-efis` binary: the page
//! runs on a pseudo-terminal that is its controlling terminal (as in a terminal
//! window), its `--port` is the slave of a second pty whose master the test taps on the
//! way to the virtual VP-X. The stop must be on the wire before the process is gone,
//! the terminal must be given back (alternate screen left, cursor shown, echo and
//! line mode on again), and the exit status must be 128 + the signal's number.
// Needs pseudo-terminals and POSIX signals, which only Unix has.
#![cfg(unix)]

use std::process::Child;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use vpx_efis::link;
use vpx_efis::protocol::message::{Message, TrimType};
use vpx_efis::sim::{self, Scenario, SimHandle, SimOptions};

mod page_rig;
use page_rig::terminal::{Term, find, page};
use page_rig::{SCENARIO, Tap, Wire, packets};

struct Bench {
    sim: SimHandle,
    wire: Wire,
    tap: Tap,
}

/// The virtual VP-X behind a tapped pty, as in `page_rig`.
fn bench() -> Bench {
    let (sim_side, page_side) = link::duplex_pipe(Duration::from_millis(20));
    let sim = sim::spawn(
        SimOptions::new(Scenario::from_toml(SCENARIO).unwrap()),
        Box::new(sim_side.reader),
        Box::new(sim_side.writer),
    );
    let wire: Wire = Arc::default();
    let tap = Tap::start(
        Arc::new(Mutex::new(page_side.writer)),
        Arc::new(Mutex::new(page_side.reader)),
        wire.clone(),
    );
    Bench { sim, wire, tap }
}

/// Pitch TRIM_MOVEs the page put on the wire: (when, on).
fn pitch_moves(wire: &Wire) -> Vec<(Instant, bool)> {
    (packets(&wire.lock().unwrap()).into_iter())
        .filter_map(|(at, p)| match p.message {
            Message::TrimMove(m) if m.trim_type == TrimType::Pitch => Some((at, m.on)),
            _ => None,
        })
        .collect()
}

fn wait_exit(child: &mut Child, limit: Duration) -> (std::process::ExitStatus, Instant) {
    let end = Instant::now() + limit;
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return (s, Instant::now());
        }
        if Instant::now() > end {
            let _ = child.kill();
            panic!("the page did not exit within {limit:?} of the signal");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Runs the pitch trim from the keyboard, sends `signal`, and checks everything.
fn signal_during_a_trim_run(signal: libc::c_int, status: i32) {
    let b = bench();
    let (mut term, slave) = Term::open();
    let mut child = page(&["--port", &b.tap.slave_path], slave);

    // The device list is up once the scenario's names are on the screen (drawn as
    // changes, so looked for one by one).
    let names: &[&[u8]] = &[b"Nav Lt", b"GPS 1"];
    term.wait_for("its device list", names, 0, Duration::from_secs(10));
    std::thread::sleep(Duration::from_millis(300));
    // Motors sort last and only the pitch trim is fitted: `j` stops on its row.
    term.typed(&[b'j'; 50]);
    std::thread::sleep(Duration::from_millis(200));
    // Hold `u` as a terminal's auto-repeat does, until the trim runs.
    let start = Instant::now();
    while !b.sim.stats().pitch_trim_running {
        assert!(
            start.elapsed() < Duration::from_secs(5),
            "the pitch trim never ran; moves on the wire: {:?}",
            pitch_moves(&b.wire)
        );
        term.typed(b"u");
        std::thread::sleep(Duration::from_millis(40));
    }
    // A few more repeats, so the run is well under way.
    for _ in 0..5 {
        term.typed(b"u");
        std::thread::sleep(Duration::from_millis(40));
    }
    let screen_before = term.output().len();
    let sent = Instant::now();
    // SAFETY: kill(2) on our own child.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
    let (exit, exited) = wait_exit(&mut child, Duration::from_secs(5));

    assert_eq!(exit.code(), Some(status), "exit status: {exit:?}");
    // The stop crossed the pty before the process was gone (the tap stamps bytes as
    // it reads them, so allow it the time to read what was already written).
    std::thread::sleep(Duration::from_millis(100));
    let moves = pitch_moves(&b.wire);
    let stop = moves
        .iter()
        .find(|(at, on)| !on && *at >= sent)
        .unwrap_or_else(|| panic!("no stop on the wire after the signal: {moves:?}"));
    assert!(
        stop.0 <= exited + Duration::from_millis(50),
        "the stop came {:?} after the exit",
        stop.0 - exited
    );
    assert!(
        moves
            .iter()
            .filter(|(at, _)| *at > stop.0)
            .all(|(_, on)| !on),
        "a move after the stop: {moves:?}"
    );
    page_rig::assert_the_trim_stopped_by_its_message(&b.sim);

    // The terminal was given back.
    let after = term.output()[screen_before..].to_vec();
    let text = String::from_utf8_lossy(&after);
    let leave = find(&after, b"\x1b[?1049l").expect("LeaveAlternateScreen after the signal");
    let show = find(&after, b"\x1b[?25h").expect("the cursor shown after the signal");
    assert!(show > leave, "cursor shown after leaving: {text:?}");
    assert!(
        find(&after, b"\x1b[?1004l").is_some(),
        "focus reports turned off: {text:?}"
    );
    let name = if signal == libc::SIGTERM {
        "SIGTERM"
    } else {
        "SIGHUP"
    };
    assert!(
        text.contains(&format!("stopped by {name}")),
        "says why: {text:?}"
    );
    assert_eq!(
        term.echo_and_line_mode(),
        (true, true),
        "echo and line mode back on"
    );
    b.tap.unplug();
}

#[test]
fn sigterm_during_a_trim_run_stops_the_motor_restores_the_terminal_and_exits_143() {
    signal_during_a_trim_run(libc::SIGTERM, 143);
}

#[test]
fn sighup_during_a_trim_run_stops_the_motor_restores_the_terminal_and_exits_129() {
    signal_during_a_trim_run(libc::SIGHUP, 129);
}

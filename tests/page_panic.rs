//! Panic safety of the page, in a process of its own: the panic hook is global, and a
//! panic here must not stop the motors of unrelated tests.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEventKind};
use vpx_efis::protocol::Packet;
use vpx_efis::protocol::message::{Message, TrimType};
use vpx_efis::ui::state::ReleaseMode;

mod page_rig;
use page_rig::*;

/// A panic on a thread other than the loop's (the link's reader, say): the hook puts
/// the stop on the wire at once, and the still-running loop never resends a move
/// after it.
#[test]
fn a_panic_while_trim_runs_sends_the_stop_and_nothing_restarts_it() {
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.select(30);
    // As `vpx-efis` arms it: the stop goes through the page's own way to the wire.
    rig.app.arm_emergency_stop();
    vpx_efis::app::install_panic_hook();
    let start = Instant::now();
    rig.key(KeyCode::Char('u'), KeyEventKind::Press);
    while !rig.sim.stats().pitch_trim_running {
        assert!(
            start.elapsed() < Duration::from_secs(2),
            "trim never started"
        );
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(20));
    }
    let from = rig.wire_len();
    let panicked = Instant::now();
    let crashed = std::thread::spawn(|| panic!("simulated crash on another thread")).join();
    assert!(crashed.is_err());
    assert!(vpx_efis::app::panicked());
    // The loop goes on (another thread died); keys keep repeating as if still held.
    let until = Instant::now() + Duration::from_millis(600);
    while Instant::now() < until {
        rig.key(KeyCode::Char('u'), KeyEventKind::Press);
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(33));
    }
    vpx_efis::app::clear_emergency_stop();
    let moves: Vec<(Instant, bool)> = rig
        .sent(from)
        .into_iter()
        .filter_map(|(at, p): (Instant, Packet)| match p.message {
            Message::TrimMove(m) if m.trim_type == TrimType::Pitch => Some((at, m.on)),
            _ => None,
        })
        .collect();
    let first_stop = moves
        .iter()
        .position(|(_, on)| !on)
        .expect("the hook's stop on the wire");
    assert!(moves[first_stop].0.saturating_duration_since(panicked) < Duration::from_millis(200));
    assert!(
        moves[first_stop..].iter().all(|(_, on)| !on),
        "a move was resent after the panic's stop: {moves:?}"
    );
    page_rig::assert_the_trim_stopped_by_its_message(&rig.sim);
}

//! The 4 Hz rule of TRIM_MOVE (ICD §6.4.2, icd-reading R19), on the wire: a page that
//! streams every 200 ms keeps the motor running; a 400 ms gap stops it once (the unit
//! stops 300 ms after the last message: 250 ms plus its margin, see `sim::motors`).
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

mod sim_common;

use std::time::{Duration, Instant};

use sim_common::{scenario, start};
use vpx_efis::protocol::message::{TrimDirection, TrimMove, TrimType};

const TRIM: &str = "[pitch_trim]\nup = 20\ndown = 235\nneutral = 100\nposition = 100\n";

fn trim_down() -> TrimMove {
    TrimMove {
        trim_type: TrimType::Pitch,
        on: true,
        direction: TrimDirection::DownOrRight,
    }
}

/// Sends TRIM_MOVE at `interval` on the client's own clock, `n` times, reading in
/// between so the pty never backs up.
fn stream(c: &mut sim_common::Client, interval: Duration, n: u32) {
    let start = Instant::now();
    for i in 0..n {
        let due = start + interval * i;
        while Instant::now() < due {
            c.poll();
        }
        c.send(trim_down());
    }
}

#[test]
fn trim_move_every_200_ms_runs_on_and_a_400_ms_gap_starves_it_once() {
    let (sim, mut c) = start(scenario(TRIM), |_| {});
    c.pump(Duration::from_millis(300));
    let p0 = sim.stats().pitch_trim_position;

    stream(&mut c, Duration::from_millis(200), 8);
    let s = sim.stats();
    assert!(
        s.pitch_trim_running,
        "still running within 250 ms of the last move"
    );
    assert_eq!(s.pitch_trim_starvations, 0, "200 ms is fast enough");
    assert_eq!(s.pitch_trim_late, 0, "and never later than 250 ms");
    let p1 = s.pitch_trim_position;
    assert!(p1 > p0 + 20, "moved down: {p0} → {p1}");

    // Now a 400 ms gap: the motor stops 300 ms after the last move, once.
    c.pump(Duration::from_millis(400));
    let s = sim.stats();
    assert!(!s.pitch_trim_running);
    assert_eq!(s.pitch_trim_starvations, 1);
    let stopped_at = s.pitch_trim_position;
    c.pump(Duration::from_millis(300));
    assert_eq!(
        sim.stats().pitch_trim_position,
        stopped_at,
        "stopped means stopped"
    );

    // Streaming again after the gap restarts it; an explicit stop is not a starvation.
    stream(&mut c, Duration::from_millis(200), 3);
    c.send(TrimMove {
        on: false,
        ..trim_down()
    });
    c.pump(Duration::from_millis(400));
    let s = sim.stats();
    assert!(!s.pitch_trim_running);
    assert_eq!(s.pitch_trim_starvations, 1);
    assert!(s.pitch_trim_position > stopped_at);
}

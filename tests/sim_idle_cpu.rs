//! `vpx-efis sim --pty` paced at the real line rate (its default) is idle when
//! nothing changes: a page reading its 1 Hz and 10 Hz broadcasts costs it well under
//! a percent of a core. Measured from /proc on the sim process alone.
//!
//! `IDLE_CPU_SECS=30 cargo test --release --test sim_idle_cpu -- --nocapture` measures
//! longer and prints the figures.
#![cfg(target_os = "linux")]

use std::time::{Duration, Instant};

mod common;
mod sim_common;

use common::cpu::process_cpu_time;
use vpx_efis::protocol::message::*;

/// The sim's share of a core over `secs` while a client reads everything it sends.
fn idle_share(extra: &[&str], secs: u64) -> (f64, usize) {
    let sim = common::process::sim(&[&["--pty", "--scenario", "disabled-pins"], extra].concat());
    let pid = sim.process.0.id();
    let mut c = sim_common::Client::open(&sim.line, Duration::from_millis(50));
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
    // Past start-up, then measured.
    c.pump(Duration::from_millis(500));
    let frames0 = c.log.len();
    let cpu0 = process_cpu_time(pid).unwrap();
    let wall0 = Instant::now();
    c.pump(Duration::from_secs(secs));
    let cpu = process_cpu_time(pid).unwrap() - cpu0;
    let share = cpu.as_secs_f64() / wall0.elapsed().as_secs_f64();
    (share, c.log.len() - frames0)
}

#[test]
fn the_paced_sim_is_idle_while_nothing_changes() {
    let secs = common::cpu::idle_secs(4);
    let (paced, frames) = idle_share(&[], secs);
    let (unpaced, _) = idle_share(&["--no-pace"], secs);
    eprintln!(
        "sim over {secs} s: paced {:.2} % of a core ({frames} frames read), --no-pace {:.2} %",
        paced * 100.0,
        unpaced * 100.0
    );
    // 1 Hz SYSTEM_STATUS and DEVICE_STATUS, 10 Hz FLAP_TRIM_STATUS.
    assert!(frames as u64 >= secs * 11, "{frames} frames in {secs} s");
    // The product promises 1 % for a release build; this is usually a debug build on
    // a shared machine, where the 10 ms tick of /proc makes short runs coarse.
    assert!(
        paced < 0.03,
        "paced sim used {:.1} % of a core",
        paced * 100.0
    );
}

//! Idle means idle: the page uses at most 1 % of a core while nothing changes,
//! whatever the unit's configuration. The real page (`vpx-efis --port`) runs in a
//! pseudo-terminal that is its controlling terminal, as in a terminal window, against
//! `vpx-efis sim --pty` in a process of its own at the real line rate; only the page
//! process's own CPU time is counted (the OS's accounting of that one process, so the
//! sim and anything else loading the machine do not count). The unit keeps up its
//! 1 Hz and 10 Hz broadcasts throughout, and the page keeps reading them.
//!
//! `IDLE_CPU_SECS=30 cargo test --release --test page_idle_cpu -- --nocapture`
//! measures longer and prints the figures.
// Needs pseudo-terminals, which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

mod common;
mod page_rig;

use common::cpu::process_cpu_time;
use common::process::{Kill, sim_pty};
use page_rig::terminal::{Term, page};

/// A unit with nothing fitted that could change: every switchable pin 4–28 disabled,
/// no flaps, no trims, the engine stopped and no switch on.
fn nothing_fitted() -> String {
    let mut s = String::from(
        "description = \"idle: every pin 4-28 disabled, no motors, engine off\"\n\
         [electrical]\nbus_volts = 12.6\nbattery_volts = 12.6\ntemperature_c = 20\n\
         [[device]]\nid = 2\nname = \"Quiet\"\nswitch = 11\nload = 2.0\n",
    );
    for id in 4..=28 {
        s.push_str(&format!("[[device]]\nid = {id}\nenabled = false\n"));
    }
    s.push_str(
        "[flap]\nenabled = false\nup = 0\ndown = 0\n\
         [pitch_trim]\nenabled = false\nup = 0\ndown = 0\nneutral = 0\n\
         [roll_trim]\nenabled = false\nup = 0\ndown = 0\nneutral = 0\n",
    );
    s
}

/// What one idle run measured.
struct Idle {
    /// The page's share of one core.
    share: f64,
    cpu: Duration,
    wall: Duration,
    /// Bytes the page wrote to its terminal meanwhile.
    drawn: usize,
}

/// The page against `scenario` over `secs` once its device list is up (`shown` on
/// the screen) and its connect requests are answered; `None` (with the reason
/// printed) where this OS cannot say a process's CPU time.
fn idle(scenario: &str, shown: &[u8], secs: u64) -> Option<Idle> {
    let (_sim, port) = sim_pty(scenario);
    let (mut term, slave) = Term::open();
    let mut child = page(&["--port", &port], slave);
    let pid = child.id();
    if let Err(why) = process_cpu_time(pid) {
        let _ = child.kill();
        let _ = child.wait();
        eprintln!("page_idle_cpu: skipped, not measurable here: {why}");
        return None;
    }
    let child = Kill(child);
    let what = format!("{scenario}'s device list");
    term.wait_for(&what, &[shown], 0, Duration::from_secs(10));
    // Past the connect requests and the first redraws.
    std::thread::sleep(Duration::from_millis(1500));
    let drawn0 = term.written();
    let cpu0 = process_cpu_time(pid).unwrap();
    let wall0 = Instant::now();
    std::thread::sleep(Duration::from_secs(secs));
    let cpu = process_cpu_time(pid).unwrap() - cpu0;
    let wall = wall0.elapsed();
    let drawn = term.written() - drawn0;
    let mut child = child;
    assert!(
        child.0.try_wait().unwrap().is_none(),
        "{scenario}: the page ended while idle: {}",
        String::from_utf8_lossy(&term.output())
    );
    // It leaves as a person makes it leave.
    term.typed(b"q");
    let end = Instant::now() + Duration::from_secs(5);
    while child.0.try_wait().unwrap().is_none() {
        assert!(
            Instant::now() < end,
            "{scenario}: the page did not quit on q"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    Some(Idle {
        share: cpu.as_secs_f64() / wall.as_secs_f64(),
        cpu,
        wall,
        drawn,
    })
}

/// Long enough that the OS's 10 ms accounting tick is a tenth of the allowance.
fn secs() -> u64 {
    common::cpu::idle_secs(10)
}

fn assert_idle(what: &str, scenario: &str, shown: &[u8]) {
    let secs = secs();
    let Some(m) = idle(scenario, shown, secs) else {
        return;
    };
    eprintln!(
        "page against {what}: {:?} CPU in {:.1?} = {:.2} % of a core, {} bytes drawn",
        m.cpu,
        m.wall,
        m.share * 100.0,
        m.drawn
    );
    assert!(
        m.share <= 0.01,
        "the page used {:.2} % of a core against {what}",
        m.share * 100.0
    );
}

#[test]
fn the_page_is_idle_against_a_unit_with_nothing_fitted() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("nothing-fitted.toml");
    std::fs::write(&file, nothing_fitted()).unwrap();
    assert_idle(
        "a unit with every pin disabled and no motors",
        file.to_str().unwrap(),
        b"Quiet",
    );
}

#[test]
fn the_page_is_idle_against_an_installed_unit_broadcasting_unchanged_values() {
    // Most pins disabled, flaps and pitch trim fitted and still, the engine running.
    assert_idle("the disabled-pins unit", "disabled-pins", b"Transponder");
}

#[test]
fn the_page_is_idle_against_a_factory_unit_with_every_pin_enabled() {
    // Every pin shown, everything off.
    assert_idle("the hangar unit", "hangar", b"EFIS");
}

//! `vpx-efis sim --pty` as a process: the first line on stdout is a path that a
//! serial client can open and find a VP-X behind.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::io::Write;
use std::time::Duration;

mod common;
mod sim_common;

use common::process::{self, sim};
use vpx_efis::protocol::message::*;

#[test]
fn sim_pty_prints_its_path_first_and_answers_on_it() {
    let dir = tempfile::tempdir().unwrap();
    let eeprom = dir.path().join("e.json");
    let sim = sim(&[
        "--pty",
        "--scenario",
        "hangar",
        "--eeprom",
        eeprom.to_str().unwrap(),
    ]);
    assert!(sim.line.starts_with("/dev/"), "first line: {:?}", sim.line);
    let mut c = sim_common::Client::open(&sim.line, Duration::from_millis(20));
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
    let d = c.next("DEVICE_STATUS", |m| match m {
        Message::DeviceStatus(d) => Some(*d),
        _ => None,
    });
    assert!(d.on.iter().all(|&on| !on), "hangar: everything off");
}

#[test]
fn an_unknown_scenario_is_a_clear_error() {
    let out = process::vpx(
        &["sim", "--pty", "--scenario", "nonesuch"],
        process::NO_CONFIG,
    )
    .output()
    .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("nonesuch") && err.contains("demo"), "{err}");
    assert!(out.stdout.is_empty(), "no path printed when nothing runs");
}

/// A person at the sim's keyboard works the cockpit switches; the `install` scenario's
/// wiring decides which inputs the unit sees, and the sim keeps running when its
/// standard input ends.
#[test]
fn switches_worked_on_standard_input_go_through_the_wiring() {
    let common::process::Sim {
        process: _guard,
        console: mut stdin,
        line,
    } = sim(&["--pty", "--scenario", "install"]);
    let mut c = sim_common::Client::open(&line, Duration::from_millis(20));
    let inputs = |c: &mut sim_common::Client| c.system_status().switches.switch;
    assert_eq!(inputs(&mut c), [false; 10], "install: every switch off");
    // Switch 5 is crossed with 6, and 7 is dead; 2 is wired right.
    stdin
        .write_all(b"help\nswitch 5 on\nswitch 7 on\nnonsense\nswitch 2 on\n")
        .unwrap();
    stdin.flush().unwrap();
    let mut want = [false; 10];
    want[1] = true;
    want[5] = true;
    let mut seen = inputs(&mut c);
    for _ in 0..3 {
        if seen == want {
            break;
        }
        seen = inputs(&mut c);
    }
    assert_eq!(seen, want, "inputs 2 and 6 closed; 5 and 7 open");
    drop(stdin);
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true }),
        "still running after standard input ended"
    );
}

//! `vpx-efis check` as a process against `vpx-efis sim --pty` as another: what the
//! headless check prints before it starts (its plan and the line that confirms it)
//! counts only what will run.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::io::Write;
use std::process::{Command, Stdio};
use std::time::Duration;

mod common;
use common::process::{EXE, Kill, lines, sim_pty};

/// The headless check's output up to and including its "Confirmed:" line, run with
/// `--yes` and `skip` against the `install` scenario; then it is told to stop.
fn plan_with_skip(skip: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let (_sim, path) = sim_pty("install");
    let mut check = Command::new(EXE)
        .env("VPX_EFIS_CONFIG", dir.path().join("config.toml"))
        .args(["check", "--port", &path, "--yes", "--skip", skip])
        .arg("--loads")
        .arg(dir.path().join("loads.toml"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run the check");
    let out = check.stdout.take().unwrap();
    let mut stdin = check.stdin.take().unwrap();
    let _check = Kill(check);
    let rx = lines(out);
    let mut text = String::new();
    loop {
        let line = rx
            .recv_timeout(Duration::from_secs(30))
            .unwrap_or_else(|_| panic!("no Confirmed line; so far:\n{text}"));
        text.push_str(&line);
        text.push('\n');
        if line.starts_with("Confirmed:") {
            break;
        }
    }
    // Stop: the check puts back what it changed (nothing yet) and ends.
    let _ = stdin.write_all(b"q\n");
    text
}

/// How many circuits the plan lists under "It leaves alone:".
fn left_alone(text: &str) -> usize {
    text.lines()
        .skip_while(|l| *l != "It leaves alone:")
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .count()
}

#[test]
fn with_the_motors_step_skipped_the_plan_counts_no_motor() {
    let text = plan_with_skip("motors");
    assert!(
        text.contains("The motors step is skipped: the check runs no motor."),
        "{text}"
    );
    let circuits = text.lines().filter(|l| l.contains(", breaker ")).count();
    assert!(circuits > 0, "{text}");
    let alone = left_alone(&text);
    assert!(alone > 0, "the install scenario has a starter: {text}");
    let confirmed = text.lines().last().unwrap();
    assert_eq!(
        confirmed,
        format!(
            "Confirmed: {circuits} circuits to power, no motor to run (motors step skipped), \
             {alone} left alone"
        ),
        "{text}"
    );
}

#[test]
fn with_circuits_and_motors_skipped_the_plan_counts_nothing_to_power_or_run() {
    let text = plan_with_skip("circuits,motors");
    assert!(
        text.contains("the circuits step is skipped, so the check switches no circuit on"),
        "{text}"
    );
    assert_eq!(
        text.lines().last().unwrap(),
        format!(
            "Confirmed: no circuit to power (circuits step skipped), no motor to run \
             (motors step skipped), {} left alone",
            left_alone(&text)
        ),
        "{text}"
    );
}

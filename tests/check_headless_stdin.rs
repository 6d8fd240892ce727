//! A headless `vpx-efis check` whose standard input is at its end (`/dev/null`, a
//! closed pipe, cron, a service, CI) must not spin a core waiting for answers. Here the check runs as the process a user starts, against
//! `vpx-efis sim --tcp` (so this runs on Windows too), with nobody to answer: it says
//! so, skips the switch step (which needs a person), powers nothing without `--yes`,
//! and is idle while it waits on the unit.
//!
//! `IDLE_CPU_SECS=20 cargo test --release --test check_headless_stdin -- --nocapture`
//! measures longer and prints the figure.

use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

mod common;
use common::process::{EXE, Kill, lines, sim_tcp};

/// `vpx-efis check --port ADDR ARGS…` with `stdin`, its config folder in `home`, and
/// its stdout lines on a channel.
fn check(
    addr: &str,
    args: &[&str],
    stdin: Stdio,
    home: &std::path::Path,
) -> (Kill, mpsc::Receiver<String>) {
    let mut child = Command::new(EXE)
        .args(["check", "--port", addr])
        .args(args)
        .env("XDG_CONFIG_HOME", home)
        .env("APPDATA", home)
        .stdin(stdin)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run vpx-efis check");
    let rx = lines(child.stdout.take().unwrap());
    (Kill(child), rx)
}

/// Lines until one contains `what` (that one included), or a failure naming them.
fn until(rx: &mpsc::Receiver<String>, what: &str, within: Duration) -> Vec<String> {
    let end = Instant::now() + within;
    let mut seen = Vec::new();
    loop {
        let left = end.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(l) => {
                let hit = l.contains(what);
                seen.push(l);
                if hit {
                    return seen;
                }
            }
            Err(_) => panic!("no line with {what:?} within {within:?}: {seen:#?}"),
        }
    }
}

/// Every line until the process closes its stdout.
fn to_the_end(rx: &mpsc::Receiver<String>, within: Duration) -> Vec<String> {
    let end = Instant::now() + within;
    let mut seen = Vec::new();
    loop {
        match rx.recv_timeout(end.saturating_duration_since(Instant::now())) {
            Ok(l) => seen.push(l),
            Err(mpsc::RecvTimeoutError::Disconnected) => return seen,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                panic!("still running after {within:?}: {seen:#?}")
            }
        }
    }
}

const NOBODY: &str = "Standard input is at its end (no terminal, /dev/null, a closed pipe): \
                      nobody can answer here.";

/// Without `--yes`, nobody can confirm: the check says so, switches nothing on and
/// ends at once (exit 2), instead of waiting a day on a closed pipe.
#[test]
fn without_yes_and_nobody_to_answer_nothing_is_switched_on() {
    let (_sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let reports = home.path().join("reports");
    let (mut child, rx) = check(
        &addr,
        &["--report", reports.to_str().unwrap()],
        // A pipe whose writer is gone at once: a closed pipe, as cron gives.
        Stdio::piped(),
        home.path(),
    );
    drop(child.0.stdin.take());
    let started = Instant::now();
    let text = to_the_end(&rx, Duration::from_secs(20)).join("\n");
    let status = child.0.wait().unwrap();
    assert_eq!(status.code(), Some(2), "{text}");
    assert!(
        started.elapsed() < Duration::from_secs(15),
        "{:?}",
        started.elapsed()
    );
    assert!(
        text.contains(&format!(
            "{NOBODY} Nobody typed yes, so nothing is switched on. To run the check with \
             nobody at the keyboard, give --yes."
        )),
        "{text}"
    );
    assert!(!text.contains("PASS"), "nothing powered: {text}");
    assert!(!text.contains("Confirmed:"), "{text}");
    assert!(
        text.contains("Every circuit it touched is as it found it."),
        "{text}"
    );
}

/// With `--yes` and stdin at its end (`/dev/null`): the switch step is skipped with
/// the reason, the circuits are checked, and the process is idle while it waits on
/// the unit's broadcasts (it spun a core at 100 % before).
#[test]
fn a_headless_check_with_stdin_at_its_end_is_idle_and_skips_the_switches() {
    let secs: u64 = std::env::var("IDLE_CPU_SECS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let (_sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let reports = home.path().join("reports");
    let (child, rx) = check(
        &addr,
        &[
            "--yes",
            "--skip",
            "motors,loads",
            "--report",
            reports.to_str().unwrap(),
        ],
        Stdio::null(),
        home.path(),
    );
    let before = until(&rx, "Confirmed:", Duration::from_secs(20)).join("\n");
    assert!(
        before.contains(&format!(
            "{NOBODY} The switch step, which needs a person to flip each switch and say \
             when it is done, is skipped."
        )),
        "{before}"
    );
    assert!(
        !before.contains("It will not ask you to flip"),
        "the plan knows the switches are skipped: {before}"
    );
    let skipped = until(&rx, "Switch inputs", Duration::from_secs(5));
    assert_eq!(
        skipped.last().map(String::as_str),
        Some("– Switch inputs: skipped"),
        "{skipped:?}"
    );
    measure(&child, secs);
    // The circuits step goes on by itself: the first circuit is judged.
    until(&rx, "EFIS (EFIS)", Duration::from_secs(15));
}

#[cfg(target_os = "linux")]
fn measure(child: &Kill, secs: u64) {
    let pid = child.0.id();
    let cpu0 = common::cpu::process_cpu_time(pid).unwrap();
    let wall0 = Instant::now();
    std::thread::sleep(Duration::from_secs(secs));
    let cpu = common::cpu::process_cpu_time(pid).unwrap() - cpu0;
    let share = cpu.as_secs_f64() / wall0.elapsed().as_secs_f64();
    eprintln!(
        "headless check, stdin at its end: {cpu:?} CPU in {secs} s = {:.2} % of a core",
        share * 100.0
    );
    assert!(
        share <= 0.01,
        "the headless check used {:.1} % of a core",
        share * 100.0
    );
}

#[cfg(not(target_os = "linux"))]
fn measure(_child: &Kill, _secs: u64) {
    eprintln!(
        "skipped: the CPU share of the headless check ({})",
        common::cpu::process_cpu_time(0).unwrap_err()
    );
}

/// "Is it lit?" headless: the question is printed, the light held on past its
/// measurement until the person types an answer, and switched off at it; then
/// standard input closes mid-check, and the next light is not held for an answer
/// that cannot come.
#[test]
fn a_headless_check_holds_a_light_on_until_the_typed_answer() {
    let (_sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let reports = home.path().join("reports");
    let (mut child, rx) = check(
        &addr,
        &[
            "--yes",
            "--skip",
            "switches,motors,loads",
            "--report",
            reports.to_str().unwrap(),
        ],
        Stdio::piped(),
        home.path(),
    );
    let mut stdin = child.0.stdin.take().unwrap();
    let asked = until(&rx, "Nav Lt: is it lit?", Duration::from_secs(30));
    assert_eq!(
        asked.last().unwrap(),
        "  Nav Lt: is it lit? Type y (lit), n (not lit) or s (skip the question); it \
         stays on until you answer, 60 s at most.",
    );
    let asked_at = Instant::now();
    // Measured within the unit's two broadcasts, and then held: nothing more for
    // 7 s (the check kept a circuit on for 5 s at most before).
    let measured = until(&rx, "Nav Lt (5A-1)", Duration::from_secs(6));
    assert!(measured.last().unwrap().contains("draws"), "{measured:?}");
    let quiet = rx.recv_timeout(Duration::from_secs(7).saturating_sub(asked_at.elapsed()));
    assert!(quiet.is_err(), "said while the light was held: {quiet:?}");
    use std::io::Write as _;
    writeln!(stdin, "y").unwrap();
    let answered = until(&rx, "Nav Lt: you saw", Duration::from_secs(3));
    assert_eq!(
        answered.last().unwrap(),
        "  Nav Lt: you saw it lit; switched back off at your answer"
    );
    // The next light is asked; standard input closes: nobody can answer it.
    until(&rx, "is it lit?", Duration::from_secs(30));
    drop(stdin);
    let rest = to_the_end(&rx, Duration::from_secs(40)).join("\n");
    assert!(rest.contains(NOBODY), "{rest}");
    assert!(
        rest.contains("not asked if it is lit: nobody could answer (standard input ended)"),
        "{rest}"
    );
    assert!(rest.contains("Summary:"), "{rest}");
}

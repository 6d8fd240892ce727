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

/// A `vpx-efis check` running against `vpx-efis sim --tcp` with the install scenario.
/// Dropped in field order: the check, the unit, then its folder.
struct Check {
    child: Kill,
    /// Its standard output, a line at a time.
    rx: mpsc::Receiver<String>,
    _sim: Kill,
    /// Its config folder, its reports in `reports/` there.
    _home: tempfile::TempDir,
}

/// `vpx-efis check --port ADDR ARGS… --report DIR` with `stdin`.
fn check(args: &[&str], stdin: Stdio) -> Check {
    let (sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let reports = home.path().join("reports");
    let mut child = Command::new(EXE)
        .args(["check", "--port", &addr])
        .args(args)
        .arg("--report")
        .arg(&reports)
        .env("XDG_CONFIG_HOME", home.path())
        .env("APPDATA", home.path())
        .stdin(stdin)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run vpx-efis check");
    let rx = lines(child.stdout.take().unwrap());
    Check {
        child: Kill(child),
        rx,
        _sim: sim,
        _home: home,
    }
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
    // A pipe whose writer is gone at once: a closed pipe, as cron gives.
    let mut c = check(&[], Stdio::piped());
    drop(c.child.0.stdin.take());
    let started = Instant::now();
    let text = to_the_end(&c.rx, Duration::from_secs(20)).join("\n");
    let status = c.child.0.wait().unwrap();
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
    let secs = common::cpu::idle_secs(3);
    let c = check(&["--yes", "--skip", "motors,loads"], Stdio::null());
    let before = until(&c.rx, "Confirmed:", Duration::from_secs(20)).join("\n");
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
    let skipped = until(&c.rx, "Switch inputs", Duration::from_secs(5));
    assert_eq!(
        skipped.last().map(String::as_str),
        Some("– Switch inputs: skipped"),
        "{skipped:?}"
    );
    measure(&c.child, secs);
    // The circuits step goes on by itself: the first circuit is judged.
    until(&c.rx, "EFIS (EFIS)", Duration::from_secs(15));
}

/// The check's share of a core over `secs` seconds: 1 % at most. Measured where the
/// OS lets a test read another process's CPU time (Linux).
fn measure(child: &Kill, secs: u64) {
    match common::cpu::share_of_a_core(child.0.id(), secs) {
        Ok(share) => {
            let percent = share * 100.0;
            eprintln!("headless check, stdin at its end: {percent:.2} % of a core in {secs} s");
            assert!(
                share <= 0.01,
                "the headless check used {percent:.1} % of a core"
            );
        }
        Err(why) if cfg!(target_os = "linux") => panic!("{why}"),
        Err(why) => eprintln!("skipped: the CPU share of the headless check ({why})"),
    }
}

/// "Is it lit?" headless: the question is printed, the light held on past its
/// measurement until the person types an answer, and switched off at it; then
/// standard input closes mid-check, and the next light is not held for an answer
/// that cannot come.
#[test]
fn a_headless_check_holds_a_light_on_until_the_typed_answer() {
    let args = ["--yes", "--skip", "switches,motors,loads"];
    let mut c = check(&args, Stdio::piped());
    let mut stdin = c.child.0.stdin.take().unwrap();
    let asked = until(&c.rx, "Nav Lt: is it lit?", Duration::from_secs(30));
    assert_eq!(
        asked.last().unwrap(),
        "  Nav Lt: is it lit? Type y (lit), n (not lit) or s (skip the question); it \
         stays on until you answer, 60 s at most.",
    );
    let asked_at = Instant::now();
    // Measured within the unit's two broadcasts, and then held: nothing more for
    // 7 s (the check kept a circuit on for 5 s at most before).
    let measured = until(&c.rx, "Nav Lt (5A-1)", Duration::from_secs(6));
    assert!(measured.last().unwrap().contains("draws"), "{measured:?}");
    let quiet =
        c.rx.recv_timeout(Duration::from_secs(7).saturating_sub(asked_at.elapsed()));
    assert!(quiet.is_err(), "said while the light was held: {quiet:?}");
    use std::io::Write as _;
    writeln!(stdin, "y").unwrap();
    let answered = until(&c.rx, "Nav Lt: you saw", Duration::from_secs(3));
    assert_eq!(
        answered.last().unwrap(),
        "  Nav Lt: you saw it lit; switched back off at your answer"
    );
    // The next light is asked; standard input closes: nobody can answer it.
    until(&c.rx, "is it lit?", Duration::from_secs(30));
    drop(stdin);
    let rest = to_the_end(&c.rx, Duration::from_secs(40)).join("\n");
    assert!(rest.contains(NOBODY), "{rest}");
    assert!(
        rest.contains("not asked if it is lit: nobody could answer (standard input ended)"),
        "{rest}"
    );
    assert!(rest.contains("Summary:"), "{rest}");
}

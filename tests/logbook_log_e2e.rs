//! Two installation checks of one aircraft against `vpx-efis sim
//! --pty` as its own process, the Landing Lt's load changed between them on the sim's
//! console (`load 17 7.6`) and a backup taken between them. The second report gives
//! both currents and the change; `log --circuit` shows the two; `log --json` lists the
//! two checks and the backup; `log --export` writes a page holding both. Every step
//! is the program as a mechanic runs it, on a real logbook file.
// Needs a pseudo-terminal, which only Unix has.
#![cfg(unix)]

use std::io::Write;
use std::path::Path;
use std::process::Output;
use std::time::Duration;

mod common;
use common::process::{self, sim};

/// Three circuits, the engine stopped, every switch off: EFIS always on, Nav Lt on
/// switch 2, Landing Lt (device 17, pin 10A-1) on switch 5 drawing 6.1 A of 10 A.
const SCENARIO: &str = include_str!("data/scenario-logbook.toml");

/// The unit's other pins, each disabled (the alternator fields and the starter are
/// not the check's to switch).
fn scenario_text() -> String {
    let mut s = SCENARIO.to_string();
    for id in [
        5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28,
    ] {
        s.push_str(&format!("\n[[device]]\nid = {id}\nenabled = false\n"));
    }
    s
}

/// `vpx-efis ARGS` on the aircraft N123AB's logbook in `dir`, its output.
fn vpx(dir: &Path, args: &[&str]) -> Output {
    process::vpx(args, dir.join("config.toml"))
        .env("VPX_EFIS_LOGBOOK", dir.join("logbook.sqlite"))
        .env("VPX_EFIS_AIRCRAFT", "N123AB")
        .env("NO_COLOR", "1")
        .output()
        .expect("run vpx-efis")
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// One check of the circuits (switches and motors skipped, nobody to answer), its
/// report's Markdown and what it printed.
fn check(dir: &Path, port: &str, reports: &str) -> (String, String) {
    let out = vpx(
        dir,
        &[
            "check",
            "--port",
            port,
            "--yes",
            "--skip",
            "switches,motors",
            "--report",
            &dir.join(reports).to_string_lossy(),
            "--loads",
            &dir.join("loads.toml").to_string_lossy(),
        ],
    );
    let folder = dir.join(reports);
    let md = std::fs::read_dir(&folder)
        .unwrap_or_else(|e| panic!("{}: {e}\n{}", folder.display(), text(&out)))
        .filter_map(Result::ok)
        .find(|e| e.path().extension().is_some_and(|x| x == "md"))
        .unwrap_or_else(|| panic!("no report in {}:\n{}", folder.display(), text(&out)));
    (std::fs::read_to_string(md.path()).unwrap(), text(&out))
}

/// The report's row of the circuit `name` in its table of circuits (its section
/// "## Circuits"; the plan before it names the circuits too).
fn row<'a>(report: &'a str, name: &str) -> &'a str {
    let head = format!("| {name} |");
    report
        .split("\n## Circuits\n")
        .nth(1)
        .unwrap_or_else(|| panic!("no circuits section:\n{report}"))
        .lines()
        .find(|l| l.starts_with(&head))
        .unwrap_or_else(|| panic!("no row for {name}:\n{report}"))
}

/// The current the report gives `name`, in tenths ("| 6.2 A |" is 62).
fn tenths_of(report: &str, name: &str) -> u16 {
    let cell = row(report, name)
        .split('|')
        .nth(5)
        .unwrap()
        .trim()
        .to_string();
    let a = cell
        .strip_suffix(" A")
        .unwrap_or_else(|| panic!("no current in {cell:?}:\n{report}"));
    (a.parse::<f64>().unwrap() * 10.0).round() as u16
}

#[test]
fn two_checks_with_a_load_changed_between_them_show_the_change_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scenario = d.join("logbook.toml");
    std::fs::write(&scenario, scenario_text()).unwrap();
    let mut unit = sim(&["--pty", "--scenario", &scenario.to_string_lossy()]);
    let port = unit.line.clone();

    let (first, _) = check(d, &port, "first");
    // No check before it: no column for one.
    assert!(!first.contains("Last check"), "{first}");
    let was = tenths_of(&first, "Landing Lt");
    assert!((58..=64).contains(&was), "the scenario's 6.1 A: {first}");
    let nav_was = tenths_of(&first, "Nav Lt");

    // Between the checks: a backup, and the landing light draws more (a corroded
    // connection, a wrong lamp).
    let backup = vpx(
        d,
        &[
            "backup",
            "--port",
            &port,
            &d.join("backup.toml").to_string_lossy(),
        ],
    );
    assert!(backup.status.success(), "{}", text(&backup));
    writeln!(unit.console, "load 17 7.6").unwrap();
    unit.console.flush().unwrap();
    std::thread::sleep(Duration::from_millis(500));

    let (second, printed) = check(d, &port, "second");
    let now = tenths_of(&second, "Landing Lt");
    assert!((73..=79).contains(&now), "the console's 7.6 A: {second}");
    // Worked here from the two figures: the change in percent of the first, rounded.
    let pct = ((f64::from(now) - f64::from(was)) * 100.0 / f64::from(was)).round();
    assert!(pct > 20.0);
    let amps = |t: u16| format!("{}.{} A", t / 10, t % 10);
    assert!(
        second.contains(&format!(
            "| Landing Lt | 10A-1 | 10 A | ✓ PASS | {} | ⚠ last check {}, +{pct} %: changed \
             since the last check |",
            amps(now),
            amps(was)
        )),
        "{second}"
    );
    // The headless check's own line says it as it goes.
    assert!(
        printed.contains(&format!(
            "Landing Lt (10A-1): draws {} of a 10 A breaker; last check {}, +{pct} %: changed \
             since the last check",
            amps(now),
            amps(was)
        )),
        "{printed}"
    );
    // The Nav Lt did not change (within the sim's tenth or two): not marked.
    let nav = row(&second, "Nav Lt");
    assert!(
        nav.contains(&format!("last check {}", amps(nav_was))),
        "{second}"
    );
    assert!(!nav.contains("changed"), "{second}");
    assert!(
        second.contains(&format!(
            "- ⚠ Landing Lt (10A-1): {}, last check {}",
            amps(now),
            amps(was)
        )),
        "{second}"
    );

    let history = vpx(d, &["log", "--circuit", "landing lt"]);
    let h = text(&history);
    assert!(history.status.success(), "{h}");
    let lines: Vec<&str> = h.lines().collect();
    assert_eq!(lines[0], "Landing Lt: current at each check (UTC)", "{h}");
    assert!(lines[1].contains(&format!("  {} ", amps(was))), "{h}");
    assert!(
        lines[2].contains(&format!("  {}   +{pct} % ⚠ changed", amps(now))),
        "{h}"
    );
    assert_eq!(lines.len(), 4, "two checks and the mark's words: {h}");

    let json = vpx(d, &["log", "--json"]);
    assert!(json.status.success(), "{}", text(&json));
    let entries: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let kinds: Vec<&str> = entries
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["kind"].as_str().unwrap())
        .filter(|k| ["check", "backup"].contains(k))
        .collect();
    // Newest first: the second check, the backup, the first check.
    assert_eq!(kinds, ["check", "backup", "check"], "{entries:#}");

    let table = vpx(d, &["log", "--circuit", "Landing Lt", "--json"]);
    let rows: serde_json::Value = serde_json::from_slice(&table.stdout).unwrap();
    let readings: Vec<f64> = rows
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["amps"].as_f64().unwrap())
        .collect();
    assert_eq!(readings.len(), 2, "{rows:#}");
    assert!(
        (readings[0] * 10.0 - f64::from(was)).abs() < 0.01
            && (readings[1] * 10.0 - f64::from(now)).abs() < 0.01,
        "{readings:?}"
    );

    let page = d.join("n123ab.html");
    let export = vpx(d, &["log", "--export", &page.to_string_lossy()]);
    assert!(export.status.success(), "{}", text(&export));
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("N123AB: electrical records"));
    assert!(
        html.contains(&format!("{} (+{pct} %)<br>⚠ changed", amps(now))),
        "{html}"
    );
    assert!(!html.contains("http") && !html.contains("//"));

    // Bad input: a circuit the logbook does not know names the ones it does.
    let unknown = vpx(d, &["log", "--circuit", "Strobe"]);
    assert_eq!(unknown.status.code(), Some(2));
    let u = text(&unknown);
    assert!(u.contains("no circuit named \"Strobe\""), "{u}");
    assert!(
        u.contains("the circuits its checks know: EFIS, Field_Pri, Landing Lt, Nav Lt, Starter"),
        "{u}"
    );
}

#[test]
fn without_a_logbook_it_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let none = vpx(d, &["log"]);
    assert!(!none.status.success());
    let t = text(&none);
    assert!(
        t.contains("logbook.sqlite: no logbook there (nothing has been recorded yet)"),
        "{t}"
    );
}

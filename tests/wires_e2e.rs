//! Wires against breakers, end to end: `vpx-efis sim --pty --scenario
//! wires` as a process of its own, and `vpx-efis wires`, `backup`, `restore` and
//! `check` as others, or the page's `App` on the sim's pty for setup.
//!
//! The `wires` scenario's unit holds a 6 A breaker on the strobe (10A-1, 3.5 A) and 3 A
//! on the nav lights (5A-1, 2.0 A), both switched on. The load file below gives them:
//! - the strobe 22 AWG: AC 43.13-1B Table 11-3 allows 5 A, so 6 A is unprotected;
//! - the nav lights 22 AWG over 24 ft and a 10 ft return: ¶11-67's run is 34 ft, and
//!   at 2.0 A Table 11-9's 16.20 Ω/1000 ft drops 0.0162 × 34 × 2.0 = 1.1016 V, over
//!   the 0.5 V Table 11-6 allows a 14 V system (bus 14.1 V, limit 16 V);
//! - the landing light (10A-2, 8 A, off) 16 AWG over 12 ft: Table 11-3 allows 15 A.
//!
//! Corrected, the strobe is 20 AWG (7.5 A allowed) and the nav lights 18 AWG:
//! 0.00623 × 34 × 2.0 = 0.4236 V, under 0.5 V.
// Needs a pseudo-terminal, which only Unix has.
#![cfg(unix)]

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::process::{self, sim_pty};

const WRONG: &str = r#"
[circuit.5A-1]
name = "Nav Lt"
wire = "22 AWG"
wire_length = "24 ft"
return_length = "10 ft"

[circuit.10A-1]
name = "Strobe Lt"
wire = "22 AWG"
wire_length = "6 ft"

[circuit.10A-2]
name = "Landing Lt"
wire = "16 AWG"
wire_length = "12 ft"
"#;

fn corrected() -> String {
    WRONG
        .replacen("wire = \"22 AWG\"", "wire = \"18 awg\"", 1)
        .replacen("wire = \"22 AWG\"", "wire = \"20 AWG\"", 1)
}

/// `vpx-efis ARGS` with no terminal on stdin and a config file that is not there.
fn vpx(dir: &Path, args: &[&str]) -> Output {
    process::vpx(args, dir.join("config.toml"))
        .output()
        .expect("run vpx-efis")
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// `vpx-efis backup` of the unit on `port`, into `dir`.
fn backup_of(dir: &Path, port: &str) -> PathBuf {
    let backup = dir.join("unit.toml");
    let o = vpx(dir, &["backup", "--port", port, backup.to_str().unwrap()]);
    assert!(o.status.success(), "{}", err(&o));
    backup
}

/// `vpx-efis wires --json` against the unit on `port` with the load file `loads`.
fn wires_json(dir: &Path, port: &str, loads: &str) -> Output {
    vpx(dir, &["wires", "--port", port, "--loads", loads, "--json"])
}

/// `wires --json`'s row for `pin`.
fn row<'a>(rows: &'a serde_json::Value, pin: &str) -> &'a serde_json::Value {
    rows.as_array()
        .unwrap()
        .iter()
        .find(|r| r["pin"] == pin)
        .unwrap_or_else(|| panic!("no row for {pin}: {rows:#}"))
}

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_str(&out(o)).unwrap_or_else(|e| panic!("{e}: {}", out(o)))
}

#[test]
fn wires_finds_the_unprotected_strobe_and_the_long_run_then_passes_once_corrected() {
    let dir = tempfile::tempdir().unwrap();
    let (_sim, port) = sim_pty("wires");
    let loads = write(dir.path(), "loads.toml", WRONG);
    let loads = loads.to_str().unwrap();

    let o = vpx(dir.path(), &["wires", "--port", &port, "--loads", loads]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let text = out(&o);
    assert!(
        text.contains(
            "UNPROTECTED 10A-1: Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows \
             5 A; a 6 A breaker would not protect it."
        ),
        "{text}"
    );
    // The sim's current wanders by a tenth or so about its 2.0 A; the drop with it.
    assert!(text.contains("DROP 5A-1: Nav Lt drops "), "{text}");
    assert!(
        text.contains(" through 34.0 ft (feed and return)"),
        "{text}"
    );
    assert!(text.contains("allows 0.5 V continuous"), "{text}");
    assert!(
        err(&o).contains("1 breaker(s) do not protect their wire, 1 measured drop(s)"),
        "{}",
        err(&o)
    );

    let o = wires_json(dir.path(), &port, loads);
    assert_eq!(o.status.code(), Some(1));
    let rows = json(&o);
    let strobe = row(&rows, "10A-1");
    assert_eq!(strobe["name"], "Strobe Lt");
    assert_eq!(strobe["wire"], "22 AWG");
    assert_eq!(strobe["breaker_amps"], 6);
    assert_eq!(strobe["max_breaker_amps"], 5.0);
    assert_eq!(strobe["run_feet"], 6.0);
    assert_eq!(strobe["verdict"], "unprotected");
    let nav = row(&rows, "5A-1");
    assert_eq!(nav["run_feet"], 34.0);
    assert_eq!(nav["drop_limit_volts"], 0.5);
    assert_eq!(nav["verdict"], "drop");
    let amps = nav["amps"].as_f64().unwrap();
    assert!((1.8..=2.2).contains(&amps), "the scenario's 2.0 A: {amps}");
    // 16.20 Ω per 1000 ft (Table 11-9) × 34 ft × the current measured.
    let drop = nav["drop_volts"].as_f64().unwrap();
    assert!((drop - 0.0162 * 34.0 * amps).abs() < 0.001, "{drop}");
    let landing = row(&rows, "10A-2");
    assert_eq!(landing["max_breaker_amps"], 15.0);
    assert_eq!(landing["verdict"], "ok");
    assert_eq!(row(&rows, "EFIS")["verdict"], "not entered");

    let fixed = write(dir.path(), "fixed.toml", &corrected());
    let o = wires_json(dir.path(), &port, fixed.to_str().unwrap());
    assert_eq!(o.status.code(), Some(0), "{}{}", out(&o), err(&o));
    let rows = json(&o);
    assert_eq!(row(&rows, "10A-1")["max_breaker_amps"], 7.5);
    for pin in ["5A-1", "10A-1", "10A-2"] {
        assert_eq!(row(&rows, pin)["verdict"], "ok", "{pin}");
    }
    // 0.00623 × 34 × the current measured, under 0.5 V.
    let nav = row(&rows, "5A-1");
    let amps = nav["amps"].as_f64().unwrap();
    let drop = nav["drop_volts"].as_f64().unwrap();
    assert!((drop - 0.00623 * 34.0 * amps).abs() < 0.001, "{drop}");
}

#[test]
fn a_bad_wire_line_is_named_by_path_line_and_field_and_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let (_sim, port) = sim_pty("wires");
    for (from, to, said) in [
        (
            "wire = \"22 AWG\"\nwire_length = \"6 ft\"",
            "wire = \"21 AWG\"\nwire_length = \"6 ft\"",
            "line 10: [circuit.10A-1] wire: \"21 AWG\": there is no 21 AWG in AC 43.13-1B \
             Table 11-9",
        ),
        (
            "\"24 ft\"",
            "\"500 ft\"",
            "line 5: [circuit.5A-1] wire_length: \"500 ft\" is implausible",
        ),
        (
            "\"10 ft\"",
            "\"0 m\"",
            "line 6: [circuit.5A-1] return_length: \"0 m\": a wire's length is more than 0",
        ),
        (
            "\"12 ft\"",
            "\"12 furlongs\"",
            "line 16: [circuit.10A-2] wire_length: \"12 furlongs\": say the unit",
        ),
    ] {
        let text = WRONG.replacen(from, to, 1);
        assert_ne!(text, WRONG, "{from}");
        let loads = write(dir.path(), "bad.toml", &text);
        let o = vpx(
            dir.path(),
            &["wires", "--port", &port, "--loads", loads.to_str().unwrap()],
        );
        assert_eq!(o.status.code(), Some(2), "{to}: {}", err(&o));
        let e = err(&o);
        assert!(
            e.contains(&format!("load file {}, {said}", loads.display())),
            "{to}: {e}"
        );
        assert!(out(&o).is_empty(), "no rows from a bad file: {}", out(&o));
    }
}

#[test]
fn from_a_backup_only_breaker_against_wire_is_judged() {
    let dir = tempfile::tempdir().unwrap();
    let (sim, port) = sim_pty("wires");
    let backup = backup_of(dir.path(), &port);
    drop(sim);
    let loads = write(dir.path(), "loads.toml", WRONG);
    let o = vpx(
        dir.path(),
        &[
            "wires",
            "--from-backup",
            backup.to_str().unwrap(),
            "--loads",
            loads.to_str().unwrap(),
            "--json",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let rows = json(&o);
    assert_eq!(row(&rows, "10A-1")["verdict"], "unprotected");
    // No unit, no current: the long run is not judged, only its wire's breaker.
    let nav = row(&rows, "5A-1");
    assert_eq!(nav["verdict"], "ok");
    assert_eq!(nav["amps"], serde_json::Value::Null);
    // The drop at its 3 A breaker is still shown: 0.0162 × 34 × 3 = 1.6524 V.
    assert_eq!(nav["drop_at_breaker_volts"], 1.652);
    // The backup's 16 V limit tells the system: 14 V, 0.5 V.
    assert_eq!(nav["drop_limit_volts"], 0.5);
}

/// `vpx-efis restore --port PORT BACKUP --yes --loads LOADS`.
fn restore(home: &Path, port: &str, backup: &str, loads: &Path) -> Output {
    let loads = loads.to_str().unwrap();
    vpx(
        home,
        &["restore", "--port", port, backup, "--yes", "--loads", loads],
    )
}

#[test]
fn restore_lists_each_breaker_over_its_wire_and_writes_nothing_unasked() {
    let dir = tempfile::tempdir().unwrap();
    let (_sim, port) = sim_pty("wires");
    let backup = backup_of(dir.path(), &port);
    // The strobe's breaker raised to 7 A in the backup: over 22 AWG's 5 A, and a
    // difference for the restore to write.
    let text = std::fs::read_to_string(&backup).unwrap();
    let raised = text.replacen(
        "name = \"Strobe Lt\"\nshow_on_page = true\nbreaker_amps = 6",
        "name = \"Strobe Lt\"\nshow_on_page = true\nbreaker_amps = 7",
        1,
    );
    assert_ne!(raised, text, "the strobe's breaker in the backup:\n{text}");
    std::fs::write(&backup, raised).unwrap();
    let loads = write(dir.path(), "loads.toml", WRONG);
    let b = backup.to_str().unwrap();

    // --yes does not answer it, and with no terminal nobody can: nothing written.
    let o = restore(dir.path(), &port, b, &loads);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(
        out(&o).contains(&format!(
            "1 breaker(s) in {b} would not protect their wire (AC 43.13-1B ¶11-48):"
        )),
        "{}",
        out(&o)
    );
    assert!(
        out(&o).contains(
            "  Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 7 A \
             breaker would not protect it"
        ),
        "{}",
        out(&o)
    );
    assert!(err(&o).contains("nothing was written"), "{}", err(&o));
    let o = wires_json(dir.path(), &port, loads.to_str().unwrap());
    assert_eq!(row(&json(&o), "10A-1")["breaker_amps"], 6, "still 6 A");

    // With the wire corrected (20 AWG: 7.5 A), the same backup is written.
    let fixed = write(dir.path(), "fixed.toml", &corrected());
    let o = restore(dir.path(), &port, b, &fixed);
    assert!(o.status.success(), "{}{}", out(&o), err(&o));
    assert!(!out(&o).contains("would not protect"), "{}", out(&o));
    let o = wires_json(dir.path(), &port, fixed.to_str().unwrap());
    assert_eq!(row(&json(&o), "10A-1")["breaker_amps"], 7);
}

/// The headless check against the sim: its report's Wires section fails the strobe
/// and warns of the nav lights' drop, with the run that would bring it under
/// (0.5 / (0.0162 × 2.0) = 15.4 ft at the scenario's 2.0 A; worked below at the current
/// the check measured, which wanders by a tenth or so).
#[test]
fn the_checks_report_has_its_wires_section() {
    let dir = tempfile::tempdir().unwrap();
    let (_sim, port) = sim_pty("wires");
    // The ratings the load analysis needs, then the wires.
    let text = format!("alternator_amps = 40\nbattery_amp_hours = 17\n{WRONG}");
    let loads = write(dir.path(), "loads.toml", &text);
    let reports = dir.path().join("reports");
    let o = vpx(
        dir.path(),
        &[
            "check",
            "--port",
            &port,
            "--yes",
            "--skip",
            "switches,motors",
            "--loads",
            loads.to_str().unwrap(),
            "--report",
            reports.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let md = std::fs::read_dir(&reports)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "md"))
        .expect("a Markdown report");
    let report = std::fs::read_to_string(md).unwrap();
    let wires = &report[report.find("## Wires").expect("a Wires section")..];
    let wires = &wires[..wires[3..].find("\n## ").map_or(wires.len(), |e| e + 3)];
    assert!(report.starts_with("# VP-X installation check"), "{report}");
    assert!(report.contains("**Result: FAILED.**"), "{report}");
    assert!(
        wires.contains(
            "- ✗ FAIL Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 6 A \
             breaker would not protect it."
        ),
        "{wires}"
    );
    assert!(wires.contains("- ⚠ WARN Nav Lt drops"), "{wires}");
    let nav = wires
        .lines()
        .find(|l| l.starts_with("| 5A-1 | Nav Lt | 22 AWG | 34.0 ft | 3 A | 5 A |"))
        .unwrap_or_else(|| panic!("no nav row: {wires}"));
    let measured: f64 = nav
        .split('|')
        .nth(7)
        .unwrap()
        .trim()
        .trim_end_matches(" A")
        .parse()
        .unwrap();
    assert!((1.8..=2.2).contains(&measured), "{nav}");
    let longest = 0.5 / (0.0162 * measured);
    assert!(
        wires.contains(&format!(
            "a run of at most {longest:.1} ft would bring it under"
        )),
        "{longest}: {wires}"
    );
    assert!(nav.ends_with("| 0.5 V | ⚠ WARN |"), "{nav}");
    assert!(
        wires.contains("| 10A-1 | Strobe Lt | 22 AWG | 6.0 ft | 6 A | 5 A |"),
        "{wires}"
    );
}

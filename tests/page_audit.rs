//! The audit log through the real page against the virtual VP-X on a
//! real pseudo-terminal (`page_rig`), with `--xfsp-control` on a UDP peer on
//! 127.0.0.1: a power key, a reset, a motor run, the installation check and an XFSp
//! command each leave their line, with their origin, in the logbook's audit log, read
//! back as the JSON lines `vpx-efis log --jsonl` gives.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

mod common;
mod page_rig;
use page_rig::*;

use std::path::Path;
use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEventKind};
use serde_json::Value;
use vpx_efis::app::{App, AppOptions};
use vpx_efis::check::Options;
use vpx_efis::check::state::Step;
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::sim::SimCommand;
use vpx_efis::ui::state::ReleaseMode;
use vpx_efis::xfsp::EcbState;
use vpx_efis::xfsp::gateway::{Control, GatewayConfig};

/// Every line of the audit log in the logbook at `path`, each parsed (a line that
/// is not JSON fails the test); none while the logbook is not there yet.
fn audit_lines(path: &Path) -> Vec<Value> {
    if !path.exists() {
        return Vec::new();
    }
    vpx_efis::logbook::jsonl::all_audit_lines(path)
        .unwrap_or_default()
        .iter()
        .map(|line| serde_json::from_str(line).unwrap_or_else(|e| panic!("not JSON ({e}): {line}")))
        .collect()
}

/// The page's loop for `ms` milliseconds.
fn pump(app: &mut App, ms: u64) {
    app.pump_until(Instant::now() + Duration::from_millis(ms));
}

fn has(lines: &[Value], origin: &str, command: &str, extra: impl Fn(&Value) -> bool) -> bool {
    lines.iter().any(|l| {
        l["origin"] == origin
            && l["command"]
                .as_str()
                .is_some_and(|c| c.starts_with(command))
            && l["result"] == "sent"
            && extra(l)
    })
}

#[test]
fn every_command_from_every_origin_leaves_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let audit = dir.path().join("logbook.sqlite");
    let mut rig = Rig::with_options(AppOptions {
        release_mode: ReleaseMode::KeyRelease,
        logbook: Some(vpx_efis::logbook::Target {
            path: audit.clone(),
            aircraft: None,
        }),
        ..AppOptions::default()
    });
    let mut peer = common::xfsp_peer::PagePeer::new();
    let target = peer.target();
    rig.app
        .enable_xfsp(
            &target,
            "127.0.0.1".parse().unwrap(),
            GatewayConfig {
                control: Control::Any,
                ..GatewayConfig::default()
            },
        )
        .unwrap();
    rig.ready();

    // A power key: Nav Lt (device 4, its switch on) off with `f`.
    rig.select(4);
    rig.key(KeyCode::Char('f'), KeyEventKind::Press);
    let end = Instant::now() + Duration::from_secs(5);
    while rig.sim.stats().powered[4] && Instant::now() < end {
        pump(&mut rig.app, 20);
    }

    // A reset: GPS 1 (device 9) trips, and `r` resets it.
    rig.sim.inject(SimCommand::Fault {
        device: 9,
        code: FaultCode::OverCurrent,
    });
    rig.until("GPS 1 faulted", Duration::from_secs(5), |app, now| {
        app.model()
            .live_faults(now)
            .is_some_and(|(f, _)| f[9].is_fault())
    });
    rig.select(9);
    rig.key(KeyCode::Char('r'), KeyEventKind::Press);

    // A motor run: pitch trim up held for about a second (repeats, then release).
    rig.select(30);
    let start = Instant::now();
    rig.key(KeyCode::Char('u'), KeyEventKind::Press);
    while start.elapsed() < Duration::from_millis(1200) {
        pump(&mut rig.app, 33);
        rig.key(KeyCode::Char('u'), KeyEventKind::Repeat);
    }
    rig.key(KeyCode::Char('u'), KeyEventKind::Release);
    pump(&mut rig.app, 300);

    // An XFSp command: ECBSTAT ON for Nav Lt from a node on the network.
    peer.wait_for_page(Duration::from_secs(5), || pump(&mut rig.app, 30), |_| true);
    peer.ecbstat(0x0777, 4, EcbState::On);
    let end = Instant::now() + Duration::from_secs(5);
    while !rig.sim.stats().powered[4] && Instant::now() < end {
        pump(&mut rig.app, 20);
    }

    // The check: circuits only, until it has switched something.
    let options = Options {
        skip: vec![Step::Switches, Step::Motors],
        loads_file: Some(dir.path().join("loads.toml")),
        ..Options::default()
    };
    rig.app
        .set_check_report_dir(Some(dir.path().join("reports")));
    rig.app.open_check(options, Instant::now());
    rig.key(KeyCode::Enter, KeyEventKind::Press);
    let end = Instant::now() + Duration::from_secs(30);
    while !has(&audit_lines(&audit), "check", "DEVICE_POWER", |_| true) {
        assert!(
            Instant::now() < end,
            "the check sent nothing: {:#?}",
            audit_lines(&audit)
        );
        // Nav Lt, on from the network, is held for "is it lit?" until answered.
        let asked = rig.app.check_view().prompt.as_ref();
        if asked.is_some_and(|p| p.todo.contains("lit?")) {
            rig.key(KeyCode::Char('y'), KeyEventKind::Press);
        }
        pump(&mut rig.app, 50);
    }
    rig.key(KeyCode::Esc, KeyEventKind::Press);
    pump(&mut rig.app, 300);

    // Written off the page's thread: within moments of each command.
    let lines = audit_lines(&audit);
    let all = format!("{lines:#?}");
    for (origin, command, what) in [
        (
            "key",
            "DEVICE_POWER: device 4 5A-1, power state off",
            "Nav Lt off by key",
        ),
        ("key", "DEVICE_CLEAR", "GPS 1 reset"),
        (
            "xfsp",
            "DEVICE_POWER: device 4 5A-1, power state on",
            "Nav Lt on from the network",
        ),
        ("check", "DEVICE_POWER", "the check"),
    ] {
        assert!(has(&lines, origin, command, |_| true), "{what}: {all}");
    }
    assert!(
        has(&lines, "key", "TRIM_MOVE", |l| l["run"] == "start"),
        "the run's start: {all}"
    );
    let stop = lines
        .iter()
        .find(|l| l["run"] == "stop" && l["run_origin"] == "key")
        .unwrap_or_else(|| panic!("the run's stop: {all}"));
    let moves = stop["moves"].as_u64().unwrap();
    // Held about 1.2 s, resent every 125 ms (control's RESEND_PERIOD).
    assert!((6..=14).contains(&moves), "moves in the run: {moves}");
    assert_eq!(
        lines
            .iter()
            .filter(|l| l["origin"] == "key"
                && l["command"]
                    .as_str()
                    .is_some_and(|c| c.starts_with("TRIM_MOVE")))
            .count(),
        2,
        "a run is two lines, not one per resend: {all}"
    );
    assert!(
        lines
            .iter()
            .all(|l| l["time"].as_str().is_some_and(|t| t.ends_with('Z'))),
        "{all}"
    );
    assert!(
        !lines
            .iter()
            .any(|l| l["command"].as_str().is_some_and(|c| c.contains("QUERY"))),
        "queries are no commands: {all}"
    );
    // The same actions, in the page's event log with their origin.
    let model = rig.app.model();
    let events: Vec<&str> = model.events.iter().map(|e| e.text.as_str()).collect();
    for words in [
        "key: Nav Lt off (DEVICE_POWER sent)",
        "key: GPS 1 reset (DEVICE_CLEAR sent)",
        "check: the installation check started",
        "XFSp 0x0777 (USERSEL): Nav Lt ON -> DEVICE_POWER",
    ] {
        assert!(
            events.iter().any(|e| e.contains(words)),
            "{words:?} not in the event log: {events:#?}"
        );
    }
    drop(model);
    let Rig { app, sim, .. } = rig;
    app.shutdown();
    sim.stop();
}

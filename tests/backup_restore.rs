//! `backup` and `restore` end to end: the virtual VP-X on the master of a real
//! pseudo-terminal, and on its slave path either the `vpx-efis` binary itself
//! (`--port PATH`) or a [`UnitClient`] opened like any serial port; and the same over
//! TCP (`--port tcp://…`), with the unit behind the line `vpx-efis sim --tcp` serves.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

use serialport::TTYPort;
use vpx_efis::exchange::TRIES;
use vpx_efis::link::request::query_answers;
use vpx_efis::link::{RequestError, SpecError, UnitClient, open_pty_pair, serial_connector};
use vpx_efis::protocol::config::UnitConfig;
use vpx_efis::protocol::message::{
    DeviceName, DeviceSpec, DeviceSpecQuery, FlapSpec, Message, SpecAckError, SwitchId, SystemSpec,
    Tenths, TrimSpec, WigWagSpec,
};
use vpx_efis::sim::{self, SimCommand, SimHandle, SimOptions};

#[path = "common/process.rs"]
#[allow(dead_code)]
mod process;
#[path = "common/tcp_unit.rs"]
mod tcp_unit;
use tcp_unit::unit_over_tcp;

/// Far above what any command here needs on a loaded two-core machine; reaching it
/// means a hang, which is the failure these tests exist to catch.
const HANG: Duration = Duration::from_secs(60);

struct Bench {
    sim: SimHandle,
    /// Held open so the master never sees the slave side close between commands.
    _slave: TTYPort,
    path: String,
    dir: tempfile::TempDir,
}

fn bench(scenario: &str, tweak: impl FnOnce(&mut SimOptions, &Path)) -> Bench {
    let dir = tempfile::tempdir().unwrap();
    let pty = open_pty_pair().expect("a pseudo-terminal");
    let reader = pty.master.try_clone_native().expect("clone the pty master");
    let mut opts = SimOptions::new(sim::load_scenario(scenario).unwrap());
    tweak(&mut opts, dir.path());
    let sim = sim::spawn(opts, Box::new(reader), Box::new(pty.master));
    Bench {
        sim,
        _slave: pty.slave,
        path: pty.path,
        dir,
    }
}

impl Bench {
    fn client(&self) -> UnitClient {
        UnitClient::new(serial_connector(PathBuf::from(&self.path), 57_600))
            .expect("open the pty slave as a serial port")
    }

    fn file(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// `vpx-efis backup` of the unit into the file `name` of the bench's folder.
    fn backup(&self, name: &str) -> PathBuf {
        let file = self.file(name);
        ok(&self.vpx(&["backup", file.to_str().unwrap()]));
        file
    }

    /// Runs `vpx-efis ARGS --port <slave>` with no terminal on stdin.
    fn vpx(&self, args: &[&str]) -> Output {
        let mut all: Vec<&str> = args.to_vec();
        all.extend(["--port", &self.path]);
        run(&all)
    }

    fn config(&self) -> UnitConfig {
        self.sim.stats().config
    }
}

fn run(args: &[&str]) -> Output {
    let mut child = process::vpx(args, process::NO_CONFIG)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > HANG {
            let _ = child.kill();
            panic!("vpx-efis {args:?} hung for {HANG:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// `text`, as the program printed or wrote it, holds `words`; else the test fails
/// showing all of it.
#[track_caller]
fn assert_says(text: &str, words: &str) {
    assert!(text.contains(words), "no {words:?} in:\n{text}");
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[track_caller]
fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "failed: {}\nstdout:\n{}\nstderr:\n{}",
        o.status,
        stdout(o),
        stderr(o)
    );
}

/// A backup file's text without its `[made]` section (which differs by the time).
fn settings_of(file: &Path) -> String {
    let text = std::fs::read_to_string(file).unwrap();
    let start = text.find("[made]\n").expect("a [made] section");
    let end = start
        + text[start..]
            .find("\n\n")
            .expect("a blank line after [made]")
        + 2;
    format!("{}{}", &text[..start], &text[end..])
}

fn first_pin_with(cfg: &UnitConfig, f: impl Fn(&DeviceSpec) -> bool) -> u8 {
    (4..=28u8)
        .find(|&i| {
            f(&cfg.devices[i as usize])
                && !cfg.is_wig_wag_device(i)
                && !cfg.is_secondary_alternator(i)
        })
        .expect("the demo scenario has such a pin")
}

#[test]
fn backup_then_change_the_unit_then_restore_then_backup_gives_the_same_file() {
    let b = bench("demo", |_, _| {});
    let first = b.backup("first.toml");
    let original = b.config();

    // Change the unit the way someone at the setup screens might, including a change
    // that ties settings together: a pin that is off in the backup becomes the wig-wag
    // device, so restoring must untie the wig-wag before it can switch that pin off.
    let mut c = b.client();
    let spare = first_pin_with(&original, |d| d.switch_id == SwitchId::Off);
    let edits: Vec<Message> = vec![
        DeviceSpec {
            device_id: spare,
            circuit_breaker: 1,
            switch_id: SwitchId::Input(7),
            current_fault: false,
            switch_raw: None,
        }
        .into(),
        WigWagSpec {
            device_one: Some(spare),
            device_two: None,
            warm_up_period: 30,
            speed: 90,
        }
        .into(),
        SystemSpec {
            secondary_alternator: None,
            ..original.system
        }
        .into(),
        FlapSpec {
            endpoint_duration: Tenths(12),
            max_speed: 85,
            ..original.flap
        }
        .into(),
        TrimSpec {
            power: 45,
            ..original.pitch_trim
        }
        .into(),
        DeviceName::new(5, "Changed").unwrap().into(),
    ];
    for m in edits {
        c.send_spec(m, Duration::from_secs(1), TRIES)
            .unwrap_or_else(|e| panic!("setting up the test: {e}"));
    }
    assert!(c.set_enable(6, !original.enabled[6]).unwrap());
    c.close();
    let changed = b.backup("changed.toml");
    assert_ne!(
        settings_of(&first),
        settings_of(&changed),
        "the edits must show in a backup, or this test proves nothing"
    );

    let out = b.vpx(&["restore", "--yes", first.to_str().unwrap()]);
    ok(&out);
    let listed = stdout(&out);
    for words in [
        format!(
            "flap endpoint duration: 1.2 s → {:.1} s",
            original.flap.endpoint_duration.0 as f64 / 10.0
        ),
        "Strobe Lt".into(),
        "wig-wag device one:".into(),
        "secondary alternator: none → 15A-1".into(),
    ] {
        assert!(
            listed.contains(&words),
            "the diff should say {words:?}:\n{listed}"
        );
    }
    assert_says(&stderr(&out), "verified");

    let again = b.backup("again.toml");
    assert_eq!(settings_of(&first), settings_of(&again));
    assert_eq!(b.config(), original);
}

#[test]
fn restore_with_erase_first_erases_then_imports() {
    let b = bench("demo", |_, _| {});
    let file = b.backup("demo.toml");
    let original = b.config();
    let writes_before = b.sim.stats().eeprom_writes;

    let out = b.vpx(&["restore", "--yes", "--erase-first", file.to_str().unwrap()]);
    ok(&out);
    assert_says(&stderr(&out), "EEPROM erased");
    assert_eq!(b.config(), original);
    // Everything that differs from the factory defaults was written again, so an
    // erase really happened in between.
    assert!(b.sim.stats().eeprom_writes > writes_before + 10);
}

#[test]
fn an_unchanged_unit_gets_no_writes() {
    let b = bench("demo", |_, _| {});
    let file = b.backup("demo.toml");
    let writes = b.sim.stats().eeprom_writes;
    let out = b.vpx(&["restore", "--yes", file.to_str().unwrap()]);
    ok(&out);
    assert_says(&stdout(&out), "nothing to write");
    assert_eq!(b.sim.stats().eeprom_writes, writes);
}

#[test]
fn without_a_terminal_or_yes_the_restore_asks_nobody_and_writes_nothing() {
    let b = bench("demo", |_, _| {});
    let file = b.backup("demo.toml");
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("warm_up_s = 5", "warm_up_s = 9");
    std::fs::write(&file, text).unwrap();
    let writes = b.sim.stats().eeprom_writes;
    let out = b.vpx(&["restore", file.to_str().unwrap()]);
    assert!(!out.status.success());
    assert_says(&stdout(&out), "wig-wag warm-up: 5 s → 9 s");
    assert_says(&stderr(&out), "Run again with --yes");
    assert_eq!(b.sim.stats().eeprom_writes, writes);
}

/// Each problem file is refused with its field named, and the unit hears nothing
/// (nothing at all for a bad file; only VERSION for a file from other hardware).
#[test]
fn bad_files_are_refused_by_field_and_nothing_is_sent() {
    let b = bench("demo", |_, _| {});
    let good = b.backup("good.toml");
    let text = std::fs::read_to_string(&good).unwrap();
    let frames_before = b.sim.stats().wire.rx_frames;
    let writes = b.sim.stats().eeprom_writes;

    let cases = [
        (
            "malformed.toml",
            text.replace("[wig_wag]", "[wig_wag"),
            vec!["malformed.toml, line ", ": not valid TOML"],
        ),
        (
            "typed.toml",
            text.replace("warm_up_s = 5", "warm_up_s = \"five\""),
            vec!["wig_wag.warm_up_s: must be a whole number 0–255, not a string"],
        ),
        (
            "range.toml",
            text.replace(
                "overvoltage_limit_volts = 16",
                "overvoltage_limit_volts = 24",
            )
            .replace("warm_up_s = 5", "warm_up_s = 61")
            .replace("max_speed_kt = 100", "max_speed_kt = 501"),
            vec![
                "Nothing was sent to the unit.",
                ": system.overvoltage_limit_volts: must be 16 or 32",
                ": flaps.max_speed_kt: flap max speed 501 is above 500",
                ": wig_wag.warm_up_s: warm-up 61 s is outside 5–60 s",
            ],
        ),
    ];
    for (name, body, expect) in cases {
        let f = b.file(name);
        std::fs::write(&f, body).unwrap();
        let out = b.vpx(&["restore", "--yes", f.to_str().unwrap()]);
        assert!(!out.status.success(), "{name} was accepted");
        for e in expect {
            assert!(
                stderr(&out).contains(e),
                "{name}: missing {e:?} in\n{}",
                stderr(&out)
            );
        }
    }
    assert_eq!(
        b.sim.stats().wire.rx_frames,
        frames_before,
        "a file refused on its own must not reach the unit at all"
    );

    let f = b.file("sport.toml");
    std::fs::write(
        &f,
        text.replace("hardware_version = 2", "hardware_version = 3"),
    )
    .unwrap();
    let out = b.vpx(&["restore", "--yes", f.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains(
            "this backup is from a VP-X Sport (hardware version 3) but the unit is a VP-X Pro (hardware version 2)"
        ),
        "{}",
        stderr(&out)
    );
    assert_eq!(
        b.sim.stats().wire.rx_frames,
        frames_before + 1,
        "only VERSION may be asked before the hardware is known"
    );
    assert_eq!(b.sim.stats().eeprom_writes, writes);
}

/// Every SPEC_ACK code the virtual unit can send, each shown in the words of ICD
/// Table 20.
#[test]
fn every_spec_ack_error_code_is_shown_in_words() {
    let b = bench("demo", |o, dir| {
        o.eeprom = Some(dir.join("eeprom/unit.json"))
    });
    std::fs::create_dir(b.dir.path().join("eeprom")).unwrap();
    let mut c = b.client();
    let cfg = b.config();
    let sec = cfg
        .system
        .secondary_alternator
        .expect("demo has a secondary alternator");
    let wig = cfg.wig_wag.device_one.expect("demo has a wig-wag");
    let primary_switch = cfg.devices[3].switch_id;
    let pin = |id: u8| cfg.devices[id as usize];

    let cases: Vec<(Message, SpecAckError, &str)> = vec![
        (
            TrimSpec {
                power: 95,
                ..cfg.pitch_trim
            }
            .into(),
            SpecAckError::OutOfRange,
            "Parameter value out of range",
        ),
        (
            DeviceSpec {
                device_id: 0,
                ..pin(4)
            }
            .into(),
            SpecAckError::InvalidDevice,
            "Invalid device identifier",
        ),
        (
            DeviceSpec {
                circuit_breaker: 9,
                ..pin(4)
            }
            .into(),
            SpecAckError::InvalidBreaker,
            "Invalid circuit breaker value",
        ),
        (
            DeviceSpec {
                switch_id: SwitchId::Off,
                ..pin(2)
            }
            .into(),
            SpecAckError::InvalidSwitch,
            "Invalid switch ID",
        ),
        (
            WigWagSpec {
                device_one: None,
                device_two: Some(wig),
                ..cfg.wig_wag
            }
            .into(),
            SpecAckError::BadConfig,
            "Invalid configuration",
        ),
        (
            FlapSpec {
                up: 10,
                midpoint_1: 150,
                midpoint_2: 100,
                down: 200,
                ..cfg.flap
            }
            .into(),
            SpecAckError::BadOrder,
            "Parameters out of order",
        ),
        (
            DeviceSpec {
                switch_id: SwitchId::Off,
                ..pin(wig)
            }
            .into(),
            SpecAckError::WigWagConfig,
            "Wig-Wag configuration error",
        ),
        (
            DeviceSpec {
                switch_id: primary_switch,
                ..pin(sec)
            }
            .into(),
            SpecAckError::SecAltConfig,
            "Secondary alternator configuration error",
        ),
    ];
    for (m, code, words) in cases {
        let err = c.send_spec(m, Duration::from_secs(1), 1).unwrap_err();
        assert!(
            matches!(err, SpecError::Refused { error, .. } if error == code),
            "{m:?}: {err:?}"
        );
        let text = err.to_string();
        assert!(text.contains(words), "{text}");
        assert!(text.contains(&format!("{:#04x}", code.to_byte())), "{text}");
    }

    // EEPROM write failure: the unit's EEPROM file can no longer be written.
    std::fs::remove_dir_all(b.dir.path().join("eeprom")).unwrap();
    let valid = DeviceSpec {
        circuit_breaker: 1,
        ..pin(4)
    };
    let err = c.send_spec(valid, Duration::from_secs(1), 1).unwrap_err();
    assert!(
        matches!(
            err,
            SpecError::Refused {
                error: SpecAckError::EepromWrite,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("EEPROM write failure"), "{err}");
}

/// A refusal in the middle of a restore stops it, says what was applied and what was
/// not, and exits non-zero.
#[test]
fn a_refused_setting_stops_the_restore_and_says_what_was_and_was_not_applied() {
    let b = bench("demo", |o, dir| {
        o.eeprom = Some(dir.join("eeprom/unit.json"))
    });
    std::fs::create_dir(b.dir.path().join("eeprom")).unwrap();
    let file = b.backup("demo.toml");
    let flap_now = b.config().flap.endpoint_duration.0 as f64 / 10.0;
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("warm_up_s = 5", "warm_up_s = 9")
        .replace(
            &format!("endpoint_duration_s = {flap_now:?}"),
            "endpoint_duration_s = 2.5",
        );
    std::fs::write(&file, text).unwrap();
    std::fs::remove_dir_all(b.dir.path().join("eeprom")).unwrap();

    let out = b.vpx(&["restore", "--yes", file.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = stderr(&out);
    for words in [
        "restore stopped at WIG_WAG_SPEC: the unit refused WIG_WAG_SPEC: EEPROM write failure (SPEC_ACK code 0x06)",
        "Applied (0 of 2):\n  (none)",
        "Not applied (2):\n  WIG_WAG_SPEC\n  FLAP_SPEC",
    ] {
        assert!(err.contains(words), "missing {words:?} in\n{err}");
    }
}

#[test]
fn a_silent_unit_is_a_timeout_not_a_hang() {
    let b = bench("demo", |_, _| {});
    let mut c = b.client();
    b.sim.inject(SimCommand::Silent(Duration::from_secs(120)));
    let start = Instant::now();
    let err = c
        .request(
            DeviceSpecQuery { device_id: 6 },
            |m| query_answers(6, m),
            Duration::from_millis(300),
            3,
        )
        .unwrap_err();
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "{:?}",
        start.elapsed()
    );
    assert_eq!(
        err,
        RequestError::Timeout {
            what: "DEVICE_SPEC_QUERY for 5A-3".into(),
            tries: 3
        }
    );
    assert_eq!(
        err.to_string(),
        "the unit did not answer DEVICE_SPEC_QUERY for 5A-3 after 3 tries"
    );
    c.close();

    // The command itself: it gives up, says on what, and leaves no file behind.
    let file = b.file("never.toml");
    let start = Instant::now();
    let out = b.vpx(&["backup", file.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(
        start.elapsed() < Duration::from_secs(20),
        "{:?}",
        start.elapsed()
    );
    assert_says(
        &stderr(&out),
        "the unit did not answer VERSION after 3 tries",
    );
    assert!(!file.exists());
    assert_eq!(
        std::fs::read_dir(b.dir.path()).unwrap().count(),
        0,
        "no temporary file left"
    );
}

#[test]
fn a_missing_port_is_reported_without_waiting() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("x.toml");
    let start = Instant::now();
    let out = run(&[
        "backup",
        "--port",
        "/dev/does-not-exist-vpx",
        file.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(start.elapsed() < Duration::from_secs(10));
    assert_says(&stderr(&out), "no such port");
}

#[test]
fn restore_without_a_port_refuses_names_the_options_and_opens_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // Not even the file is read: the refusal comes first.
    let file = dir.path().join("missing.toml");
    let out = run(&["restore", "--yes", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    for words in [
        "--port PATH",
        "tcp://HOST:PORT",
        "VPX_EFIS_PORT",
        "--sim",
        "Nothing was opened",
    ] {
        assert!(err.contains(words), "{words:?} missing from: {err}");
    }
    assert!(!err.contains("virtual VP-X (scenario"), "{err}");
}

#[test]
fn restore_with_sim_goes_to_the_built_in_unit_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("sim.toml");
    ok(&run(&["backup", file.to_str().unwrap()]));
    let text = std::fs::read_to_string(&file).unwrap();
    assert_says(&text, "simulated = true");
    assert_says(
        &text,
        "from = \"the built-in virtual VP-X (scenario demo)\"",
    );
    let out = run(&["restore", "--sim", "--yes", file.to_str().unwrap()]);
    ok(&out);
    let err = stderr(&out);
    assert_says(&err, "THE VIRTUAL VP-X, not an aircraft");
    assert_says(&err, "SIMULATED");
    // A port given as a flag and --sim contradict each other.
    let out = run(&[
        "restore",
        "--sim",
        "--port",
        "/dev/ttyUSB0",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_says(&stderr(&out), "contradict");
}

#[test]
fn a_backup_says_when_from_what_and_by_what_and_restore_shows_it_before_asking() {
    let b = bench("demo", |_, _| {});
    let file = b.backup("made.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    let (backup, made) = vpx_efis::backup::load_made(&file).unwrap();
    let made = made.expect("a [made] section");
    assert_eq!(made.from, b.path);
    assert!(!made.simulated);
    assert!(made.by.starts_with("vpx-efis 0.1.0"), "{}", made.by);
    // YYYY-MM-DDTHH:MM:SS.mmmZ, this year or later.
    assert_eq!(made.at.len(), 24, "{}", made.at);
    assert!(
        made.at.ends_with('Z') && made.at[..4] >= *"2025",
        "{}",
        made.at
    );
    assert_says(&text, "software = \"2.1\"");
    assert_eq!(backup.version.software_major, 2);

    // Change one thing so there is something to confirm; nobody is there to confirm.
    std::fs::write(&file, text.replace("warm_up_s = 5", "warm_up_s = 9")).unwrap();
    let out = b.vpx(&["restore", file.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = stderr(&out);
    let shown = err
        .find(&format!("The backup was made {} from {}", made.at, b.path))
        .unwrap_or_else(|| panic!("provenance not shown: {err}"));
    assert_says(&err, "a VP-X Pro software 2.1, by vpx-efis 0.1.0");
    let asked = err
        .find("Run again with --yes")
        .expect("the refusal to ask");
    assert!(shown < asked, "shown after the question: {err}");
}

#[test]
fn a_backup_from_before_provenance_still_restores_and_says_it_cannot_tell() {
    let b = bench("demo", |_, _| {});
    let file = b.backup("old.toml");
    std::fs::write(&file, settings_of(&file)).unwrap();
    assert!(!std::fs::read_to_string(&file).unwrap().contains("[made]"));
    let out = b.vpx(&["restore", "--yes", file.to_str().unwrap()]);
    ok(&out);
    assert_says(&stderr(&out), "does not say when or from what it was made");
}

#[test]
fn backup_and_restore_over_tcp_bring_a_changed_unit_back() {
    let (sim, addr) = unit_over_tcp("demo");
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("tcp.toml");
    ok(&run(&["backup", "--port", &addr, file.to_str().unwrap()]));
    let original = sim.stats().config;
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains(&format!("from = \"{addr}\"")), "{text}");

    // Change a setting over TCP with a client, as the setup screens would.
    let mut c = UnitClient::new(vpx_efis::link::port_connector(
        &addr.parse().unwrap(),
        57_600,
    ))
    .unwrap();
    c.send_spec(
        Message::from(TrimSpec {
            power: 45,
            ..original.pitch_trim
        }),
        Duration::from_secs(1),
        TRIES,
    )
    .unwrap();
    c.close();
    assert_ne!(sim.stats().config, original, "the change must have landed");

    let out = run(&["restore", "--port", &addr, "--yes", file.to_str().unwrap()]);
    ok(&out);
    assert_says(&stderr(&out), "verified");
    assert_eq!(sim.stats().config, original);
}

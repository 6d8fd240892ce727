//! The command line as a person types it: every refusal comes before anything is
//! opened (exit code 2, words that say what to type instead), and the settings read
//! from flags, the environment and the config file show where they came from.

use std::path::Path;
use std::process::Output;

#[path = "common/process.rs"]
#[allow(dead_code)]
mod process;

fn vpx(args: &[&str], env: &[(&str, &str)], config: &Path) -> Output {
    let mut c = process::vpx(args, config);
    c.envs(env.iter().copied());
    c.output().unwrap()
}

fn no_config() -> std::path::PathBuf {
    process::NO_CONFIG.into()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Refused with exit code 2 and `words` in the message.
#[track_caller]
fn refused(o: &Output, words: &str) {
    assert_eq!(o.status.code(), Some(2), "{}", err(o));
    assert!(err(o).contains(words), "{words:?} not in: {}", err(o));
}

#[test]
fn only_standard_baud_rates_are_taken_from_flags_and_the_environment() {
    let c = no_config();
    for (args, words) in [
        (
            &["--baud", "0"][..],
            "0 is not a baud rate (it would hang up a real adapter)",
        ),
        (
            &["--baud", "57601"][..],
            "57601 is not a standard baud rate",
        ),
        (&["backup", "--baud", "0", "x.toml"][..], "hang up"),
        (
            &["restore", "--baud", "12", "x.toml"][..],
            "not a standard baud rate",
        ),
        (&["gateway", "--baud", "fast"][..], "not a number"),
        (&["flash", "--baud", "0", "cu_2.hex"][..], "hang up"),
    ] {
        refused(&vpx(args, &[], &c), words);
    }
    let o = vpx(&["config"], &[("VPX_EFIS_BAUD", "0")], &c);
    refused(&o, "0 is not a baud rate");
    let o = vpx(&["config"], &[("VPX_EFIS_BAUD", "115200")], &c);
    assert!(o.status.success(), "{}", err(&o));
    assert!(
        out(&o).contains("baud               115200")
            && out(&o).contains("environment (VPX_EFIS_BAUD)"),
        "{}",
        out(&o)
    );
}

#[test]
fn the_xfsp_options_are_checked_before_the_terminal_is_taken() {
    let c = no_config();
    // stdin is not a terminal: had the page got as far as taking the terminal, the
    // error would be about that instead.
    refused(
        &vpx(&["--xfsp", "--xfsp-iface", "eth0"], &[], &c),
        "\"eth0\" is not an IPv4 address",
    );
    refused(
        &vpx(&["--xfsp-source-id", "0x10000"], &[], &c),
        "not a 16-bit source id",
    );
    refused(&vpx(&["--xfsp", "224.0.2.69"], &[], &c), "--xfsp");
    refused(
        &vpx(&["gateway", "--xfsp-iface", "10.0.0"], &[], &c),
        "not an IPv4 address",
    );
    refused(
        &vpx(&["xfsp-dump", "--xfsp-iface", "any"], &[], &c),
        "not an IPv4 address",
    );
}

#[test]
fn the_source_id_is_read_in_hex_and_its_default_shown_in_hex() {
    let c = no_config();
    let help = out(&vpx(&["--help"], &[], &c));
    assert!(help.contains("[default: 0x5650]"), "{help}");
    let o = vpx(&["config", "--xfsp-source-id", "0x5651"], &[], &c);
    assert!(o.status.success(), "{}", err(&o));
    assert!(out(&o).contains("xfsp_source_id     0x5651"), "{}", out(&o));
    let o = vpx(&["config", "--xfsp-source-id", "22097"], &[], &c);
    assert!(out(&o).contains("xfsp_source_id     0x5651"), "{}", out(&o));
}

#[test]
fn sim_needs_pty_or_tcp_and_says_so() {
    let o = vpx(&["sim"], &[], &no_config());
    refused(&o, "vpx-efis sim --pty");
    assert!(
        err(&o).contains("vpx-efis sim --tcp 127.0.0.1:0"),
        "{}",
        err(&o)
    );
    refused(
        &vpx(&["sim", "--tcp", "localhost"], &[], &no_config()),
        "--tcp",
    );
}

#[test]
fn flash_help_offers_no_simulator_and_flash_without_a_port_says_how_to_get_one() {
    let help = out(&vpx(&["flash", "--help"], &[], &no_config()));
    assert!(help.contains("--port <PATH|tcp://HOST:PORT>"), "{help}");
    for absent in ["--scenario", "--sim ", "built-in virtual VP-X is used"] {
        assert!(
            !help.contains(absent),
            "{absent:?} in flash --help:\n{help}"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let hex = dir.path().join("cu_2.hex");
    std::fs::write(&hex, ":00000001FF\n").unwrap();
    let o = vpx(
        &["flash", "--yes", hex.to_str().unwrap()],
        &[],
        &no_config(),
    );
    refused(&o, "flash needs the unit's port");
    assert!(err(&o).contains("vpx-efis sim --tcp"), "{}", err(&o));
}

#[test]
fn a_port_is_a_path_or_a_whole_tcp_address() {
    let c = no_config();
    for (port, words) in [
        ("tcp://192.168.4.1", "no port number"),
        ("tcp://192.168.4.1:0", "not a port number"),
        ("telnet://192.168.4.1:23", "not a transport vpx-efis speaks"),
    ] {
        refused(&vpx(&["backup", "--port", port, "x.toml"], &[], &c), words);
    }
    refused(
        &vpx(&["--replay", "x.vpxcap", "--port", "/dev/ttyUSB0"], &[], &c),
        "--replay and --port contradict each other",
    );
}

#[test]
fn a_refused_tcp_bridge_is_a_clear_error_not_a_wait() {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("x.toml");
    let started = std::time::Instant::now();
    let o = vpx(
        &[
            "backup",
            "--port",
            &format!("tcp://127.0.0.1:{port}"),
            file.to_str().unwrap(),
        ],
        &[],
        &no_config(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    assert!(
        err(&o).contains(&format!(
            "tcp://127.0.0.1:{port}: connection refused: nothing listens on that port"
        )),
        "{}",
        err(&o)
    );
    assert!(started.elapsed() < std::time::Duration::from_secs(10));
    assert!(!file.exists());
}

#[test]
fn config_shows_each_value_and_where_it_came_from() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("config.toml");
    std::fs::write(
        &cfg,
        "# bench set-up\nport = \"tcp://192.168.4.1:8880\"\nbaud = 115200\ntheme = \"light\"\n\
         xfsp_source_id = 0x5651\n",
    )
    .unwrap();
    let o = vpx(&["config"], &[], &cfg);
    assert!(o.status.success(), "{}", err(&o));
    let text = out(&o);
    for line in [
        format!(
            "config file        {}  [named by VPX_EFIS_CONFIG]",
            cfg.display()
        ),
        "port               tcp://192.168.4.1:8880".into(),
        "baud               115200".into(),
        "xfsp_iface         0.0.0.0".into(),
        "theme              light".into(),
    ] {
        assert!(text.contains(&line), "{line:?} missing:\n{text}");
    }
    let origin = |key: &str| -> String {
        text.lines()
            .find(|l| l.starts_with(&format!("{key} ")))
            .unwrap_or_else(|| panic!("no {key} line:\n{text}"))
            .to_string()
    };
    assert!(origin("port").ends_with("config file, line 2"), "{text}");
    assert!(origin("baud").ends_with("config file, line 3"), "{text}");
    assert!(
        origin("xfsp_source_id").ends_with("config file, line 5"),
        "{text}"
    );
    assert!(origin("xfsp_cert").ends_with("default"), "{text}");
    assert!(origin("theme").ends_with("config file, line 4"), "{text}");

    // The environment beats the file, and a flag beats both.
    let o = vpx(&["config"], &[("VPX_EFIS_PORT", "/dev/ttyUSB3")], &cfg);
    let text = out(&o);
    assert!(
        text.contains("port               /dev/ttyUSB3")
            && text.contains("environment (VPX_EFIS_PORT)"),
        "{text}"
    );
    let o = vpx(
        &["config", "--port", "COM4", "--baud", "9600"],
        &[("VPX_EFIS_PORT", "/dev/ttyUSB3")],
        &cfg,
    );
    let text = out(&o);
    let port = text.lines().find(|l| l.starts_with("port ")).unwrap();
    assert!(port.contains("COM4") && port.ends_with("flag"), "{text}");
    let baud = text.lines().find(|l| l.starts_with("baud ")).unwrap();
    assert!(baud.contains("9600") && baud.ends_with("flag"), "{text}");
    // --sim wins over a configured port.
    let o = vpx(&["config", "--sim"], &[], &cfg);
    let port = out(&o)
        .lines()
        .find(|l| l.starts_with("port "))
        .unwrap()
        .to_string();
    assert!(
        port.contains("none: the built-in virtual VP-X") && port.ends_with("flag"),
        "{port}"
    );
}

#[test]
fn a_bad_config_file_is_refused_naming_its_line_by_the_commands_that_read_it() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("config.toml");
    std::fs::write(&cfg, "port = \"/dev/ttyUSB0\"\n\nbaud = 0\n").unwrap();
    for args in [
        &["config"][..],
        &["backup", "x.toml"][..],
        &["gateway"][..],
        &[][..],
    ] {
        let o = vpx(args, &[], &cfg);
        refused(
            &o,
            &format!(
                "config file {}, line 3: baud: 0 is not a baud rate",
                cfg.display()
            ),
        );
    }
    std::fs::write(&cfg, "port = \"/dev/ttyUSB0\"\nspeed = 3\n").unwrap();
    refused(
        &vpx(&["config"], &[], &cfg),
        "line 2: speed: unknown key; the keys are port, baud",
    );
    // Commands that use no setting are not stopped by it.
    let o = vpx(&["ports"], &[], &cfg);
    assert!(o.status.success(), "{}", err(&o));
}

#[test]
fn completions_man_and_version() {
    let c = no_config();
    for shell in ["bash", "zsh", "fish", "powershell"] {
        let o = vpx(&["completions", shell], &[], &c);
        assert!(o.status.success(), "{shell}: {}", err(&o));
        assert!(out(&o).contains("vpx-efis"), "{shell}");
        assert!(out(&o).contains("xfsp-source-id"), "{shell}");
    }
    refused(&vpx(&["completions", "tcsh"], &[], &c), "tcsh");
    let man = out(&vpx(&["man"], &[], &c));
    assert!(
        man.starts_with(".ie") || man.contains(".TH vpx-efis"),
        "{man}"
    );
    assert!(man.contains("restore"), "{man}");
    let v = out(&vpx(&["--version"], &[], &c));
    // "vpx-efis 0.1.0", with " (abc1234)" when built from a checkout.
    let v = v.trim();
    assert!(v.starts_with("vpx-efis 0.1.0"), "{v}");
    let rest = &v["vpx-efis 0.1.0".len()..];
    assert!(
        rest.is_empty()
            || (rest.starts_with(" (")
                && rest.ends_with(')')
                && rest[2..rest.len() - 1]
                    .chars()
                    .all(|c| c.is_ascii_hexdigit())),
        "{v}"
    );
}

/// Commands from the network are off by default; the flag, the
/// environment and the file turn them on and `config` says which; a malformed list
/// and a list without `--xfsp-control` are refused before anything is opened.
#[test]
fn xfsp_control_is_off_unless_asked_for_and_a_bad_list_is_refused() {
    let c = no_config();
    let line = |o: &std::process::Output, key: &str| -> String {
        out(o)
            .lines()
            .find(|l| l.starts_with(&format!("{key} ")))
            .unwrap_or_else(|| panic!("no {key} line:\n{}", out(o)))
            .to_string()
    };
    let o = vpx(&["config"], &[], &c);
    assert!(line(&o, "xfsp_control").contains("off"), "{}", out(&o));
    assert!(line(&o, "xfsp_control").ends_with("default"), "{}", out(&o));
    let o = vpx(
        &["config"],
        &[
            ("VPX_EFIS_XFSP_CONTROL", "1"),
            ("VPX_EFIS_XFSP_CONTROL_FROM", "0x1234,22136"),
        ],
        &c,
    );
    assert!(o.status.success(), "{}", err(&o));
    assert!(
        line(&o, "xfsp_control").contains("on: takes commands")
            && line(&o, "xfsp_control").ends_with("environment (VPX_EFIS_XFSP_CONTROL)"),
        "{}",
        out(&o)
    );
    assert!(
        line(&o, "xfsp_control_from").contains("0x1234, 0x5678"),
        "{}",
        out(&o)
    );
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("config.toml");
    std::fs::write(
        &cfg,
        "xfsp_control = true\nxfsp_control_from = \"0x0999\"\n",
    )
    .unwrap();
    let o = vpx(&["config"], &[], &cfg);
    assert!(
        line(&o, "xfsp_control_from").ends_with("config file, line 2"),
        "{}",
        out(&o)
    );
    refused(
        &vpx(&["--xfsp", "--xfsp-control-from", "0x1234,zz"], &[], &c),
        "\"zz\" is not a 16-bit source id",
    );
    refused(
        &vpx(&["gateway", "--xfsp-control-from", ""], &[], &c),
        "empty list",
    );
    refused(
        &vpx(&["config"], &[("VPX_EFIS_XFSP_CONTROL", "maybe")], &c),
        "neither true nor false",
    );
    // Naming who may command does not turn commands on: refused, for both.
    for args in [
        &["--xfsp", "--xfsp-control-from", "0x1234"][..],
        &["gateway", "--xfsp-control-from", "0x1234"][..],
    ] {
        let o = vpx(args, &[], &c);
        refused(&o, "network commands are off: add --xfsp-control");
        assert_eq!(o.status.code(), Some(2), "{args:?}");
    }
}

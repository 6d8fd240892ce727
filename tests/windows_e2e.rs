//! What a mechanic on Windows relies on, run as the processes they start,
//! through what Windows has: `vpx-efis sim --tcp` over TCP (no pseudo-terminals on
//! Windows), the gateway over UDP on 127.0.0.1, every file we write under a path of
//! the OS (on Windows `C:\…`), and, under Wine, a real COM port above COM9 mapped to a
//! virtual unit's pseudo-terminal. CI runs this file on Linux and, for
//! x86_64-pc-windows-gnu, under Wine (`.ci/windows`); the Windows-only tests say why
//! they are skipped elsewhere.

use std::net::UdpSocket;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::process::{Kill, sim_tcp};

const EXE: &str = env!("CARGO_BIN_EXE_vpx-efis");

/// `vpx-efis ARGS…` run to its end with stdin at its end and a fresh config folder.
fn run(args: &[&str], home: &Path) -> Output {
    Command::new(EXE)
        .args(args)
        .env("XDG_CONFIG_HOME", home)
        .env_remove("VPX_EFIS_PORT")
        .env_remove("VPX_EFIS_CONFIG")
        .stdin(Stdio::null())
        .output()
        .expect("run vpx-efis")
}

fn text(o: &Output) -> String {
    format!(
        "exit {:?}\n--- stdout\n{}--- stderr\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// On Windows a temporary folder is a drive path (`C:\users\…\Temp\…`): the files
/// below are written under the OS's own kind of path.
fn os_path(p: &Path) {
    #[cfg(windows)]
    {
        let s = p.to_string_lossy();
        let b = s.as_bytes();
        assert!(
            b.len() > 3 && b[0].is_ascii_alphabetic() && b[1] == b':' && b[2] == b'\\',
            "{s}"
        );
    }
    #[cfg(not(windows))]
    assert!(p.is_absolute(), "{}", p.display());
}

/// The headless check over TCP writes its report (Markdown and CSV) into the folder
/// given and, on a first run, the load file's template where `--loads` says.
#[test]
fn the_headless_check_over_tcp_writes_its_reports_and_the_load_template() {
    let (_sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    os_path(home.path());
    let reports = home.path().join("USB stick").join("reports");
    let loads = home.path().join("loads").join("loads.toml");
    let o = run(
        &[
            "check",
            "--port",
            &addr,
            "--yes",
            "--skip",
            "switches,circuits,motors",
            "--report",
            reports.to_str().unwrap(),
            "--loads",
            loads.to_str().unwrap(),
        ],
        home.path(),
    );
    let t = text(&o);
    // Nothing failed (the load file to fill in is left to fix, not a failure): exit 0.
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(
        t.contains(&format!(
            "its template, listing every circuit, was written to {}",
            loads.display()
        )),
        "{t}"
    );
    let template = std::fs::read_to_string(&loads).unwrap();
    assert!(template.contains("Landing Lt"), "{template}");
    let mut written: Vec<String> = std::fs::read_dir(&reports)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        // The check's own files; the audit log of what was sent lives beside them.
        .filter(|n| n.starts_with("vpx-check-"))
        .collect();
    written.sort();
    assert_eq!(written.len(), 2, "{written:?}");
    assert!(
        written[0].starts_with("vpx-check-") && written[0].ends_with(".csv"),
        "{written:?}"
    );
    assert!(written[1].ends_with(".md"), "{written:?}");
    assert!(
        t.contains(&format!("in {}", reports.display())),
        "the report's folder said as the OS writes it: {t}"
    );
}

/// `backup` of the `install` unit over TCP, to a file of the OS's kind of path in a
/// folder with a space in its name (as "My Documents" has). Returns the sim, its
/// address, the config folder and the backup file.
fn backup_over_tcp() -> (Kill, String, tempfile::TempDir, PathBuf) {
    let (sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("N123AB backups");
    std::fs::create_dir(&dir).unwrap();
    let file = dir.join("unit.toml");
    os_path(&file);
    let o = run(
        &["backup", "--port", &addr, file.to_str().unwrap()],
        home.path(),
    );
    assert!(o.status.success(), "{}", text(&o));
    (sim, addr, home, file)
}

#[test]
fn backup_over_tcp_writes_the_file_where_asked() {
    let (_sim, _, _home, file) = backup_over_tcp();
    let toml = std::fs::read_to_string(&file).unwrap();
    assert!(toml.contains("Landing Lt"), "{toml}");
}

/// `restore` over TCP changes a breaker: the backup file edited as a person would
/// (Nav Lt's 3 A breaker lowered to 2 A), restored with `--yes`, says the change and
/// verifies it, and a backup taken after it reads 2 A.
#[test]
fn restore_over_tcp_changes_a_breaker() {
    let (_sim, addr, home, file) = backup_over_tcp();
    let nav = "[devices.5A-1]\nname = \"Nav Lt\"\nshow_on_page = true\nbreaker_amps = ";
    let backup = std::fs::read_to_string(&file).unwrap();
    assert!(backup.contains(&format!("{nav}3\n")), "{backup}");
    std::fs::write(
        &file,
        backup.replace(&format!("{nav}3\n"), &format!("{nav}2\n")),
    )
    .unwrap();
    let o = run(
        &["restore", "--port", &addr, "--yes", file.to_str().unwrap()],
        home.path(),
    );
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("Nav Lt") && t.contains("3 A → 2 A"), "{t}");
    assert!(t.contains("verified"), "{t}");
    let after = file.with_file_name("after.toml");
    let o = run(
        &["backup", "--port", &addr, after.to_str().unwrap()],
        home.path(),
    );
    assert!(o.status.success(), "{}", text(&o));
    let after = std::fs::read_to_string(&after).unwrap();
    assert!(after.contains(&format!("{nav}2\n")), "{after}");
}

/// The gateway bridges a unit reached over TCP onto XFSp over UDP, to a peer on
/// 127.0.0.1: ECBSTAT for the unit's circuits arrives.
#[test]
fn the_gateway_publishes_over_udp_on_127_0_0_1() {
    let (_sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
    peer.set_read_timeout(Some(Duration::from_millis(200)))
        .unwrap();
    let gateway = Command::new(EXE)
        .args([
            "gateway",
            "--port",
            &addr,
            "--xfsp-iface",
            "127.0.0.1",
            "--xfsp",
        ])
        .arg(peer.local_addr().unwrap().to_string())
        .env("XDG_CONFIG_HOME", home.path())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("run vpx-efis gateway");
    let _gateway = Kill(gateway);
    let end = Instant::now() + Duration::from_secs(20);
    let mut buf = [0u8; 4096];
    let mut units = std::collections::BTreeSet::new();
    // The install unit's EFIS (1) and Landing Lt (12, pin 10A-1) among them.
    while !(units.contains(&1) && units.contains(&12)) {
        assert!(Instant::now() < end, "ECBSTAT units so far: {units:?}");
        let Ok(n) = peer.recv(&mut buf) else { continue };
        if let Ok(vpx_efis::xfsp::Message {
            body: vpx_efis::xfsp::Body::Params(ps),
            ..
        }) = vpx_efis::xfsp::Message::parse(&buf[..n])
        {
            units.extend(
                ps.iter()
                    .filter(|p| p.ident == vpx_efis::xfsp::idents::ECBSTAT)
                    .map(|p| p.unit),
            );
        }
    }
}

/// `vpx-efis config` names the config file in the OS's configuration folder: on
/// Windows `%APPDATA%\vpx-efis\config\config.toml`; and a config file given by
/// `VPX_EFIS_CONFIG` (a Windows path there) is read.
#[test]
fn the_config_file_is_in_the_os_folder_and_read_from_its_path() {
    let home = tempfile::tempdir().unwrap();
    let o = run(&["config"], home.path());
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    #[cfg(windows)]
    let folder = Path::new(&std::env::var_os("APPDATA").expect("%APPDATA% is set"))
        .join("vpx-efis")
        .join("config");
    #[cfg(not(windows))]
    let folder = if cfg!(target_os = "macos") {
        // macOS ignores XDG_CONFIG_HOME.
        Path::new(&std::env::var_os("HOME").unwrap()).join("Library/Application Support/vpx-efis")
    } else {
        home.path().join("vpx-efis")
    };
    let first = t
        .lines()
        .find(|l| l.starts_with("config file"))
        .unwrap_or("");
    assert!(
        first.contains(&folder.join("config.toml").display().to_string()),
        "{first} (expected in {})",
        folder.display()
    );
    let file = home.path().join("hangar config.toml");
    os_path(&file);
    std::fs::write(&file, "port = \"COM12\"\nbaud = 19200\n").unwrap();
    let o = Command::new(EXE)
        .arg("config")
        .env("VPX_EFIS_CONFIG", &file)
        .env_remove("VPX_EFIS_PORT")
        .env_remove("VPX_EFIS_BAUD")
        .output()
        .unwrap();
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains(&file.display().to_string()), "{t}");
    let port = t.lines().find(|l| l.starts_with("port")).unwrap_or("");
    assert!(
        port.contains("COM12") && port.contains("config file"),
        "{port}"
    );
}

/// Under Wine, the prefix (set by `.ci/wine/run`) whose `dosdevices` maps COM ports,
/// and a Linux build of vpx-efis to run the virtual unit on a pseudo-terminal;
/// elsewhere why the COM port test cannot run.
#[cfg(windows)]
fn wine_com_rig() -> Result<(String, std::ffi::OsString), String> {
    let prefix = std::env::var("WINEPREFIX").map_err(|_| {
        "not under Wine (no WINEPREFIX): a real Windows has no pseudo-terminal to map a \
         COM port to; a USB-serial adapter and a unit are needed"
            .to_string()
    })?;
    let unix = std::env::var_os("VPX_EFIS_UNIX_EXE")
        .ok_or("VPX_EFIS_UNIX_EXE (a Linux build of vpx-efis, for sim --pty) is not set")?;
    Ok((prefix, unix))
}

/// A COM port above COM9, `COM12` and `\\.\COM12`, through serialport's Windows backend
/// (57600 8N1 raw): under Wine, COM12 is mapped to the pseudo-terminal of a virtual
/// unit run as a Linux process; `backup` over it reads the unit's settings, and
/// `ports` runs.
#[cfg(windows)]
#[test]
fn a_com_port_above_com9_talks_to_the_unit() {
    let (prefix, unix) = match wine_com_rig() {
        Ok(r) => r,
        Err(why) => {
            eprintln!("skipped: {why}");
            return;
        }
    };
    // Wine starts a Linux program given by its path, as Windows starts an exe, but
    // hands it none of our pipes and cannot wait for it: a shell runs the virtual
    // unit on a pseudo-terminal and links Wine's `dosdevices/com12` to it (Wine maps
    // COMn to whatever that links to, looked up at each open), and says so in files,
    // in a folder both sides name alike (`/tmp/…` is `Z:\tmp\…` here).
    let dir = format!("/tmp/vpx-efis-com12-{}", std::process::id());
    let link = format!("{prefix}/dosdevices/com12");
    struct Stop(String, String);
    impl Drop for Stop {
        fn drop(&mut self) {
            let (d, link) = (&self.0, &self.1);
            let _ = Command::new("/bin/sh")
                .args([
                    "-c",
                    &format!("kill $(cat {d}/pid); rm -f '{link}'; rm -rf {d}"),
                ])
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn();
        }
    }
    let script = format!(
        "mkdir -p {dir} || exit 1; \
         {unix} sim --pty --scenario install > {dir}/out 2>/dev/null & echo $! > {dir}/pid; \
         for i in $(seq 100); do head -1 {dir}/out 2>/dev/null | grep -q /dev/ && break; \
         sleep 0.1; done; \
         ln -sfn \"$(head -1 {dir}/out)\" '{link}' && echo done > {dir}/linked",
        unix = unix.to_string_lossy()
    );
    let started = Command::new("/bin/sh")
        .args(["-c", &script])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn();
    assert!(started.is_ok(), "run /bin/sh: {started:?}");
    let _stop = Stop(dir.clone(), link.clone());
    let end = Instant::now() + Duration::from_secs(15);
    while !Path::new(&format!("{dir}/linked")).exists() {
        let out = std::fs::read_to_string(format!("{dir}/out")).unwrap_or_default();
        assert!(
            Instant::now() < end,
            "COM12 not mapped; the virtual unit printed {out:?}"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    let home = tempfile::tempdir().unwrap();
    for port in ["COM12", r"\\.\COM12"] {
        let file = home.path().join("unit.toml");
        let o = run(
            &["backup", "--port", port, file.to_str().unwrap()],
            home.path(),
        );
        assert!(o.status.success(), "{port}: {}", text(&o));
        let toml = std::fs::read_to_string(&file).unwrap();
        assert!(toml.contains("Landing Lt"), "{port}: {toml}");
        std::fs::remove_file(&file).unwrap();
    }
    let o = run(&["ports"], home.path());
    eprintln!("vpx-efis ports under Wine:\n{}", text(&o));
    assert!(o.status.success(), "{}", text(&o));
}

/// Ctrl-Break (the console event a Windows console sends a process group; Ctrl-C is
/// the same path) ends a headless check while it runs the flaps: the motor is
/// stopped through the check's interruption (the page's own stop path) and the check
/// says what it left, exit 2.
#[cfg(windows)]
#[test]
fn ctrl_break_stops_a_running_motor() {
    use std::io::{BufRead, BufReader};
    use std::os::windows::process::CommandExt;
    const CREATE_NEW_PROCESS_GROUP: u32 = 0x0000_0200;
    let (_sim, addr) = sim_tcp("install");
    let home = tempfile::tempdir().unwrap();
    let mut child = Command::new(EXE)
        .args([
            "check",
            "--port",
            &addr,
            "--yes",
            "--skip",
            "switches,circuits,loads",
        ])
        .env("XDG_CONFIG_HOME", home.path())
        .creation_flags(CREATE_NEW_PROCESS_GROUP)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run vpx-efis check");
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let child = Kill(child);
    let mut seen = String::new();
    while !seen.contains("Confirmed:") {
        let n = out.read_line(&mut seen).unwrap();
        assert!(n > 0, "{seen}");
    }
    // The flaps run 0.6 s each way: Ctrl-Break part way through the first run.
    std::thread::sleep(Duration::from_millis(300));
    // SAFETY: a plain Win32 call with a process group id (the child's pid).
    let sent = unsafe {
        windows_sys::Win32::System::Console::GenerateConsoleCtrlEvent(
            windows_sys::Win32::System::Console::CTRL_BREAK_EVENT,
            child.0.id(),
        )
    };
    if sent == 0 {
        eprintln!(
            "skipped: GenerateConsoleCtrlEvent failed ({}): no console to send Ctrl-Break \
             through here",
            std::io::Error::last_os_error()
        );
        return;
    }
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut out, &mut rest).unwrap();
    let mut child = child;
    let status = child.0.wait().unwrap();
    let t = format!("{seen}{rest}");
    assert_eq!(status.code(), Some(2), "{t}");
    assert!(
        t.contains("Interrupted: ended by a signal (Ctrl-Break)"),
        "{t}"
    );
}

/// The page's key-release mode on Windows (`control::release_mode`) rests on
/// crossterm's Windows event path giving Release events natively: a key-up record in
/// the console's input comes out of `crossterm::event::read` as a Release, with no
/// keyboard enhancement asked for. Skipped, saying why, where there is no console.
#[cfg(windows)]
#[test]
fn the_windows_console_gives_key_release_events_natively() {
    use crossterm::event::{Event, KeyCode, KeyEventKind};
    use std::os::windows::io::AsRawHandle;
    use windows_sys::Win32::System::Console::{
        INPUT_RECORD, INPUT_RECORD_0, KEY_EVENT, KEY_EVENT_RECORD, KEY_EVENT_RECORD_0,
        WriteConsoleInputW,
    };
    assert_eq!(
        vpx_efis::control::release_mode_here(false),
        vpx_efis::ui::state::ReleaseMode::KeyRelease
    );
    let conin = match std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open("CONIN$")
    {
        Ok(f) => f,
        Err(e) => {
            eprintln!("skipped: no console input here (CONIN$: {e})");
            return;
        }
    };
    let key = |down: bool| INPUT_RECORD {
        EventType: KEY_EVENT as u16,
        Event: INPUT_RECORD_0 {
            KeyEvent: KEY_EVENT_RECORD {
                bKeyDown: i32::from(down),
                wRepeatCount: 1,
                wVirtualKeyCode: 0x57, // W
                wVirtualScanCode: 0x11,
                uChar: KEY_EVENT_RECORD_0 {
                    UnicodeChar: u16::from(b'w'),
                },
                dwControlKeyState: 0,
            },
        },
    };
    let records = [key(true), key(false)];
    let mut written = 0u32;
    // SAFETY: a console input handle, two initialised records, a valid out pointer.
    let ok = unsafe {
        WriteConsoleInputW(
            conin.as_raw_handle() as _,
            records.as_ptr(),
            2,
            &mut written,
        )
    };
    if ok == 0 || written != 2 {
        eprintln!(
            "skipped: the console took no input records ({})",
            std::io::Error::last_os_error()
        );
        return;
    }
    let mut kinds = Vec::new();
    while kinds.len() < 2 && crossterm::event::poll(Duration::from_secs(2)).unwrap() {
        if let Event::Key(k) = crossterm::event::read().unwrap()
            && k.code == KeyCode::Char('w')
        {
            kinds.push(k.kind);
        }
    }
    assert_eq!(kinds, [KeyEventKind::Press, KeyEventKind::Release]);
}

//! The program run as a user runs it: a child process killed when dropped, and the
//! virtual unit as a process of its own (`vpx-efis sim --pty` or `--tcp`), as a
//! mechanic starts it.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::{Arc, Mutex, mpsc};

/// The program under test.
pub const EXE: &str = env!("CARGO_BIN_EXE_vpx-efis");

/// A config file that is not there: the program's defaults.
pub const NO_CONFIG: &str = "/nonexistent/vpx-efis-test-config.toml";

/// `vpx-efis ARGS…` as a script runs it: standard input at its end (no terminal,
/// nobody to answer) and none of the settings of whoever runs the tests: its config
/// file is `config` (which need not exist), `VPX_EFIS_PORT` and `VPX_EFIS_BAUD` unset.
/// The caller adds what else it needs, and runs it.
pub fn vpx(args: &[&str], config: impl AsRef<Path>) -> Command {
    let mut c = Command::new(EXE);
    c.args(args)
        .env("VPX_EFIS_CONFIG", config.as_ref())
        .env_remove("VPX_EFIS_PORT")
        .env_remove("VPX_EFIS_BAUD")
        .stdin(Stdio::null());
    c
}

/// A child process, killed and reaped when dropped.
pub struct Kill(pub Child);

impl Drop for Kill {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A running `vpx-efis sim`.
pub struct Sim {
    /// The process, killed when this is dropped.
    pub process: Kill,
    /// Its console: a line written here works a switch, a fault or a silence (`help`
    /// lists them). Dropping it ends the console, not the unit.
    pub console: ChildStdin,
    /// What it printed first: the pty's path, or `tcp://HOST:PORT`.
    pub line: String,
}

/// `vpx-efis sim ARGS…`, its console on a pipe, past the first line it prints.
pub fn sim(args: &[&str]) -> Sim {
    let mut child = Command::new(EXE)
        .arg("sim")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run vpx-efis sim");
    let console = child.stdin.take().unwrap();
    let stdout = child.stdout.take().unwrap();
    let process = Kill(child);
    let mut line = String::new();
    BufReader::new(stdout).read_line(&mut line).unwrap();
    assert!(!line.trim().is_empty(), "the sim did not start: {args:?}");
    Sim {
        process,
        console,
        line: line.trim().to_string(),
    }
}

/// `vpx-efis sim --pty --scenario <scenario>` (a name or a file) and its pty's path.
pub fn sim_pty(scenario: &str) -> (Kill, String) {
    let s = sim(&["--pty", "--scenario", scenario]);
    (s.process, s.line)
}

/// `vpx-efis sim --tcp 127.0.0.1:0 --scenario NAME` and its `tcp://` address.
pub fn sim_tcp(scenario: &str) -> (Kill, String) {
    let s = sim(&["--tcp", "127.0.0.1:0", "--scenario", scenario]);
    assert!(s.line.starts_with("tcp://"), "{:?}", s.line);
    (s.process, s.line)
}

/// Every line `out` gives, on a channel, read by a thread of its own until it ends or
/// nobody listens.
pub fn lines(out: impl Read + Send + 'static) -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for l in BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(l).is_err() {
                return;
            }
        }
    });
    rx
}

/// `vpx-efis gateway` on `port`, publishing to the XFSp receiver at `to` through
/// 127.0.0.1, its config file and audit log in `home`; and what it has said on
/// standard error so far.
pub fn gateway(port: &str, to: &str, home: &Path) -> (Kill, Arc<Mutex<Vec<String>>>) {
    let mut gateway = Command::new(EXE)
        .env("XDG_CONFIG_HOME", home)
        .env("VPX_EFIS_CONFIG", home.join("none.toml"))
        .args(["gateway", "--port", port, "--xfsp-iface", "127.0.0.1"])
        .args(["--xfsp", to])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run vpx-efis gateway");
    let said = Arc::new(Mutex::new(Vec::new()));
    let stderr = lines(gateway.stderr.take().unwrap());
    let kept = said.clone();
    std::thread::spawn(move || {
        for l in stderr {
            kept.lock().unwrap().push(l);
        }
    });
    (Kill(gateway), said)
}

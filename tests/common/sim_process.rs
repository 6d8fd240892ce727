//! The virtual VP-X as a process of its own, as a mechanic starts it:
//! `vpx-efis sim --pty --scenario …`, killed when dropped.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

/// A child process killed (and reaped) when dropped.
pub struct Kill(pub Child);

impl Drop for Kill {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `vpx-efis sim --pty --scenario <scenario>` (a name or a file) and the path of its
/// pty, read from the first line it prints.
pub fn sim_pty(scenario: &str) -> (Kill, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_vpx-efis"))
        .args(["sim", "--pty", "--scenario", scenario])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run vpx-efis sim");
    let stdout = child.stdout.take().unwrap();
    let child = Kill(child);
    let mut path = String::new();
    BufReader::new(stdout).read_line(&mut path).unwrap();
    assert!(
        !path.trim().is_empty(),
        "the sim did not start on {scenario}"
    );
    (child, path.trim().to_string())
}

//! The program run as a user runs it: a child process killed when dropped, and the
//! virtual unit on TCP (`vpx-efis sim --tcp`), which every OS has.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

/// A child process, killed and reaped when dropped.
pub struct Kill(pub Child);

impl Drop for Kill {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `vpx-efis sim --tcp 127.0.0.1:0 --scenario NAME` and its `tcp://` address.
pub fn sim_tcp(scenario: &str) -> (Kill, String) {
    let mut sim = Command::new(env!("CARGO_BIN_EXE_vpx-efis"))
        .args(["sim", "--tcp", "127.0.0.1:0", "--scenario", scenario])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run vpx-efis sim");
    let mut addr = String::new();
    BufReader::new(sim.stdout.take().unwrap())
        .read_line(&mut addr)
        .unwrap();
    assert!(addr.starts_with("tcp://"), "{addr:?}");
    (Kill(sim), addr.trim().to_string())
}

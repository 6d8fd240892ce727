//! A client built from the `protocol` module, on the far end of a real pseudo-terminal
//! from the virtual VP-X. Shared by the `sim_*` integration tests.
#![allow(dead_code)]

use std::io::{Read, Write};
use std::time::{Duration, Instant};

use serialport::{SerialPort, TTYPort};
use vpx_efis::protocol::decoder::{Decoder, Event};
use vpx_efis::protocol::message::SystemStatus;
use vpx_efis::protocol::{Message, Packet};
use vpx_efis::sim::{self, Scenario, SimHandle, SimOptions};

/// Generous: the tests must pass on a loaded two-core machine.
pub const TIMEOUT: Duration = Duration::from_secs(5);

pub struct Client {
    pub port: TTYPort,
    decoder: Decoder,
    cnt: u8,
    /// Every packet received, with its arrival time.
    pub log: Vec<(Instant, Packet)>,
    /// Packets before this index have been looked at by `wait_for`.
    seen: usize,
    /// Bytes received, for the bootloader's unframed replies.
    pub raw: Vec<u8>,
}

/// Starts a sim on the master of a fresh pty and a client on its slave.
pub fn start(scenario: Scenario, tweak: impl FnOnce(&mut SimOptions)) -> (SimHandle, Client) {
    let pty = vpx_efis::link::open_pty_pair().expect("pty");
    let reader = pty.master.try_clone_native().expect("clone pty master");
    let mut opts = SimOptions::new(scenario);
    tweak(&mut opts);
    let handle = sim::spawn(opts, Box::new(reader), Box::new(pty.master));
    let mut port = pty.slave;
    port.set_timeout(Duration::from_millis(20)).unwrap();
    (handle, Client::new(port))
}

pub fn scenario(toml: &str) -> Scenario {
    Scenario::from_toml(toml).expect("test scenario")
}

impl Client {
    /// A client on the pty a `vpx-efis sim --pty` printed, reading in `tick`s.
    pub fn open(path: &str, tick: Duration) -> Self {
        let port = serialport::new(path, 57_600)
            .timeout(tick)
            .open_native()
            .expect("open the printed path");
        Client::new(port)
    }

    pub fn new(port: TTYPort) -> Self {
        Client {
            port,
            decoder: Decoder::new(),
            cnt: 0,
            log: Vec::new(),
            seen: 0,
            raw: Vec::new(),
        }
    }

    /// Sends a request with a fresh command number and returns that number.
    pub fn send(&mut self, m: impl Into<Message>) -> u8 {
        self.cnt = self.cnt.wrapping_add(1).max(1);
        let bytes = Packet::request(self.cnt, m).to_bytes();
        self.send_raw(&bytes);
        self.cnt
    }

    pub fn send_raw(&mut self, bytes: &[u8]) {
        self.port.write_all(bytes).expect("write to the pty");
    }

    /// Reads whatever arrives for at most one read timeout.
    pub fn poll(&mut self) {
        let mut buf = [0u8; 4096];
        match self.port.read(&mut buf) {
            Ok(n) if n > 0 => {
                let at = Instant::now();
                self.raw.extend_from_slice(&buf[..n]);
                let mut got = Vec::new();
                self.decoder.push(&buf[..n], |e| {
                    if let Event::Frame(f) = e
                        && let Ok(p) = Packet::parse(&f)
                    {
                        got.push(p);
                    }
                });
                self.log.extend(got.into_iter().map(|p| (at, p)));
            }
            _ => {}
        }
    }

    /// Reads for `d`.
    pub fn pump(&mut self, d: Duration) {
        let end = Instant::now() + d;
        while Instant::now() < end {
            self.poll();
        }
    }

    /// Waits for the first packet not yet looked at for which `f` says yes.
    pub fn wait_for<T>(&mut self, what: &str, f: impl Fn(&Packet) -> Option<T>) -> T {
        let end = Instant::now() + TIMEOUT;
        loop {
            while self.seen < self.log.len() {
                let p = self.log[self.seen].1;
                self.seen += 1;
                if let Some(t) = f(&p) {
                    return t;
                }
            }
            assert!(Instant::now() < end, "timed out waiting for {what}");
            self.poll();
        }
    }

    /// Sends a request and waits for the reply carrying its command number.
    pub fn request(&mut self, m: impl Into<Message>) -> Message {
        let m = m.into();
        let name = m.name();
        let cnt = self.send(m);
        self.wait_for(&format!("the reply to {name} #{cnt}"), |p| {
            (p.cnt == cnt && !is_broadcast(&p.message)).then_some(p.message)
        })
    }

    /// The next broadcast of this kind that starts after now.
    pub fn next<T>(&mut self, what: &str, f: impl Fn(&Message) -> Option<T>) -> T {
        self.seen = self.log.len();
        self.wait_for(what, |p| f(&p.message))
    }

    /// The next SYSTEM_STATUS broadcast.
    pub fn system_status(&mut self) -> SystemStatus {
        self.next("SYSTEM_STATUS", |m| match m {
            Message::SystemStatus(s) => Some(*s),
            _ => None,
        })
    }

    /// Waits until `n` raw bytes have arrived after index `from` of `raw`.
    pub fn raw_after(&mut self, from: usize, n: usize) -> Vec<u8> {
        let end = Instant::now() + TIMEOUT;
        while self.raw.len() < from + n {
            assert!(Instant::now() < end, "timed out waiting for {n} bytes");
            self.poll();
        }
        self.raw[from..from + n].to_vec()
    }
}

pub fn is_broadcast(m: &Message) -> bool {
    matches!(
        m,
        Message::SystemStatus(_)
            | Message::DeviceStatus(_)
            | Message::FlapTrimStatus(_)
            | Message::FaultStatus(_)
    )
}

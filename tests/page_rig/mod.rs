//! The page on one side of a real pseudo-terminal, the virtual VP-X on the other, and a
//! tap in between that records every byte the page puts on the wire. Shared by the
//! end-to-end tests and the page benchmark (`#[path]`-included), so both measure the
//! same thing.
//!
//! The page opens a symlink to the pty's slave, as a mechanic opens
//! /dev/serial/by-id/…: pulling the cable is closing the pty; plugging it back in is a
//! new pty behind the same link name.
#![allow(dead_code)]

pub mod terminal;

use std::io::{Read, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use serialport::SerialPort;
use vpx_efis::app::{App, AppOptions};
use vpx_efis::link::{self, PipeReader, PipeWriter};
use vpx_efis::model::Source;
use vpx_efis::protocol::{Decoder, Event as DecEvent, Packet};
use vpx_efis::sim::{self, Scenario, SimHandle, SimOptions};
use vpx_efis::ui::state::ReleaseMode;

pub const SCENARIO: &str = r#"
description = "e2e: a few devices, pitch trim fitted, nothing scheduled"
[electrical]
bus_volts = 14.0
battery_volts = 12.6
temperature_c = 20
switches = [2]
[[device]]
id = 2
name = "EFIS 1"
switch = 11
load = 3.0
[[device]]
id = 4
name = "Nav Lt"
switch = 2
load = 1.5
[[device]]
id = 9
name = "GPS 1"
breaker = 2
switch = 0
load = 1.0
[pitch_trim]
up = 30
down = 220
neutral = 125
position = 120
"#;

pub type Wire = Arc<Mutex<Vec<(Instant, Vec<u8>)>>>;

/// Joins a pty's master to the sim's pipe end and records what the page sends.
pub struct Tap {
    pub stop: Arc<AtomicBool>,
    pub threads: Vec<JoinHandle<()>>,
    pub slave_path: String,
}

impl Tap {
    pub fn start(
        to_sim: Arc<Mutex<PipeWriter>>,
        from_sim: Arc<Mutex<PipeReader>>,
        wire: Wire,
    ) -> Tap {
        let pty = link::open_pty_pair().expect("pty");
        let stop = Arc::new(AtomicBool::new(false));
        let mut master_in = pty.master.try_clone_native().expect("clone master");
        let mut master_out = pty.master;
        master_in.set_timeout(Duration::from_millis(20)).unwrap();
        let slave = pty.slave;
        let s = stop.clone();
        let up = std::thread::spawn(move || {
            let _keep_slave_open_until_unplugged = slave;
            let mut buf = [0u8; 512];
            while !s.load(Ordering::SeqCst) {
                if let Ok(n) = master_in.read(&mut buf)
                    && n > 0
                {
                    wire.lock()
                        .unwrap()
                        .push((Instant::now(), buf[..n].to_vec()));
                    let _ = to_sim.lock().unwrap().write_all(&buf[..n]);
                }
            }
        });
        let s = stop.clone();
        let down = std::thread::spawn(move || {
            let mut buf = [0u8; 512];
            while !s.load(Ordering::SeqCst) {
                let r = from_sim.lock().unwrap().read(&mut buf);
                if let Ok(n) = r
                    && n > 0
                {
                    let _ = master_out.write_all(&buf[..n]);
                }
            }
        });
        Tap {
            stop,
            threads: vec![up, down],
            slave_path: pty.path,
        }
    }

    /// Closes every handle on the master: the page's reads fail, like a pulled cable.
    pub fn unplug(self) {
        self.stop.store(true, Ordering::SeqCst);
        for t in self.threads {
            let _ = t.join();
        }
    }
}

pub struct Rig {
    pub app: App,
    pub sim: SimHandle,
    pub wire: Wire,
    pub tap: Option<Tap>,
    pub link_path: PathBuf,
    pub to_sim: Arc<Mutex<PipeWriter>>,
    pub from_sim: Arc<Mutex<PipeReader>>,
    pub _dir: tempfile::TempDir,
}

impl Rig {
    pub fn new(mode: ReleaseMode) -> Rig {
        Rig::with_options(AppOptions {
            release_mode: mode,
            ..AppOptions::default()
        })
    }

    pub fn with_options(options: AppOptions) -> Rig {
        let scenario = Scenario::from_toml(SCENARIO).expect("scenario");
        Rig::with_sim(options, SimOptions::new(scenario))
    }

    /// The page with `options` against a sim run with `sim_options` (a line paced at
    /// the real rate, another scenario).
    pub fn with_sim(options: AppOptions, sim_options: SimOptions) -> Rig {
        let (sim_side, page_side) = link::duplex_pipe(Duration::from_millis(20));
        let sim = sim::spawn(
            sim_options,
            Box::new(sim_side.reader),
            Box::new(sim_side.writer),
        );
        let to_sim = Arc::new(Mutex::new(page_side.writer));
        let from_sim = Arc::new(Mutex::new(page_side.reader));
        let wire: Wire = Arc::default();
        let tap = Tap::start(to_sim.clone(), from_sim.clone(), wire.clone());
        let dir = tempfile::tempdir().unwrap();
        let link_path = dir.path().join("vpx-serial");
        std::os::unix::fs::symlink(&tap.slave_path, &link_path).unwrap();
        let app = App::new(
            Source::Serial {
                path: link_path.display().to_string(),
            },
            link::serial_connector(link_path.clone(), 57_600),
            options,
        );
        Rig {
            app,
            sim,
            wire,
            tap: Some(tap),
            link_path,
            to_sim,
            from_sim,
            _dir: dir,
        }
    }

    /// Pumps the page until `f` holds, or fails after `limit`.
    pub fn until(
        &mut self,
        what: &str,
        limit: Duration,
        f: impl Fn(&App, Instant) -> bool,
    ) -> Instant {
        let end = Instant::now() + limit;
        loop {
            let now = Instant::now();
            if f(&self.app, now) {
                return now;
            }
            assert!(now < end, "timed out waiting for {what}");
            self.app.pump_until(now + Duration::from_millis(20));
        }
    }

    pub fn key(&mut self, code: KeyCode, kind: KeyEventKind) {
        let mut k = KeyEvent::new(code, KeyModifiers::NONE);
        k.kind = kind;
        self.app.handle_term_event(Event::Key(k), Instant::now());
    }

    /// Waits until the page has heard both status broadcasts and every name.
    pub fn ready(&mut self) {
        self.until("the device list", Duration::from_secs(6), |app, now| {
            let m = app.model();
            m.live_system(now).is_some()
                && m.live_devices(now).is_some()
                && m.names.iter().all(Option::is_some)
        });
    }

    pub fn select(&mut self, id: u8) {
        self.ready();
        for _ in 0..40 {
            if self.app.view().selected == Some(id) {
                return;
            }
            self.key(KeyCode::Char('j'), KeyEventKind::Press);
        }
        panic!("could not select device {id}");
    }

    /// Every packet the page sent since `from` (an index into the wire log).
    pub fn sent(&self, from: usize) -> Vec<(Instant, Packet)> {
        let wire = self.wire.lock().unwrap();
        let mut dec = Decoder::new();
        let mut out = Vec::new();
        for (at, bytes) in &wire[from..] {
            dec.push(bytes, |e| {
                if let DecEvent::Frame(f) = e {
                    out.push((
                        *at,
                        Packet::parse(&f).expect("the page sends only valid frames"),
                    ));
                }
            });
        }
        out
    }

    pub fn wire_len(&self) -> usize {
        self.wire.lock().unwrap().len()
    }

    pub fn render(&mut self) -> Buffer {
        let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
        self.app.draw(&mut term, Instant::now()).unwrap();
        term.backend().buffer().clone()
    }
}

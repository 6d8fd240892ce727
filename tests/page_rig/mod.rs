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

/// What a tap recorded of what the page sent: each read, with its time.
pub type Recorded<T> = Arc<Mutex<Vec<(T, Vec<u8>)>>>;

pub type Wire = Recorded<Instant>;

/// A built-in scenario's devices as its file writes them (`assets/scenarios`), for
/// the lists a person sees: the pins it disables, and the names it gives the others.
pub struct ScenarioDevices {
    pub disabled: Vec<u64>,
    pub names: Vec<(u64, String)>,
    /// The whole file, for what else it says.
    pub toml: toml::Table,
}

impl ScenarioDevices {
    pub fn read(name: &str) -> ScenarioDevices {
        let path = format!(
            "{}/assets/scenarios/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let toml: toml::Table = std::fs::read_to_string(&path)
            .unwrap()
            .parse()
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        let mut out = ScenarioDevices {
            disabled: Vec::new(),
            names: Vec::new(),
            toml: toml.clone(),
        };
        for d in toml["device"].as_array().unwrap() {
            let id = d["id"].as_integer().unwrap() as u64;
            if d.get("enabled").and_then(|e| e.as_bool()) == Some(false) {
                out.disabled.push(id);
            } else if let Some(n) = d.get("name").and_then(|n| n.as_str()) {
                out.names.push((id, n.to_string()));
            }
        }
        out
    }

    /// A list of circuits (id, name), as `what` shows it, against the file: no
    /// disabled pin, every name given, and no flaps 0x00, pitch trim 0x1D or roll
    /// trim 0x1E (ICD Table 40), which are motors, not circuits.
    pub fn assert_listed(&self, what: &str, listed: &[(u64, String)]) {
        let on_list = |id: u64| listed.iter().find(|(i, _)| *i == id);
        for &id in &self.disabled {
            assert!(on_list(id).is_none(), "{what}: disabled pin {id} listed");
        }
        for (id, name) in &self.names {
            assert_eq!(
                on_list(*id).map(|(_, n)| n),
                Some(name),
                "{what}: device {id}"
            );
        }
        for motor in [0x00, 0x1D, 0x1E] {
            assert!(
                on_list(motor).is_none(),
                "{what}: motor {motor:#04x} listed as a circuit: {listed:?}"
            );
        }
    }
}

/// The unit's account of a pitch trim run the page ended: stopped by the page's stop
/// message, not by the unit's own 250 ms cut-off, and never more than 250 ms between
/// move messages (the unit forgives 300).
pub fn assert_the_trim_stopped_by_its_message(sim: &SimHandle) {
    let s = sim.stats();
    assert!(!s.pitch_trim_running, "the unit's motor still runs");
    assert_eq!(
        s.pitch_trim_starvations, 0,
        "stopped by the unit's 250 ms cut-off, not by the message"
    );
    assert_eq!(
        s.pitch_trim_late, 0,
        "a gap over 250 ms between move messages"
    );
}

/// The packets in what a tap recorded, each with the time of the read that ended it.
pub fn packets<T: Copy>(recorded: &[(T, Vec<u8>)]) -> Vec<(T, Packet)> {
    let mut dec = Decoder::new();
    let mut out = Vec::new();
    for (at, bytes) in recorded {
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

/// A pty for the page, its master joined to the unit, recording what the page sends;
/// stopped (its threads joined) when unplugged or dropped.
pub struct Tap {
    pub stop: Arc<AtomicBool>,
    pub threads: Vec<JoinHandle<()>>,
    pub slave_path: String,
}

/// One end of the sim's pipe, shared with the taps that come after this one.
struct Shared<T>(Arc<Mutex<T>>);

impl<T: Read> Read for Shared<T> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().read(buf)
    }
}

impl<T: Write> Write for Shared<T> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.0.lock().unwrap().flush()
    }
}

impl Tap {
    /// On the sim's pipe ends, kept for the tap plugged in after this one.
    pub fn start(
        to_sim: Arc<Mutex<PipeWriter>>,
        from_sim: Arc<Mutex<PipeReader>>,
        wire: Wire,
    ) -> Tap {
        Tap::between(Shared(to_sim), Shared(from_sim), wire, Instant::now)
    }

    /// A new pty whose master is joined to the unit's `to_unit` and `from_unit`, which
    /// must time out now and then so that the tap can stop; each read of what the page
    /// sends is recorded in `wire` at `clock()`.
    pub fn between<T: Send + 'static>(
        mut to_unit: impl Write + Send + 'static,
        mut from_unit: impl Read + Send + 'static,
        wire: Recorded<T>,
        clock: fn() -> T,
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
                    wire.lock().unwrap().push((clock(), buf[..n].to_vec()));
                    let _ = to_unit.write_all(&buf[..n]);
                }
            }
        });
        let s = stop.clone();
        let down = std::thread::spawn(move || {
            let mut buf = [0u8; 512];
            while !s.load(Ordering::SeqCst) {
                if let Ok(n) = from_unit.read(&mut buf)
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
        drop(self);
    }
}

impl Drop for Tap {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        for t in self.threads.drain(..) {
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
        packets(&self.wire.lock().unwrap()[from..])
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

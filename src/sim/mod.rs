//! The virtual VP-X: a second, independent implementation of the device side of the
//! ICD, speaking the real wire protocol over any byte stream (a pseudo-terminal's
//! master, or one end of an in-process [`duplex_pipe`](crate::link::duplex_pipe)). It
//! shares nothing with the page but bytes.
//!
//! ```
//! use std::time::Duration;
//! use vpx_efis::sim::{self, SimCommand, SimOptions};
//! // Any byte stream will do; this one builds and runs on every OS. (`sim --pty`
//! // gives the unit a pseudo-terminal's master instead, on Unix.)
//! let (ours, unit) = vpx_efis::link::duplex_pipe(Duration::from_millis(50));
//! let opts = SimOptions::new(sim::load_scenario("demo").unwrap());
//! let handle = sim::spawn(opts, Box::new(unit.reader), Box::new(unit.writer));
//! // … read the unit's broadcasts from `ours.reader`, write requests to `ours.writer` …
//! handle.inject(SimCommand::Switch { switch: 3, on: true });
//! println!("{:?}", handle.stats().wire);
//! handle.stop();
//! ```
//!
//! One file per concern: [`unit`] is the pure state machine (bytes in, bytes out, a
//! caller's clock), [`motors`] the flap and trim motors, [`eeprom`] persistence,
//! [`scenario`] the TOML aircraft and timeline, [`bootloader`] §7. This file runs a
//! unit on threads.
//!
//! Decisions where the ICD is silent (each also written where it is made):
//!
//! * Broadcasts run on an absolute schedule (1 Hz and 10 Hz, FLAP_TRIM_STATUS offset
//!   from the others); broadcasts carry the unit's own count, replies echo the request.
//! * The primary alternator wins; the secondary runs only while the primary is off or
//!   faulted. An over-voltage trips the running one and its regulator fault goes with
//!   it, so the other alternator takes over at the scenario's bus volts.
//! * DEVICE_POWER overrides a pin until its switch input changes; DEVICE_POWER to a
//!   faulted pin, the starter or a motor is ignored (counted). DEVICE_CLEAR drops the
//!   cleared pin's override and those of every switch-11 pin (§6.5.1 note 2).
//! * The system fault bit is only set by injection; nothing in the ICD says what sets it.
//! * A *_SPEC whose payload does not decode (a flag byte of 2) is answered SPEC_ACK
//!   OutOfRange with the id from the payload (253/254/0/29/30 for system, wig-wag,
//!   flaps, roll and pitch trim). SPEC_ACK for TRIM_SPEC carries 29 (roll) or 30 (pitch).
//! * The overspeed inhibit also refuses FLAP_MOVE down. Wig-wag lights alternate every
//!   0.5 s. EEPROM_ERASE reports integrity code 0x01 (General EEPROM).
//! * A silent unit still takes requests in; its replies are lost like its broadcasts.
//! * DEVICE_ENABLE defaults to enabled; a set gets no reply, a query (flag 2) does,
//!   for every id 0–30 (1–3 always enabled, 0/29/30 as their FLAP_SPEC/TRIM_SPEC
//!   enable flag says; Table 23 notes 1 and 2); a set outside 4–28 is ignored.
//! * A TRIM_MOVE/FLAP_MOVE run lasts 300 ms after its last message: the 250 ms of the
//!   4 Hz rule plus a margin for an EFIS streaming at exactly 4 Hz. Messages more than
//!   250 ms apart are counted (`SimStats::*_late`) so our tests still hold the page to
//!   250 ms. A stop (power 0) is honoured whatever its direction or trim type byte.
//! * Liberal on receipt: VERSION of any payload length (§6.1.2), EEPROM_ERASE without
//!   its byte, DEVICE_NAME of 2–17 bytes, DEVICE_STATUS_QUERY with any payload; FLASH_PROG
//!   as `'p'` or `'P'`. Every reply is sent at its table's size.
//! * DATA_INTEGRITY from EEPROM_ERASE clears at any restart (warm reset, bootloader
//!   EXIT, power cycle; §6.1.4). The Software Update flag is set by an EXIT only when a
//!   page was programmed (Table 24 note 1).

pub mod bootloader;
pub mod console;
pub mod eeprom;
pub mod line_rate;
pub mod motors;
pub mod scenario;
pub mod unit;

use std::collections::VecDeque;
use std::io::{ErrorKind, Read, Write};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, Sender, bounded, select, unbounded};

pub use scenario::{MotorDirection, MotorId, Scenario, load_scenario};
pub use unit::{SimCommand, SimStats, Unit, UnitOptions};

use eeprom::{Eeprom, LoadOutcome};

/// How a sim is started.
#[derive(Debug, Clone)]
pub struct SimOptions {
    pub scenario: Scenario,
    /// EEPROM file (`--eeprom`); `None` keeps it in memory.
    pub eeprom: Option<PathBuf>,
    /// VERSION hardware version (ICD Table 11 note 1).
    pub hardware_version: u8,
    pub software_version: (u8, u8),
    /// Seed of the load noise and garbage bytes.
    pub seed: u64,
    /// Also print log lines on standard error (not when a terminal UI owns it).
    pub log_to_stderr: bool,
    /// Bytes a second the line carries each way ([`line_rate::BYTES_PER_SECOND`] for
    /// a real 57600 8N1 cable); `None`: as fast as the pipe goes, for tests that
    /// need speed. `vpx-efis sim` paces unless told `--no-pace`.
    pub line_rate: Option<u32>,
}

impl SimOptions {
    /// A VP-X Pro (hardware 2) with software 2.1, EEPROM in memory, quiet.
    pub fn new(scenario: Scenario) -> Self {
        let d = UnitOptions::default();
        SimOptions {
            scenario,
            eeprom: None,
            hardware_version: d.hardware_version,
            software_version: d.software_version,
            seed: d.seed,
            log_to_stderr: false,
            line_rate: None,
        }
    }

    /// The same, at the real line's 5760 bytes a second each way.
    pub fn paced(mut self) -> Self {
        self.line_rate = Some(line_rate::BYTES_PER_SECOND);
        self
    }
}

enum Ctrl {
    Inject(SimCommand),
    Stats(Sender<SimStats>),
    Flash(Sender<Vec<u8>>),
    Stop,
}

/// A running sim. Dropping it stops it.
pub struct SimHandle {
    ctrl: Sender<Ctrl>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

/// How many log lines the handle keeps.
const LOG_LINES: usize = 200;
/// The longest the run loop sleeps. Bytes and commands wake it at once (they arrive on
/// the channels it selects over), and motors are judged against each chunk's arrival
/// time, so this only bounds how stale a quiet unit's clock may get; the 10 Hz
/// FLAP_TRIM_STATUS deadline is shorter anyway. Waking every 10 ms cost ~1 % of a core.
const MAX_SLEEP: Duration = Duration::from_millis(100);

impl SimHandle {
    /// A snapshot of the unit (counters, motor positions, power, faults, config, log).
    /// Panics if the sim thread has died, which is a bug worth a loud test failure.
    pub fn stats(&self) -> SimStats {
        let (tx, rx) = bounded(1);
        self.ctrl.send(Ctrl::Stats(tx)).expect("sim thread is gone");
        rx.recv().expect("sim thread is gone")
    }

    /// Does something to the unit from outside the wire.
    pub fn inject(&self, cmd: SimCommand) {
        let _ = self.ctrl.send(Ctrl::Inject(cmd));
    }

    /// A person flips cockpit switch 1–10 to its other position and back `hold`
    /// later, without blocking the caller. Hold it over a second: the unit shows its
    /// inputs once a second (SYSTEM_STATUS), so a page may miss a shorter flip.
    pub fn flip_switch(&self, switch: u8, hold: Duration) {
        self.inject(SimCommand::FlipSwitch { switch, hold });
    }

    /// The whole 256 KiB program flash.
    pub fn flash(&self) -> Vec<u8> {
        let (tx, rx) = bounded(1);
        self.ctrl.send(Ctrl::Flash(tx)).expect("sim thread is gone");
        rx.recv().expect("sim thread is gone")
    }

    /// Stops the unit and waits for it.
    pub fn stop(mut self) {
        self.shutdown();
    }

    fn shutdown(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        let _ = self.ctrl.send(Ctrl::Stop);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for SimHandle {
    fn drop(&mut self) {
        self.shutdown();
    }
}

/// Builds the unit: reads the EEPROM (file or the scenario's config) at `now`.
pub fn build_unit(options: &SimOptions, now: Instant) -> Unit {
    let opts = UnitOptions {
        hardware_version: options.hardware_version,
        software_version: options.software_version,
        seed: options.seed,
    };
    // The scenario was checked when it was loaded; a hand-built one that the rules
    // refuse falls back to the defaults rather than failing to start.
    let (initial, mut log) = match options.scenario.unit_config() {
        Ok(c) => (c, Vec::new()),
        Err(e) => (
            Default::default(),
            vec![format!(
                "scenario configuration refused ({e:#}); using defaults"
            )],
        ),
    };
    let (eeprom, mut outcome) = match &options.eeprom {
        Some(path) => Eeprom::open(path, initial),
        None => (
            Eeprom::in_memory(initial.clone()),
            LoadOutcome {
                config: initial,
                integrity: None,
                log: Vec::new(),
            },
        ),
    };
    log.append(&mut outcome.log);
    outcome.log = log;
    Unit::new(&options.scenario, (eeprom, outcome), opts, now)
}

/// Runs the unit on any byte stream (a pty master, or an in-process pipe end).
///
/// Three threads: one reads (and stamps each chunk with its arrival time, so a motor
/// stream's timing is measured on arrival, not on when the unit got round to it), one
/// writes (a stuck port drops bytes, like a serial line nobody listens to, instead of
/// stalling the unit), and one runs the unit. With a `line_rate`, the reader hands
/// on bytes only once they would have crossed a real line, and the writer lets them
/// out no faster than one would carry them.
pub fn spawn(
    options: SimOptions,
    reader: Box<dyn Read + Send>,
    writer: Box<dyn Write + Send>,
) -> SimHandle {
    let (ctrl_tx, ctrl_rx) = unbounded();
    let (rx_tx, rx_rx) = unbounded::<(Instant, Vec<u8>)>();
    let (tx_tx, tx_rx) = bounded::<Vec<u8>>(256);
    let stop = Arc::new(AtomicBool::new(false));

    let pacer = || options.line_rate.map(line_rate::LinePacer::new);
    let (rx_pacer, tx_pacer) = (pacer(), pacer());

    let s = stop.clone();
    // Not joined: a reader without a timeout may block in `read` until its port closes.
    let _ = std::thread::Builder::new()
        .name("sim-rx".into())
        .spawn(move || read_loop(reader, rx_tx, s, rx_pacer));
    let s = stop.clone();
    let _ = std::thread::Builder::new()
        .name("sim-tx".into())
        .spawn(move || write_loop(writer, tx_rx, s, tx_pacer));

    let s = stop.clone();
    let thread = std::thread::Builder::new()
        .name("sim".into())
        .spawn(move || run_loop(options, rx_rx, ctrl_rx, tx_tx, s))
        .expect("cannot start the sim thread");
    SimHandle {
        ctrl: ctrl_tx,
        stop,
        thread: Some(thread),
    }
}

/// Sleeps until `t` (at once if it has passed).
fn sleep_until(t: Instant) {
    let now = Instant::now();
    if t > now {
        std::thread::sleep(t - now);
    }
}

fn read_loop(
    mut reader: Box<dyn Read + Send>,
    tx: Sender<(Instant, Vec<u8>)>,
    stop: Arc<AtomicBool>,
    mut pacer: Option<line_rate::LinePacer>,
) {
    let mut buf = [0u8; 1024];
    while !stop.load(Ordering::SeqCst) {
        match reader.read(&mut buf) {
            Ok(0) => {
                // End of file: an in-process pipe whose page has gone, or a pty whose
                // other side is closed for now. Keep listening, gently.
                std::thread::sleep(Duration::from_millis(20));
            }
            Ok(n) => {
                let now = Instant::now();
                let Some(p) = pacer.as_mut() else {
                    if tx.send((now, buf[..n].to_vec())).is_err() {
                        return;
                    }
                    continue;
                };
                // The unit gets each piece when its last byte would have arrived.
                for (piece, at) in p.schedule(now, n) {
                    sleep_until(at);
                    if tx.send((at, buf[piece].to_vec())).is_err() {
                        return;
                    }
                }
            }
            Err(e) if crate::transient::is_transient(&e) => {}
            Err(_) => std::thread::sleep(Duration::from_millis(50)),
        }
    }
}

fn write_loop(
    mut writer: Box<dyn Write + Send>,
    rx: Receiver<Vec<u8>>,
    stop: Arc<AtomicBool>,
    mut pacer: Option<line_rate::LinePacer>,
) {
    while let Ok(bytes) = rx.recv() {
        let pieces = match pacer.as_mut() {
            Some(p) => p.schedule(Instant::now(), bytes.len()),
            None => vec![(0..bytes.len(), Instant::now())],
        };
        for (piece, at) in pieces {
            if stop.load(Ordering::SeqCst) {
                return;
            }
            // Paced, a piece is let out once its last byte would have crossed the line.
            sleep_until(at);
            // A port nobody reads times out; those bytes are lost, as on a real line.
            if let Err(e) = writer.write_all(&bytes[piece])
                && e.kind() == ErrorKind::BrokenPipe
            {
                return;
            }
        }
    }
}

fn run_loop(
    options: SimOptions,
    rx: Receiver<(Instant, Vec<u8>)>,
    ctrl: Receiver<Ctrl>,
    tx: Sender<Vec<u8>>,
    stop: Arc<AtomicBool>,
) {
    let log_to_stderr = options.log_to_stderr;
    let mut unit = build_unit(&options, Instant::now());
    let mut log: VecDeque<String> = VecDeque::new();
    let keep_log = |unit: &mut Unit, log: &mut VecDeque<String>| {
        for line in unit.take_log() {
            unit_log_line(log, log_to_stderr, line);
        }
    };
    let mut dropped = 0u64;
    while !stop.load(Ordering::SeqCst) {
        let now = Instant::now();
        let wait = unit
            .next_deadline()
            .saturating_duration_since(now)
            .min(MAX_SLEEP);
        select! {
            recv(rx) -> chunk => if let Ok((at, bytes)) = chunk {
                unit.feed(&bytes, at);
            },
            recv(ctrl) -> c => match c {
                Ok(Ctrl::Inject(cmd)) => unit.apply(cmd, Instant::now()),
                Ok(Ctrl::Stats(reply)) => {
                    keep_log(&mut unit, &mut log);
                    let mut s = unit.snapshot(Instant::now());
                    s.log = log.iter().cloned().collect();
                    let _ = reply.send(s);
                }
                Ok(Ctrl::Flash(reply)) => {
                    let _ = reply.send(unit.flash.bytes.clone());
                }
                Ok(Ctrl::Stop) | Err(_) => break,
            },
            default(wait) => {},
        }
        // Everything that has arrived is taken in before time moves on, so a move
        // message already here is never counted as late.
        let now = Instant::now();
        while let Ok((at, bytes)) = rx.try_recv() {
            unit.feed(&bytes, at);
        }
        unit.tick(now);
        let out = unit.take_output();
        if !out.is_empty() && tx.try_send(out).is_err() {
            dropped += 1;
            if dropped.is_power_of_two() {
                unit_log_line(
                    &mut log,
                    log_to_stderr,
                    format!("output dropped {dropped} times: nobody is reading the port"),
                );
            }
        }
        keep_log(&mut unit, &mut log);
    }
}

fn unit_log_line(log: &mut VecDeque<String>, to_stderr: bool, line: String) {
    if to_stderr {
        eprintln!("vpx-efis sim: {line}");
    }
    if log.len() == LOG_LINES {
        log.pop_front();
    }
    log.push_back(line);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::duplex_pipe;
    use crate::protocol::message::Ping;
    use crate::protocol::{Decoder, Event, Message, Packet};

    /// The page's built-in default: the sim on one end of an in-process pipe.
    #[test]
    fn runs_on_a_pipe_end_with_the_demo_scenario() {
        let (page, unit) = duplex_pipe(Duration::from_millis(20));
        let handle = spawn(
            SimOptions::new(load_scenario("demo").unwrap()),
            Box::new(unit.reader),
            Box::new(unit.writer),
        );
        let (mut r, mut w) = (page.reader, page.writer);
        w.write_all(&Packet::request(77, Ping { ack: false }).to_bytes())
            .unwrap();
        let mut dec = Decoder::new();
        let mut got = Vec::new();
        let end = Instant::now() + Duration::from_secs(5);
        let mut buf = [0u8; 512];
        while Instant::now() < end
            && !got
                .iter()
                .any(|p: &Packet| matches!(p.message, Message::DeviceStatus(_)))
        {
            if let Ok(n) = r.read(&mut buf) {
                dec.push(&buf[..n], |e| {
                    if let Event::Frame(f) = e {
                        got.push(Packet::parse(&f).unwrap());
                    }
                });
            }
        }
        assert!(
            got.iter()
                .any(|p| p.cnt == 77 && p.message == Ping { ack: true }.into())
        );
        let on = got.iter().find_map(|p| match p.message {
            Message::DeviceStatus(d) => Some(d.on),
            _ => None,
        });
        let on = on.expect("DEVICE_STATUS within 5 s");
        assert!(
            on[2] && on[3] && on[4],
            "demo: EFIS, alternator and nav lights on"
        );
        assert!(!on[23], "demo: the standby alternator waits");
        handle.stop();
    }
}

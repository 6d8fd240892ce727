//! The writer thread: recording off the hot path.
//!
//! [`Recorder`] is cheap to clone and never blocks: each record is put on a channel.
//! One thread of its own opens the logbook (so a migration, or a wait for another
//! process's lock, never holds up the page), then sleeps in the channel's `recv`
//! (no polling: an idle page costs it nothing), and at each wake takes whatever has
//! come and writes it in **one transaction**: a burst costs one commit, and a kill at
//! any moment leaves every batch before it whole and the one in flight absent, never
//! half there.
//!
//! Its faults:
//! - **locked** longer than the busy timeout, or **the disk full**: the batch stays
//!   in memory (up to [`MAX_PENDING`] records) and goes with the next one; the
//!   problem is said once, through [`Recorder::take_problem`], and the action that
//!   made the record has already finished.
//! - **corrupt**, or written by a newer program: nothing is written, it is said,
//!   and the program goes on without it.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, SystemTime};

use crossbeam_channel::{Receiver, Sender, unbounded};
use rusqlite::{OptionalExtension, Transaction, params};

use super::record::{Entry, Unit, What};
use super::{Error, Logbook, Mode};
use crate::audit::{self, Origin};
use crate::protocol::message::Packet;

/// Records kept in memory while the logbook cannot take them (locked, disk full),
/// at most: past this the oldest go, and that is said.
pub const MAX_PENDING: usize = 100_000;

enum Msg {
    Entry(Box<Entry>),
    Command(audit::Item),
    Unit(Unit),
    /// Answered once everything before it is written (or has failed).
    Flush(Sender<()>),
}

/// What the page shows of the logbook, kept up to date by the thread.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Status {
    /// The file, once opened read-write; `None` before, or when it could not be.
    pub open: bool,
    /// Why nothing is being recorded, when that is so (corrupt, newer, locked).
    pub problem: Option<String>,
    /// The unit seen before in another aircraft: its registration, and the day it
    /// was last seen there ("2026-11-03").
    pub was_in: Option<(String, String)>,
    /// Records written so far.
    pub written: u64,
}

#[derive(Default)]
struct Shared {
    status: Status,
    /// Problems not yet taken for the event log.
    news: Vec<String>,
}

/// The way into the logbook: cheap to clone, never blocks.
#[derive(Clone)]
pub struct Recorder {
    tx: Sender<Msg>,
    shared: Arc<Mutex<Shared>>,
    aircraft: Option<String>,
}

/// The writer thread; dropping every [`Recorder`] ends it after the last record.
pub struct RecorderThread(Option<JoinHandle<()>>);

impl RecorderThread {
    /// Waits for the records already sent to be written (after the last
    /// `Recorder` is dropped).
    pub fn join(mut self) {
        if let Some(t) = self.0.take() {
            let _ = t.join();
        }
    }
}

impl Recorder {
    /// Starts the writer for the logbook at `path`, recording under `aircraft` (a
    /// registration, already checked), or under the unit alone.
    pub fn start(
        path: PathBuf,
        aircraft: Option<String>,
    ) -> std::io::Result<(Recorder, RecorderThread)> {
        Recorder::start_with(path, aircraft, super::BUSY_TIMEOUT)
    }

    /// As [`Recorder::start`], waiting at most `busy` for another process's lock.
    pub fn start_with(
        path: PathBuf,
        aircraft: Option<String>,
        busy: Duration,
    ) -> std::io::Result<(Recorder, RecorderThread)> {
        let (tx, rx) = unbounded();
        let shared = Arc::new(Mutex::new(Shared::default()));
        let s = shared.clone();
        let a = aircraft.clone();
        let t = std::thread::Builder::new()
            .name("logbook".into())
            .spawn(move || Writer::new(path, a, busy, s).run(&rx))?;
        Ok((
            Recorder {
                tx,
                shared,
                aircraft,
            },
            RecorderThread(Some(t)),
        ))
    }

    /// The registration recorded under, if one was named.
    pub fn aircraft(&self) -> Option<&str> {
        self.aircraft.as_deref()
    }

    /// Records `entry`.
    pub fn record(&self, entry: Entry) {
        let _ = self.tx.send(Msg::Entry(Box::new(entry)));
    }

    /// Records `packet` in the audit log if it is a command ([`audit::is_command`]);
    /// `result` is `Err(words)` when it was not sent.
    pub fn command(&self, origin: Origin, packet: &Packet, result: Result<(), &str>) {
        if !audit::is_command(&packet.message) {
            return;
        }
        let _ = self.tx.send(Msg::Command(audit::Item {
            at: SystemTime::now(),
            origin,
            packet: *packet,
            result: result.map_err(str::to_string),
        }));
    }

    /// The unit now connected, as it told who it is: the records from here on are
    /// its.
    pub fn unit(&self, unit: Unit) {
        let _ = self.tx.send(Msg::Unit(unit));
    }

    /// Waits (at most `within`) until every record sent before is written or has
    /// failed; `false` if the thread did not answer in time.
    pub fn flush(&self, within: Duration) -> bool {
        let (tx, rx) = crossbeam_channel::bounded(1);
        self.tx.send(Msg::Flush(tx)).is_ok() && rx.recv_timeout(within).is_ok()
    }

    /// A problem not said yet, for the event log: each once.
    pub fn take_problem(&self) -> Option<String> {
        let mut s = self.shared.lock().ok()?;
        (!s.news.is_empty()).then(|| s.news.remove(0))
    }

    /// The unit's earlier aircraft and the day it was last seen there, once the
    /// writer has found one.
    pub fn was_in(&self) -> Option<(String, String)> {
        self.shared.lock().ok()?.status.was_in.clone()
    }

    pub fn status(&self) -> Status {
        self.shared
            .lock()
            .map(|s| s.status.clone())
            .unwrap_or_default()
    }
}

/// One record from a program that records once and leaves (`backup`, `restore`,
/// `flash`): written before it returns, under `unit` when known, in the logbook
/// the command line chose ([`super::target`]). What went wrong is returned in words
/// for the program to print: the action itself has already happened.
pub fn record_now(entry: Entry, unit: Option<Unit>) -> Option<String> {
    let target = super::target()?;
    record_now_in(target, entry, unit)
}

/// [`record_now`] into `target`.
pub fn record_now_in(target: super::Target, entry: Entry, unit: Option<Unit>) -> Option<String> {
    let (book, thread) = match Recorder::start(target.path, target.aircraft) {
        Ok(r) => r,
        Err(e) => return Some(format!("logbook: its thread could not start ({e})")),
    };
    if let Some(u) = unit {
        book.unit(u);
    }
    book.record(entry);
    book.flush(super::BUSY_TIMEOUT + super::SHUTDOWN_WAIT);
    let mut said = Vec::new();
    while let Some(p) = book.take_problem() {
        said.push(p);
    }
    let status = book.status();
    drop(book);
    thread.join();
    if status.written > 0 {
        None
    } else if said.is_empty() {
        Some("logbook: the record was not written".into())
    } else {
        Some(said.join("; "))
    }
}

struct Writer {
    path: PathBuf,
    aircraft: Option<String>,
    busy: Duration,
    book: Option<Logbook>,
    /// Set once the logbook has been found unusable for good (corrupt, newer).
    given_up: bool,
    unit: Option<Unit>,
    /// The unit's row, once written.
    unit_id: Option<i64>,
    lines: audit::Lines,
    pending: Vec<Pending>,
    shared: Arc<Mutex<Shared>>,
    /// The last problem said, so a fault that goes on is said once.
    said: Option<String>,
}

/// A record waiting for its transaction, with the unit it belongs to.
struct Pending {
    entry: Entry,
    unit: Option<Unit>,
}

impl Writer {
    fn new(
        path: PathBuf,
        aircraft: Option<String>,
        busy: Duration,
        shared: Arc<Mutex<Shared>>,
    ) -> Writer {
        Writer {
            path,
            aircraft,
            busy,
            book: None,
            given_up: false,
            unit: None,
            unit_id: None,
            lines: audit::Lines::default(),
            pending: Vec::new(),
            shared,
            said: None,
        }
    }

    fn run(mut self, rx: &Receiver<Msg>) {
        self.open();
        let mut flushes = Vec::new();
        while let Ok(m) = rx.recv() {
            self.take(m, &mut flushes);
            while let Ok(m) = rx.try_recv() {
                self.take(m, &mut flushes);
            }
            self.write();
            for f in flushes.drain(..) {
                let _ = f.send(());
            }
        }
        let now = SystemTime::now();
        for line in self.lines.close(now) {
            self.push(Entry {
                at: line.at,
                origin: line.origin,
                summary: line.command.clone(),
                what: What::Command(line),
            });
        }
        self.write();
    }

    fn take(&mut self, m: Msg, flushes: &mut Vec<Sender<()>>) {
        match m {
            Msg::Entry(e) => self.push(*e),
            Msg::Command(item) => {
                for line in self.lines.take(item) {
                    self.push(Entry {
                        at: line.at,
                        origin: line.origin,
                        summary: summary_of(&line),
                        what: What::Command(line),
                    });
                }
            }
            Msg::Unit(u) => {
                if self.unit.as_ref() != Some(&u) {
                    self.unit = Some(u);
                    self.unit_id = None;
                }
            }
            Msg::Flush(tx) => flushes.push(tx),
        }
    }

    fn push(&mut self, entry: Entry) {
        if self.pending.len() >= MAX_PENDING {
            self.pending.remove(0);
            self.say(format!(
                "logbook: {} records waiting; the oldest are no longer kept",
                MAX_PENDING
            ));
        }
        self.pending.push(Pending {
            entry,
            unit: self.unit.clone(),
        });
    }

    fn open(&mut self) {
        if self.book.is_some() || self.given_up {
            return;
        }
        match Logbook::open_with(&self.path, Mode::ReadWrite, self.busy) {
            Ok(book) => {
                if let Some(why) = book.read_only() {
                    self.give_up(format!("logbook {}: {why}", self.path.display()));
                    return;
                }
                self.book = Some(book);
                self.set(|s| {
                    s.open = true;
                    s.problem = None;
                });
                self.said = None;
            }
            Err(e @ Error::Corrupt { .. }) => self.give_up(format!("logbook {e}")),
            Err(e) => self.say(format!("logbook {e}")),
        }
    }

    fn give_up(&mut self, why: String) {
        self.given_up = true;
        self.pending.clear();
        self.set(|s| {
            s.open = false;
            s.problem = Some(why.clone());
        });
        self.say(why);
    }

    fn write(&mut self) {
        self.open();
        if self.given_up {
            self.pending.clear();
            return;
        }
        let Some(book) = self.book.as_mut() else {
            return;
        };
        if self.pending.is_empty() {
            return;
        }
        let result = (|| -> rusqlite::Result<(usize, Option<(String, String)>)> {
            let tx = book
                .conn_mut()
                .transaction_with_behavior(rusqlite::TransactionBehavior::Immediate)?;
            if let (Some(reg), Some(first)) = (self.aircraft.as_deref(), self.pending.first()) {
                tx.execute(
                    "INSERT INTO aircraft (registration, first_seen) VALUES (?1, ?2)
                     ON CONFLICT (registration) DO NOTHING",
                    params![reg, crate::utc::utc_text(first.entry.at)],
                )?;
            }
            let mut ids = UnitIds::default();
            let mut was_in = None;
            for p in &self.pending {
                let unit = match &p.unit {
                    Some(u) => {
                        let (id, w) = ids.of(&tx, u, self.aircraft.as_deref(), p.entry.at)?;
                        was_in = was_in.or(w);
                        Some(id)
                    }
                    None => None,
                };
                insert(&tx, &p.entry, self.aircraft.as_deref(), unit)?;
            }
            tx.commit()?;
            Ok((self.pending.len(), was_in))
        })();
        match result {
            Ok((n, was_in)) => {
                self.pending.clear();
                self.said = None;
                self.set(|s| {
                    s.written += n as u64;
                    s.problem = None;
                    if was_in.is_some() {
                        s.was_in = was_in;
                    }
                });
            }
            Err(e) => {
                let e = book.error(e);
                let why = match &e {
                    Error::Corrupt { .. } => return self.give_up(format!("logbook {e}")),
                    Error::Locked { .. } => format!(
                        "logbook {e}; {} records wait in memory for it",
                        self.pending.len()
                    ),
                    _ => format!(
                        "logbook {e}; {} records wait in memory, written when it can take them",
                        self.pending.len()
                    ),
                };
                self.set(|s| s.problem = Some(why.clone()));
                self.say(why);
            }
        }
    }

    fn set(&self, f: impl FnOnce(&mut Status)) {
        if let Ok(mut s) = self.shared.lock() {
            f(&mut s.status);
        }
    }

    /// Says `why` once for as long as it goes on.
    fn say(&mut self, why: String) {
        let key = why.split(';').next().unwrap_or_default().to_string();
        if self.said.as_deref() == Some(&key) {
            return;
        }
        self.said = Some(key);
        if let Ok(mut s) = self.shared.lock() {
            s.news.push(why);
        }
    }
}

/// The units' rows looked up once per batch.
#[derive(Default)]
struct UnitIds {
    known: Vec<(String, i64)>,
}

impl UnitIds {
    /// The unit's row (made if new), its install in `aircraft` brought up to `at`,
    /// and, when first looked up in this batch, the aircraft it was last in before
    /// (another one), with the day.
    fn of(
        &mut self,
        tx: &Transaction,
        u: &Unit,
        aircraft: Option<&str>,
        at: SystemTime,
    ) -> rusqlite::Result<(i64, Option<(String, String)>)> {
        let identity = u.identity();
        let time = crate::utc::utc_text(at);
        let id = match self.known.iter().find(|(k, _)| *k == identity) {
            Some((_, id)) => *id,
            None => {
                tx.execute(
                    "INSERT INTO units (identity, hardware, software, names, first_seen)
                     VALUES (?1, ?2, ?3, ?4, ?5) ON CONFLICT (identity) DO NOTHING",
                    params![
                        identity,
                        u.hardware,
                        u.software,
                        serde_json::to_string(&u.names).unwrap_or_default(),
                        time
                    ],
                )?;
                let id: i64 = tx.query_row(
                    "SELECT id FROM units WHERE identity = ?1",
                    [&identity],
                    |r| r.get(0),
                )?;
                self.known.push((identity, id));
                id
            }
        };
        let mut was_in = None;
        if let Some(reg) = aircraft {
            was_in = tx
                .query_row(
                    "SELECT aircraft, substr(last_seen, 1, 10) FROM installs
                     WHERE unit = ?1 AND aircraft <> ?2 ORDER BY last_seen DESC LIMIT 1",
                    params![id, reg],
                    |r| Ok((r.get(0)?, r.get(1)?)),
                )
                .optional()?;
            tx.execute(
                "INSERT INTO installs (unit, aircraft, first_seen, last_seen)
                 VALUES (?1, ?2, ?3, ?3)
                 ON CONFLICT (unit, aircraft) DO UPDATE SET
                   last_seen = max(last_seen, excluded.last_seen)",
                params![id, reg, time],
            )?;
        }
        Ok((id, was_in))
    }
}

/// One entry and its details.
fn insert(
    tx: &Transaction,
    e: &Entry,
    aircraft: Option<&str>,
    unit: Option<i64>,
) -> rusqlite::Result<()> {
    let time = crate::utc::utc_text(e.at);
    tx.prepare_cached(
        "INSERT INTO entries (time, aircraft, unit, origin, kind, summary)
         VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
    )?
    .execute(params![
        time,
        aircraft,
        unit,
        e.origin,
        e.what.kind(),
        e.summary
    ])?;
    let id = tx.last_insert_rowid();
    match &e.what {
        What::Check(c) => {
            tx.execute(
                "INSERT INTO checks (entry, port, program, tally, interrupted, report,
                   load_path, load_file, alternator_amps, battery_amp_hours, battery_usable)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
                params![
                    id,
                    c.port,
                    c.program,
                    c.tally,
                    c.interrupted,
                    c.report,
                    c.load_path,
                    c.load_file,
                    c.alternator_amps,
                    c.battery_amp_hours,
                    c.battery_usable
                ],
            )?;
            let mut st = tx.prepare_cached(
                "INSERT INTO check_circuits (entry, device, name, pin, breaker, switch,
                   amps, verdict, finding) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
            )?;
            for x in &c.circuits {
                st.execute(params![
                    id, x.device, x.name, x.pin, x.breaker, x.switch, x.amps, x.verdict, x.finding
                ])?;
            }
            let mut st = tx.prepare_cached(
                "INSERT INTO check_switches (entry, input, circuits, verdict, finding)
                 VALUES (?1, ?2, ?3, ?4, ?5)",
            )?;
            for x in &c.switches {
                st.execute(params![id, x.input, x.circuits, x.verdict, x.finding])?;
            }
            let mut st = tx.prepare_cached(
                "INSERT INTO check_motors (entry, motor, positions, verdict, finding)
                 VALUES (?1, ?2, ?3, ?4, ?5)",
            )?;
            for x in &c.motors {
                st.execute(params![id, x.motor, x.positions, x.verdict, x.finding])?;
            }
            let mut st = tx.prepare_cached(
                "INSERT INTO check_loads (entry, phase, amps, margin_percent,
                   endurance_minutes, level) VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
            )?;
            for x in &c.loads {
                st.execute(params![
                    id,
                    x.phase,
                    x.amps,
                    x.margin_percent,
                    x.endurance_minutes,
                    x.level
                ])?;
            }
        }
        What::Backup { path, text } => {
            tx.execute(
                "INSERT INTO backups (entry, path, text) VALUES (?1, ?2, ?3)",
                params![id, path, text],
            )?;
        }
        What::Restore { changes } => {
            for c in changes {
                setting(tx, id, c)?;
            }
        }
        What::Setting(c) => setting(tx, id, c)?,
        What::Firmware(f) => {
            tx.execute(
                "INSERT INTO firmware (entry, image_sha256, image_path, version_before,
                   version_after, outcome) VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
                params![
                    id,
                    f.image_sha256,
                    f.image_path,
                    f.version_before,
                    f.version_after,
                    f.outcome
                ],
            )?;
        }
        What::Command(l) => {
            tx.prepare_cached(
                "INSERT INTO commands (entry, command, frame, result, run, run_origin,
                   moves, seconds) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)",
            )?
            .execute(params![
                id,
                l.command,
                l.frame,
                l.result,
                l.run,
                l.run_origin,
                l.moves.map(|m| m as i64),
                l.seconds
            ])?;
        }
        What::Fault {
            device,
            name,
            fault,
        } => {
            tx.execute(
                "INSERT INTO faults (entry, device, name, fault) VALUES (?1, ?2, ?3, ?4)",
                params![id, device, name, fault],
            )?;
        }
    }
    Ok(())
}

fn setting(tx: &Transaction, entry: i64, c: &super::record::SettingChange) -> rusqlite::Result<()> {
    tx.prepare_cached(
        "INSERT INTO setting_changes (entry, setting, old, new, confirmed)
         VALUES (?1, ?2, ?3, ?4, ?5)",
    )?
    .execute(params![entry, c.setting, c.old, c.new, c.confirmed])?;
    Ok(())
}

/// An audit line in words, for the list: the command and how it went.
fn summary_of(l: &audit::Line) -> String {
    let mut s = l.command.clone();
    if let Some(run) = &l.run {
        s = format!("{s} ({run})");
    }
    if l.result != "sent" {
        s = format!("{s}: {}", l.result);
    }
    s
}

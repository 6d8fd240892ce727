//! `--replay FILE [--speed N]`: the page driven by a capture, read-only.
//!
//! Received bytes take the same path as from a cable: a replay thread writes each
//! Rx record into an in-process pipe at its recorded offset (scaled by the speed), and
//! the ordinary `Link` reads, decodes and reports them to the ordinary sink, so
//! decoding, staleness and COMMUNICATION LOST behave as they did live. Tx records go
//! straight to the sink as what the page sent (the traffic view and the sent counter
//! show them); nothing is ever written anywhere.
//!
//! The page runs on the capture's clock: time zero is the connection, and a record's
//! facts are stamped with `zero + offset`, not with when the pipe happened to deliver
//! them. So pausing freezes the page (nothing goes stale while you look), stepping
//! moves it one record, `--speed 10` ages everything ten times as fast, and a frame
//! drawn at offset T is the frame the live page drew at T.

use std::collections::VecDeque;
use std::io::{self, Write};
use std::path::Path;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, select};
use crossterm::event::{Event as TermEvent, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::Backend;

use super::{
    App, AppOptions, Flow, IDLE_REDRAW, MIN_FRAME_GAP, SharedSink, TerminalGuard, Terminated,
    Termination, lock, spawn_input_thread,
};
use crate::control::Action;
use crate::link::{
    CaptureError, Connector, Crossing, Link, LinkEvent, PipeWriter, Record, parse_capture,
    pipe_pair,
};
use crate::model::{Connection, Model, Source};
use crate::protocol::{Decoder, Event, Packet};
use crate::traffic::ReplayStatus;
use crate::ui::{self, state::Screen};

/// The link reads at most this much at once; the replay writes no more per chunk, so
/// each chunk is exactly one read and gets exactly its record's time.
const CHUNK: usize = 1024;
const SPEEDS: (f64, f64) = (1.0 / 16.0, 256.0);
const READ_ONLY: &str = "replay is read-only: nothing is sent to a unit";

/// A capture read into memory, checked.
#[derive(Debug, Clone)]
pub struct Capture {
    pub name: String,
    pub records: Vec<Record>,
    /// A truncated capture: what is replayed stops at the cut, and this says so.
    pub problem: Option<String>,
}

impl Capture {
    /// Reads a capture file; a file that is not a capture, or is corrupt, is an error in
    /// words (never a panic). A truncated one is accepted up to the cut.
    pub fn load(path: &Path) -> anyhow::Result<Capture> {
        let data = std::fs::read(path)
            .map_err(|e| anyhow::anyhow!("cannot read the capture {}: {e}", path.display()))?;
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into(),
        );
        Capture::from_bytes(&name, &data)
    }

    pub fn from_bytes(name: &str, data: &[u8]) -> anyhow::Result<Capture> {
        let (records, err, _) = parse_capture(data);
        let problem = match err {
            None => None,
            Some(e @ CaptureError::Truncated { .. }) => Some(e.to_string()),
            Some(e @ CaptureError::Corrupt { .. }) => anyhow::bail!(
                "{name}: {e} ({} records before it were intact); not replaying a damaged capture",
                records.len()
            ),
            Some(e) => anyhow::bail!("{name}: {e}"),
        };
        Ok(Capture {
            name: name.to_string(),
            records,
            problem,
        })
    }

    /// Offset of the last record: how long the replay runs.
    pub fn length(&self) -> Duration {
        self.records.last().map_or(Duration::ZERO, |r| r.offset)
    }
}

struct Clock {
    /// The real instant the replayed link connected: capture offset zero.
    origin: Option<Instant>,
    base_real: Instant,
    base_pos: Duration,
    speed: f64,
    paused: bool,
    length: Duration,
    /// Index of the next record to deliver.
    next: usize,
    delivered_rx: u64,
    consumed_rx: u64,
    stop: bool,
}

impl Clock {
    fn position(&self, real: Instant) -> Duration {
        let p = match self.origin {
            Some(_) if !self.paused => {
                self.base_pos
                    + real
                        .saturating_duration_since(self.base_real)
                        .mul_f64(self.speed)
            }
            _ => self.base_pos,
        };
        p.min(self.length)
    }

    fn rebase(&mut self, real: Instant) {
        self.base_pos = self.position(real);
        self.base_real = real;
    }
}

struct Shared {
    clock: Mutex<Clock>,
    cv: Condvar,
    /// Times of the Rx chunks written into the pipe and not yet read by the link.
    stamps: Mutex<VecDeque<Instant>>,
    /// Time of the chunk the link is decoding now.
    current: Mutex<Option<Instant>>,
}

impl Shared {
    fn clock(&self) -> MutexGuard<'_, Clock> {
        self.clock.lock().unwrap_or_else(|p| p.into_inner())
    }
}

/// The running replay, held by the app.
pub struct Replay {
    shared: Arc<Shared>,
    offsets: Vec<Duration>,
    file: String,
    problem: Option<String>,
    feeder: Option<JoinHandle<()>>,
    last_status: Option<ReplayStatus>,
}

impl Drop for Replay {
    fn drop(&mut self) {
        self.shared.clock().stop = true;
        self.shared.cv.notify_all();
        if let Some(t) = self.feeder.take() {
            let _ = t.join();
        }
    }
}

/// Starts the link on a pipe fed from `capture`, and the thread that feeds it.
fn start(
    capture: Capture,
    speed: f64,
    paused: bool,
    sink: SharedSink,
    model: Arc<Mutex<Model>>,
) -> (Link, Option<Replay>) {
    let now = Instant::now();
    let shared = Arc::new(Shared {
        clock: Mutex::new(Clock {
            origin: None,
            base_real: now,
            base_pos: Duration::ZERO,
            speed,
            paused,
            length: capture.length(),
            next: 0,
            delivered_rx: 0,
            consumed_rx: 0,
            stop: false,
        }),
        cv: Condvar::new(),
        stamps: Mutex::new(VecDeque::new()),
        current: Mutex::new(None),
    });
    let (pipe_w, pipe_r) = pipe_pair(Duration::from_millis(50));
    let mut reader = Some(pipe_r);
    let name = format!("replay of {}", capture.name);
    let connector: Connector = Box::new(move || match reader.take() {
        Some(r) => Ok((Box::new(r) as _, Box::new(io::sink()) as _, name.clone())),
        None => Err(io::Error::new(
            io::ErrorKind::NotConnected,
            "the replay cannot be reopened",
        )),
    });
    let link = Link::start(connector, retimer(shared.clone(), sink.clone(), model));
    let offsets = capture.records.iter().map(|r| r.offset).collect();
    let feeder = {
        let shared = shared.clone();
        let records = capture.records;
        std::thread::Builder::new()
            .name("replay".into())
            .spawn(move || feed(&shared, records, pipe_w, &sink))
            .expect("spawning the replay thread")
    };
    let replay = Replay {
        shared,
        offsets,
        file: capture.name,
        problem: capture.problem,
        feeder: Some(feeder),
        last_status: None,
    };
    (link, Some(replay))
}

/// Puts the capture's times on what the link reports, then hands it to the page's sink.
fn retimer(
    shared: Arc<Shared>,
    inner: SharedSink,
    model: Arc<Mutex<Model>>,
) -> impl Fn(LinkEvent) + Send + Sync + 'static {
    move |ev| match ev {
        LinkEvent::Connected { .. } => {
            let zero = Instant::now();
            inner(ev);
            {
                // Offset zero is the connection, as when recording.
                let mut m = lock(&model);
                m.traffic.origin = Some(zero);
                if let Connection::Connected { since, .. } = &mut m.connection {
                    *since = zero;
                }
            }
            let mut c = shared.clock();
            if c.origin.is_none() {
                c.origin = Some(zero);
                c.base_real = zero;
            }
            drop(c);
            shared.cv.notify_all();
        }
        LinkEvent::Bytes {
            at,
            dir: Crossing::Rx,
            bytes,
        } => {
            let at = lock_any(&shared.stamps).pop_front().unwrap_or(at);
            *lock_any(&shared.current) = Some(at);
            inner(LinkEvent::Bytes {
                at,
                dir: Crossing::Rx,
                bytes,
            });
            shared.clock().consumed_rx += 1;
            shared.cv.notify_all();
        }
        LinkEvent::Rx {
            at,
            item,
            raw,
            stats,
        } => {
            let at = lock_any(&shared.current).unwrap_or(at);
            inner(LinkEvent::Rx {
                at,
                item,
                raw,
                stats,
            });
        }
        other => inner(other),
    }
}

/// What the page sent, as the traffic view shows it: a packet, or bytes that were not one.
fn sent_item(e: Event<'_>) -> (Option<Packet>, Vec<u8>) {
    match e {
        Event::Frame(f) => (Packet::parse(&f).ok(), f.as_bytes().to_vec()),
        Event::Skipped(b)
        | Event::BadChecksum(b)
        | Event::BadLength(b)
        | Event::UnknownMessage(b)
        | Event::Truncated(b) => (None, b.to_vec()),
    }
}

fn lock_any<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// The replay thread: each record at its time; then it keeps the pipe open, so the
/// page sees the silence after the last byte, as it would have live.
fn feed(shared: &Shared, records: Vec<Record>, mut pipe: PipeWriter, sink: &SharedSink) {
    let mut tx_decoder = Decoder::new();
    for rec in &records {
        let zero = {
            let mut c = shared.clock();
            loop {
                if c.stop {
                    return;
                }
                let real = Instant::now();
                if let Some(zero) = c.origin
                    && c.position(real) >= rec.offset
                {
                    break zero;
                }
                let wait = match c.origin {
                    Some(_) if !c.paused => (rec.offset - c.position(real))
                        .div_f64(c.speed)
                        .min(Duration::from_millis(50)),
                    _ => Duration::from_millis(50),
                };
                c = shared
                    .cv
                    .wait_timeout(c, wait)
                    .unwrap_or_else(|p| p.into_inner())
                    .0;
            }
        };
        let at = zero + rec.offset;
        match rec.dir {
            Crossing::Rx => {
                for piece in rec.bytes.chunks(CHUNK) {
                    lock_any(&shared.stamps).push_back(at);
                    shared.clock().delivered_rx += 1;
                    if pipe.write_all(piece).is_err() {
                        return;
                    }
                }
            }
            Crossing::Tx => {
                // What we sent goes in after everything received before it.
                wait_consumed(shared);
                sink(LinkEvent::Bytes {
                    at,
                    dir: Crossing::Tx,
                    bytes: rec.bytes.clone(),
                });
                let mut sent = Vec::new();
                tx_decoder.push(&rec.bytes, |e| sent.push(sent_item(e)));
                for (packet, raw) in sent {
                    sink(LinkEvent::Tx { at, packet, raw });
                }
            }
        }
        shared.clock().next += 1;
        shared.cv.notify_all();
    }
    // The capture is over: what the page sent and what it received end here, so
    // bytes held back as the start of a longer frame are scanned again (nothing intact
    // among them stays hidden). The pipe stays open: the page goes on to see silence.
    if let Some(last) = records.last() {
        let zero = shared.clock().origin;
        let at = zero.map_or_else(Instant::now, |z| z + last.offset);
        let mut sent = Vec::new();
        tx_decoder.finish(|e| sent.push(sent_item(e)));
        for (packet, raw) in sent {
            sink(LinkEvent::Tx { at, packet, raw });
        }
        wait_consumed(shared);
        let _ = pipe.end_of_stream();
    }
    let mut c = shared.clock();
    while !c.stop {
        c = shared
            .cv
            .wait_timeout(c, Duration::from_millis(100))
            .unwrap_or_else(|p| p.into_inner())
            .0;
    }
}

/// Waits (briefly) until the link has read every chunk written, and decoded the last.
fn wait_consumed(shared: &Shared) {
    let end = Instant::now() + Duration::from_secs(1);
    let mut c = shared.clock();
    while c.consumed_rx < c.delivered_rx && !c.stop && Instant::now() < end {
        c = shared
            .cv
            .wait_timeout(c, Duration::from_millis(5))
            .unwrap_or_else(|p| p.into_inner())
            .0;
    }
    drop(c);
    // The link decodes a chunk right after reporting its bytes: microseconds.
    std::thread::sleep(Duration::from_millis(1));
}

impl App {
    /// The page driven by `capture`, playing at `speed` (or paused at its start).
    pub fn replay(capture: Capture, options: AppOptions, speed: f64, paused: bool) -> App {
        let source = Source::Replay {
            file: capture.name.clone(),
        };
        App::build(source, options, None, move |sink, model| {
            start(capture, speed, paused, sink, model)
        })
    }

    /// The page's clock: the capture's time during a replay, the real one otherwise.
    pub fn now(&self) -> Instant {
        let real = Instant::now();
        match &self.replay {
            Some(r) => {
                let c = r.shared.clock();
                c.origin.map_or(real, |zero| zero + c.position(real))
            }
            None => real,
        }
    }

    /// Moves a replay to `offset` into the capture and holds it there (paused), once
    /// every record up to it has reached the model. Returns the page's `now` there.
    /// For tests and stepping; `None` when not replaying.
    pub fn replay_seek(&mut self, offset: Duration) -> Option<Instant> {
        let r = self.replay.as_ref()?;
        let shared = r.shared.clone();
        let due = r.offsets.iter().take_while(|&&o| o <= offset).count();
        let end = Instant::now() + Duration::from_secs(5);
        let mut c = shared.clock();
        while c.origin.is_none() && Instant::now() < end {
            c = shared
                .cv
                .wait_timeout(c, Duration::from_millis(5))
                .unwrap_or_else(|p| p.into_inner())
                .0;
        }
        let real = Instant::now();
        c.rebase(real);
        c.paused = true;
        c.base_pos = c.base_pos.max(offset.min(c.length));
        shared.cv.notify_all();
        while (c.next < due || c.consumed_rx < c.delivered_rx) && Instant::now() < end {
            c = shared
                .cv
                .wait_timeout(c, Duration::from_millis(5))
                .unwrap_or_else(|p| p.into_inner())
                .0;
        }
        let zero = c.origin?;
        let pos = c.position(real);
        drop(c);
        // The link decodes the last chunk right after reporting it.
        std::thread::sleep(Duration::from_millis(20));
        let now = zero + pos.max(offset);
        while let Ok(w) = self.wake_rx.try_recv() {
            self.on_wake(w, now);
        }
        self.replay_sync();
        Some(now)
    }

    /// Where the replay is, as the screen shows it.
    pub fn replay_status(&self) -> Option<ReplayStatus> {
        let r = self.replay.as_ref()?;
        let c = r.shared.clock();
        let pos = c.position(Instant::now());
        Some(ReplayStatus {
            file: r.file.clone(),
            position: pos,
            length: c.length,
            speed: c.speed,
            paused: c.paused,
            finished: c.next >= r.offsets.len() && pos >= c.length,
            problem: r.problem.clone(),
        })
    }

    /// Copies the replay's position into the model for the screen; dirty if it changed.
    fn replay_sync(&mut self) {
        let Some(status) = self.replay_status() else {
            return;
        };
        let changed = self.replay.as_ref().is_some_and(|r| {
            r.last_status.as_ref().is_none_or(|s| {
                s.paused != status.paused
                    || s.finished != status.finished
                    || s.speed != status.speed
                    || (s.position.as_millis() / 100) != (status.position.as_millis() / 100)
            })
        });
        if changed {
            self.dirty = true;
            lock(&self.model).traffic.replay = Some(status.clone());
            if let Some(r) = self.replay.as_mut() {
                r.last_status = Some(status);
            }
        }
    }

    fn replay_control<R>(&mut self, f: impl FnOnce(&mut Clock, &[Duration]) -> R) -> Option<R> {
        let r = self.replay.as_ref()?;
        let mut c = r.shared.clock();
        c.rebase(Instant::now());
        let out = f(&mut c, &r.offsets);
        drop(c);
        r.shared.cv.notify_all();
        self.replay_sync();
        Some(out)
    }

    /// Replay keys (pause, step, speed) and the read-only rule; `None` lets the key
    /// through to the screen's own handling.
    pub(super) fn replay_key(&mut self, event: &TermEvent, now: Instant) -> Option<Flow> {
        self.replay.as_ref()?;
        let TermEvent::Key(key) = event else {
            return None;
        };
        if key.kind == KeyEventKind::Release {
            return Some(Flow::Continue);
        }
        let notice = match key.code {
            KeyCode::Char('p') => self.replay_control(|c, _| {
                c.paused = !c.paused;
                if c.paused {
                    "replay paused: p plays, . steps one record"
                } else {
                    "replay playing"
                }
            }),
            KeyCode::Char('.') => self.replay_control(|c, offsets| {
                c.paused = true;
                match offsets.get(c.next) {
                    Some(&o) => {
                        c.base_pos = c.base_pos.max(o);
                        "stepped one record"
                    }
                    None => "end of the capture",
                }
            }),
            KeyCode::Char('+') | KeyCode::Char('=') => self.replay_control(|c, _| {
                c.speed = (c.speed * 2.0).min(SPEEDS.1);
                "faster"
            }),
            KeyCode::Char('-') => self.replay_control(|c, _| {
                c.speed = (c.speed / 2.0).max(SPEEDS.0);
                "slower"
            }),
            _ if self.view.screen == Screen::Devices => return self.replay_device_key(key, now),
            _ => return None,
        };
        if let (Some(n), Some(s)) = (notice, self.replay_status()) {
            let text = format!(
                "{n} ({} of {}, ×{})",
                crate::ui::values::secs(s.position),
                crate::ui::values::secs(s.length),
                s.speed
            );
            self.set_notice(now, Some(text));
        }
        Some(Flow::Continue)
    }

    /// On the device list only looking is allowed: arrows select (never run a motor),
    /// and every command key is refused with a notice.
    fn replay_device_key(&mut self, key: &KeyEvent, now: Instant) -> Option<Flow> {
        if key.modifiers.contains(KeyModifiers::CONTROL) || self.view.overlay != Default::default()
        {
            return None;
        }
        let action = match key.code {
            KeyCode::Up | KeyCode::Char('k') => Action::SelectPrev,
            KeyCode::Down | KeyCode::Char('j') => Action::SelectNext,
            KeyCode::Char('s' | 't' | 'c' | '?' | 'q') | KeyCode::Esc => return None,
            _ => {
                self.set_notice(now, Some(READ_ONLY.into()));
                return Some(Flow::Continue);
            }
        };
        let rows = ui::ordered_circuits(&lock(&self.model), &self.view, now);
        self.apply_view_action(&action, &rows);
        Some(Flow::Continue)
    }

    /// The select loop of a replay: like [`App::run`], on the capture's clock.
    pub fn run_replay<B: Backend>(
        &mut self,
        terminal: &mut Terminal<B>,
        input: &Receiver<TermEvent>,
        terminations: &Receiver<Termination>,
    ) -> anyhow::Result<()> {
        let mut last_real_draw: Option<Instant> = None;
        loop {
            self.replay_sync();
            let now = self.now();
            self.tick(now);
            let real = Instant::now();
            let since = last_real_draw.map(|t| real.saturating_duration_since(t));
            if since.is_none_or(|d| (self.dirty && d >= MIN_FRAME_GAP) || d >= IDLE_REDRAW) {
                self.draw(terminal, now)?;
                last_real_draw = Some(real);
            }
            select! {
                recv(input) -> ev => match ev {
                    Ok(ev) => {
                        let now = self.now();
                        if self.handle_term_event(ev, now) == Flow::Quit {
                            return Ok(());
                        }
                    }
                    Err(_) => return Err(super::input_closed(terminations)),
                },
                recv(terminations) -> t => if let Ok(t) = t {
                    return Err(Terminated(t).into());
                },
                recv(self.wake_rx) -> w => if let Ok(w) = w { let now = self.now(); self.on_wake(w, now) },
                default(MIN_FRAME_GAP) => {}
            }
            while let Ok(w) = self.wake_rx.try_recv() {
                let now = self.now();
                self.on_wake(w, now);
            }
        }
    }
}

/// `vpx-efis --replay FILE [--speed N]`.
pub fn run(file: &Path, args: &super::PageOptions) -> anyhow::Result<()> {
    if !(SPEEDS.0..=SPEEDS.1).contains(&args.speed) {
        anyhow::bail!(
            "--speed must be between {} and {} (1 is the recorded pace)",
            SPEEDS.0,
            SPEEDS.1
        );
    }
    if args.record.is_some() {
        anyhow::bail!("--record and --replay together would copy the capture; use cp");
    }
    let capture = Capture::load(file)?;
    let problem = capture.problem.clone();
    let theme = super::choose_theme(args.theme);
    let terminations = super::signals::listen()?;
    let mut guard = TerminalGuard::enter()?;
    let options = AppOptions {
        theme,
        release_mode: crate::control::release_mode_here(guard.key_release),
        ..AppOptions::default()
    };
    let mut app = App::replay(capture, options, args.speed, false);
    let start_notice = match &problem {
        Some(p) => p.clone(),
        None => "REPLAY, read-only: p pause, . step, +/- speed, t traffic".to_string(),
    };
    app.set_notice(Instant::now(), Some(start_notice));
    let input = spawn_input_thread();
    let result = app.run_replay(&mut guard.terminal, &input, &terminations);
    app.shutdown();
    drop(guard);
    if let Some(p) = problem {
        eprintln!("vpx-efis: note: {p}");
    }
    result
}

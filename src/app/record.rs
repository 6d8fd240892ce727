//! `--record FILE`: every byte in both directions into a capture file.
//!
//! The file is created when the page starts (so a bad path fails before the terminal
//! is taken) and its time zero is the first connection, the same instant the page's
//! traffic timestamps count from, so a replay lines up with what was on screen. A
//! flusher thread writes buffered records at least every [`FLUSH_EVERY`] even when the
//! link is idle: a crash or a pulled cable loses at most that much.

use std::fs::File;
use std::path::Path;
use std::sync::{Arc, Mutex, Weak};
use std::time::{Duration, Instant};

use crate::link::{CaptureWriter, Crossing};
use crate::model::{LogLevel, Model};

/// Well inside the one second the capture format promises.
pub const FLUSH_EVERY: Duration = Duration::from_millis(250);

enum State {
    /// Created, waiting for the first connection to be time zero.
    Waiting(File),
    Recording {
        writer: CaptureWriter<File>,
        start: Instant,
        /// Reader and writer threads report out of order by microseconds; the format
        /// requires offsets that never go back.
        last: Instant,
        dirty: bool,
    },
    Failed,
}

/// A capture being written; cheap to clone (the link sink and the app share one).
#[derive(Clone)]
pub struct Recorder {
    state: Arc<Mutex<State>>,
}

impl Recorder {
    pub fn create(path: &Path) -> anyhow::Result<Recorder> {
        let file = File::create(path).map_err(|e| {
            anyhow::anyhow!("cannot write the capture file {}: {e}", path.display())
        })?;
        let state = Arc::new(Mutex::new(State::Waiting(file)));
        let weak = Arc::downgrade(&state);
        std::thread::Builder::new()
            .name("capture-flush".into())
            .spawn(move || flush_loop(weak))?;
        Ok(Recorder { state })
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Time zero of the capture (the first connection); later calls change nothing.
    pub fn start(&self, at: Instant) -> std::io::Result<()> {
        let mut s = self.lock();
        if let State::Waiting(_) = &*s {
            let State::Waiting(file) = std::mem::replace(&mut *s, State::Failed) else {
                unreachable!()
            };
            let writer = CaptureWriter::new(file, at)?;
            *s = State::Recording {
                writer,
                start: at,
                last: at,
                dirty: false,
            };
        }
        Ok(())
    }

    /// When the capture's offset zero is, once recording.
    pub fn started_at(&self) -> Option<Instant> {
        match &*self.lock() {
            State::Recording { start, .. } => Some(*start),
            _ => None,
        }
    }

    /// Appends bytes; after a write error the recorder stops and says why once.
    pub fn record(&self, at: Instant, dir: Crossing, bytes: &[u8]) -> Result<(), String> {
        let mut s = self.lock();
        let State::Recording {
            writer,
            last,
            dirty,
            ..
        } = &mut *s
        else {
            return Ok(());
        };
        let at = at.max(*last);
        *last = at;
        *dirty = true;
        if let Err(e) = writer.record(at, dir, bytes) {
            *s = State::Failed;
            return Err(e.to_string());
        }
        Ok(())
    }
}

fn flush_loop(state: Weak<Mutex<State>>) {
    loop {
        std::thread::sleep(FLUSH_EVERY);
        let Some(state) = state.upgrade() else {
            return;
        };
        let mut s = state.lock().unwrap_or_else(|p| p.into_inner());
        if let State::Recording { writer, dirty, .. } = &mut *s
            && *dirty
        {
            let _ = writer.flush(Instant::now());
            *dirty = false;
        }
    }
}

/// The link sink's part: time zero at the first connection.
pub(super) fn on_connected(recorder: &Option<Recorder>, model: &mut Model, at: Instant) {
    if let Some(r) = recorder
        && let Err(e) = r.start(at)
    {
        model.log(at, LogLevel::Warning, format!("recording stopped: {e}"));
    }
}

/// The link sink's part: every byte into the capture.
pub(super) fn on_bytes(
    recorder: &Option<Recorder>,
    model: &mut Model,
    at: Instant,
    dir: Crossing,
    bytes: &[u8],
) {
    if let Some(r) = recorder
        && let Err(e) = r.record(at, dir, bytes)
    {
        model.log(at, LogLevel::Warning, format!("recording stopped: {e}"));
    }
}

impl super::App {
    /// The page with `--record`: every byte both ways goes to `recorder`.
    pub fn recording(
        source: crate::model::Source,
        connector: crate::link::Connector,
        options: super::AppOptions,
        recorder: Recorder,
    ) -> super::App {
        super::App::build(source, options, Some(recorder), |sink, _| {
            (crate::link::Link::start(connector, move |e| sink(e)), None)
        })
    }

    /// Offset zero of the capture being recorded (the first connection), once known.
    pub fn recording_started(&self) -> Option<Instant> {
        self.recorder.as_ref().and_then(Recorder::started_at)
    }
}

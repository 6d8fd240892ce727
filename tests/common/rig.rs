//! The virtual VP-X in this process on the master of a real pseudo-terminal, and the
//! page (`App`) on its slave as on a USB adapter: what the end-to-end tests that
//! drive a page, and those that drive another part of the program over the pty,
//! share.

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use vpx_efis::app::{App, AppOptions, Flow};
use vpx_efis::link;
use vpx_efis::model::Source;
use vpx_efis::sim::{self, SimHandle, SimOptions};

/// The unit on a pty, for whatever opens `path`.
pub struct PtyUnit {
    pub sim: SimHandle,
    /// The slave's path, as the page opens it.
    pub path: String,
    /// Held so the master never sees end-of-file between two openings of `path`.
    pub slave: serialport::TTYPort,
    /// A folder of the test's own (its files, its reports).
    pub dir: tempfile::TempDir,
}

impl PtyUnit {
    /// The unit `options` describe, on the master of a new pseudo-terminal.
    pub fn start(options: SimOptions) -> PtyUnit {
        let pty = link::open_pty_pair().expect("pty");
        let reader = pty.master.try_clone_native().expect("clone master");
        let sim = sim::spawn(options, Box::new(reader), Box::new(pty.master));
        PtyUnit {
            sim,
            path: pty.path,
            slave: pty.slave,
            dir: tempfile::tempdir().unwrap(),
        }
    }
}

/// One rig at a time, for the tests that ask: each is a sim, a page and a pty at
/// the real line rate, and a loaded machine that runs several at once can starve a
/// unit's 1 Hz status into COMMUNICATION LOST.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// This test's turn, held until dropped.
pub fn one_at_a_time() -> MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner())
}

/// The page against a [`PtyUnit`], pumped on the real clock.
///
/// Dropped in field order, on a failure too: the page (its link closed, its motor
/// stopped), the sim, the pty; only then is the next rig's turn.
pub struct Rig {
    pub app: App,
    pub sim: SimHandle,
    pub path: String,
    _slave: serialport::TTYPort,
    /// A folder of the test's own (its load file, its reports).
    pub dir: tempfile::TempDir,
    _turn: Option<MutexGuard<'static, ()>>,
}

impl Rig {
    /// The page with `app` options against the unit `sim` describes.
    pub fn start(sim: SimOptions, app: AppOptions) -> Rig {
        Rig::started(None, sim, app)
    }

    /// As [`Rig::start`], once no other rig of this test binary that asked the same
    /// is running.
    pub fn alone(sim: SimOptions, app: AppOptions) -> Rig {
        Rig::started(Some(one_at_a_time()), sim, app)
    }

    fn started(turn: Option<MutexGuard<'static, ()>>, sim: SimOptions, app: AppOptions) -> Rig {
        let unit = PtyUnit::start(sim);
        let app = App::new(
            Source::Serial {
                path: unit.path.clone(),
            },
            link::serial_connector(PathBuf::from(&unit.path), 57_600),
            app,
        );
        Rig {
            app,
            sim: unit.sim,
            path: unit.path,
            _slave: unit.slave,
            dir: unit.dir,
            _turn: turn,
        }
    }

    /// Pumps the page until `f` holds, or fails after `limit` naming `what`.
    pub fn until(&mut self, what: &str, limit: Duration, f: impl Fn(&App) -> bool) {
        super::app::until(&mut self.app, what, limit, |app, _| f(app));
    }

    /// Pumps the page for `ms` milliseconds.
    pub fn pump(&mut self, ms: u64) {
        self.app
            .pump_until(Instant::now() + Duration::from_millis(ms));
    }

    /// How many frames of the message `name` the page has written.
    pub fn sent(&self, name: &str) -> u64 {
        super::app::sent(&self.app, name)
    }

    /// A press of `code`.
    pub fn key(&mut self, code: KeyCode) -> Flow {
        self.key_with(code, KeyModifiers::NONE)
    }

    /// A press of `code` with `mods` held.
    pub fn key_with(&mut self, code: KeyCode, mods: KeyModifiers) -> Flow {
        let k = KeyEvent::new_with_kind(code, mods, KeyEventKind::Press);
        self.app.handle_term_event(Event::Key(k), Instant::now())
    }
}

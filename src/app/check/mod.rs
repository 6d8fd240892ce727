//! The installation check wired to its flow ([`crate::check`]): `i` on the device list
//! opens it, keys become the flow's commands, the page's loop ticks it at its
//! deadlines and after every packet. `vpx-efis check` runs the same flow with no
//! screen ([`headless`]), printing each result as it comes.
//!
//! Everything it does to the aircraft goes through the page's own paths: its packets
//! are queued under the motor controller's lock (so a stop decided after a move never
//! reaches the wire before it), its motor runs are the controller's, and every way
//! the page ends (quit, a signal, a closed terminal, a panic, the drop guard) first
//! interrupts the check, which switches off the circuit it has on.

mod headless;
mod report_files;

pub use headless::{CheckEnd, HeadlessCheck, run_headless, run_headless_with};
pub use report_files::{prepare as prepare_report_dir, write as write_report};

use std::path::PathBuf;
use std::time::Instant;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::{App, Flow, lock};
use crate::check::state::{CheckView, Step};
use crate::check::words;
use crate::check::{Cause, CheckFlow, Command, Options};
use crate::control::StopReason;
use crate::model::Source;
use crate::ui::state::Screen;

/// The check as the app holds it.
#[derive(Debug, Default)]
pub(super) struct CheckState {
    flow: Option<CheckFlow>,
    view: CheckView,
    /// Results as they came, for a headless run to print.
    progress: Vec<String>,
    /// Where the report goes once the check ends, and when the check started.
    report_dir: Option<PathBuf>,
    started: Option<std::time::SystemTime>,
    reported: bool,
    /// The check's record is in the logbook (once per check, whatever the report).
    logged: bool,
    /// Esc was pressed once with the report not written: the next one leaves.
    leave_asked: bool,
}

/// The options of a check opened from the page: everything run, the load file beside
/// the config file.
fn page_options() -> Options {
    Options {
        loads_file: crate::places::loads_path(),
        ..Options::default()
    }
}

impl App {
    /// Starts a new check and shows its screen.
    pub fn open_check(&mut self, mut options: Options, now: Instant) {
        let shared = self.model.clone();
        let model = lock(&shared);
        // The wall clock at `now`, so findings can say the time of day ("sent at
        // 21:40:12 UTC"); the flow itself reads no clock.
        let wall = std::time::SystemTime::now();
        options.clock = Some(wall);
        // The trend: this aircraft's last check, from the logbook, unless given.
        if options.last_check.is_none() {
            options.last_check = self.reload_last_check();
        }
        self.check.flow = Some(CheckFlow::new(options, &mut self.check.view, &model, now));
        drop(model);
        lock(&shared).log(
            now,
            crate::model::LogLevel::Info,
            "check: the installation check started".into(),
        );
        self.check.progress.clear();
        self.check.started = Some(wall);
        self.check.reported = false;
        self.check.logged = false;
        self.check.leave_asked = false;
        self.view.screen = Screen::Check;
        self.dirty = true;
    }

    pub fn check_view(&self) -> &CheckView {
        &self.check.view
    }

    /// Whether no check is running (none opened, or it ended).
    pub fn check_finished(&self) -> bool {
        self.check.flow.as_ref().is_none_or(CheckFlow::finished)
    }

    /// The results that came since the last call, in words.
    pub fn take_check_progress(&mut self) -> Vec<String> {
        std::mem::take(&mut self.check.progress)
    }

    /// Runs `f` on the flow with the model and the controller, queueing the packets
    /// it returns before letting go of the controller.
    fn with_check(
        &mut self,
        f: impl FnOnce(
            &mut CheckFlow,
            &mut CheckView,
            &crate::model::Model,
            &mut crate::control::Controller,
        ) -> crate::check::CheckEffects,
    ) {
        let Some(flow) = self.check.flow.as_mut() else {
            return;
        };
        let was_finished = flow.finished();
        let view = &mut self.check.view;
        let before = view.clone();
        let shared = self.model.clone();
        let out = {
            let model = lock(&shared);
            self.controller.act_with(crate::audit::Origin::Check, |c| {
                let mut out = f(flow, view, &model, c);
                // The flow touches no file: the load file is opened here, and the
                // flow goes on with what was found, in the same turn.
                if let Some(req) = out.open_loads.take() {
                    let opened = crate::loads::disk::open_or_create(&req.path, &req.circuits);
                    out.absorb(flow.loads_opened(opened, view, &model, c, Instant::now()));
                }
                (std::mem::take(&mut out.packets), out)
            })
        };
        self.check.progress.extend(out.progress);
        if !was_finished && flow.finished() {
            let how = match CheckEnd::of(view) {
                CheckEnd::Passed => "everything passed",
                CheckEnd::Failed => "something failed (see its results)",
                CheckEnd::Interrupted => "interrupted",
            };
            lock(&shared).log(
                Instant::now(),
                crate::model::LogLevel::Info,
                format!("check: the installation check ended: {how}"),
            );
        }
        if *view != before {
            self.dirty = true;
        }
        if out.ended {
            // However it ended (a key, a tick, an interruption), at whatever stage.
            self.write_check_report();
        }
    }

    /// Something the person did, as the flow's command.
    pub fn check_command(&mut self, cmd: Command, now: Instant) {
        self.with_check(|flow, view, model, c| flow.command(cmd, view, model, c, now));
    }

    /// Ends a running check from outside (quit, a signal, a panic). `may_wait`: the
    /// caller goes on ticking, so a circuit switched off now is seen off. Once the
    /// check has ended, its report is written (marked INCOMPLETE, with what it left in
    /// which state), as the headless check writes it: the page may be on its way
    /// out, and a report written later would never be. (`with_check` writes the
    /// report of every check that ends, on the flow's `ended`.)
    pub fn check_interrupt(&mut self, cause: Cause, may_wait: bool, now: Instant) {
        if self.check_finished() {
            return;
        }
        self.with_check(|flow, view, model, c| {
            flow.interrupt_for(cause, may_wait, view, model, c, now)
        });
    }

    /// The flow's clocks, after the controller's tick saw the model.
    pub(super) fn check_tick(&mut self, now: Instant) {
        if self.check_finished() {
            return;
        }
        self.with_check(|flow, view, model, c| flow.tick(view, model, c, now));
    }

    /// Sets where the report of the check goes (`--report DIR`; the page's folder).
    pub fn set_check_report_dir(&mut self, dir: Option<PathBuf>) {
        self.check.report_dir = dir;
    }

    /// Writes the report of an ended check, once, into the report folder: Markdown
    /// and CSV (`crate::check::report`), complete or not.
    fn write_check_report(&mut self) {
        if self.check.reported || self.check.flow.is_none() {
            return;
        }
        let about = self.check_about();
        let Some(dir) = self.check.report_dir.clone() else {
            self.log_check(&about);
            return;
        };
        let written = report_files::write(&dir, &self.check.view, &about);
        // Only a report on the disk counts as written: one that failed (a USB stick
        // pulled, a folder made read-only) stays to be written again with `w`, the
        // results still in memory.
        let line = match written {
            Ok(w) => {
                self.check.reported = true;
                self.check.view.report = Some(w.markdown.clone());
                self.check.view.report_error = None;
                words::report_written(&w.markdown, &w.csv)
            }
            Err(e) => {
                let why = format!("{}: {e}", dir.display());
                self.check.view.report_error = Some(why.clone());
                format!("✗ The report could not be written to {why}")
            }
        };
        // The logbook has it whether the report could be written or not (with the
        // report's path when it was).
        self.log_check(&about);
        // The screen's one line of news is short (the summary's head has the path
        // and the reason); the headless run prints the whole line.
        self.check.view.message = Some(match &self.check.view.report_error {
            Some(_) => "✗ The report could not be written (why: above); w writes it again.".into(),
            None => line.clone(),
        });
        self.check.progress.push(line);
        self.dirty = true;
    }

    /// The check's record into the logbook, once: its results, and the load file's
    /// text as it is now (the check read it at its load analysis, minutes ago).
    fn log_check(&mut self, about: &crate::check::report::About) {
        if self.check.logged {
            return;
        }
        self.check.logged = true;
        let Some(book) = &self.logbook else {
            return;
        };
        let load_file = match &self.check.view.loads {
            Some(crate::check::state::LoadsView::Analysed { path, .. }) => {
                std::fs::read_to_string(path).ok()
            }
            _ => None,
        };
        let record = crate::check::record::check(&self.check.view, about, load_file);
        book.record(crate::logbook::Entry {
            at: about.when,
            origin: crate::audit::Origin::Check.word(),
            summary: crate::check::record::summary(&record),
            what: crate::logbook::What::Check(Box::new(record)),
        });
    }

    /// Where and when the check ran, for its report and its record.
    fn check_about(&self) -> crate::check::report::About {
        let (port, unit, travel) = {
            // One lock for all: two guards in one expression would deadlock.
            let m = self.model();
            let port = match &m.source {
                Source::Serial { path } => path.clone(),
                Source::Simulated { scenario } => format!("built-in virtual VP-X ({scenario})"),
                Source::Replay { file } => file.clone(),
            };
            let now = Instant::now();
            // The ends the screen showed the positions on.
            let travel = self
                .check
                .view
                .motors
                .iter()
                .filter_map(|r| {
                    crate::ui::check::motors::ends(r.motor, &m, now).map(|e| (r.motor, e))
                })
                .collect();
            (port, m.version.map(|v| v.value), travel)
        };
        crate::check::report::About {
            when: self
                .check
                .started
                .unwrap_or_else(std::time::SystemTime::now),
            port,
            unit,
            ours: crate::program::VERSION.to_string(),
            travel,
        }
    }

    /// Why the report of an ended check is not on the disk, if it failed.
    pub fn check_report_error(&self) -> Option<&str> {
        self.check.view.report_error.as_deref()
    }

    pub(super) fn check_deadline(&self) -> Option<Instant> {
        self.check.flow.as_ref().and_then(CheckFlow::next_deadline)
    }

    /// `i` on the device list.
    pub(super) fn open_check_from_list(&mut self, now: Instant) {
        // A check left open (finished or stopped) is shown again; a new one starts
        // only from the device list after it was left with Esc.
        if self.check.flow.is_some() {
            self.view.screen = Screen::Check;
            self.dirty = true;
            return;
        }
        self.open_check(page_options(), now);
        // The report goes beside the config file, with the load file.
        self.set_check_report_dir(crate::places::reports_dir());
    }

    /// Scrolls the results (or the load analysis) of an ended check by `by` lines,
    /// kept within the list as the terminal shows it now.
    fn check_scroll(&mut self, by: isize) -> Flow {
        let (w, h) = crossterm::terminal::size().unwrap_or((80, 24));
        let max = {
            let m = self.model();
            crate::ui::check::results_scroll_max(
                &self.check.view,
                &m,
                &self.view,
                Instant::now(),
                ratatui::layout::Rect::new(0, 0, w, h),
            )
        };
        let v = &mut self.check.view;
        v.scroll = v.scroll.saturating_add_signed(by).min(max);
        Flow::Continue
    }

    /// A key on the check screen.
    pub(super) fn check_key(&mut self, key: KeyEvent, now: Instant) -> Flow {
        if key.kind == KeyEventKind::Release {
            return Flow::Continue;
        }
        self.dirty = true;
        if key.modifiers.contains(KeyModifiers::CONTROL)
            && matches!(key.code, KeyCode::Char('c' | 'C'))
        {
            self.controller.stop(now, StopReason::Quit);
            self.check_interrupt(Cause::Quit, false, now);
            return Flow::Quit;
        }
        // Any key stops a running motor before it does anything else, as everywhere.
        self.controller.stop(now, StopReason::OtherKey);
        let n = self.controller.take_notice();
        self.set_notice(now, n);
        let leave = matches!(key.code, KeyCode::Esc | KeyCode::Char('q'));
        if self.check_finished() && self.check.flow.is_some() {
            match key.code {
                // The report again, into the same folder, after a write that failed.
                KeyCode::Char('w') if !self.check.reported => {
                    self.write_check_report();
                    return Flow::Continue;
                }
                KeyCode::Char('l') if self.check.view.loads.is_some() => {
                    self.check.view.show_loads = !self.check.view.show_loads;
                    self.check.view.scroll = 0;
                    return Flow::Continue;
                }
                KeyCode::Up | KeyCode::Char('k') => return self.check_scroll(-1),
                KeyCode::Down | KeyCode::Char('j') => return self.check_scroll(1),
                KeyCode::PageUp => return self.check_scroll(-(page_lines() as isize)),
                KeyCode::PageDown => return self.check_scroll(page_lines() as isize),
                KeyCode::Home => return self.check_scroll(isize::MIN / 2),
                KeyCode::End => return self.check_scroll(isize::MAX / 2),
                _ => {}
            }
        }
        if self.check_finished()
            && leave
            && self.check.view.report_error.is_some()
            && !self.check.leave_asked
        {
            // Leaving drops the results, and the report is not on the disk yet.
            self.check.leave_asked = true;
            self.check.view.message = Some(
                "The report is not written: w writes it again; Esc again leaves without it.".into(),
            );
            return Flow::Continue;
        }
        if self.check_finished() || (leave && self.check.view.step == Step::Confirm) {
            if leave || key.code == KeyCode::Enter {
                // Nothing is running (or nothing was touched yet): back to the list.
                self.check.flow = None;
                self.view.screen = Screen::Devices;
            }
            return Flow::Continue;
        }
        let cmd = match key.code {
            KeyCode::Esc | KeyCode::Char('q') => Command::Stop,
            KeyCode::Enter => Command::Enter,
            KeyCode::Up | KeyCode::Char('k') => Command::Up,
            KeyCode::Down | KeyCode::Char('j') => Command::Down,
            KeyCode::Char('x') => Command::Toggle,
            KeyCode::Char('s') => Command::SkipItem,
            KeyCode::Char('S') => Command::SkipStep,
            KeyCode::Char('r') => Command::Retry,
            KeyCode::Char('y') => Command::Lit(true),
            KeyCode::Char('n') => Command::Lit(false),
            _ => return Flow::Continue,
        };
        self.check_command(cmd, now);
        Flow::Continue
    }
}

/// How far PgUp and PgDn scroll the results: most of a screen, from the terminal's
/// height now, keeping a few lines of the last page in sight.
fn page_lines() -> usize {
    let (_, h) = crossterm::terminal::size().unwrap_or((80, 24));
    usize::from(h).saturating_sub(16).max(5)
}

//! The installation check wired to its flow ([`crate::check`]): `i` on the device list
//! opens it, keys become the flow's commands, the page's loop ticks it at its
//! deadlines and after every packet, and `vpx-efis check` runs the same flow with no
//! screen, printing each result as it comes.
//!
//! Everything it does to the aircraft goes through the page's own paths: its packets
//! are queued under the motor controller's lock (so a stop decided after a move never
//! reaches the wire before it), its motor runs are the controller's, and every way
//! the page ends (quit, a signal, a closed terminal, a panic, the drop guard) first
//! interrupts the check, which switches off the circuit it has on.

mod report_files;

pub use report_files::{prepare as prepare_report_dir, write as write_report};

use std::io::BufRead;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, select, unbounded};
use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::{App, AppOptions, Flow, builtin_sim, lock, signals};
use crate::check::state::{CheckView, Mark, Step};
use crate::check::words;
use crate::check::{Cause, CheckFlow, Command, Options, plan};
use crate::control::{MotorStreamer, StopReason};
use crate::link::{self, PortAddr};
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
    /// Esc was pressed once with the report not written: the next one leaves.
    leave_asked: bool,
}

/// The options of a check opened from the page: everything run, the load file beside
/// the config file.
fn page_options() -> Options {
    Options {
        loads_file: crate::loads::disk::default_path(),
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
        ) -> crate::check::Effects,
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
        self.view.motor_run = self.controller.running();
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
        let Some(dir) = self.check.report_dir.clone() else {
            return;
        };
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
        let about = crate::check::report::About {
            when: self
                .check
                .started
                .unwrap_or_else(std::time::SystemTime::now),
            port,
            unit,
            ours: crate::program::VERSION.to_string(),
            travel,
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
        // The screen's one line of news is short (the summary's head has the path
        // and the reason); the headless run prints the whole line.
        self.check.view.message = Some(match &self.check.view.report_error {
            Some(_) => "✗ The report could not be written (why: above); w writes it again.".into(),
            None => line.clone(),
        });
        self.check.progress.push(line);
        self.dirty = true;
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
        self.set_check_report_dir(crate::check::report::default_dir());
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
        self.view.motor_run = self.controller.running();
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

/// `vpx-efis check`'s arguments, parsed.
#[derive(Debug, Clone)]
pub struct HeadlessCheck {
    /// `None`: the built-in virtual VP-X with `scenario`.
    pub port: Option<PortAddr>,
    pub baud: u32,
    pub scenario: String,
    pub options: Options,
    /// `--report DIR`.
    pub report: Option<PathBuf>,
}

/// How a headless check ended, for its exit status: 0 all passed, 1 something
/// failed, 2 interrupted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CheckEnd {
    Passed,
    Failed,
    Interrupted,
}

impl CheckEnd {
    pub fn of(view: &CheckView) -> CheckEnd {
        if view.interrupted.is_some() {
            CheckEnd::Interrupted
        } else if view.any_failed() {
            CheckEnd::Failed
        } else {
            CheckEnd::Passed
        }
    }

    pub fn code(self) -> u8 {
        match self {
            CheckEnd::Passed => 0,
            CheckEnd::Failed => 1,
            CheckEnd::Interrupted => 2,
        }
    }
}

/// How long a headless check waits for the unit's settings before giving up.
const READY_WITHIN: Duration = Duration::from_secs(10);

/// Lines typed on standard input, each trimmed.
fn stdin_lines() -> Receiver<String> {
    let (tx, rx) = unbounded();
    let _ = std::thread::Builder::new()
        .name("stdin".into())
        .spawn(move || {
            for line in std::io::stdin().lock().lines() {
                let Ok(line) = line else { return };
                if tx.send(line.trim().to_string()).is_err() {
                    return;
                }
            }
        });
    rx
}

/// What a typed line asks of the flow.
fn typed(line: &str) -> Option<Command> {
    Some(match line {
        "" => Command::Enter,
        "s" | "skip" => Command::SkipItem,
        "S" | "skip step" => Command::SkipStep,
        "r" | "retry" => Command::Retry,
        "q" | "quit" | "stop" => Command::Stop,
        _ => return None,
    })
}

/// Runs the check with no screen. `out` gets every line meant for the person (the
/// plan, each result as it comes, the summary); `lines` what the person types.
pub fn run_headless_with(
    h: HeadlessCheck,
    lines: &Receiver<String>,
    terminations: &Receiver<signals::Termination>,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<CheckEnd> {
    let mut sim = None;
    let (source, connector) = match &h.port {
        Some(addr) => {
            link::check_port(addr, h.baud)?;
            (
                Source::Serial {
                    path: addr.to_string(),
                },
                link::port_connector(addr, h.baud),
            )
        }
        None => {
            let (source, connector, handle) = builtin_sim(&h.scenario)?;
            sim = Some(handle);
            (source, connector)
        }
    };
    let options = AppOptions {
        // The audit log goes with the report.
        audit: h.report.clone().or_else(crate::check::report::default_dir),
        ..AppOptions::default()
    };
    let mut app = App::new(source, connector, options);
    let handle = app.link_handle();
    super::terminal::install_panic_hook();
    super::terminal::set_emergency_stop(move || {
        for p in MotorStreamer::emergency_stop_packets() {
            let _ = handle.send(p);
        }
        std::thread::sleep(Duration::from_millis(50));
    });
    let result = headless_loop(&mut app, h, lines, terminations, out);
    app.shutdown();
    super::terminal::clear_emergency_stop();
    if let Some(s) = sim {
        s.stop();
    }
    result
}

/// Standard input as the headless check reads it: the typed lines, and whether it has
/// ended (`/dev/null`, a closed pipe, cron, CI). An ended channel is no longer
/// selected on: it is always ready, and selecting on it spun a core at 100 %.
struct Typed<'a> {
    lines: &'a Receiver<String>,
    ended: bool,
}

/// Why [`pump`] returned.
enum Pumped {
    /// `done` became true, or `until` came.
    Done,
    Signal(signals::Termination),
    /// Standard input ended just now: nobody can answer any more.
    InputEnded,
}

/// What the headless check says when standard input ends.
const NOBODY_TO_ANSWER: &str = "Standard input is at its end (no terminal, /dev/null, a closed \
     pipe): nobody can answer here.";

/// Why the switch step is skipped when standard input has ended.
const SWITCHES_NEED_A_PERSON: &str = "The switch step, which needs a person to flip each \
     switch and say when it is done, is skipped.";

/// Waits for wake-ups, typed lines or a signal until `until` or `done`.
fn pump(
    app: &mut App,
    input: &mut Typed,
    terminations: &Receiver<signals::Termination>,
    until: Instant,
    mut on_line: impl FnMut(&mut App, String),
    done: impl Fn(&App) -> bool,
    mut after_tick: impl FnMut(&mut App),
) -> Pumped {
    let never = crossbeam_channel::never();
    loop {
        let now = Instant::now();
        app.tick(now);
        // No screen: nothing is ever waiting to be drawn.
        app.dirty = false;
        app.last_draw = Some(now);
        after_tick(app);
        if done(app) || now >= until {
            return Pumped::Done;
        }
        let deadline = app.next_deadline(now).min(until);
        let lines = if input.ended { &never } else { input.lines };
        select! {
            recv(app.wake_rx) -> w => if let Ok(w) = w { app.on_wake(w, Instant::now()) },
            recv(lines) -> l => match l {
                Ok(l) => on_line(app, l),
                Err(_) => {
                    input.ended = true;
                    return Pumped::InputEnded;
                }
            },
            recv(terminations) -> t => if let Ok(t) = t { return Pumped::Signal(t) },
            default(deadline.saturating_duration_since(Instant::now())) => {}
        }
        while let Ok(w) = app.wake_rx.try_recv() {
            app.on_wake(w, Instant::now());
        }
    }
}

fn headless_loop(
    app: &mut App,
    h: HeadlessCheck,
    lines: &Receiver<String>,
    terminations: &Receiver<signals::Termination>,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<CheckEnd> {
    let port = h.port.as_ref().map_or_else(
        || format!("the built-in virtual VP-X ({})", h.scenario),
        |p| p.to_string(),
    );
    writeln!(
        out,
        "Installation check on {port}: waiting for the unit's settings…"
    )?;
    let ready = |app: &App| plan::ready(&app.model(), Instant::now()).is_ok();
    let mut input = Typed {
        lines,
        ended: false,
    };
    let ready_by = Instant::now() + READY_WITHIN;
    loop {
        match pump(
            app,
            &mut input,
            terminations,
            ready_by,
            |_, _| {},
            ready,
            |_| {},
        ) {
            Pumped::InputEnded => continue,
            Pumped::Signal(t) => {
                writeln!(out, "Stopped by {} before anything was touched.", t.name())?;
                return Ok(CheckEnd::Interrupted);
            }
            Pumped::Done => break,
        }
    }
    if let Err(why) = plan::ready(&app.model(), Instant::now()) {
        anyhow::bail!(
            "{port}: {why} after {} s; is the VP-X on and the cable in?",
            READY_WITHIN.as_secs()
        );
    }
    let unmatched = plan::unmatched(&app.model(), Instant::now(), &h.options.choices.exclude);
    if !unmatched.is_empty() {
        let names: Vec<String> = app
            .model()
            .circuits(Instant::now())
            .iter()
            .map(|c| format!("{} ({})", c.name, c.pin))
            .collect();
        return Err(crate::program::UsageError(format!(
            "--exclude {}: no circuit has that name or pin; the unit's circuits are: {}",
            unmatched.join(", "),
            names.join(", ")
        ))
        .into());
    }
    let yes = h.options.yes;
    let mut options = h.options;
    // Nobody to flip the switches: that step is skipped before the plan is made, so
    // the plan, the report and the summary all say so.
    let skips_switches = input.ended && yes && !options.skip.contains(&Step::Switches);
    if skips_switches {
        options.skip.push(Step::Switches);
    }
    app.set_check_report_dir(h.report.clone());
    app.open_check(options, Instant::now());
    print_plan(app.check_view(), out)?;
    if skips_switches {
        writeln!(out, "{NOBODY_TO_ANSWER} {SWITCHES_NEED_A_PERSON}")?;
    }
    if !yes {
        writeln!(
            out,
            "Is the aircraft safe to power these circuits and to move its flaps and trims? \
             Type yes and Enter to start; anything else stops here."
        )?;
        out.flush()?;
        let confirmed = |app: &App| app.check_view().step != Step::Confirm || app.check_finished();
        let mut pumped = Pumped::InputEnded;
        if !input.ended {
            pumped = pump(
                app,
                &mut input,
                terminations,
                Instant::now() + Duration::from_secs(24 * 3600),
                |app, l| {
                    let cmd = if matches!(l.to_ascii_lowercase().as_str(), "y" | "yes") {
                        Command::Enter
                    } else {
                        Command::Stop
                    };
                    app.check_command(cmd, Instant::now());
                },
                confirmed,
                |_| {},
            );
        }
        match pumped {
            Pumped::Signal(t) => {
                app.check_interrupt(Cause::Signal(t.name().into()), false, Instant::now());
            }
            // Only a person at the keyboard or `--yes` allows power.
            Pumped::InputEnded if !confirmed(app) => {
                writeln!(
                    out,
                    "{NOBODY_TO_ANSWER} Nobody typed yes, so nothing is switched on. To run \
                     the check with nobody at the keyboard, give --yes."
                )?;
                app.check_command(Command::Stop, Instant::now());
            }
            _ => {}
        }
    }
    if !app.check_finished() {
        writeln!(
            out,
            "Where you must act, the check asks. Type Enter to go on, s to skip an item, S to \
         skip the rest of a step, r to retry, q to stop (it puts back what it changed)."
        )?;
    }
    let far = Instant::now() + Duration::from_secs(24 * 3600);
    let on_line = |app: &mut App, l: String| {
        if let Some(cmd) = typed(&l) {
            app.check_command(cmd, Instant::now());
        }
    };
    loop {
        let progress = |app: &mut App| print_progress(app, out);
        match pump(
            app,
            &mut input,
            terminations,
            far,
            on_line,
            App::check_finished,
            progress,
        ) {
            Pumped::InputEnded => {
                // Standard input ended part way: the switch step, if it is under way,
                // is skipped (what it found stands); the rest needs nobody.
                let switching = app.check_view().step == Step::Switches;
                if switching {
                    writeln!(out, "{NOBODY_TO_ANSWER} {SWITCHES_NEED_A_PERSON}")?;
                } else {
                    writeln!(out, "{NOBODY_TO_ANSWER}")?;
                }
                if switching {
                    app.check_command(Command::SkipStep, Instant::now());
                }
            }
            Pumped::Signal(t) => {
                // Ctrl-C or SIGTERM: stop the motor, switch the circuit back off, and
                // wait (a few seconds at most) to see it off before saying what is left.
                app.check_interrupt(Cause::Signal(t.name().into()), true, Instant::now());
                let soon = Instant::now() + Duration::from_secs(5);
                while let Pumped::InputEnded = pump(
                    app,
                    &mut input,
                    terminations,
                    soon,
                    |_, _| {},
                    App::check_finished,
                    |app: &mut App| print_progress(app, out),
                ) {}
                app.check_interrupt(Cause::Signal(t.name().into()), false, Instant::now());
                break;
            }
            Pumped::Done => break,
        }
    }
    app.write_check_report();
    print_progress(app, out);
    let view = app.check_view().clone();
    print_summary(&view, out)?;
    let end = CheckEnd::of(&view);
    // A report asked for and not written is an error of the run (exit 1, the reason
    // on stderr), whatever the check found; an interrupted check keeps its 2, the
    // state it left the aircraft in being the more urgent news.
    match &view.report_error {
        Some(why) if end != CheckEnd::Interrupted => {
            anyhow::bail!("the report could not be written to {why}")
        }
        _ => Ok(end),
    }
}

/// Prints the check's results that came since the last call, as they came.
fn print_progress(app: &mut App, out: &mut dyn std::io::Write) {
    for line in app.take_check_progress() {
        let _ = writeln!(out, "{line}");
    }
    let _ = out.flush();
}

/// `vpx-efis check` on this process's terminal.
pub fn run_headless(h: HeadlessCheck) -> anyhow::Result<CheckEnd> {
    let terminations = signals::listen()?;
    let lines = stdin_lines();
    let mut out = std::io::stdout();
    run_headless_with(h, &lines, &terminations, &mut out)
}

fn print_plan(view: &CheckView, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    // A step skipped from the start (`--skip`) touches nothing: the plan says so
    // rather than list what it would have switched on or run.
    let skipped = |s| view.skipped_steps.contains(&s);
    if skipped(Step::Circuits) {
        writeln!(
            out,
            "Before power: the circuits step is skipped, so the check switches no circuit on."
        )?;
    } else {
        writeln!(
            out,
            "Before power, the check will switch on, one at a time:"
        )?;
        for p in &view.plan {
            writeln!(
                out,
                "  {} ({}), breaker {}, for up to {} s",
                p.name,
                p.pin,
                p.breaker.map_or("?".into(), |b| format!("{b} A")),
                p.on_for.as_secs()
            )?;
        }
    }
    if skipped(Step::Motors) && !view.planned_motors.is_empty() {
        writeln!(out, "The motors step is skipped: the check runs no motor.")?;
    } else {
        for (m, d) in &view.planned_motors {
            writeln!(
                out,
                "  {}: run briefly each way and back, about {} s",
                m.name(),
                d.as_secs()
            )?;
        }
    }
    if !view.excluded.is_empty() {
        writeln!(out, "It leaves alone:")?;
        for e in &view.excluded {
            writeln!(out, "  {}: {}", e.name, e.why)?;
        }
    }
    // The confirm screen's words for the same inputs (the plan's, `plan::unasked`), so
    // the person confirming here knows as much as one confirming on the page.
    if !view.unasked.is_empty() && !view.skipped_steps.contains(&Step::Switches) {
        writeln!(out, "It will not ask you to flip:")?;
        for u in &view.unasked {
            writeln!(out, "  {}", u.why)?;
        }
    }
    Ok(())
}

/// The end of a headless run: what is left to fix, the switches to cycle, what an
/// interruption left.
fn print_summary(view: &CheckView, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    let count = |m| view.marks().filter(|x| *x == m).count();
    writeln!(
        out,
        "Summary: {} passed, {} failed, {}, {} skipped, {} not run",
        count(Mark::Pass),
        count(Mark::Fail),
        words::count(count(Mark::Warn), "warning", "warnings"),
        count(Mark::Skipped),
        count(Mark::NotRun)
    )?;
    let fix = view.left_to_fix();
    if !fix.is_empty() {
        writeln!(out, "Left to fix:")?;
        for f in fix {
            writeln!(out, "  - {f}")?;
        }
    }
    if let Some(i) = &view.interrupted {
        writeln!(out, "The check was interrupted: {}", i.cause)?;
        if i.left.is_empty() && view.to_cycle.is_empty() {
            writeln!(out, "  Every circuit it touched is as it found it.")?;
        } else if i.left.is_empty() {
            writeln!(
                out,
                "  Every circuit it touched is back as it found it, but held there by \
                 DEVICE_POWER: flip the switches listed above."
            )?;
        }
        for crate::check::state::LeftBehind {
            id,
            name,
            state: why,
        } in &i.left
        {
            writeln!(out, "  - {name} (device {id}): {why}")?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::state::{Excluded, Input, Unasked};

    fn view() -> CheckView {
        CheckView {
            excluded: vec![Excluded {
                id: 7,
                name: "Pitot Heat".into(),
                pin: "10A-4",
                breaker: Some(10),
                switch: None,
                why: "suggested: the name has \"pitot\"".into(),
                may_include: true,
            }],
            unasked: vec![
                Unasked {
                    input: Input::Switch(8),
                    circuits: vec![7],
                    why: "switch 8 powers only Pitot Heat (excluded): not asked".into(),
                },
                Unasked {
                    input: Input::FlapUp,
                    circuits: vec![],
                    why: "flap switch UP drives Flaps (excluded): not asked".into(),
                },
            ],
            ..CheckView::default()
        }
    }

    /// The headless plan says, before the person confirms, which switch inputs the
    /// check will not ask for and why, in the plan's words (the confirm screen's).
    #[test]
    fn the_headless_plan_lists_the_inputs_it_will_not_ask_for() {
        let mut out = Vec::new();
        print_plan(&view(), &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(
            text.ends_with(
                "It leaves alone:\n  Pitot Heat: suggested: the name has \"pitot\"\n\
                 It will not ask you to flip:\n  \
                 switch 8 powers only Pitot Heat (excluded): not asked\n  \
                 flap switch UP drives Flaps (excluded): not asked\n"
            ),
            "{text}"
        );
        // With the switch step skipped nothing is asked anyway: not said.
        let mut out = Vec::new();
        let skipped = CheckView {
            skipped_steps: vec![Step::Switches],
            ..view()
        };
        print_plan(&skipped, &mut out).unwrap();
        assert!(!String::from_utf8(out).unwrap().contains("flip"));
    }

    /// `--skip circuits,motors`: the plan does not list circuits it will not switch
    /// on or motors it will not run, and says why.
    #[test]
    fn the_headless_plan_says_what_a_skipped_step_will_not_touch() {
        use crate::check::state::Planned;
        use crate::model::Motor;
        let planned = CheckView {
            plan: vec![Planned {
                id: 4,
                name: "Nav Lt".into(),
                pin: "5A-1",
                breaker: Some(3),
                switch: None,
                on_for: Duration::from_secs(5),
            }],
            planned_motors: vec![(Motor::Flaps, Duration::from_secs(3))],
            ..CheckView::default()
        };
        let plan = |v: &CheckView| {
            let mut out = Vec::new();
            print_plan(v, &mut out).unwrap();
            String::from_utf8(out).unwrap()
        };
        let all = plan(&planned);
        assert!(
            all.starts_with(
                "Before power, the check will switch on, one at a time:\n  \
             Nav Lt (5A-1), breaker 3 A, for up to 5 s\n  \
             flaps: run briefly each way and back, about 3 s\n"
            ),
            "{all}"
        );
        let text = plan(&CheckView {
            skipped_steps: vec![Step::Circuits, Step::Motors],
            ..planned
        });
        assert_eq!(
            text,
            "Before power: the circuits step is skipped, so the check switches no circuit on.\n\
             The motors step is skipped: the check runs no motor.\n"
        );
    }
}

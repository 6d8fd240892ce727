//! The check's driver: the steps in order, the person's commands, and interruption.
//!
//! The app (or `vpx-efis check`) calls [`CheckFlow::tick`] at
//! [`CheckFlow::next_deadline`] and after packets arrive, [`CheckFlow::command`] for
//! what the person does, and [`CheckFlow::interrupt`] for what ends the check from
//! outside (quit, a signal, a panic). Each call gets the page's [`Controller`], so a
//! motor test is a run of the page's own safe stream (every stop cause of the page
//! applies), and gives back the packets to queue, in order, while the controller is
//! still held. The flow itself notices COMMUNICATION LOST, a link that cannot send,
//! and a fault that appears mid-step, from the model.

use std::time::Instant;

use super::calls::{CheckEffects, Command};
use super::plan::{self, Choices};
use super::state::{CheckView, Interruption, LeftBehind, Prompt, Step};
use super::step::{
    Call, CallContext, Next, Powered, Shared, StepRun, circuit_on, put_back, view_or_model_name,
};
use super::timing::Timing;
use super::words;
use super::{circuits, motors, switches};
use crate::control::{Controller, StopReason};
use crate::model::{Connection, Model};
use crate::protocol::device::DEVICE_COUNT;

/// How the check was asked to run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    /// Steps not to run (`--skip`).
    pub skip: Vec<Step>,
    pub choices: Choices,
    /// `--yes`: the person already confirmed the aircraft is safe to power.
    pub yes: bool,
    /// The load analysis file (`crate::loads`); `None`: the step says there is none.
    pub loads_file: Option<std::path::PathBuf>,
    pub timing: Timing,
    /// The wall-clock time at the `now` the flow is made with ([`CheckFlow::new`]), so
    /// a finding can name the time of day something happened ("sent at 21:40:12
    /// UTC"); `None`: it says how long before instead. The flow never reads a clock.
    pub clock: Option<std::time::SystemTime>,
    /// This aircraft's last check, from the logbook, for the trend beside each
    /// current (`super::trend`); `None`: there is none (or no logbook).
    pub last_check: Option<super::trend::LastCheck>,
}

/// What ended the check from outside.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Cause {
    /// The person stopped the check (or quit the page).
    Quit,
    /// SIGTERM, SIGHUP, SIGINT, a closed console.
    Signal(String),
    /// A thread of the program panicked.
    Panic,
}

impl Cause {
    fn words(&self) -> String {
        match self {
            Cause::Quit => "stopped by you".into(),
            Cause::Signal(s) => format!("ended by a signal ({s})"),
            Cause::Panic => "the program failed".into(),
        }
    }

    /// A signal ends the check as it ends the page: as a quit (the page's own stop
    /// cause for SIGTERM/SIGHUP).
    fn stop_reason(&self) -> StopReason {
        match self {
            Cause::Panic => StopReason::Panic,
            Cause::Quit | Cause::Signal(_) => StopReason::Quit,
        }
    }
}

#[derive(Debug)]
pub(super) enum Phase {
    Confirm,
    /// A step's item under test.
    Testing(Step, Box<dyn StepRun>),
    /// Waiting for the app to open the load file (`CheckEffects::open_loads`).
    Loads,
    /// Interrupted: waiting to see `Powered` go off before the list of what is left
    /// is final.
    Stopping {
        powered: Powered,
        until: Instant,
        cause: String,
        left: Vec<LeftBehind>,
    },
    Done,
}

/// The line that starts the check: what it will power and run, counting only the
/// steps that run (a step skipped from the start, `--skip`, touches nothing, as the
/// plan above it says).
pub fn confirmed_line(view: &CheckView) -> String {
    let to = |step, n, one, verb| {
        if view.skipped_steps.contains(&step) {
            format!("no {one} to {verb} ({one}s step skipped)")
        } else {
            format!("{} to {verb}", words::count(n, one, &format!("{one}s")))
        }
    };
    format!(
        "Confirmed: {}, {}, {} left alone",
        to(Step::Circuits, view.plan.len(), "circuit", "power"),
        to(Step::Motors, view.planned_motors.len(), "motor", "run"),
        view.excluded.len()
    )
}

/// The installation check in progress. See the module docs.
#[derive(Debug)]
pub struct CheckFlow {
    opts: Options,
    phase: Phase,
    /// What the steps read and add to: the timing, the faults known, trouble ahead,
    /// the clock.
    shared: Shared,
    system_fault_at_start: bool,
    write_errors_at_start: u64,
}

impl CheckFlow {
    /// A new check on the unit the model describes; the view starts over.
    pub fn new(opts: Options, view: &mut CheckView, model: &Model, now: Instant) -> CheckFlow {
        *view = CheckView {
            skipped_steps: opts.skip.clone(),
            last_check: opts.last_check.clone(),
            ..CheckView::default()
        };
        let (codes, system) = model
            .live_faults(now)
            .unwrap_or(([crate::protocol::FaultCode::NoFault; DEVICE_COUNT], false));
        let flow = CheckFlow {
            shared: Shared {
                timing: opts.timing,
                known_faults: (0..DEVICE_COUNT as u8)
                    .filter(|&i| codes[i as usize].is_fault())
                    .collect(),
                trouble_ahead: None,
                clock: opts.clock,
                made_at: now,
                nobody_to_answer: false,
            },
            system_fault_at_start: system,
            write_errors_at_start: model.link.write_errors,
            opts,
            phase: Phase::Confirm,
        };
        flow.replan(view, model, now);
        flow
    }

    /// Where the check is, for the tests that stop it at every stage: the step, then
    /// the item's own stage ("circuits: measure, as it is").
    #[cfg(test)]
    pub(super) fn stage(&self) -> String {
        match &self.phase {
            Phase::Confirm => "before power".into(),
            Phase::Testing(step, run) => {
                let step = Step::SKIPPABLE
                    .iter()
                    .find(|(s, _)| s == step)
                    .map_or("", |(_, word)| word);
                format!("{step}: {}", run.stage())
            }
            Phase::Stopping { .. } => "stopping".into(),
            Phase::Loads => "loads".into(),
            Phase::Done => "done".into(),
        }
    }

    /// Whether the check has ended (finished or interrupted, all put back that could be).
    pub fn finished(&self) -> bool {
        matches!(self.phase, Phase::Done)
    }

    /// When the flow must be ticked next, if it waits on a clock.
    pub fn next_deadline(&self) -> Option<Instant> {
        match &self.phase {
            Phase::Confirm | Phase::Done | Phase::Loads => None,
            Phase::Testing(_, run) => run.deadline(),
            Phase::Stopping { until, .. } => Some(*until),
        }
    }

    fn replan(&self, view: &mut CheckView, model: &Model, now: Instant) {
        let t = &self.shared.timing;
        let lengths = plan::Lengths {
            on_for: t.on_for,
            motor_for: t.motor_for(),
        };
        let p = plan::build(model, now, &self.opts.choices, &self.opts.skip, lengths);
        view.plan = p.circuits;
        view.planned_motors = p.motors;
        view.excluded = p.excluded;
        view.unasked = p.unasked;
        let ready = plan::ready(model, now);
        let confirm = if self.opts.yes {
            "confirmed with --yes"
        } else {
            "Enter: the aircraft is safe to power these"
        };
        view.prompt = Some(Prompt {
            todo: match &ready {
                Ok(()) => format!(
                    "Make sure the aircraft is safe to power the circuits listed and to move \
                     its flaps and trims; {confirm}."
                ),
                Err(why) => why.clone(),
            },
            watching: "what the unit says it holds: names, switches, breakers".into(),
            time_left: None,
            keys: vec![
                ("Enter", "confirm"),
                ("x", "exclude / include"),
                ("Esc", "leave"),
            ],
        });
        let rows = view.plan.len() + view.excluded.len();
        view.current = match view.current {
            Some(c) if rows > 0 => Some(c.min(rows - 1)),
            _ if rows > 0 => Some(0),
            _ => None,
        };
    }

    /// A command from the person.
    pub fn command(
        &mut self,
        cmd: Command,
        view: &mut CheckView,
        model: &Model,
        ctl: &mut Controller,
        now: Instant,
    ) -> CheckEffects {
        effects(model, ctl, now, |cx| {
            if cmd == Command::NobodyToAnswer {
                self.shared.nobody_to_answer = true;
            }
            if cmd == Command::Stop {
                if !self.finished() {
                    self.interrupt(Cause::Quit, true, view, cx);
                }
                return;
            }
            match &mut self.phase {
                Phase::Confirm => self.confirm_command(cmd, view, cx),
                Phase::Testing(..) => self.item_command(cmd, view, cx),
                Phase::Stopping { .. } | Phase::Done | Phase::Loads => {}
            }
        })
    }

    fn confirm_command(&mut self, cmd: Command, view: &mut CheckView, cx: &mut CallContext) {
        let rows = view.plan.len() + view.excluded.len();
        match cmd {
            Command::Up => view.current = view.current.map(|c| c.saturating_sub(1)),
            Command::Down => {
                view.current = view.current.map(|c| (c + 1).min(rows.saturating_sub(1)))
            }
            Command::Toggle => {
                let Some(c) = view.current else { return };
                if let Some(p) = view.plan.get(c) {
                    self.opts.choices.excluded_here.push(p.id);
                    view.message = Some(format!("{} excluded", p.name));
                } else if let Some(e) = view.excluded.get(c - view.plan.len()) {
                    let here = self
                        .opts
                        .choices
                        .excluded_here
                        .iter()
                        .position(|&i| i == e.id);
                    if let Some(i) = here {
                        self.opts.choices.excluded_here.remove(i);
                        view.message = Some(format!("{} included", e.name));
                    } else if e.may_include {
                        self.opts.choices.include.push(e.id);
                        view.message = Some(format!("{} included", e.name));
                    } else if let Some(i) = self
                        .opts
                        .choices
                        .exclude
                        .iter()
                        .position(|x| plan::names(x, &e.name, ""))
                    {
                        self.opts.choices.exclude.remove(i);
                        view.message = Some(format!("{} included", e.name));
                    } else {
                        view.message = Some(format!("{}: {}", e.name, e.why));
                    }
                }
                self.replan(view, cx.model, cx.now);
            }
            Command::Enter => self.start(view, cx),
            _ => {}
        }
    }

    /// Starts the steps, once the unit's settings are known and the person confirmed.
    fn start(&mut self, view: &mut CheckView, cx: &mut CallContext) {
        let (model, now) = (cx.model, cx.now);
        self.replan(view, model, now);
        if let Err(why) = plan::ready(model, now) {
            view.message = Some(format!("not yet: {why}"));
            return;
        }
        view.message = None;
        cx.out.progress.push(confirmed_line(view));
        // Every item gets its line now, so an interruption leaves the ones never
        // reached listed as not run.
        view.switches = super::switches::rows(view, model, now);
        view.circuits = super::circuits::rows(view, model, now);
        view.motors = super::motors::rows(view);
        self.enter_step(Step::Switches, view, cx);
    }

    /// Moves to `step` (or the first one after it not skipped) and starts its first item.
    fn enter_step(&mut self, mut step: Step, view: &mut CheckView, cx: &mut CallContext) {
        loop {
            view.step = step;
            view.current = None;
            view.prompt = None;
            let skipped = self.opts.skip.contains(&step);
            let run: Option<Box<dyn StepRun>> = match step {
                Step::Confirm => None,
                Step::Switches => Some(Box::new(switches::Switches::default())),
                Step::Circuits => Some(Box::new(circuits::Circuits::default())),
                Step::Motors => Some(Box::new(motors::Motors::default())),
                Step::Loads => {
                    if !skipped {
                        if self.loads(view, cx) {
                            // The app opens the file, then `loads_opened` goes on.
                            return;
                        }
                    } else {
                        cx.out.progress.push(skipped_line(step));
                    }
                    None
                }
                Step::Done => {
                    self.finish(view, cx);
                    return;
                }
            };
            if let Some(mut run) = run {
                if !skipped {
                    let shared = &mut self.shared;
                    run.begin(&mut Call { view, cx, shared });
                }
                if self.next_item(step, run, 0, view, cx) {
                    return;
                }
            }
            step = next_step(step);
        }
    }

    /// The step loop: starts the step's first item from `from` not done yet, and the
    /// next while each is done at once (faulted before it was touched, refused, …).
    /// Whether one is under test now; if not, the step is over.
    fn next_item(
        &mut self,
        step: Step,
        mut run: Box<dyn StepRun>,
        mut from: usize,
        view: &mut CheckView,
        cx: &mut CallContext,
    ) -> bool {
        loop {
            if self.opts.skip.contains(&step) {
                let any = view.skip_rest(step, "step skipped");
                if from == 0 || (any && run.says_skip_midway()) {
                    cx.out.progress.push(skipped_line(step));
                }
            }
            let Some(idx) = view.next_not_run(step, from) else {
                return false;
            };
            // The item under test is the selected row, whatever its step.
            view.current = Some(idx);
            let shared = &mut self.shared;
            match run.start(idx, &mut Call { view, cx, shared }) {
                Next::Stay => {
                    self.phase = Phase::Testing(step, run);
                    return true;
                }
                Next::From(i) => from = i,
            }
        }
    }

    /// After a call into the item under test: on `Next::From`, the next item, or the
    /// next step.
    fn go_on(&mut self, next: Next, view: &mut CheckView, cx: &mut CallContext) {
        let Next::From(from) = next else { return };
        let Phase::Testing(step, run) = std::mem::replace(&mut self.phase, Phase::Done) else {
            return;
        };
        if !self.next_item(step, run, from, view, cx) {
            self.enter_step(next_step(step), view, cx);
        }
    }

    /// Step 5: the builder's load file with the currents just measured, or its
    /// template written for next time. The flow touches no file: it asks the app to
    /// open it (`CheckEffects::open_loads`) and goes on in [`CheckFlow::loads_opened`].
    /// Whether it waits for the app to open the file.
    fn loads(&mut self, view: &mut CheckView, cx: &mut CallContext) -> bool {
        let Some(path) = self.opts.loads_file.clone() else {
            view.loads = Some(super::state::LoadsView::Refused(
                "no place for the load file (no config folder on this system)".into(),
            ));
            cx.out
                .progress
                .push("– Load analysis: no place for the load file".into());
            return false;
        };
        cx.out.open_loads = Some(super::calls::LoadsToOpen {
            path,
            circuits: cx.model.circuits(cx.now),
        });
        self.phase = Phase::Loads;
        true
    }

    /// The app opened the load file the flow asked for (`CheckEffects::open_loads`): the
    /// analysis with the currents just measured, or the template written, or why
    /// neither; then the report.
    pub fn loads_opened(
        &mut self,
        opened: Result<crate::loads::disk::Opened, crate::toml_lines::FileError>,
        view: &mut CheckView,
        model: &Model,
        ctl: &mut Controller,
        now: Instant,
    ) -> CheckEffects {
        use super::state::LoadsView;
        use crate::loads::disk::Opened;
        let (Phase::Loads, Some(path)) = (&self.phase, self.opts.loads_file.clone()) else {
            return CheckEffects::default();
        };
        effects(model, ctl, now, |cx| {
            let loads = match opened {
                Ok(Opened::Read(file)) => {
                    let (rows, system) = crate::loads::wiring::from_model(
                        &file.circuits,
                        cx.model,
                        cx.now,
                        &view.measured_amps(),
                    );
                    for r in &rows {
                        if let Some(w) = r.unprotected_words() {
                            cx.out.progress.push(format!(
                                "{} wires: {w}",
                                super::words::badge(super::state::Mark::Fail)
                            ));
                        } else if let Some(w) = r.drop_words() {
                            cx.out.progress.push(format!(
                                "{} wires: {w}",
                                super::words::badge(super::state::Mark::Warn)
                            ));
                        }
                    }
                    view.wires = Some(super::state::WiresView { rows, system });
                    let analysis = crate::loads::analyse(&file, &view.measured_amps());
                    cx.out
                        .progress
                        .push(format!("Load analysis ({}):", path.display()));
                    for phase in crate::loads::Phase::ALL {
                        cx.out.progress.push(format!(
                            "  {}: {:.1} A, {}",
                            phase.title(),
                            analysis.phase(phase).amps,
                            analysis.verdict(phase)
                        ));
                    }
                    LoadsView::Analysed { path, analysis }
                }
                Ok(Opened::TemplateWritten(p)) => {
                    cx.out.progress.push(format!(
                        "– Load analysis: no load file yet; its template, listing every \
                         circuit, was written to {}: fill it in and run the check again",
                        p.display()
                    ));
                    LoadsView::TemplateWritten(p)
                }
                Err(e) => {
                    cx.out.progress.push(format!("✗ Load analysis: {e}"));
                    LoadsView::Refused(e.to_string())
                }
            };
            view.loads = Some(loads);
            self.phase = Phase::Done;
            self.enter_step(next_step(Step::Loads), view, cx);
        })
    }

    fn finish(&mut self, view: &mut CheckView, cx: &mut CallContext) {
        self.phase = Phase::Done;
        cx.out.ended = true;
        // An interrupted check stays on the step where it stopped: the step bar must
        // not show the report as reached.
        if view.interrupted.is_none() {
            view.step = Step::Done;
        }
        view.current = None;
        let fails = view.marks().filter(|m| *m == super::state::Mark::Fail);
        let n = fails.count();
        view.prompt = Some(Prompt {
            todo: if view.interrupted.is_some() {
                "The check was interrupted: see what it left, below.".into()
            } else if n == 0 {
                "The check is complete: nothing failed.".into()
            } else {
                format!("The check is complete: {n} failed; the list of what to fix is below.")
            },
            watching: String::new(),
            time_left: None,
            keys: vec![("Esc", "back to the device list")],
        });
        if view.interrupted.is_none() {
            cx.out.progress.push(format!(
                "Check complete: {} to fix",
                view.left_to_fix().len()
            ));
        }
    }

    fn item_command(&mut self, cmd: Command, view: &mut CheckView, cx: &mut CallContext) {
        match cmd {
            Command::SkipStep => {
                // The item under test is skipped (and put back); each step's next
                // item then sees its step skipped and marks the rest so.
                let step = view.step;
                self.opts.skip.push(step);
                if !view.skipped_steps.contains(&step) {
                    view.skipped_steps.push(step);
                }
                self.item_command(Command::SkipItem, view, cx);
            }
            _ => {
                if let Phase::Testing(_, run) = &mut self.phase {
                    let shared = &mut self.shared;
                    let next = run.command(cmd, &mut Call { view, cx, shared });
                    self.go_on(next, view, cx);
                }
            }
        }
    }

    /// Time passed or packets arrived.
    pub fn tick(
        &mut self,
        view: &mut CheckView,
        model: &Model,
        ctl: &mut Controller,
        now: Instant,
    ) -> CheckEffects {
        effects(model, ctl, now, |cx| {
            if matches!(self.phase, Phase::Confirm) {
                self.replan(view, model, now);
                if self.opts.yes && plan::ready(model, now).is_ok() {
                    self.start(view, cx);
                }
                return;
            }
            if let Some((cause, reason)) = self.trouble(view, model, now) {
                self.interrupt_with(cause, reason, true, view, cx);
                return;
            }
            match &mut self.phase {
                Phase::Testing(_, run) => {
                    let shared = &mut self.shared;
                    let next = run.tick(&mut Call { view, cx, shared });
                    self.go_on(next, view, cx);
                }
                Phase::Stopping { .. } => self.stopping_tick(view, cx),
                Phase::Confirm | Phase::Done | Phase::Loads => {}
            }
            if let Some(cause) = self.shared.trouble_ahead.take() {
                // The step already stopped its motor (the controller's own reason
                // stands); a circuit that will not go back off has no motor running.
                self.interrupt_with(cause, StopReason::Quit, true, view, cx);
            }
        })
    }

    /// Something that ends the check, seen in the model: lost communication, a link
    /// that failed or cannot send, a new fault elsewhere than the item under test;
    /// with the reason a motor under test stops for.
    fn trouble(
        &self,
        view: &CheckView,
        model: &Model,
        now: Instant,
    ) -> Option<(String, StopReason)> {
        if matches!(self.phase, Phase::Stopping { .. } | Phase::Done) {
            return None;
        }
        if let Connection::Lost { reason, .. } = &model.connection {
            return Some((format!("the link failed: {reason}"), StopReason::LinkError));
        }
        if model.link.write_errors > self.write_errors_at_start {
            let why = model.link.last_write_error.clone().unwrap_or_default();
            return Some((
                format!("the link could not send: {why}"),
                StopReason::LinkError,
            ));
        }
        if model.comm_lost(now) {
            return Some(("COMMUNICATION LOST".into(), StopReason::CommLost));
        }
        let (codes, system) = model.live_faults(now)?;
        if system && !self.system_fault_at_start {
            return Some((
                "a system fault (FAULT_STATUS)".into(),
                StopReason::UnitFault,
            ));
        }
        let under_test = self.under_test();
        (0..DEVICE_COUNT as u8)
            .filter(|&i| codes[i as usize].is_fault())
            .find(|i| !self.shared.known_faults.contains(i) && !under_test.contains(i))
            .map(|i| {
                let name = view_or_model_name(view, model, i);
                (
                    format!("{name} faulted ({})", codes[i as usize].name()),
                    StopReason::UnitFault,
                )
            })
    }

    /// The devices whose fault is a finding rather than an interruption: the circuit
    /// or motor under test, or the circuits the switch under test powers.
    fn under_test(&self) -> Vec<u8> {
        match &self.phase {
            Phase::Testing(_, run) => run.under_test(),
            _ => Vec::new(),
        }
    }

    /// Ends the check from outside: quit, a signal, a panic. `may_wait`: the caller
    /// keeps ticking, so a circuit switched off now can be seen off before the list
    /// of what is left is final; otherwise it is listed as sent but not confirmed.
    #[allow(clippy::too_many_arguments)]
    pub fn interrupt_for(
        &mut self,
        cause: Cause,
        may_wait: bool,
        view: &mut CheckView,
        model: &Model,
        ctl: &mut Controller,
        now: Instant,
    ) -> CheckEffects {
        effects(model, ctl, now, |cx| {
            if !matches!(self.phase, Phase::Done) {
                self.interrupt(cause, may_wait, view, cx);
            }
        })
    }

    fn interrupt(
        &mut self,
        cause: Cause,
        may_wait: bool,
        view: &mut CheckView,
        cx: &mut CallContext,
    ) {
        let reason = cause.stop_reason();
        if matches!(self.phase, Phase::Confirm) {
            // Nothing was touched yet.
            cx.stop_run(reason);
            view.interrupted = Some(Interruption {
                cause: cause.words(),
                left: Vec::new(),
            });
            self.finish(view, cx);
            return;
        }
        if let Phase::Stopping { until, .. } = &mut self.phase {
            // A second stop (quit while waiting to see a circuit off): stop waiting.
            *until = cx.now;
            self.stopping_tick(view, cx);
            return;
        }
        cx.stop_run(reason);
        self.interrupt_with(cause.words(), reason, may_wait, view, cx);
    }

    /// Stops the item under test, puts back what it can, marks the rest not run, and
    /// fills [`Interruption::left`].
    fn interrupt_with(
        &mut self,
        cause: String,
        reason: StopReason,
        may_wait: bool,
        view: &mut CheckView,
        cx: &mut CallContext,
    ) {
        let (model, now) = (cx.model, cx.now);
        let link_failed = model.link.write_errors > self.write_errors_at_start
            || !matches!(model.connection, Connection::Connected { .. });
        let comm = !model.comm_lost(now) && !link_failed;
        let mut left: Vec<LeftBehind> = Vec::new();
        let mut powered = None;
        if let Phase::Testing(_, mut run) = std::mem::replace(&mut self.phase, Phase::Done) {
            let stopped = run.stop(reason, view, cx);
            powered = stopped.powered;
            left.extend(stopped.left);
        }
        cx.out.progress.push(format!("Interrupted: {cause}"));
        match powered {
            Some(p) if may_wait && comm => {
                self.phase = Phase::Stopping {
                    powered: p,
                    until: now + self.shared.timing.stop_wait,
                    cause,
                    left,
                };
                view.prompt = Some(Prompt {
                    todo: format!(
                        "Stopping: switching {} back off.",
                        view_or_model_name(view, model, p.id)
                    ),
                    watching: "DEVICE_STATUS, to see it off".into(),
                    time_left: Some(self.shared.timing.stop_wait),
                    keys: vec![],
                });
            }
            Some(p) => {
                let name = view_or_model_name(view, model, p.id);
                let why = if comm {
                    "ON when the check stopped: DEVICE_POWER off sent, not confirmed".to_string()
                } else {
                    format!(
                        "unknown: it was ON; DEVICE_POWER off sent, not confirmed ({})",
                        if link_failed {
                            "the link could not send"
                        } else {
                            "COMMUNICATION LOST"
                        }
                    )
                };
                left.insert(0, LeftBehind::new(p.id, name, why));
                self.end_interrupted(cause, left, view, cx);
            }
            None => self.end_interrupted(cause, left, view, cx),
        }
    }

    fn stopping_tick(&mut self, view: &mut CheckView, cx: &mut CallContext) {
        let Phase::Stopping { powered, until, .. } = &self.phase else {
            return;
        };
        let (powered, until) = (*powered, *until);
        let state = circuit_on(cx.model, cx.now, powered.id);
        let off = state == Some(false);
        if !off && cx.now < until {
            if let Some(p) = view.prompt.as_mut() {
                p.time_left = Some(until.saturating_duration_since(cx.now));
            }
            return;
        }
        let Phase::Stopping {
            cause, mut left, ..
        } = std::mem::replace(&mut self.phase, Phase::Done)
        else {
            return;
        };
        let name = view_or_model_name(view, cx.model, powered.id);
        if off {
            put_back(powered.id, view, cx.model, cx.now);
        } else {
            let why = match state {
                Some(true) => "ON: DEVICE_POWER off sent, the unit still shows it on",
                _ => "unknown: it was ON; DEVICE_POWER off sent, no status since",
            };
            left.insert(0, LeftBehind::new(powered.id, name, why.to_string()));
        }
        self.end_interrupted(cause, left, view, cx);
    }

    fn end_interrupted(
        &mut self,
        cause: String,
        left: Vec<LeftBehind>,
        view: &mut CheckView,
        cx: &mut CallContext,
    ) {
        for LeftBehind {
            id,
            name,
            state: why,
        } in &left
        {
            cx.out
                .progress
                .push(format!("  left: {name} (device {id}): {why}"));
        }
        view.interrupted = Some(Interruption { cause, left });
        self.finish(view, cx);
    }
}

/// One call from the caller (a tick, a command, …): what the flow does in `call`, with
/// the effects it gathers.
fn effects(
    model: &Model,
    ctl: &mut Controller,
    now: Instant,
    call: impl FnOnce(&mut CallContext),
) -> CheckEffects {
    let mut out = CheckEffects::default();
    call(&mut CallContext {
        model,
        ctl,
        now,
        out: &mut out,
    });
    out
}

/// The line a headless run prints when `step` is skipped.
fn skipped_line(step: Step) -> String {
    format!("– {}: skipped", step.title())
}

/// The step after `step`.
fn next_step(step: Step) -> Step {
    match step {
        Step::Confirm => Step::Switches,
        Step::Switches => Step::Circuits,
        Step::Circuits => Step::Motors,
        Step::Motors => Step::Loads,
        Step::Loads | Step::Done => Step::Done,
    }
}

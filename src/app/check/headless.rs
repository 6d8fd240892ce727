//! `vpx-efis check`: the page's check with no screen. The same [`App`] and flow as
//! the page, fed from standard input ("y", "s", "r", …) instead of keys, each result
//! printed as it comes, the plan before and the summary after.

use std::io::BufRead;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, unbounded};

use super::super::serve::{Outside, Wait};
use super::super::{App, AppOptions, builtin_sim, signals};
use crate::check::state::{CheckView, Mark, Step};
use crate::check::words;
use crate::check::{Cause, Command, Options, plan};
use crate::link::{self, PortAddr};
use crate::model::Source;

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
        "y" | "yes" | "lit" => Command::Lit(true),
        "n" | "no" | "dark" => Command::Lit(false),
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
        logbook: crate::logbook::target(),
        ..AppOptions::default()
    };
    let mut app = App::new(source, connector, options);
    // The page's panic path: the hook's stop goes through the app's stop gate, after
    // any send in progress and before any later move, and into the audit log.
    super::super::terminal::install_panic_hook();
    app.arm_emergency_stop();
    let result = headless_loop(&mut app, h, lines, terminations, out);
    app.shutdown();
    super::super::terminal::clear_emergency_stop();
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

/// What the headless check does with a prompt that waits for r or s (a motor test
/// paused) once standard input has ended.
const PAUSE_NEEDS_A_PERSON: &str = "The check was waiting for r (retry) or s (skip), which \
     nobody can type now: skipped.";

/// Whether the check waits, with no time limit, for the person to retry or skip (a
/// motor test paused).
fn waits_for_retry_or_skip(app: &App) -> bool {
    let view = app.check_view();
    let answers = view.prompt_answers();
    view.prompt.as_ref().is_some_and(|p| p.time_left.is_none())
        && answers.iter().any(|a| a.id == "skip")
        && answers.iter().any(|a| a.id == "retry" || a.id == "go_on")
}

/// Once standard input has ended, a prompt that waits for r or s is said and skipped,
/// as the switch step is.
fn skip_if_nobody(app: &mut App, ended: bool, out: &mut dyn std::io::Write) {
    if ended && !app.check_finished() && waits_for_retry_or_skip(app) {
        let _ = writeln!(out, "{NOBODY_TO_ANSWER} {PAUSE_NEEDS_A_PERSON}");
        app.check_command(Command::SkipItem, Instant::now());
        print_progress(app, out);
    }
}

/// Why the switch step is skipped when standard input has ended.
const SWITCHES_NEED_A_PERSON: &str = "The switch step, which needs a person to flip each \
     switch and say when it is done, is skipped.";

/// The headless check's front on the app's loop ([`App::serve`]): typed lines and
/// signals until `until` or `done`.
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
    let wait = Wait {
        input: if input.ended { &never } else { input.lines },
        terminations,
        until: Some(until),
        poll: None,
    };
    let pumped = app.serve(
        wait,
        |app, now| {
            app.no_screen(now);
            after_tick(app);
            done(app).then_some(Pumped::Done)
        },
        |app, outside| match outside {
            Outside::Input(l) => {
                on_line(app, l);
                None
            }
            Outside::InputEnded => Some(Pumped::InputEnded),
            Outside::Signal(t) => Some(Pumped::Signal(t)),
        },
    );
    match pumped {
        Some(Pumped::InputEnded) => {
            input.ended = true;
            Pumped::InputEnded
        }
        Some(p) => p,
        None => Pumped::Done,
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
    if input.ended {
        // No light is held on for an answer nobody can give.
        app.check_command(Command::NobodyToAnswer, Instant::now());
    }
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
        let ended = input.ended;
        let progress = |app: &mut App| {
            print_progress(app, out);
            skip_if_nobody(app, ended, out);
        };
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
                app.check_command(Command::NobodyToAnswer, Instant::now());
                skip_if_nobody(app, true, out);
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

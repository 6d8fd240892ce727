//! The process runner: `vpx-efis` with no subcommand, from its options to a page on
//! the terminal and back (the checks, the unit or the built-in one, the terminal, the
//! input thread, the clean stop).

use std::time::Duration;

use crossbeam_channel::{Receiver, unbounded};
use crossterm::event::Event as TermEvent;

use super::options::{max_run, repeat_delay};
use super::{
    App, AppOptions, PageOptions, Recorder, TerminalGuard, background, replay, signals, terminal,
    xfsp_setup,
};
use crate::link::{self, Connector};
use crate::model::Source;
use crate::sim::{self, SimHandle, SimOptions};

/// Starts the built-in virtual VP-X on one end of an in-process pipe.
pub fn builtin_sim(scenario: &str) -> anyhow::Result<(Source, Connector, SimHandle)> {
    let scenario_data = sim::load_scenario(scenario)?;
    let (ours, theirs) = link::duplex_pipe(Duration::from_millis(50));
    let sim = sim::spawn(
        SimOptions::new(scenario_data),
        Box::new(theirs.reader),
        Box::new(theirs.writer),
    );
    let connector = link::pipe_connector(ours, "built-in virtual VP-X");
    Ok((
        Source::Simulated {
            scenario: scenario.to_string(),
        },
        connector,
        sim,
    ))
}
/// `vpx-efis` with no subcommand: the page.
pub fn run(args: PageOptions) -> anyhow::Result<()> {
    let max_run = max_run(args.max_run)?;
    let repeat_delay = args.repeat_delay.map(repeat_delay).transpose()?;
    // Refused (a list of sources without --xfsp-control) before anything is opened.
    let xfsp = xfsp_setup(&args.xfsp)?;
    if args.replay.is_some() && args.remote.is_some() {
        anyhow::bail!("--remote: a replay is read-only, so it serves no remote");
    }
    if let Some(file) = &args.replay {
        return replay::run(file, &args);
    }
    let mut sim = None;
    let (source, connector) = match &args.port {
        Some(addr) => {
            // Fail before taking over the terminal, with the likely fix in words.
            link::check_port(addr, args.baud)?;
            let connector = link::port_connector(addr, args.baud);
            (
                Source::Serial {
                    path: addr.to_string(),
                },
                connector,
            )
        }
        None => {
            let (source, connector, handle) = builtin_sim(&args.scenario)?;
            sim = Some(handle);
            (source, connector)
        }
    };
    // A path that cannot be written fails here, before the terminal is taken.
    let recorder = args.record.as_deref().map(Recorder::create).transpose()?;
    // Asked before the alternate screen, while the terminal still shows its own colours.
    let theme = background::choose_theme(args.theme);
    // Before the terminal is taken: from here a kill or a closed window takes the
    // same way out as `q`.
    let terminations = signals::listen()?;
    let mut guard = TerminalGuard::enter()?;
    let options = AppOptions {
        max_run,
        theme,
        release_mode: crate::control::release_mode_here(guard.key_release),
        repeat_delay,
        logbook: crate::logbook::target(),
    };
    let mut app = match recorder {
        Some(r) => App::recording(source, connector, options, r),
        None => App::new(source, connector, options),
    };
    if let Some((target, iface, config)) = xfsp {
        app.enable_xfsp(&target, iface, config)?;
    }
    if let Some(addr) = args.remote {
        app.start_remote(addr, std::time::Instant::now())?;
    }
    app.reload_wires();
    app.reload_last_check();
    app.arm_emergency_stop();
    let input = spawn_input_thread();
    let result = app.run(&mut guard.terminal, &input, &terminations);
    app.shutdown();
    terminal::clear_emergency_stop();
    drop(guard);
    if let Some(sim) = sim {
        sim.stop();
    }
    result
}

pub(super) fn spawn_input_thread() -> Receiver<TermEvent> {
    let (tx, rx) = unbounded();
    let _ = std::thread::Builder::new()
        .name("input".into())
        .spawn(move || {
            while let Ok(ev) = crossterm::event::read() {
                if tx.send(ev).is_err() {
                    return;
                }
            }
        });
    rx
}

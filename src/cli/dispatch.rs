//! Dispatch: parse, resolve the config file, run the subcommand, and turn its error
//! into words and an exit code.

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

use crate::cli::resolve::resolve;
use crate::cli::{Cli, Command};
use crate::program::{UsageError, exit};

/// Entry point of the binary: parse, dispatch, and turn errors into words and an exit code.
pub fn main() -> ExitCode {
    let matches = Cli::command().get_matches();
    let mut cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result = resolve(&mut cli.command, &mut cli.page, &mut cli.logbook, &matches)
        .inspect(|_| {
            // Every command that records finds its logbook and aircraft here.
            crate::logbook::set_target(cli.logbook.target());
        })
        .and_then(|report| match cli.command {
            None => crate::cmd::page::run(cli.page),
            Some(Command::Decode(a)) => crate::cmd::decode::run(a),
            Some(Command::Sim(a)) => crate::cmd::sim::run(a),
            Some(Command::Ports) => crate::cmd::ports::run(),
            Some(Command::Backup(a)) => crate::cmd::backup::run(a),
            Some(Command::Restore(a)) => crate::cmd::restore::run(a),
            Some(Command::Flash(a)) => crate::cmd::flash::run(a),
            Some(Command::Gateway(a)) => crate::cmd::gateway::run(a),
            Some(Command::XfspDump(a)) => crate::cmd::xfsp_dump::run(a),
            Some(Command::Config(_)) => crate::cmd::config::run(&report),
            Some(Command::Completions(a)) => crate::cmd::completions::run(a.shell, Cli::command()),
            Some(Command::Man) => crate::cmd::completions::man(Cli::command()),
            Some(Command::Check(a)) => crate::cmd::check::run(a),
            Some(Command::Wires(a)) => crate::cmd::wires::run(a),
            Some(Command::Log(a)) => crate::cmd::log::run(a),
            Some(Command::Reference { dir }) => crate::cli::reference::run(&dir),
        });
    match result {
        Ok(()) => ExitCode::from(exit::OK),
        Err(e) => {
            eprintln!("vpx-efis: {e:#}");
            if let Some(end) = e.downcast_ref::<crate::cmd::check::Ended>() {
                ExitCode::from(end.0.code())
            } else if e.downcast_ref::<UsageError>().is_some() {
                ExitCode::from(exit::USAGE)
            } else if let Some(t) = e.downcast_ref::<crate::app::Terminated>() {
                // Stopped by a signal after a clean stop: 128 + n, as a shell expects.
                ExitCode::from(t.0.exit_status())
            } else {
                ExitCode::from(exit::FAILURE)
            }
        }
    }
}

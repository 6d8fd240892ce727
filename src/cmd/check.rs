//! `vpx-efis check [--port PATH] [--yes] [--skip STEP,…] [--exclude NAME]… [--report DIR]`:
//! the installation check with no screen ([`crate::app::run_headless`]). Exit status
//! 0 when everything passed, 1 when anything failed, 2 when it was interrupted (or
//! the command line was refused).

use std::path::PathBuf;

use clap::Args;

use crate::app::{CheckEnd, HeadlessCheck, run_headless};
use crate::check::state::Step;
use crate::check::{Choices, Options};
use crate::cmd::common::PortArgs;
use crate::program::UsageError;

/// How the check ended, carried to `main` for the exit status; its text is the
/// one-line verdict printed last.
#[derive(Debug, thiserror::Error)]
#[error("{}", match .0 {
    CheckEnd::Passed => "the check passed",
    CheckEnd::Failed => "the check found things to fix (listed above)",
    CheckEnd::Interrupted => "the check was interrupted (what it left is listed above)",
})]
pub struct Ended(pub CheckEnd);

/// `--skip` words as steps, or a clear error naming the words that are not steps.
pub fn steps(words: &[String]) -> Result<Vec<Step>, UsageError> {
    let mut out = Vec::new();
    for w in words.iter().map(|w| w.trim()).filter(|w| !w.is_empty()) {
        let Some((step, _)) = Step::SKIPPABLE
            .iter()
            .find(|(_, word)| word.eq_ignore_ascii_case(w))
        else {
            let all: Vec<&str> = Step::SKIPPABLE.iter().map(|(_, w)| *w).collect();
            return Err(UsageError(format!(
                "--skip {w}: not a step; the steps are {}",
                all.join(", ")
            )));
        };
        out.push(*step);
    }
    Ok(out)
}

/// The headless check's settings from its arguments.
pub fn headless(args: CheckArgs) -> Result<HeadlessCheck, UsageError> {
    let skip = steps(&args.skip)?;
    if let Some(bad) = args.exclude.iter().find(|e| e.trim().is_empty()) {
        return Err(UsageError(format!(
            "--exclude {bad:?}: give a circuit's name or pin"
        )));
    }
    if let Some(dir) = &args.report
        && dir.exists()
        && !dir.is_dir()
    {
        return Err(UsageError(format!(
            "--report {}: that is a file; give a folder",
            dir.display()
        )));
    }
    Ok(HeadlessCheck {
        port: if args.port.sim { None } else { args.port.port },
        baud: args.port.baud,
        scenario: args.port.scenario,
        options: Options {
            skip,
            choices: Choices {
                exclude: args.exclude,
                include: Vec::new(),
                excluded_here: Vec::new(),
            },
            yes: args.yes,
            loads_file: args.loads.or_else(crate::places::loads_path),
            ..Options::default()
        },
        report: args.report,
    })
}

#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub port: PortArgs,
    /// Answer the safety confirmation: the aircraft is safe to power the circuits the
    /// check lists and to move its flaps and trims.
    #[arg(long)]
    pub yes: bool,
    /// Steps not to run: switches, circuits, motors, loads (comma-separated or repeated).
    #[arg(long, value_delimiter = ',', value_name = "STEP,...")]
    pub skip: Vec<String>,
    /// A circuit never to power, by its name or its pin (5A-3); repeat for more.
    #[arg(long, value_name = "NAME")]
    pub exclude: Vec<String>,
    /// Where to write the report (Markdown and CSV, named with the date).
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// The load analysis file (default: loads.toml beside the config file; its
    /// template is written there on the first run).
    #[arg(long, value_name = "FILE")]
    pub loads: Option<PathBuf>,
}

pub fn run(args: CheckArgs) -> anyhow::Result<()> {
    let h = headless(args)?;
    // A report folder that cannot be made is said now, before the port is opened,
    // not at the end of the check when the report would be lost.
    if let Some(dir) = &h.report {
        crate::app::prepare_report_dir(dir).map_err(|e| UsageError(format!("--report: {e}")))?;
    }
    match run_headless(h)? {
        CheckEnd::Passed => Ok(()),
        end => Err(Ended(end).into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skip_takes_the_four_steps_and_names_a_wrong_one() {
        let w = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(
            steps(&w(&["switches", "Loads"])).unwrap(),
            vec![Step::Switches, Step::Loads]
        );
        assert_eq!(
            steps(&w(&["circuits", "motors"])).unwrap(),
            vec![Step::Circuits, Step::Motors]
        );
        let e = steps(&w(&["switch"])).unwrap_err().0;
        assert_eq!(
            e,
            "--skip switch: not a step; the steps are switches, circuits, motors, loads"
        );
    }

    #[test]
    fn exit_codes_are_0_passed_1_failed_2_interrupted() {
        assert_eq!(CheckEnd::Passed.code(), 0);
        assert_eq!(CheckEnd::Failed.code(), 1);
        assert_eq!(CheckEnd::Interrupted.code(), 2);
    }
}

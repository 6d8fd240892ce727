//! `vpx-efis restore --port PATH|tcp://HOST:PORT FILE [--yes] [--erase-first]`: writes a
//! backup back to the unit.
//!
//! 0. A restore writes, so it never goes to a simulator by accident: without a port (a
//!    flag, `VPX_EFIS_PORT` or the config file) it refuses unless `--sim` says so.
//! 1. The file is checked as a whole before the unit is even opened; an invalid file is
//!    refused with every problem by its path, and nothing is sent. Where the backup came
//!    from (its `[made]` section) is shown before anything is asked.
//! 2. VERSION: a file from other hardware is refused (only VERSION has been sent).
//! 3. The unit's settings are read and the differences listed; the person confirms
//!    (or `--yes`). With no terminal to ask on and no `--yes`, nothing is written.
//!    A breaker of the backup above what its circuit's wire allows (the load file's
//!    `wire`, AC 43.13-1B Table 11-3) is listed and asked on the terminal even with
//!    `--yes`: it disarms the wire's protection, as setup asks it.
//! 4. With `--erase-first`, EEPROM_ERASE (ICD §6.1.4) must answer result code 0, and
//!    the now-factory settings are read again.
//! 5. Each differing setting is written in the order [`crate::backup::plan`] explains,
//!    each waiting for its SPEC_ACK. The first failure stops the restore and the
//!    report says which settings were applied and which were not.
//! 6. Everything is read back and compared with the file.

use std::io::{BufRead, IsTerminal, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use clap::Args;

use crate::backup::{self, RestoreWrite, normalized};
use crate::cmd::backup::{connect, progress_bar, read_with_progress};
use crate::cmd::common::PortArgs;
use crate::exchange::{ANSWER_TIMEOUT, TRIES};
use crate::link::{SpecError, UnitClient};
use crate::loads::wiring;
use crate::program::UsageError;
use crate::protocol::config::UnitConfig;
use crate::protocol::message::Message;
use crate::protocol::validate;

#[derive(Debug, Args)]
pub struct RestoreArgs {
    /// Restore needs a port (a flag, VPX_EFIS_PORT or the config file), or `--sim` to
    /// try it on the built-in virtual VP-X: never a simulator by accident.
    #[command(flatten)]
    pub port: PortArgs,
    /// The TOML backup to restore.
    pub file: PathBuf,
    /// Don't ask for confirmation (a breaker over its wire is still asked).
    #[arg(long)]
    pub yes: bool,
    /// Erase the EEPROM first (ICD §6.1.4), then import.
    #[arg(long)]
    pub erase_first: bool,
    /// The load file whose `wire` lines the backup's breakers are held against
    /// (default: loads.toml beside the config file, where there is one).
    #[arg(long, value_name = "FILE")]
    pub loads: Option<PathBuf>,
}

pub fn run(args: RestoreArgs) -> anyhow::Result<()> {
    if args.port.port.is_none() && !args.port.sim {
        return Err(UsageError(
            "restore writes to a unit, so say which: --port PATH or tcp://HOST:PORT (or \
             VPX_EFIS_PORT, or `port` in the config file; `vpx-efis ports` lists serial ports) \
             for a real VP-X, or --sim for the built-in virtual VP-X. Nothing was opened."
                .into(),
        )
        .into());
    }
    let (target, made) = backup::load_made(&args.file)
        .map_err(|e| anyhow::anyhow!("{e}\nNothing was sent to the unit."))?;
    // Read before the unit is opened: a bad load file is refused with nothing sent.
    let over_wires = over_wires(args.loads.as_deref(), &target.config)?;
    eprintln!(
        "{}",
        backup::provenance::describe(made.as_ref(), &target.version)
    );
    let mut unit = connect(&args.port)?;
    eprintln!(
        "Restoring to {}{}.",
        unit.from,
        if unit.simulated { " (SIMULATED)" } else { "" }
    );
    let client = &mut unit.client;

    let version = client.version().context("asking the unit's VERSION")?;
    if let Err(why) = backup::check_hardware(&target.version, &version) {
        bail!("{}: {why}", args.file.display());
    }
    if let Some(note) = backup::software_note(&target.version, &version) {
        eprintln!("{note}");
    }

    let current = read_all(client, "reading")?;
    let changes = backup::diff(&current, &target.config);
    if changes.is_empty() && !args.erase_first {
        println!(
            "The unit already holds every setting in {}; nothing to write.",
            args.file.display()
        );
        return Ok(());
    }
    if changes.is_empty() {
        println!(
            "The unit already holds every setting in {}.",
            args.file.display()
        );
    } else {
        println!(
            "{} setting(s) on the unit differ from {}:",
            changes.len(),
            args.file.display()
        );
        for c in &changes {
            println!("  {c}");
        }
    }
    if !over_wires.is_empty() {
        println!(
            "{} breaker(s) in {} would not protect their wire (AC 43.13-1B ¶11-48):",
            over_wires.len(),
            args.file.display()
        );
        for w in &over_wires {
            println!("  {w}");
        }
        // Asked even with --yes, as setup asks it: a breaker over its wire disarms the
        // wire's protection, and only a person at the terminal can mean that.
        confirm_wires(over_wires.len())?;
    }
    let question = if args.erase_first {
        "Erase the unit's EEPROM (every setting back to its factory default, ICD §6.1.4) and then write the backup?"
    } else {
        "Write these settings to the unit?"
    };
    if !args.yes {
        confirm(question)?;
    }

    let current = if args.erase_first {
        erase(client)?;
        read_all(client, "re-read")?
    } else {
        current
    };
    let steps = backup::plan(&current, &target.config)?;
    let planned = backup::diff(&current, &target.config);
    let log = |left: Option<&[backup::Change]>, failed: Option<String>| {
        log_restore(&args.file, &version, &target.config, &planned, left, failed);
    };
    if let Err(e) = write_steps(client, &current, &steps, args.erase_first) {
        log(None, Some(format!("{e:#}")));
        return Err(e);
    }

    let after = match read_all(client, "verify") {
        Ok(a) => a,
        Err(e) => {
            log(None, Some(format!("{e:#}")));
            return Err(e);
        }
    };
    let left = backup::diff(&after, &target.config);
    log(Some(&left), None);
    if !left.is_empty() || normalized(&after) != normalized(&target.config) {
        let mut msg = format!(
            "every setting was acknowledged, but reading them back, {} still differ from {}:",
            left.len(),
            args.file.display()
        );
        for c in &left {
            msg.push_str(&format!("\n  {c}"));
        }
        bail!(msg);
    }
    eprintln!(
        "Restored {} ({} setting(s) written) and verified by reading every setting back.",
        args.file.display(),
        steps.len()
    );
    Ok(())
}

/// The restore into the logbook: each setting it set out to change, from what to
/// what, confirmed when the read-back no longer differs (`left`: what still differs;
/// `None` when the unit was not read back). A logbook that cannot take it is said;
/// the restore stands.
fn log_restore(
    file: &Path,
    version: &crate::protocol::message::Version,
    config: &UnitConfig,
    planned: &[backup::Change],
    left: Option<&[backup::Change]>,
    failed: Option<String>,
) {
    use crate::logbook::record::{COMMAND_LINE, SettingChange, Unit};
    let changes: Vec<SettingChange> = planned
        .iter()
        .map(|c| SettingChange {
            setting: c.setting.clone(),
            old: Some(c.from.clone()),
            new: c.to.clone(),
            confirmed: left.is_some_and(|l| !l.iter().any(|x| x.path == c.path)),
        })
        .collect();
    let confirmed = changes.iter().filter(|c| c.confirmed).count();
    let summary = match &failed {
        Some(why) => format!(
            "restore of {}: failed ({why}); {} setting(s) meant to change",
            file.display(),
            changes.len()
        ),
        None => format!(
            "restore of {}: {} setting(s) changed, {confirmed} confirmed by reading back",
            file.display(),
            changes.len()
        ),
    };
    let entry = crate::logbook::Entry {
        at: std::time::SystemTime::now(),
        origin: COMMAND_LINE,
        summary,
        what: crate::logbook::What::Restore { changes },
    };
    if let Some(why) = crate::logbook::record_now(entry, Some(Unit::of_config(version, config))) {
        eprintln!("vpx-efis: {why}");
    }
}

fn read_all(client: &mut UnitClient, what: &str) -> anyhow::Result<UnitConfig> {
    Ok(read_with_progress(client, what)
        .context("reading the unit's settings")?
        .1)
}

/// Asks on the terminal; anything but yes stops here with nothing written.
fn confirm(question: &str) -> anyhow::Result<()> {
    if !std::io::stdin().is_terminal() {
        bail!(
            "standard input is not a terminal, so nobody can confirm; nothing was written. \
             Run again with --yes to write without asking."
        );
    }
    eprint!("{question} [y/N] ");
    let _ = std::io::stderr().flush();
    let mut line = String::new();
    std::io::stdin().lock().read_line(&mut line)?;
    if matches!(line.trim().to_ascii_lowercase().as_str(), "y" | "yes") {
        Ok(())
    } else {
        bail!("not confirmed; nothing was written")
    }
}

/// Each breaker of `config` above what the load file's wire for its circuit allows,
/// in words ("Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 6 A
/// breaker would not protect it"). `--loads` must be readable; the default file may
/// be absent (then nothing is held against a wire).
fn over_wires(loads: Option<&Path>, config: &UnitConfig) -> anyhow::Result<Vec<String>> {
    let path = match loads {
        Some(p) => p.to_path_buf(),
        None => match crate::places::loads_path().filter(|p| p.exists()) {
            Some(p) => p,
            None => return Ok(Vec::new()),
        },
    };
    let file = crate::loads::disk::read_circuits(&path).map_err(|e| UsageError(e.to_string()))?;
    let unit: Vec<(u8, String, u8)> = wiring::configured(config);
    let circuits: Vec<wiring::Circuit<'_>> = unit
        .iter()
        .map(|(id, name, breaker)| wiring::Circuit {
            id: *id,
            name: Some(name),
            breaker_amps: Some(*breaker),
            amps: None,
        })
        .collect();
    Ok(wiring::assess(&file, &circuits, None)
        .iter()
        .filter_map(wiring::Row::unprotected_words)
        .collect())
}

/// The wire question: `y` on the terminal, whatever `--yes` says; without a terminal
/// nothing is written.
fn confirm_wires(n: usize) -> anyhow::Result<()> {
    if !std::io::stdin().is_terminal() {
        bail!(
            "{n} breaker(s) would not protect their wire, and standard input is not a \
             terminal to ask on (--yes does not answer this); nothing was written. Lower \
             those breakers in the backup, or correct the wires in the load file."
        );
    }
    eprint!("y: set them anyway; anything else: nothing is written. [y/N] ");
    let _ = std::io::stderr().flush();
    let mut line = String::new();
    std::io::stdin().lock().read_line(&mut line)?;
    if line.trim().eq_ignore_ascii_case("y") {
        Ok(())
    } else {
        bail!("not confirmed; nothing was written")
    }
}

/// EEPROM_ERASE, ICD §6.1.4: only a result code of 0 lets the import go on.
fn erase(client: &mut UnitClient) -> anyhow::Result<()> {
    let code = client
        .erase_eeprom()
        .context("erasing the EEPROM; nothing was erased or written as far as we know")?;
    if code != 0 {
        bail!(
            "the unit answered EEPROM_ERASE with result code {code} (not 0: the erase did \
             not complete, ICD Table 12); nothing was written"
        );
    }
    eprintln!(
        "EEPROM erased. The unit reports a data-integrity flag until it is power-cycled \
         (ICD §6.1.4); that is expected."
    );
    Ok(())
}

/// Writes `steps` in order; on the first failure, says what was and was not applied.
fn write_steps(
    client: &mut UnitClient,
    current: &UnitConfig,
    steps: &[RestoreWrite],
    erased: bool,
) -> anyhow::Result<()> {
    let bar = progress_bar(steps.len() as u64, "writing");
    // What the unit holds after each acknowledged step, to explain a refusal in terms
    // of the state the unit judged it against.
    let mut held = current.clone();
    for (i, step) in steps.iter().enumerate() {
        bar.set_position(i as u64);
        let result: Result<(), String> = match *step {
            RestoreWrite::Spec { message, .. } => client
                .send_spec(message, ANSWER_TIMEOUT, TRIES)
                .map_err(|e| match e {
                    SpecError::Refused { error, .. } => {
                        format!("{e}. {}", validate::explain(error, &held, &message))
                    }
                    e => e.to_string(),
                }),
            RestoreWrite::Enable { device_id, shown } => {
                match client.set_enable(device_id, shown) {
                    Ok(true) => Ok(()),
                    Ok(false) => Err(format!(
                        "the unit did not store {step}: read back, it still holds the other value"
                    )),
                    Err(e) => Err(e.to_string()),
                }
            }
        };
        if let Err(why) = result {
            bar.finish_and_clear();
            bail!(failure_report(steps, i, &why, erased));
        }
        match step.message() {
            Message::DeviceEnable(e) => held.apply_device_enable(&e),
            m => {
                validate::accept(&mut held, &m);
            }
        }
    }
    bar.finish_and_clear();
    Ok(())
}

/// "Stopped at …; applied: …; not applied: …", with a warning when a setting was only
/// cleared for a moment and its real value never written.
pub fn failure_report(steps: &[RestoreWrite], failed: usize, why: &str, erased: bool) -> String {
    let (applied, not_applied) = steps.split_at(failed);
    let mut out = format!("restore stopped at {}: {why}", steps[failed]);
    out.push_str(&format!(
        "\nApplied ({} of {}):",
        applied.len(),
        steps.len()
    ));
    if applied.is_empty() {
        out.push_str("\n  (none)");
    }
    for s in applied {
        out.push_str(&format!("\n  {s}"));
    }
    out.push_str(&format!("\nNot applied ({}):", not_applied.len()));
    for s in not_applied {
        out.push_str(&format!("\n  {s}"));
    }
    for s in applied {
        if let RestoreWrite::Spec {
            message,
            untie: true,
        } = s
        {
            let what = match message {
                Message::WigWagSpec(_) => "the unit now has no wig-wag devices",
                _ => "the unit now has no secondary alternator",
            };
            out.push_str(&format!(
                "\nWarning: {s} was applied but the final value was not: {what}."
            ));
        }
    }
    if erased {
        out.push_str(
            "\nThe EEPROM was erased first: every setting not applied is at its factory default.",
        );
    }
    out
}

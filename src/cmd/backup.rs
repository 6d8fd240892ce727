//! `vpx-efis backup [--port PATH|tcp://HOST:PORT] FILE`: reads the unit's whole
//! configuration into a TOML file (format in [`crate::backup`]), written
//! atomically so that an interrupted backup leaves no half file. The file records when
//! it was made, from what, and by which vpx-efis ([`crate::backup::provenance`]).

use std::io::IsTerminal;
use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::backup::{self, Backup, Provenance};
use crate::cmd::common::PortArgs;
use crate::link::{RequestError, UnitClient, port_connector};
use crate::protocol::config::UnitConfig;
use crate::protocol::message::Version;
use crate::sim::SimHandle;

#[derive(Debug, Args)]
pub struct BackupArgs {
    #[command(flatten)]
    pub port: PortArgs,
    /// The TOML file to write.
    pub file: PathBuf,
}

pub fn run(args: BackupArgs) -> anyhow::Result<()> {
    let mut unit = connect(&args.port)?;
    let (version, config) = read_with_progress(&mut unit.client, "reading")
        .context("reading the unit's configuration; no file was written")?;
    let b = Backup { version, config };
    let made = Provenance::at(&unit.from, unit.simulated, std::time::SystemTime::now());
    backup::save_made(&args.file, &b, &made)
        .with_context(|| format!("cannot write {}", args.file.display()))?;
    eprintln!(
        "Saved the configuration of {} (software {}.{}) from {} to {}.",
        version.hardware_version.name(),
        version.software_major,
        version.software_minor,
        unit.from,
        args.file.display()
    );
    // The logbook keeps the backup's text as written (the file may be moved or
    // edited later). A logbook that cannot take it is said; the backup stands.
    let text = std::fs::read_to_string(&args.file).unwrap_or_default();
    if let Some(why) = crate::logbook::record_now(
        crate::logbook::Entry {
            at: std::time::SystemTime::now(),
            origin: crate::logbook::record::COMMAND_LINE,
            summary: format!("backup to {}", args.file.display()),
            what: crate::logbook::What::Backup {
                path: Some(args.file.display().to_string()),
                text,
            },
        },
        Some(crate::logbook::record::Unit::of_config(&version, &b.config)),
    ) {
        eprintln!("vpx-efis: {why}");
    }
    Ok(())
}

/// A client on the unit `--port` names, or on the built-in virtual VP-X without it.
pub struct Connected {
    pub client: UnitClient,
    /// What the client talks to, in words: a port, a bridge, or the virtual VP-X.
    pub from: String,
    pub simulated: bool,
    /// Kept so the virtual unit runs as long as the client.
    _sim: Option<SimHandle>,
}

/// Opens `--port`, or starts the built-in virtual VP-X (its `--scenario`) on an
/// in-process pipe, saying on standard error which it is.
pub fn connect(port: &PortArgs) -> anyhow::Result<Connected> {
    match &port.port {
        Some(addr) => {
            let client = UnitClient::new(port_connector(addr, port.baud))?;
            Ok(Connected {
                client,
                from: addr.to_string(),
                simulated: false,
                _sim: None,
            })
        }
        None => {
            let (_, connector, handle) = crate::app::builtin_sim(&port.scenario)?;
            eprintln!(
                "{}: using the built-in virtual VP-X (scenario {}). SIMULATED.",
                if port.sim { "--sim" } else { "No --port given" },
                port.scenario
            );
            let client = UnitClient::new(connector)?;
            Ok(Connected {
                client,
                from: format!("the built-in virtual VP-X (scenario {})", port.scenario),
                simulated: true,
                _sim: Some(handle),
            })
        }
    }
}

/// [`UnitClient::query_config`] with a progress bar. The bar is made at the first
/// report, when the number of requests is known, so it never shows an empty "0/0".
pub fn read_with_progress(
    client: &mut UnitClient,
    what: &str,
) -> Result<(Version, UnitConfig), RequestError> {
    let mut bar: Option<ProgressBar> = None;
    let got = client.query_config(|done, total| {
        bar.get_or_insert_with(|| progress_bar(total as u64, what))
            .set_position(done as u64);
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    got
}

/// A progress bar on standard error, hidden when that is not a terminal (a script or
/// a test reading the output wants no control characters).
pub fn progress_bar(len: u64, what: &str) -> ProgressBar {
    let target = if std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(len), target);
    if let Ok(style) = ProgressStyle::with_template("{msg:>8} [{bar:40}] {pos}/{len}") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_string());
    bar
}

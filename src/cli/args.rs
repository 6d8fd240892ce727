//! The command line's shape: the page's options and one subcommand each, composed
//! from the `Args` every `cmd/` file owns, so that `--help` is one coherent document.

use clap::{Parser, Subcommand};

use crate::cmd::backup::BackupArgs;
use crate::cmd::check::CheckArgs;
use crate::cmd::common::LogbookArgs;
use crate::cmd::completions::CompletionsArgs;
use crate::cmd::config::ConfigArgs;
use crate::cmd::decode::DecodeArgs;
use crate::cmd::flash::FlashArgs;
use crate::cmd::gateway::GatewayArgs;
use crate::cmd::log::LogArgs;
use crate::cmd::page::PageArgs;
use crate::cmd::restore::RestoreArgs;
use crate::cmd::sim::SimArgs;
use crate::cmd::wires::WiresArgs;
use crate::cmd::xfsp_dump::XfspDumpArgs;
use crate::program::VERSION;

/// A terminal EFIS electrical page for the Vertical Power VP-X.
///
/// With no subcommand and no `--port`, the page runs against the built-in virtual
/// VP-X (the `demo` scenario), clearly labelled SIMULATED.
#[derive(Debug, Parser)]
#[command(name = "vpx-efis", version = VERSION, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,

    #[command(flatten)]
    pub page: PageArgs,

    #[command(flatten)]
    pub logbook: LogbookArgs,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Decode a raw VP-X byte capture (or a vpx-efis capture file) into readable lines.
    Decode(DecodeArgs),
    /// Run the virtual VP-X on a pseudo-terminal (--pty) or a TCP port (--tcp).
    Sim(SimArgs),
    /// List serial ports.
    Ports,
    /// Read the unit's whole configuration into a TOML file.
    Backup(BackupArgs),
    /// Write a TOML backup back to the unit.
    Restore(RestoreArgs),
    /// Update the VP-X firmware through its bootloader.
    Flash(FlashArgs),
    /// Bridge the VP-X onto XFSp with no terminal UI.
    Gateway(GatewayArgs),
    /// Print decoded XFSp traffic.
    XfspDump(XfspDumpArgs),
    /// Show the config file's path and every setting with where it came from.
    Config(ConfigArgs),
    /// Print a shell completion script (bash, zsh, fish, powershell) on standard output.
    Completions(CompletionsArgs),
    /// Print the manual page (roff) on standard output.
    Man,
    /// The installation check with no screen: every switch, circuit and motor, results
    /// as they come. Exits 0 when everything passed, 1 when anything failed, 2 when it
    /// was interrupted.
    Check(CheckArgs),
    /// Hold each circuit's breaker against its wire (AC 43.13-1B Table 11-3) and its
    /// current against its voltage drop (Table 11-6), from the load file's `wire`
    /// lines. Exits 1 when a breaker does not protect its wire or a measured drop is
    /// over the limit.
    Wires(WiresArgs),
    /// The aircraft's logbook: its latest entries, a circuit's current at every check
    /// (--circuit), a printable page of its records (--export), the audit log's JSON
    /// lines (--jsonl).
    Log(LogArgs),
    /// Write the guide's reference pages (docs/src/reference) from the code that
    /// defines them; hidden, for developers (`cargo run -- reference`).
    #[command(hide = true)]
    Reference {
        /// The folder to write them in.
        #[arg(default_value = crate::cli::reference::DIR)]
        dir: std::path::PathBuf,
    },
}

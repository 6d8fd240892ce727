//! The command line. Every subcommand's arguments live here so that `--help` is one
//! coherent document; the work itself lives in `cmd/` and `app`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::ui::palette::Requested;

/// A terminal EFIS electrical page for the Vertical Power VP-X.
///
/// With no subcommand and no `--port`, the page runs against the built-in virtual
/// VP-X (the `demo` scenario), clearly labelled SIMULATED.
#[derive(Debug, Parser)]
#[command(name = "vpx-efis", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,

    #[command(flatten)]
    pub page: PageArgs,
}

#[derive(Debug, Clone, Args)]
pub struct PortArgs {
    /// Serial port of a real VP-X (or any serial path, e.g. one printed by `vpx-efis sim --pty`).
    /// Without it, the built-in virtual VP-X is used.
    #[arg(long, value_name = "PATH")]
    pub port: Option<PathBuf>,

    /// Baud rate. The VP-X talks 57600 8N1 (ICD §3.2.1).
    #[arg(long, default_value_t = 57_600)]
    pub baud: u32,

    /// Scenario for the built-in virtual VP-X: a name under assets/scenarios or a TOML file.
    #[arg(long, default_value = "demo", value_name = "NAME|FILE")]
    pub scenario: String,
}

#[derive(Debug, Clone, Args)]
pub struct XfspArgs {
    /// Bridge onto an XFSp network (multicast GROUP:PORT, default 224.0.2.69:20234).
    #[arg(long, value_name = "GROUP:PORT", num_args = 0..=1, default_missing_value = "224.0.2.69:20234")]
    pub xfsp: Option<String>,

    /// Local interface address to join the XFSp group on.
    #[arg(long, value_name = "ADDR", default_value = "0.0.0.0")]
    pub xfsp_iface: String,

    /// Our XFSp source id.
    #[arg(long, value_name = "ID", default_value_t = 0x5650)]
    pub xfsp_source_id: u16,

    /// Certification level published in our XFSp parameters.
    #[arg(long, value_name = "LEVEL", default_value_t = 0)]
    pub xfsp_cert: u8,
}

#[derive(Debug, Clone, Args)]
pub struct PageArgs {
    #[command(flatten)]
    pub port: PortArgs,

    #[command(flatten)]
    pub xfsp: XfspArgs,

    /// Record every byte in both directions to a capture file.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,

    /// Drive the page from a capture file instead of a unit (read-only).
    #[arg(long, value_name = "FILE", conflicts_with = "port")]
    pub replay: Option<PathBuf>,

    /// Replay speed factor.
    #[arg(long, default_value_t = 1.0)]
    pub speed: f64,

    /// Longest continuous trim/flap run, in seconds, before the key must be pressed again.
    #[arg(long, default_value_t = 10.0, value_name = "SECONDS")]
    pub max_run: f64,

    /// Colours: `dark` paints its own black background (the EFIS look), `light` is for
    /// light terminals, `mono` uses no colour; `auto` asks the terminal for its
    /// background (OSC 11) and picks dark or light, dark if it does not answer, and
    /// mono when NO_COLOR is set; `terminal` keeps the terminal's own 16 colours.
    #[arg(long, value_enum, default_value_t = ThemeArg::Auto)]
    pub theme: ThemeArg,
}

/// `--theme`; see [`crate::ui::palette`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ThemeArg {
    Auto,
    Dark,
    Light,
    Mono,
    Terminal,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Decode a raw VP-X byte capture (or a vpx-efis capture file) into readable lines.
    Decode(DecodeArgs),
    /// Run the virtual VP-X on a pseudo-terminal.
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
    #[command(after_help = crate::cmd::xfsp_dump::SCALES_HELP)]
    XfspDump(XfspDumpArgs),
}

#[derive(Debug, Args)]
pub struct DecodeArgs {
    /// Capture file, or `-` (the default) for standard input.
    #[arg(default_value = "-")]
    pub file: String,
    /// One JSON object per line.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Args)]
pub struct SimArgs {
    /// Create a pseudo-terminal and print its path as the first line on stdout.
    #[arg(long)]
    pub pty: bool,
    /// Persist settings to this file (written atomically), like the unit's EEPROM.
    #[arg(long, value_name = "FILE")]
    pub eeprom: Option<PathBuf>,
    /// Scenario: a name under assets/scenarios or a TOML file.
    #[arg(long, default_value = "demo", value_name = "NAME|FILE")]
    pub scenario: String,
}

#[derive(Debug, Args)]
pub struct BackupArgs {
    #[command(flatten)]
    pub port: PortArgs,
    /// The TOML file to write.
    pub file: PathBuf,
}

#[derive(Debug, Args)]
pub struct RestoreArgs {
    #[command(flatten)]
    pub port: PortArgs,
    /// The TOML backup to restore.
    pub file: PathBuf,
    /// Don't ask for confirmation.
    #[arg(long)]
    pub yes: bool,
    /// Erase the EEPROM first (ICD §6.1.4), then import.
    #[arg(long)]
    pub erase_first: bool,
}

#[derive(Debug, Args)]
pub struct FlashArgs {
    #[command(flatten)]
    pub port: PortArgs,
    /// Intel HEX image, named like `cu_2.hex` for hardware version 2.
    pub file: PathBuf,
    /// Accept this hardware version even if the file name's suffix disagrees.
    #[arg(long, value_name = "N")]
    pub force_hardware: Option<u8>,
    /// Don't ask for confirmation.
    #[arg(long)]
    pub yes: bool,
    /// Where to write the exchange log (default: next to the hex file).
    #[arg(long, value_name = "FILE")]
    pub log: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct GatewayArgs {
    #[command(flatten)]
    pub port: PortArgs,
    #[command(flatten)]
    pub xfsp: XfspArgs,
    /// Record every serial byte to a capture file.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct XfspDumpArgs {
    /// Multicast GROUP:PORT to listen on.
    #[arg(long, default_value = "224.0.2.69:20234", value_name = "GROUP:PORT")]
    pub xfsp: String,
    /// Local interface address to join the group on.
    #[arg(long, default_value = "0.0.0.0", value_name = "ADDR")]
    pub xfsp_iface: String,
    /// JSON lines instead of text.
    #[arg(long)]
    pub json: bool,
}

impl From<XfspArgs> for crate::app::XfspOptions {
    fn from(a: XfspArgs) -> Self {
        crate::app::XfspOptions {
            xfsp: a.xfsp,
            xfsp_iface: a.xfsp_iface,
            xfsp_source_id: a.xfsp_source_id,
            xfsp_cert: a.xfsp_cert,
        }
    }
}

impl From<PageArgs> for crate::app::PageOptions {
    fn from(a: PageArgs) -> Self {
        crate::app::PageOptions {
            port: a.port.port,
            baud: a.port.baud,
            scenario: a.port.scenario,
            xfsp: a.xfsp.into(),
            record: a.record,
            replay: a.replay,
            speed: a.speed,
            max_run: a.max_run,
            theme: match a.theme {
                ThemeArg::Auto => Requested::Auto,
                ThemeArg::Dark => Requested::Dark,
                ThemeArg::Light => Requested::Light,
                ThemeArg::Mono => Requested::Mono,
                ThemeArg::Terminal => Requested::Terminal,
            },
        }
    }
}

/// Entry point of the binary: parse, dispatch, and turn errors into words and an exit code.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => crate::app::run(cli.page.into()),
        Some(Command::Decode(a)) => crate::cmd::decode::run(a),
        Some(Command::Sim(a)) => crate::cmd::sim::run(a),
        Some(Command::Ports) => crate::cmd::ports::run(),
        Some(Command::Backup(a)) => crate::cmd::backup::run(a),
        Some(Command::Restore(a)) => crate::cmd::restore::run(a),
        Some(Command::Flash(a)) => crate::cmd::flash::run(a),
        Some(Command::Gateway(a)) => crate::cmd::gateway::run(a),
        Some(Command::XfspDump(a)) => crate::cmd::xfsp_dump::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("vpx-efis: {e:#}");
            ExitCode::FAILURE
        }
    }
}

//! The command line. Every subcommand's arguments live here so that `--help` is one
//! coherent document; the work itself lives in `cmd/` and `app`.

use std::net::Ipv4Addr;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::parser::ValueSource;
use clap::{ArgMatches, Args, CommandFactory, FromArgMatches, Parser, Subcommand, ValueEnum};

use crate::link::PortAddr;
use crate::program::{UsageError, VERSION, exit};
use crate::settings::{
    self, BAUD_ENV, Origin, PORT_ENV, Setting, XFSP_CONTROL_ENV, XFSP_CONTROL_FROM_ENV, values,
};
use crate::ui::palette::Requested;

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
}

#[derive(Debug, Clone, Args)]
pub struct PortArgs {
    /// The VP-X: a serial port (/dev/ttyUSB0, COM3, /dev/cu.usbserial-…, or a path printed
    /// by `vpx-efis sim --pty`), or tcp://HOST:PORT for a serial-to-network bridge (ser2net,
    /// a WiFi serial bridge, `vpx-efis sim --tcp`). Also read from the config file. Without
    /// one, the built-in virtual VP-X is used.
    #[arg(long, value_name = "PATH|tcp://HOST:PORT", env = PORT_ENV, value_parser = values::port)]
    pub port: Option<PortAddr>,

    /// Use the built-in virtual VP-X, even when a port is set in the environment or the
    /// config file.
    #[arg(long)]
    pub sim: bool,

    /// Baud rate of a serial port (a TCP bridge's rate is set on the bridge). The VP-X
    /// talks 57600 8N1 (ICD §3.2.1).
    #[arg(long, default_value_t = values::VPX_BAUD, env = BAUD_ENV, value_parser = values::baud)]
    pub baud: u32,

    /// Scenario for the built-in virtual VP-X: a name under assets/scenarios or a TOML file.
    #[arg(long, default_value = "demo", value_name = "NAME|FILE")]
    pub scenario: String,
}

#[derive(Debug, Clone, Args)]
pub struct XfspArgs {
    /// Bridge onto an XFSp network: multicast GROUP:PORT, or without a value the
    /// config file's `xfsp`, else 224.0.2.69:20234.
    #[arg(long, value_name = "GROUP:PORT", num_args = 0..=1, value_parser = values::xfsp_target)]
    pub xfsp: Option<Option<String>>,

    /// Local interface address to join the XFSp group on.
    #[arg(long, value_name = "ADDR", default_value = "0.0.0.0", value_parser = values::iface)]
    pub xfsp_iface: Ipv4Addr,

    /// Our XFSp source id, hex (0x5650) or decimal.
    #[arg(long, value_name = "ID", default_value = "0x5650", value_parser = values::source_id)]
    pub xfsp_source_id: u16,

    /// Certification level published in our XFSp parameters.
    #[arg(long, value_name = "LEVEL", default_value_t = 0)]
    pub xfsp_cert: u8,

    /// Take commands from the XFSp network: ECBSTAT requests (switch and reset
    /// circuits), FLAPREQ/PTRIMREQ/RTRIMREQ (run motors), master resets. XFSp has no
    /// authentication, so without this they are refused, logged and counted;
    /// publishing and air data work either way.
    #[arg(long, env = XFSP_CONTROL_ENV, value_parser = values::yes_no, num_args = 0, default_missing_value = "true", default_value = "false")]
    pub xfsp_control: bool,

    /// With --xfsp-control: only from these XFSp source ids, comma-separated
    /// (0x1234,0x5678).
    #[arg(long, value_name = "ID,…", env = XFSP_CONTROL_FROM_ENV, value_parser = values::source_ids)]
    pub xfsp_control_from: Option<values::SourceIds>,
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

    /// Drive the page from a capture file instead of a unit (read-only). A port set in
    /// the environment or the config file is ignored; one given as a flag is refused.
    #[arg(long, value_name = "FILE")]
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
    #[arg(long, value_enum, default_value_t = Requested::Auto)]
    pub theme: Requested,

    /// Without key-release reports, how long a held motor key may take to repeat for
    /// the first time, in milliseconds (300-1500). By default the page waits 700 ms
    /// and then learns the terminal's own delay; set this for a terminal that repeats
    /// later. A tap runs the motor at most this long.
    #[arg(long, value_name = "MS")]
    pub repeat_delay: Option<u64>,

    /// Serve the walk-around remote, the page on a phone (pair it with the code the
    /// page shows), on ADDR:PORT; without a value, on this laptop's LAN address, port
    /// 8750. Off by default; `p` on the page starts and stops it.
    #[arg(long, value_name = "ADDR:PORT", num_args = 0..=1)]
    pub remote: Option<Option<std::net::SocketAddr>>,
}

/// `--theme` takes the words the config file takes ([`values::THEMES`]); see
/// [`crate::ui::palette`].
impl ValueEnum for Requested {
    fn value_variants<'a>() -> &'a [Self] {
        const ALL: [Requested; values::THEMES.len()] = {
            let mut all = [Requested::Auto; values::THEMES.len()];
            let mut i = 0;
            while i < all.len() {
                all[i] = values::THEMES[i].1;
                i += 1;
            }
            all
        };
        &ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(clap::builder::PossibleValue::new(values::theme_word(*self)))
    }
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
    #[command(after_help = crate::cmd::xfsp_dump::SCALES_HELP)]
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
    /// Create a pseudo-terminal and print its path as the first line on stdout (Unix).
    #[arg(long, conflicts_with = "tcp")]
    pub pty: bool,
    /// Serve the unit on TCP, one client at a time (e.g. 127.0.0.1:5760; port 0 picks a
    /// free one); the bound address is the first line on stdout, as tcp://HOST:PORT.
    #[arg(long, value_name = "ADDR:PORT")]
    pub tcp: Option<std::net::SocketAddr>,
    /// Persist settings to this file (written atomically), like the unit's EEPROM.
    #[arg(long, value_name = "FILE")]
    pub eeprom: Option<PathBuf>,
    /// Scenario: a name under assets/scenarios or a TOML file.
    #[arg(long, default_value = "demo", value_name = "NAME|FILE")]
    pub scenario: String,
    /// Send and take bytes as fast as the pty or socket goes, instead of at the real
    /// line's 5760 bytes a second (57600 baud, 8N1) each way.
    #[arg(long)]
    pub no_pace: bool,
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
    /// Restore needs a port (a flag, VPX_EFIS_PORT or the config file), or `--sim` to
    /// try it on the built-in virtual VP-X: never a simulator by accident.
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

/// `flash` talks to a real port only: flashing the built-in unit would show nothing
/// but the sim's memory changing inside this process.
#[derive(Debug, Clone, Args)]
pub struct FlashPortArgs {
    /// The VP-X's serial port (or tcp://HOST:PORT for a network bridge; the path or
    /// address printed by `vpx-efis sim --pty` or `--tcp` for the virtual VP-X). Also
    /// read from VPX_EFIS_PORT or the config file.
    #[arg(long, value_name = "PATH|tcp://HOST:PORT", env = PORT_ENV, value_parser = values::port)]
    pub port: Option<PortAddr>,

    /// Baud rate of a serial port. The VP-X talks 57600 8N1 (ICD §3.2.1).
    #[arg(long, default_value_t = values::VPX_BAUD, env = BAUD_ENV, value_parser = values::baud)]
    pub baud: u32,
}

#[derive(Debug, Args)]
pub struct FlashArgs {
    #[command(flatten)]
    pub port: FlashPortArgs,
    /// Intel HEX image, named like `cu_2.hex` for hardware version 2.
    pub file: PathBuf,
    /// Accept this hardware version even if the file name's suffix disagrees.
    #[arg(long, value_name = "N")]
    pub force_hardware: Option<u8>,
    /// Flash an image that cannot be a whole program (under 8 KiB of data, no reset
    /// vector, or data outside the program range 0x00000-0x3DFFF), at your own risk:
    /// the unit is erased first and may not start again.
    #[arg(long)]
    pub force_image: bool,
    /// Don't ask for confirmation (the precautions are printed all the same).
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
    #[arg(long, default_value = "224.0.2.69:20234", value_name = "GROUP:PORT", value_parser = values::xfsp_target)]
    pub xfsp: String,
    /// Local interface address to join the group on.
    #[arg(long, default_value = "0.0.0.0", value_name = "ADDR", value_parser = values::iface)]
    pub xfsp_iface: Ipv4Addr,
    /// JSON lines instead of text.
    #[arg(long)]
    pub json: bool,
}

impl From<XfspArgs> for crate::app::XfspOptions {
    fn from(a: XfspArgs) -> Self {
        crate::app::XfspOptions {
            // The command line's resolution has put the group in (flag, file or default).
            xfsp: a
                .xfsp
                .map(|g| g.unwrap_or_else(|| crate::xfsp::net::DEFAULT_TARGET.to_string())),
            xfsp_iface: a.xfsp_iface,
            xfsp_source_id: a.xfsp_source_id,
            xfsp_cert: a.xfsp_cert,
            xfsp_control: a.xfsp_control,
            xfsp_control_from: a.xfsp_control_from.map(|l| l.0),
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
            remote: a.remote,
            repeat_delay: a.repeat_delay,
            theme: a.theme,
        }
    }
}

#[derive(Debug, Args)]
pub struct ConfigArgs {
    /// The same options the commands take, to see how they combine with the file.
    #[command(flatten)]
    pub port: PortArgs,
    #[command(flatten)]
    pub xfsp: XfspArgs,
    /// Colours, as the page's --theme.
    #[arg(long, value_enum, default_value_t = Requested::Auto)]
    pub theme: Requested,
    /// The first key auto-repeat, as the page's --repeat-delay.
    #[arg(long, value_name = "MS")]
    pub repeat_delay: Option<u64>,
}

#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell.
    pub shell: clap_complete::Shell,
}

/// A refusal of the command line or the config file: nothing was opened. Exit code 2.
/// One effective setting for `vpx-efis config`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Effective {
    pub key: &'static str,
    pub value: String,
    pub origin: Origin,
}

/// A file's setting as the value of a flag that may be absent (`--port`,
/// `--repeat-delay`).
fn optional<T: Clone>(s: &Option<Setting<T>>) -> Option<Setting<Option<T>>> {
    s.clone().map(|s| Setting {
        value: Some(s.value),
        line: s.line,
    })
}

/// Fills what the command line left at its default from the config file, and notes
/// where each value came from. Flags and environment variables (clap's) come first.
struct Resolver<'a> {
    m: &'a ArgMatches,
    file: &'a settings::SettingsFile,
    report: Vec<Effective>,
}

impl Resolver<'_> {
    /// Flag or environment, if the value came from either.
    fn explicit(&self, id: &str, env: Option<&'static str>) -> Option<Origin> {
        // A setting with no flag (yet) can only come from the file or its default.
        self.m.try_contains_id(id).ok()?;
        match self.m.value_source(id) {
            Some(ValueSource::CommandLine) => Some(Origin::Flag),
            Some(ValueSource::EnvVariable) => Some(Origin::Env(env.unwrap_or("?"))),
            _ => None,
        }
    }

    fn pick<T: Clone>(
        &mut self,
        key: &'static str,
        id: &str,
        env: Option<&'static str>,
        value: &mut T,
        file: &Option<Setting<T>>,
        show: impl Fn(&T) -> String,
    ) {
        let origin = match (self.explicit(id, env), file) {
            (Some(o), _) => o,
            (None, Some(s)) => {
                *value = s.value.clone();
                Origin::File { line: s.line }
            }
            (None, None) => Origin::Default,
        };
        self.report.push(Effective {
            key,
            value: show(value),
            origin,
        });
    }

    /// `--port`, `--sim` and `--baud`. `--sim` wins over a port from the environment or
    /// the file; against a `--port` flag it is a contradiction.
    fn port(&mut self, p: &mut PortArgs) -> Result<(), UsageError> {
        if p.sim && self.m.value_source("port") == Some(ValueSource::CommandLine) {
            return Err(UsageError(
                "--port and --sim contradict each other: give one".into(),
            ));
        }
        let file = optional(&self.file.port);
        self.pick("port", "port", Some(PORT_ENV), &mut p.port, &file, |_| {
            String::new()
        });
        let e = self.report.last_mut().expect("just pushed");
        if p.sim {
            p.port = None;
            e.origin = Origin::Flag;
        }
        e.value = match &p.port {
            Some(a) => a.to_string(),
            None => "none: the built-in virtual VP-X".into(),
        };
        self.baud(&mut p.baud);
        Ok(())
    }

    fn flash_port(&mut self, p: &mut FlashPortArgs) {
        let file = optional(&self.file.port);
        self.pick("port", "port", Some(PORT_ENV), &mut p.port, &file, |a| {
            a.as_ref()
                .map_or_else(|| "none".into(), PortAddr::to_string)
        });
        self.baud(&mut p.baud);
    }

    /// `--baud` (or its environment variable), or the file's `baud`.
    fn baud(&mut self, baud: &mut u32) {
        let file = self.file.baud.clone();
        self.pick("baud", "baud", Some(BAUD_ENV), baud, &file, u32::to_string);
    }

    /// `--xfsp` without a value takes the file's group; so does `gateway` (always on
    /// the network). The other XFSp options are filled like any setting.
    fn xfsp(&mut self, x: &mut XfspArgs, always_on: bool) {
        let (group, origin) = match (&x.xfsp, &self.file.xfsp) {
            (Some(Some(g)), _) => (g.clone(), Origin::Flag),
            (_, Some(f)) => (f.value.clone(), Origin::File { line: f.line }),
            _ => (
                crate::xfsp::net::DEFAULT_TARGET.to_string(),
                Origin::Default,
            ),
        };
        if always_on || x.xfsp.is_some() {
            x.xfsp = Some(Some(group.clone()));
        }
        self.report.push(Effective {
            key: "xfsp",
            value: group,
            origin,
        });
        self.pick(
            "xfsp_iface",
            "xfsp_iface",
            None,
            &mut x.xfsp_iface,
            &self.file.xfsp_iface.clone(),
            Ipv4Addr::to_string,
        );
        self.pick(
            "xfsp_source_id",
            "xfsp_source_id",
            None,
            &mut x.xfsp_source_id,
            &self.file.xfsp_source_id.clone(),
            |id| format!("{id:#06x}"),
        );
        self.pick(
            "xfsp_cert",
            "xfsp_cert",
            None,
            &mut x.xfsp_cert,
            &self.file.xfsp_cert.clone(),
            u8::to_string,
        );
        self.pick(
            "xfsp_control",
            "xfsp_control",
            Some(XFSP_CONTROL_ENV),
            &mut x.xfsp_control,
            &self.file.xfsp_control.clone(),
            |on| {
                if *on {
                    "on: takes commands from the network"
                } else {
                    "off"
                }
                .to_string()
            },
        );
        let from = optional(&self.file.xfsp_control_from);
        self.pick(
            "xfsp_control_from",
            "xfsp_control_from",
            Some(XFSP_CONTROL_FROM_ENV),
            &mut x.xfsp_control_from,
            &from,
            |l| {
                l.as_ref()
                    .map_or_else(|| "any source".into(), |l| l.to_string())
            },
        );
    }

    /// `--theme`, or the file's `theme`.
    fn theme(&mut self, theme: &mut Requested) {
        let file = self.file.theme.clone();
        self.pick("theme", "theme", None, theme, &file, |t| {
            values::theme_word(*t).to_string()
        });
    }

    /// `--repeat-delay`, or the file's `repeat_delay` (checked by the page).
    fn repeat_delay(&mut self, d: &mut Option<u64>) {
        let delay = optional(&self.file.repeat_delay_ms);
        self.pick("repeat_delay", "repeat_delay", None, d, &delay, |d| {
            d.map_or_else(
                || "learned from the terminal".into(),
                |ms| format!("{ms} ms"),
            )
        });
    }
}

/// Reads the config file and applies it to the commands that use it.
fn resolve(
    command: &mut Option<Command>,
    page: &mut PageArgs,
    matches: &ArgMatches,
) -> anyhow::Result<Vec<Effective>> {
    resolve_with(command, page, matches, settings::load)
}

/// [`resolve`] with the config file read by `load` (tests give one directly).
fn resolve_with(
    command: &mut Option<Command>,
    page: &mut PageArgs,
    matches: &ArgMatches,
    load: impl FnOnce() -> Result<settings::Loaded, settings::ConfigError>,
) -> anyhow::Result<Vec<Effective>> {
    let uses_settings = matches!(
        command,
        None | Some(
            Command::Backup(_)
                | Command::Check(_)
                | Command::Restore(_)
                | Command::Flash(_)
                | Command::Gateway(_)
                | Command::Config(_)
        )
    );
    if !uses_settings {
        return Ok(Vec::new());
    }
    let loaded = load().map_err(|e| UsageError(e.to_string()))?;
    let m = matches.subcommand().map_or(matches, |(_, m)| m);
    let mut r = Resolver {
        m,
        file: &loaded.file,
        report: Vec::new(),
    };
    match command {
        None => {
            if page.replay.is_some() {
                if m.value_source("port") == Some(ValueSource::CommandLine) {
                    return Err(UsageError("--replay and --port contradict each other: a replay is read-only and needs no unit".into()).into());
                }
                page.port.port = None;
            } else {
                r.port(&mut page.port)?;
            }
            r.xfsp(&mut page.xfsp, false);
            r.theme(&mut page.theme);
            r.repeat_delay(&mut page.repeat_delay);
        }
        Some(Command::Backup(a)) => r.port(&mut a.port)?,
        Some(Command::Check(a)) => r.port(&mut a.port)?,
        Some(Command::Restore(a)) => r.port(&mut a.port)?,
        Some(Command::Flash(a)) => r.flash_port(&mut a.port),
        Some(Command::Gateway(a)) => {
            r.port(&mut a.port)?;
            r.xfsp(&mut a.xfsp, true);
        }
        Some(Command::Config(a)) => {
            r.port(&mut a.port)?;
            r.xfsp(&mut a.xfsp, false);
            r.theme(&mut a.theme);
            r.repeat_delay(&mut a.repeat_delay);
        }
        _ => {}
    }
    let mut report = r.report;
    if let Some(Command::Config(_)) = command {
        report.insert(
            0,
            Effective {
                key: "config file",
                value: match (&loaded.path, loaded.exists) {
                    (Some(p), true) => p.display().to_string(),
                    (Some(p), false) => format!("{} (not there: nothing set)", p.display()),
                    (None, _) => "(this system has no configuration folder)".into(),
                },
                origin: if std::env::var_os(settings::CONFIG_ENV).is_some_and(|v| !v.is_empty()) {
                    Origin::Env(settings::CONFIG_ENV)
                } else {
                    Origin::Default
                },
            },
        );
    }
    Ok(report)
}

/// Entry point of the binary: parse, dispatch, and turn errors into words and an exit code.
pub fn main() -> ExitCode {
    let matches = Cli::command().get_matches();
    let mut cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result =
        resolve(&mut cli.command, &mut cli.page, &matches).and_then(|report| match cli.command {
            None => crate::app::run(cli.page.into()),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The page's options after the command line `args` and a config file `text`.
    fn page_with(args: &[&str], text: &str) -> anyhow::Result<crate::app::PageOptions> {
        let m = Cli::command().try_get_matches_from(args)?;
        let mut cli = Cli::from_arg_matches(&m)?;
        let file = settings::parse(text).expect("a good file");
        resolve_with(&mut cli.command, &mut cli.page, &m, || {
            Ok(settings::Loaded {
                path: None,
                exists: true,
                file,
            })
        })?;
        Ok(cli.page.into())
    }

    #[test]
    fn the_file_fills_what_the_command_line_left_to_its_default() {
        let file = "port = \"tcp://10.0.0.9:4001\"\nbaud = 115200\ntheme = \"light\"\n\
                    xfsp = \"239.1.1.1:7000\"\nxfsp_iface = \"10.0.0.2\"\nxfsp_source_id = 0x5651\n";
        let p = page_with(&["vpx-efis", "--xfsp"], file).unwrap();
        assert_eq!(p.port, Some("tcp://10.0.0.9:4001".parse().unwrap()));
        assert_eq!(p.baud, 115_200);
        assert_eq!(p.theme, Requested::Light);
        assert_eq!(p.xfsp.xfsp.as_deref(), Some("239.1.1.1:7000"));
        assert_eq!(p.xfsp.xfsp_iface, Ipv4Addr::new(10, 0, 0, 2));
        assert_eq!(p.xfsp.xfsp_source_id, 0x5651);
        assert_eq!(p.repeat_delay, None);
        let with_delay = format!("{file}repeat_delay = 900\n");
        assert_eq!(
            page_with(&["vpx-efis"], &with_delay).unwrap().repeat_delay,
            Some(900)
        );
        assert_eq!(
            page_with(&["vpx-efis", "--repeat-delay", "400"], &with_delay)
                .unwrap()
                .repeat_delay,
            Some(400)
        );

        // Flags win; the file's group is no reason to start bridging.
        let p = page_with(
            &[
                "vpx-efis",
                "--port",
                "/dev/ttyUSB1",
                "--baud",
                "9600",
                "--theme",
                "dark",
            ],
            file,
        )
        .unwrap();
        assert_eq!(p.port, Some(PortAddr::Serial("/dev/ttyUSB1".into())));
        assert_eq!(p.baud, 9600);
        assert_eq!(p.theme, Requested::Dark);
        assert_eq!(p.xfsp.xfsp, None);

        // --sim wins over the file's port; a replay ignores it.
        assert_eq!(page_with(&["vpx-efis", "--sim"], file).unwrap().port, None);
        let replay = page_with(&["vpx-efis", "--replay", "x.vpxcap"], file).unwrap();
        assert_eq!(replay.port, None);
    }

    #[test]
    fn with_no_file_the_defaults_stand() {
        let p = page_with(&["vpx-efis"], "").unwrap();
        assert_eq!(p.port, None);
        assert_eq!(p.baud, 57_600);
        assert_eq!(p.theme, Requested::Auto);
        assert_eq!(p.xfsp.xfsp_source_id, 0x5650);
        let p = page_with(&["vpx-efis", "--xfsp"], "").unwrap();
        assert_eq!(
            p.xfsp.xfsp.as_deref(),
            Some(crate::xfsp::net::DEFAULT_TARGET)
        );
    }

    #[test]
    fn port_and_sim_together_is_a_usage_error() {
        let e = page_with(&["vpx-efis", "--sim", "--port", "COM3"], "").unwrap_err();
        assert!(e.downcast_ref::<UsageError>().is_some(), "{e}");
        assert!(e.to_string().contains("contradict"), "{e}");
    }
}

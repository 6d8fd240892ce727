//! The options several subcommands share: the unit's port (the page, `backup`,
//! `restore`, `check`, `gateway`, `config`) and the XFSp bridge (the page, `gateway`,
//! `config`), and the words `--theme` takes.

use std::net::Ipv4Addr;
use std::path::PathBuf;

use clap::{Args, ValueEnum};

use crate::app::XfspOptions;
use crate::link::PortAddr;
use crate::settings::values::Theme as Requested;
use crate::settings::{
    AIRCRAFT_ENV, BAUD_ENV, LOGBOOK_ENV, PORT_ENV, XFSP_CONTROL_ENV, XFSP_CONTROL_FROM_ENV, values,
};

/// The aircraft's logbook and the aircraft: options of every command, before or after
/// the subcommand's name.
#[derive(Debug, Clone, Default, Args)]
pub struct LogbookArgs {
    /// The aircraft's logbook, an SQLite file: every check, backup, restore, setting
    /// written, firmware update, fault and command sent. Also read from the config
    /// file. Default: logbook.sqlite beside the config file.
    #[arg(long, global = true, value_name = "FILE", env = LOGBOOK_ENV)]
    pub logbook: Option<std::path::PathBuf>,

    /// The aircraft's registration (N123AB, G-ABCD), to record under. Also read from
    /// the config file. Without one, records go under the unit (its VERSION and
    /// circuit names).
    #[arg(long, global = true, value_name = "REGISTRATION", env = AIRCRAFT_ENV,
          value_parser = crate::logbook::registration)]
    pub aircraft: Option<String>,
}

impl LogbookArgs {
    /// Where to record: the file named, else the one beside the config file.
    pub fn target(&self) -> Option<crate::logbook::Target> {
        let path = self.logbook.clone().or_else(crate::places::logbook_path)?;
        Some(crate::logbook::Target {
            path,
            aircraft: self.aircraft.clone(),
        })
    }
}

/// The unit's link as the page and `gateway` take it: its port, the XFSp bridge, and a
/// capture of the serial line.
#[derive(Debug, Clone, Args)]
pub struct LinkArgs {
    #[command(flatten)]
    pub port: PortArgs,

    #[command(flatten)]
    pub xfsp: XfspArgs,

    /// Record every byte in both directions to a capture file.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
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

impl From<XfspArgs> for XfspOptions {
    fn from(a: XfspArgs) -> Self {
        XfspOptions {
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

/// `--theme` takes the words the config file takes ([`values::THEMES`]); see
/// the page's palette (`ui::palette`).
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

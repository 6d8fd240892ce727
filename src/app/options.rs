//! What the page is asked to do, in the page's own terms. The command line (`cli`)
//! fills these; `app` never looks up at clap's argument structs, so the page can be
//! started the same way from a test, a config file or another front end.

use std::net::Ipv4Addr;
use std::path::PathBuf;

use crate::link::PortAddr;

/// Everything `vpx-efis` with no subcommand was given.
#[derive(Debug, Clone)]
pub struct PageOptions {
    /// A serial path or a TCP bridge, or `None` for the built-in virtual VP-X.
    pub port: Option<PortAddr>,
    pub baud: u32,
    /// Scenario of the built-in virtual VP-X.
    pub scenario: String,
    pub xfsp: XfspOptions,
    /// Record every byte in both directions to this capture file.
    pub record: Option<PathBuf>,
    /// Drive the page from this capture file instead of a unit (read-only).
    pub replay: Option<PathBuf>,
    /// Replay speed factor.
    pub speed: f64,
    /// Longest continuous trim/flap run, in seconds, as typed (checked by `run`).
    pub max_run: f64,
    /// `--repeat-delay` in milliseconds, as typed (checked by `run`).
    pub repeat_delay: Option<u64>,
    /// `--theme`: a palette, or `Auto` to ask the terminal.
    pub theme: crate::ui::palette::Requested,
    /// `--remote [ADDR:PORT]`: serve the walk-around remote from the start (`None`
    /// inside: the LAN address, port 8750).
    pub remote: Option<Option<std::net::SocketAddr>>,
}

/// The XFSp bridge's settings, as typed (checked by [`super::xfsp_setup`]).
#[derive(Debug, Clone)]
pub struct XfspOptions {
    /// Multicast GROUP:PORT, or `None` for no bridge.
    pub xfsp: Option<String>,
    /// Local interface address to join the group on.
    pub xfsp_iface: Ipv4Addr,
    pub xfsp_source_id: u16,
    pub xfsp_cert: u8,
    /// `--xfsp-control`: take commands from the network (off by default).
    pub xfsp_control: bool,
    /// `--xfsp-control-from`: only from these source ids (needs `xfsp_control`).
    pub xfsp_control_from: Option<Vec<u16>>,
}

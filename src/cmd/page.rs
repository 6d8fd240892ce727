//! `vpx-efis` with no subcommand: the electrical page ([`crate::app::run`]).

use std::path::PathBuf;

use clap::Args;

use crate::app::PageOptions;
use crate::cmd::common::LinkArgs;
use crate::settings::values::Theme as Requested;

#[derive(Debug, Clone, Args)]
pub struct PageArgs {
    #[command(flatten)]
    pub link: LinkArgs,

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

impl From<PageArgs> for PageOptions {
    fn from(a: PageArgs) -> Self {
        PageOptions {
            port: a.link.port.port,
            baud: a.link.port.baud,
            scenario: a.link.port.scenario,
            xfsp: a.link.xfsp.into(),
            record: a.link.record,
            replay: a.replay,
            speed: a.speed,
            max_run: a.max_run,
            remote: a.remote,
            repeat_delay: a.repeat_delay,
            theme: a.theme,
        }
    }
}

pub fn run(args: PageArgs) -> anyhow::Result<()> {
    crate::app::run(args.into())
}

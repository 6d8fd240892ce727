//! What the page is asked to do, in the page's own terms, and the checks of it.
//! `cmd::page` fills these from clap's arguments (after `cli` has applied the config
//! file); `app` never looks up at clap's structs, so the page can be started the same
//! way from a test or another front end.

use std::net::Ipv4Addr;
use std::path::PathBuf;
use std::time::Duration;

use crate::link::PortAddr;
use crate::settings::values::REPEAT_DELAY_MS;

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

/// `--max-run`: a positive number of seconds up to the streamer's cap, which stays
/// below the flaps' 30 s (Appendix F). Anything else is refused in words rather than
/// silently clamped or turned into a panicking `Duration`.
pub(super) fn max_run(secs: f64) -> anyhow::Result<Duration> {
    let limit = crate::control::streamer::MAX_RUN_LIMIT;
    if !(secs > 0.0 && secs <= limit.as_secs_f64()) {
        anyhow::bail!(
            "--max-run must be more than 0 and at most {} seconds, below the flaps' 30 s maximum run time",
            limit.as_secs()
        );
    }
    Ok(Duration::from_secs_f64(secs))
}

/// `--repeat-delay`: refused in words outside [`REPEAT_DELAY_MS`].
pub(super) fn repeat_delay(ms: u64) -> anyhow::Result<Duration> {
    let (lo, hi) = REPEAT_DELAY_MS;
    if !(lo..=hi).contains(&ms) {
        anyhow::bail!(
            "--repeat-delay (or the config file's repeat_delay) must be between {lo} and \
             {hi} milliseconds: the time your terminal takes to repeat a held key for the \
             first time (a tap runs a motor this long at most)"
        );
    }
    Ok(Duration::from_millis(ms))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_run_refuses_nonsense_in_words_instead_of_panicking() {
        assert_eq!(max_run(10.0).unwrap(), Duration::from_secs(10));
        assert_eq!(max_run(25.0).unwrap(), Duration::from_secs(25));
        for bad in [0.0, -1.0, 26.0, 1e300, f64::NAN, f64::INFINITY] {
            let err = max_run(bad).unwrap_err().to_string();
            assert!(err.contains("--max-run"), "{bad}: {err}");
        }
    }

    #[test]
    fn repeat_delay_refuses_values_no_terminal_uses() {
        assert_eq!(repeat_delay(300).unwrap(), Duration::from_millis(300));
        assert_eq!(repeat_delay(1100).unwrap(), Duration::from_millis(1100));
        assert_eq!(repeat_delay(1500).unwrap(), Duration::from_millis(1500));
        for bad in [0, 299, 1501, 60_000] {
            let err = repeat_delay(bad).unwrap_err().to_string();
            assert!(
                err.contains("--repeat-delay") && err.contains("300 and 1500"),
                "{bad}: {err}"
            );
        }
    }
}

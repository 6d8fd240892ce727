//! Choosing the palette before the page takes the terminal: `--theme`, NO_COLOR, and
//! for `auto` the terminal's own background, asked with OSC 11 while the terminal
//! still shows its normal screen.

use std::time::Duration;

use crate::ui::osc11;
use crate::ui::palette::{Palette, Requested, Rgb, ThemeChoice};

/// Long enough for a terminal over ssh to answer; a terminal that answers nothing (a
/// serial console) costs this once at start. Terminals that ignore OSC 11 still answer
/// the DA1 sent after it, which ends the wait at once.
const REPLY_TIMEOUT: Duration = Duration::from_millis(300);

pub fn choose_theme(requested: Requested) -> ThemeChoice {
    // no-color.org: set and not empty.
    let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
    let choice = ThemeChoice::decide(requested, no_color, ask_background);
    // crossterm honours NO_COLOR itself by writing an empty SGR (a full reset) for
    // every colour change, which would wipe bold and reverse mid-line. Mono paints no
    // colour at all, so that never happens; a colour theme asked for on the command
    // line overrides NO_COLOR, as no-color.org asks.
    if matches!(
        choice.palette,
        Palette::Dark | Palette::Light | Palette::Terminal
    ) {
        crossterm::style::force_color_output(true);
    }
    choice
}

/// Writes the OSC 11 + DA1 query and reads the answers, in raw mode so they are
/// neither echoed nor held back for a newline.
fn ask_background() -> Option<Rgb> {
    if crossterm::terminal::enable_raw_mode().is_err() {
        return None;
    }
    let bytes = exchange(osc11::QUERY, REPLY_TIMEOUT);
    let _ = crossterm::terminal::disable_raw_mode();
    osc11::parse(&bytes).background
}

/// Sends `query` to the terminal and collects what it sends back until the DA1
/// answer or `timeout`.
#[cfg(unix)]
fn exchange(query: &[u8], timeout: Duration) -> Vec<u8> {
    use std::io::Write;
    use std::time::Instant;
    // SAFETY: isatty only inspects the descriptor.
    if unsafe { libc::isatty(0) != 1 || libc::isatty(1) != 1 } {
        return Vec::new();
    }
    let mut out = std::io::stdout();
    if out.write_all(query).and_then(|()| out.flush()).is_err() {
        return Vec::new();
    }
    let deadline = Instant::now() + timeout;
    let mut got = Vec::new();
    while !osc11::parse(&got).complete {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            break;
        }
        let mut fd = libc::pollfd {
            fd: 0,
            events: libc::POLLIN,
            revents: 0,
        };
        // SAFETY: one valid pollfd, and a read into a buffer of the length given.
        let ready = unsafe { libc::poll(&mut fd, 1, left.as_millis().max(1) as libc::c_int) };
        if ready <= 0 {
            break;
        }
        let mut buf = [0u8; 256];
        let n = unsafe { libc::read(0, buf.as_mut_ptr().cast(), buf.len()) };
        if n <= 0 {
            break;
        }
        got.extend_from_slice(&buf[..n as usize]);
    }
    got
}

/// Windows consoles are not asked: the page uses its own dark background there.
#[cfg(not(unix))]
fn exchange(_query: &[u8], _timeout: Duration) -> Vec<u8> {
    Vec::new()
}

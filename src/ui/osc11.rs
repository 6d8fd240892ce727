//! Asking a terminal for its background colour, as bytes: the query to write and a
//! pure reading of whatever came back, so `auto` is tested without a terminal.
//!
//! The query is OSC 11 (xterm's "report background colour") followed by DA1 (primary
//! device attributes). Terminals answer in order and every terminal answers DA1, so
//! the DA1 answer says "nothing more is coming": a terminal that ignores OSC 11 costs
//! one round trip, not the whole timeout, and no late answer is left behind to be read
//! as key presses.

use super::palette::Rgb;

/// OSC 11 query (ST-terminated), then DA1.
pub const QUERY: &[u8] = b"\x1b]11;?\x1b\\\x1b[c";

/// What the bytes read so far say.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Reply {
    /// The background colour, if the terminal gave one we can read.
    pub background: Option<Rgb>,
    /// The DA1 answer has arrived: stop waiting.
    pub complete: bool,
}

/// Reads the terminal's answers in `bytes` (anything else, such as a key pressed
/// meanwhile, is skipped).
pub fn parse(bytes: &[u8]) -> Reply {
    let mut reply = Reply::default();
    let mut i = 0;
    while i < bytes.len() {
        let rest = &bytes[i..];
        if let Some(body) = rest.strip_prefix(b"\x1b]11;") {
            // The colour runs to BEL or ST (ESC \).
            let end = body
                .iter()
                .position(|&b| b == 0x07 || b == 0x1b)
                .unwrap_or(body.len());
            let terminated = end < body.len();
            if terminated {
                reply.background = colour(&body[..end]).or(reply.background);
            }
            i += 5 + end + 1;
        } else if let Some(body) = rest.strip_prefix(b"\x1b[?") {
            // DA1: CSI ? digits and semicolons, ending in 'c'.
            let len = body
                .iter()
                .position(|b| !(b.is_ascii_digit() || *b == b';'))
                .unwrap_or(body.len());
            if body.get(len) == Some(&b'c') {
                reply.complete = true;
            }
            i += 3 + len;
        } else {
            i += 1;
        }
    }
    reply
}

/// `rgb:RRRR/GGGG/BBBB` (1 to 4 hex digits a component, as XParseColor reads them),
/// or `rgba:` with an alpha that does not matter here.
fn colour(spec: &[u8]) -> Option<Rgb> {
    let spec = std::str::from_utf8(spec).ok()?;
    let components = spec
        .strip_prefix("rgb:")
        .or_else(|| spec.strip_prefix("rgba:"))?;
    let mut parts = components.split('/');
    let mut next = || -> Option<u8> {
        let hex = parts.next()?;
        if hex.is_empty() || hex.len() > 4 {
            return None;
        }
        let v = u32::from_str_radix(hex, 16).ok()?;
        let max = (1u32 << (4 * hex.len())) - 1;
        Some(((v * 255 + max / 2) / max) as u8)
    };
    Some(Rgb(next()?, next()?, next()?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ui::palette::{Palette, ThemeChoice, Why};

    fn choose(reply: &[u8]) -> ThemeChoice {
        ThemeChoice::for_background(parse(reply).background)
    }

    #[test]
    fn white_answer_is_light_and_black_answer_is_dark() {
        // xterm's own answers with its default colours (ST) and with -bg black (BEL),
        // each followed by its DA1.
        let white = choose(b"\x1b]11;rgb:ffff/ffff/ffff\x1b\\\x1b[?64;1;2;6;9;15;18;21;22c");
        assert_eq!(white.palette, Palette::Light);
        assert_eq!(white.why, Why::Background(Rgb(255, 255, 255)));
        let black = choose(b"\x1b]11;rgb:0000/0000/0000\x07\x1b[?62;c");
        assert_eq!(black.palette, Palette::Dark);
        assert_eq!(black.why, Why::Background(Rgb(0, 0, 0)));
    }

    #[test]
    fn no_answer_is_dark_on_its_own_background() {
        // A terminal that only answers DA1 (tmux without passthrough), and silence.
        for bytes in [&b"\x1b[?1;2c"[..], b""] {
            let c = choose(bytes);
            assert_eq!(
                (c.palette, c.why),
                (Palette::Dark, Why::NoReply),
                "{bytes:?}"
            );
        }
        assert!(parse(b"\x1b[?1;2c").complete);
        assert!(!parse(b"").complete);
    }

    #[test]
    fn component_widths_scale_like_xparsecolor() {
        for (bytes, want) in [
            (&b"\x1b]11;rgb:fd/f6/e3\x07"[..], Rgb(0xfd, 0xf6, 0xe3)),
            (b"\x1b]11;rgb:f/8/0\x07", Rgb(255, 136, 0)),
            (b"\x1b]11;rgb:2b2b/2c2c/2e2e\x1b\\", Rgb(0x2b, 0x2c, 0x2e)),
            (b"\x1b]11;rgba:ffff/ffff/ffff/ffff\x07", Rgb(255, 255, 255)),
        ] {
            assert_eq!(
                parse(bytes).background,
                Some(want),
                "{}",
                bytes.escape_ascii()
            );
        }
    }

    #[test]
    fn garbage_and_half_answers_give_no_colour_and_no_panic() {
        for bytes in [
            &b"\x1b]11;rgb:ffff/ffff\x07"[..],
            b"\x1b]11;rgb:ffff/ffff/ffff",
            b"\x1b]11;#ffffff\x07",
            b"\x1b]11;rgb:fffff/0/0\x07",
            b"\x1b]11;rgb:zz/00/00\x07",
            b"\x1b]11;",
            b"\x1b[?",
            b"q\x1b]11\x1b[?6",
        ] {
            let r = parse(bytes);
            assert_eq!(r.background, None, "{bytes:?}");
            assert!(!r.complete, "{bytes:?}");
        }
        // A key pressed while waiting does not hide the answer.
        let r = parse(b"j\x1b]11;rgb:ffff/ffff/ffff\x07k\x1b[?62c");
        assert_eq!(r.background, Some(Rgb(255, 255, 255)));
        assert!(r.complete);
    }
}

//! What the page's colour words look like on the person's terminal.
//!
//! Widgets draw with [`super::theme`]'s words (green=on, white=off, red=faulted, as
//! Appendix A writes them), and [`Palette::paint`] then repaints the finished frame
//! once, cell by cell:
//! - `Dark` is the EFIS look and paints its own background, so every colour is the one
//!   designed here whatever the terminal's palette;
//! - `Light` is for a light terminal: dark text, OFF in the text colour, and green, red
//!   and amber dark enough to read on white; the background is the terminal's;
//! - `Mono` is for NO_COLOR: no colour at all, and whatever stood on a coloured
//!   background (the COMMUNICATION LOST banner, keys, the selection, SIMULATED) in
//!   reverse video instead, so nothing that meant something is lost;
//! - `Terminal` leaves the words as the terminal's own 16 colours show them (what a
//!   tuned terminal theme may prefer; its contrast is that theme's business). The
//!   selection, which has no colour among those 16, is underlined on the terminal's
//!   own background instead of a band, so it reads on any palette, light or dark. It is
//!   the type's default, for tests and tools; the page itself always chooses.
//!
//! Colours are xterm's 256-colour indices 16–255, whose values every 256-colour
//! terminal agrees on (unlike 0–15, which each terminal's theme redefines), so the
//! contrast the tests compute is the contrast people get.

use std::fmt;

use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};

use super::theme;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Palette {
    Dark,
    Light,
    Mono,
    #[default]
    Terminal,
}

impl Palette {
    pub fn name(self) -> &'static str {
        match self {
            Palette::Dark => "dark",
            Palette::Light => "light",
            Palette::Mono => "no colour",
            Palette::Terminal => "terminal",
        }
    }

    /// The background the page's cells stand on: its own for dark, the terminal's
    /// (assumed white) for light, unknown without colour.
    pub fn assumed_background(self) -> Option<Rgb> {
        match self {
            Palette::Dark => rgb(DARK_BG),
            Palette::Light => Some(Rgb(255, 255, 255)),
            Palette::Mono | Palette::Terminal => None,
        }
    }

    /// Repaints `buf` from the page's colour words into this palette's colours.
    pub fn paint(self, buf: &mut Buffer) {
        match self {
            Palette::Dark => paint_with(buf, Some(DARK_BG), Color::Indexed(235), dark_word),
            Palette::Light => paint_with(buf, None, Color::Indexed(254), light_word),
            Palette::Terminal => {
                for cell in &mut buf.content {
                    if cell.bg == theme::SELECTION {
                        // Not reverse video: a coloured word reversed stands on its
                        // colour in the terminal's background colour, unreadable for
                        // white=off on a light terminal. Underlined (and bold, and
                        // marked ▶), each word keeps its Appendix A colour.
                        cell.bg = Color::Reset;
                        cell.modifier.insert(Modifier::UNDERLINED);
                    }
                }
            }
            Palette::Mono => {
                for cell in &mut buf.content {
                    // The remote's QR code is a picture that must be dark on light
                    // to scan: it keeps its own two colours (ui::remote).
                    if cell.bg == super::remote::QR_LIGHT {
                        continue;
                    }
                    if cell.bg != Color::Reset {
                        cell.modifier.insert(Modifier::REVERSED);
                    }
                    cell.fg = Color::Reset;
                    cell.bg = Color::Reset;
                }
            }
        }
    }
}

/// The page's dark background: black, as an EFIS screen.
const DARK_BG: Color = Color::Indexed(16);

/// The dark palette's colour for each foreground colour word.
fn dark_word(c: Color) -> Color {
    match c {
        Color::Reset => Color::Indexed(255),
        Color::White => Color::Indexed(231),
        Color::Gray => Color::Indexed(250),
        Color::DarkGray => Color::Indexed(246),
        Color::Green => Color::Indexed(40),
        Color::Red => Color::Indexed(203),
        Color::Yellow => Color::Indexed(220),
        Color::Cyan => Color::Indexed(45),
        Color::Magenta => Color::Indexed(207),
        Color::Black => Color::Indexed(16),
        other => other,
    }
}

/// The light palette's colour for each foreground colour word.
fn light_word(c: Color) -> Color {
    match c {
        // Appendix A's white=off is the text colour on a light screen.
        Color::Reset | Color::White | Color::Black => Color::Indexed(234),
        Color::Gray => Color::Indexed(237),
        Color::DarkGray => Color::Indexed(240),
        Color::Green => Color::Indexed(22),
        Color::Red => Color::Indexed(124),
        Color::Yellow => Color::Indexed(94),
        Color::Cyan => Color::Indexed(25),
        Color::Magenta => Color::Indexed(90),
        other => other,
    }
}

/// The text on a badge: white on the dark ones (the mark, COMMUNICATION LOST), black
/// on the light ones, whatever colour word the text had on the page.
fn badge_text(bg: Color) -> Color {
    match bg {
        Color::Black | Color::Red | Color::Blue | Color::DarkGray => Color::Indexed(231),
        _ => Color::Indexed(16),
    }
}

/// Badges (keys, the mark, banners, a search hit: words on a coloured background of
/// their own) look the same in both palettes, since each carries its own text colour.
fn badge_bg(c: Color) -> Color {
    match c {
        Color::Black => Color::Indexed(16),
        Color::Red => Color::Indexed(124),
        Color::Magenta => Color::Indexed(201),
        Color::Yellow => Color::Indexed(220),
        Color::Gray => Color::Indexed(250),
        other => other,
    }
}

/// One palette's pass over the frame: `background` for the page's own (`None`: the
/// terminal's), `selection` for the selected row's band, `on_page` for the words on
/// either (a function item, so the pass is compiled per palette with it inlined).
fn paint_with(
    buf: &mut Buffer,
    background: Option<Color>,
    selection: Color,
    on_page: impl Fn(Color) -> Color,
) {
    let page = background.unwrap_or(Color::Reset);
    for cell in &mut buf.content {
        let bg = cell.bg;
        if bg == Color::Reset || bg == theme::SELECTION {
            cell.fg = on_page(cell.fg);
            cell.bg = if bg == Color::Reset { page } else { selection };
        } else {
            cell.fg = badge_text(bg);
            cell.bg = badge_bg(bg);
        }
    }
}

/// How the page came to use its palette: the help overlay says it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Why {
    /// `--theme dark|light|mono|terminal`.
    Asked,
    /// NO_COLOR is set (no-color.org) and no theme was asked for.
    NoColor,
    /// The terminal answered OSC 11 with its background colour.
    Background(Rgb),
    /// The terminal did not answer OSC 11 in time (tmux without passthrough, a serial
    /// console): dark, on its own background.
    NoReply,
    /// Not chosen by the page (tests, tools).
    #[default]
    Default,
}

/// The palette in use and why: set once before the alternate screen, shown in help.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ThemeChoice {
    pub palette: Palette,
    pub why: Why,
}

/// What `--theme` asked for: a setting, so it is the settings' own type.
pub use crate::settings::values::Theme as Requested;

impl ThemeChoice {
    /// Decides the palette. `background` is asked only when the terminal's colour
    /// matters: `auto` without NO_COLOR.
    pub fn decide(
        requested: Requested,
        no_color: bool,
        background: impl FnOnce() -> Option<Rgb>,
    ) -> ThemeChoice {
        let asked = |palette| ThemeChoice {
            palette,
            why: Why::Asked,
        };
        match requested {
            Requested::Dark => asked(Palette::Dark),
            Requested::Light => asked(Palette::Light),
            Requested::Mono => asked(Palette::Mono),
            Requested::Terminal => asked(Palette::Terminal),
            Requested::Auto if no_color => ThemeChoice {
                palette: Palette::Mono,
                why: Why::NoColor,
            },
            Requested::Auto => ThemeChoice::for_background(background()),
        }
    }

    /// `auto` given the terminal's answer: light on a light background, otherwise
    /// (dark, or no answer) dark on the page's own background.
    pub fn for_background(background: Option<Rgb>) -> ThemeChoice {
        match background {
            Some(bg) if bg.is_light() => ThemeChoice {
                palette: Palette::Light,
                why: Why::Background(bg),
            },
            Some(bg) => ThemeChoice {
                palette: Palette::Dark,
                why: Why::Background(bg),
            },
            None => ThemeChoice {
                palette: Palette::Dark,
                why: Why::NoReply,
            },
        }
    }
}

impl fmt::Display for ThemeChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.palette.name();
        match self.why {
            Why::Asked => write!(f, "theme {name}, from --theme"),
            Why::NoColor => write!(f, "theme {name}, because NO_COLOR is set"),
            Why::Background(bg) => write!(f, "theme {name}: terminal background {bg}"),
            Why::NoReply => write!(f, "theme {name}: no answer to OSC 11, own black background"),
            Why::Default => write!(f, "theme {name}"),
        }
    }
}

/// A colour as red, green and blue, 0–255.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl fmt::Display for Rgb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

impl Rgb {
    /// WCAG 2 relative luminance.
    pub fn luminance(self) -> f64 {
        let lin = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.040_45 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * lin(self.0) + 0.7152 * lin(self.1) + 0.0722 * lin(self.2)
    }

    /// Light when dark text reads better on it than white text does (luminance above
    /// about 0.18, where the two contrasts are equal).
    pub fn is_light(self) -> bool {
        contrast(self, Rgb(0, 0, 0)) > contrast(self, Rgb(255, 255, 255))
    }
}

/// WCAG 2 contrast ratio, 1 to 21.
pub fn contrast(a: Rgb, b: Rgb) -> f64 {
    let (la, lb) = (a.luminance(), b.luminance());
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

/// The value of a painted colour: xterm's 256-colour cube and grey ramp, or RGB. The
/// first 16 colours are the terminal theme's own, so they have no known value.
pub fn rgb(c: Color) -> Option<Rgb> {
    match c {
        Color::Rgb(r, g, b) => Some(Rgb(r, g, b)),
        Color::Indexed(i @ 16..=231) => {
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            let i = i - 16;
            Some(Rgb(level(i / 36), level(i / 6 % 6), level(i % 6)))
        }
        Color::Indexed(i @ 232..=255) => {
            let v = 8 + 10 * (i - 232);
            Some(Rgb(v, v, v))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;
    use ratatui::style::Style;

    #[test]
    fn the_256_colour_values_are_xterms() {
        // Hand-checked against xterm's 256colres.h.
        assert_eq!(rgb(Color::Indexed(16)), Some(Rgb(0, 0, 0)));
        assert_eq!(rgb(Color::Indexed(22)), Some(Rgb(0, 0x5f, 0)));
        assert_eq!(rgb(Color::Indexed(203)), Some(Rgb(0xff, 0x5f, 0x5f)));
        assert_eq!(rgb(Color::Indexed(231)), Some(Rgb(0xff, 0xff, 0xff)));
        assert_eq!(rgb(Color::Indexed(232)), Some(Rgb(8, 8, 8)));
        assert_eq!(rgb(Color::Indexed(255)), Some(Rgb(0xee, 0xee, 0xee)));
        assert_eq!(rgb(Color::White), None);
    }

    #[test]
    fn contrast_matches_wcag_reference_values() {
        let c = contrast(Rgb(255, 255, 255), Rgb(0, 0, 0));
        assert!((c - 21.0).abs() < 1e-9, "{c}");
        // #767676 on white is the well-known 4.54:1.
        let c = contrast(Rgb(0x76, 0x76, 0x76), Rgb(255, 255, 255));
        assert!((c - 4.54).abs() < 0.01, "{c}");
        assert!(Rgb(255, 255, 255).is_light());
        assert!(Rgb(0xfd, 0xf6, 0xe3).is_light(), "solarized light");
        assert!(!Rgb(0, 0x2b, 0x36).is_light(), "solarized dark");
        assert!(!Rgb(0, 0, 0).is_light());
    }

    #[test]
    fn auto_without_an_answer_is_dark_with_its_own_background() {
        let c = ThemeChoice::decide(Requested::Auto, false, || None);
        assert_eq!(c.palette, Palette::Dark);
        assert_eq!(c.why, Why::NoReply);
        assert_eq!(Palette::Dark.assumed_background(), Some(Rgb(0, 0, 0)));
    }

    #[test]
    fn no_color_wins_over_auto_and_loses_to_an_explicit_theme() {
        let asked = std::cell::Cell::new(false);
        let c = ThemeChoice::decide(Requested::Auto, true, || {
            asked.set(true);
            None
        });
        assert_eq!((c.palette, c.why), (Palette::Mono, Why::NoColor));
        assert!(!asked.get(), "no need to ask the terminal");
        let c = ThemeChoice::decide(Requested::Light, true, || None);
        assert_eq!((c.palette, c.why), (Palette::Light, Why::Asked));
    }

    #[test]
    fn dark_paints_every_cell_and_light_leaves_the_background_to_the_terminal() {
        let area = Rect::new(0, 0, 4, 1);
        let mut buf = Buffer::empty(area);
        buf.set_string(0, 0, "ab", Style::new().fg(theme::OFF));
        buf.set_string(2, 0, "c", Style::new().fg(Color::White).bg(theme::FAULT));
        let mut dark = buf.clone();
        Palette::Dark.paint(&mut dark);
        for cell in &dark.content {
            assert!(rgb(cell.fg).is_some() && rgb(cell.bg).is_some(), "{cell:?}");
        }
        // White text on the red badge stays white; white=off on the page is white.
        assert_eq!(dark[(2, 0)].fg, Color::Indexed(231));
        assert_eq!(dark[(2, 0)].bg, Color::Indexed(124));
        let mut light = buf.clone();
        Palette::Light.paint(&mut light);
        assert_eq!(light[(0, 0)].bg, Color::Reset);
        assert_eq!(
            light[(0, 0)].fg,
            Color::Indexed(234),
            "off is the text colour"
        );
        assert_eq!(light[(2, 0)].fg, Color::Indexed(231), "badge keeps white");
        let mut mono = buf;
        Palette::Mono.paint(&mut mono);
        assert!(
            mono.content
                .iter()
                .all(|c| c.fg == Color::Reset && c.bg == Color::Reset)
        );
        assert!(mono[(2, 0)].modifier.contains(Modifier::REVERSED));
        assert!(!mono[(0, 0)].modifier.contains(Modifier::REVERSED));
    }
}

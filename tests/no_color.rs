//! What reaches the terminal under NO_COLOR: the page is drawn through crossterm into a
//! byte buffer (not only a `TestBackend`) and the bytes are read as a terminal would.
//!
//! crossterm honours NO_COLOR by writing an empty SGR (`ESC [ m`, a full reset) for
//! every colour change, which wipes bold and reverse video mid-line. Its own test
//! switch, `force_color_output(false)`, is how crossterm sees NO_COLOR=1; this file is
//! its own test binary, so flipping that global touches no other test.

use std::time::{Duration, Instant};

use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;
use vpx_efis::model::{Model, Source};
use vpx_efis::ui;
use vpx_efis::ui::palette::{Palette, ThemeChoice, Why};
use vpx_efis::ui::state::ViewState;

/// The text a terminal would show, each character with (bold, reverse), and every
/// SGR parameter list seen.
struct Screen {
    chars: Vec<(char, bool, bool)>,
    sgr: Vec<String>,
}

fn interpret(bytes: &[u8]) -> Screen {
    let s = String::from_utf8_lossy(bytes);
    let mut chars = Vec::new();
    let mut sgr = Vec::new();
    let (mut bold, mut reverse) = (false, false);
    let mut it = s.chars().peekable();
    while let Some(c) = it.next() {
        if c != '\x1b' {
            chars.push((c, bold, reverse));
            continue;
        }
        if it.peek() != Some(&'[') {
            continue;
        }
        it.next();
        let mut params = String::new();
        let mut fin = ' ';
        for p in it.by_ref() {
            if ('\x40'..='\x7e').contains(&p) {
                fin = p;
                break;
            }
            params.push(p);
        }
        if fin != 'm' {
            continue;
        }
        sgr.push(params.clone());
        let list: Vec<&str> = params.split(';').collect();
        for p in list {
            match p {
                "" | "0" => (bold, reverse) = (false, false),
                "1" => bold = true,
                "22" => bold = false,
                "7" => reverse = true,
                "27" => reverse = false,
                _ => {}
            }
        }
    }
    Screen { chars, sgr }
}

/// The data stopped 6 s ago on a real port: the COMMUNICATION LOST banner.
fn comm_lost() -> (Model, Instant) {
    let t0 = Instant::now();
    let mut m = Model::new(Source::Serial {
        path: "/dev/ttyUSB0".into(),
    });
    m.note_connected(t0, "/dev/ttyUSB0".into());
    let status = vpx_efis::protocol::message::SystemStatus {
        system_current: vpx_efis::protocol::message::Tenths(150),
        main_bus_volts: vpx_efis::protocol::message::SignedTenths(139),
        internal_temp: 30,
        ..Default::default()
    };
    m.apply_packet(t0, &vpx_efis::protocol::Packet::from_vpx(0, status));
    (m, t0 + Duration::from_secs(6))
}

fn bytes_for(palette: Palette) -> Vec<u8> {
    let (m, now) = comm_lost();
    let view = ViewState {
        theme: ThemeChoice {
            palette,
            why: Why::NoColor,
        },
        ..Default::default()
    };
    let mut bytes = Vec::new();
    {
        // A fixed viewport: the backend would otherwise ask the real terminal's size.
        let mut term = Terminal::with_options(
            CrosstermBackend::new(&mut bytes),
            ratatui::TerminalOptions {
                viewport: ratatui::Viewport::Fixed(ratatui::layout::Rect::new(0, 0, 80, 24)),
            },
        )
        .unwrap();
        term.draw(|f| {
            ui::draw(
                f,
                &m,
                &view,
                &vpx_efis::ui::state::ControlState::default(),
                now,
            )
        })
        .unwrap();
    }
    bytes
}

/// (bold, reverse) of each character of `needle` as the terminal shows it.
fn emphasis(screen: &Screen, needle: &str) -> Vec<(bool, bool)> {
    let text: Vec<char> = screen.chars.iter().map(|c| c.0).collect();
    let n: Vec<char> = needle.chars().collect();
    let at = (0..text.len() - n.len())
        .find(|&i| text[i..i + n.len()] == n[..])
        .unwrap_or_else(|| {
            panic!(
                "{needle:?} not written: {}",
                text.iter().collect::<String>()
            )
        });
    screen.chars[at..at + n.len()]
        .iter()
        .map(|c| (c.1, c.2))
        .collect()
}

#[test]
fn no_colour_escape_is_written_and_the_banner_is_still_bold_and_reversed() {
    crossterm::style::force_color_output(false);
    let screen = interpret(&bytes_for(Palette::Mono));
    for p in &screen.sgr {
        for code in p.split(';').filter_map(|c| c.parse::<u32>().ok()) {
            assert!(
                !matches!(code, 30..=49 | 58 | 59 | 90..=107),
                "colour escape ESC[{p}m written under NO_COLOR"
            );
        }
    }
    let banner = emphasis(&screen, "C O M M U N I C A T I O N   L O S T");
    assert!(
        banner.iter().all(|&(bold, reverse)| bold && reverse),
        "banner lost its emphasis: {banner:?}"
    );
    // The explanation line under it is part of the banner too.
    let why = emphasis(&screen, "no status from the VP-X");
    assert!(why.iter().all(|&(_, reverse)| reverse), "{why:?}");
}

/// Why mono exists: the dark palette's colour changes, under crossterm's NO_COLOR,
/// become full resets that strip the banner's bold.
#[test]
fn colour_under_crossterms_no_color_would_have_lost_the_emphasis() {
    crossterm::style::force_color_output(false);
    let screen = interpret(&bytes_for(Palette::Dark));
    let banner = emphasis(&screen, "C O M M U N I C A T I O N");
    assert!(
        banner.iter().any(|&(bold, _)| !bold),
        "crossterm no longer resets on colour; the mono palette may be revisited"
    );
}

//! The walk-around remote's overlay on the page (TestBackend): the URL with its key as
//! text and as a QR code that holds exactly the code's modules with its quiet zone,
//! dark on light in every palette (NO_COLOR included: not reverse video), read back
//! from the drawn cells by a QR decoder (`rqrr`) as a phone's camera would see them on
//! light and dark terminals; the address and words for a phone without a camera,
//! what is protected, and the count of phones (those paired by typed words marked),
//! also in the title.

use std::time::Instant;

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use vpx_efis::model::{Model, Source};
use vpx_efis::ui;
use vpx_efis::ui::palette::Palette;
use vpx_efis::ui::palette::rgb;
use vpx_efis::ui::remote::qr_rows;
use vpx_efis::ui::state::{Overlay, RemoteView, ViewState};

mod themes;

mod common;
use common::screen::text;

/// A key of 128 bits in base64url, as the remote makes them.
const URL: &str = "http://192.168.1.20:8750/#k=q83vEjRWeJCrze8SNFZ4kA";
const WORDS: &str = "abandon ability able about above";

fn view(paired: usize, typed: usize) -> ViewState {
    ViewState {
        overlay: Overlay::Remote,
        remote: Some(RemoteView {
            url: URL.into(),
            address: "http://192.168.1.20:8750/".into(),
            words: WORDS.into(),
            paired,
            typed,
            loopback_only: false,
            qr: [qr_rows(URL, 4), qr_rows(URL, 2)],
        }),
        ..ViewState::default()
    }
}

/// The overlay alone on an empty screen, its words unwrapped into one line.
fn overlay_words(view: &ViewState, w: u16, h: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal
        .draw(|f| ui::remote::render(f, view.remote.as_ref().unwrap()))
        .unwrap();
    let t = text(terminal.backend().buffer());
    t.chars()
        .map(|c| {
            if "█▀▄│╭╮╰╯─".contains(c) {
                ' '
            } else {
                c
            }
        })
        .collect::<String>()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

fn draw(view: &ViewState, w: u16, h: u16) -> Buffer {
    let model = Model::new(Source::Simulated {
        scenario: "demo".into(),
    });
    common::screen::rendered(&model, view, Instant::now(), w, h)
}

/// The QR code's cells: every cell on xterm white, as (x, y).
fn qr_cells(buf: &Buffer) -> Vec<(u16, u16)> {
    let a = buf.area;
    (a.y..a.y + a.height)
        .flat_map(|y| (a.x..a.x + a.width).map(move |x| (x, y)))
        .filter(|&(x, y)| buf[(x, y)].bg == Color::Indexed(231))
        .collect()
}

/// The modules drawn (true = dark), two a cell, from the half blocks.
fn modules_drawn(buf: &Buffer) -> Vec<Vec<bool>> {
    let cells = qr_cells(buf);
    let (x0, y0) = cells
        .iter()
        .fold((u16::MAX, u16::MAX), |(a, b), &(x, y)| (a.min(x), b.min(y)));
    let x1 = cells.iter().map(|c| c.0).max().unwrap();
    let y1 = cells.iter().map(|c| c.1).max().unwrap();
    assert_eq!(
        cells.len(),
        usize::from(x1 - x0 + 1) * usize::from(y1 - y0 + 1),
        "the code is one rectangle"
    );
    let mut rows = Vec::new();
    for y in y0..=y1 {
        let (mut top, mut bottom) = (Vec::new(), Vec::new());
        for x in x0..=x1 {
            let cell = &buf[(x, y)];
            assert_eq!(
                cell.fg,
                Color::Indexed(16),
                "dark is xterm black at {x},{y}"
            );
            let (t, b) = match cell.symbol() {
                "█" => (true, true),
                "▀" => (true, false),
                "▄" => (false, true),
                " " => (false, false),
                s => panic!("{s:?} in the code at {x},{y}"),
            };
            top.push(t);
            bottom.push(b);
        }
        rows.push(top);
        rows.push(bottom);
    }
    rows
}

/// The code's own modules for `URL`, with a light quiet zone of `zone` around them.
fn modules_wanted(zone: usize) -> Vec<Vec<bool>> {
    let code =
        qrcode::QrCode::with_error_correction_level(URL.as_bytes(), qrcode::EcLevel::L).unwrap();
    let w = code.width();
    let colors = code.to_colors();
    let side = w + 2 * zone;
    // Rows come in pairs: an odd side has one light row more at the bottom.
    let height = side + side % 2;
    (0..height)
        .map(|y| {
            (0..side)
                .map(|x| {
                    (zone..zone + w).contains(&x)
                        && (zone..zone + w).contains(&y)
                        && colors[(y - zone) * w + (x - zone)] == qrcode::Color::Dark
                })
                .collect()
        })
        .collect()
}

#[test]
fn the_overlay_shows_the_url_the_qr_code_the_words_and_the_phones() {
    let buf = draw(&view(2, 0), 100, 40);
    insta::assert_snapshot!(text(&buf));
    let t = text(&buf);
    assert!(t.contains(&format!("or open {URL}")), "{t}");
    assert!(
        t.lines()
            .next()
            .unwrap()
            .contains("REMOTE: 2 phones paired")
    );
    let words = overlay_words(&view(2, 0), 100, 40);
    for want in [
        "No camera? Open http://192.168.1.20:8750/ and type the words",
        WORDS,
        vpx_efis::remote::PROTECTED,
        "2 phones paired",
    ] {
        assert!(words.contains(want), "{want:?} missing: {words}");
    }
    assert!(!words.contains("typed words"), "{words}");
    assert_eq!(
        modules_drawn(&buf),
        modules_wanted(4),
        "the code drawn is not the URL's"
    );
}

/// A phone paired by typed words is marked, with what it risks, in the overlay and
/// the title.
#[test]
fn a_phone_paired_by_typed_words_is_marked() {
    let buf = draw(&view(2, 1), 120, 40);
    let t = text(&buf);
    assert!(
        t.lines()
            .next()
            .unwrap()
            .contains("REMOTE: 2 phones paired, 1 by typed words"),
        "{t}"
    );
    let words = overlay_words(&view(2, 1), 120, 40);
    assert!(
        words.contains(&format!(
            "2 phones paired, 1 by typed words {}",
            vpx_efis::ui::remote::TYPED_RISK
        )),
        "{words}"
    );
    let narrow = text(&draw(&view(1, 1), 80, 24));
    assert!(
        narrow
            .lines()
            .next()
            .unwrap()
            .contains("REMOTE: 1 paired (1 typed)"),
        "{narrow}"
    );
}

#[test]
fn on_80x24_the_words_go_beside_the_code_and_it_keeps_its_full_quiet_zone() {
    let buf = draw(&view(0, 0), 80, 24);
    insta::assert_snapshot!(text(&buf));
    let t = text(&buf);
    for words in [URL, WORDS, "no phone paired", "unpair all"] {
        assert!(t.contains(words), "{words} missing:\n{t}");
    }
    assert!(
        overlay_words(&view(0, 0), 80, 24).contains(vpx_efis::remote::PROTECTED),
        "what is protected, at 80x24"
    );
    assert_eq!(modules_drawn(&buf), modules_wanted(4));
}

#[test]
fn the_code_is_dark_on_light_in_every_palette_and_legible_without_colour() {
    let buf = draw(&view(1, 0), 100, 40);
    let cells = qr_cells(&buf);
    // NO_COLOR too: the code is a picture that must be dark on light to scan, so it
    // keeps its two colours there, never reverse video.
    for palette in [
        Palette::Dark,
        Palette::Light,
        Palette::Terminal,
        Palette::Mono,
    ] {
        let p = themes::painted(&buf, palette);
        for &(x, y) in &cells {
            assert_eq!(
                (p[(x, y)].fg, p[(x, y)].bg),
                (Color::Indexed(16), Color::Indexed(231)),
                "{palette:?} at {x},{y}"
            );
            assert!(
                !p[(x, y)].modifier.contains(Modifier::REVERSED),
                "{palette:?} at {x},{y}"
            );
        }
    }
    themes::check_themes("remote_overlay", &buf);
    // Without colour every word is still there, and nothing but the code has colour.
    let mono = themes::painted(&buf, Palette::Mono);
    let t = text(&mono);
    for words in [URL, WORDS, "1 phone paired", "REMOTE: 1 phone paired"] {
        assert!(t.contains(words), "{words} missing without colour:\n{t}");
    }
    let qr: std::collections::HashSet<_> = cells.into_iter().collect();
    let w = mono.area.width;
    for (i, c) in mono.content.iter().enumerate() {
        let at = (i as u16 % w, i as u16 / w);
        if !qr.contains(&at) {
            assert_eq!((c.fg, c.bg), (Color::Reset, Color::Reset), "{at:?}");
        }
    }
}

/// The terminal's own text and background colours, for cells that use them.
#[derive(Clone, Copy, Debug)]
enum Term {
    Dark,
    Light,
}

/// The screen as a camera sees it: `SCALE` pixels a module across, two modules a cell
/// down (half blocks), each pixel's grey from the cell's colours as the terminal shows
/// them (reverse video swapped, the terminal's defaults for Reset). Text other than
/// the code's blocks is a blob of its colour in the middle of its cell.
fn photograph(buf: &Buffer, term: Term) -> (usize, usize, Vec<u8>) {
    const SCALE: usize = 4;
    let (w, h) = (buf.area.width as usize, buf.area.height as usize);
    let (pw, ph) = (w * SCALE, h * 2 * SCALE);
    let (text_grey, page_grey) = match term {
        Term::Dark => (230u8, 20u8),
        Term::Light => (20u8, 250u8),
    };
    let grey = |c: Color, default: u8| match rgb(c) {
        Some(v) => (v.luminance() * 255.0).round() as u8,
        None => default,
    };
    let mut px = vec![0u8; pw * ph];
    for y in 0..h {
        for x in 0..w {
            let cell = &buf[(x as u16, y as u16)];
            let (mut fg, mut bg) = (grey(cell.fg, text_grey), grey(cell.bg, page_grey));
            if cell.modifier.contains(Modifier::REVERSED) {
                std::mem::swap(&mut fg, &mut bg);
            }
            let sym = cell.symbol();
            let (top, bottom) = match sym {
                "█" => (true, true),
                "▀" => (true, false),
                "▄" => (false, true),
                _ => (false, false),
            };
            let blob = !matches!(sym, "█" | "▀" | "▄" | " " | "");
            for dy in 0..2 * SCALE {
                for dx in 0..SCALE {
                    let on = if dy < SCALE { top } else { bottom }
                        || (blob
                            && (1..SCALE - 1).contains(&dx)
                            && (2..2 * SCALE - 2).contains(&dy));
                    px[(y * 2 * SCALE + dy) * pw + x * SCALE + dx] = if on { fg } else { bg };
                }
            }
        }
    }
    (pw, ph, px)
}

/// What a QR decoder reads off the photographed screen: every code it finds.
fn decoded(buf: &Buffer, term: Term) -> Vec<String> {
    let (w, h, px) = photograph(buf, term);
    let mut img = rqrr::PreparedImage::prepare_from_greyscale(w, h, |x, y| px[y * w + x]);
    img.detect_grids()
        .into_iter()
        .filter_map(|g| g.decode().ok().map(|(_, text)| text))
        .collect()
}

/// A decoder reads the URL off the drawn cells in the dark and light
/// themes and without colour, on dark and light terminals, at 80x24 and 120x40.
#[test]
fn a_qr_decoder_reads_the_url_off_the_drawn_cells_in_every_theme_and_size() {
    for (w, h) in [(80, 24), (120, 40)] {
        let buf = draw(&view(1, 0), w, h);
        for (palette, terms) in [
            (Palette::Dark, &[Term::Dark, Term::Light][..]),
            (Palette::Light, &[Term::Light][..]),
            (Palette::Mono, &[Term::Dark, Term::Light][..]),
        ] {
            let painted = themes::painted(&buf, palette);
            for &term in terms {
                assert_eq!(
                    decoded(&painted, term),
                    vec![URL.to_string()],
                    "{palette:?} on a {term:?} terminal at {w}x{h}"
                );
            }
        }
    }
}

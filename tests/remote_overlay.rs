//! The walk-around remote's overlay on the page (TestBackend): the URL as text, the
//! same URL as a QR code that holds exactly the code's modules with its quiet zone,
//! dark on light in every palette, the code in words and the count of phones, also
//! in the title; legible without colour.

use std::time::Instant;

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use vpx_efis::model::{Model, Source};
use vpx_efis::ui;
use vpx_efis::ui::palette::Palette;
use vpx_efis::ui::remote::qr_rows;
use vpx_efis::ui::state::{Overlay, RemoteView, ViewState};

mod themes;

const URL: &str = "http://192.168.1.20:8750/?pair=482913";

fn view(paired: usize) -> ViewState {
    ViewState {
        overlay: Overlay::Remote,
        remote: Some(RemoteView {
            url: URL.into(),
            code: "482913".into(),
            paired,
            loopback_only: false,
            qr: [qr_rows(URL, 4), qr_rows(URL, 2)],
        }),
        ..ViewState::default()
    }
}

fn draw(view: &ViewState, w: u16, h: u16) -> Buffer {
    let model = Model::new(Source::Simulated {
        scenario: "demo".into(),
    });
    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal
        .draw(|f| ui::render(f, &model, view, Instant::now()))
        .unwrap();
    terminal.backend().buffer().clone()
}

fn text(buf: &Buffer) -> String {
    let w = buf.area.width as usize;
    let mut out = String::new();
    for (i, cell) in buf.content.iter().enumerate() {
        out.push_str(cell.symbol());
        if (i + 1) % w == 0 {
            out.push('\n');
        }
    }
    out
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
fn the_overlay_shows_the_url_the_qr_code_the_code_and_the_phones() {
    let buf = draw(&view(2), 100, 40);
    insta::assert_snapshot!(text(&buf));
    let t = text(&buf);
    assert!(t.contains(&format!("open {URL}")), "{t}");
    assert!(t.contains("pairing code 482 913"), "{t}");
    assert!(t.contains("2 phones paired"), "{t}");
    assert!(
        t.lines()
            .next()
            .unwrap()
            .contains("REMOTE: 2 phones paired")
    );
    assert_eq!(
        modules_drawn(&buf),
        modules_wanted(4),
        "the code drawn is not the URL's"
    );
}

#[test]
fn on_80x24_the_code_keeps_a_quiet_zone_of_two_and_everything_fits() {
    let buf = draw(&view(0), 80, 24);
    insta::assert_snapshot!(text(&buf));
    let t = text(&buf);
    for words in [URL, "pairing code 482 913", "no phone paired", "unpair all"] {
        assert!(t.contains(words), "{words} missing:\n{t}");
    }
    assert_eq!(modules_drawn(&buf), modules_wanted(2));
}

#[test]
fn the_code_is_dark_on_light_in_every_palette_and_legible_without_colour() {
    let buf = draw(&view(1), 100, 40);
    let cells = qr_cells(&buf);
    for palette in [Palette::Dark, Palette::Light, Palette::Terminal] {
        let p = themes::painted(&buf, palette);
        for &(x, y) in &cells {
            assert_eq!(
                (p[(x, y)].fg, p[(x, y)].bg),
                (Color::Indexed(16), Color::Indexed(231)),
                "{palette:?} at {x},{y}"
            );
        }
    }
    themes::check_themes("remote_overlay", &buf);
    // NO_COLOR: no colour at all; the code's cells in reverse video (dark glyphs on
    // the terminal's text colour), and every word still there.
    let mono = themes::painted(&buf, Palette::Mono);
    for &(x, y) in &cells {
        let c = &mono[(x, y)];
        assert_eq!((c.fg, c.bg), (Color::Reset, Color::Reset));
        assert!(c.modifier.contains(Modifier::REVERSED), "{x},{y}");
    }
    let t = text(&mono);
    for words in [
        URL,
        "pairing code 482 913",
        "1 phone paired",
        "REMOTE: 1 phone paired",
    ] {
        assert!(t.contains(words), "{words} missing without colour:\n{t}");
    }
    assert!(
        mono.content
            .iter()
            .all(|c| c.fg == Color::Reset && c.bg == Color::Reset)
    );
}

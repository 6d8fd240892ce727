//! The load analysis on screen (step 5 of the installation check): the phase table,
//! the bar chart against the alternator, the circuits, and the words for a missing or
//! refused file. Each state as text, as the colours of each theme (dark, light, no
//! colour), and held to the WCAG contrast of the page.

use std::path::PathBuf;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;

use vpx_efis::check::state::LoadsView;
use vpx_efis::loads::{self, Phase};
use vpx_efis::ui::check::loads::render;

mod themes;

mod common;
use common::screen::text;

/// The aircraft of `loads::analysis`'s hand-worked test: landing leaves 16 % of a
/// 32 A alternator.
const WARNED: &str = include_str!("data/loads-32a-alternator.toml");

fn warned() -> LoadsView {
    let file = loads::file::parse(WARNED).unwrap();
    LoadsView::Analysed {
        path: PathBuf::from("/home/pilot/.config/vpx-efis/loads.toml"),
        analysis: loads::analyse(&file, &[(0x02, 2.5), (0x04, 1.5)]),
    }
}

/// Everything that can go wrong at once, worked by hand: a 20 A alternator, a
/// 4 Ah battery (× 0.8 = 3.2 Ah usable), the nav lights typed 4.5 A but measured
/// 4.8 A and on half the ground time, a com radio with no current, and a measured
/// 5A-3 in no phase.
///
/// ground    2.5 + 3 + 0.5 × 4.8              =  7.9 A, 60.5 % spare
/// taxi      2.5 + 3 + 7.5 + 0.1 (+ com)      = 13.1 A, 34.5 %, at least
/// take-off  2.5 + 3 + 7.5 + 12 + 0.1 (+ com) = 25.1 A, 5.1 A over
/// day       2.5 + 3 + 12 + 0.1               = 17.6 A, 12 %
/// night     2.5 + 3 + 4.8 + 12 + 0.1         = 22.4 A, 2.4 A over
/// landing   … + 4.8 + 7.5 + 12 + 0.1 (+ com) = 29.9 A, 9.9 A over
/// emergency 2.5 + 4.8 + 0.1 (+ com)          =  7.4 A, 3.2 × 60 / 7.4 = 25.9 min
fn troubled() -> LoadsView {
    let text = WARNED
        .replace("alternator_amps = 32", "alternator_amps = 20")
        .replace("battery_amp_hours = 17", "battery_amp_hours = 4")
        .replace(
            "name = \"Nav lights\"",
            "name = \"Nav lights\"\namps = 4.5\nground = 0.5",
        )
        + "\n[circuit.5A-2]\nname = \"Com radio\"\ntaxi = true\ntake_off = true\n\
           landing = true\nemergency = true\n";
    let file = loads::file::parse(&text).unwrap();
    LoadsView::Analysed {
        path: PathBuf::from("loads.toml"),
        analysis: loads::analyse(&file, &[(0x02, 2.5), (0x04, 4.8), (0x06, 1.2)]),
    }
}

fn draw(view: Option<&LoadsView>, first: usize, w: u16, h: u16) -> Buffer {
    let mut buf = Buffer::empty(Rect::new(0, 0, w, h));
    render(&mut buf, Rect::new(0, 0, w, h), view, first);
    buf
}

/// Every state the step can show, named, with the width and height drawn at.
fn every_state() -> Vec<(&'static str, Option<LoadsView>, usize, u16, u16)> {
    vec![
        ("analysed_80x24", Some(warned()), 0, 80, 24),
        ("analysed_scrolled_80x24", Some(warned()), 3, 80, 24),
        ("troubled_120x40", Some(troubled()), 0, 120, 40),
        ("troubled_80x24", Some(troubled()), 0, 80, 24),
        ("short_80x14", Some(warned()), 0, 80, 14),
        (
            "template_written",
            Some(LoadsView::TemplateWritten(PathBuf::from(
                "/home/pilot/.config/vpx-efis/loads.toml",
            ))),
            0,
            80,
            6,
        ),
        (
            "refused",
            Some(LoadsView::Refused(
                "load file loads.toml, line 12: [circuit.5A-7] taxi: 1.5 is not on, off or a \
                 fraction of the time; write true, false, or a number from 0 to 1"
                    .into(),
            )),
            0,
            80,
            6,
        ),
        ("skipped", None, 0, 80, 2),
    ]
}

#[test]
fn every_state_as_text() {
    for (name, view, first, w, h) in every_state() {
        let buf = draw(view.as_ref(), first, w, h);
        insta::assert_snapshot!(name, text(&buf));
    }
}

#[test]
fn every_state_in_every_theme() {
    for (name, view, first, w, h) in every_state() {
        let buf = draw(view.as_ref(), first, w, h);
        themes::assert_every_palette("loads_snapshots", name, &buf);
    }
}

#[test]
fn every_state_meets_wcag_contrast_in_both_themes() {
    let mut failures = Vec::new();
    for (name, view, first, w, h) in every_state() {
        let buf = draw(view.as_ref(), first, w, h);
        failures.extend(themes::contrast_in_both(name, &buf));
    }
    themes::assert_contrast(failures);
}

/// The first cell of `needle` on the line that holds `row`.
fn find(buf: &Buffer, row: &str, needle: &str) -> (u16, u16) {
    let t = text(buf);
    for (y, line) in t.lines().enumerate() {
        if line.contains(row)
            && let Some(i) = line.find(needle)
        {
            let x = line[..i].chars().count();
            return (x as u16, y as u16);
        }
    }
    panic!("{needle:?} not on a line with {row:?}:\n{t}");
}

#[test]
fn warnings_are_in_words_as_well_as_colour() {
    let buf = draw(Some(&warned()), 0, 80, 24);
    let t = text(&buf);
    // The table: landing's margin in words and its mark.
    assert!(
        t.contains("landing                    26.6 A  ⚠ WARN    margin 16 % of 32 A: under 20 %"),
        "{t}"
    );
    assert!(
        t.contains("ground                      5.5 A  ✓ PASS    margin 82 % of 32 A"),
        "{t}"
    );
    assert!(t.contains("4.1 A  ✓ PASS    endurance 199 min"), "{t}");
    let (x, y) = find(&buf, "margin 16 %", "⚠");
    assert_eq!(buf[(x, y)].fg, Color::Yellow);
    // The chart names the alternator's line and the warning mark.
    assert!(t.contains("│ alternator 32 A   ┆ 80 % of it"), "{t}");
    // Where each current came from.
    assert!(t.contains("EFIS           EFIS      2.5 A measured"), "{t}");
    assert!(t.contains("↓ 4 more circuits"), "{t}");
    let t = text(&draw(Some(&warned()), 3, 80, 24));
    assert!(t.contains("Landing light  10A-1     7.5 A typed"), "{t}");

    let buf = draw(Some(&troubled()), 0, 120, 40);
    let t = text(&buf);
    assert!(t.contains("✗ FAIL    "), "{t}");
    assert!(t.contains("over the alternator's 20 A"), "{t}");
    assert!(t.contains("endurance 25 min: under 30 min"), "{t}");
    assert!(t.contains("⚠ no current"), "{t}");
    let (x, y) = find(&buf, "over the alternator", "✗");
    assert_eq!(buf[(x, y)].fg, Color::Red);
}

/// At 80 columns the longest verdicts ("9.9 A over the alternator's 20 A; at least:
/// no current for Com radio") are wrapped under themselves, never cut at the edge.
#[test]
fn at_80_columns_no_verdict_is_cut() {
    let LoadsView::Analysed { analysis, .. } = troubled() else {
        unreachable!()
    };
    let t = text(&draw(Some(&troubled()), 0, 80, 24));
    // The screen's words, joined back where they were wrapped.
    let joined = t.lines().map(str::trim).collect::<Vec<_>>().join(" ");
    for p in Phase::ALL {
        let v = analysis.verdict(p);
        assert!(joined.contains(&v), "{v:?} not whole in\n{t}");
    }
    assert!(
        joined.contains("the 5A-3 pin draws 1.2 A but is not in the load file: it is in no phase"),
        "{t}"
    );
    for l in t.lines() {
        assert!(l.chars().count() <= 80, "{l:?}");
    }
}

#[test]
fn the_bars_are_drawn_to_scale_against_the_alternator() {
    let LoadsView::Analysed { analysis, .. } = troubled() else {
        unreachable!()
    };
    let landing = analysis.phase(Phase::Landing).amps;
    assert!((landing - 29.9).abs() < 1e-6, "{landing}");
    assert!((analysis.phase(Phase::Ground).amps - 7.9).abs() < 1e-6);
    // 120 columns: the bars have 120 − 13 − 18 = 89 cells for the scale's top, the
    // landing's 29.9 A, which is over the 20 A alternator.
    let buf = draw(Some(&troubled()), 0, 120, 40);
    let bar_row = |label: &str| {
        (0..40)
            .find(|&y| {
                text(&buf)
                    .lines()
                    .nth(y as usize)
                    .unwrap()
                    .starts_with(label)
                    && buf[(13, y)].symbol() == "█"
            })
            .unwrap_or_else(|| panic!("no bar for {label}"))
    };
    let l = bar_row("landing ");
    let full = (13..13 + 89)
        .filter(|&x| buf[(x, l)].symbol() == "█")
        .count();
    assert_eq!(full, 89, "the biggest phase fills the chart");
    // The alternator's line at 20 / 29.9 × 89 = 59.5 → column 13 + 60, the 80 % mark
    // at 16 / 29.9 × 89 = 47.6 → 13 + 48; the ground bar 7.9 / 29.9 × 89 = 23.5
    // cells: 23 full and a half one.
    let g = bar_row("ground ");
    assert_eq!(buf[(13 + 60, g)].symbol(), "│");
    assert_eq!(buf[(13 + 48, g)].symbol(), "┆");
    assert_eq!(buf[(13 + 22, g)].symbol(), "█");
    assert_eq!(buf[(13 + 23, g)].symbol(), "▌");
    assert_eq!(buf[(13 + 24, g)].symbol(), " ");
    // The emergency phase is on the battery: no alternator line on its row.
    let e = bar_row("emergency ");
    assert_eq!(buf[(13 + 60, e)].symbol(), " ");
}

/// The guide's load-file example (docs/src/loads.md) reads as it says, and its screen
/// is this file's.
#[test]
fn the_guides_example_file_and_screen_are_what_the_code_does() {
    let section = include_str!("../docs/src/loads.md");
    let toml = section
        .split("```toml\n")
        .nth(1)
        .and_then(|s| s.split("\n```").next())
        .unwrap();
    let f = loads::file::parse(toml).unwrap();
    assert_eq!(f.alternator_amps, 40.0);
    assert_eq!(f.battery_amp_hours, 17.0);
    assert_eq!(f.battery_usable, 0.8);
    assert_eq!(f.circuits.len(), 1);
    assert_eq!(f.circuits[0].pin(), "10A-1");
    assert_eq!(f.circuits[0].name, "Landing Lt");
    assert_eq!(f.circuits[0].amps, Some(7.5));
    assert_eq!(f.circuits[0].duty, [0., 1., 1., 0., 0., 1., 0.]);
    let screen = section
        .split("```text\n")
        .nth(1)
        .and_then(|s| s.split("\n```").next())
        .unwrap();
    let drawn = text(&draw(Some(&warned()), 0, 80, 24));
    let drawn: Vec<&str> = drawn.lines().map(str::trim_end).collect();
    assert_eq!(
        screen.lines().collect::<Vec<_>>(),
        drawn[..screen.lines().count()]
    );
}

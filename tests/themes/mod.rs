//! Shared by the snapshot tests: a frame repainted in each palette, a compact picture
//! of its colours for snapshots, and the WCAG contrast check over every cell.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::fmt::Write;

use ratatui::buffer::{Buffer, Cell};
use ratatui::style::{Color, Modifier};
use vpx_efis::ui::palette::{Palette, Rgb, contrast, rgb};

pub const PALETTES: [Palette; 3] = [Palette::Dark, Palette::Light, Palette::Mono];

pub fn painted(buf: &Buffer, palette: Palette) -> Buffer {
    let mut b = buf.clone();
    palette.paint(&mut b);
    b
}

/// The frame's colours as a picture: one letter per cell, each letter a style listed
/// under the picture, so a snapshot diff shows where a colour changed.
pub fn colour_map(buf: &Buffer) -> String {
    let mut legend: BTreeMap<String, char> = BTreeMap::new();
    let mut order: Vec<String> = Vec::new();
    let letters: Vec<char> = ('a'..='z').chain('A'..='Z').chain('0'..='9').collect();
    let mut grid = String::new();
    let w = buf.area.width as usize;
    for (i, cell) in buf.content.iter().enumerate() {
        let key = format!("fg {:?} bg {:?} {:?}", cell.fg, cell.bg, cell.modifier);
        let n = legend.len();
        let letter = *legend.entry(key.clone()).or_insert_with(|| {
            order.push(key.clone());
            letters.get(n).copied().unwrap_or('?')
        });
        grid.push(letter);
        if (i + 1) % w == 0 {
            grid.push('\n');
        }
    }
    for key in order {
        let _ = writeln!(grid, "{}: {key}", legend[&key]);
    }
    grid
}

/// WCAG 2 asks 4.5:1 of text and 3:1 of graphics (borders, gauge tracks, plot
/// marks); dimmed "not now" keys are inactive controls, which WCAG exempts, and are
/// held to 3:1 here anyway.
fn required(cell: &Cell, dim_colour: Color) -> f64 {
    let graphic = cell
        .symbol()
        .chars()
        .all(|c| matches!(c as u32, 0x2500..=0x25FF | 0x2800..=0x28FF));
    if graphic || cell.modifier.contains(Modifier::DIM) || cell.fg == dim_colour {
        3.0
    } else {
        4.5
    }
}

/// Every visible cell's contrast against what it stands on; one line per failure
/// naming the state, the cell, its text and both colours.
pub fn contrast_failures(state: &str, buf: &Buffer, palette: Palette) -> Vec<String> {
    let page = palette
        .assumed_background()
        .expect("contrast is checked for colour palettes only");
    let mut probe = Buffer::empty(ratatui::layout::Rect::new(0, 0, 1, 1));
    probe.content[0].fg = Color::DarkGray;
    palette.paint(&mut probe);
    let dim_colour = probe.content[0].fg;
    let mut out = Vec::new();
    let w = buf.area.width;
    for (i, cell) in buf.content.iter().enumerate() {
        if cell.symbol().chars().all(|c| c == ' ' || c == '\u{a0}') {
            continue;
        }
        let (x, y) = (i as u16 % w, i as u16 / w);
        let colour = |c: Color| -> Option<Rgb> { if c == Color::Reset { None } else { rgb(c) } };
        let (Some(mut fg), mut bg) = (colour(cell.fg), colour(cell.bg).unwrap_or(page)) else {
            out.push(format!(
                "{state}: ({x},{y}) {:?} has fg {:?}, a colour of unknown value",
                cell.symbol(),
                cell.fg
            ));
            continue;
        };
        if cell.bg != Color::Reset && colour(cell.bg).is_none() {
            out.push(format!(
                "{state}: ({x},{y}) {:?} has bg {:?}, a colour of unknown value",
                cell.symbol(),
                cell.bg
            ));
            continue;
        }
        if cell.modifier.contains(Modifier::REVERSED) {
            std::mem::swap(&mut fg, &mut bg);
        }
        let ratio = contrast(fg, bg);
        let need = required(cell, dim_colour);
        if ratio + 1e-9 < need {
            let line: String = (0..w).map(|x| buf[(x, y)].symbol().to_string()).collect();
            out.push(format!(
                "{state} ({}): cell ({x},{y}) {:?} fg {fg} on bg {bg} is {ratio:.2}:1, needs {need}:1 — line {:?}",
                palette.name(),
                cell.symbol(),
                line.trim_end()
            ));
        }
    }
    out
}

/// Panics with every failure of every state, not just the first.
pub fn assert_contrast(failures: Vec<String>) {
    assert!(
        failures.is_empty(),
        "{} cells below the WCAG contrast asked for:\n{}",
        failures.len(),
        failures
            .iter()
            .take(40)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// `buf` painted in `palette`: the text unchanged, and the colours pinned as the
/// snapshot `<file>__theme_<palette>_<state>`.
pub fn assert_painted(file: &str, state: &str, palette: Palette, buf: &Buffer) {
    let painted = painted(buf, palette);
    let mut cells = painted.content.iter().zip(&buf.content);
    assert!(
        cells.all(|(p, b)| p.symbol() == b.symbol()),
        "{state}: painting {} changes the text",
        palette.name()
    );
    let name = format!("{file}__theme_{}_{state}", palette.name().replace(' ', "_"));
    in_snapshots(|| insta::assert_snapshot!(name, colour_map(&painted)));
}

/// [`assert_painted`] in every palette.
pub fn assert_every_palette(file: &str, state: &str, buf: &Buffer) {
    for palette in PALETTES {
        assert_painted(file, state, palette, buf);
    }
}

/// The contrast failures of `buf` painted in `palette`, named `state`.
pub fn contrast_in(state: &str, palette: Palette, buf: &Buffer) -> Vec<String> {
    contrast_failures(state, &painted(buf, palette), palette)
}

/// The contrast failures of `buf` painted in each colour palette, named `state`.
pub fn contrast_in_both(state: &str, buf: &Buffer) -> Vec<String> {
    [Palette::Dark, Palette::Light]
        .into_iter()
        .flat_map(|palette| contrast_in(state, palette, buf))
        .collect()
}

/// Runs `f` with snapshots named in full by their caller, in `tests/snapshots`.
fn in_snapshots(f: impl FnOnce()) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.bind(f);
}

thread_local! {
    static FRAMES: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// For test files whose snapshots pin the page's colour words (setup, traffic): checks
/// the frame's contrast in both colour palettes and snapshots how the light palette
/// paints it, named `<file>__light__<test>[_<n>]` after the running test.
pub fn check_themes(file: &str, buf: &Buffer) {
    let test = std::thread::current()
        .name()
        .unwrap_or("unnamed")
        .rsplit("::")
        .next()
        .unwrap_or("unnamed")
        .to_string();
    let n = FRAMES.with(|f| {
        f.set(f.get() + 1);
        f.get()
    });
    assert_contrast(contrast_in_both(&test, buf));
    let name = if n == 1 {
        format!("{file}__light__{test}")
    } else {
        format!("{file}__light__{test}_{n}")
    };
    in_snapshots(|| insta::assert_snapshot!(name, colour_map(&painted(buf, Palette::Light))));
}

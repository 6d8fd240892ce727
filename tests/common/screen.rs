//! A drawn frame read back as text, a line per row: what a snapshot holds and what a
//! failure's message shows.

use std::time::Instant;

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use vpx_efis::model::Model;
use vpx_efis::ui;
use vpx_efis::ui::state::{ControlState, ViewState};

/// The page for `model` and `view` at `now`, rendered on a `w`×`h` test terminal with
/// no motor key held (the controller at rest), in the page's colour words: before a
/// palette paints them (`ui::render`, not `ui::draw`).
pub fn rendered(model: &Model, view: &ViewState, now: Instant, w: u16, h: u16) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal
        .draw(|f| ui::render(f, model, view, &ControlState::default(), now))
        .unwrap();
    terminal.backend().buffer().clone()
}

/// Every cell's symbol as drawn, no-break spaces kept.
pub fn text(buf: &Buffer) -> String {
    let w = usize::from(buf.area.width).max(1);
    let mut out = String::new();
    for row in buf.content.chunks(w) {
        for cell in row {
            out.push_str(cell.symbol());
        }
        out.push('\n');
    }
    out
}

/// As [`text`], a no-break space read as the space it looks like.
pub fn plain_text(buf: &Buffer) -> String {
    text(buf).replace('\u{a0}', " ")
}

/// The cell where `needle` starts, on the first row that holds `on_line` and it;
/// compared cell by cell, since a cell's symbol may be several bytes.
pub fn find(buf: &Buffer, on_line: &str, needle: &str) -> (u16, u16) {
    let n: Vec<String> = needle.chars().map(String::from).collect();
    for y in 0..buf.area.height {
        let cells: Vec<&str> = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
        if !cells.concat().contains(on_line) {
            continue;
        }
        if let Some(x) = (0..=cells.len().saturating_sub(n.len()))
            .find(|&x| (0..n.len()).all(|k| cells[x + k] == n[k]))
        {
            return (x as u16, y);
        }
    }
    panic!(
        "{needle:?} not on a line with {on_line:?}:\n{}",
        plain_text(buf)
    );
}

/// The first row holding `needle`: its index and its text.
pub fn line_of(buf: &Buffer, needle: &str) -> Option<(u16, String)> {
    (0..buf.area.height).find_map(|y| {
        let line: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
        line.contains(needle).then_some((y, line))
    })
}

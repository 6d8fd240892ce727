//! The bottom line: the last notice for the person, then the keys that work on any
//! row (the selected row's own keys are in the detail panel).

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use super::state::{SortOrder, ViewState};
use super::theme;

pub fn render(frame: &mut Frame, area: Rect, view: &ViewState) {
    let mut spans = Vec::new();
    if let Some(n) = &view.notice {
        spans.push(Span::styled(format!("{n} "), theme::caution()));
        spans.push(Span::styled("│ ", theme::border()));
    }
    let sort = match view.sort {
        SortOrder::Pin => "A-Z",
        SortOrder::Alphabetical => "by pin",
    };
    for (k, what) in [
        ("↑↓", "select"),
        ("R", "reset system"),
        ("w", "wig-wag"),
        ("s", sort),
        ("?", "help"),
        ("q", "quit"),
    ] {
        spans.push(Span::styled(format!(" {k} "), theme::key()));
        spans.push(Span::raw(format!(" {what}  ")));
    }
    super::fast::lines(frame.buffer_mut(), area, &[Line::from(spans)]);
}

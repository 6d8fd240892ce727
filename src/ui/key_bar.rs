//! The bottom line: the last notice for the person, then the keys that work on any
//! row (the selected row's own keys are in the detail panel).

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use super::state::{SortOrder, ViewState};
use super::theme;

/// The most rows a notice takes: a long one (a motor stopped for moving against its
/// command, with what to do) is read whole rather than cut at the terminal's edge.
const NOTICE_ROWS: u16 = 3;

/// Rows the bottom line needs at `width`: the notice and the keys on one row when
/// they fit; else the notice word-wrapped on rows of its own above the keys.
pub fn height(view: &ViewState, width: u16) -> u16 {
    1 + notice_rows(view, width)
}

/// Rows the notice takes above the keys: none when it fits beside them.
fn notice_rows(view: &ViewState, width: u16) -> u16 {
    let Some(n) = &view.notice else { return 0 };
    let w = usize::from(width.max(1));
    let notice = n.chars().count() + 3;
    if notice + keys(view).width() <= w {
        return 0;
    }
    let rows = super::wrap::lines(&Line::raw(n), width.max(1)).len();
    u16::try_from(rows).unwrap_or(u16::MAX).min(NOTICE_ROWS)
}

fn keys(view: &ViewState) -> Line<'static> {
    let sort = match view.sort {
        SortOrder::Pin => "A-Z",
        SortOrder::Alphabetical => "by pin",
    };
    let mut spans = Vec::new();
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
    Line::from(spans)
}

pub fn render(frame: &mut Frame, area: Rect, view: &ViewState) {
    let above = notice_rows(view, area.width).min(area.height.saturating_sub(1));
    let keys = keys(view);
    match &view.notice {
        Some(n) if above > 0 => {
            let notice = Rect {
                height: above,
                ..area
            };
            let line = Line::from(Span::styled(n.clone(), theme::caution()));
            frame.render_widget(Paragraph::new(line).wrap(Wrap { trim: true }), notice);
            let row = Rect {
                y: area.y + above,
                height: area.height - above,
                ..area
            };
            super::unwrapped::lines(frame.buffer_mut(), row, &[keys]);
        }
        Some(n) => {
            let mut spans = vec![
                Span::styled(format!("{n} "), theme::caution()),
                Span::styled("│ ", theme::border()),
            ];
            spans.extend(keys.spans);
            super::unwrapped::lines(frame.buffer_mut(), area, &[Line::from(spans)]);
        }
        None => super::unwrapped::lines(frame.buffer_mut(), area, &[keys]),
    }
}

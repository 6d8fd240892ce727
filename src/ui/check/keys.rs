//! The check's bottom line: the page's last notice, then the keys that act now. The
//! flow says which keys act (`Prompt::keys`); when it asks nothing (or the check
//! stopped), the one key left is the one that leaves (Esc, as the flow reads it).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use crate::check::state::{CheckView, Step};
use crate::ui::state::ViewState;
use crate::ui::{theme, unwrapped};

/// The keys shown for `view`, with their words.
pub fn keys(view: &CheckView) -> Vec<(&'static str, &'static str)> {
    if view.interrupted.is_some() || view.step == Step::Done {
        // The check has ended: what is left is to read it, and to leave.
        // Shorter words when `w` must fit too: the line holds at 80 columns.
        let (leave, scroll, loads) = match (view.report_error.is_some(), view.show_loads) {
            (true, true) => ("leave", "↑↓ PgUp PgDn", "results"),
            (true, false) => ("leave", "↑↓ PgUp PgDn", "loads"),
            (false, true) => (
                "back to the device list",
                "↑↓ PgUp PgDn Home End",
                "results",
            ),
            (false, false) => (
                "back to the device list",
                "↑↓ PgUp PgDn Home End",
                "load analysis",
            ),
        };
        let mut k = vec![("Esc", leave)];
        if view.report_error.is_some() {
            k.push(("w", "write the report again"));
        }
        k.push((scroll, "scroll"));
        if view.loads.is_some() {
            k.push(("l", loads));
        }
        return k;
    }
    let asked = view
        .prompt
        .as_ref()
        .filter(|_| view.interrupted.is_none())
        .map(|p| p.keys.clone())
        .unwrap_or_default();
    if !asked.is_empty() {
        return asked;
    }
    vec![("Esc", "stop the check")]
}

pub fn render(buf: &mut Buffer, area: Rect, view: &CheckView, page: &ViewState) {
    let mut spans = Vec::new();
    if let Some(n) = &page.notice {
        spans.push(Span::styled(format!("{n} "), theme::caution()));
        spans.push(Span::styled("│ ", theme::border()));
    }
    for (k, what) in keys(view) {
        spans.push(Span::styled(format!(" {k} "), theme::key()));
        spans.push(Span::raw(format!(" {what}  ")));
    }
    unwrapped::lines(buf, area, &[Line::from(spans)]);
}

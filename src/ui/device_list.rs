//! The Appendix A device list: one row per enabled circuit, flaps and trim grouped
//! apart, coloured green=on, white=off, red=faulted.

use std::cmp::Ordering;
use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Cell, HighlightSpacing, Row, Table, TableState};

use super::state::{SortOrder, ViewState};
use super::{theme, values};
use crate::model::{Circuit, CircuitKind, Model};

/// Flaps and trims form their own group under the other devices (Appendix A).
fn is_motor(c: &Circuit) -> bool {
    matches!(c.kind, CircuitKind::Flaps | CircuitKind::Trim(_))
}

/// The rows in display order; see [`super::ordered_circuits`].
pub fn ordered(model: &Model, view: &ViewState, now: Instant) -> Vec<Circuit> {
    let mut rows = model.circuits(now);
    let by = |a: &Circuit, b: &Circuit| -> Ordering {
        let group = is_motor(a).cmp(&is_motor(b));
        let within = match view.sort {
            SortOrder::Pin => a.id.cmp(&b.id),
            SortOrder::Alphabetical => a
                .name
                .to_lowercase()
                .cmp(&b.name.to_lowercase())
                .then(a.id.cmp(&b.id)),
        };
        group.then(within)
    };
    rows.sort_by(by);
    rows
}

/// "A1"/"A2" beside the alternators, so a dual-alternator system shows which is which.
fn role(c: &Circuit) -> &'static str {
    match c.kind {
        CircuitKind::Alternator { primary: true } => "A1",
        CircuitKind::Alternator { primary: false } => "A2",
        _ => "",
    }
}

fn row(c: &Circuit) -> Row<'static> {
    let dim = theme::unknown();
    let live = |s: String, live: bool| {
        if live {
            Cell::from(s)
        } else {
            Cell::from(Span::styled(s, dim))
        }
    };
    Row::new(vec![
        Cell::from(c.name.clone()),
        Cell::from(Span::styled(c.pin, theme::label())),
        Cell::from(Span::styled(role(c), theme::info())),
        Cell::from(Span::styled(
            values::state_text(c.state),
            theme::state(c.state),
        )),
        live(values::amps(c.amps), c.amps.is_some()).style(Style::new()),
        // A spec left unknown by an unanswered write is "?" until re-read, never
        // the value from before the write.
        if c.spec_unknown {
            Cell::from(Span::styled("?A", theme::caution()))
        } else {
            Cell::from(
                c.breaker
                    .map_or_else(|| values::BLANK.into(), |b| format!("{b}A")),
            )
        },
        match c.kind {
            CircuitKind::Starter => Cell::from("VP-X"),
            CircuitKind::Flaps => Cell::from("flap"),
            CircuitKind::Trim(_) => Cell::from("trim"),
            _ if c.spec_unknown => Cell::from(Span::styled("?", theme::caution())),
            _ => Cell::from(values::switch_short(c.switch)),
        },
    ])
}

fn group_header(text: &'static str) -> Row<'static> {
    Row::new(vec![Cell::from(Line::from(Span::styled(
        text,
        theme::label().add_modifier(Modifier::ITALIC),
    )))])
}

pub fn render(frame: &mut Frame, area: Rect, rows: &[Circuit], view: &ViewState) {
    // `None` is the flaps & trim group header.
    let mut lines: Vec<Option<&Circuit>> = Vec::with_capacity(rows.len() + 1);
    let mut selected_index = None;
    let mut in_motors = false;
    for c in rows {
        if is_motor(c) && !in_motors {
            in_motors = true;
            lines.push(None);
        }
        if view.selected == Some(c.id) {
            selected_index = Some(lines.len());
        }
        lines.push(Some(c));
    }
    let sort = match view.sort {
        SortOrder::Pin => "by pin",
        SortOrder::Alphabetical => "A-Z",
    };
    let header = Row::new(["Device", "Pin", "", "State", "Amps", "CB", "Switch"])
        .style(theme::label().add_modifier(Modifier::UNDERLINED));
    let widths = [
        Constraint::Fill(1),
        Constraint::Length(9),
        Constraint::Length(2),
        Constraint::Length(13),
        Constraint::Length(4),
        Constraint::Length(3),
        Constraint::Length(6),
    ];
    // The offset the table would scroll to (rows are one line each), worked out here so
    // the title can say how many rows are off screen: a short terminal must never
    // hide a device silently.
    let visible = area.height.saturating_sub(2) as usize;
    let total = lines.len();
    let offset = selected_index.map_or(0, |i| (i + 1).saturating_sub(visible));
    // Only the rows on screen are built: the list is the widest part of the frame.
    let table_rows: Vec<Row> = lines
        .iter()
        .skip(offset)
        .take(visible)
        .map(|l| l.map_or_else(|| group_header("flaps/trim"), row))
        .collect();
    let below = total.saturating_sub(offset + visible);
    let mut more = Vec::new();
    if offset > 0 {
        more.push(format!("▲{offset} more"));
    }
    if below > 0 {
        more.push(format!("▼{below} more"));
    }
    let more = if more.is_empty() {
        Line::default()
    } else {
        Line::styled(format!(" {} ", more.join(" ")), theme::caution()).right_aligned()
    };
    let table = Table::new(table_rows, widths)
        .header(header)
        .column_spacing(1)
        .block(
            Block::new()
                .borders(Borders::TOP | Borders::RIGHT)
                .border_style(theme::border())
                .title(Span::styled(" Devices ", theme::panel_title()))
                .title(Span::styled(format!("{sort} "), theme::label()))
                .title(more),
        )
        .row_highlight_style(theme::selected_row())
        .highlight_symbol("▶")
        .highlight_spacing(HighlightSpacing::Always);
    let mut state = TableState::new().with_selected(selected_index.map(|i| i - offset));
    frame.render_stateful_widget(table, area, &mut state);
}

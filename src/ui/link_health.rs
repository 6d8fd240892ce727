//! Where the data comes from and how the link is doing: seconds since each broadcast,
//! decoder error counts, and COMMUNICATION LOST in words.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::panel;
use super::{theme, values};
use crate::model::{
    COMM_LOST_AFTER, Connection, FAULT_STATUS_QUIET_AFTER, FLAP_TRIM_STALE_AFTER, Model, Source,
};
use crate::protocol::message::{DeviceStatus, FaultStatus, FlapTrimStatus, Payload, SystemStatus};

pub fn height(width: u16) -> u16 {
    if width >= 60 { 4 } else { 5 }
}

/// The source label: SIMULATED and REPLAY loud, so neither is taken for an aircraft.
pub fn source_span(source: &Source) -> Span<'static> {
    match source {
        Source::Simulated { scenario } => {
            Span::styled(format!(" SIMULATED {scenario} "), theme::source_not_live())
        }
        Source::Replay { file } => {
            Span::styled(format!(" REPLAY {file} "), theme::source_not_live())
        }
        Source::Serial { path } => Span::styled(path.clone(), theme::panel_title()),
    }
}

pub fn connection_span(model: &Model, now: Instant) -> Span<'static> {
    match &model.connection {
        Connection::Connecting => Span::styled("connecting…", theme::caution()),
        Connection::Connected { since, .. } => {
            if model.comm_lost(now) {
                Span::styled("port open, COMMUNICATION LOST", theme::alert())
            } else {
                Span::styled(
                    format!("connected {}", values::age(now, *since)),
                    theme::on_off(true),
                )
            }
        }
        Connection::Lost { reason, since } => Span::styled(
            format!(
                "PORT LOST {} ago: {reason}; reopening",
                values::age(now, *since)
            ),
            theme::alert(),
        ),
    }
}

fn age_item(
    model: &Model,
    now: Instant,
    short: &str,
    name: &str,
    stale: std::time::Duration,
) -> Vec<Span<'static>> {
    let stat = model.link.rx.get(name);
    let (text, style) = match stat {
        None => ("never".to_string(), theme::unknown()),
        Some(s) => {
            let age = now.saturating_duration_since(s.last);
            let style = if age > stale {
                theme::alert()
            } else {
                Style::new()
            };
            (values::secs(age), style)
        }
    };
    vec![
        Span::styled(format!("{short} "), theme::label()),
        Span::styled(text, style),
    ]
}

/// Seconds since each broadcast type, one item each.
fn age_items(model: &Model, now: Instant) -> Vec<Vec<Span<'static>>> {
    let mut items = vec![
        age_item(model, now, "SYS", SystemStatus::NAME, COMM_LOST_AFTER),
        age_item(model, now, "DEV", DeviceStatus::NAME, COMM_LOST_AFTER),
        age_item(
            model,
            now,
            "F/T",
            FlapTrimStatus::NAME,
            FLAP_TRIM_STALE_AFTER,
        ),
    ];
    // icd-reading R9: FAULT_STATUS is only sent while a fault exists, so its silence
    // while status flows is good news, not a link problem.
    let fault_quiet = model
        .link
        .rx
        .get(FaultStatus::NAME)
        .is_none_or(|s| now.saturating_duration_since(s.last) > FAULT_STATUS_QUIET_AFTER);
    let flt = if fault_quiet && !model.comm_lost(now) {
        Span::styled("quiet = no faults", theme::on_off(true))
    } else if let Some(s) = model.link.rx.get(FaultStatus::NAME) {
        Span::raw(values::age(now, s.last))
    } else {
        Span::styled("never", theme::unknown())
    };
    items.push(vec![Span::styled("FLT ", theme::label()), flt]);
    items
}

/// Items side by side on one line, two spaces in `gap` style apart.
fn joined(items: Vec<Vec<Span<'static>>>, gap: Style) -> Line<'static> {
    let mut spans = Vec::new();
    for (i, item) in items.into_iter().enumerate() {
        if i > 0 {
            spans.push(Span::styled("  ", gap));
        }
        spans.extend(item);
    }
    Line::from(spans)
}

/// Decoder error counts and what we sent, one item each; `long` spells each counter
/// out.
fn count_items(model: &Model, long: bool) -> Vec<Vec<Span<'static>>> {
    let d = &model.link.decoder;
    let errors = d.errors() + model.link.malformed;
    let err_style = if errors > 0 {
        theme::caution()
    } else {
        Style::new()
    };
    let text = if long {
        format!(
            "checksum {} length {} unknown {} malformed {} skipped {} B",
            d.bad_checksum, d.bad_length, d.unknown_message, model.link.malformed, d.skipped_bytes
        )
    } else if errors == 0 {
        "0".to_string()
    } else {
        format!(
            "{errors} (cksum {} len {} unk {} bad {})",
            d.bad_checksum, d.bad_length, d.unknown_message, model.link.malformed
        )
    };
    let mut out = vec![
        vec![
            Span::styled("errors ", theme::label()),
            Span::styled(text, err_style),
        ],
        vec![Span::styled(
            format!("sent {}", model.link.tx_frames),
            theme::label(),
        )],
    ];
    if model.link.write_errors > 0 {
        out.push(vec![Span::styled(
            format!("({} write errors)", model.link.write_errors),
            theme::alert(),
        )]);
    }
    out
}

/// The width of spans on screen.
fn width(spans: &[Span]) -> usize {
    spans.iter().map(Span::width).sum()
}

/// The link's items flowed into rows of `width` columns: "Link" first, two spaces
/// between items, an item never split (one wider than a row is cut at its end), the
/// counts after a "│" when they share the ages' row.
fn flowed(model: &Model, now: Instant, row_width: u16) -> Vec<Line<'static>> {
    let row_width = usize::from(row_width);
    let mut rows: Vec<Vec<Span<'static>>> = vec![vec![Span::styled("Link", theme::panel_title())]];
    let ages = age_items(model, now).into_iter().map(|i| (i, false));
    // The first count goes after a bar, so ages and counts read as two groups.
    let counts = count_items(model, false)
        .into_iter()
        .enumerate()
        .map(|(k, i)| (i, k == 0));
    for (k, (item, after_bar)) in ages.chain(counts).enumerate() {
        let gap = if after_bar {
            vec![Span::styled(" │ ", theme::border())]
        } else if k == 0 {
            vec![Span::raw(" ")]
        } else {
            vec![Span::raw("  ")]
        };
        let row = rows.last_mut().expect("one row at least");
        let fits = width(row) + width(&gap) + width(&item) <= row_width;
        if fits {
            row.extend(gap);
            row.extend(item);
        } else {
            // A continued row starts under the first item, past "Link ".
            let mut next = vec![Span::raw("     ")];
            next.extend(item);
            rows.push(next);
        }
    }
    rows.into_iter().map(Line::from).collect()
}

/// Rows the link needs as lines [`render_line`] draws in an area `width` wide.
pub fn line_rows(model: &Model, now: Instant, width: u16) -> u16 {
    flowed(model, now, width.saturating_sub(1)).len() as u16
}

/// The link as lines at the foot of the left column, for terminals too short for the
/// panel (the title bar already shows the source and connection): as many rows as
/// [`line_rows`] says, each ending at the column's edge with its border.
pub fn render_line(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    if area.is_empty() {
        return;
    }
    let inner = Rect {
        width: area.width - 1,
        ..area
    };
    let lines = flowed(model, now, inner.width);
    let buf = frame.buffer_mut();
    super::unwrapped::lines(buf, inner, &lines);
    for y in area.top()..area.bottom() {
        super::unwrapped::put(
            buf,
            area.right() - 1,
            y,
            ratatui::symbols::line::VERTICAL,
            1,
            theme::border(),
        );
    }
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let lines = vec![
        Line::from(vec![
            source_span(&model.source),
            Span::raw(" "),
            connection_span(model, now),
        ]),
        joined(age_items(model, now), Style::new()),
        joined(count_items(model, area.width >= 72), theme::label()),
    ];
    let inner = panel::titled(frame.buffer_mut(), area, " Link ");
    super::unwrapped::lines(frame.buffer_mut(), inner, &lines);
}

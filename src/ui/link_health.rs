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

fn age_span(
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
        Span::raw("  "),
    ]
}

/// Seconds since each broadcast type.
fn ages(model: &Model, now: Instant) -> Vec<Span<'static>> {
    let mut ages = Vec::new();
    ages.extend(age_span(
        model,
        now,
        "SYS",
        SystemStatus::NAME,
        COMM_LOST_AFTER,
    ));
    ages.extend(age_span(
        model,
        now,
        "DEV",
        DeviceStatus::NAME,
        COMM_LOST_AFTER,
    ));
    ages.extend(age_span(
        model,
        now,
        "F/T",
        FlapTrimStatus::NAME,
        FLAP_TRIM_STALE_AFTER,
    ));
    // Reading note 9: FAULT_STATUS is only sent while a fault exists, so its silence
    // while status flows is good news, not a link problem.
    let fault_quiet = model
        .link
        .rx
        .get(FaultStatus::NAME)
        .is_none_or(|s| now.saturating_duration_since(s.last) > FAULT_STATUS_QUIET_AFTER);
    ages.push(Span::styled("FLT ", theme::label()));
    if fault_quiet && !model.comm_lost(now) {
        ages.push(Span::styled("quiet = no faults", theme::on_off(true)));
    } else if let Some(s) = model.link.rx.get(FaultStatus::NAME) {
        ages.push(Span::raw(values::age(now, s.last)));
    } else {
        ages.push(Span::styled("never", theme::unknown()));
    }
    ages
}

/// Decoder error counts and what we sent; `long` spells each counter out.
fn counts(model: &Model, long: bool) -> Vec<Span<'static>> {
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
        Span::styled("errors ", theme::label()),
        Span::styled(text, err_style),
        Span::styled(format!("  sent {}", model.link.tx_frames), theme::label()),
    ];
    if model.link.write_errors > 0 {
        out.push(Span::styled(
            format!(" ({} write errors)", model.link.write_errors),
            theme::alert(),
        ));
    }
    out
}

/// The link as one full-width line, for terminals too short for the panel (the title
/// bar already shows the source and connection).
pub fn render_line(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let mut spans = vec![Span::styled("Link ", theme::panel_title())];
    spans.extend(ages(model, now));
    spans.push(Span::styled(" │ ", theme::border()));
    spans.extend(counts(model, false));
    super::fast::lines(frame.buffer_mut(), area, &[Line::from(spans)]);
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let lines = vec![
        Line::from(vec![
            source_span(&model.source),
            Span::raw(" "),
            connection_span(model, now),
        ]),
        Line::from(ages(model, now)),
        Line::from(counts(model, area.width >= 72)),
    ];
    let inner = panel::titled(frame.buffer_mut(), area, " Link ");
    super::fast::lines(frame.buffer_mut(), inner, &lines);
}

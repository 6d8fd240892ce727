//! The COMMUNICATION LOST banner (Appendix A: "clearly indicate the condition"), and the
//! quieter "waiting" banner before the unit has ever been heard.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::Line;
use ratatui::widgets::Paragraph;

use super::{theme, values};
use crate::model::{COMM_LOST_AFTER, Connection, Model};

pub const LOST_TEXT: &str = "COMMUNICATION LOST";

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Banner {
    /// Data stopped, the port failed, or a port opened but the unit never spoke.
    Lost { why: String },
    /// Nothing heard yet, and not yet long enough to call it lost.
    Waiting { why: String },
}

pub fn banner(model: &Model, now: Instant) -> Option<Banner> {
    if let Connection::Lost { reason, since } = &model.connection {
        return Some(Banner::Lost {
            why: format!(
                "serial port failed {} ago ({reason}); reopening it. Values blanked.",
                values::age(now, *since)
            ),
        });
    }
    if !model.comm_lost(now) {
        return None;
    }
    let last = [
        model.system_status.map(|s| s.at),
        model.device_status.map(|s| s.at),
    ]
    .into_iter()
    .flatten()
    .max();
    if let Some(last) = last {
        return Some(Banner::Lost {
            why: format!(
                "no status from the VP-X for {}; values blanked until data returns.",
                values::age(now, last)
            ),
        });
    }
    match &model.connection {
        Connection::Connected { port, since }
            if now.saturating_duration_since(*since) > COMM_LOST_AFTER =>
        {
            Some(Banner::Lost {
                why: format!(
                    "{port} open for {}, nothing heard: check power, wiring and baud.",
                    values::age(now, *since)
                ),
            })
        }
        Connection::Connected { port, .. } => Some(Banner::Waiting {
            why: format!("{port} open, waiting for the VP-X's first status…"),
        }),
        _ => Some(Banner::Waiting {
            why: "connecting to the VP-X…".into(),
        }),
    }
}

pub fn height(banner: Option<&Banner>, screen_height: u16) -> u16 {
    match banner {
        None => 0,
        Some(_) if screen_height >= 40 => 5,
        Some(_) => 3,
    }
}

/// Letter-spaced, so the words read as a banner even in a small terminal.
fn spaced(s: &str) -> String {
    s.chars()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

pub fn render(frame: &mut Frame, area: Rect, banner: &Banner) {
    let (title, why, style): (&str, &str, Style) = match banner {
        Banner::Lost { why } => (LOST_TEXT, why, theme::banner_lost()),
        Banner::Waiting { why } => ("NO DATA YET", why, theme::banner_waiting()),
    };
    let mut lines = vec![
        Line::raw(""),
        Line::raw(spaced(title)),
        Line::raw(why.to_string()),
    ];
    if area.height >= 5 {
        lines.insert(2, Line::raw(""));
    }
    frame.render_widget(Paragraph::new(lines).style(style).centered(), area);
}

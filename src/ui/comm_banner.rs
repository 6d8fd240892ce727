//! The COMMUNICATION LOST banner (Appendix A: "clearly indicate the condition"), and the
//! quieter "waiting" banner before the unit has ever been heard.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::Line;
use ratatui::widgets::Paragraph;

use super::{theme, values};
use crate::model::{COMM_LOST_AFTER, Connection, Model, Source};

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
        // What failed, by what the page opened: a TCP bridge is not a serial port.
        let what = match &model.source {
            Source::Serial { path } if path.starts_with("tcp://") => {
                format!("the network bridge at {}", &path["tcp://".len()..])
            }
            Source::Serial { path } => format!("the serial port {path}"),
            Source::Simulated { .. } => "the link to the virtual VP-X".into(),
            Source::Replay { file } => format!("the replay of {file}"),
        };
        return Some(Banner::Lost {
            why: format!(
                "{what} failed {} ago: {}. Reopening it; values blanked.",
                values::age(now, *since),
                reason.trim_end().trim_end_matches('.')
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

/// Rows for the banner on a screen `screen_height` × `width`: the reason wraps at
/// words onto as many rows as it needs, never cut mid-word.
pub fn height(banner: Option<&Banner>, screen_height: u16, width: u16) -> u16 {
    let Some(b) = banner else {
        return 0;
    };
    let extra = why_lines(b, width).len().saturating_sub(1) as u16;
    let base: u16 = if screen_height >= 40 { 5 } else { 3 };
    base.saturating_add(extra)
}

fn why_lines(banner: &Banner, width: u16) -> Vec<String> {
    let why = match banner {
        Banner::Lost { why } | Banner::Waiting { why } => why,
    };
    super::wrap::text(why, usize::from(width.saturating_sub(2)))
}

/// Letter-spaced, so the words read as a banner even in a small terminal.
fn spaced(s: &str) -> String {
    s.chars()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

pub fn render(frame: &mut Frame, area: Rect, banner: &Banner) {
    let (title, style): (&str, Style) = match banner {
        Banner::Lost { .. } => (LOST_TEXT, theme::banner_lost()),
        Banner::Waiting { .. } => ("NO DATA YET", theme::banner_waiting()),
    };
    let mut lines = vec![Line::raw(""), Line::raw(spaced(title))];
    let why = why_lines(banner, area.width);
    // The blank line between title and reason only where the rows allow it.
    if area.height as usize >= 4 + why.len() {
        lines.push(Line::raw(""));
    }
    lines.extend(why.into_iter().map(Line::raw));
    frame.render_widget(Paragraph::new(lines).style(style).centered(), area);
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::Terminal;
    use ratatui::backend::TestBackend;

    fn lost(source: Source, reason: &str) -> (Model, Instant) {
        let t0 = Instant::now();
        let mut m = Model::new(source);
        m.note_link_lost(t0, reason.into());
        (m, t0 + std::time::Duration::from_secs(3))
    }

    /// The banner's rows at `w` columns, as drawn.
    fn drawn(b: &Banner, w: u16, screen_h: u16) -> Vec<String> {
        let h = height(Some(b), screen_h, w);
        let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
        term.draw(|f| render(f, f.area(), b)).unwrap();
        let buf = term.backend().buffer().clone();
        (0..h)
            .map(|y| {
                (0..w)
                    .map(|x| buf[(x, y)].symbol().to_string())
                    .collect::<String>()
                    .trim()
                    .to_string()
            })
            .collect()
    }

    /// A TCP bridge that drops is said as the bridge, not a serial port; the reason's
    /// own full stop is not doubled into ".;"; and at 80, 120 and 200 columns the
    /// reason wraps at words, every word whole on screen.
    #[test]
    fn what_failed_is_named_and_the_reason_wraps_at_words() {
        let reason = "the device was removed: check that the USB-serial cable is plugged in.";
        let (m, now) = lost(
            Source::Serial {
                path: "tcp://hangar-pi:4001".into(),
            },
            reason,
        );
        let b = banner(&m, now).unwrap();
        let Banner::Lost { why } = &b else {
            panic!("{b:?}")
        };
        assert_eq!(
            why,
            "the network bridge at hangar-pi:4001 failed 3.0 s ago: the device was removed: \
             check that the USB-serial cable is plugged in. Reopening it; values blanked."
        );
        let (m, now) = lost(
            Source::Serial {
                path: "/dev/ttyUSB0".into(),
            },
            "read failed.",
        );
        let Some(Banner::Lost { why }) = banner(&m, now) else {
            panic!()
        };
        assert!(
            why.starts_with(
                "the serial port /dev/ttyUSB0 failed 3.0 s ago: read failed. Reopening"
            ),
            "{why}"
        );
        for w in [80, 120, 200] {
            for screen_h in [24, 50] {
                let rows = drawn(&b, w, screen_h);
                let text = rows.join(" ");
                let words: Vec<&str> = text.split_whitespace().collect();
                let Banner::Lost { why } = &b else { panic!() };
                for word in why.split_whitespace() {
                    assert!(
                        words.contains(&word),
                        "{w}×{screen_h}: {word:?} cut: {rows:#?}"
                    );
                }
                assert!(!text.contains(".;"), "{text}");
            }
        }
    }
}

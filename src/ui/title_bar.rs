//! The top line: the Vertical Power mark (Appendix A asks for it on the page), the
//! source, the link state and the unit's version.
//!
//! A narrow terminal never gets a word cut in half: the line is built whole pieces at a
//! time, dropping the least needed first ("VP-X electrical", shortened to "electrical"
//! where that fits, then the mark), shortening
//! a long port path, scenario or capture name with an ellipsis in its middle, and
//! saying the connection state in its short form. The connection state, SIMULATED or
//! REPLAY, and the unit's version always stay.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::{link_health, theme, values};
use crate::model::{Connection, Model, Source};

pub const MARK: &str = " VERTICAL POWER ";
const TITLE: &str = " VP-X electrical ";
/// The page's name where the whole one does not fit: the mark beside it already says
/// whose unit, and the version at the end which one.
const SHORT_TITLE: &str = " electrical ";
/// The shortest a shortened name gets: enough for "/dev/…port0".
const MIN_NAME: usize = 12;

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let l = with_aircraft(line(model, now, area.width), model, area.width as usize);
    super::unwrapped::lines(frame.buffer_mut(), area, &[l]);
}

/// `s` in at most `max` characters, the middle replaced by "…" if it must be
/// shortened. The end is kept longer than the start: a by-id path's serial number
/// and port are at its end.
pub fn middle_ellipsis(s: &str, max: usize) -> String {
    let n = s.chars().count();
    if n <= max {
        return s.to_string();
    }
    if max <= 1 {
        return "…".chars().take(max).collect();
    }
    let head = (max - 1) * 2 / 5;
    let tail = max - 1 - head;
    let start: String = s.chars().take(head).collect();
    let end: String = s.chars().skip(n - tail).collect();
    format!("{start}…{end}")
}

/// The source as (label, name, style): the name is the part that may be shortened.
fn source_parts(source: &Source) -> (&'static str, &str, Style) {
    match source {
        Source::Simulated { scenario } => (" SIMULATED ", scenario, theme::source_not_live()),
        Source::Replay { file } => (" REPLAY ", file, theme::source_not_live()),
        Source::Serial { path } => ("", path, theme::panel_title()),
    }
}

/// The connection state without the port's error text (the banner has it).
fn connection_short(model: &Model, now: Instant) -> Span<'static> {
    match &model.connection {
        Connection::Lost { since, .. } => Span::styled(
            format!("PORT LOST {} ago; reopening", values::age(now, *since)),
            theme::alert(),
        ),
        _ => link_health::connection_span(model, now),
    }
}

/// The title line for a terminal `width` columns wide.
pub fn line(model: &Model, now: Instant, width: u16) -> Line<'static> {
    let width = width as usize;
    let (label, name, source_style) = source_parts(&model.source);
    let version = model.version.map(|v| {
        let v = v.value;
        Span::styled(
            format!(
                "  {} sw {}.{}",
                v.hardware_version.name(),
                v.software_major,
                v.software_minor
            ),
            theme::label(),
        )
    });
    let build = |mark: bool, title: Option<&'static str>, name_max: usize, short: bool| {
        let mut spans = Vec::new();
        if mark {
            spans.push(Span::styled(MARK, theme::brand()));
        }
        if let Some(title) = title {
            spans.push(Span::styled(title, theme::panel_title()));
        } else if mark {
            spans.push(Span::raw(" "));
        }
        let name = middle_ellipsis(name, name_max);
        let trail = if label.is_empty() || name.is_empty() {
            ""
        } else {
            " "
        };
        spans.push(Span::styled(format!("{label}{name}{trail}"), source_style));
        spans.push(Span::raw(" "));
        spans.push(if short {
            connection_short(model, now)
        } else {
            link_health::connection_span(model, now)
        });
        if let Some(v) = &version {
            spans.push(v.clone());
        }
        Line::from(spans)
    };
    let full = name.chars().count();
    // Least needed first: the page's name, the path's middle, the port's error text,
    // the mark, and last whatever of the name is left.
    let mut tries = vec![
        (true, Some(TITLE), full, false),
        (true, Some(SHORT_TITLE), full, false),
        (true, None, full, false),
    ];
    for keep_mark in [true, false] {
        for short in [false, true] {
            tries.push((keep_mark, None, usize::MAX, short));
        }
    }
    for (mark, title, name_max, short) in tries {
        let probe = build(mark, title, full, short);
        let over = probe.width().saturating_sub(width);
        let fitted = if name_max == usize::MAX {
            full.saturating_sub(over)
        } else {
            name_max
        };
        if over == 0 || (name_max == usize::MAX && fitted >= MIN_NAME.min(full)) {
            return build(mark, title, fitted, short);
        }
    }
    build(false, None, 0, true)
}

/// The title line with the aircraft the page records under ([`crate::model::Aircraft`])
/// where the room left allows: its registration, or "aircraft not named
/// (--aircraft)"; and "this unit was in N123AB until 2026-11-03" after it when the
/// unit was seen in another aircraft. What does not fit is left out whole (the event
/// log says it too).
fn with_aircraft(mut l: Line<'static>, model: &Model, width: usize) -> Line<'static> {
    let Some(a) = &model.aircraft else {
        return l;
    };
    let (name, was) = a.words();
    let style = if a.registration.is_some() {
        theme::panel_title()
    } else {
        theme::caution()
    };
    let mut pieces = vec![Span::styled(format!("  {name}"), style)];
    if let Some(w) = was {
        pieces.push(Span::styled(format!("  {w}"), theme::caution()));
    }
    // At the end of the line, after the version: the words that always stay keep
    // their place.
    for p in pieces {
        if l.width() + p.width() <= width {
            l.spans.push(p);
        } else {
            break;
        }
    }
    l
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::{HardwareVersion, Version};
    use std::time::Duration;

    const BY_ID: &str = "/dev/serial/by-id/usb-FTDI_FT232R_USB_UART_A50285BI-if00-port0";

    fn model(source: Source, lost: bool) -> (Model, Instant) {
        let t0 = Instant::now();
        let mut m = Model::new(source);
        m.note_connected(t0, "x".into());
        m.version = Some(crate::model::Stamped::new(
            Version {
                hardware_version: HardwareVersion::VpxPro,
                software_major: 2,
                software_minor: 1,
            },
            t0,
        ));
        if lost {
            m.note_link_lost(t0, "No such file or directory (os error 2)".into());
        }
        (m, t0 + Duration::from_secs(3))
    }

    fn text(l: &Line) -> String {
        l.spans.iter().map(|s| s.content.as_ref()).collect()
    }

    #[test]
    fn middle_ellipsis_keeps_both_ends() {
        assert_eq!(middle_ellipsis("abc", 5), "abc");
        let s = middle_ellipsis(BY_ID, 30);
        assert_eq!(s.chars().count(), 30);
        assert!(
            s.starts_with("/dev/serial") && s.ends_with("-if00-port0"),
            "{s}"
        );
        assert!(s.contains('…'));
    }

    #[test]
    fn a_long_by_id_path_at_80_columns_keeps_state_and_version_whole() {
        let (m, now) = model(Source::Serial { path: BY_ID.into() }, false);
        let l = line(&m, now, 80);
        let t = text(&l);
        assert!(l.width() <= 80, "{t}");
        let state = link_health::connection_span(&m, now).content.to_string();
        assert!(t.contains(&state), "{state:?} missing: {t}");
        assert!(t.ends_with("VP-X Pro sw 2.1"), "{t}");
        assert!(t.contains('…') && t.contains("port0"), "{t}");
        assert!(
            t.contains("VERTICAL POWER"),
            "the mark stays while it fits: {t}"
        );
    }

    #[test]
    fn the_version_is_never_cut_at_80_columns() {
        let (m, now) = model(
            Source::Simulated {
                scenario: "demo".into(),
            },
            false,
        );
        let t = text(&line(&m, now, 80));
        assert!(t.contains("SIMULATED demo") && t.ends_with("sw 2.1"), "{t}");
    }

    /// Where the whole name does not fit, the short one takes the room it would have
    /// left blank; the name goes only where neither fits.
    #[test]
    fn the_page_name_is_shortened_before_it_is_dropped() {
        let demo = Source::Simulated {
            scenario: "demo".into(),
        };
        for source in [demo, Source::Serial { path: BY_ID.into() }] {
            let (m, now) = model(source, false);
            for w in 60..=200u16 {
                let l = line(&m, now, w);
                let t = text(&l);
                // The name goes before the mark: without the mark there is no name.
                if t.contains("VERTICAL POWER") && !t.contains("electrical") {
                    let blank = usize::from(w) - l.width();
                    assert!(
                        blank < SHORT_TITLE.len() - 1,
                        "{w}: {blank} columns left blank without the page's name: {t}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_width_keeps_the_words_that_matter_whole() {
        for (source, label) in [
            (Source::Serial { path: BY_ID.into() }, "port0"),
            (
                Source::Replay {
                    file: "captures/2024-05-01-hangar-engine-run-with-strobe-short.vpxcap".into(),
                },
                "REPLAY",
            ),
        ] {
            let (m, now) = model(source, true);
            for w in 60..=200u16 {
                let l = line(&m, now, w);
                let t = text(&l);
                assert!(l.width() <= w as usize, "{w}: {t}");
                for must in [label, "PORT LOST", "reopening", "VP-X Pro sw 2.1"] {
                    assert!(t.contains(must), "{w}: {must:?} missing from {t}");
                }
            }
        }
    }
}

//! `vpx-efis log --circuit NAME`: one circuit's current at every check of the aircraft,
//! as a small chart for the terminal. ratatui's own horizontal [`BarChart`], drawn into
//! a buffer and printed as plain text, so it reads the same piped into a file, on a
//! light or a dark terminal and with NO_COLOR: each bar's figure is written beside it
//! in its label, and a change the trend rule marks ([`crate::check::trend`]) is said
//! in words.

use std::time::SystemTime;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Bar, BarChart, Widget};

use crate::check::trend::{self, amps_text, change_text};

/// The circuit at one check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Point {
    pub when: SystemTime,
    /// Its pin at that check (a load may move).
    pub pin: String,
    /// Its current in tenths of an amp; `None`: no reading at that check.
    pub tenths: Option<u16>,
    /// The check's verdict for it, in words ("PASS", "FAIL: no current while on").
    pub verdict: String,
}

/// "2026-12-01 18:30": the check's time in UTC, to the minute.
pub fn minute(when: SystemTime) -> String {
    let t = crate::utc::utc_text(when);
    format!("{} {}", &t[..10], &t[11..16])
}

/// The label of one bar: the time, the current and, against the check before, the
/// change (with the words when the rule marks it).
fn label(p: &Point, before: Option<u16>, pin_changed: bool) -> String {
    let mut l = format!(
        "{}  {:>7}",
        minute(p.when),
        p.tenths.map_or_else(|| "none".into(), amps_text)
    );
    if let (Some(b), Some(n)) = (before, p.tenths) {
        l.push_str(&format!(" {:>7}", change_text(b, n)));
        if trend::changed(b, n) {
            l.push_str(" ⚠ changed");
        }
    }
    if pin_changed {
        l.push_str(&format!(" (now on pin {})", p.pin));
    }
    if p.tenths.is_none() {
        l.push_str(&format!(" ({})", p.verdict));
    }
    l
}

/// The chart, `width` columns wide, one line per check, oldest first, under a line
/// naming the circuit. Lines end without trailing blanks.
pub fn chart(name: &str, points: &[Point], width: u16) -> String {
    let mut out = format!("{name}: current at each check (UTC)\n");
    if points.is_empty() {
        out.push_str("No check has measured it yet.\n");
        return out;
    }
    let mut before = None;
    let mut last_pin: Option<&str> = None;
    let labels: Vec<String> = points
        .iter()
        .map(|p| {
            let moved = last_pin.is_some_and(|l| l != p.pin);
            let l = label(p, before, moved);
            if p.tenths.is_some() {
                before = p.tenths;
            }
            last_pin = Some(&p.pin);
            l
        })
        .collect();
    // Room for the bars: at least ten columns, however long the labels.
    let label_w = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let width = width.max(u16::try_from(label_w + 11).unwrap_or(u16::MAX));
    let bars: Vec<Bar> = points
        .iter()
        .zip(labels)
        .map(|(p, l)| {
            Bar::default()
                .value(u64::from(p.tenths.unwrap_or(0)))
                .label(l)
                // The figure is in the label; no text over the bar.
                .text_value(String::new())
        })
        .collect();
    let max = points.iter().filter_map(|p| p.tenths).max().unwrap_or(0);
    let height = u16::try_from(bars.len()).unwrap_or(u16::MAX);
    let area = Rect::new(0, 0, width, height);
    let mut buf = Buffer::empty(area);
    BarChart::horizontal(bars)
        .bar_width(1)
        .bar_gap(0)
        .max(u64::from(max.max(1)))
        .render(area, &mut buf);
    for y in 0..area.height {
        let line: String = (0..area.width)
            .map(|x| buf[(x, y)].symbol().to_string())
            .collect();
        out.push_str(line.trim_end());
        out.push('\n');
    }
    // What the mark means, in full, once.
    if out.contains("⚠ changed") {
        out.push_str(&format!(
            "⚠ changed: changed since the check before, by over {} % and at least {}.\n",
            trend::CHANGED_PERCENT,
            amps_text(trend::CHANGED_MIN_TENTHS as u16)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn at(day: u64) -> SystemTime {
        // 2026-12-01T18:30:00Z, then a day apart.
        std::time::UNIX_EPOCH + Duration::from_secs(1_796_149_800 + day * 86_400)
    }

    fn point(day: u64, tenths: Option<u16>) -> Point {
        Point {
            when: at(day),
            pin: "J5-3".into(),
            tenths,
            verdict: if tenths.is_some() {
                "PASS".into()
            } else {
                "FAIL: faulted".into()
            },
        }
    }

    #[test]
    fn each_check_is_a_line_with_its_figure_and_a_bar_to_scale() {
        let text = chart(
            "Landing Lt",
            &[point(0, Some(61)), point(1, None), point(2, Some(75))],
            60,
        );
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "Landing Lt: current at each check (UTC)");
        assert!(lines[1].starts_with("2026-12-01 18:30    6.1 A "), "{text}");
        assert!(
            lines[2].starts_with("2026-12-02 18:30     none (FAIL: faulted)"),
            "{text}"
        );
        // Compared with the last reading (6.1 A), not with the check that got none.
        assert!(
            lines[3].starts_with("2026-12-03 18:30    7.5 A   +23 % ⚠ changed "),
            "{text}"
        );
        assert_eq!(
            lines[4],
            "⚠ changed: changed since the check before, by over 20 % and at least 0.3 A."
        );
        // The largest reading fills the bars' room; 6.1 A about 61/75 of it.
        let bars = |l: &str| l.chars().filter(|&c| c == '█').count();
        let full = bars(lines[3]);
        assert!(full >= 10, "{text}");
        assert_eq!(bars(lines[2]), 0);
        let part = bars(lines[1]);
        assert!(
            part * 100 / full >= 75 && part * 100 / full <= 87,
            "{part} of {full}\n{text}"
        );
        assert!(text.lines().all(|l| !l.ends_with(' ')));
    }

    #[test]
    fn no_check_says_so() {
        assert_eq!(
            chart("Strobe", &[], 60),
            "Strobe: current at each check (UTC)\nNo check has measured it yet.\n"
        );
    }
}

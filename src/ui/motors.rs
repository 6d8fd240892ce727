//! Flaps and trim: each position on a gauge marked with its up/down ends, the trim
//! neutral and the flap midpoints; motor running, faults, overspeed, flap-down
//! inhibit; and which way the page knows a held key was let go.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use super::panel;
use super::state::{ControlState, ReleaseMode, RepeatTiming};
use super::{theme, values};
use crate::model::{Model, Motor, TrimKind};
use crate::protocol::message::FlapTrimStatus;

pub const POSITION_MARK: &str = "●";

fn shown(model: &Model, now: Instant) -> Vec<Motor> {
    Motor::ALL
        .into_iter()
        .filter(|m| model.is_shown(m.device_id(), now))
        .collect()
}

pub fn height(model: &Model, now: Instant, width: u16) -> u16 {
    let n = shown(model, now).len().max(1) as u16;
    let chars: usize = flags(model, now)
        .iter()
        .map(|(t, _)| t.chars().count() + 3)
        .sum();
    let flag_lines = chars.div_ceil(width.max(1) as usize) as u16;
    1 + n + flag_lines + 1
}

/// A motor's gauge geometry, in the sensor's raw 0–255 units.
struct Gauge {
    label: &'static str,
    left: &'static str,
    right: &'static str,
    /// The sensor value at the left end ("up") and the right end ("down").
    from: u8,
    to: u8,
    marks: Vec<(u8, &'static str)>,
    position: u8,
    running: bool,
    faulted: bool,
}

/// The gauge's label and the words at its ends.
fn names(m: Motor) -> (&'static str, &'static str, &'static str) {
    match m {
        Motor::Flaps => ("Flaps", "UP", "DN"),
        Motor::Trim(TrimKind::Pitch) => ("Pitch", "UP", "DN"),
        // Roll "up" is left (ICD Table 30 note 2).
        Motor::Trim(TrimKind::Roll) => ("Roll", " L", "R "),
    }
}

fn gauge(m: Motor, ft: &FlapTrimStatus) -> Gauge {
    let a = ft.axis(m.axis());
    let (label, left, right) = names(m);
    let marks = match a.neutral {
        Some(neutral) => vec![(neutral, "N")],
        None => vec![(ft.flap_midpoint_1, "1"), (ft.flap_midpoint_2, "2")],
    };
    Gauge {
        label,
        left,
        right,
        from: a.up,
        to: a.down,
        marks,
        position: a.position,
        running: a.motor_running,
        faulted: a.fault || a.fault_code.is_fault(),
    }
}

/// Where `v` falls on a track of `w` cells from `from` to `to` (either may be larger:
/// an inverted installation has "up" above "down"). `None` when outside the travel.
fn cell(v: u8, from: u8, to: u8, w: usize) -> Option<usize> {
    let (lo, hi) = (from.min(to), from.max(to));
    if !(lo..=hi).contains(&v) || w == 0 {
        return None;
    }
    if from == to {
        return Some(0);
    }
    let frac = (f64::from(v) - f64::from(from)) / (f64::from(to) - f64::from(from));
    Some(((frac * (w - 1) as f64).round() as usize).min(w - 1))
}

/// Percent of travel from the up end; clamped, since a sensor can read past an end.
fn percent(g: &Gauge) -> u8 {
    if g.from == g.to {
        return 0;
    }
    let frac = (f64::from(g.position) - f64::from(g.from)) / (f64::from(g.to) - f64::from(g.from));
    (frac.clamp(0.0, 1.0) * 100.0).round() as u8
}

fn gauge_line(m: Motor, ft: Option<&FlapTrimStatus>, width: u16) -> Line<'static> {
    // label 6, ends 2+2, status 5
    let track_w = (width as usize).saturating_sub(6 + 4 + 1 + 5).max(3);
    let Some(ft) = ft else {
        return Line::from(vec![
            Span::styled(format!("{:<6}", names(m).0), theme::label()),
            Span::styled(
                format!("{:^w$}", values::BLANK, w = track_w + 4),
                theme::unknown(),
            ),
        ]);
    };
    let g = gauge(m, ft);
    let mut track: Vec<(String, Style)> = vec![("─".into(), theme::border()); track_w];
    for (v, mark) in &g.marks {
        if let Some(i) = cell(*v, g.from, g.to, track_w) {
            track[i] = ((*mark).into(), theme::label());
        }
    }
    let pos_style = if g.faulted {
        theme::alert()
    } else {
        Style::new().fg(theme::ON).add_modifier(Modifier::BOLD)
    };
    let pos = cell(g.position, g.from, g.to, track_w).unwrap_or(
        // Past an end: pin the mark to the nearer end so it is still seen.
        if g.position.abs_diff(g.from) < g.position.abs_diff(g.to) {
            0
        } else {
            track_w - 1
        },
    );
    track[pos] = (POSITION_MARK.into(), pos_style);
    let mut spans = vec![
        Span::styled(format!("{:<6}", g.label), theme::label()),
        Span::styled(g.left, theme::label()),
        Span::styled("├", theme::border()),
    ];
    spans.extend(track.into_iter().map(|(t, s)| Span::styled(t, s)));
    spans.push(Span::styled("┤", theme::border()));
    spans.push(Span::styled(g.right, theme::label()));
    let status = if g.faulted {
        Span::styled(" FLT", theme::alert())
    } else if g.running {
        Span::styled(" RUN", theme::on_off(true))
    } else {
        Span::styled(
            // One space after the end's label always: "DN 97%", "DN 100%".
            format!("{:<5}", format!(" {}%", percent(&g))),
            theme::label(),
        )
    };
    spans.push(status);
    Line::from(spans)
}

/// Motor faults, overspeed alarm and flap-down inhibit, in words.
fn flags(model: &Model, now: Instant) -> Vec<(String, Style)> {
    let Some(ft) = model.live_flap_trim(now) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for m in Motor::ALL {
        let code = m.fault(ft);
        if code.is_fault() {
            out.push((
                format!("{} {} ({:#04x})", m.name(), code.name(), code.to_byte()),
                theme::alert(),
            ));
        }
    }
    if ft.flap.overspeed_alarm {
        out.push(("FLAP OVERSPEED ALARM".into(), theme::alert()));
    }
    if ft.flap.down_switch_inhibited {
        out.push(("flap down inhibited".into(), theme::caution()));
    }
    out
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, control: &ControlState, now: Instant) {
    let ft = model.live_flap_trim(now);
    let motors = shown(model, now);
    let mut lines: Vec<Line> = motors
        .iter()
        .map(|&m| gauge_line(m, ft, area.width))
        .collect();
    if motors.is_empty() {
        lines.push(Line::styled("no flaps or trim enabled", theme::label()));
    }
    let mut flag_spans = Vec::new();
    for (i, (t, s)) in flags(model, now).into_iter().enumerate() {
        if i > 0 {
            flag_spans.push(Span::styled(" · ", theme::border()));
        }
        flag_spans.push(Span::styled(t, s));
    }
    let run = control
        .run
        .map(|run| format!("▶ {} {}", run.motor.name(), run.direction));
    let run_width = run.as_ref().map_or(0, |r| r.chars().count() + 2);
    let mut mode = match control.release_mode {
        ReleaseMode::KeyRelease => "keys: release seen".to_string(),
        ReleaseMode::AutoRepeat => "keys: auto-repeat".to_string(),
    };
    // The timing the page judges repeats by, where the panel has room for it.
    if let (ReleaseMode::AutoRepeat, Some(t)) = (control.release_mode, control.repeat) {
        let full = format!("{mode} · {}", repeat_timing(&t));
        if full.chars().count() + run_width <= usize::from(area.width) {
            mode = full;
        }
    }
    let mut last = vec![Span::styled(mode, theme::label())];
    if let Some(run) = run {
        last.push(Span::raw("  "));
        last.push(Span::styled(
            run,
            Style::new().fg(theme::ON).add_modifier(Modifier::BOLD),
        ));
    }
    let inner = panel::titled(frame.buffer_mut(), area, " Flaps & trim ");
    // Gauges and the mode line fit by construction; only the flags may wrap.
    let [gauges, flags_area, mode_area] = Layout::vertical([
        Constraint::Length(lines.len() as u16),
        Constraint::Fill(1),
        Constraint::Length(1),
    ])
    .areas(inner);
    super::unwrapped::lines(frame.buffer_mut(), gauges, &lines);
    if !flag_spans.is_empty() {
        let flags = Paragraph::new(Line::from(flag_spans)).wrap(Wrap { trim: true });
        frame.render_widget(flags, flags_area);
    }
    super::unwrapped::lines(frame.buffer_mut(), mode_area, &[Line::from(last)]);
}

/// "660 ms / 40 ms, learned": the first-repeat delay and the repeat interval the page
/// measured, or the wait it uses until it has.
pub fn repeat_timing(t: &RepeatTiming) -> String {
    let ms = |d: std::time::Duration| d.as_millis();
    match (t.set_by_hand, t.delay, t.interval) {
        (false, Some(d), Some(i)) => format!("{} ms / {} ms, learned", ms(d), ms(i)),
        (false, _, Some(i)) => format!("{} ms / {} ms, learning", ms(t.first_window), ms(i)),
        (false, _, None) => format!("{} ms, learning", ms(t.first_window)),
        (true, _, Some(i)) => format!("{} ms set / {} ms learned", ms(t.first_window), ms(i)),
        (true, _, None) => format!("{} ms, set", ms(t.first_window)),
    }
}

//! Total amps inside a drawn VP-X box, main bus volts inside a drawn battery (as in
//! Appendix A's example screen), aux battery, temperature and the system flags in words.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use super::panel;
use super::{theme, values};
use crate::model::Model;
use crate::protocol::message::{SystemStatus, WigWagModeSetting};

/// Rows the panel needs at `width` (title, drawing, values, flags).
pub fn height(model: &Model, now: Instant, width: u16) -> u16 {
    let flags: usize = flags(model, now)
        .iter()
        .map(|(t, _)| t.chars().count() + 3)
        .sum();
    let flag_lines = flags.div_ceil(width.max(1) as usize).max(1) as u16;
    1 + 4 + 1 + flag_lines
}

/// The system flags of SYSTEM_STATUS and FAULT_STATUS in words, most serious first.
pub fn flags(model: &Model, now: Instant) -> Vec<(String, Style)> {
    let Some(s) = model.live_system(now) else {
        return vec![(values::BLANK.into(), theme::unknown())];
    };
    let mut out = Vec::new();
    if model.live_faults(now).is_some_and(|(_, system)| system) {
        out.push(("SYSTEM FAULT (R resets)".into(), theme::alert()));
    }
    let f = &s.faults;
    if f.current_over_60a {
        out.push(("OVER 60 A".into(), theme::alert()));
    }
    if f.current_over_48a {
        out.push(("OVER 48 A".into(), theme::caution()));
    }
    if f.data_integrity_failure {
        let what = s
            .data_integrity_code
            .map_or_else(|| "no code given".into(), |c| c.description());
        out.push((format!("DATA INTEGRITY FAILURE: {what}"), theme::alert()));
    }
    if f.warm_reset {
        out.push(("WARM RESET".into(), theme::caution()));
    }
    if f.external_data_missing {
        out.push(("EXTERNAL DATA MISSING".into(), theme::caution()));
    }
    if s.misc.software_update {
        out.push(("SOFTWARE UPDATED".into(), theme::info()));
    }
    if s.misc.starter_annunciator {
        out.push(("STARTER ENGAGED".into(), theme::caution()));
    }
    out.push((wig_wag(s), theme::info()));
    out
}

fn wig_wag(s: &SystemStatus) -> String {
    let mode = match s.misc.wig_wag_mode {
        WigWagModeSetting::Auto => "auto".to_string(),
        WigWagModeSetting::Steady => "steady".to_string(),
        WigWagModeSetting::Unknown(n) => format!("mode {n}"),
    };
    if s.misc.wig_wag_active {
        format!("WIG-WAG ACTIVE ({mode})")
    } else {
        format!("wig-wag {mode}")
    }
}

/// `text` centred in `width` columns.
fn centred(text: &str, width: usize) -> String {
    format!("{text:^width$}")
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let live = model.live_system(now);
    let amps = live.map(|s| s.system_current.value());
    let bus = live.map(|s| s.main_bus_volts.value());
    let value_style = |live: bool| {
        if live {
            theme::panel_title()
        } else {
            theme::unknown()
        }
    };
    let box_s = theme::label();
    let amps_text = centred(&format!("{} A", values::amps(amps)), 8);
    let bus_text = centred(&format!("{} V", values::volts(bus)), 9);
    let mut lines = vec![
        Line::from(vec![
            Span::styled("╭─ VP-X ─╮", box_s),
            Span::styled("   ┬─BUS─┬", box_s),
        ]),
        Line::from(vec![
            Span::styled("│", box_s),
            Span::styled(amps_text, value_style(amps.is_some())),
            Span::styled("│", box_s),
            Span::styled(" ┌─┴─────┴─┐", box_s),
        ]),
        Line::from(vec![
            Span::styled("╰────────╯", box_s),
            Span::styled(" │", box_s),
            Span::styled(bus_text, value_style(bus.is_some())),
            Span::styled("│", box_s),
        ]),
        Line::from(Span::styled("           └─────────┘", box_s)),
    ];
    let mut values_line = Vec::new();
    // Aux battery: shown when the unit reports one; a unit without one reports 0 V.
    match live.map(|s| s.aux_battery_volts.value()) {
        Some(v) if v > 0.0 => {
            values_line.push(Span::styled("aux ", theme::label()));
            values_line.push(Span::styled(format!("{v:.1} V"), theme::panel_title()));
            values_line.push(Span::raw("  "));
        }
        Some(_) => values_line.push(Span::styled("no aux batt  ", theme::label())),
        None => {
            values_line.push(Span::styled("aux ", theme::label()));
            values_line.push(Span::styled("-- V  ", theme::unknown()));
        }
    }
    values_line.push(Span::styled("temp ", theme::label()));
    values_line.push(match live {
        Some(s) => Span::styled(format!("{} °C", s.internal_temp), theme::panel_title()),
        None => Span::styled("-- °C", theme::unknown()),
    });
    lines.push(Line::from(values_line));
    let mut flag_spans = Vec::new();
    for (i, (text, style)) in flags(model, now).into_iter().enumerate() {
        if i > 0 {
            flag_spans.push(Span::styled(" · ", theme::border()));
        }
        flag_spans.push(Span::styled(text, style));
    }
    let inner = panel::titled(frame.buffer_mut(), area, " System ");
    // Only the flags can run past the width; wrapping is the costly part of a
    // paragraph, so the fixed drawing is not wrapped.
    let [drawing, flags_area] =
        Layout::vertical([Constraint::Length(lines.len() as u16), Constraint::Fill(1)])
            .areas(inner);
    super::unwrapped::lines(frame.buffer_mut(), drawing, &lines);
    let flags = Paragraph::new(Line::from(flag_spans)).wrap(Wrap { trim: true });
    frame.render_widget(flags, flags_area);
}

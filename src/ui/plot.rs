//! Bus volts and total amps over the last minutes, as sparklines: people would rather
//! look than read. Each column is a time bucket ending at `now`, so a gap in the data
//! (communication lost) shows as a gap, not as a line drawn through it.

use std::time::{Duration, Instant};

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Sparkline};

use super::theme;
use crate::model::{BusSample, Model};

/// How far back the plot looks.
pub const WINDOW: Duration = Duration::from_secs(5 * 60);

/// Per-column averages of `value` over `width` equal buckets ending at `now`; `None`
/// for a bucket without samples.
pub fn buckets(
    history: impl Iterator<Item = BusSample>,
    value: impl Fn(&BusSample) -> f32,
    now: Instant,
    width: usize,
) -> Vec<Option<f32>> {
    let mut sum = vec![(0.0f32, 0u32); width];
    let per = WINDOW.as_secs_f64() / width.max(1) as f64;
    for s in history {
        let ago = now.saturating_duration_since(s.at).as_secs_f64();
        if s.at > now || ago >= WINDOW.as_secs_f64() {
            continue;
        }
        let col = width - 1 - ((ago / per) as usize).min(width - 1);
        sum[col].0 += value(&s);
        sum[col].1 += 1;
    }
    sum.into_iter()
        .map(|(t, n)| (n > 0).then(|| t / n as f32))
        .collect()
}

/// Scales to 1..=100 between the window's low and high (at least `min_span` apart, so
/// sensor noise on a steady bus does not look like a swing). Zero is reserved for
/// gaps, which the sparkline leaves blank.
fn scale(b: &[Option<f32>], min_span: f32) -> (Vec<Option<u64>>, f32, f32) {
    let vals = b.iter().flatten();
    let lo = vals.clone().copied().fold(f32::INFINITY, f32::min);
    let hi = vals.copied().fold(f32::NEG_INFINITY, f32::max);
    if !lo.is_finite() {
        return (vec![None; b.len()], 0.0, 0.0);
    }
    let mid = (lo + hi) / 2.0;
    let span = (hi - lo).max(min_span);
    let base = mid - span / 2.0;
    let data = b
        .iter()
        .map(|v| v.map(|v| (1.0 + (v - base) / span * 99.0).clamp(1.0, 100.0) as u64))
        .collect();
    (data, lo, hi)
}

struct Trace {
    name: &'static str,
    unit: &'static str,
    value: fn(&BusSample) -> f32,
    min_span: f32,
    colour: Style,
}

/// `ranged`: room to print the window's low–high beside the name.
fn trace(frame: &mut Frame, area: Rect, model: &Model, now: Instant, t: Trace, ranged: bool) {
    let Trace {
        name,
        unit,
        value,
        min_span,
        colour,
    } = t;
    let [label_area, spark_area] =
        Layout::vertical([Constraint::Length(1), Constraint::Fill(1)]).areas(area);
    let b = buckets(
        model.history.iter().copied(),
        value,
        now,
        spark_area.width as usize,
    );
    let (data, lo, hi) = scale(&b, min_span);
    let range = if !ranged {
        String::new()
    } else if lo.is_finite() && hi >= lo && b.iter().any(Option::is_some) {
        format!(" {lo:.1}–{hi:.1} {unit}")
    } else {
        " no data".into()
    };
    frame.render_widget(
        Paragraph::new(Line::from(vec![
            Span::styled(name.to_string(), colour),
            Span::styled(range, theme::label()),
        ])),
        label_area,
    );
    frame.render_widget(
        Sparkline::default()
            .data(data)
            .max(100)
            .style(colour)
            .absent_value_symbol(" "),
        spark_area,
    );
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let block = Block::new()
        .borders(Borders::TOP)
        .border_style(theme::border())
        .title(Span::styled(
            format!(" Last {} min ", WINDOW.as_secs() / 60),
            theme::panel_title(),
        ));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    if inner.height < 2 {
        return;
    }
    let stacked = inner.height >= 4;
    let halves = if stacked {
        Layout::vertical([Constraint::Fill(1), Constraint::Fill(1)]).split(inner)
    } else {
        Layout::horizontal([Constraint::Fill(1), Constraint::Fill(1)])
            .spacing(1)
            .split(inner)
    };
    let volts = Trace {
        name: "bus V",
        unit: "V",
        value: |s| s.main_bus_volts,
        min_span: 1.0,
        colour: Style::new().fg(theme::INFO),
    };
    let amps = Trace {
        name: "amps",
        unit: "A",
        value: |s| s.system_amps,
        min_span: 2.0,
        colour: Style::new().fg(theme::CAUTION),
    };
    let ranged = stacked || inner.width >= 60;
    trace(frame, halves[0], model, now, volts, ranged);
    trace(frame, halves[1], model, now, amps, ranged);
}

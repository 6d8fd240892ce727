//! Bus volts and total amps over the last minutes, as charts read at a glance: a braille
//! line against a time axis, the low and high as value labels, and on the volts chart
//! the unit's overvoltage limit (SYSTEM_SPEC, ICD Table 14) as a dashed red line, told
//! from the bus trace by its dashes where colour is not shown. Samples are
//! averaged into time buckets ending at `now`, and a bucket without samples (the
//! unit went quiet) breaks the line: a gap is shown as a gap, never bridged.

use std::time::{Duration, Instant};

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};

use super::chart::{Chart, Series};
use super::panel;
use super::theme;
use crate::model::{BusSample, Model};
use crate::protocol::message::OvervoltageLimit;

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

/// The runs of consecutive buckets with data, as chart points: x in seconds before
/// `now` (negative), y the bucket's mean.
fn runs(b: &[Option<f32>]) -> Vec<Vec<(f64, f64)>> {
    let per = WINDOW.as_secs_f64() / b.len().max(1) as f64;
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current = Vec::new();
    for (i, v) in b.iter().enumerate() {
        match v {
            Some(v) => {
                let x = -WINDOW.as_secs_f64() + (i as f64 + 0.5) * per;
                current.push((x, f64::from(*v)));
            }
            None if !current.is_empty() => out.push(std::mem::take(&mut current)),
            None => {}
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// The chart's value range: the data's low–high, at least `min_span` wide (so sensor
/// noise on a steady bus is not drawn as a swing), widened to show `limit`.
fn bounds(lo: f64, hi: f64, min_span: f64, limit: Option<f64>) -> [f64; 2] {
    let (lo, hi) = match limit {
        Some(l) => (lo.min(l), hi.max(l)),
        None => (lo, hi),
    };
    let mid = (lo + hi) / 2.0;
    let span = (hi - lo).max(min_span) * 1.1;
    [mid - span / 2.0, mid + span / 2.0]
}

struct Trace {
    name: &'static str,
    unit: &'static str,
    value: fn(&BusSample) -> f32,
    min_span: f64,
    colour: Style,
    /// A limit drawn across the chart in red, with its label.
    limit: Option<f64>,
}

/// `ranged`: room to print the window's low–high beside the name; `time_axis`: this
/// chart carries the time labels (the lower of two stacked charts shares its own).
fn trace(
    frame: &mut Frame,
    area: Rect,
    model: &Model,
    now: Instant,
    t: &Trace,
    ranged: bool,
    time_axis: bool,
) {
    let [label_area, chart_area] =
        Layout::vertical([Constraint::Length(1), Constraint::Fill(1)]).areas(area);
    // The history is in time order (the model appends), so the samples older than the
    // window are skipped without a look at each: half the history, on every frame.
    let start = model
        .history
        .partition_point(|s| now.saturating_duration_since(s.at) >= WINDOW);
    // Two samples a cell: braille has two dot columns in each.
    let b = buckets(
        model.history.range(start..).copied(),
        t.value,
        now,
        (chart_area.width as usize * 2).max(2),
    );
    let vals = b.iter().flatten().map(|v| f64::from(*v));
    let lo = vals.clone().fold(f64::INFINITY, f64::min);
    let hi = vals.fold(f64::NEG_INFINITY, f64::max);
    let mut label = vec![Span::styled(t.name, t.colour)];
    if !lo.is_finite() {
        label.push(Span::styled(" no data", theme::unknown()));
    } else if ranged {
        label.push(Span::styled(
            format!(" {lo:.1}–{hi:.1} {}", t.unit),
            theme::label(),
        ));
    }
    if let Some(l) = t.limit {
        // Only whole: the dashed red line says it too, so a narrow label drops the words.
        let words = Span::styled(format!("  limit {l:.0} {}", t.unit), theme::alert());
        if Line::from(label.clone()).width() + words.width() <= label_area.width as usize {
            label.push(words);
        }
    }
    super::fast::lines(frame.buffer_mut(), label_area, &[Line::from(label)]);
    if !lo.is_finite() || chart_area.height < 2 {
        return;
    }
    let y = bounds(lo, hi, t.min_span, t.limit);
    let x = [-WINDOW.as_secs_f64(), 0.0];
    let runs = runs(&b);
    let limit_line = t.limit.map(|l| [(x[0], l), (x[1], l)]);
    let mut series: Vec<Series> = Vec::with_capacity(runs.len() + 1);
    if let Some(line) = &limit_line {
        series.push(Series {
            points: line,
            colour: theme::FAULT,
            joined: true,
            dashed: true,
        });
    }
    let colour = t.colour.fg.unwrap_or(Color::Reset);
    for run in &runs {
        // A lone bucket between gaps is still a point on the chart.
        series.push(Series {
            points: run,
            colour,
            joined: run.len() > 1,
            dashed: false,
        });
    }
    let minutes = WINDOW.as_secs() / 60;
    // The time labels take two rows (axis and labels): only where the chart keeps at
    // least two rows of plot.
    let time_labels = if time_axis && chart_area.height >= 4 {
        vec![
            Span::styled(format!("-{minutes} min"), theme::label()),
            Span::styled(
                format!("-{} min", WINDOW.as_secs_f64() / 120.0),
                theme::label(),
            ),
            Span::styled("now", theme::label()),
        ]
    } else {
        Vec::new()
    };
    let value_labels = y.map(|v| {
        // A narrow chart keeps whole numbers rather than cut ones.
        let text = if chart_area.width >= 24 {
            format!("{v:.1}")
        } else {
            format!("{v:.0}")
        };
        Span::styled(text, theme::label())
    });
    let chart = Chart {
        x_bounds: x,
        y_bounds: y,
        x_labels: &time_labels,
        y_labels: &value_labels,
        axis_style: theme::border(),
    };
    chart.render(chart_area, frame.buffer_mut(), &series);
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let title = format!(" Last {} min ", WINDOW.as_secs() / 60);
    let inner = panel::titled(frame.buffer_mut(), area, &title);
    if inner.height < 2 {
        return;
    }
    let stacked = inner.height >= 8;
    let halves = if stacked {
        Layout::vertical([Constraint::Fill(1), Constraint::Fill(1)]).split(inner)
    } else {
        Layout::horizontal([Constraint::Fill(1), Constraint::Fill(1)])
            .spacing(1)
            .split(inner)
    };
    let limit = model.system_spec.map(|s| match s.value.overvoltage_limit {
        OvervoltageLimit::V16 => 16.0,
        OvervoltageLimit::V32 => 32.0,
        OvervoltageLimit::Unknown(_) => f64::NAN,
    });
    let volts = Trace {
        name: "bus V",
        unit: "V",
        value: |s| s.main_bus_volts,
        min_span: 1.0,
        colour: Style::new().fg(theme::INFO),
        limit: limit.filter(|l| l.is_finite()),
    };
    let amps = Trace {
        name: "amps",
        unit: "A",
        value: |s| s.system_amps,
        min_span: 2.0,
        colour: Style::new().fg(theme::CAUTION),
        limit: None,
    };
    let ranged = stacked || inner.width >= 60;
    trace(frame, halves[0], model, now, &volts, ranged, !stacked);
    trace(frame, halves[1], model, now, &amps, ranged, true);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gap_in_the_data_breaks_the_line() {
        let b = [
            Some(14.0),
            Some(14.1),
            None,
            None,
            Some(13.9),
            None,
            Some(14.2),
        ];
        let r = runs(&b);
        assert_eq!(r.len(), 3, "{r:?}");
        assert_eq!(r[0].len(), 2);
        assert_eq!(r[1].len(), 1);
        // Times run from the window's start to now, each at its bucket's middle.
        let per = WINDOW.as_secs_f64() / 7.0;
        assert!((r[0][0].0 - (-WINDOW.as_secs_f64() + per / 2.0)).abs() < 1e-9);
        assert!((r[2][0].0 - (-per / 2.0)).abs() < 1e-9);
        assert!(runs(&[None, None]).is_empty());
    }

    #[test]
    fn the_range_is_never_narrower_than_noise_and_shows_the_limit() {
        let [lo, hi] = bounds(14.0, 14.1, 1.0, None);
        assert!(hi - lo >= 1.0 && lo < 14.0 && hi > 14.1, "{lo} {hi}");
        let [lo, hi] = bounds(13.8, 14.2, 1.0, Some(16.0));
        assert!(lo < 13.8 && hi > 16.0, "{lo} {hi}");
    }
}

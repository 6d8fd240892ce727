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
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Chart, Dataset, GraphType};

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
    super::unwrapped::lines(frame.buffer_mut(), label_area, &[Line::from(label)]);
    if !lo.is_finite() || chart_area.height < 2 {
        return;
    }
    let y = bounds(lo, hi, t.min_span, t.limit);
    let x = [-WINDOW.as_secs_f64(), 0.0];
    let runs = runs(&b);
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
    let dashes = t.limit.map(|l| {
        let columns = graph_width(chart_area.width, &time_labels, &value_labels);
        dashed(l, x, columns)
    });
    let mut datasets = Vec::with_capacity(runs.len() + 1);
    if let Some(dashes) = &dashes {
        datasets.push(dataset(dashes, theme::FAULT, GraphType::Scatter));
    }
    let colour = t.colour.fg.unwrap_or(Color::Reset);
    for run in &runs {
        // A lone bucket between gaps is still a point on the chart.
        let kind = if run.len() > 1 {
            GraphType::Line
        } else {
            GraphType::Scatter
        };
        datasets.push(dataset(run, colour, kind));
    }
    let chart = Chart::new(datasets)
        .x_axis(axis(x, time_labels))
        .y_axis(axis(y, value_labels.to_vec()))
        .legend_position(None);
    frame.render_widget(chart, chart_area);
}

fn axis(bounds: [f64; 2], labels: Vec<Span<'static>>) -> Axis<'static> {
    let axis = Axis::default().bounds(bounds).style(theme::border());
    if labels.is_empty() {
        axis
    } else {
        axis.labels(labels)
    }
}

fn dataset(points: &[(f64, f64)], colour: Color, kind: GraphType) -> Dataset<'_> {
    Dataset::default()
        .marker(Marker::Braille)
        .graph_type(kind)
        .style(Style::new().fg(colour))
        .data(points)
}

/// The columns `Chart` leaves its graph in an area `width` wide: right of the y
/// labels (widened for the part of the first time label left of the y axis, never
/// more than a third of the chart) and of the y axis. ratatui's own layout for the
/// axes drawn here; `a_dashed_line_leaves_every_other_cell_blank` holds it.
fn graph_width(width: u16, x_labels: &[Span], y_labels: &[Span]) -> u16 {
    let has_y = !y_labels.is_empty();
    let mut left = y_labels.iter().map(Span::width).max().unwrap_or(0);
    if let Some(first) = x_labels.first() {
        left = left.max(first.width().saturating_sub(usize::from(has_y)));
    }
    let left = u16::try_from(left).unwrap_or(u16::MAX).min(width / 3);
    let axis = u16::from(has_y && left + 1 < width);
    width - left - axis
}

/// A level across the chart as dashes, for a graph `columns` cells wide: both dots
/// of every other cell (braille has two dot columns a cell), so the line is told from
/// a solid trace without colour.
fn dashed(level: f64, [left, right]: [f64; 2], columns: u16) -> Vec<(f64, f64)> {
    let dots = f64::from(columns) * 2.0 - 1.0;
    (0..columns)
        .step_by(2)
        .flat_map(|c| [2 * c, 2 * c + 1])
        .filter(|&d| d < columns * 2)
        .map(|d| (left + f64::from(d) * (right - left) / dots.max(1.0), level))
        .collect()
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

    /// The limit's dashes fill every other cell of the graph from its first column,
    /// which holds `graph_width` to where `Chart` puts the graph.
    #[test]
    fn a_dashed_line_leaves_every_other_cell_blank() {
        use ratatui::buffer::Buffer;
        use ratatui::widgets::Widget;
        for (width, time_axis, y_text) in [(40u16, true, "16.0"), (13, false, "16"), (9, true, "1")]
        {
            let area = Rect::new(0, 0, width, 6);
            let time: Vec<Span<'static>> = if time_axis {
                vec![Span::raw("-5 min"), Span::raw("now")]
            } else {
                Vec::new()
            };
            let values = vec![Span::raw(y_text), Span::raw(y_text)];
            let columns = graph_width(width, &time, &values);
            let dashes = dashed(16.0, [-300.0, 0.0], columns);
            let mut buf = Buffer::empty(area);
            Chart::new(vec![dataset(&dashes, Color::Red, GraphType::Scatter)])
                .x_axis(axis([-300.0, 0.0], time))
                .y_axis(axis([12.0, 16.0], values))
                .legend_position(None)
                .render(area, &mut buf);
            let top: String = (width - columns..width)
                .map(|x| buf[(x, 0)].symbol().to_string())
                .collect();
            let want: String = (0..columns)
                .map(|c| if c % 2 == 0 { "⠉" } else { " " })
                .collect();
            assert_eq!(top, want, "{width} wide");
            assert_eq!(buf[(width - columns - 1, 0)].symbol(), "│");
        }
    }

    #[test]
    fn the_range_is_never_narrower_than_noise_and_shows_the_limit() {
        let [lo, hi] = bounds(14.0, 14.1, 1.0, None);
        assert!(hi - lo >= 1.0 && lo < 14.0 && hi > 14.1, "{lo} {hi}");
        let [lo, hi] = bounds(13.8, 14.2, 1.0, Some(16.0));
        assert!(lo < 13.8 && hi > 16.0, "{lo} {hi}");
    }
}

//! Step 4, motors: flaps and each enabled trim run briefly each way on the page's safe
//! stream, the position compared in FLAP_TRIM_STATUS, then put back. Shown: each
//! motor's live position on its travel, which way the page is running it now (what
//! the page streams, read from its controller), the positions the check recorded, and the
//! results. Without a live FLAP_TRIM_STATUS a position is "--".

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Modifier;
use ratatui::text::{Line, Span};

use super::list::{self, Row};
use super::{fit, head_w, progress_span, progress_words, section, words_style};
use crate::check::state::{CheckView, Mark};
use crate::check::words;
use crate::model::{Model, Motor, TrimKind};
use crate::protocol::message::FlapTrimStatus;
use crate::ui::state::MotorRun;
use crate::ui::{theme, unwrapped, values};

/// A motor's travel: its ends' words, the sensor at each end, and where it is now.
fn travel(m: Motor, ft: &FlapTrimStatus) -> (&'static str, &'static str, u8, u8, u8, bool) {
    let a = ft.axis(m.axis());
    let (left, right) = match m {
        Motor::Flaps | Motor::Trim(TrimKind::Pitch) => ("UP", "DN"),
        // Roll "up" is left (ICD Table 30 note 2).
        Motor::Trim(TrimKind::Roll) => (" L", "R "),
    };
    (left, right, a.up, a.down, a.position, a.motor_running)
}

/// A motor's travel ends in sensor counts: the live FLAP_TRIM_STATUS's, else the
/// spec the unit reported (configuration, not a reading, so it may be old).
pub fn ends(m: Motor, model: &Model, now: Instant) -> Option<(u8, u8)> {
    if let Some(ft) = model.live_flap_trim(now) {
        let (_, _, from, to, _, _) = travel(m, ft);
        return Some((from, to));
    }
    model.motor_spec(m).map(|(_, ends)| ends)
}

/// The positions a motor went through (raw counts) as percent of its travel from
/// the up end, or as counts when its ends are not known.
fn positions(m: Motor, raw: &[u8], model: &Model, now: Instant) -> String {
    words::positions(raw, ends(m, model, now))
}

fn gauge(
    m: Motor,
    ft: Option<&FlapTrimStatus>,
    streaming: Option<MotorRun>,
    width: u16,
) -> Line<'static> {
    let name = Span::raw(fit(m.name(), 11));
    let track_w = usize::from(width)
        .saturating_sub(11 + 4 + 2 + 7 + 18)
        .clamp(8, 50);
    let Some(ft) = ft else {
        return Line::from(vec![
            name,
            Span::styled(format!("{:<4}", values::BLANK), theme::unknown()),
            Span::styled(
                "position unknown: no live FLAP_TRIM_STATUS",
                theme::caution(),
            ),
        ]);
    };
    let (left, right, from, to, pos, running) = travel(m, ft);
    let p = words::percent_of_travel((from, to), pos);
    let at = (usize::from(p) * (track_w - 1) + 50) / 100;
    let mut spans = vec![
        name,
        Span::styled(left, theme::label()),
        Span::styled("├", theme::border()),
        Span::styled("─".repeat(at), theme::border()),
        Span::styled("●", theme::on_off(true)),
        Span::styled("─".repeat(track_w - 1 - at), theme::border()),
        Span::styled("┤", theme::border()),
        Span::styled(right, theme::label()),
        Span::raw(format!("{:>5} %", p)),
    ];
    match streaming.filter(|r| r.motor == m) {
        Some(run) => spans.push(Span::styled(
            format!("  ▶ running {}", run.direction),
            theme::on_off(true).add_modifier(Modifier::BOLD),
        )),
        None if running => spans.push(Span::styled("  moving", theme::caution())),
        None => spans.push(Span::styled("  stopped", theme::label())),
    }
    Line::from(spans)
}

/// The results of step 4 as rows, for this screen and the summary.
pub fn rows(view: &CheckView, model: &Model, now: Instant, current: Option<usize>) -> Vec<Row> {
    view.motors
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mark = r.mark();
            let mut w = words::motor(r);
            if !r.positions.is_empty() {
                w = format!("{w} ({})", positions(r.motor, &r.positions, model, now));
            }
            let w = match progress_words(mark, i, current, w) {
                // While it runs, the positions so far are the news.
                w if current == Some(i) && mark == Mark::NotRun && !r.positions.is_empty() => {
                    format!(
                        "{w}, so far {}",
                        positions(r.motor, &r.positions, model, now)
                    )
                }
                w => w,
            };
            Row {
                head: vec![
                    progress_span(mark, i, current),
                    Span::raw(fit(r.motor.name(), head_w(view))),
                    Span::raw(" "),
                ],
                words: w,
                words_style: words_style(mark),
                current: current == Some(i),
            }
        })
        .collect()
}

pub fn render(
    frame: &mut Frame,
    area: Rect,
    view: &CheckView,
    model: &Model,
    running: Option<MotorRun>,
    now: Instant,
) {
    let mut motors: Vec<Motor> = view.planned_motors.iter().map(|(m, _)| *m).collect();
    for r in &view.motors {
        if !motors.contains(&r.motor) {
            motors.push(r.motor);
        }
    }
    let [gauges_area, results_area] = Layout::vertical([
        Constraint::Length(motors.len().max(1) as u16 + 1),
        Constraint::Fill(1),
    ])
    .areas(area);
    let inner = section(frame, gauges_area, "Flaps & trim, live");
    let ft = model.live_flap_trim(now);
    let mut lines: Vec<Line> = motors
        .iter()
        .map(|&m| gauge(m, ft, running, inner.width))
        .collect();
    if lines.is_empty() {
        lines.push(Line::styled("No flaps or trim enabled.", theme::label()));
    }
    unwrapped::lines(frame.buffer_mut(), inner, &lines);
    let inner = section(frame, results_area, "Results");
    list::render(
        frame.buffer_mut(),
        inner,
        &rows(view, model, now, view.current),
        view.current,
    );
}

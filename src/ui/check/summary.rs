//! The end of the check: every result with what is left to fix first, the switches
//! the person must flip (a circuit put back by DEVICE_POWER stays held by the unit
//! until its switch is cycled, ICD Appendix A), and where the report went. And the screen of
//! a check that was interrupted: why, and exactly which circuits were left in which
//! state.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::list::{self, Row};
use super::state::{CheckView, LoadsView, Mark, Step};
use super::{HEAD_NAME_W, circuits, fit, mark_span, motors, section, switches, words, words_style};
use crate::loads::Level;
use crate::model::Model;
use crate::protocol::message::SwitchId;
use crate::ui::title_bar::middle_ellipsis;
use crate::ui::{fast, theme};

/// Every result of every step, in step order.
fn all_rows(view: &CheckView, model: &Model, now: Instant) -> Vec<(Step, Mark, Row)> {
    let mut out = Vec::new();
    for (r, row) in view.switches.iter().zip(switches::rows(view, model, None)) {
        out.push((Step::Switches, r.mark(), row));
    }
    for (r, row) in view.circuits.iter().zip(circuits::rows(view, None)) {
        out.push((Step::Circuits, r.mark(), row));
    }
    for (r, row) in view.motors.iter().zip(motors::rows(view, model, now, None)) {
        out.push((Step::Motors, r.mark(), row));
    }
    out.extend(
        load_rows(view)
            .into_iter()
            .map(|(m, r)| (Step::Loads, m, r)),
    );
    out
}

/// Step 5's results: each phase with its verdict, each measured circuit missing from
/// the load file, or why there is no analysis.
fn load_rows(view: &CheckView) -> Vec<(Mark, Row)> {
    let row = |mark: Mark, name: &str, words: String| {
        (
            mark,
            Row {
                head: vec![
                    mark_span(mark),
                    Span::raw(fit(name, HEAD_NAME_W)),
                    Span::raw(" "),
                ],
                words,
                words_style: words_style(mark),
                current: false,
            },
        )
    };
    match &view.loads {
        None => Vec::new(),
        Some(LoadsView::TemplateWritten(path)) => vec![row(
            Mark::Skipped,
            "load file",
            format!(
                "none yet: a template was written to {}; fill it in and run the check again",
                path.display()
            ),
        )],
        Some(LoadsView::Refused(why)) => vec![row(Mark::Warn, "load file", why.clone())],
        Some(LoadsView::Analysed { analysis, .. }) => {
            let mut out: Vec<(Mark, Row)> = analysis
                .phases
                .iter()
                .map(|p| {
                    row(
                        Mark::of(p.level),
                        p.phase.title(),
                        analysis.verdict(p.phase),
                    )
                })
                .collect();
            // The warnings list the phases that are not OK first, then the circuits
            // measured but missing from the file.
            let phase_warnings = analysis
                .phases
                .iter()
                .filter(|p| p.level != Level::Ok)
                .count();
            out.extend(
                analysis
                    .warnings()
                    .into_iter()
                    .skip(phase_warnings)
                    .map(|w| row(Mark::Warn, "load file", w)),
            );
            out
        }
    }
}

fn count_line(marks: &[Mark]) -> Line<'static> {
    let mut spans = Vec::new();
    for (mark, what) in [
        (Mark::Pass, "passed"),
        (Mark::Fail, "failed"),
        (Mark::Warn, "warned"),
        (Mark::Skipped, "skipped"),
        (Mark::NotRun, "not run"),
    ] {
        let n = marks.iter().filter(|&&m| m == mark).count();
        if n == 0 && matches!(mark, Mark::Skipped | Mark::NotRun) {
            continue;
        }
        let s = mark_span(mark);
        spans.push(Span::styled(
            format!("{} {n} {what}   ", mark.symbol()),
            if n == 0 { theme::label() } else { s.style },
        ));
    }
    Line::from(spans)
}

fn report_line(view: &CheckView, width: u16) -> Line<'static> {
    match &view.report {
        Some(p) => Line::from(vec![
            Span::styled("Report ", theme::label()),
            Span::styled(
                middle_ellipsis(&p.display().to_string(), usize::from(width) - 7),
                theme::info(),
            ),
        ]),
        None => Line::styled("No report written yet.", theme::label()),
    }
}

/// "Flip switch 6 to the other position and back: Landing Lt, Taxi Lt": the circuits
/// to release, by switch.
fn cycle_lines(view: &CheckView) -> Vec<Line<'static>> {
    let mut groups: Vec<(SwitchId, Vec<String>)> = Vec::new();
    for (_, name, sw) in &view.to_cycle {
        match groups.iter_mut().find(|(s, _)| s == sw) {
            Some((_, names)) => names.push(name.clone()),
            None => groups.push((*sw, vec![name.clone()])),
        }
    }
    groups
        .into_iter()
        .map(|(sw, names)| {
            let what = words::cycle(sw);
            let mut c = what.chars();
            let what: String = c
                .next()
                .map(|f| f.to_uppercase().collect::<String>() + c.as_str())
                .unwrap_or_default();
            Line::from(vec![
                Span::styled(format!("{what}: "), theme::caution()),
                Span::raw(names.join(", ")),
            ])
        })
        .collect()
}

/// The circuits to release, in a section of their own.
fn render_cycle(frame: &mut Frame, area: Rect, view: &CheckView) {
    let inner = section(
        frame,
        area,
        &format!(
            "Held by DEVICE_POWER until the switch is cycled ({})",
            words::HOLD_RULE
        ),
    );
    fast::lines(frame.buffer_mut(), inner, &cycle_lines(view));
}

fn cycle_height(view: &CheckView) -> u16 {
    if view.to_cycle.is_empty() {
        0
    } else {
        cycle_lines(view).len() as u16 + 1
    }
}

/// What is left to fix (failures and warnings), then every result.
fn results_rows(view: &CheckView, model: &Model, now: Instant) -> Vec<Row> {
    let all = all_rows(view, model, now);
    let mut rows = Vec::new();
    let fix: Vec<&Row> = all
        .iter()
        .filter(|(_, m, _)| matches!(m, Mark::Fail | Mark::Warn))
        .map(|(_, _, r)| r)
        .collect();
    let heading = |t: &str| Row {
        head: vec![Span::styled(t.to_string(), theme::panel_title())],
        words: String::new(),
        words_style: Style::new(),
        current: false,
    };
    let not_run = all.iter().filter(|(_, m, _)| *m == Mark::NotRun).count();
    if fix.is_empty() {
        // Green only when everything ran: "nothing to fix" with items never tested
        // would read as a clean installation.
        let head = if not_run == 0 {
            Span::styled("Nothing left to fix.", theme::on_off(true))
        } else {
            Span::styled(
                format!("Nothing failed so far, but {not_run} not run: check again."),
                theme::caution(),
            )
        };
        rows.push(Row {
            head: vec![head],
            words: String::new(),
            words_style: Style::new(),
            current: false,
        });
    } else {
        rows.push(heading("Left to fix"));
        rows.extend(fix.into_iter().map(|r| Row {
            head: r.head.clone(),
            words: r.words.clone(),
            words_style: r.words_style,
            current: false,
        }));
    }
    let mut step = None;
    for (s, _, r) in all {
        if step != Some(s) {
            rows.push(heading(&format!(
                "Every result: {}",
                s.title().to_lowercase()
            )));
            step = Some(s);
        }
        rows.push(r);
    }
    rows
}

pub fn render_done(frame: &mut Frame, area: Rect, view: &CheckView, model: &Model, now: Instant) {
    let marks: Vec<Mark> = all_rows(view, model, now)
        .into_iter()
        .map(|(_, m, _)| m)
        .collect();
    let [head, cycle, results] = Layout::vertical([
        Constraint::Length(3),
        Constraint::Length(cycle_height(view)),
        Constraint::Fill(1),
    ])
    .areas(area);
    let inner = section(frame, head, "Check complete");
    fast::lines(
        frame.buffer_mut(),
        inner,
        &[count_line(&marks), report_line(view, inner.width)],
    );
    if !view.to_cycle.is_empty() {
        render_cycle(frame, cycle, view);
    }
    let inner = section(frame, results, "Results");
    list::render(
        frame.buffer_mut(),
        inner,
        &results_rows(view, model, now),
        view.current,
    );
}

pub fn render_interrupted(
    frame: &mut Frame,
    area: Rect,
    view: &CheckView,
    model: &Model,
    now: Instant,
) {
    let Some(int) = &view.interrupted else {
        return;
    };
    let marks: Vec<Mark> = all_rows(view, model, now)
        .into_iter()
        .map(|(_, m, _)| m)
        .collect();
    let left_lines: Vec<Line> = if int.left.is_empty() {
        // "As it found it" only when nothing is held: a circuit put back by
        // DEVICE_POWER is in its old state but held there (the section below).
        let text = if view.to_cycle.is_empty() {
            "Every circuit the check switched was put back as it found it."
        } else {
            "Every circuit the check switched is back as it found it, but held there by \
             DEVICE_POWER: flip the switches below."
        };
        list::wrap(text, usize::from(area.width))
            .into_iter()
            .map(|l| Line::styled(l, theme::label()))
            .collect()
    } else {
        int.left
            .iter()
            .map(|(_, name, state)| {
                Line::from(vec![
                    Span::raw(fit(name, 16)),
                    Span::raw(" "),
                    Span::styled(state.clone(), theme::caution()),
                ])
            })
            .collect()
    };
    let left_h = (left_lines.len() as u16 + 1).min(area.height / 3).max(2);
    let [head, left, cycle, results] = Layout::vertical([
        Constraint::Length(2),
        Constraint::Length(left_h),
        Constraint::Length(cycle_height(view)),
        Constraint::Fill(1),
    ])
    .areas(area);
    let mut head_lines = list::wrap(
        &format!("Stopped: {}.", int.cause),
        usize::from(area.width.saturating_sub(8)),
    )
    .into_iter()
    .take(1)
    .map(|t| {
        Line::from(vec![
            Span::styled(" STOP ", theme::banner_lost()),
            Span::raw(" "),
            Span::styled(t, theme::alert()),
        ])
    })
    .collect::<Vec<_>>();
    head_lines.push(Line::styled(
        match &view.report {
            Some(p) => format!(
                "Report, marked incomplete: {}",
                middle_ellipsis(&p.display().to_string(), usize::from(area.width) - 27)
            ),
            None => "No report written: the check is incomplete.".into(),
        },
        theme::label(),
    ));
    fast::lines(frame.buffer_mut(), head, &head_lines);
    let inner = section(frame, left, "Left by the check in this state");
    let hidden = left_lines.len().saturating_sub(usize::from(inner.height));
    let mut shown = left_lines;
    if hidden > 0 {
        shown.truncate(usize::from(inner.height) - 1);
        shown.push(Line::styled(
            format!("and {} more: see the report", hidden + 1),
            theme::caution(),
        ));
    }
    fast::lines(frame.buffer_mut(), inner, &shown);
    if !view.to_cycle.is_empty() {
        render_cycle(frame, cycle, view);
    }
    let inner = section(frame, results, "Results so far");
    let [counts, rest] =
        Layout::vertical([Constraint::Length(1), Constraint::Fill(1)]).areas(inner);
    fast::lines(frame.buffer_mut(), counts, &[count_line(&marks)]);
    list::render(
        frame.buffer_mut(),
        rest,
        &results_rows(view, model, now),
        None,
    );
}

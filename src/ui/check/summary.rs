//! The end of the check: every result with what is left to fix first, the switches
//! the person must flip (a circuit put back by DEVICE_POWER stays held by the unit
//! until its switch is cycled, ICD Appendix A), and where the report went. And the screen of
//! a check that was interrupted: why, and exactly which circuits were left in which
//! state.

use std::time::Instant;

use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::list::{self, Row};
use super::{circuits, fit, head_w, mark_span, motors, section, switches, words_style};
use crate::check::state::{CheckView, LoadsView, Mark, Step};
use crate::check::words;
use crate::model::Model;
use crate::protocol::message::SwitchId;
use crate::ui::title_bar::middle_ellipsis;
use crate::ui::{theme, unwrapped, wrap};

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
                    Span::raw(fit(name, head_w(view))),
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
            // The phases are above; then what the file leaves out.
            out.extend(
                analysis
                    .file_warnings()
                    .into_iter()
                    .map(|w| row(Mark::Warn, "load file", w)),
            );
            out
        }
    }
}

/// The counts of the items tested, as the report and the headless run count them,
/// then the load analysis' own, apart: its phases are not items of the check.
fn count_line(marks: &[Mark], view: &CheckView) -> Line<'static> {
    let mut line = item_counts(marks);
    let loads: Vec<Mark> = load_rows(view).into_iter().map(|(m, _)| m).collect();
    let n = |m| loads.iter().filter(|&&x| x == m).count();
    let said: Vec<(Mark, usize)> = [Mark::Fail, Mark::Warn]
        .into_iter()
        .map(|m| (m, n(m)))
        .filter(|(_, k)| *k > 0)
        .collect();
    if !said.is_empty() {
        line.spans
            .push(Span::styled("│ load analysis ", theme::label()));
        for (m, k) in said {
            let what = if m == Mark::Fail { "failed" } else { "warned" };
            line.spans.push(Span::styled(
                format!("{} {k} {what}  ", m.symbol()),
                mark_span(m).style,
            ));
        }
    }
    line
}

fn item_counts(marks: &[Mark]) -> Line<'static> {
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

/// Where the report went (its file name whole, the folder shortened if it must be,
/// and the CSV beside it), or why it is not on the disk and the key that writes it
/// again.
fn report_line(view: &CheckView, width: u16) -> Line<'static> {
    let width = usize::from(width);
    if let Some(why) = &view.report_error {
        let lead = format!("{} Report NOT written: ", Mark::Fail.symbol());
        let tail = "  w: write it again";
        let room = width.saturating_sub(lead.chars().count() + tail.chars().count());
        return Line::from(vec![
            Span::styled(lead, theme::alert()),
            Span::styled(middle_ellipsis(why, room), theme::caution()),
            Span::styled(tail, theme::key()),
        ]);
    }
    match &view.report {
        Some(p) => {
            let also = " (and .csv)";
            let room = width.saturating_sub("Report ".len() + also.len());
            Line::from(vec![
                Span::styled("Report ", theme::label()),
                Span::styled(path_fit(p, room), theme::info()),
                Span::styled(also, theme::label()),
            ])
        }
        None => Line::styled("No report written yet.", theme::label()),
    }
}

/// "Flip switch 6 to the other position and back: Landing Lt, Taxi Lt": the circuits
/// to release, by switch.
/// A line wider than `width` wraps at words: a release that needs a switch fixed first
/// is a sentence, and a cut one would lose what to do.
fn cycle_lines(view: &CheckView, width: u16) -> Vec<Line<'static>> {
    let mut groups: Vec<(SwitchId, Vec<String>)> = Vec::new();
    for (_, name, sw) in &view.to_cycle {
        match groups.iter_mut().find(|(s, _)| s == sw) {
            Some((_, names)) => names.push(name.clone()),
            None => groups.push((*sw, vec![name.clone()])),
        }
    }
    groups
        .into_iter()
        .flat_map(|(sw, names)| {
            let what = view.release(sw);
            let mut c = what.chars();
            let what: String = c
                .next()
                .map(|f| f.to_uppercase().collect::<String>() + c.as_str())
                .unwrap_or_default();
            let names = names.join(", ");
            let whole = format!("{what}: {names}");
            if whole.chars().count() <= usize::from(width) {
                vec![Line::from(vec![
                    Span::styled(format!("{what}: "), theme::caution()),
                    Span::raw(names),
                ])]
            } else {
                wrap::text(&whole, usize::from(width))
                    .into_iter()
                    .map(|l| Line::styled(l, theme::caution()))
                    .collect()
            }
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
    unwrapped::lines(frame.buffer_mut(), inner, &cycle_lines(view, inner.width));
}

fn cycle_height(view: &CheckView, width: u16) -> u16 {
    if view.to_cycle.is_empty() {
        0
    } else {
        cycle_lines(view, width).len() as u16 + 1
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

/// Below a section's title: where its lines go.
fn under_title(area: Rect) -> Rect {
    Rect {
        y: area.y.saturating_add(1).min(area.bottom()),
        height: area.height.saturating_sub(1),
        ..area
    }
}

/// The ended check's areas: its head (counts, report), the switches to cycle, and
/// the results (or the load analysis, `l`).
fn done_areas(view: &CheckView, area: Rect) -> [Rect; 3] {
    Layout::vertical([
        Constraint::Length(3),
        Constraint::Length(cycle_height(view, area.width)),
        Constraint::Fill(1),
    ])
    .areas(area)
}

/// The counts of the items tested (switches, circuits, motors), the same as the
/// report's and the headless summary's: the load analysis is said in its own rows.
fn item_marks(view: &CheckView) -> Vec<Mark> {
    view.marks().collect()
}

/// The load analysis drawn whole (its table, its bar chart, every circuit) on a
/// page as tall as it needs, and the lines it took.
fn loads_page(view: &CheckView, width: u16) -> (Buffer, usize) {
    let rows = match &view.loads {
        Some(LoadsView::Analysed { analysis, .. }) => analysis.rows.len() + analysis.unlisted.len(),
        _ => 0,
    };
    // Head, phases, chart and circuits: 40 lines and a line a circuit is room enough;
    // what is left blank at the end is trimmed.
    let tall = Rect::new(0, 0, width, 40 + 2 * rows as u16);
    let mut page = Buffer::empty(tall);
    super::loads::render(&mut page, tall, view.loads.as_ref(), 0);
    let used = (0..tall.height)
        .rev()
        .find(|&y| (0..width).any(|x| page[(x, y)].symbol() != " "))
        .map_or(0, |y| usize::from(y) + 1);
    (page, used)
}

/// After the check (`l`): the load analysis, all of it, scrolled by lines like the
/// results, so its bar chart and every circuit are seen at 80×24 too.
fn render_loads(buf: &mut Buffer, area: Rect, view: &CheckView) {
    let (page, total) = loads_page(view, area.width);
    let s = list::scrolled(total, usize::from(area.height), view.scroll);
    let mut y = area.y;
    let say = |buf: &mut Buffer, y: u16, text: String| {
        unwrapped::lines(
            buf,
            Rect::new(area.x, y, area.width, 1),
            &[Line::styled(text, theme::label())],
        );
    };
    if s.above {
        say(buf, y, format!("↑ {} more lines above", s.top));
        y += 1;
    }
    for line in s.top..s.top + s.body {
        for x in 0..area.width {
            buf[(area.x + x, y)] = page[(x, line as u16)].clone();
        }
        y += 1;
    }
    if s.below {
        say(
            buf,
            y,
            format!("↓ {} more lines below", total - s.top - s.body),
        );
    }
}

pub fn render_done(frame: &mut Frame, area: Rect, view: &CheckView, model: &Model, now: Instant) {
    if view.show_loads {
        // The whole body: the analysis needs its height more than the head.
        let inner = section(frame, area, "Load analysis (l: back to the results)");
        return render_loads(frame.buffer_mut(), inner, view);
    }
    let [head, cycle, results] = done_areas(view, area);
    let inner = section(frame, head, "Check complete");
    unwrapped::lines(
        frame.buffer_mut(),
        inner,
        &[
            count_line(&item_marks(view), view),
            report_line(view, inner.width),
        ],
    );
    if !view.to_cycle.is_empty() {
        render_cycle(frame, cycle, view);
    }
    let inner = section(frame, results, "Results");
    list::render_scrolled(
        frame.buffer_mut(),
        inner,
        &results_rows(view, model, now),
        view.scroll,
    );
}

/// How far the ended check's results (or its load analysis' circuits) scroll in
/// `area`, the body of the screen.
pub fn scroll_max(view: &CheckView, model: &Model, now: Instant, area: Rect) -> usize {
    if view.show_loads {
        let inner = under_title(area);
        let (_, total) = loads_page(view, inner.width);
        return list::scroll_max_of(total, usize::from(inner.height));
    }
    let results = match &view.interrupted {
        Some(_) => interrupted_areas(view, area).3,
        None => done_areas(view, area)[2],
    };
    let mut inner = under_title(results);
    if view.interrupted.is_some() {
        // The counts' line.
        inner = under_title(inner);
    }
    list::scroll_max(inner, &results_rows(view, model, now))
}

/// What an interrupted check left, a line each (or that it left nothing changed).
fn left_lines(view: &CheckView, area: Rect) -> Vec<Line<'static>> {
    let Some(int) = &view.interrupted else {
        return Vec::new();
    };
    if int.left.is_empty() {
        // "As it found it" only when nothing is held: a circuit put back by
        // DEVICE_POWER is in its old state but held there (the section below).
        let text = if view.to_cycle.is_empty() {
            "Every circuit the check switched was put back as it found it."
        } else {
            "Every circuit the check switched is back as it found it, but held there by \
             DEVICE_POWER: flip the switches below."
        };
        wrap::text(text, usize::from(area.width))
            .into_iter()
            .map(|l| Line::styled(l, theme::label()))
            .collect()
    } else {
        int.left
            .iter()
            .map(|l| {
                Line::from(vec![
                    Span::raw(fit(&l.name, 16)),
                    Span::raw(" "),
                    Span::styled(l.state.clone(), theme::caution()),
                ])
            })
            .collect()
    }
}

/// The interrupted check's areas: its head, what it left, the switches to cycle, the
/// results so far.
fn interrupted_areas(view: &CheckView, area: Rect) -> (Rect, Rect, Rect, Rect) {
    let left_h = (left_lines(view, area).len() as u16 + 1)
        .min(area.height / 3)
        .max(2);
    let [head, left, cycle, results] = Layout::vertical([
        Constraint::Length(2),
        Constraint::Length(left_h),
        Constraint::Length(cycle_height(view, area.width)),
        Constraint::Fill(1),
    ])
    .areas(area);
    (head, left, cycle, results)
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
    let marks = item_marks(view);
    let left_lines = left_lines(view, area);
    let (head, left, cycle, results) = interrupted_areas(view, area);
    let mut head_lines = wrap::text(
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
    head_lines.push(match (&view.report, &view.report_error) {
        (_, Some(_)) => report_line(view, area.width),
        (Some(p), None) => Line::styled(
            format!(
                "Report, marked incomplete: {}",
                path_fit(p, usize::from(area.width).saturating_sub(27))
            ),
            theme::label(),
        ),
        (None, None) => Line::styled(
            "No report written: there is no folder to write it to.",
            theme::label(),
        ),
    });
    unwrapped::lines(frame.buffer_mut(), head, &head_lines);
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
    unwrapped::lines(frame.buffer_mut(), inner, &shown);
    if !view.to_cycle.is_empty() {
        render_cycle(frame, cycle, view);
    }
    let inner = section(frame, results, "Results so far");
    let [counts, rest] =
        Layout::vertical([Constraint::Length(1), Constraint::Fill(1)]).areas(inner);
    unwrapped::lines(frame.buffer_mut(), counts, &[count_line(&marks, view)]);
    list::render_scrolled(
        frame.buffer_mut(),
        rest,
        &results_rows(view, model, now),
        view.scroll,
    );
}

/// `path` in at most `width` characters: the file name kept whole (it is what a
/// person looks for), the folder shortened in its middle ("/home/…/reports/").
/// Only a file name wider than `width` itself is cut, at its start.
pub fn path_fit(path: &std::path::Path, width: usize) -> String {
    let full = path.display().to_string();
    if full.chars().count() <= width {
        return full;
    }
    let name = path
        .file_name()
        .map_or_else(|| full.clone(), |n| n.to_string_lossy().into_owned());
    let name_w = name.chars().count();
    let sep = std::path::MAIN_SEPARATOR;
    // "…/" and the name at least.
    if name_w + 2 > width {
        let keep = width.saturating_sub(1);
        let tail: String = name.chars().skip(name_w.saturating_sub(keep)).collect();
        return format!("…{tail}").chars().take(width).collect();
    }
    let dir = path
        .parent()
        .map(|d| format!("{}{sep}", d.display()))
        .unwrap_or_default();
    let room = width - name_w;
    format!(
        "{}{name}",
        crate::ui::title_bar::middle_ellipsis(&dir, room)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_too_long_keeps_its_file_name_whole() {
        use std::path::Path;
        let p = Path::new("/home/builder/.config/vpx-efis/reports/vpx-check-2026-12-02T0028Z.md");
        assert_eq!(path_fit(p, 200), p.display().to_string());
        let short = path_fit(p, 50);
        assert_eq!(short.chars().count(), 50, "{short}");
        // The name is joined with the OS's separator (a `\` on Windows).
        let sep = std::path::MAIN_SEPARATOR;
        assert!(
            short.ends_with(&format!("{sep}vpx-check-2026-12-02T0028Z.md")),
            "{short}"
        );
        assert!(short.starts_with("/home/"), "{short}");
        assert!(short.contains('…'), "{short}");
        // Narrower than the name: the end of the name, which tells the reports apart.
        assert_eq!(path_fit(p, 10), "…T0028Z.md");
    }
}

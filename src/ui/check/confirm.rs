//! Before anything is powered: every circuit the check will switch on and for how
//! long, the motors it will run, and beside them what it leaves alone and why, with
//! the exclusions the person may take back, and the switch inputs it will not ask
//! for because they power one left alone. The person confirms from this screen, so
//! nothing that will be powered is ever hidden: a list too long for the terminal is
//! packed into columns, and if even that does not fit the screen says how many are
//! not shown and asks for a larger window.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::list::{self, Row};
use super::{fit, section};
use crate::check::state::{CheckView, Planned};
use crate::check::words;
use crate::ui::{theme, unwrapped, values};

const NAME_W: usize = 16;
const PACKED_NAME_W: usize = 14;

fn breaker(b: Option<u8>) -> String {
    b.map_or_else(|| values::BLANK.into(), |b| format!("{b} A"))
}

fn row(p: &Planned, selected: bool, width: u16) -> Line<'static> {
    let mut line = Line::from(vec![
        Span::raw(fit(&p.name, NAME_W)),
        Span::raw(" "),
        Span::styled(format!("{:<6}", p.pin), theme::label()),
        Span::raw(format!("{:>5} ", breaker(p.breaker))),
        Span::styled(
            format!("{:<7}", values::switch_short(p.switch)),
            theme::label(),
        ),
        Span::styled(format!("{:>7}", words::duration(p.on_for)), theme::info()),
    ]);
    if selected {
        let pad = usize::from(width).saturating_sub(line.width());
        line.spans.push(Span::raw(" ".repeat(pad)));
        line = line.style(theme::selected_row());
    }
    line
}

fn header() -> Line<'static> {
    Line::styled(
        format!(
            "{:<NAME_W$} {:<6}{:>5} {:<7}{:>7}",
            "Circuit", "Pin", "CB", "Switch", "On for"
        ),
        theme::label(),
    )
}

/// The plan as a table if it fits, else names and times in as many columns as the
/// width allows; the lines it takes, and how many circuits it could not show.
/// `selected` is the plan row the person has selected, if any.
fn plan_lines(
    plan: &[Planned],
    selected: Option<usize>,
    width: u16,
    height: usize,
) -> (Vec<Line<'static>>, usize) {
    if plan.len() < height {
        let mut out = vec![header()];
        out.extend(
            plan.iter()
                .enumerate()
                .map(|(i, p)| row(p, selected == Some(i), width)),
        );
        return (out, 0);
    }
    // Two columns in the narrowest left column (46).
    let cell_w = PACKED_NAME_W + 8;
    let cols = (usize::from(width) / cell_w).max(1);
    let rows = height.saturating_sub(1).max(1);
    let shown = (rows * cols).min(plan.len());
    // When some must be left out, the last line says so.
    let (rows, shown) = if shown < plan.len() {
        let rows = rows.saturating_sub(1).max(1);
        (rows, (rows * cols).min(plan.len()))
    } else {
        (rows.min(plan.len().div_ceil(cols)), shown)
    };
    let mut out = vec![Line::styled(
        "Circuit and how long it is on:",
        theme::label(),
    )];
    for r in 0..rows {
        let mut spans = Vec::new();
        for c in 0..cols {
            // Down the columns, as one reads a list.
            let i = c * rows + r;
            let Some(p) = plan.get(i).filter(|_| i < shown) else {
                continue;
            };
            let band = if selected == Some(i) {
                theme::selected_row()
            } else {
                Style::new()
            };
            spans.push(Span::styled(fit(&p.name, PACKED_NAME_W), band));
            spans.push(Span::styled(
                format!("{:>6}  ", words::duration(p.on_for)),
                theme::info().patch(band),
            ));
        }
        out.push(Line::from(spans));
    }
    (out, plan.len() - shown)
}

pub fn render(frame: &mut Frame, area: Rect, view: &CheckView) {
    let left_w = (area.width * 58 / 100).clamp(46, 72);
    let [left, _, right] = Layout::horizontal([
        Constraint::Length(left_w),
        Constraint::Length(1),
        Constraint::Fill(1),
    ])
    .areas(area);

    // The circuits get the whole left column: it is what the person confirms.
    let inner = section(frame, left, "Will switch on, one at a time");
    let room = inner.height.saturating_sub(1);
    // The selection runs down the plan, then the exclusions (as the flow moves it).
    let selected = view.current.filter(|&c| c < view.plan.len());
    let selected_excluded = view.current.and_then(|c| c.checked_sub(view.plan.len()));
    let (mut lines, hidden) = plan_lines(&view.plan, selected, inner.width, room.into());
    if view.plan.is_empty() {
        lines = vec![Line::styled("No circuit is switched on.", theme::label())];
    }
    if hidden > 0 {
        lines.push(Line::styled(
            format!("{hidden} more not shown: enlarge the window"),
            theme::caution(),
        ));
    }
    lines.push(Line::styled(
        "Each is put back as it was found.",
        theme::label(),
    ));
    unwrapped::lines(frame.buffer_mut(), inner, &lines);

    let motor_h = if view.planned_motors.is_empty() {
        0
    } else {
        view.planned_motors.len() as u16 + 2
    };
    let [right, motors_area] =
        Layout::vertical([Constraint::Fill(1), Constraint::Length(motor_h)]).areas(right);
    if !view.planned_motors.is_empty() {
        let inner = section(frame, motors_area, "Motors, run both ways and back");
        let mut m = vec![Line::styled(
            format!("{:<NAME_W$} {:>9}", "Motor", "In all"),
            theme::label(),
        )];
        for (motor, d) in &view.planned_motors {
            m.push(Line::from(vec![
                Span::raw(fit(motor.name(), NAME_W)),
                Span::styled(format!(" {:>9}", words::duration(*d)), theme::info()),
            ]));
        }
        unwrapped::lines(frame.buffer_mut(), inner, &m);
    }

    let inner = section(frame, right, "Left alone");
    if view.excluded.is_empty() {
        unwrapped::lines(
            frame.buffer_mut(),
            inner,
            &[Line::styled("Nothing is excluded.", theme::label())],
        );
        return;
    }
    let rows: Vec<Row> = view
        .excluded
        .iter()
        .enumerate()
        .map(|(i, e)| Row {
            head: vec![Span::raw(fit(&e.name, NAME_W)), Span::raw(" ")],
            words: if e.may_include {
                format!("{}; you may take it back", e.why)
            } else {
                e.why.clone()
            },
            words_style: if e.may_include {
                theme::info()
            } else {
                Style::new().fg(theme::LABEL)
            },
            current: selected_excluded == Some(i),
        })
        // Then the switch inputs the person will not be asked to flip, each because it
        // powers something above: never selectable, they follow the exclusions.
        .chain(view.unasked.iter().map(|u| {
            let label = u.input.label();
            let words = u
                .why
                .strip_prefix(&format!("{label} "))
                .unwrap_or(&u.why)
                .to_string();
            Row {
                // Its label only, not the name column: the words get the room.
                head: vec![Span::raw(label), Span::raw(" ")],
                words,
                words_style: theme::caution(),
                current: false,
            }
        }))
        .collect();
    list::render(frame.buffer_mut(), inner, &rows, selected_excluded);
}

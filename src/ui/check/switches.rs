//! Step 2, switch inputs: the person flips a switch while the page watches. Shown: the
//! live inputs 1–10 and the flap and trim inputs with the one under test on a badge,
//! the circuits assigned to it with their live state and current, and the results so
//! far. With no live SYSTEM_STATUS every input reads "-" and says why: an old reading
//! could look like the switch did (or did not) move.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::list::{self, Row};
use super::{fit, head_w, progress_span, progress_words, section, words_style};
use crate::check::state::{CheckView, Input};
use crate::check::words;
use crate::model::{CircuitState, Model};
use crate::protocol::message::SwitchInputs;
use crate::ui::switches::{OFF_MARK, ON_MARK};
use crate::ui::{theme, unwrapped, values};

/// The inputs in the order the strip shows them, with their short labels.
const FLAP_TRIM: [(Input, &str); 6] = [
    (Input::FlapUp, "flap ↑"),
    (Input::FlapDown, "↓"),
    (Input::PitchTrimUp, "pitch ↑"),
    (Input::PitchTrimDown, "↓"),
    // Roll "up" is left and "down" is right (ICD Table 30 note 2).
    (Input::RollTrimUp, "roll ←"),
    (Input::RollTrimDown, "→"),
];

fn input_spans(
    input: Input,
    label: &str,
    live: Option<&SwitchInputs>,
    tested: Option<Input>,
) -> Vec<Span<'static>> {
    let (mark, style) = match live {
        Some(s) => {
            let on = input.is_on(s);
            (if on { ON_MARK } else { OFF_MARK }, theme::on_off(on))
        }
        None => ("-", theme::unknown()),
    };
    if tested == Some(input) {
        // The input under test on a badge: reverse video without colour.
        vec![
            Span::styled(format!("▶{label}{mark}◀"), theme::key()),
            Span::raw(" "),
        ]
    } else {
        vec![
            Span::styled(format!(" {label}"), theme::label()),
            Span::styled(mark, style),
            Span::raw("  "),
        ]
    }
}

fn inputs_lines(live: Option<&SwitchInputs>, tested: Option<Input>) -> Vec<Line<'static>> {
    let numbered: Vec<Span> = (1..=10u8)
        .flat_map(|n| input_spans(Input::Switch(n), &format!("{n:>2}"), live, tested))
        .collect();
    let mut flaps: Vec<Span> = FLAP_TRIM
        .iter()
        .flat_map(|&(i, label)| input_spans(i, label, live, tested))
        .collect();
    if live.is_none() {
        flaps.push(Span::styled(
            "inputs unknown: no live status",
            theme::caution(),
        ));
    }
    vec![Line::from(numbered), Line::from(flaps)]
}

fn circuit_lines(
    view: &CheckView,
    model: &Model,
    now: Instant,
    height: usize,
) -> Vec<Line<'static>> {
    let Some(r) = view.current.and_then(|i| view.switches.get(i)) else {
        return vec![Line::styled("No input under test.", theme::label())];
    };
    if r.circuits.is_empty() {
        return vec![Line::styled(
            "No circuit is assigned to it: the page watches the input alone.",
            theme::label(),
        )];
    }
    let all = model.circuits(now);
    let mut out = vec![Line::styled(
        format!(
            "{:<16} {:<6} {:<8}{:>6}  {}",
            "Circuit", "Pin", "State", "Amps", "Assigned to"
        ),
        theme::label(),
    )];
    for &id in &r.circuits {
        let c = all.iter().find(|c| c.id == id);
        let state = c.map_or(CircuitState::Unknown, |c| c.state);
        out.push(Line::from(vec![
            Span::raw(fit(&model.display_name(id), 16)),
            Span::raw(" "),
            Span::styled(format!("{:<6} ", c.map_or("?", |c| c.pin)), theme::label()),
            Span::styled(fit(&values::state_text(state), 8), theme::state(state)),
            Span::styled(
                format!("{:>6}", values::amps(c.and_then(|c| c.amps))),
                if c.and_then(|c| c.amps).is_some() {
                    Style::new()
                } else {
                    theme::unknown()
                },
            ),
            Span::styled(
                format!(
                    "  {}",
                    c.and_then(|c| c.switch)
                        .map_or_else(|| values::BLANK.into(), words::switch_id)
                ),
                theme::label(),
            ),
        ]));
    }
    if out.len() > height {
        let hidden = out.len() - (height - 1);
        out.truncate(height - 1);
        out.push(Line::styled(format!("and {hidden} more"), theme::label()));
    }
    out
}

/// The results of step 2 as rows, for this screen and the summary.
pub fn rows(view: &CheckView, model: &Model, current: Option<usize>) -> Vec<Row> {
    view.switches
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mark = r.mark();
            Row {
                head: vec![
                    progress_span(mark, i, current),
                    Span::raw(fit(&r.input.label(), head_w(view))),
                    Span::raw(" "),
                ],
                words: progress_words(
                    mark,
                    i,
                    current,
                    words::switch(r, |id| model.display_name(id)),
                ),
                words_style: words_style(mark),
                current: current == Some(i),
            }
        })
        .collect()
}

pub fn render(frame: &mut Frame, area: Rect, view: &CheckView, model: &Model, now: Instant) {
    let live = model.live_system(now).map(|s| &s.switches);
    let tested = view
        .current
        .and_then(|i| view.switches.get(i))
        .map(|r| r.input);
    let n_circuits = view
        .current
        .and_then(|i| view.switches.get(i))
        .map_or(1, |r| {
            r.circuits.len().max(1) + usize::from(!r.circuits.is_empty())
        });
    // The circuits get at most a third of the body; the results the rest.
    let circuits_h = (n_circuits as u16 + 1).min((area.height / 3).max(3));
    let [inputs_area, circuits_area, results_area] = Layout::vertical([
        Constraint::Length(3),
        Constraint::Length(circuits_h),
        Constraint::Fill(1),
    ])
    .areas(area);

    let inner = section(frame, inputs_area, "Switch inputs, live");
    unwrapped::lines(frame.buffer_mut(), inner, &inputs_lines(live, tested));

    let title = match tested {
        Some(i) => format!("Circuits on {}", i.label()),
        None => "Circuits".into(),
    };
    let inner = section(frame, circuits_area, &title);
    let lines = circuit_lines(view, model, now, inner.height.into());
    unwrapped::lines(frame.buffer_mut(), inner, &lines);

    let inner = section(frame, results_area, "Results");
    let rows = rows(view, model, view.current);
    if rows.is_empty() {
        unwrapped::lines(
            frame.buffer_mut(),
            inner,
            &[Line::styled(
                "No input has circuits assigned.",
                theme::label(),
            )],
        );
    }
    list::render(frame.buffer_mut(), inner, &rows, view.current);
}

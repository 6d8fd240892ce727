//! Step 3, circuits: each circuit switched on by DEVICE_POWER in turn, its current read
//! from two fresh DEVICE_STATUS broadcasts, then put back. Shown: the circuit under
//! test with its live state and current against its breaker (a bar, and the share in
//! words), and the results so far. Without a live DEVICE_STATUS the current is "--".

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::list::{self, Row};
use super::{fit, progress_span, progress_words, section, words_style};
use crate::check::state::{BreakerLoad, CheckView, CircuitResult, Mark, Outcome};
use crate::check::words;
use crate::model::{CircuitState, Model};
use crate::protocol::message::Tenths;
use crate::ui::{theme, unwrapped, values};

/// The current against the breaker: a bar and the share in words, in the colour of
/// its meaning (within, tight, over), judged as the flow judges it ([`BreakerLoad`]).
pub fn load_bar(current: Tenths, breaker: u8, width: usize) -> Vec<Span<'static>> {
    let share = if breaker == 0 {
        f32::INFINITY
    } else {
        current.value() / f32::from(breaker)
    };
    let (style, word) = match BreakerLoad::of(current, breaker) {
        BreakerLoad::Over => (theme::alert(), "over the breaker"),
        BreakerLoad::Tight => (theme::caution(), "≥ 80 %: tight"),
        BreakerLoad::Within => (theme::on_off(true), "within"),
    };
    let filled = ((share.min(1.0) * width as f32).round() as usize).min(width);
    vec![
        Span::styled("█".repeat(filled), style),
        Span::styled("░".repeat(width - filled), theme::border()),
        Span::styled(
            if share.is_finite() {
                format!(" {:>3.0} % ", share * 100.0)
            } else {
                " ? % ".into()
            },
            style,
        ),
        Span::styled(word, style),
    ]
}

fn under_test(
    r: &CircuitResult,
    last: Option<&crate::check::trend::LastCheck>,
    model: &Model,
    now: Instant,
    width: u16,
) -> Vec<Line<'static>> {
    let live = model.circuits(now).into_iter().find(|c| c.id == r.id);
    let state = live.as_ref().map_or(CircuitState::Unknown, |c| c.state);
    let amps = live.as_ref().and_then(|c| c.amps);
    let breaker = r.breaker.or(live.as_ref().and_then(|c| c.breaker));
    let mut first = vec![
        Span::styled(r.name.clone(), theme::panel_title()),
        Span::styled(format!("   pin {}", r.pin), theme::label()),
        Span::styled(
            format!(
                "   breaker {}",
                breaker.map_or_else(|| values::BLANK.into(), |b| format!("{b} A"))
            ),
            theme::label(),
        ),
    ];
    if let Some(s) = r.switch {
        first.push(Span::styled(
            format!("   {}", words::switch_id(s)),
            theme::label(),
        ));
    }
    // What it drew at the last check, before this one is measured.
    if let Some(w) = crate::check::trend::trend(last, r.pin, &r.name, None).words() {
        first.push(Span::styled(format!("   {w}"), theme::label()));
    }
    let mut second = vec![
        Span::styled("Now ", theme::label()),
        Span::styled(
            format!("{:<5}", values::state_text(state)),
            theme::state(state),
        ),
        Span::styled(
            format!("{:>6} A", values::amps(amps)),
            if amps.is_some() {
                Style::new()
            } else {
                theme::unknown()
            },
        ),
    ];
    match (amps, breaker) {
        (Some(a), Some(b)) => {
            second.push(Span::styled(format!(" of {b} A  "), theme::label()));
            let bar_w = usize::from(width).saturating_sub(16 + 9 + 26).clamp(8, 40);
            // The model's amps are the unit's tenths over ten: back to tenths exactly.
            second.extend(load_bar(Tenths((a * 10.0).round() as u16), b, bar_w));
        }
        (None, _) => second.push(Span::styled(
            "  no live DEVICE_STATUS: current unknown",
            theme::caution(),
        )),
        (Some(_), None) => second.push(Span::styled("  breaker unknown", theme::label())),
    }
    vec![Line::from(first), Line::from(second)]
}

/// The circuits put back so far by DEVICE_POWER, which the page now holds until
/// their switch is cycled (ICD Appendix A): said as the step goes, not only at its end.
fn held_line(view: &CheckView) -> Option<Line<'static>> {
    if view.to_cycle.is_empty() {
        return None;
    }
    let each: Vec<String> = view
        .to_cycle
        .iter()
        .map(|(_, name, sw)| format!("{name} ({})", words::switch_id(*sw)))
        .collect();
    Some(Line::from(vec![
        Span::styled("Held until its switch is cycled: ", theme::caution()),
        Span::raw(each.join(", ")),
    ]))
}

/// The results of step 3 as rows, for this screen and the summary.
pub fn rows(view: &CheckView, current: Option<usize>) -> Vec<Row> {
    // The name and the pin share the head's width; the pin always whole.
    let (_, pin_w) = super::circuit_columns(view);
    let name_w = super::head_w(view) - 1 - pin_w;
    view.circuits
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mark = r.mark();
            // The last check's current and the change after the finding; a change the
            // rule marks is in words and, on a pass, drawn as a caution too.
            let trend = view.trend(r);
            let mut what = words::circuit(r);
            if let (Some(t), Outcome::Found(_)) = (trend.words(), &r.outcome) {
                what = format!("{what}; {t}");
            }
            let style = if trend.changed() && mark == Mark::Pass {
                theme::caution()
            } else {
                words_style(mark)
            };
            Row {
                head: vec![
                    progress_span(mark, i, current),
                    Span::raw(fit(&r.name, name_w)),
                    Span::raw(" "),
                    Span::styled(fit(r.pin, pin_w), theme::label()),
                    Span::raw(" "),
                ],
                words: progress_words(mark, i, current, what),
                words_style: style,
                current: current == Some(i),
            }
        })
        .collect()
}

pub fn render(frame: &mut Frame, area: Rect, view: &CheckView, model: &Model, now: Instant) {
    let held = held_line(view);
    let [test_area, results_area] = Layout::vertical([
        Constraint::Length(3 + u16::from(held.is_some())),
        Constraint::Fill(1),
    ])
    .areas(area);
    let inner = section(frame, test_area, "Under test");
    let mut lines = match view.current.and_then(|i| view.circuits.get(i)) {
        Some(r) => under_test(r, view.last_check.as_ref(), model, now, inner.width),
        None => vec![Line::styled("No circuit under test.", theme::label())],
    };
    lines.extend(held);
    unwrapped::lines(frame.buffer_mut(), inner, &lines);
    let inner = section(frame, results_area, "Results");
    let rows = rows(view, view.current);
    if rows.is_empty() {
        unwrapped::lines(
            frame.buffer_mut(),
            inner,
            &[Line::styled("No circuit to test.", theme::label())],
        );
    }
    list::render(frame.buffer_mut(), inner, &rows, view.current);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(current: u16, breaker: u8) -> String {
        load_bar(Tenths(current), breaker, 10)
            .last()
            .unwrap()
            .content
            .to_string()
    }

    /// The bar says what the flow found: exactly 80 % of a 9 A breaker (72 tenths,
    /// worked by hand) is tight, as the finding says.
    #[test]
    fn the_bar_calls_exactly_80_percent_tight_as_the_flow_does() {
        assert_eq!(word(72, 9), "≥ 80 %: tight");
        assert_eq!(word(71, 9), "within");
        assert_eq!(word(208, 26), "≥ 80 %: tight");
        assert_eq!(word(260, 26), "≥ 80 %: tight");
        assert_eq!(word(261, 26), "over the breaker");
    }
}

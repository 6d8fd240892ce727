//! The device page: DEVICE_SPEC, DEVICE_NAME and DEVICE_ENABLE of one pin.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use crate::loads::LoadCircuit;
use crate::loads::wiring::amps_text;
use crate::model::Model;
use crate::protocol::names::PIN_NAMES;
use crate::setup::view::{Field, SetupView};
use crate::ui::theme;

/// `wires`: the load file's circuits, for the breaker's limit on the pin's wire.
pub fn render(
    frame: &mut Frame,
    area: Rect,
    model: &Model,
    sv: &SetupView,
    wires: &[LoadCircuit],
    now: Instant,
) {
    let mut extra = Vec::new();
    let id = sv.forms.device.device_id;
    if sv.field() == Field::Breaker
        && let Some(w) = wires.iter().find(|c| c.id == id).and_then(|c| c.wire.wire)
    {
        // The limit beside the number being typed: Enter above it asks first.
        let (limit, style) = match w.max_breaker_amps() {
            Some(m) if f64::from(sv.forms.device.circuit_breaker) <= m => {
                (format!("allows {} A", amps_text(m)), theme::label())
            }
            Some(m) => (
                format!("allows {} A: over it, Enter asks first", amps_text(m)),
                theme::caution(),
            ),
            None => ("gives no breaker for it".into(), theme::caution()),
        };
        extra.push(Line::styled(
            format!("its wire is {w}: AC 43.13-1B Table 11-3 {limit}"),
            style,
        ));
    }
    if sv.field() == Field::Name {
        // Where ←/→ goes next in the Appendix C list.
        let at = PIN_NAMES.iter().position(|&n| n == sv.forms.name);
        let around: Vec<&str> = match at {
            Some(i) => (i.saturating_sub(2)..(i + 3).min(PIN_NAMES.len()))
                .map(|j| PIN_NAMES[j])
                .collect(),
            None => PIN_NAMES.iter().take(5).copied().collect(),
        };
        extra.push(Line::from(vec![
            Span::styled("Appendix C: ", theme::label()),
            Span::styled(around.join(" · "), theme::info()),
        ]));
        extra.push(Line::styled(
            format!("{} of 16 characters", sv.forms.name.len()),
            theme::label(),
        ));
    }
    if model.secondary_alternator() == Some(id) {
        extra.push(Line::styled(
            "this pin is the secondary alternator: it may not share the primary's switch",
            theme::caution(),
        ));
    }
    if let Some(w) = model.wig_wag_spec.map(|w| w.value)
        && (w.device_one == Some(id) || w.device_two == Some(id))
    {
        extra.push(Line::styled(
            "this pin is a wig-wag device: it must stay on a switch 1–10",
            theme::caution(),
        ));
    }
    super::render_form(frame, area, model, sv, now, extra);
}

//! The system page: SYSTEM_SPEC (overvoltage limit, secondary alternator).

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::Line;

use crate::model::Model;
use crate::protocol::device::FIELD_PRI;
use crate::setup::view::{SetupView, switch_text};
use crate::ui::theme;

pub fn render(frame: &mut Frame, area: Rect, model: &Model, sv: &SetupView, now: Instant) {
    let mut extra = Vec::new();
    let switch = |id: u8| {
        model.device_specs[id as usize]
            .map_or("not known".to_string(), |s| switch_text(s.value.switch_id))
    };
    extra.push(Line::styled(
        format!("primary alternator (Field_Pri): {}", switch(FIELD_PRI)),
        theme::label(),
    ));
    if let Some(id) = sv.forms.system.secondary_alternator {
        extra.push(Line::styled(
            format!(
                "{} is on {}; the two alternators need different switches",
                model.display_name(id),
                switch(id)
            ),
            theme::label(),
        ));
    }
    super::render_form(frame, area, model, sv, now, extra);
}

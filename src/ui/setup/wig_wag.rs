//! The wig-wag page: WIG_WAG_SPEC (both devices, warm-up, speed).

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::Line;

use crate::model::Model;
use crate::setup::view::{SetupView, switch_text};
use crate::ui::theme;

pub fn render(frame: &mut Frame, area: Rect, model: &Model, sv: &SetupView, now: Instant) {
    let w = sv.forms.wig_wag;
    let extra = [w.device_one, w.device_two]
        .into_iter()
        .flatten()
        .map(|id| {
            let sw = model.device_specs[id as usize].map(|s| s.value.switch_id);
            let ok = matches!(sw, Some(crate::protocol::message::SwitchId::Input(_)));
            Line::styled(
                format!(
                    "{}: {}",
                    model.display_name(id),
                    sw.map_or("switch not known".into(), switch_text)
                ),
                if ok { theme::label() } else { theme::caution() },
            )
        })
        .collect();
    super::render_form(frame, area, model, sv, now, extra);
}

//! The pitch and roll trim pages: every TRIM_SPEC field (ICD Table 15), the live
//! position, and the motor run from here to calibrate the endpoints.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;

use crate::model::Model;
use crate::ui::state::{MotorRun, ViewState};

pub fn render(
    frame: &mut Frame,
    area: Rect,
    model: &Model,
    view: &ViewState,
    running: Option<MotorRun>,
    now: Instant,
) {
    let motor = view.setup.page.motor().expect("a trim page");
    let extra = super::flaps::live_lines(model, running, motor, now);
    super::render_form(frame, area, model, &view.setup, now, extra);
}

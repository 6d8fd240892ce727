//! The flaps and the pitch and roll trim pages: every FLAP_SPEC or TRIM_SPEC field
//! (ICD Tables 16 and 15), the live position, and the motor run from here to calibrate
//! the endpoints.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use crate::model::{Model, Motor};
use crate::ui::state::{MotorRun, ViewState};
use crate::ui::theme;

/// The live position line and the motor's run.
fn live_lines(
    model: &Model,
    running: Option<MotorRun>,
    motor: Motor,
    now: Instant,
) -> Vec<Line<'static>> {
    let live = model.live_flap_trim(now).map(|ft| {
        let a = ft.axis(motor.axis());
        (a.position, a.enabled, a.motor_running)
    });
    let mut spans = vec![Span::styled("live position ", theme::label())];
    match live {
        Some((pos, enabled, running)) => {
            spans.push(Span::styled(format!("{pos:>3}"), theme::panel_title()));
            if running {
                spans.push(Span::styled("  motor running", theme::caution()));
            }
            if !enabled {
                spans.push(Span::styled(
                    "  not enabled: the unit will not run it",
                    theme::caution(),
                ));
            }
        }
        None => spans.push(Span::styled(
            "-- (no live FLAP_TRIM_STATUS)",
            theme::unknown(),
        )),
    }
    if let Some(run) = running.filter(|r| r.motor == motor) {
        spans.push(Span::styled(
            format!("  ◀ running {} while held", run.direction),
            theme::caution(),
        ));
    }
    vec![Line::from(spans)]
}

pub fn render(
    frame: &mut Frame,
    area: Rect,
    model: &Model,
    view: &ViewState,
    running: Option<MotorRun>,
    now: Instant,
) {
    let extra = match view.setup.page.motor() {
        Some(motor) => live_lines(model, running, motor, now),
        None => Vec::new(),
    };
    super::render_form(frame, area, model, &view.setup, now, extra);
}

//! ratatui widgets that render the model and nothing else: no I/O, no clocks. The
//! caller passes `now`, so the same model renders the same frame every time.

pub mod aircraft_page;
pub mod check;
pub mod circuit_history;
pub mod comm_banner;
pub mod detail;
pub mod device_list;
pub mod events;
pub mod help;
pub mod key_bar;
pub mod link_health;
pub mod motors;
pub mod osc11;
pub mod palette;
pub mod panel;
pub mod plot;
pub mod remote;
pub mod setup;
pub mod state;
pub mod switches;
pub mod system_panel;
pub mod theme;
pub mod title_bar;
pub mod too_small;
pub mod traffic;
pub mod unwrapped;
pub mod values;
pub mod wrap;

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout};

use crate::control::run_state::ControlState;
use crate::model::{Circuit, Model};
use state::{Overlay, ViewState};

/// The smallest terminal the page lays out in; below it, a message says so.
pub const MIN_WIDTH: u16 = 80;
pub const MIN_HEIGHT: u16 = 24;
/// The widest the device list (and the detail under it) gets: the name column is then
/// 21 wide, room for DEVICE_NAME's 16 characters (ICD Table 21).
pub const LIST_MAX_WIDTH: u16 = 66;

/// The width of the left column (the device list, the detail, and on short terminals
/// the link lines) on a terminal `width` columns wide. The list needs ~56 columns for
/// its seven columns, and past [`LIST_MAX_WIDTH`] its name column would only stretch
/// blank space between a name and its pin: a wide terminal's extra width goes to the
/// right-hand panels (gauges, plot, events) instead.
pub fn left_column_width(width: u16) -> u16 {
    (width * 55 / 100).clamp(56, LIST_MAX_WIDTH)
}

/// The rows of the device list in display order (flaps and trims grouped apart from
/// the rest; by pin or alphabetical per `view.sort`) — the app uses it to move the
/// selection.
pub fn ordered_circuits(model: &Model, view: &ViewState, now: Instant) -> Vec<Circuit> {
    device_list::ordered(model, view, now)
}

/// Draws the page as the person sees it: [`render`], then repainted in the palette
/// `view.theme` chose (dark, light or no colour). `control` is the controller's state
/// (the motor run it streams, its key release mode and repeat timing), read from it
/// for this frame.
pub fn draw(
    frame: &mut Frame,
    model: &Model,
    view: &ViewState,
    control: &ControlState,
    now: Instant,
) {
    render(frame, model, view, control, now);
    view.theme.palette.paint(frame.buffer_mut());
}

/// Draws the whole page for `model` as it stands at `now`, in the page's colour words
/// (Appendix A's green=on, white=off, red=faulted); see [`palette`] for what they
/// become on the terminal.
pub fn render(
    frame: &mut Frame,
    model: &Model,
    view: &ViewState,
    control: &ControlState,
    now: Instant,
) {
    if view.screen == state::Screen::Traffic {
        return traffic::render(frame, model, view, now);
    }
    if view.screen == state::Screen::Setup {
        return setup::render(frame, model, view, control.run, now);
    }
    let area = frame.area();
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        too_small::render(frame, MIN_WIDTH, MIN_HEIGHT);
        return;
    }
    let rows = ordered_circuits(model, view, now);
    let selected = view
        .selected
        .and_then(|id| rows.iter().find(|c| c.id == id));
    let banner = comm_banner::banner(model, now);
    // Tall terminals get the link as a panel in the right column.
    let link_panel = area.height >= 36;
    let [title, banner_area, body, footer] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(comm_banner::height(
            banner.as_ref(),
            area.height,
            area.width,
        )),
        Constraint::Fill(1),
        Constraint::Length(key_bar::height(view, area.width)),
    ])
    .areas(area);
    match &view.remote {
        // The remote's note takes the title's right end, and the title the rest:
        // the title shortens its own words to fit rather than being painted over.
        Some(r) => {
            let note = remote::title_note(r, title.width);
            let w = (note.chars().count() as u16).min(title.width);
            let [left, right] =
                Layout::horizontal([Constraint::Fill(1), Constraint::Length(w)]).areas(title);
            title_bar::render(frame, left, model, now);
            remote::render_title(frame, right, &note);
        }
        None => title_bar::render(frame, title, model, now),
    }
    if let Some(b) = &banner {
        comm_banner::render(frame, banner_area, b);
    }
    key_bar::render(frame, footer, view);

    let left_w = left_column_width(area.width);
    let [left, right] =
        Layout::horizontal([Constraint::Length(left_w), Constraint::Fill(1)]).areas(body);
    let detail_h = if body.height >= 30 { 12 } else { 7 };
    // Short terminals get the link as lines at the foot of the left column (every row
    // of the column ends at its edge), leaving the right column room for the plot.
    let link_rows = if link_panel {
        0
    } else {
        link_health::line_rows(model, now, left_w)
    };
    let [list, detail_area, link_line] = Layout::vertical([
        Constraint::Fill(1),
        Constraint::Length(detail_h),
        Constraint::Length(link_rows),
    ])
    .areas(left);
    device_list::render(frame, list, &rows, view, model.rereading().is_some());
    // Without a load file no circuit has a wire to show, not even "not entered".
    let wire = selected.filter(|_| !view.wires.is_empty()).map(|c| {
        let system = crate::loads::wiring::model_system(model, now);
        crate::loads::wiring::circuit_row(&view.wires, c, system.as_ref())
    });
    detail::render(
        frame,
        detail_area,
        model,
        selected,
        wire.as_ref(),
        view.last_check.as_ref(),
    );
    if !link_panel {
        link_health::render_line(frame, link_line, model, now);
    }

    let [system, switches_area, motors_area, plot_area, link] = Layout::vertical([
        Constraint::Length(system_panel::height(model, now, right.width)),
        Constraint::Length(switches::height(right.width)),
        Constraint::Length(motors::height(model, now, right.width)),
        Constraint::Fill(1),
        Constraint::Length(if link_panel {
            link_health::height(right.width)
        } else {
            0
        }),
    ])
    .areas(right);
    system_panel::render(frame, system, model, now);
    switches::render(frame, switches_area, model, now);
    motors::render(frame, motors_area, model, control, now);
    // Tall terminals share the plot's space with the event log.
    if plot_area.height >= 12 {
        let [plot_part, events_part] = Layout::vertical([
            Constraint::Fill(1),
            Constraint::Length(events::height(model, now, plot_area.height / 2)),
        ])
        .areas(plot_area);
        plot::render(frame, plot_part, model, now);
        events::render(frame, events_part, model, now);
    } else {
        plot::render(frame, plot_area, model, now);
    }
    if link_panel {
        link_health::render(frame, link, model, now);
    }

    if view.overlay == Overlay::Help {
        let replay = matches!(model.source, crate::model::Source::Replay { .. });
        help::render(frame, view, control, replay);
    }
    if view.overlay == Overlay::Remote
        && let Some(r) = &view.remote
    {
        remote::render(frame, r);
    }
}

//! A terminal smaller than the layout needs gets a plain message instead of a garbled
//! page.

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout};
use ratatui::text::{Line, Text};
use ratatui::widgets::{Paragraph, Wrap};

use super::theme;

pub fn render(frame: &mut Frame, min_width: u16, min_height: u16) {
    let area = frame.area();
    let text = Text::from(vec![
        Line::styled("VERTICAL POWER VP-X", theme::brand()),
        Line::styled("Terminal too small", theme::caution()),
        Line::raw(format!(
            "{}×{} now, needs {min_width}×{min_height}.",
            area.width, area.height
        )),
        Line::raw("Enlarge the window or use a smaller font."),
        Line::styled("Until then keys do nothing; Ctrl-C quits.", theme::label()),
    ])
    .centered();
    let [mid] = Layout::vertical([Constraint::Length(5)])
        .flex(Flex::Center)
        .areas(area);
    frame.render_widget(Paragraph::new(text).wrap(Wrap { trim: true }), mid);
}

//! The top line: the Vertical Power mark (Appendix A asks for it on the page), the
//! source, the link state and the unit's version.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::{link_health, theme};
use crate::model::Model;

pub const MARK: &str = " VERTICAL POWER ";

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let mut spans = vec![
        Span::styled(MARK, theme::brand()),
        Span::styled(" VP-X electrical ", theme::panel_title()),
        link_health::source_span(&model.source),
        Span::raw(" "),
        link_health::connection_span(model, now),
    ];
    if let Some(v) = model.version.map(|v| v.value) {
        spans.push(Span::styled(
            format!(
                "  {} sw {}.{}",
                v.hardware_version.name(),
                v.software_major,
                v.software_minor
            ),
            theme::label(),
        ));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

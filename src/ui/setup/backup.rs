//! Backup and erase: save the unit's configuration to a file, load one (with its
//! differences shown first), re-read the unit, and EEPROM_ERASE behind a confirmation.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Row, Table};

use crate::setup::view::{Diagnostic, Field, SetupView};
use crate::ui::theme;

pub fn render(frame: &mut Frame, area: Rect, sv: &SetupView) {
    let rows: Vec<Row> = sv
        .page
        .fields()
        .iter()
        .map(|&f| {
            let value = match f {
                Field::File if sv.file.is_empty() && f == sv.field() => {
                    Span::styled("▏(type a path)", theme::unknown())
                }
                Field::File if sv.file.is_empty() => Span::styled("(none)", theme::unknown()),
                Field::File if f == sv.field() => Span::raw(format!("{}▏", sv.file)),
                Field::File => Span::raw(sv.file.clone()),
                Field::Erase => match sv.erase {
                    Diagnostic::Waiting { .. } => {
                        Span::styled("waiting for the unit…", theme::caution())
                    }
                    Diagnostic::Answered { .. } => {
                        Span::styled("erased: factory settings", theme::caution())
                    }
                    Diagnostic::NoAnswer => Span::styled("no answer", theme::alert()),
                    Diagnostic::Idle => Span::styled("asks first", theme::label()),
                },
                _ => Span::styled("Enter", theme::label()),
            };
            let row = Row::new(vec![
                Line::styled(f.label(), theme::label()),
                Line::from(value),
            ]);
            if f == sv.field() {
                row.style(theme::selected_row())
            } else {
                row
            }
        })
        .collect();
    let [heading, table, help] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(sv.page.fields().len() as u16),
        Constraint::Fill(1),
    ])
    .areas(area);
    frame.render_widget(
        Paragraph::new(Line::styled("Backup and erase", theme::panel_title())),
        heading,
    );
    frame.render_widget(
        Table::new(rows, [Constraint::Length(22), Constraint::Fill(1)]),
        table,
    );
    frame.render_widget(
        Paragraph::new(Line::styled(sv.field().help(0, sv.page), theme::label())),
        help,
    );
}

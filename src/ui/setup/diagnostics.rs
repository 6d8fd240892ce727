//! Diagnostics: PING round-trip time and VERSION (hardware name, software version).

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Row, Table};

use crate::model::Model;
use crate::setup::view::{Diagnostic, Field, SetupView};
use crate::ui::theme;

fn diagnostic(
    p: &Diagnostic,
    answered: impl FnOnce(std::time::Duration) -> String,
) -> Span<'static> {
    match p {
        Diagnostic::Idle => Span::styled("not asked yet: Enter", theme::unknown()),
        Diagnostic::Waiting { attempt, of } if *of > 1 => {
            Span::styled(format!("waiting (try {attempt}/{of})"), theme::caution())
        }
        Diagnostic::Waiting { .. } => Span::styled("waiting…", theme::caution()),
        Diagnostic::Answered { after } => Span::styled(answered(*after), theme::on_off(true)),
        Diagnostic::NoAnswer => Span::styled("no answer", theme::alert()),
    }
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, sv: &SetupView, now: Instant) {
    let version = model.version.map(|v| v.value);
    let rows: Vec<Row> = sv
        .page
        .fields()
        .iter()
        .map(|&f| {
            let value = match f {
                Field::Ping => diagnostic(&sv.ping, |d| {
                    format!("{:.1} ms round trip", d.as_secs_f64() * 1000.0)
                }),
                _ => match (&sv.version, version) {
                    (Diagnostic::Waiting { .. } | Diagnostic::NoAnswer, _) | (_, None) => {
                        diagnostic(&sv.version, |_| String::new())
                    }
                    (_, Some(v)) => Span::styled(
                        format!(
                            "{} (hardware {}), software {}.{}",
                            v.hardware_version.name(),
                            v.hardware_version.to_byte(),
                            v.software_major,
                            v.software_minor
                        ),
                        theme::info(),
                    ),
                },
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
    let [heading, table, help] = ratatui::layout::Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(3),
        Constraint::Fill(1),
    ])
    .areas(area);
    frame.render_widget(
        Paragraph::new(Line::styled("Diagnostics", theme::panel_title())),
        heading,
    );
    frame.render_widget(
        Table::new(rows, [Constraint::Length(22), Constraint::Fill(1)]),
        table,
    );
    let mut lines = vec![Line::styled(sv.field().help(0, sv.page), theme::label())];
    if let Some(v) = model.version {
        lines.push(Line::styled(
            format!("VERSION last heard {:.0} s ago", v.age(now).as_secs_f64()),
            theme::label(),
        ));
    }
    frame.render_widget(Paragraph::new(lines), help);
}

//! Backup and erase: save the unit's configuration to a file, load one (with its
//! differences shown first), re-read the unit, and EEPROM_ERASE behind a confirmation.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use crate::setup::view::{Diagnostic, Field, SetupView};
use crate::ui::theme;

pub fn render(frame: &mut Frame, area: Rect, sv: &SetupView) {
    let value = |f| match f {
        Field::File if sv.file.is_empty() && f == sv.field() => {
            Span::styled("▏(type a path)", theme::unknown())
        }
        Field::File if sv.file.is_empty() => Span::styled("(none)", theme::unknown()),
        Field::File if f == sv.field() => Span::raw(format!("{}▏", sv.file)),
        Field::File => Span::raw(sv.file.clone()),
        Field::Erase => match sv.erase {
            Diagnostic::Waiting { .. } => Span::styled("waiting for the unit…", theme::caution()),
            Diagnostic::Answered { .. } => {
                Span::styled("erased: factory settings", theme::caution())
            }
            Diagnostic::NoAnswer => Span::styled("no answer", theme::alert()),
            Diagnostic::Idle => Span::styled("asks first", theme::label()),
        },
        _ => Span::styled("Enter", theme::label()),
    };
    let help = vec![Line::styled(sv.field().help(0, sv.page), theme::label())];
    super::render_actions(frame, area, sv, "Backup and erase", value, help);
}

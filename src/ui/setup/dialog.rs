//! The confirmations: EEPROM_ERASE (what is lost, a backup first), applying a
//! loaded backup (what changes), and a page's writes that disarm a protection (what
//! it turns off).

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Wrap};

use crate::model::Model;
use crate::setup::view::{Dialog, SetupView, missing_summary};
use crate::ui::theme;

fn popup(frame: &mut Frame, height: u16) -> Rect {
    let area = frame.area();
    let width = area.width.saturating_sub(8).min(96);
    let [row] = Layout::vertical([Constraint::Length(height.min(area.height - 2))])
        .flex(Flex::Center)
        .areas(area);
    let [p] = Layout::horizontal([Constraint::Length(width)])
        .flex(Flex::Center)
        .areas(row);
    p
}

fn key(k: &str, what: String) -> Line<'static> {
    Line::from(vec![
        Span::styled(format!(" {k} "), theme::key()),
        Span::raw(format!(" {what}")),
    ])
}

pub fn render(frame: &mut Frame, model: &Model, sv: &SetupView, dialog: &Dialog) {
    let (title, lines) = match dialog {
        Dialog::None => return,
        Dialog::Erase { missing, backed_up } => {
            ("Erase the EEPROM?", erase(model, sv, missing, backed_up))
        }
        Dialog::Load {
            file,
            changes,
            notes,
            writes,
        } => ("Apply this backup?", load(file, changes, notes, *writes)),
        Dialog::Disarm { consequences } => ("Turn a protection off?", disarm(consequences)),
    };
    // Rows once wrapped inside the border, so the last key is never cut off.
    let inner = frame
        .area()
        .width
        .saturating_sub(8)
        .min(96)
        .saturating_sub(2)
        .max(1) as usize;
    // Word wrap can take a row more than the characters need.
    let rows: usize = lines.iter().map(|l| (l.width() + 8).div_ceil(inner)).sum();
    let area = popup(frame, rows as u16 + 2);
    frame.render_widget(Clear, area);
    frame.render_widget(
        Paragraph::new(lines).wrap(Wrap { trim: false }).block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .border_style(theme::caution())
                .title(Span::styled(format!(" {title} "), theme::caution())),
        ),
        area,
    );
}

fn erase(
    model: &Model,
    sv: &SetupView,
    missing: &[String],
    backed_up: &Option<String>,
) -> Vec<Line<'static>> {
    let named: Vec<String> = model
        .names
        .iter()
        .flatten()
        .map(|n| n.value.text())
        .filter(|n| !n.trim().is_empty())
        .collect();
    let mut lines = vec![
        Line::styled(
            "EEPROM_ERASE puts every setting back to the ICD Appendix F factory values:",
            theme::panel_title(),
        ),
        Line::raw("• every pin's breaker, switch and current-fault check (DEVICE_SPEC 1–28)"),
        Line::raw(format!(
            "• every name ({}: {})",
            named.len(),
            if named.is_empty() {
                "none known".to_string()
            } else {
                let mut s = named.iter().take(8).cloned().collect::<Vec<_>>().join(", ");
                if named.len() > 8 {
                    s.push_str(", …");
                }
                s
            }
        )),
        Line::raw("• which devices the page shows (DEVICE_ENABLE)"),
        Line::raw("• the system spec, flap and both trim calibrations, and the wig-wag"),
        Line::styled(
            "The unit then reports a data integrity error until it is power cycled.",
            theme::label(),
        ),
        Line::raw(""),
    ];
    match backed_up {
        Some(words) => lines.push(Line::styled(format!("✓ {words}"), theme::on_off(true))),
        None if !missing.is_empty() => {
            lines.push(Line::styled(
                format!(
                    "A backup now would be incomplete: the page has not heard {}.",
                    missing_summary(missing)
                ),
                theme::caution(),
            ));
            lines.push(key("r", "re-read the unit first".into()));
        }
        None => {
            let file = if sv.file.trim().is_empty() {
                "the Backup file field is empty: Esc, type one, then come back".to_string()
            } else {
                format!("back up first to {}", sv.file.trim())
            };
            lines.push(key("b", file));
        }
    }
    lines.push(key("y", "erase now".into()));
    lines.push(key("Esc", "cancel: nothing is sent".into()));
    lines
}

fn load(file: &str, changes: &[String], notes: &[String], writes: usize) -> Vec<Line<'static>> {
    let mut lines = vec![Line::styled(
        format!(
            "{file} differs from the unit in {} setting{} ({writes} write{}):",
            changes.len(),
            if changes.len() == 1 { "" } else { "s" },
            if writes == 1 { "" } else { "s" }
        ),
        theme::panel_title(),
    )];
    const SHOWN: usize = 10;
    for c in changes.iter().take(SHOWN) {
        lines.push(Line::raw(format!("• {c}")));
    }
    if changes.len() > SHOWN {
        lines.push(Line::styled(
            format!("… and {} more", changes.len() - SHOWN),
            theme::label(),
        ));
    }
    for n in notes {
        lines.push(Line::styled(n.clone(), theme::caution()));
    }
    lines.push(Line::raw(""));
    lines.push(key(
        "y",
        "apply, one write at a time, each waiting for the unit's acknowledgement".into(),
    ));
    lines.push(key("Esc", "cancel: nothing is sent".into()));
    lines
}

fn disarm(consequences: &[String]) -> Vec<Line<'static>> {
    let mut lines = vec![Line::styled(
        "Nothing is sent yet. This write turns a protection off:",
        theme::panel_title(),
    )];
    for c in consequences {
        lines.push(Line::raw(format!("• {c}")));
    }
    lines.push(Line::raw(""));
    lines.push(key("y", "send it anyway: I mean this".into()));
    lines.push(key("Esc", "cancel: nothing is sent, the edit stays".into()));
    lines
}

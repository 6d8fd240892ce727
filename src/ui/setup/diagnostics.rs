//! Diagnostics: PING round-trip time and VERSION (hardware name, software version).

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

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
    let value = |f| match f {
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
    // A blank row between the answers and the help.
    let mut help = vec![
        Line::raw(""),
        Line::styled(sv.field().help(0, sv.page), theme::label()),
    ];
    if let Some(v) = model.version {
        help.push(Line::styled(
            format!("VERSION last heard {:.0} s ago", v.age(now).as_secs_f64()),
            theme::label(),
        ));
    }
    super::render_actions(frame, area, sv, "Diagnostics", value, help);
}

//! The event log: commands sent, faults seen, link changes and commands taken from the
//! XFSp network, newest last; and, when the page forwards air data to the unit, what
//! it sent. A mechanic reads what happened without opening the traffic view.

use std::time::{Duration, Instant};

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use super::panel;
use super::{theme, values};
use crate::model::{LogLevel, Model};

/// EXTERNAL_DATA goes out at 1 Hz; older than this, the page no longer says it is
/// forwarding.
const FORWARDING_FRESH: Duration = Duration::from_millis(2500);

/// The line that says what the page sends the unit as EXTERNAL_DATA, if it does.
pub fn forwarding(model: &Model, now: Instant) -> Option<Line<'static>> {
    let sent = model.external_data_sent.as_ref()?;
    let d = sent.fresh(now, FORWARDING_FRESH)?;
    let v = d.valid;
    let field = |name: &str, valid: bool, value: String| {
        if valid {
            Span::styled(format!("{name} {value}  "), theme::on_off(true))
        } else {
            Span::styled(format!("{name} --  "), theme::unknown())
        }
    };
    Some(Line::from(vec![
        Span::styled("to VP-X: ", theme::label()),
        field(
            "IAS",
            v.indicated_airspeed,
            d.indicated_airspeed.to_string(),
        ),
        field("GS", v.ground_speed, d.ground_speed.to_string()),
        field("ALT", v.baro_altitude, format!("{} ft", d.baro_altitude)),
        field("FP", v.fuel_pressure, format!("{} psi", d.fuel_pressure)),
        field("RPM", v.rpm, d.rpm.to_string()),
    ]))
}

/// Rows the log wants, up to `max`: its title and every line, so the plot beside it
/// keeps the rest.
pub fn height(model: &Model, now: Instant, max: u16) -> u16 {
    let lines = model.events.len() + usize::from(forwarding(model, now).is_some());
    (lines.max(1) as u16 + 1).clamp(3.min(max), max)
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let inner = panel::titled(frame.buffer_mut(), area, " Events ");
    let mut lines: Vec<Line> = Vec::new();
    if let Some(f) = forwarding(model, now) {
        lines.push(f);
    }
    let room = (inner.height as usize).saturating_sub(lines.len());
    let skip = model.events.len().saturating_sub(room);
    for e in model.events.iter().skip(skip) {
        let style = match e.level {
            LogLevel::Info => theme::label(),
            LogLevel::Warning => theme::caution(),
            LogLevel::Alert => theme::alert(),
        };
        lines.push(Line::from(vec![
            Span::styled(
                format!("{:>6} ago ", values::age(now, e.at)),
                theme::unknown(),
            ),
            Span::styled(e.text.clone(), style),
        ]));
    }
    if lines.is_empty() {
        lines.push(Line::styled("nothing yet", theme::unknown()));
    }
    super::unwrapped::lines(frame.buffer_mut(), inner, &lines);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Source, Stamped};
    use crate::protocol::message::{ExternalData, ExternalValidity};
    use ratatui::Terminal;
    use ratatui::backend::TestBackend;
    use ratatui::style::Color;

    fn screen(model: &Model, now: Instant) -> (String, ratatui::buffer::Buffer) {
        let mut t = Terminal::new(TestBackend::new(70, 6)).unwrap();
        t.draw(|f| render(f, f.area(), model, now)).unwrap();
        let buf = t.backend().buffer().clone();
        let text = (0..6)
            .map(|y| {
                (0..70)
                    .map(|x| buf[(x, y)].symbol().to_string())
                    .collect::<String>()
                    + "\n"
            })
            .collect();
        (text, buf)
    }

    #[test]
    fn shows_network_commands_and_what_is_forwarded_and_forgets_stale_forwarding() {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        m.log(t0, LogLevel::Alert, "Nav Lt: SHORT_CIRCUIT".into());
        m.log(
            t0,
            LogLevel::Info,
            "XFSp 0x0777: ECBSTAT OFF for GPS 1".into(),
        );
        let valid = ExternalValidity {
            indicated_airspeed: true,
            ..Default::default()
        };
        m.external_data_sent = Some(Stamped::new(
            ExternalData {
                indicated_airspeed: 95,
                valid,
                ..Default::default()
            },
            t0,
        ));
        let (text, buf) = screen(&m, t0 + Duration::from_secs(1));
        assert!(text.contains("IAS 95") && text.contains("GS --"), "{text}");
        assert!(
            text.contains("XFSp 0x0777: ECBSTAT OFF for GPS 1"),
            "{text}"
        );
        let y = (0..6u16)
            .find(|&y| {
                (0..70u16)
                    .map(|x| buf[(x, y)].symbol().to_string())
                    .collect::<String>()
                    .contains("SHORT")
            })
            .unwrap();
        let x = (0..70u16).find(|&x| buf[(x, y)].symbol() == "N").unwrap();
        assert_eq!(buf[(x, y)].fg, Color::Red, "alerts are red");
        let (later, _) = screen(&m, t0 + Duration::from_secs(5));
        assert!(
            !later.contains("IAS 95"),
            "no old forwarding shown as current: {later}"
        );
    }
}

//! The external switch inputs 1–10 and the flap/trim switches, live: an installer flips
//! a switch and watches its input change here.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use super::panel;
use super::theme;
use crate::model::Model;

pub const ON_MARK: &str = "●";
pub const OFF_MARK: &str = "○";
const UNKNOWN_MARK: &str = "-";

pub fn height(width: u16) -> u16 {
    // title + 1..10 (two rows when narrow) + flap/trim (two rows when narrow)
    if width >= 44 { 3 } else { 5 }
}

fn input(label: String, state: Option<bool>) -> Vec<Span<'static>> {
    let (mark, style) = match state {
        Some(on) => (if on { ON_MARK } else { OFF_MARK }, theme::on_off(on)),
        None => (UNKNOWN_MARK, theme::unknown()),
    };
    vec![
        Span::styled(label, theme::label()),
        Span::styled(mark, style),
        Span::raw(" "),
    ]
}

pub fn render(frame: &mut Frame, area: Rect, model: &Model, now: Instant) {
    let sw = model.live_system(now).map(|s| s.switches);
    let mut lines = Vec::new();
    let numbered: Vec<Vec<Span>> = (0..10)
        .map(|i| input(format!("{:>2}", i + 1), sw.map(|s| s.switch[i])))
        .collect();
    let wide = area.width >= 44;
    if wide {
        lines.push(Line::from(numbered.concat()));
    } else {
        lines.push(Line::from(numbered[..5].concat()));
        lines.push(Line::from(numbered[5..].concat()));
    }
    let flap = [
        input("flap ↑".into(), sw.map(|s| s.flap_up)),
        input("↓".into(), sw.map(|s| s.flap_down)),
    ]
    .concat();
    // Roll "up" is left and "down" is right (ICD Table 30 note 2).
    let trim = [
        input("pitch ↑".into(), sw.map(|s| s.pitch_trim_up)),
        input("↓".into(), sw.map(|s| s.pitch_trim_down)),
        input("roll ←".into(), sw.map(|s| s.roll_trim_up)),
        input("→".into(), sw.map(|s| s.roll_trim_down)),
    ]
    .concat();
    if wide {
        lines.push(Line::from([flap, trim].concat()));
    } else {
        lines.push(Line::from(flap));
        lines.push(Line::from(trim));
    }
    let inner = panel::titled(frame.buffer_mut(), area, " Switch inputs ");
    // Lines are laid out above for the width; no wrapping needed.
    super::unwrapped::lines(frame.buffer_mut(), inner, &lines);
}

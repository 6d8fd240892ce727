//! The help overlay: every key the page answers to.

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Wrap};

use super::state::{ReleaseMode, ViewState};
use super::theme;

/// The key list, agreed with the control module; one place so the overlay and any
/// test of the key map read the same words.
pub const KEYS: &[(&str, &str)] = &[
    ("↑/↓  j/k", "move the selection (never runs a motor)"),
    ("Shift+↑  u", "flaps / pitch trim row: run up while held"),
    ("Shift+↓  d", "flaps / pitch trim row: run down while held"),
    ("Shift+←  ,", "roll trim row: run left while held"),
    ("Shift+→  .", "roll trim row: run right while held"),
    ("any key", "stops a running motor (and does nothing else)"),
    ("o  Enter", "switch the selected device on (DEVICE_POWER)"),
    ("f", "switch the selected device off (DEVICE_POWER)"),
    // One line for both, so the list still fits 80×24.
    ("r  Y", "reset the fault (DEVICE_CLEAR); Y: confirm a 2nd"),
    ("R", "reset the system fault (DEVICE_CLEAR 255)"),
    ("w", "wig-wag steady / auto (WIG_WAG_MODE)"),
    ("s", "sort by pin / by name"),
    // t and c share a line so the phone remote's fits 80×24 too.
    ("t  c", "traffic view; c: setup screens"),
    ("i", "installation check"),
    ("p  P", "phone remote: on / show / off; P: unpair phones"),
    ("?  Esc", "this help"),
    ("q  Ctrl-C", "quit"),
];

/// Extra keys while the page replays a capture (handled by the app's replay, not the
/// keymap: nothing in replay reaches a unit).
pub const REPLAY_KEYS: &[(&str, &str)] = &[
    ("p", "replay: play / pause"),
    (".", "replay: step one record"),
    ("+  -", "replay: faster / slower"),
];

/// How a held motor key is judged here, in words: what ends a run, and how far a tap
/// moves a motor.
pub fn release_lines(view: &ViewState) -> Vec<String> {
    match (view.release_mode, view.repeat) {
        (ReleaseMode::KeyRelease, _) => {
            vec!["key release seen: a run ends when you let go (or if repeats stop)".into()]
        }
        (ReleaseMode::AutoRepeat, None) => vec![
            "no key release here: a run ends ~0.2 s after key repeats stop".into(),
            "a tap (no repeat) runs a motor until the first repeat is due".into(),
        ],
        (ReleaseMode::AutoRepeat, Some(t)) => vec![
            format!(
                "no key release here: a run ends {} ms after key repeats stop",
                t.end_gap.as_millis()
            ),
            format!(
                "a tap (no repeat) runs a motor {} ms at most",
                t.first_window.as_millis()
            ),
        ],
    }
}

pub fn render(frame: &mut Frame, view: &ViewState, replay: bool) {
    let keys: Vec<&(&str, &str)> = KEYS
        .iter()
        .chain(if replay { REPLAY_KEYS } else { &[] })
        .collect();
    let area = frame.area();
    let width = (keys
        .iter()
        .map(|(_, d)| 10 + d.chars().count())
        .max()
        .unwrap_or(40) as u16
        + 6)
    .min(area.width.saturating_sub(2));
    let release = release_lines(view);
    let height = (keys.len() as u16 + 6 + release.len() as u16 + u16::from(replay))
        .min(area.height.saturating_sub(2));
    let [row] = Layout::vertical([Constraint::Length(height)])
        .flex(Flex::Center)
        .areas(area);
    let [popup]: [Rect; 1] = Layout::horizontal([Constraint::Length(width)])
        .flex(Flex::Center)
        .areas(row);
    let mut lines: Vec<Line> = keys
        .iter()
        .map(|(k, d)| {
            Line::from(vec![
                Span::styled(format!("{k:<10}"), theme::panel_title()),
                Span::raw(" "),
                Span::raw(*d),
            ])
        })
        .collect();
    lines.push(Line::raw(""));
    if replay {
        lines.push(Line::styled(
            "REPLAY is read-only: nothing is sent to a unit",
            theme::caution(),
        ));
    }
    for line in release {
        lines.push(Line::styled(line, theme::label()));
    }
    lines.push(Line::styled(
        "any other key stops a run; after 10 s press again",
        theme::label(),
    ));
    lines.push(Line::styled(view.theme.to_string(), theme::label()));
    // Short of room (80×24), the blank line under the keys goes before any words do.
    if lines.len() > usize::from(popup.height.saturating_sub(2)) {
        lines.remove(keys.len());
    }
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines).wrap(Wrap { trim: false }).block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .title(Span::styled(" Keys ", theme::panel_title()))
                .title_bottom(Line::styled(" ? closes ", theme::label())),
        ),
        popup,
    );
}

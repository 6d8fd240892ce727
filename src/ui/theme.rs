//! Every colour the page uses, in one place, so Appendix A's green=on, white=off,
//! red=faulted cannot drift apart between widgets.
//!
//! These are the page's colour *words*, as Appendix A writes them. Widgets draw with
//! them and tests assert them; what each word looks like on the person's terminal
//! (dark, light or no colour at all) is decided afterwards by [`super::palette`], which
//! repaints the finished frame.

use ratatui::style::{Color, Modifier, Style};

use crate::model::CircuitState;

pub const ON: Color = Color::Green;
pub const OFF: Color = Color::White;
pub const FAULT: Color = Color::Red;
/// Values we do not have live: dim, so "--" never reads as a reading.
pub const UNKNOWN: Color = Color::DarkGray;
pub const CAUTION: Color = Color::Yellow;
pub const INFO: Color = Color::Cyan;
pub const LABEL: Color = Color::Gray;
/// The selected row's background: a word like the others, painted by the palette
/// (a lighter band on dark, a grey band on light, reverse video without colour,
/// underlined in the terminal's own colours).
pub const SELECTION: Color = Color::Indexed(236);

pub fn state(state: CircuitState) -> Style {
    match state {
        CircuitState::On => Style::new().fg(ON).add_modifier(Modifier::BOLD),
        CircuitState::Off => Style::new().fg(OFF),
        CircuitState::Fault(_) => Style::new().fg(FAULT).add_modifier(Modifier::BOLD),
        // Not red: the fault may be gone. The words say what is known.
        CircuitState::ResetSent(_) => caution(),
        CircuitState::Unknown => Style::new().fg(UNKNOWN),
    }
}

pub fn on_off(on: bool) -> Style {
    if on {
        Style::new().fg(ON).add_modifier(Modifier::BOLD)
    } else {
        Style::new().fg(OFF)
    }
}

pub fn label() -> Style {
    Style::new().fg(LABEL)
}

pub fn unknown() -> Style {
    Style::new().fg(UNKNOWN)
}

pub fn alert() -> Style {
    Style::new().fg(FAULT).add_modifier(Modifier::BOLD)
}

pub fn caution() -> Style {
    Style::new().fg(CAUTION).add_modifier(Modifier::BOLD)
}

pub fn info() -> Style {
    Style::new().fg(INFO)
}

/// A key the person can press now.
pub fn key() -> Style {
    Style::new().fg(Color::Black).bg(Color::Gray)
}

/// A key that would be refused now (Appendix A: reset dimmed unless faulted).
pub fn key_dimmed() -> Style {
    Style::new().fg(UNKNOWN).add_modifier(Modifier::DIM)
}

pub fn selected_row() -> Style {
    Style::new().bg(SELECTION).add_modifier(Modifier::BOLD)
}

pub fn panel_title() -> Style {
    Style::new().fg(Color::White).add_modifier(Modifier::BOLD)
}

pub fn border() -> Style {
    Style::new().fg(Color::DarkGray)
}

/// The Vertical Power mark: Appendix A asks for their white-on-black logo.
pub fn brand() -> Style {
    Style::new()
        .fg(Color::White)
        .bg(Color::Black)
        .add_modifier(Modifier::BOLD)
}

/// The source label, loud, so a simulation or replay is never taken for an aircraft.
pub fn source_not_live() -> Style {
    Style::new()
        .fg(Color::Black)
        .bg(Color::Magenta)
        .add_modifier(Modifier::BOLD)
}

pub fn banner_lost() -> Style {
    Style::new()
        .fg(Color::White)
        .bg(FAULT)
        .add_modifier(Modifier::BOLD)
}

pub fn banner_waiting() -> Style {
    Style::new()
        .fg(Color::Black)
        .bg(CAUTION)
        .add_modifier(Modifier::BOLD)
}

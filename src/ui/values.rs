//! How numbers are written on the page. A value we do not have live is "--", never 0:
//! a mechanic reading 0.0 A would believe the circuit draws nothing.

use std::time::{Duration, Instant};

use crate::model::CircuitState;
use crate::protocol::message::SwitchId;

pub const BLANK: &str = "--";

pub fn amps(a: Option<f32>) -> String {
    a.map_or_else(|| BLANK.into(), |a| format!("{a:.1}"))
}

pub fn volts(v: Option<f32>) -> String {
    v.map_or_else(|| BLANK.into(), |v| format!("{v:.1}"))
}

pub fn state_text(s: CircuitState) -> String {
    match s {
        CircuitState::On => "ON".into(),
        CircuitState::Off => "OFF".into(),
        CircuitState::Fault(code) => code.name(),
        CircuitState::ResetSent(code) => crate::model::reset_sent_words(code),
        CircuitState::Unknown => BLANK.into(),
    }
}

/// Short switch label for the device list column.
pub fn switch_short(s: Option<SwitchId>) -> String {
    match s {
        None => BLANK.into(),
        Some(SwitchId::Off) => "off".into(),
        Some(SwitchId::Input(n)) => format!("sw {n}"),
        Some(SwitchId::AlwaysOn) => "always".into(),
        Some(SwitchId::Unknown(n)) => format!("?{n}"),
    }
}

/// Seconds since `at`, one decimal: link health ages, deterministic given `now`.
pub fn age(now: Instant, at: Instant) -> String {
    secs(now.saturating_duration_since(at))
}

pub fn secs(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s < 100.0 {
        format!("{s:.1} s")
    } else {
        format!("{:.0} s", s.floor())
    }
}

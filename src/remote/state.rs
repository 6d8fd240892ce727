//! The state the remote serves (`GET /api/state`, `/api/events`), built from the
//! model at the moment it is asked for, with the model's own staleness: a value that
//! is not live is `null`, never an old number, and with COMMUNICATION LOST every
//! value is `null` and every circuit `"UNKNOWN"`.
//!
//! The devices are the page's list (ICD Appendix A: "Only enabled devices should be
//! displayed", by name: `Model::circuits`), less the flaps and trims, which the phone
//! shows only under MOTORS, as motors to run rather than circuits to switch.

use std::time::Instant;

use serde::Serialize;

use crate::control::{Direction, switchable};
use crate::model::{
    CircuitKind, CircuitState, Connection, Model, Motor, TrimKind, reset_sent_words,
};
use crate::protocol::message::FlapTrimStatus;

/// What only the page knows: the motor it is streaming and the installation check's
/// prompt. The page updates it; the server reads it with the model.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PageSide {
    pub running: Option<(Motor, Direction)>,
    pub check: Option<CheckPrompt>,
}

/// The installation check's DO NOW, for the phone.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct CheckPrompt {
    pub step: String,
    pub prompt: String,
    pub answers: Vec<Answer>,
    pub lit_question: Option<String>,
}

#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Answer {
    pub id: &'static str,
    pub label: &'static str,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct State {
    /// Counts changes of everything else ([`super::server`] numbers them).
    pub seq: u64,
    pub comm_lost: bool,
    pub comm_reason: Option<String>,
    pub bus_volts: Option<f64>,
    pub total_amps: Option<f64>,
    pub devices: Vec<Device>,
    pub motors: Motors,
    pub check: Option<CheckPrompt>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Device {
    pub id: u8,
    pub name: String,
    pub pin: &'static str,
    /// "ON", "OFF", "FAULT" or "UNKNOWN".
    pub state: &'static str,
    pub amps: Option<f64>,
    /// The fault's name; "SHORT_CIRCUIT · reset sent" while a reset is unanswered.
    pub fault: Option<String>,
    /// Whether DEVICE_POWER may switch it at all: not the starter (only reset) nor a
    /// motor (run, not switched), by control's own rule ([`switchable`]), so the
    /// phone offers no button that can only be refused.
    pub switchable: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Motors {
    pub flaps: MotorState,
    pub pitch: MotorState,
    pub roll: MotorState,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotorState {
    pub fitted: Option<bool>,
    pub position_percent: Option<u8>,
    pub running: Option<&'static str>,
}

/// Tenths, as the unit sends them, without f32's noise (3.8, not 3.799999952).
fn tenths(x: f32) -> f64 {
    (f64::from(x) * 10.0).round() / 10.0
}

/// The state at `now`; `seq` 0 (the server numbers it).
pub fn build(model: &Model, page: &PageSide, now: Instant) -> State {
    let comm_lost = model.comm_lost(now);
    let comm_reason = comm_lost.then(|| match &model.connection {
        Connection::Lost { reason, .. } => format!("the link is down: {reason}"),
        Connection::Connecting => "connecting to the VP-X".to_string(),
        Connection::Connected { .. } if !model.ever_heard() => {
            "nothing heard from the VP-X yet".to_string()
        }
        Connection::Connected { .. } => "no status from the VP-X for over 2.5 s".to_string(),
    });
    let system = (!comm_lost).then(|| model.live_system(now)).flatten();
    let devices = model
        .circuits(now)
        .into_iter()
        .filter(|c| !matches!(c.kind, CircuitKind::Flaps | CircuitKind::Trim(_)))
        .map(|c| {
            let (state, fault) = match c.state {
                _ if comm_lost => ("UNKNOWN", None),
                CircuitState::On => ("ON", None),
                CircuitState::Off => ("OFF", None),
                CircuitState::Fault(code) => ("FAULT", Some(code.name())),
                CircuitState::ResetSent(code) => ("FAULT", Some(reset_sent_words(code))),
                CircuitState::Unknown => ("UNKNOWN", None),
            };
            Device {
                id: c.id,
                name: c.name.trim().to_string(),
                pin: c.pin,
                state,
                amps: c.amps.filter(|_| !comm_lost).map(tenths),
                fault,
                switchable: switchable(c.id),
            }
        })
        .collect();
    let ft = (!comm_lost).then(|| model.live_flap_trim(now)).flatten();
    let motor = |m: Motor| MotorState {
        fitted: ft.map(|ft| fitted(ft, m)),
        position_percent: ft.and_then(|ft| percent(ft, m)),
        running: page
            .running
            .filter(|(r, _)| *r == m && !comm_lost)
            .map(|(_, d)| d.name()),
    };
    State {
        seq: 0,
        comm_lost,
        comm_reason,
        bus_volts: system.map(|s| tenths(s.main_bus_volts.value())),
        total_amps: system.map(|s| tenths(s.system_current.value())),
        devices,
        motors: Motors {
            flaps: motor(Motor::Flaps),
            pitch: motor(Motor::Trim(TrimKind::Pitch)),
            roll: motor(Motor::Trim(TrimKind::Roll)),
        },
        check: page.check.clone(),
    }
}

fn fitted(ft: &FlapTrimStatus, m: Motor) -> bool {
    ft.axis(m.axis()).enabled
}

/// Percent of travel from the up (left) end, clamped, as the page's gauge shows it;
/// `None` for a motor not fitted or with no travel configured.
fn percent(ft: &FlapTrimStatus, m: Motor) -> Option<u8> {
    let a = ft.axis(m.axis());
    let (pos, from, to) = (a.position, a.up, a.down);
    if !fitted(ft, m) || from == to {
        return None;
    }
    let frac = (f64::from(pos) - f64::from(from)) / (f64::from(to) - f64::from(from));
    Some((frac.clamp(0.0, 1.0) * 100.0).round() as u8)
}

//! Actions to commands, judged against what the model knows right now.
//!
//! Every refusal comes back in words the person can act on; nothing is sent that the
//! ICD says the unit will not honour, or whose effect the page could not show.

use std::fmt;
use std::time::Instant;

use crate::model::{CircuitKind, CircuitState, Model, Motor};
use crate::protocol::device::{self, FLAPS, STARTER, SYSTEM_FAULT_ID, TRIM_P, TRIM_R};
use crate::protocol::fault::FaultCode;
use crate::protocol::message::{DeviceClear, DevicePower, Message, WigWagMode, WigWagModeSetting};

use super::keymap::Action;
use super::streamer::{Direction, StopReason};

/// Why a key did nothing, in words for the notice line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal(pub String);

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

fn refuse<T>(why: impl Into<String>) -> Result<T, Refusal> {
    Err(Refusal(why.into()))
}

pub(super) const COMM_LOST: &str = "COMMUNICATION LOST: nothing is sent until the VP-X is heard again, \
                         because the result could not be seen";

/// The message for a command action (`Action::is_command`), or why not. Other actions
/// are refused as "not a command".
pub fn command(action: &Action, model: &Model, now: Instant) -> Result<Message, Refusal> {
    if !action.is_command() {
        return refuse("not a command");
    }
    if model.comm_lost(now) {
        return refuse(COMM_LOST);
    }
    match *action {
        Action::PowerOn(id) => device_power(model, now, id, true),
        Action::PowerOff(id) => device_power(model, now, id, false),
        Action::Reset(id) => reset(model, now, id, false),
        Action::ResetSystemFault => match model.live_faults(now) {
            Some((_, true)) => Ok(DeviceClear {
                device_id: SYSTEM_FAULT_ID,
            }
            .into()),
            _ => refuse("there is no system fault to reset"),
        },
        Action::ToggleWigWag => match model.live_system(now) {
            Some(s) => Ok(WigWagMode {
                mode: match s.misc.wig_wag_mode {
                    WigWagModeSetting::Auto => WigWagModeSetting::Steady,
                    _ => WigWagModeSetting::Auto,
                },
            }
            .into()),
            None => refuse("the wig-wag mode is not known yet (no live SYSTEM_STATUS)"),
        },
        _ => refuse("not a command"),
    }
}

/// The event log's line for a command action someone gave, with its origin first
/// ("key", "check", "xfsp", "remote", as the audit log names them): "key: Nav Lt
/// off (DEVICE_POWER sent)", or "key: Landing Lt reset refused: it is not faulted".
/// The person's own actions belong in the log beside the unit's faults.
pub fn said(
    origin: &str,
    action: &Action,
    model: &Model,
    result: Result<&Message, &str>,
) -> String {
    let what = match *action {
        Action::PowerOn(id) => format!("{} on", model.display_name(id).trim()),
        Action::PowerOff(id) => format!("{} off", model.display_name(id).trim()),
        Action::Reset(id) => format!("{} reset", model.display_name(id).trim()),
        Action::ResetSystemFault => "system fault reset".into(),
        Action::ToggleWigWag => "wig-wag mode changed".into(),
        _ => format!("{action:?}"),
    };
    match result {
        Ok(m) => format!("{origin}: {what} ({} sent)", m.name()),
        Err(why) => format!("{origin}: {what} refused: {why}"),
    }
}

fn circuit_state(model: &Model, now: Instant, id: u8) -> Option<(CircuitKind, CircuitState)> {
    model
        .circuits(now)
        .into_iter()
        .find(|c| c.id == id)
        .map(|c| (c.kind, c.state))
}

/// DEVICE_POWER for circuit `id`, or why not: the rule for the page's power keys and
/// the installation check's switching on alike (ICD §6.4.1).
pub fn device_power(model: &Model, now: Instant, id: u8, on: bool) -> Result<Message, Refusal> {
    if model.comm_lost(now) {
        return refuse(COMM_LOST);
    }
    power(model, now, id, on)
}

/// DEVICE_POWER off for a circuit the page itself switched on (the installation
/// check putting back what it changed), or why not. What no DEVICE_POWER may ever
/// touch still refuses (the starter, a motor). Unlike [`device_power`], neither
/// COMMUNICATION LOST nor an unknown state stops it: an off that undoes the page's
/// own on is the safe side even unseen (the unit may still hear the page when the
/// page no longer hears the unit), and the caller says it is not confirmed.
pub fn put_back_off(model: &Model, id: u8) -> Result<Message, Refusal> {
    let name = model.display_name(id);
    match id {
        STARTER => refuse("the starter cannot be switched from the EFIS, only reset"),
        FLAPS | TRIM_P | TRIM_R => refuse(format!(
            "{name} is a motor: it is run up or down, not switched on or off"
        )),
        _ => Ok(DevicePower {
            device_id: id,
            on: false,
        }
        .into()),
    }
}

fn power(model: &Model, now: Instant, id: u8, on: bool) -> Result<Message, Refusal> {
    let name = model.display_name(id);
    if id == STARTER {
        // ICD Appendix B note 1, icd-reading R18.
        return refuse(
            "the starter cannot be switched from the EFIS, only reset; \
             the VP-X turns it off above 500 RPM",
        );
    }
    let Some((kind, state)) = circuit_state(model, now, id) else {
        return refuse(format!("{name} is not on this unit's device list"));
    };
    match kind {
        CircuitKind::Flaps | CircuitKind::Trim(_) => refuse(format!(
            "{name} is a motor: it is run up or down, not switched on or off"
        )),
        _ => match state {
            // Not "reset it first" to a circuit that is past its one reset. The words
            // name no key: they reach the phone and the network too.
            CircuitState::Fault(_) if on && model.faulted_again_after_reset(id, now) => {
                refuse(faulted_again(&name))
            }
            // Appendix E: a faulted pin stays off until the fault is cleared.
            CircuitState::Fault(code) if on => refuse(format!(
                "{name} is faulted ({}): reset it first",
                code.name()
            )),
            CircuitState::ResetSent(code) if on => refuse(waiting_for_reset(model, now, id, code)),
            CircuitState::Unknown => refuse(format!("{name}'s state is not known yet")),
            _ => Ok(DevicePower { device_id: id, on }.into()),
        },
    }
}

/// Why a circuit that faulted again after a reset is not reset again.
pub fn faulted_again(name: &str) -> String {
    format!("{name} faulted again after a reset: find the cause before resetting it again")
}

/// DEVICE_CLEAR for circuit `id`, or why not: the rule for the page's `r`, a remote's
/// RESET and anything else that resets a circuit.
///
/// FAA AC 43.13-1B (the breaker-reset practice): a tripped breaker is reset once; one
/// that trips again has a cause to find first, as resetting it into a short again
/// heats the wiring each time. So a circuit that faulted again after a reset sent this
/// session ([`Model::faulted_again_after_reset`]) is refused with those words unless
/// the reset is `confirmed`: a deliberate second step by a person who has looked (the
/// page's `Y` right after the refusal). A remote has no such step.
pub fn reset(model: &Model, now: Instant, id: u8, confirmed: bool) -> Result<Message, Refusal> {
    let name = model.display_name(id);
    if device::device(id).is_none() {
        return refuse(format!("device {id} does not exist"));
    }
    if model.comm_lost(now) {
        return refuse(COMM_LOST);
    }
    if !confirmed && model.faulted_again_after_reset(id, now) {
        return refuse(faulted_again(&name));
    }
    match circuit_state(model, now, id) {
        Some((_, CircuitState::Fault(code))) => match code {
            // Appendix E: these clear only by a power cycle, so DEVICE_CLEAR is futile.
            FaultCode::FlapDisabled | FaultCode::TrimDisabled => refuse(format!(
                "{name}: {} clears only when the system is power cycled",
                code.name()
            )),
            _ => Ok(DeviceClear { device_id: id }.into()),
        },
        // A second reset before the unit answered the first would count as a reset
        // of a circuit that may no longer have a fault.
        Some((_, CircuitState::ResetSent(code))) => refuse(waiting_for_reset(model, now, id, code)),
        Some((_, CircuitState::Unknown)) => refuse(format!("{name}'s state is not known yet")),
        _ => refuse(format!("{name} has no fault to reset")),
    }
}

/// Why nothing more is sent to a circuit whose reset the unit has not yet answered.
fn waiting_for_reset(model: &Model, now: Instant, id: u8, code: FaultCode) -> String {
    let name = model.display_name(id);
    let ago = model
        .resets_sent(id)
        .map_or(0.0, |r| now.saturating_duration_since(r.at).as_secs_f64());
    format!(
        "{name}: a reset was sent {ago:.1} s ago and the unit has not yet said whether \
         {} cleared; nothing more is sent until it does (its next broadcast)",
        code.name()
    )
}

/// Whether `motor` may run (or keep running) `direction` now. Each reason is also the
/// [`StopReason`] that ends a run already going.
pub fn motor_check(
    model: &Model,
    motor: Motor,
    direction: Direction,
    now: Instant,
) -> Result<(), StopReason> {
    if model.comm_lost(now) {
        return Err(StopReason::CommLost);
    }
    let Some(ft) = model.live_flap_trim(now) else {
        return Err(StopReason::MotorStatusLost);
    };
    let axis = ft.axis(motor.axis());
    let (enabled, flagged) = (axis.enabled, axis.fault);
    let code = motor.fault(ft);
    if code.is_fault() {
        return Err(StopReason::MotorFault(code));
    }
    // FAULT_STATUS carries the motor's device bit too; either source is enough.
    let listed = model
        .live_faults(now)
        .map(|(codes, _)| codes[motor.device_id() as usize])
        .filter(|c| c.is_fault());
    if let Some(code) = listed {
        return Err(StopReason::MotorFault(code));
    }
    if flagged {
        return Err(StopReason::MotorFault(FaultCode::Unknown(0xFF)));
    }
    if !enabled {
        return Err(StopReason::MotorDisabled);
    }
    if motor == Motor::Flaps && direction == Direction::Down && ft.flap.down_switch_inhibited {
        return Err(StopReason::FlapDownInhibited);
    }
    Ok(())
}

//! Actions to commands, judged against what the model knows right now.
//!
//! Every refusal comes back in words the person can act on; nothing is sent that the
//! ICD says the unit will not honour, or whose effect the page could not show.

use std::fmt;
use std::time::Instant;

use crate::model::{CircuitState, Model, Motor};
use crate::protocol::device::{self, STARTER, SYSTEM_FAULT_ID};
use crate::protocol::fault::FaultCode;
use crate::protocol::message::{DeviceClear, DevicePower, Message, WigWagMode, WigWagModeSetting};

use super::keymap::Action;
use super::streamer::{Direction, StopReason};

/// A command refused: why, as a type a caller decides by, and the words for the
/// person (the notice line, the phone, the network's log).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    pub reason: Reason,
    pub words: String,
}

/// Why a command was refused ([`Refusal`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reason {
    /// The action sends nothing ([`Action::is_command`]).
    NotACommand,
    /// COMMUNICATION LOST: nothing is sent that the page could not see the result of.
    CommLost,
    /// No device has this id (ICD Table 40).
    NoSuchDevice,
    /// The device is not on this unit's device list (disabled, not fitted).
    NotListed,
    /// What DEVICE_POWER never switches (see [`switchable`]).
    NeverSwitched(Unswitched),
    /// Faulted: a faulted pin stays off until the fault is cleared (Appendix E).
    Faulted(FaultCode),
    /// Faulted again after a reset this session: its cause is to be found first.
    FaultedAgain,
    /// A reset went out that the unit has not answered yet.
    ResetWaiting(FaultCode),
    /// Its state (or the wig-wag mode) is not known yet.
    NotKnown,
    /// Nothing to reset: no fault (or no system fault).
    NoFault,
    /// The fault clears only by a power cycle (Appendix E): DEVICE_CLEAR is futile.
    ClearsOnlyByPowerCycle(FaultCode),
}

/// What DEVICE_POWER never switches, whoever asks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unswitched {
    /// The starter: only reset (ICD Appendix B note 1, icd-reading R18).
    Starter,
    /// Flaps or a trim: run up or down, not switched.
    Motor,
}

impl Reason {
    /// Whether asking again cannot change the answer while the unit stays as it is
    /// configured: no such circuit, or one that is never switched. The rest may pass
    /// on a retry once the state it needed comes.
    pub fn lasts(self) -> bool {
        matches!(
            self,
            Reason::NoSuchDevice | Reason::NotListed | Reason::NeverSwitched(_)
        )
    }
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.words)
    }
}

fn refuse<T>(reason: Reason, words: impl Into<String>) -> Result<T, Refusal> {
    Err(Refusal {
        reason,
        words: words.into(),
    })
}

pub(super) const COMM_LOST: &str = "COMMUNICATION LOST: nothing is sent until the VP-X is heard again, \
                         because the result could not be seen";

/// The message for a command action (`Action::is_command`), or why not. Other actions
/// are refused as "not a command".
pub fn command(action: &Action, model: &Model, now: Instant) -> Result<Message, Refusal> {
    match *action {
        Action::PowerOn(id) => device_power(model, now, id, true),
        Action::PowerOff(id) => device_power(model, now, id, false),
        Action::Reset(id) => reset(model, now, id, false),
        _ if !action.is_command() => refuse(Reason::NotACommand, "not a command"),
        _ if model.comm_lost(now) => refuse(Reason::CommLost, COMM_LOST),
        Action::ResetSystemFault => match model.live_faults(now) {
            Some((_, true)) => Ok(DeviceClear {
                device_id: SYSTEM_FAULT_ID,
            }
            .into()),
            _ => refuse(Reason::NoFault, "there is no system fault to reset"),
        },
        Action::ToggleWigWag => match model.live_system(now) {
            Some(s) => Ok(WigWagMode {
                mode: match s.misc.wig_wag_mode {
                    WigWagModeSetting::Auto => WigWagModeSetting::Steady,
                    _ => WigWagModeSetting::Auto,
                },
            }
            .into()),
            None => refuse(
                Reason::NotKnown,
                "the wig-wag mode is not known yet (no live SYSTEM_STATUS)",
            ),
        },
        _ => refuse(Reason::NotACommand, "not a command"),
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

/// The state of circuit `id`, or why there is none: no such device, or not on this
/// unit's device list. Asked before anything else, so a command to nothing is told so
/// even while communication is lost.
fn circuit_state(model: &Model, now: Instant, id: u8) -> Result<CircuitState, Refusal> {
    if device::device(id).is_none() {
        return refuse(Reason::NoSuchDevice, format!("device {id} does not exist"));
    }
    match model.circuits(now).into_iter().find(|c| c.id == id) {
        Some(c) => Ok(c.state),
        None => refuse(
            Reason::NotListed,
            format!(
                "{} is not on this unit's device list",
                model.display_name(id)
            ),
        ),
    }
}

/// What DEVICE_POWER never switches, whoever asks (keys, check, remote, network):
/// the starter, which the EFIS may only reset (ICD Appendix B note 1, icd-reading
/// R18), and a motor, which is run. The one place that says so.
fn unswitched(id: u8) -> Option<Unswitched> {
    if id == STARTER {
        Some(Unswitched::Starter)
    } else if Motor::of_device(id).is_some() {
        Some(Unswitched::Motor)
    } else {
        None
    }
}

/// Whether DEVICE_POWER may ever switch device `id` ([`unswitched`]).
pub fn switchable(id: u8) -> bool {
    unswitched(id).is_none()
}

/// The refusal of what DEVICE_POWER never switches ([`unswitched`]).
fn never_switched(model: &Model, id: u8) -> Result<(), Refusal> {
    let Some(what) = unswitched(id) else {
        return Ok(());
    };
    let words = match what {
        Unswitched::Starter => "the starter cannot be switched from the EFIS, only reset; \
                                the VP-X turns it off above 500 RPM"
            .to_string(),
        Unswitched::Motor => format!(
            "{} is a motor: it is run up or down, not switched on or off",
            model.display_name(id)
        ),
    };
    refuse(Reason::NeverSwitched(what), words)
}

/// DEVICE_POWER for circuit `id`, or why not: the rule for the page's power keys and
/// the installation check's switching on alike (ICD §6.4.1).
pub fn device_power(model: &Model, now: Instant, id: u8, on: bool) -> Result<Message, Refusal> {
    let state = circuit_state(model, now, id)?;
    if model.comm_lost(now) {
        return refuse(Reason::CommLost, COMM_LOST);
    }
    never_switched(model, id)?;
    power(model, now, id, on, state)
}

/// DEVICE_POWER off for a circuit the page itself switched on (the installation
/// check putting back what it changed), or why not. What no DEVICE_POWER may ever
/// touch still refuses (the starter, a motor). Unlike [`device_power`], neither
/// COMMUNICATION LOST nor an unknown state stops it: an off that undoes the page's
/// own on is the safe side even unseen (the unit may still hear the page when the
/// page no longer hears the unit), and the caller says it is not confirmed.
pub fn put_back_off(model: &Model, id: u8) -> Result<Message, Refusal> {
    never_switched(model, id)?;
    Ok(DevicePower {
        device_id: id,
        on: false,
    }
    .into())
}

fn power(
    model: &Model,
    now: Instant,
    id: u8,
    on: bool,
    state: CircuitState,
) -> Result<Message, Refusal> {
    let name = model.display_name(id);
    match state {
        // Not "reset it first" to a circuit that is past its one reset. The words
        // name no key: they reach the phone and the network too.
        CircuitState::Fault(_) if on && model.faulted_again_after_reset(id, now) => {
            refuse(Reason::FaultedAgain, faulted_again(&name))
        }
        // Appendix E: a faulted pin stays off until the fault is cleared.
        CircuitState::Fault(code) if on => refuse(
            Reason::Faulted(code),
            format!("{name} is faulted ({}): reset it first", code.name()),
        ),
        CircuitState::ResetSent(code) if on => refuse(
            Reason::ResetWaiting(code),
            waiting_for_reset(model, now, id, code),
        ),
        CircuitState::Unknown => {
            refuse(Reason::NotKnown, format!("{name}'s state is not known yet"))
        }
        _ => Ok(DevicePower { device_id: id, on }.into()),
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
    let state = circuit_state(model, now, id)?;
    let name = model.display_name(id);
    if model.comm_lost(now) {
        return refuse(Reason::CommLost, COMM_LOST);
    }
    if !confirmed && model.faulted_again_after_reset(id, now) {
        return refuse(Reason::FaultedAgain, faulted_again(&name));
    }
    match state {
        CircuitState::Fault(code) => match code {
            // Appendix E: these clear only by a power cycle, so DEVICE_CLEAR is futile.
            FaultCode::FlapDisabled | FaultCode::TrimDisabled => refuse(
                Reason::ClearsOnlyByPowerCycle(code),
                format!(
                    "{name}: {} clears only when the system is power cycled",
                    code.name()
                ),
            ),
            _ => Ok(DeviceClear { device_id: id }.into()),
        },
        // A second reset before the unit answered the first would count as a reset
        // of a circuit that may no longer have a fault.
        CircuitState::ResetSent(code) => refuse(
            Reason::ResetWaiting(code),
            waiting_for_reset(model, now, id, code),
        ),
        CircuitState::Unknown => {
            refuse(Reason::NotKnown, format!("{name}'s state is not known yet"))
        }
        CircuitState::On | CircuitState::Off => {
            refuse(Reason::NoFault, format!("{name} has no fault to reset"))
        }
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

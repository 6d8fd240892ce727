//! Before anything is powered: which circuits the check will switch on and for how
//! long, which motors it will run, and what it leaves alone and why.
//!
//! Never touched, whatever the person says: the starter (ICD Appendix B note 1,
//! icd-reading R18: the EFIS may only reset it) and the alternator fields (Field_Pri
//! and the SYSTEM_SPEC secondary alternator: an alternator field powered with the
//! engine stopped only drains the battery and heats the field winding). Suggested for
//! exclusion, which the person may take back on the screen: names with "pitot",
//! "heat" or "starter" (a pitot heater burns out on the ground).
//!
//! Nor is the person ever asked to flip a switch input that would power something
//! left alone: an input 1–10 carrying a planned circuit and an excluded one, the
//! starter or an alternator field is not asked at all (its planned circuits are then
//! untested by the switch step, and the plan says so in words). The flap and trim
//! switch inputs of SYSTEM_STATUS byte 8 (ICD Table 24) drive only their own motor:
//! Appendix B gives flaps the switch "Flaps, not assignable", and DEVICE_SPEC's
//! switch id (Table 13) names only inputs 1–10, so no circuit can follow a flap or
//! trim input. They are not asked when their motor is excluded, nor when the motors
//! step is skipped (`--skip motors`): flipping one runs its motor from the cockpit,
//! and a person who skipped the motors did not mean any to move.

use std::time::{Duration, Instant};

use super::state::{Excluded, Input, Planned, Step, Unasked};
use crate::model::{Circuit, CircuitKind, Model, Motor, TrimKind};
use crate::protocol::message::SwitchId;

/// Words in a circuit's name that make the check suggest leaving it alone.
pub const SUGGEST_EXCLUDING: [&str; 3] = ["pitot", "heat", "starter"];

/// What the person asked for, on the command line or on the screen.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Choices {
    /// `--exclude NAME`: matched against a circuit's name or its pin, ignoring case.
    pub exclude: Vec<String>,
    /// Suggested exclusions the person took back (device ids).
    pub include: Vec<u8>,
    /// Circuits the person excluded with `x` on the check screen (device ids): said
    /// so, not as `--exclude`.
    pub excluded_here: Vec<u8>,
}

/// The plan: circuits to power, motors to run, circuits left alone, and the switch
/// inputs the person will not be asked to flip because they power one left alone.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plan {
    pub circuits: Vec<Planned>,
    pub motors: Vec<(Motor, Duration)>,
    pub excluded: Vec<Excluded>,
    pub unasked: Vec<Unasked>,
}

/// Whether `name` (or `pin`) is what `--exclude NAME` names.
pub fn names(pattern: &str, name: &str, pin: &str) -> bool {
    let p = pattern.trim();
    p.eq_ignore_ascii_case(name.trim()) || p.eq_ignore_ascii_case(pin)
}

/// The word of [`SUGGEST_EXCLUDING`] in `name`, if any.
pub fn suggested(name: &str) -> Option<&'static str> {
    let lower = name.to_ascii_lowercase();
    SUGGEST_EXCLUDING.into_iter().find(|w| lower.contains(w))
}

/// The `--exclude` names that match no circuit on the unit, for a clear error.
pub fn unmatched(model: &Model, now: Instant, exclude: &[String]) -> Vec<String> {
    let circuits = model.circuits(now);
    exclude
        .iter()
        .filter(|e| !circuits.iter().any(|c| names(e, &c.name, c.pin)))
        .cloned()
        .collect()
}

/// How long the plan's items take: the longest a circuit stays on, a motor's test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lengths {
    pub on_for: Duration,
    pub motor_for: Duration,
}

/// The plan for the unit the model describes now, with the check's steps `skip`ped
/// from the start.
pub fn build(
    model: &Model,
    now: Instant,
    choices: &Choices,
    skip: &[Step],
    lengths: Lengths,
) -> Plan {
    let Lengths { on_for, motor_for } = lengths;
    let mut plan = Plan::default();
    let circuits = model.circuits(now);
    for c in circuits.iter().cloned() {
        let by_name = choices.exclude.iter().any(|e| names(e, &c.name, c.pin));
        let here = choices.excluded_here.contains(&c.id);
        let never = match c.kind {
            CircuitKind::Starter => Some("never touched: the starter"),
            CircuitKind::Alternator { .. } => Some("never touched: an alternator field"),
            _ => None,
        };
        let motor = match c.kind {
            CircuitKind::Flaps => Some(Motor::Flaps),
            CircuitKind::Trim(k) => Some(Motor::Trim(k)),
            _ => None,
        };
        let why = if let Some(w) = never {
            Some((w.to_string(), false))
        } else if here {
            Some(("excluded by you (x on this screen)".to_string(), false))
        } else if by_name {
            Some(("excluded by you (--exclude)".to_string(), false))
        } else {
            suggested(&c.name)
                .filter(|_| !choices.include.contains(&c.id))
                .map(|word| (format!("suggested: the name has \"{word}\""), true))
        };
        if let Some((why, may_include)) = why {
            plan.excluded.push(Excluded {
                id: c.id,
                name: c.name.clone(),
                pin: c.pin,
                breaker: c.breaker,
                switch: c.switch,
                why,
                may_include,
            });
            continue;
        }
        match motor {
            Some(m) => plan.motors.push((m, motor_for)),
            None => plan.circuits.push(Planned {
                id: c.id,
                name: c.name.clone(),
                pin: c.pin,
                breaker: c.breaker,
                switch: c.switch,
                on_for,
            }),
        }
    }
    // Flaps first, then pitch and roll: the order of the motors panel.
    plan.motors.sort_by_key(|(m, _)| m.index());
    plan.unasked = unasked(&circuits, &plan, skip.contains(&Step::Motors));
    plan
}

/// The circuits a switch input 1–10 powers, as the unit's DEVICE_SPEC assigns them
/// (ICD Table 13): every circuit on the input, whether the check plans it or not.
pub fn on_input(circuits: &[Circuit], n: u8) -> Vec<&Circuit> {
    circuits
        .iter()
        .filter(|c| matches!(c.kind, CircuitKind::Device | CircuitKind::Alternator { .. }))
        .filter(|c| c.switch == Some(SwitchId::Input(n)))
        .collect()
}

/// "Pitot Heat (excluded)", "Main Alt (an alternator field)": a circuit left alone,
/// named with why, for the words of an input not asked.
fn left_alone(c: &Circuit) -> String {
    let why = match c.kind {
        CircuitKind::Starter => "the starter",
        CircuitKind::Alternator { .. } => "an alternator field",
        _ => "excluded",
    };
    format!("{} ({why})", c.name)
}

/// The inputs the person is not asked to flip, in the order the switch step runs:
/// an input 1–10 carrying any circuit the plan leaves alone, and the flap and trim
/// inputs of an excluded motor, or of every motor when `motors_skipped` (see the
/// module docs).
fn unasked(circuits: &[Circuit], plan: &Plan, motors_skipped: bool) -> Vec<Unasked> {
    let planned = |id: u8| plan.circuits.iter().any(|p| p.id == id);
    let mut out = Vec::new();
    for n in 1..=10u8 {
        let on = on_input(circuits, n);
        let left: Vec<String> = on
            .iter()
            .filter(|c| !planned(c.id))
            .map(|c| left_alone(c))
            .collect();
        if left.is_empty() {
            continue;
        }
        let how = if left.len() == on.len() {
            "powers only"
        } else {
            "also powers"
        };
        out.push(Unasked {
            input: Input::Switch(n),
            circuits: on.iter().map(|c| c.id).collect(),
            why: format!("switch {n} {how} {}: not asked", left.join(", ")),
        });
    }
    for c in circuits {
        let inputs = match c.kind {
            CircuitKind::Flaps => [Input::FlapUp, Input::FlapDown],
            CircuitKind::Trim(TrimKind::Pitch) => [Input::PitchTrimUp, Input::PitchTrimDown],
            CircuitKind::Trim(TrimKind::Roll) => [Input::RollTrimUp, Input::RollTrimDown],
            _ => continue,
        };
        let why = if plan.excluded.iter().any(|e| e.id == c.id) {
            "excluded"
        } else if motors_skipped {
            "the motors step is skipped"
        } else {
            continue;
        };
        out.extend(inputs.map(|input| Unasked {
            input,
            circuits: Vec::new(),
            why: format!("{} drives {} ({why}): not asked", input.label(), c.name),
        }));
    }
    out
}

/// Whether the page has heard every setting the plan depends on (specs, names,
/// enable flags, the system spec's secondary alternator) and the unit is live.
pub fn ready(model: &Model, now: Instant) -> Result<(), String> {
    if model.comm_lost(now) {
        return Err("waiting for the VP-X: nothing heard from it yet".into());
    }
    let missing = crate::model::Setting::all()
        .filter(|&s| model.setting_heard(s).is_none() || model.is_unknown(s))
        .count();
    if missing > 0 {
        return Err(format!(
            "waiting for {missing} of the unit's settings (names, switches, breakers)"
        ));
    }
    if model.live_devices(now).is_none() || model.live_system(now).is_none() {
        return Err("waiting for the unit's first status broadcasts".into());
    }
    Ok(())
}

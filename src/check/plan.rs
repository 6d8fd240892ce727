//! Before anything is powered: which circuits the check will switch on and for how
//! long, which motors it will run, and what it leaves alone and why.
//!
//! Never touched, whatever the person says: the starter (ICD Appendix B note 1,
//! reading note 18: the EFIS may only reset it) and the alternator fields (Field_Pri
//! and the SYSTEM_SPEC secondary alternator: an alternator field powered with the
//! engine stopped only drains the battery and heats the field winding). Suggested for
//! exclusion, which the person may take back on the screen: names with "pitot",
//! "heat" or "starter" (a pitot heater burns out on the ground).

use std::time::{Duration, Instant};

use crate::model::{CircuitKind, Model, Motor, TrimKind};
use crate::ui::check::state::{Excluded, Planned};

/// Words in a circuit's name that make the check suggest leaving it alone.
pub const SUGGEST_EXCLUDING: [&str; 3] = ["pitot", "heat", "starter"];

/// What the person asked for, on the command line or on the screen.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Choices {
    /// `--exclude NAME`: matched against a circuit's name or its pin, ignoring case.
    pub exclude: Vec<String>,
    /// Suggested exclusions the person took back (device ids).
    pub include: Vec<u8>,
}

/// The plan: circuits to power, motors to run, circuits left alone.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plan {
    pub circuits: Vec<Planned>,
    pub motors: Vec<(Motor, Duration)>,
    pub excluded: Vec<Excluded>,
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

/// The plan for the unit the model describes now. `on_for` is the longest a circuit
/// stays on; `motor_for` how long a motor's test takes.
pub fn build(
    model: &Model,
    now: Instant,
    choices: &Choices,
    on_for: Duration,
    motor_for: Duration,
) -> Plan {
    let mut plan = Plan::default();
    for c in model.circuits(now) {
        let by_name = choices.exclude.iter().any(|e| names(e, &c.name, c.pin));
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
    plan.motors.sort_by_key(|(m, _)| match m {
        Motor::Flaps => 0,
        Motor::Trim(TrimKind::Pitch) => 1,
        Motor::Trim(TrimKind::Roll) => 2,
    });
    plan
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

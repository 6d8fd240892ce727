//! In which order a restore writes, so that the unit accepts every step.
//!
//! The unit judges each spec against what it holds *at that moment* (ICD §6.2), and
//! three settings are tied to each other:
//!
//! * a wig-wag device must stay on a switch 1–10 (Table 13 note 5, Table 17 note 1);
//! * the secondary alternator may not be a wig-wag device (Table 14 note 4, Table 17
//!   note 2);
//! * the secondary alternator and the primary (Field_Pri) may not share a switch
//!   (Table 13 note 6, Table 14 note 5).
//!
//! A file that is valid as a whole can still be refused step by step: moving the
//! wig-wag from pin A to pin B while A goes to "off" is refused whichever is sent first
//! (A is still a wig-wag device; B is not yet on a switch), and swapping the two
//! alternators' switches is refused for either DEVICE_SPEC first. So:
//!
//! 1. **Untie**, only when the direct order below would be refused: WIG_WAG_SPEC with no
//!    devices, and SYSTEM_SPEC with no secondary alternator. Neither has any rule left
//!    to break, and with them gone no DEVICE_SPEC is tied to anything.
//! 2. **Every DEVICE_SPEC** (pins 1–28): each is now judged only on its own values.
//! 3. **SYSTEM_SPEC**, then **WIG_WAG_SPEC**: each is judged against the pins' final
//!    switches, which is what `validate::whole_config` already checked in the file.
//! 4. **FLAP_SPEC, the TRIM_SPECs, every DEVICE_NAME, every DEVICE_ENABLE**: tied to
//!    nothing. Last, so that a failure here leaves the tied group whole.
//!
//! Only settings that differ from what the unit holds are written (fewer EEPROM writes,
//! and a shorter list of what was and was not applied). Whether step 1 is needed is
//! decided by running the plan through the same rules the unit applies
//! ([`validate::accept`]) on a copy of the unit's settings; a plan those rules would
//! refuse is never sent.

use std::fmt;

use crate::link::request::setting_name;
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{TRIM_R, enable_flag_allowed};
use crate::protocol::message::{
    DeviceEnable, DeviceName, DeviceSpec, EnableFlag, Message, SystemSpec, WigWagSpec,
};
use crate::protocol::validate;

use super::writer::normalize_name;

/// One write of a restore.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RestoreWrite {
    /// A message the unit answers with SPEC_ACK. `untie` marks the step-1 writes that
    /// clear the wig-wag or the secondary alternator for a moment.
    Spec { message: Message, untie: bool },
    /// DEVICE_ENABLE flag 0/1, which the unit does not acknowledge (ICD Table 23): it
    /// is read back instead.
    Enable { device_id: u8, shown: bool },
}

impl RestoreWrite {
    fn spec(message: impl Into<Message>) -> RestoreWrite {
        RestoreWrite::Spec {
            message: message.into(),
            untie: false,
        }
    }

    /// The message this step sends.
    pub fn message(&self) -> Message {
        match *self {
            RestoreWrite::Spec { message, .. } => message,
            RestoreWrite::Enable { device_id, shown } => Message::DeviceEnable(DeviceEnable {
                device_id,
                flag: if shown {
                    EnableFlag::Enabled
                } else {
                    EnableFlag::Disabled
                },
            }),
        }
    }
}

impl fmt::Display for RestoreWrite {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RestoreWrite::Spec {
                message: Message::WigWagSpec(_),
                untie: true,
            } => write!(f, "WIG_WAG_SPEC with no devices (for a moment, to untie)"),
            RestoreWrite::Spec {
                message: Message::SystemSpec(_),
                untie: true,
            } => write!(
                f,
                "SYSTEM_SPEC with no secondary alternator (for a moment, to untie)"
            ),
            RestoreWrite::Spec { message, .. } => write!(f, "{}", setting_name(message)),
            RestoreWrite::Enable { shown, .. } => write!(
                f,
                "{} ({})",
                setting_name(&self.message()),
                if *shown { "shown" } else { "hidden" }
            ),
        }
    }
}

/// The plan would be refused by the §6.2 rules (the unit's settings themselves break
/// them in a way no order can get around). Nothing has been sent.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "no order of writes gets from the unit's settings to the file's: {step} would be refused ({reason})"
)]
pub struct PlanError {
    pub step: String,
    pub reason: String,
}

/// The writes that take a unit holding `current` to `target`, in an order the §6.2
/// rules accept (module doc). `target` should have passed `validate::whole_config`.
pub fn plan(current: &UnitConfig, target: &UnitConfig) -> Result<Vec<RestoreWrite>, PlanError> {
    let direct = tied(current, target, false);
    let tied_steps = match simulate(current, &direct) {
        Ok(()) => direct,
        Err(direct_err) => {
            let untied = tied(current, target, true);
            simulate(current, &untied).map_err(|_| direct_err)?;
            untied
        }
    };
    let mut steps = tied_steps;
    if current.flap != target.flap {
        steps.push(RestoreWrite::spec(target.flap));
    }
    if current.pitch_trim != target.pitch_trim {
        steps.push(RestoreWrite::spec(target.pitch_trim));
    }
    if current.roll_trim != target.roll_trim {
        steps.push(RestoreWrite::spec(target.roll_trim));
    }
    for id in 0..target.names.len() {
        let want = normalize_name(&target.names[id]);
        if normalize_name(&current.names[id]) != want {
            steps.push(RestoreWrite::spec(DeviceName {
                device_id: id as u8,
                name: want,
            }));
        }
    }
    for id in 0..target.enabled.len() as u8 {
        let i = id as usize;
        if enable_flag_allowed(id) && current.enabled[i] != target.enabled[i] {
            steps.push(RestoreWrite::Enable {
                device_id: id,
                shown: target.enabled[i],
            });
        }
    }
    simulate(current, &steps)?;
    Ok(steps)
}

/// Steps 1–3 of the module doc; step 1 only when `untie`.
fn tied(current: &UnitConfig, target: &UnitConfig, untie: bool) -> Vec<RestoreWrite> {
    let mut steps = Vec::new();
    let mut wig_wag = current.wig_wag;
    let mut system = current.system;
    if untie {
        if current.wig_wag.device_one.is_some() || current.wig_wag.device_two.is_some() {
            // The file's warm-up and speed passed the rules; the unit's own might not.
            wig_wag = WigWagSpec {
                device_one: None,
                device_two: None,
                ..target.wig_wag
            };
            steps.push(RestoreWrite::Spec {
                message: wig_wag.into(),
                untie: true,
            });
        }
        if current.system.secondary_alternator.is_some() {
            system = SystemSpec {
                secondary_alternator: None,
                ..target.system
            };
            steps.push(RestoreWrite::Spec {
                message: system.into(),
                untie: true,
            });
        }
    }
    for id in 1..TRIM_R {
        let i = id as usize;
        if current.devices[i] != target.devices[i] {
            let spec: DeviceSpec = target.devices[i];
            steps.push(RestoreWrite::spec(spec));
        }
    }
    if system != target.system {
        steps.push(RestoreWrite::spec(target.system));
    }
    if wig_wag != target.wig_wag {
        steps.push(RestoreWrite::spec(target.wig_wag));
    }
    steps
}

/// Runs `steps` through the unit's rules on a copy of `current`.
fn simulate(current: &UnitConfig, steps: &[RestoreWrite]) -> Result<(), PlanError> {
    let mut sim = current.clone();
    for step in steps {
        let m = step.message();
        if let Message::DeviceEnable(e) = m {
            if let Err(code) = validate::device_enable(&sim, &e) {
                return Err(PlanError {
                    step: step.to_string(),
                    reason: code.description(),
                });
            }
            sim.apply_device_enable(&e);
            continue;
        }
        if let Some(Err(r)) = validate::check(&sim, &m) {
            return Err(PlanError {
                step: step.to_string(),
                reason: r.to_string(),
            });
        }
        validate::accept(&mut sim, &m);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::device::FIELD_PRI;
    use crate::protocol::message::SwitchId;

    fn on(c: &mut UnitConfig, id: u8, n: u8) {
        c.devices[id as usize].switch_id = SwitchId::Input(n);
    }

    fn names(steps: &[RestoreWrite]) -> Vec<String> {
        steps.iter().map(|s| s.to_string()).collect()
    }

    /// Applies a plan the way the unit would, refusing as the unit would.
    fn run(current: &UnitConfig, steps: &[RestoreWrite]) -> UnitConfig {
        let mut sim = current.clone();
        for s in steps {
            match s.message() {
                Message::DeviceEnable(e) => sim.apply_device_enable(&e),
                m => validate::accept(&mut sim, &m)
                    .unwrap()
                    .unwrap_or_else(|e| panic!("{s} refused: {e:?}")),
            }
        }
        sim
    }

    /// The plan from `cur` to `target` (a target the rules take), once running it
    /// as the unit would has come to hold `target`.
    fn planned(cur: &UnitConfig, target: &UnitConfig) -> Vec<RestoreWrite> {
        assert!(
            validate::whole_config(target).is_empty(),
            "the rules take it"
        );
        let steps = plan(cur, target).unwrap();
        assert_eq!(&run(cur, &steps), target);
        steps
    }

    #[test]
    fn nothing_to_do_when_the_unit_already_holds_the_file() {
        let c = UnitConfig::default();
        assert!(plan(&c, &c).unwrap().is_empty());
    }

    #[test]
    fn unrelated_changes_are_written_without_untying() {
        let mut cur = UnitConfig::default();
        on(&mut cur, 10, 4);
        cur.wig_wag.device_one = Some(10);
        let mut target = cur.clone();
        target.devices[6].circuit_breaker = 5;
        let steps = planned(&cur, &target);
        assert_eq!(names(&steps), ["DEVICE_SPEC for 5A-3"]);
    }

    #[test]
    fn moving_the_wig_wag_off_a_pin_that_goes_off_unties_first() {
        let mut cur = UnitConfig::default();
        on(&mut cur, 10, 4);
        cur.wig_wag.device_one = Some(10);
        let mut target = UnitConfig::default();
        on(&mut target, 11, 5);
        target.wig_wag.device_one = Some(11);
        let steps = planned(&cur, &target);
        assert_eq!(
            names(&steps),
            [
                "WIG_WAG_SPEC with no devices (for a moment, to untie)",
                "DEVICE_SPEC for 5A-7",
                "DEVICE_SPEC for 5A-8",
                "WIG_WAG_SPEC",
            ]
        );
    }

    #[test]
    fn swapping_the_alternators_switches_unties_the_secondary_first() {
        let mut cur = UnitConfig::default();
        on(&mut cur, FIELD_PRI, 1);
        on(&mut cur, 17, 2);
        cur.system.secondary_alternator = Some(17);
        let mut target = cur.clone();
        on(&mut target, FIELD_PRI, 2);
        on(&mut target, 17, 1);
        let steps = planned(&cur, &target);
        assert_eq!(
            names(&steps),
            [
                "SYSTEM_SPEC with no secondary alternator (for a moment, to untie)",
                "DEVICE_SPEC for Field_Pri",
                "DEVICE_SPEC for 10A-1",
                "SYSTEM_SPEC",
            ]
        );
    }

    #[test]
    fn the_secondary_alternator_becoming_the_wig_wag_device_and_back() {
        // The unit has 5A-1 as secondary alternator and 5A-2 as wig-wag; the file swaps
        // their roles. Neither SYSTEM_SPEC nor WIG_WAG_SPEC can go first without untying.
        let mut cur = UnitConfig::default();
        on(&mut cur, 4, 3);
        on(&mut cur, 5, 4);
        cur.system.secondary_alternator = Some(4);
        cur.wig_wag.device_one = Some(5);
        let mut target = cur.clone();
        target.system.secondary_alternator = Some(5);
        target.wig_wag.device_one = Some(4);
        let steps = planned(&cur, &target);
        assert!(matches!(steps[0], RestoreWrite::Spec { untie: true, .. }));
    }

    #[test]
    fn independent_settings_come_after_the_tied_group() {
        let cur = UnitConfig::default();
        let mut target = cur.clone();
        target.flap.enabled = true;
        target.roll_trim.enabled = true;
        target.names[0] = *b"Flaps\0\0\0\0\0\0\0\0\0\0\0";
        target.enabled[9] = false;
        on(&mut target, 9, 2);
        let steps = planned(&cur, &target);
        assert_eq!(
            names(&steps),
            [
                "DEVICE_SPEC for 5A-6",
                "FLAP_SPEC",
                "TRIM_SPEC (roll)",
                "DEVICE_NAME for Flaps",
                "DEVICE_ENABLE for 5A-6 (hidden)",
            ]
        );
    }

    #[test]
    fn a_target_the_rules_refuse_is_never_planned() {
        let cur = UnitConfig::default();
        let mut target = cur.clone();
        // A wig-wag device on no switch: whole_config refuses this file, and so must
        // the plan if a caller skipped that check.
        target.wig_wag.device_one = Some(10);
        let err = plan(&cur, &target).unwrap_err();
        assert_eq!(err.step, "WIG_WAG_SPEC");
    }
}

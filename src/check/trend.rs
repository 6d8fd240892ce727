//! The trend: each circuit's current at this check beside the last check's, with the
//! change. A motor wearing or a connection corroding shows as a current that creeps,
//! so a change over [`CHANGED_PERCENT`] % that is also at least
//! [`CHANGED_MIN_TENTHS`] tenths of an amp is marked "changed since the last check",
//! in words (never by colour alone).
//!
//! Judged on the unit's own tenths of an amp (ICD Table 26), in integers, as
//! [`super::state::BreakerLoad`] is: "over 20 %" is strict, so 5.0 A to 6.0 A
//! (exactly +20 %) is not marked, 5.0 A to 6.1 A is.
//!
//! Which circuit of the last check is "the same" one. Decision: **by name**, the name
//! the builder gave the load (trimmed, letter case ignored), because the trend is the
//! load's (a lamp, a motor, a pump): a load moved to another pin is still compared,
//! and the words say which pin it was on. A pin whose name changed is **not**
//! compared: a typo mended cannot be told from another load wired to a freed pin,
//! and comparing a pump's current with a strobe's would mark a change that is none
//! (or hide one). The words give what that pin read then, under its old name, so the
//! person can judge. Two circuits of one name (the unit allows it): the one on the
//! same pin, else the first.
//!
//! The flow reads no file: the app loads the last check from the logbook and hands
//! it in ([`super::Options::last_check`]).

use std::time::SystemTime;

/// A change must be over this share of the last current to be marked.
pub const CHANGED_PERCENT: u32 = 20;
/// ...and at least this many tenths of an amp: a 0.5 A load reading 0.7 A is the
/// unit's resolution and the lamp's warm-up, not wear.
pub const CHANGED_MIN_TENTHS: u32 = 3;

/// The words that mark a change.
pub const CHANGED_WORDS: &str = "changed since the last check";

/// The last check of this aircraft, as the logbook kept it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LastCheck {
    pub when: Option<SystemTime>,
    pub circuits: Vec<Reading>,
}

/// One circuit at a check: its pin and name then, and its current in tenths of an
/// amp; `None` when the check got no reading (skipped, faulted, did not switch).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reading {
    pub pin: String,
    pub name: String,
    pub tenths: Option<u16>,
}

impl From<&crate::logbook::query::CircuitRow> for Reading {
    /// A circuit as the logbook kept it.
    fn from(r: &crate::logbook::query::CircuitRow) -> Reading {
        Reading {
            pin: r.pin.clone(),
            name: r.name.clone(),
            tenths: r.amps.map(|a| tenths(a as f32)),
        }
    }
}

impl From<crate::logbook::query::LastCheckRows> for LastCheck {
    fn from(l: crate::logbook::query::LastCheckRows) -> LastCheck {
        LastCheck {
            when: crate::logbook::query::time_of(&l.time),
            circuits: l.circuits.iter().map(Reading::from).collect(),
        }
    }
}

/// Amperes as the unit's tenths (the model's amps are the unit's tenths over ten).
pub fn tenths(amps: f32) -> u16 {
    (amps * 10.0).round().clamp(0.0, f32::from(u16::MAX)) as u16
}

/// What the last check says of one circuit.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Then {
    /// The aircraft has no check before this one.
    NoLastCheck,
    /// No circuit of this name, and its pin was not in use.
    NotInLastCheck,
    /// The pin had another name then: not compared (see the module's decision).
    Renamed { name: String, tenths: Option<u16> },
    /// In the last check, with its reading (or none), and the pin it was on if it
    /// was on another.
    Found {
        tenths: Option<u16>,
        moved_from: Option<String>,
    },
}

/// One circuit's current now beside the last check's.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Trend {
    pub now: Option<u16>,
    pub then: Then,
}

fn same_name(a: &str, b: &str) -> bool {
    a.trim().eq_ignore_ascii_case(b.trim())
}

/// The trend of the circuit on `pin` named `name`, reading `now` tenths (`None`: no
/// reading this time).
pub fn trend(last: Option<&LastCheck>, pin: &str, name: &str, now: Option<u16>) -> Trend {
    let Some(last) = last else {
        return Trend {
            now,
            then: Then::NoLastCheck,
        };
    };
    let named: Vec<&Reading> = last
        .circuits
        .iter()
        .filter(|r| same_name(&r.name, name))
        .collect();
    let then = if let Some(r) = named.iter().find(|r| r.pin == pin).or(named.first()) {
        Then::Found {
            tenths: r.tenths,
            moved_from: (r.pin != pin).then(|| r.pin.clone()),
        }
    } else if let Some(r) = last.circuits.iter().find(|r| r.pin == pin) {
        Then::Renamed {
            name: r.name.clone(),
            tenths: r.tenths,
        }
    } else {
        Then::NotInLastCheck
    };
    Trend { now, then }
}

/// Whether a current went from `then` to `now` tenths by more than the rule allows.
/// From 0 A any change of at least the minimum is marked (no share of nothing).
pub fn changed(then: u16, now: u16) -> bool {
    let (then, now) = (u32::from(then), u32::from(now));
    let d = then.abs_diff(now);
    d >= CHANGED_MIN_TENTHS && d * 100 > CHANGED_PERCENT * then
}

/// "6.1 A", "0 A": tenths as the report writes a current.
pub fn amps_text(tenths: u16) -> String {
    if tenths == 0 {
        "0 A".into()
    } else {
        format!("{}.{} A", tenths / 10, tenths % 10)
    }
}

/// The change in words: "+15 %", "−100 %"; from 0 A, in amps: "+2.0 A". The sign is
/// a real minus, as the page writes negative figures.
pub fn change_text(then: u16, now: u16) -> String {
    let d = i32::from(now) - i32::from(then);
    let sign = if d < 0 { "−" } else { "+" };
    if then == 0 {
        let d = d.unsigned_abs();
        format!("{sign}{}.{} A", d / 10, d % 10)
    } else {
        // Rounded half away from zero, in integers.
        let pct = (d.unsigned_abs() * 100 * 2 + u32::from(then)) / (2 * u32::from(then));
        format!("{sign}{pct} %")
    }
}

impl Trend {
    /// Whether this circuit is marked "changed since the last check".
    pub fn changed(&self) -> bool {
        match (&self.then, self.now) {
            (
                Then::Found {
                    tenths: Some(then), ..
                },
                Some(now),
            ) => changed(*then, now),
            _ => false,
        }
    }

    /// The last check's current, if the two are compared.
    pub fn then_tenths(&self) -> Option<u16> {
        match self.then {
            Then::Found { tenths, .. } => tenths,
            _ => None,
        }
    }

    /// In words, beside this check's current: "last check 6.1 A, +15 %", "last check
    /// 6.1 A, +23 %: changed since the last check". `None` with no last check.
    pub fn words(&self) -> Option<String> {
        Some(match &self.then {
            Then::NoLastCheck => return None,
            Then::NotInLastCheck => "not in the last check".into(),
            Then::Renamed { name, tenths } => format!(
                "this pin was \"{name}\" at the last check{}: not compared",
                tenths.map_or_else(String::new, |t| format!(" ({})", amps_text(t)))
            ),
            Then::Found { tenths, moved_from } => {
                let pin = moved_from
                    .as_ref()
                    .map_or_else(String::new, |p| format!(" (then on pin {p})"));
                match (tenths, self.now) {
                    (None, _) => format!("not measured at the last check{pin}"),
                    (Some(t), None) => format!("last check {}{pin}", amps_text(*t)),
                    (Some(t), Some(n)) => {
                        let mut w =
                            format!("last check {}{pin}, {}", amps_text(*t), change_text(*t, n));
                        if changed(*t, n) {
                            w.push_str(": ");
                            w.push_str(CHANGED_WORDS);
                        }
                        w
                    }
                }
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last(rows: &[(&str, &str, Option<u16>)]) -> LastCheck {
        LastCheck {
            when: None,
            circuits: rows
                .iter()
                .map(|&(pin, name, tenths)| Reading {
                    pin: pin.into(),
                    name: name.into(),
                    tenths,
                })
                .collect(),
        }
    }

    /// The edges of "over 20 % and at least 0.3 A", worked by hand in tenths.
    #[test]
    fn a_change_is_marked_over_20_percent_and_from_three_tenths() {
        // Each row: from `then`, to `not` is not marked, to `marked` is.
        for (then, not, marked) in [
            // 5.0 A -> 6.0 A is exactly +20 %: not over it; 6.1 A is.
            (50, 60, 61),
            // Down as well as up: 5.0 -> 4.0 is -20 %, -> 3.9 is -22 %.
            (50, 40, 39),
            // 1.0 A -> 1.2 A is +20 %, not; 1.3 A: +30 % and 0.3 A, marked.
            (10, 12, 13),
            // 0.5 A -> 0.7 A: +40 % but 0.2 A, the unit's resolution: not marked.
            (5, 7, 8),
            // From 0 A, any change of 0.3 A or more.
            (0, 2, 3),
            // No change is not marked; to 0 A (a load gone) is.
            (61, 61, 0),
        ] {
            assert!(!changed(then, not), "{then} -> {not}");
            assert!(changed(then, marked), "{then} -> {marked}");
        }
    }

    /// Each row: the circuit now (pin, name, tenths), the words its trend gives and
    /// whether it is marked changed.
    type Row<'a> = (&'a str, &'a str, Option<u16>, Option<&'a str>, bool);

    #[track_caller]
    fn says(last: Option<&LastCheck>, rows: &[Row]) {
        for &(pin, name, now, words, marked) in rows {
            let t = trend(last, pin, name, now);
            assert_eq!(t.words().as_deref(), words, "{pin} {name} {now:?}");
            assert_eq!(t.changed(), marked, "{pin} {name} {now:?}");
        }
    }

    const CHANGED: &str = ": changed since the last check";

    #[test]
    fn the_words_give_both_currents_and_the_change() {
        let l = last(&[("J5-3", "Landing Lt", Some(61))]);
        says(
            Some(&l),
            &[
                (
                    "J5-3",
                    "Landing Lt",
                    Some(70),
                    Some("last check 6.1 A, +15 %"),
                    false,
                ),
                (
                    "J5-3",
                    "Landing Lt",
                    Some(75),
                    Some(&format!("last check 6.1 A, +23 %{CHANGED}")),
                    true,
                ),
                (
                    "J5-3",
                    "Landing Lt",
                    Some(0),
                    Some(&format!("last check 6.1 A, −100 %{CHANGED}")),
                    true,
                ),
                // No reading now: the last one, alone.
                ("J5-3", "Landing Lt", None, Some("last check 6.1 A"), false),
            ],
        );
    }

    #[test]
    fn from_0_a_the_change_is_in_amps() {
        let l = last(&[("J5-3", "Taxi Lt", Some(0))]);
        says(
            Some(&l),
            &[
                (
                    "J5-3",
                    "Taxi Lt",
                    Some(20),
                    Some(&format!("last check 0 A, +2.0 A{CHANGED}")),
                    true,
                ),
                (
                    "J5-3",
                    "Taxi Lt",
                    Some(0),
                    Some("last check 0 A, +0.0 A"),
                    false,
                ),
            ],
        );
    }

    #[test]
    fn no_last_check_says_nothing_and_marks_nothing() {
        says(None, &[("J5-3", "Landing Lt", Some(70), None, false)]);
        let l = last(&[("J5-3", "Landing Lt", None)]);
        says(
            Some(&l),
            &[
                (
                    "J5-3",
                    "Landing Lt",
                    Some(70),
                    Some("not measured at the last check"),
                    false,
                ),
                (
                    "J6-1",
                    "Strobe",
                    Some(70),
                    Some("not in the last check"),
                    false,
                ),
            ],
        );
    }

    /// The decision: the same name follows the load to another pin; another name on
    /// the same pin is not compared, and its old name and figure are said.
    #[test]
    fn a_moved_circuit_is_followed_by_name_and_a_renamed_pin_is_not_compared() {
        let l = last(&[("J5-3", "Landing Lt", Some(61)), ("J6-1", "Pump", Some(40))]);
        says(
            Some(&l),
            &[
                (
                    "J5-9",
                    " landing lt ",
                    Some(80),
                    Some(&format!(
                        "last check 6.1 A (then on pin J5-3), +31 %{CHANGED}"
                    )),
                    true,
                ),
                (
                    "J6-1",
                    "Strobe",
                    Some(20),
                    Some("this pin was \"Pump\" at the last check (4.0 A): not compared"),
                    false,
                ),
            ],
        );
        assert_eq!(
            trend(Some(&l), "J6-1", "Strobe", Some(20)).then_tenths(),
            None
        );
    }

    #[test]
    fn of_two_circuits_of_one_name_the_one_on_the_same_pin_is_compared() {
        let l = last(&[("J5-1", "Lights", Some(10)), ("J5-2", "Lights", Some(50))]);
        let t = trend(Some(&l), "J5-2", "Lights", Some(50));
        assert_eq!(t.then_tenths(), Some(50));
        assert_eq!(t.words().unwrap(), "last check 5.0 A, +0 %");
    }

    #[test]
    fn percentages_round_half_away_from_zero() {
        assert_eq!(change_text(61, 70), "+15 %"); // 14.75
        assert_eq!(change_text(40, 39), "−3 %"); // 2.5
        assert_eq!(change_text(8, 9), "+13 %"); // 12.5
        assert_eq!(tenths(6.1), 61);
        assert_eq!(tenths(0.04), 0);
    }
}

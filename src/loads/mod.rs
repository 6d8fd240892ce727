//! The electrical load analysis: which circuit is on in which phase of flight, how
//! much each draws, and what that leaves of the alternator and the battery.
//!
//! - [`file`]: the TOML file the builder edits (the phases, the alternator's rating,
//!   the battery's capacity, every circuit), its commented template and its errors;
//! - [`analysis`]: the arithmetic (total per phase, margin against the alternator,
//!   emergency endurance on the battery), pure;
//! - [`disk`]: reading the file, and writing the template on the first run without
//!   ever writing over a file that is there;
//! - [`guess`]: the template's phases for each circuit, guessed from its name;
//! - [`wire`]: the wire rules of FAA AC 43.13-1B chapter 11 (the largest breaker per
//!   gauge, resistance per foot, the allowable voltage drop), each citing its table;
//! - [`wiring`]: each circuit's wire (from the file) held against its breaker and its
//!   current by those rules, with a verdict.
//!
//! It stands on `protocol` (the pins of Appendix B) and `model` (the circuits the unit
//! has) only; the installation check (`crate::check`), its screen (`ui::check::loads`)
//! and its report stand on it.

pub mod analysis;
pub mod disk;
pub mod file;
pub mod guess;
pub mod wire;
pub mod wiring;

pub use analysis::{Analysis, Figure, Level, analyse};
pub use file::LoadCircuit;

/// The phases of flight the analysis adds up, in the order they are flown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Phase {
    Ground,
    Taxi,
    TakeOff,
    CruiseDay,
    CruiseNight,
    Landing,
    /// The alternator has failed: everything left on runs from the battery alone.
    Emergency,
}

impl Phase {
    pub const ALL: [Phase; 7] = [
        Phase::Ground,
        Phase::Taxi,
        Phase::TakeOff,
        Phase::CruiseDay,
        Phase::CruiseNight,
        Phase::Landing,
        Phase::Emergency,
    ];

    /// Its key in the load file.
    pub fn key(self) -> &'static str {
        match self {
            Phase::Ground => "ground",
            Phase::Taxi => "taxi",
            Phase::TakeOff => "take_off",
            Phase::CruiseDay => "cruise_day",
            Phase::CruiseNight => "cruise_night",
            Phase::Landing => "landing",
            Phase::Emergency => "emergency",
        }
    }

    /// Its name in words, for screens and the report.
    pub fn title(self) -> &'static str {
        match self {
            Phase::Ground => "ground",
            Phase::Taxi => "taxi",
            Phase::TakeOff => "take-off",
            Phase::CruiseDay => "cruise day",
            Phase::CruiseNight => "cruise night",
            Phase::Landing => "landing",
            Phase::Emergency => "emergency (battery only)",
        }
    }

    /// The emergency phase runs on the battery alone; every other phase on the
    /// alternator.
    pub fn on_battery(self) -> bool {
        self == Phase::Emergency
    }

    pub fn index(self) -> usize {
        self as usize
    }
}

/// For tests: a circuit as the model lists it, with no live values.
#[cfg(test)]
pub(crate) fn test_circuit(
    id: u8,
    name: &str,
    kind: crate::model::CircuitKind,
) -> crate::model::Circuit {
    crate::model::Circuit {
        id,
        name: name.into(),
        pin: crate::protocol::device::device(id).map_or("?", |d| d.system_name),
        kind,
        state: crate::model::CircuitState::Unknown,
        amps: None,
        breaker: None,
        switch: None,
        spec_unknown: false,
        faulted_again: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_are_in_flying_order_with_their_keys() {
        let keys: Vec<&str> = Phase::ALL.iter().map(|p| p.key()).collect();
        assert_eq!(
            keys,
            [
                "ground",
                "taxi",
                "take_off",
                "cruise_day",
                "cruise_night",
                "landing",
                "emergency"
            ]
        );
        for (i, p) in Phase::ALL.into_iter().enumerate() {
            assert_eq!(p.index(), i);
        }
        assert!(Phase::Emergency.on_battery());
        assert!(!Phase::CruiseNight.on_battery());
    }
}

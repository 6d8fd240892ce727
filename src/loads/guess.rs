//! The load file's template starts from what each circuit's name says: a landing
//! light is on to taxi, take off and land; a nav light at night; strobes and beacons
//! from taxi on; pitot heat off until the builder turns it on; flaps and trims are
//! short intermittent loads; the emergency phase keeps the avionics and one light.
//! Every such guess is marked in the file for the builder to check.
//!
//! Decisions (none of them in the ICD, which knows no phases of flight):
//! - a flap or trim motor runs a tenth of the phase it is used in: AC 43.13-1B
//!   par. 11-35c counts "operating the gear and flaps" among the "short intermittent
//!   loads";
//! - a circuit whose name says nothing known is on in every phase on the alternator
//!   (the worst case) and off on the battery;
//! - the one light on the battery is a landing light if there is one (it is needed to
//!   land), else a taxi light, else a nav light.

use super::Phase;
use crate::model::{Circuit, CircuitKind};

/// What the template guessed for one circuit: its duty per phase ([`Phase::index`])
/// and, for a guess, what it took the circuit for.
#[derive(Debug, Clone, PartialEq)]
pub struct Guess {
    pub duty: [f64; 7],
    /// `None` where nothing is guessed (the starter, an alternator field).
    pub why: Option<String>,
}

/// A motor's share of a phase it runs in.
pub const INTERMITTENT: f64 = 0.1;

/// What a circuit is taken for, by its kind and then its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    Starter,
    Field,
    Flaps,
    Trim,
    LandingLight,
    TaxiLight,
    NavLight,
    AntiCollision,
    PitotHeat,
    Avionics,
    Unknown,
}

fn role(c: &Circuit) -> Role {
    match c.kind {
        CircuitKind::Starter => return Role::Starter,
        CircuitKind::Alternator { .. } => return Role::Field,
        CircuitKind::Flaps => return Role::Flaps,
        CircuitKind::Trim(_) => return Role::Trim,
        CircuitKind::Device => {}
    }
    let name = c.name.to_lowercase();
    let has = |words: &[&str]| words.iter().any(|w| name.contains(w));
    let light = has(&["lt", "light", "lamp"]);
    if has(&["flap"]) {
        Role::Flaps
    } else if has(&["trim"]) {
        Role::Trim
    } else if has(&["landing", "ldg"]) {
        Role::LandingLight
    } else if has(&["taxi"]) {
        Role::TaxiLight
    } else if has(&["strobe", "beacon", "anti-col", "anticol", "acl"]) {
        Role::AntiCollision
    } else if has(&["position"]) || (light && has(&["nav"])) {
        Role::NavLight
    } else if has(&["pitot", "heat"]) {
        Role::PitotHeat
    } else if c.id == crate::protocol::device::EFIS
        || has(&[
            "efis",
            "avionic",
            "radio",
            "com",
            "gps",
            "nav",
            "xpdr",
            "transponder",
            "audio",
            "intercom",
            "autopilot",
            "a/p",
            "ahrs",
            "ads-b",
            "adsb",
            "ems",
            "engine",
            "display",
            "pfd",
            "mfd",
            "servo",
        ])
    {
        Role::Avionics
    } else {
        Role::Unknown
    }
}

/// `share` in the phases named, off in the others.
fn on_in<'a>(phases: impl IntoIterator<Item = &'a Phase>, share: f64) -> [f64; 7] {
    let mut duty = [0.0; 7];
    for p in phases {
        duty[p.index()] = share;
    }
    duty
}

/// Every phase on the alternator: all but the emergency, which is last.
const ON_THE_ALTERNATOR: &[Phase] = Phase::ALL.split_at(6).0;

/// Every circuit's guess, in the order given.
pub fn guesses(circuits: &[Circuit]) -> Vec<Guess> {
    let roles: Vec<Role> = circuits.iter().map(role).collect();
    // The one light kept on the battery.
    let light = [Role::LandingLight, Role::TaxiLight, Role::NavLight]
        .into_iter()
        .find_map(|r| roles.iter().position(|&x| x == r));
    roles
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            let (mut duty, why) = match r {
                Role::Starter => (on_in(&[], 1.0), None),
                Role::Field => (on_in(ON_THE_ALTERNATOR, 1.0), None),
                Role::Flaps => (
                    on_in(&[Phase::Taxi, Phase::TakeOff, Phase::Landing], INTERMITTENT),
                    Some("flaps: a short intermittent load, set for take-off and landing"),
                ),
                Role::Trim => (
                    on_in(&ON_THE_ALTERNATOR[1..], INTERMITTENT),
                    Some("a trim: a short intermittent load in flight"),
                ),
                Role::LandingLight | Role::TaxiLight => (
                    on_in(&[Phase::Taxi, Phase::TakeOff, Phase::Landing], 1.0),
                    Some("a landing or taxi light: on to taxi, take off and land"),
                ),
                Role::NavLight => (
                    on_in(&[Phase::CruiseNight], 1.0),
                    Some("a nav light: on at night"),
                ),
                Role::AntiCollision => (
                    on_in(&ON_THE_ALTERNATOR[1..], 1.0),
                    Some("a strobe or beacon: on from taxi on"),
                ),
                Role::PitotHeat => (
                    on_in(&[], 1.0),
                    Some("pitot heat: off unless you turn it on"),
                ),
                Role::Avionics => (
                    on_in(&Phase::ALL, 1.0),
                    Some("avionics: on throughout, and on the battery"),
                ),
                Role::Unknown => (
                    on_in(ON_THE_ALTERNATOR, 1.0),
                    Some("not known from its name: on throughout, off on the battery"),
                ),
            };
            let mut why = why.map(String::from);
            if Some(i) == light {
                duty[Phase::Emergency.index()] = 1.0;
                why = why.map(|w| format!("{w}; the one light kept on the battery"));
            }
            Guess { duty, why }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loads::test_circuit as circuit;
    use crate::model::TrimKind;
    use crate::protocol::device::{EFIS, FIELD_PRI, FLAPS, STARTER, TRIM_P};

    /// The phases a duty is on in, by key, with its share where not whole.
    fn phases(duty: &[f64; 7]) -> String {
        Phase::ALL
            .iter()
            .filter(|p| duty[p.index()] > 0.0)
            .map(|p| match duty[p.index()] {
                1.0 => p.key().to_string(),
                d => format!("{}={d}", p.key()),
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    #[test]
    fn each_name_gets_the_phases_it_says() {
        let d = CircuitKind::Device;
        let unit = [
            circuit(STARTER, "Starter", CircuitKind::Starter),
            circuit(EFIS, "EFIS", d),
            circuit(
                FIELD_PRI,
                "Alternator",
                CircuitKind::Alternator { primary: true },
            ),
            circuit(4, "Nav Lt", d),
            circuit(5, "Strobe Lt", d),
            circuit(6, "Beacon", d),
            circuit(7, "Comm 1", d),
            circuit(8, "NAV/COM 2", d),
            circuit(17, "Landing Lt", d),
            circuit(18, "Taxi Lt", d),
            circuit(19, "Boost Pump", d),
            circuit(20, "Pitot Heat", d),
            circuit(FLAPS, "Flaps", CircuitKind::Flaps),
            circuit(TRIM_P, "Trim_P", CircuitKind::Trim(TrimKind::Pitch)),
        ];
        let got: Vec<(String, String)> = unit
            .iter()
            .zip(guesses(&unit))
            .map(|(c, g)| (c.name.clone(), phases(&g.duty)))
            .collect();
        let want = [
            ("Starter", ""),
            (
                "EFIS",
                "ground taxi take_off cruise_day cruise_night landing emergency",
            ),
            (
                "Alternator",
                "ground taxi take_off cruise_day cruise_night landing",
            ),
            ("Nav Lt", "cruise_night"),
            ("Strobe Lt", "taxi take_off cruise_day cruise_night landing"),
            ("Beacon", "taxi take_off cruise_day cruise_night landing"),
            (
                "Comm 1",
                "ground taxi take_off cruise_day cruise_night landing emergency",
            ),
            (
                "NAV/COM 2",
                "ground taxi take_off cruise_day cruise_night landing emergency",
            ),
            ("Landing Lt", "taxi take_off landing emergency"),
            ("Taxi Lt", "taxi take_off landing"),
            (
                "Boost Pump",
                "ground taxi take_off cruise_day cruise_night landing",
            ),
            ("Pitot Heat", ""),
            ("Flaps", "taxi=0.1 take_off=0.1 landing=0.1"),
            (
                "Trim_P",
                "taxi=0.1 take_off=0.1 cruise_day=0.1 cruise_night=0.1 landing=0.1",
            ),
        ]
        .map(|(n, p)| (n.to_string(), p.to_string()));
        assert_eq!(got, want);
        // Every guess says what it took the circuit for; the known cases are not guesses.
        let g = guesses(&unit);
        assert_eq!((g[0].why.as_deref(), g[2].why.as_deref()), (None, None));
        assert!(g[3..].iter().all(|g| g.why.is_some()));
        assert!(
            g[8].why
                .as_deref()
                .unwrap()
                .ends_with("the one light kept on the battery")
        );
    }

    #[test]
    fn without_a_landing_light_the_taxi_or_nav_light_is_the_one_kept_on() {
        let d = CircuitKind::Device;
        let g = guesses(&[circuit(4, "Nav Lt", d), circuit(18, "Taxi Lt", d)]);
        let e = Phase::Emergency.index();
        assert_eq!((g[0].duty[e], g[1].duty[e]), (0.0, 1.0));
        let g = guesses(&[circuit(4, "Nav Lt", d), circuit(7, "Radio", d)]);
        assert_eq!((g[0].duty[e], g[1].duty[e]), (1.0, 1.0));
    }
}

//! Each circuit's wire held against its breaker and its current, by the rules of
//! [`super::wire`]: one [`Row`] per circuit, with a [`Verdict`]. Pure: the caller
//! brings the breakers (a unit or a backup), the currents measured now and the system
//! voltage. `vpx-efis wires`, the check's report, the page and setup all read it here.

use super::file::LoadCircuit;
use super::wire::{self, SystemVoltage, Wire};
use std::time::Instant;

use crate::model::{CircuitState, Model};
use crate::protocol::config::UnitConfig;
use crate::protocol::device;

/// A circuit's wiring as the load file gives it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WireRun {
    /// `wire`: its size.
    pub wire: Option<Wire>,
    /// `wire_length`: from the VP-X pin to the load, feet.
    pub feed_feet: Option<f64>,
    /// `return_length`: the load's ground wire back to a ground block, feet; absent
    /// means grounded at the load.
    pub return_feet: Option<f64>,
}

impl WireRun {
    /// ¶11-67: the run is the feed and the ground return; `None` without a feed length.
    pub fn run_feet(&self) -> Option<f64> {
        self.feed_feet.map(|f| f + self.return_feet.unwrap_or(0.0))
    }
}

/// What a circuit's wire comes to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The breaker protects the wire, and the drop measured (if any) is within limit.
    Ok,
    /// The breaker is above what Table 11-3 allows for the wire: it would not open
    /// before the wire overheats (¶11-48). A failure.
    Unprotected,
    /// The drop at the current measured now is over Table 11-6's limit. A warning.
    Drop,
    /// No wire in the load file: listed, failing nothing.
    NotEntered,
}

impl Verdict {
    /// The word, the same on screen, in the report and in JSON.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Ok => "ok",
            Verdict::Unprotected => "unprotected",
            Verdict::Drop => "drop",
            Verdict::NotEntered => "not entered",
        }
    }
}

/// One circuit's wire against its breaker and its current.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub id: u8,
    pub pin: &'static str,
    pub name: String,
    pub wire: Option<Wire>,
    /// Feed plus return (¶11-67), feet.
    pub run_feet: Option<f64>,
    /// No return length entered: taken as grounded at the load.
    pub return_assumed: bool,
    pub breaker_amps: Option<u8>,
    /// Table 11-3's largest breaker for the wire.
    pub max_breaker_amps: Option<f64>,
    /// Its current now (DEVICE_STATUS, while it is on).
    pub amps: Option<f64>,
    /// The drop at `amps`.
    pub drop_volts: Option<f64>,
    /// The drop at the breaker's current.
    pub drop_at_breaker_volts: Option<f64>,
    /// Table 11-6's continuous limit for the system.
    pub drop_limit_volts: Option<f64>,
    /// The longest run (feed and return) that keeps `amps` within the limit.
    pub longest_run_feet: Option<f64>,
    pub verdict: Verdict,
}

impl Row {
    /// The setup prompt's and the report's sentence for an unprotected wire: "Strobe
    /// Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 6 A breaker would not
    /// protect it".
    pub fn unprotected_words(&self) -> Option<String> {
        let (Some(w), Some(b)) = (self.wire, self.breaker_amps) else {
            return None;
        };
        (self.verdict == Verdict::Unprotected).then(|| breaker_words(&self.name, &w, b))
    }
}

impl Row {
    /// A measured drop over the limit, in words with the run that would bring it
    /// under: "Nav Lt drops 0.65 V at 4.0 A through 26.0 ft (feed and return); AC
    /// 43.13-1B Table 11-6 allows 0.5 V: a run of at most 20.0 ft would bring it under".
    pub fn drop_words(&self) -> Option<String> {
        if self.verdict != Verdict::Drop {
            return None;
        }
        let (d, a, r, l) = (
            self.drop_volts?,
            self.amps?,
            self.run_feet?,
            self.drop_limit_volts?,
        );
        let under = self
            .longest_run_feet
            .map(|f| {
                format!(
                    ": a run of at most {} would bring it under",
                    wire::feet_text(f)
                )
            })
            .unwrap_or_default();
        Some(format!(
            "{} drops {d:.2} V at {a:.1} A through {} (feed and return); AC 43.13-1B \
             Table 11-6 allows {l} V continuous{under}",
            self.name,
            wire::feet_text(r)
        ))
    }
}

/// The notes that go with a set of rows: the system, the assumptions and the chart's
/// basis, in words, each once.
pub fn notes(rows: &[Row], system: Option<&SystemVoltage>) -> Vec<String> {
    let mut out = Vec::new();
    match system {
        Some(s) => {
            out.push(format!(
                "a {} system: AC 43.13-1B Table 11-6 allows a continuous drop of {} V from \
                 the bus to the equipment",
                s.system.words(),
                s.system.allowed_drop()
            ));
            if let Some(n) = &s.note {
                out.push(n.clone());
            }
        }
        None => out.push(
            "the system voltage is not known (no bus voltage, no overvoltage limit): no \
             drop is held against a limit"
                .into(),
        ),
    }
    let assumed: Vec<&str> = rows
        .iter()
        .filter(|r| r.return_assumed)
        .map(|r| r.pin)
        .collect();
    if !assumed.is_empty() {
        out.push(format!(
            "no return_length for {}: taken as grounded at the load (the run is the feed \
             alone)",
            assumed.join(", ")
        ));
    }
    for r in rows {
        if let Some(w) = r.wire
            && let wire::Size::Mm2(mm) = w.size
        {
            out.push(format!(
                "{}: {mm} mm² is counted as {} AWG, the largest gauge whose cross-section it \
                 is at least (AC 43.13-1B Table 11-9; 1 mm² = {} circular mils)",
                r.pin,
                w.awg,
                wire::CIRCULAR_MILS_PER_MM2
            ));
        }
    }
    if rows.iter().any(|r| r.wire.is_some()) {
        out.push(wire::CHART_BASIS.to_string());
        out.push(
            "drops are at 20 °C (Table 11-9's resistance); a hotter conductor's allowed run \
             is shorter (AC 43.13-1B ¶11-66)"
                .into(),
        );
    }
    out
}

/// "NAME's wire is W: AC 43.13-1B Table 11-3 allows X A; a B A breaker would not
/// protect it", for a breaker over its wire.
pub fn breaker_words(name: &str, wire: &Wire, breaker_amps: u8) -> String {
    let allows = match wire.max_breaker_amps() {
        Some(a) => format!("allows {} A", amps_text(a)),
        None => format!("gives no breaker for {} AWG", wire.awg),
    };
    format!(
        "{name}'s wire is {wire}: AC 43.13-1B Table 11-3 {allows}; a {breaker_amps} A \
         breaker would not protect it"
    )
}

/// Amperes as the chart writes them: "5", "7.5".
pub fn amps_text(a: f64) -> String {
    format!("{a}")
}

/// What one circuit is, from wherever the caller reads it.
#[derive(Debug, Clone, PartialEq)]
pub struct Circuit<'a> {
    pub id: u8,
    /// The unit's name for it, where known; else the file's.
    pub name: Option<&'a str>,
    pub breaker_amps: Option<u8>,
    /// Measured now, while it is on.
    pub amps: Option<f64>,
}

/// One row per circuit: every circuit the file lists and every one `unit` has, in pin
/// order.
pub fn assess(
    file: &[LoadCircuit],
    unit: &[Circuit<'_>],
    system: Option<&SystemVoltage>,
) -> Vec<Row> {
    let mut ids: Vec<u8> = file
        .iter()
        .map(|c| c.id)
        .chain(unit.iter().map(|c| c.id))
        .collect();
    ids.sort_unstable();
    ids.dedup();
    ids.into_iter()
        .map(|id| {
            let f = file.iter().find(|c| c.id == id);
            let u = unit.iter().find(|c| c.id == id);
            let name = u
                .and_then(|u| u.name)
                .map(str::to_string)
                .or_else(|| f.map(|f| f.name.clone()))
                .unwrap_or_else(|| pin(id).to_string());
            row(
                id,
                name,
                f.map(|f| f.wire).unwrap_or_default(),
                u.and_then(|u| u.breaker_amps),
                u.and_then(|u| u.amps),
                system,
            )
        })
        .collect()
}

/// The system as the model knows it: SYSTEM_SPEC's overvoltage limit and the live bus.
pub fn model_system(model: &Model, now: Instant) -> Option<SystemVoltage> {
    wire::system(
        model
            .system_spec
            .and_then(|s| wire::limit_volts(s.value.overvoltage_limit)),
        model.live_system(now).map(|s| s.main_bus_volts.value()),
    )
}

/// The rows for the circuits the model shows, with their breakers; a circuit's current
/// is `measured`'s where it has one (the check's), else its live one while it is on.
pub fn from_model(
    file: &[LoadCircuit],
    model: &Model,
    now: Instant,
    measured: &[(u8, f32)],
) -> (Vec<Row>, Option<SystemVoltage>) {
    let system = model_system(model, now);
    let circuits = model.circuits(now);
    let unit: Vec<Circuit<'_>> = circuits
        .iter()
        .map(|c| Circuit {
            id: c.id,
            name: Some(&c.name),
            breaker_amps: c.breaker,
            amps: measured
                .iter()
                .find(|(id, _)| *id == c.id)
                .map(|(_, a)| f64::from(*a))
                .or_else(|| {
                    (c.state == CircuitState::On)
                        .then_some(c.amps)
                        .flatten()
                        .map(f64::from)
                }),
        })
        .collect();
    (assess(file, &unit, system.as_ref()), system)
}

/// The row of one circuit as the page lists it: its breaker, and its current while on.
pub fn circuit_row(
    file: &[LoadCircuit],
    c: &crate::model::Circuit,
    system: Option<&SystemVoltage>,
) -> Row {
    let run = file
        .iter()
        .find(|f| f.id == c.id)
        .map(|f| f.wire)
        .unwrap_or_default();
    let amps = (c.state == CircuitState::On)
        .then_some(c.amps)
        .flatten()
        .map(f64::from);
    row(c.id, c.name.clone(), run, c.breaker, amps, system)
}

/// Whether circuit `id`'s breaker is over the wire `file` gives it (Table 11-3).
pub fn unprotected(file: &[LoadCircuit], id: u8, breaker: Option<u8>) -> bool {
    let wire = file.iter().find(|f| f.id == id).and_then(|f| f.wire.wire);
    matches!((wire, breaker), (Some(w), Some(b)) if !w.protected_by(f64::from(b)))
}

/// The circuits a unit's configuration (read from it, or from a backup) shows: each
/// one's name (DEVICE_NAME, else its pin) and breaker (DEVICE_SPEC; the trims' fixed
/// one). Flaps and trims count where they are enabled, pins 4–28 where shown.
pub fn configured(cfg: &UnitConfig) -> Vec<(u8, String, u8)> {
    device::DEVICES
        .iter()
        .filter(|d| match d.id {
            device::FLAPS => cfg.flap.enabled,
            device::TRIM_R => cfg.roll_trim.enabled,
            device::TRIM_P => cfg.pitch_trim.enabled,
            id if device::enable_flag_allowed(id) => cfg.enabled[id as usize],
            _ => true,
        })
        .map(|d| {
            let name: String = cfg.names[d.id as usize]
                .iter()
                .take_while(|&&b| b != 0)
                .map(|&b| b as char)
                .collect();
            let name = if name.trim().is_empty() {
                d.system_name.to_string()
            } else {
                name
            };
            let breaker = if d.breaker_changeable() {
                cfg.devices[d.id as usize].circuit_breaker
            } else {
                d.amps_min
            };
            (d.id, name, breaker)
        })
        .collect()
}

fn pin(id: u8) -> &'static str {
    device::device(id).map_or("?", |d| d.system_name)
}

/// One circuit's row.
pub fn row(
    id: u8,
    name: String,
    run: WireRun,
    breaker_amps: Option<u8>,
    amps: Option<f64>,
    system: Option<&SystemVoltage>,
) -> Row {
    let limit = system.map(|s| s.system.allowed_drop());
    let run_feet = run.run_feet();
    let at = |a: Option<f64>| match (run.wire, run_feet, a) {
        (Some(w), Some(r), Some(a)) => Some(wire::drop_volts(&w, r, a)),
        _ => None,
    };
    let drop_volts = at(amps);
    let drop_at_breaker_volts = at(breaker_amps.map(f64::from));
    let verdict = match run.wire {
        None => Verdict::NotEntered,
        Some(w) if breaker_amps.is_some_and(|b| !w.protected_by(f64::from(b))) => {
            Verdict::Unprotected
        }
        Some(_) if matches!((drop_volts, limit), (Some(d), Some(l)) if d > l) => Verdict::Drop,
        Some(_) => Verdict::Ok,
    };
    let longest_run_feet = match (run.wire, amps, limit) {
        (Some(w), Some(a), Some(l)) if a > 0.0 => Some(wire::longest_run_feet(&w, a, l)),
        _ => None,
    };
    Row {
        id,
        pin: pin(id),
        name,
        wire: run.wire,
        run_feet,
        return_assumed: run.feed_feet.is_some() && run.return_feet.is_none(),
        breaker_amps,
        max_breaker_amps: run.wire.and_then(|w| w.max_breaker_amps()),
        amps,
        drop_volts,
        drop_at_breaker_volts,
        drop_limit_volts: limit,
        longest_run_feet,
        verdict,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loads::wire::{System, system};

    fn run(w: &str, feed: Option<f64>, ret: Option<f64>) -> WireRun {
        WireRun {
            wire: Some(Wire::parse(w).unwrap()),
            feed_feet: feed,
            return_feet: ret,
        }
    }

    /// A circuit's row on a 14 V system: its `wire`, its breaker, its current.
    fn on_14v(wire: WireRun, breaker: u8, amps: Option<f64>) -> Row {
        let v14 = SystemVoltage {
            system: System::V14,
            note: None,
        };
        row(3, "x".into(), wire, Some(breaker), amps, Some(&v14))
    }

    /// A 6 A breaker on 22 AWG: Table 11-3 allows 5 A. The issue's own example.
    #[test]
    fn a_breaker_over_its_wire_is_unprotected_and_says_so() {
        let r = row(
            0x08,
            "Strobe Lt".into(),
            run("22 AWG", None, None),
            Some(6),
            None,
            None,
        );
        assert_eq!(r.verdict, Verdict::Unprotected);
        assert_eq!(r.max_breaker_amps, Some(5.0));
        assert_eq!(
            r.unprotected_words().unwrap(),
            "Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 6 A breaker \
             would not protect it"
        );
        let ok = on_14v(run("22 AWG", None, None), 5, None);
        assert_eq!(ok.verdict, Verdict::Ok);
        assert_eq!(ok.unprotected_words(), None);
        // 20 AWG allows 7.5 A: a whole-amp breaker of 7 protects it, 8 does not.
        let b = |a| on_14v(run("20 AWG", None, None), a, None).verdict;
        assert_eq!(b(7), Verdict::Ok);
        assert_eq!(b(8), Verdict::Unprotected);
    }

    /// The run includes the return (¶11-67): 18 AWG, 20 ft feed and 6 ft return, 4 A
    /// measured on a 14 V system: 0.00623 × 26 × 4 = 0.64792 V, over 0.5 V. The
    /// longest run: 0.5 / (0.00623 × 4) = 20.06 ft. Without the return, 20 ft gives
    /// 0.4984 V, under the limit: the return is what tips it.
    #[test]
    fn a_drop_over_the_limit_counts_the_return_and_gives_the_run_that_would_pass() {
        let r = on_14v(run("18 AWG", Some(20.0), Some(6.0)), 10, Some(4.0));
        assert_eq!(r.run_feet, Some(26.0));
        assert!(!r.return_assumed);
        assert!((r.drop_volts.unwrap() - 0.64792).abs() < 1e-6);
        assert_eq!(r.drop_limit_volts, Some(0.5));
        assert_eq!(r.verdict, Verdict::Drop);
        assert!((r.longest_run_feet.unwrap() - 20.064).abs() < 0.001);
        // At the breaker's 10 A: 0.00623 × 26 × 10 = 1.6198 V.
        assert!((r.drop_at_breaker_volts.unwrap() - 1.6198).abs() < 1e-6);
        let no_return = on_14v(run("18 AWG", Some(20.0), None), 10, Some(4.0));
        assert!(no_return.return_assumed);
        assert_eq!(no_return.verdict, Verdict::Ok);
        assert!((no_return.drop_volts.unwrap() - 0.4984).abs() < 1e-6);
    }

    #[test]
    fn unprotected_outranks_drop_and_an_unentered_wire_fails_nothing() {
        let r = on_14v(run("22 AWG", Some(40.0), None), 10, Some(4.0));
        assert_eq!(r.verdict, Verdict::Unprotected);
        let n = on_14v(WireRun::default(), 15, Some(4.0));
        assert_eq!(n.verdict, Verdict::NotEntered);
        assert_eq!(n.drop_volts, None);
        // No current measured: no drop verdict, but the drop at the breaker is there.
        let idle = on_14v(run("22 AWG", Some(40.0), None), 5, None);
        assert_eq!(idle.verdict, Verdict::Ok);
        // 0.0162 × 40 × 5 = 3.24 V.
        assert!((idle.drop_at_breaker_volts.unwrap() - 3.24).abs() < 1e-9);
    }

    /// A unit's configuration: disabled pins are not circuits, a name read or the pin,
    /// and the trims' breaker is their fixed 2 A (ICD Table 40), whatever is stored.
    #[test]
    fn a_configuration_gives_its_shown_circuits_names_and_breakers() {
        use crate::protocol::device::{TRIM_P, TRIM_R};
        let mut cfg = UnitConfig::default();
        cfg.enabled[5] = false;
        cfg.names[4][..6].copy_from_slice(b"Nav Lt");
        cfg.devices[4].circuit_breaker = 3;
        cfg.pitch_trim.enabled = true;
        cfg.roll_trim.enabled = false;
        cfg.devices[TRIM_P as usize].circuit_breaker = 9;
        let got = configured(&cfg);
        assert!(got.iter().all(|(id, _, _)| *id != 5 && *id != TRIM_R));
        assert!(got.contains(&(4, "Nav Lt".into(), 3)));
        assert!(got.contains(&(6, "5A-3".into(), cfg.devices[6].circuit_breaker)));
        assert!(got.contains(&(TRIM_P, "Trim_P".into(), 2)));
    }

    /// The notes say the system, each assumption and the metric count, once each.
    #[test]
    fn the_notes_say_the_system_the_assumptions_and_the_metric_count() {
        let file = vec![
            LoadCircuit {
                id: 4,
                name: "Nav".into(),
                amps: None,
                duty: [0.0; 7],
                wire: run("1.0 mm2", Some(10.0), None),
            },
            LoadCircuit {
                id: 5,
                name: "Strobe".into(),
                amps: None,
                duty: [0.0; 7],
                wire: run("20 AWG", Some(10.0), Some(2.0)),
            },
        ];
        let s = system(Some(32), Some(14.2)).unwrap();
        let rows = assess(&file, &[], Some(&s));
        let notes = notes(&rows, Some(&s));
        assert!(
            notes[0].starts_with(
                "a 14 V system: AC 43.13-1B Table 11-6 allows a continuous drop of 0.5 V"
            ),
            "{notes:?}"
        );
        assert!(notes[1].contains("the bus decides"), "{notes:?}");
        assert!(
            notes
                .iter()
                .any(|n| n.starts_with("no return_length for 5A-1: taken as grounded at the load")),
            "{notes:?}"
        );
        assert!(
            notes
                .iter()
                .any(|n| n.starts_with("5A-1: 1 mm² is counted as 18 AWG")),
            "{notes:?}"
        );
        assert!(
            notes.iter().any(|n| n.contains("in general conservative")),
            "{notes:?}"
        );
        // No system and no wire: only that no drop is held against a limit.
        let none = super::notes(&[], None);
        assert_eq!(none.len(), 1, "{none:?}");
        assert!(
            none[0].contains("no drop is held against a limit"),
            "{none:?}"
        );
    }

    #[test]
    fn every_circuit_of_the_file_and_the_unit_is_listed_once_in_pin_order() {
        let file = vec![LoadCircuit {
            id: 10,
            name: "Landing (file)".into(),
            amps: None,
            duty: [0.0; 7],
            wire: run("16 AWG", Some(12.0), None),
        }];
        let unit = [
            Circuit {
                id: 10,
                name: Some("Landing Lt"),
                breaker_amps: Some(15),
                amps: None,
            },
            Circuit {
                id: 4,
                name: Some("EFIS"),
                breaker_amps: Some(5),
                amps: None,
            },
        ];
        let s = system(Some(16), None).unwrap();
        let rows = assess(&file, &unit, Some(&s));
        let got: Vec<(u8, &str, &str)> = rows
            .iter()
            .map(|r| (r.id, r.name.as_str(), r.verdict.word()))
            .collect();
        assert_eq!(got, [(4, "EFIS", "not entered"), (10, "Landing Lt", "ok")]);
    }
}

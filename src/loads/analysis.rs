//! The load analysis' arithmetic. Pure: the file and the check's measurements in, the
//! figures out.
//!
//! For each circuit, the current used is the one the check **measured** if it has
//! one, else the one the builder **typed** in the file, else none (the circuit then
//! counts 0 A and every phase it is on in says its total is only a lower bound).
//!
//! - Total of a phase: `Σ current × duty`, over every circuit, where `duty` is the
//!   fraction of the time the circuit is on in that phase (1 on, 0 off).
//! - Margin of a phase on the alternator: `(rating − total) × 100 / rating` percent;
//!   under [`MARGIN_WARNING_PERCENT`] (20 %: FAA AC 43.13-1B par. 11-35a asks for a
//!   smaller load or a bigger alternator where the continuous load can pass 80 % of
//!   its rating, and calls that "strictly a rule of thumb", not a load analysis) is a
//!   warning, below zero the alternator cannot carry it.
//! - Endurance of the emergency phase, in minutes: `capacity (Ah) × usable × 60 /
//!   total (A)`. `usable` derates the rated capacity (0.8 unless the file says,
//!   the capacity a battery still passes its capacity test with). It does not model
//!   Peukert's effect: a battery discharged several times faster than its 20-hour
//!   rate gives less than its rating, which a builder allows for with a lower
//!   `battery_usable`. Under [`ENDURANCE_WARNING_MINUTES`] (30 min, the usual target
//!   for reaching a landing on the battery) is a warning.
//!
//! The alternator's rating is taken as it is written; the current the battery takes
//! back while charging, and an alternator's lower output at idle, are the builder's
//! to allow for.

use super::Phase;
use super::file::LoadFile;
use crate::protocol::device;

/// Under this share of the alternator's rating left spare, a phase gets a warning.
pub const MARGIN_WARNING_PERCENT: f64 = 20.0;
/// Under this many minutes on the battery, the emergency phase gets a warning.
pub const ENDURANCE_WARNING_MINUTES: f64 = 30.0;

/// Where a circuit's current comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Figure {
    /// Measured by the installation check.
    Measured(f64),
    /// Typed by the builder in the file, the check having none.
    Typed(f64),
    /// Neither: counted as 0 A.
    Missing,
}

impl Figure {
    pub fn amps(self) -> f64 {
        match self {
            Figure::Measured(a) | Figure::Typed(a) => a,
            Figure::Missing => 0.0,
        }
    }

    /// "measured", "typed" or "none".
    pub fn source(self) -> &'static str {
        match self {
            Figure::Measured(_) => "measured",
            Figure::Typed(_) => "typed",
            Figure::Missing => "none",
        }
    }
}

/// How a phase came out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    Ok,
    /// Margin under 20 %, endurance under 30 min, or a circuit on with no current.
    Warn,
    /// More than the alternator's rating.
    Fail,
}

/// One circuit's line of the analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub id: u8,
    pub pin: &'static str,
    pub name: String,
    /// The current used.
    pub figure: Figure,
    /// The current typed in the file, shown beside a measured one that replaced it.
    pub typed: Option<f64>,
    /// Per phase, the fraction of the time it is on.
    pub duty: [f64; 7],
}

impl Row {
    /// What it adds to `phase`'s total.
    pub fn in_phase(&self, phase: Phase) -> f64 {
        self.figure.amps() * self.duty[phase.index()]
    }

    pub fn is_on_in(&self, phase: Phase) -> bool {
        self.duty[phase.index()] > 0.0
    }
}

/// One phase's line of the analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseTotal {
    pub phase: Phase,
    /// The total current, amperes.
    pub amps: f64,
    /// On the alternator: the share of its rating left spare, percent (negative when
    /// the total is over it). `None` for the emergency phase.
    pub margin_percent: Option<f64>,
    /// On the battery: minutes until the usable capacity is spent. `None` for the
    /// other phases, and for an emergency phase with nothing on.
    pub endurance_minutes: Option<f64>,
    /// Circuits on in this phase with no current at all (ids): the total is at least
    /// `amps`.
    pub missing: Vec<u8>,
    pub level: Level,
}

/// The whole analysis, as the screen and the report show it.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    pub alternator_amps: f64,
    pub battery_amp_hours: f64,
    pub battery_usable: f64,
    /// In pin order, as the file lists them.
    pub rows: Vec<Row>,
    /// Every phase, in [`Phase::ALL`] order.
    pub phases: Vec<PhaseTotal>,
    /// Circuits the check measured that the file does not list: in no phase, so not
    /// counted. Id and amperes.
    pub unlisted: Vec<(u8, f64)>,
}

/// The analysis of `file` with the check's `measured` currents (device id, amperes),
/// which replace the typed ones.
pub fn analyse(file: &LoadFile, measured: &[(u8, f32)]) -> Analysis {
    let measured_amps = |id: u8| -> Option<f64> {
        measured
            .iter()
            .rev()
            .find(|m| m.0 == id)
            .map(|m| decimal(m.1))
    };
    let rows: Vec<Row> = file
        .circuits
        .iter()
        .map(|c| Row {
            id: c.id,
            pin: c.pin(),
            name: c.name.clone(),
            figure: match (measured_amps(c.id), c.amps) {
                (Some(m), _) => Figure::Measured(m),
                (None, Some(t)) => Figure::Typed(t),
                (None, None) => Figure::Missing,
            },
            typed: c.amps,
            duty: c.duty,
        })
        .collect();
    let phases = Phase::ALL
        .into_iter()
        .map(|phase| phase_total(file, &rows, phase))
        .collect();
    let mut unlisted: Vec<(u8, f64)> = Vec::new();
    for &(id, amps) in measured {
        if !file.circuits.iter().any(|c| c.id == id) {
            unlisted.retain(|u| u.0 != id);
            unlisted.push((id, decimal(amps)));
        }
    }
    unlisted.sort_by_key(|u| u.0);
    Analysis {
        alternator_amps: file.alternator_amps,
        battery_amp_hours: file.battery_amp_hours,
        battery_usable: file.battery_usable,
        rows,
        phases,
        unlisted,
    }
}

/// A measured `f32` as the decimal it stands for (4.8, not 4.800000190734863).
fn decimal(a: f32) -> f64 {
    a.to_string().parse().unwrap_or(f64::from(a))
}

/// Totals, margins and minutes are kept to a millionth, so that binary fractions
/// never turn a margin of 12 % into 11.999… (and its "under 20 %" into a false one).
fn micro(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

fn phase_total(file: &LoadFile, rows: &[Row], phase: Phase) -> PhaseTotal {
    let amps = micro(rows.iter().map(|r| r.in_phase(phase)).sum());
    let missing: Vec<u8> = rows
        .iter()
        .filter(|r| r.is_on_in(phase) && r.figure == Figure::Missing)
        .map(|r| r.id)
        .collect();
    let (margin_percent, endurance_minutes, mut level) = if phase.on_battery() {
        let endurance =
            (amps > 0.0).then(|| micro(file.battery_amp_hours * file.battery_usable * 60.0 / amps));
        let level = match endurance {
            Some(m) if m < ENDURANCE_WARNING_MINUTES => Level::Warn,
            _ => Level::Ok,
        };
        (None, endurance, level)
    } else {
        let margin = micro((file.alternator_amps - amps) * 100.0 / file.alternator_amps);
        let level = if margin < 0.0 {
            Level::Fail
        } else if margin < MARGIN_WARNING_PERCENT {
            Level::Warn
        } else {
            Level::Ok
        };
        (Some(margin), None, level)
    };
    if !missing.is_empty() {
        level = level.max(Level::Warn);
    }
    PhaseTotal {
        phase,
        amps,
        margin_percent,
        endurance_minutes,
        missing,
        level,
    }
}

impl Analysis {
    /// The usable capacity in ampere-hours: rated × usable.
    pub fn usable_amp_hours(&self) -> f64 {
        self.battery_amp_hours * self.battery_usable
    }

    pub fn phase(&self, phase: Phase) -> &PhaseTotal {
        &self.phases[phase.index()]
    }

    fn name_of(&self, id: u8) -> String {
        self.rows
            .iter()
            .find(|r| r.id == id)
            .map(|r| r.name.clone())
            .unwrap_or_else(|| device::device(id).map_or("?", |d| d.system_name).into())
    }

    /// A phase's verdict in words, never by colour alone: "margin 42 % of 40 A",
    /// "margin 12 % of 40 A: under 20 %", "4.5 A over the alternator's 40 A",
    /// "endurance 55 min", "endurance 20 min: under 30 min"; with, when a circuit on
    /// in it has no current, "at least: no current for Landing Lt".
    pub fn verdict(&self, phase: Phase) -> String {
        let mut words = self.figures_verdict(phase);
        let p = self.phase(phase);
        if !p.missing.is_empty() {
            words.push_str(&format!(
                "; at least: no current for {}",
                self.names(&p.missing)
            ));
        }
        words
    }

    fn names(&self, ids: &[u8]) -> String {
        let names: Vec<String> = ids.iter().map(|&id| self.name_of(id)).collect();
        names.join(", ")
    }

    /// [`Analysis::verdict`] of the figures alone, without the circuits missing.
    fn figures_verdict(&self, phase: Phase) -> String {
        let p = self.phase(phase);
        match (p.margin_percent, p.endurance_minutes) {
            (Some(m), _) if m < 0.0 => format!(
                "{} A over the alternator's {} A",
                amps_text(p.amps - self.alternator_amps),
                amps_text(self.alternator_amps)
            ),
            (Some(m), _) if m < MARGIN_WARNING_PERCENT => format!(
                "margin {} % of {} A: under {MARGIN_WARNING_PERCENT} %",
                percent_text(m),
                amps_text(self.alternator_amps)
            ),
            (Some(m), _) => format!(
                "margin {} % of {} A",
                percent_text(m),
                amps_text(self.alternator_amps)
            ),
            (None, Some(min)) if min < ENDURANCE_WARNING_MINUTES => format!(
                "endurance {} min: under {ENDURANCE_WARNING_MINUTES} min",
                minutes_text(min)
            ),
            (None, Some(min)) => format!("endurance {} min", minutes_text(min)),
            (None, None) => "nothing on: no load on the battery".into(),
        }
    }

    /// Everything the builder should look at, one line each, for the list of what is
    /// left to fix: [`Analysis::phase_warnings`], then [`Analysis::file_warnings`].
    pub fn warnings(&self) -> Vec<String> {
        let mut out = self.phase_warnings();
        out.extend(self.file_warnings());
        out
    }

    /// Each phase whose figures are not OK (a margin or an endurance under its rule,
    /// a total over the alternator), with its verdict of the figures. A phase that
    /// is only a lower bound is not one of them: the circuits it misses are said once,
    /// in [`Analysis::file_warnings`], not once a phase (a template straight from the
    /// check lists every circuit in every phase).
    pub fn phase_warnings(&self) -> Vec<String> {
        self.phases
            .iter()
            .filter(|p| {
                p.margin_percent.is_some_and(|m| m < MARGIN_WARNING_PERCENT)
                    || p.endurance_minutes
                        .is_some_and(|m| m < ENDURANCE_WARNING_MINUTES)
            })
            .map(|p| format!("{}: {}", p.phase.title(), self.figures_verdict(p.phase)))
            .collect()
    }

    /// What the load file leaves out: the circuits on in some phase with no current
    /// at all (not measured, none typed), all in one line; and each circuit measured
    /// but not in the file.
    pub fn file_warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        let missing: Vec<u8> = self
            .rows
            .iter()
            .map(|r| r.id)
            .filter(|id| self.phases.iter().any(|p| p.missing.contains(id)))
            .collect();
        if !missing.is_empty() {
            out.push(format!(
                "no current for {}: not measured, and no amps in the load file, so every \
                 phase they are on in counts them as 0 A (its total is at least what it \
                 says); type their amps in the file",
                self.names(&missing)
            ));
        }
        for &(id, amps) in &self.unlisted {
            out.push(format!(
                "the {} pin draws {} A but is not in the load file: it is in no phase",
                device::device(id).map_or("?", |d| d.system_name),
                amps_text(amps)
            ));
        }
        out
    }

    /// The worst level of any phase.
    pub fn level(&self) -> Level {
        let unlisted = if self.unlisted.is_empty() {
            Level::Ok
        } else {
            Level::Warn
        };
        self.phases
            .iter()
            .map(|p| p.level)
            .fold(unlisted, Level::max)
    }
}

/// Amperes to a tenth, as the page shows them: "7.5", "40".
pub fn amps_text(a: f64) -> String {
    let t = format!("{:.1}", a);
    t.strip_suffix(".0").map(str::to_string).unwrap_or(t)
}

/// A margin to the whole percent, rounded down so a warning never reads as "20 %".
pub fn percent_text(p: f64) -> String {
    format!("{}", p.floor() as i64)
}

/// Endurance to the whole minute, rounded down: the battery gives no more than this.
pub fn minutes_text(m: f64) -> String {
    format!("{}", m.floor() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loads::file::LoadCircuit;
    use crate::protocol::device::{EFIS, FIELD_PRI, FLAPS, TRIM_P};

    const NAV: u8 = 0x04; // 5A-1
    const COM: u8 = 0x05; // 5A-2
    const LANDING: u8 = 0x11; // 10A-1
    const PITOT: u8 = 0x17; // 15A-1

    fn c(id: u8, name: &str, amps: Option<f64>, duty: [f64; 7]) -> LoadCircuit {
        LoadCircuit {
            id,
            name: name.into(),
            amps,
            duty,
            wire: Default::default(),
        }
    }

    /// A small aircraft, worked by hand below.
    ///
    /// | circuit    | current           | gnd | taxi | t/o | day | night | ldg | emer |
    /// |------------|-------------------|-----|------|-----|-----|-------|-----|------|
    /// | EFIS       | 2.5 measured (3.0 typed, not used) | 1 | 1 | 1 | 1 | 1 | 1 | 1 |
    /// | Field_Pri  | 3.0 typed         | 1   | 1    | 1   | 1   | 1     | 1   | 0    |
    /// | Nav 5A-1   | 1.5 measured      | 0   | 0    | 0   | 0   | 1     | 1   | 1    |
    /// | Landing    | 7.5 typed         | 0   | 1    | 1   | 0   | 0     | 1   | 0    |
    /// | Pitot      | 12.0 typed        | 0   | 0    | 1   | 1   | 1     | 1   | 0    |
    /// | Trim_P     | 1.0 typed         | 0   | 0.1  | 0.1 | 0.1 | 0.1   | 0.1 | 0.1  |
    fn aircraft() -> (LoadFile, Vec<(u8, f32)>) {
        let file = LoadFile {
            alternator_amps: 32.0,
            battery_amp_hours: 17.0,
            battery_usable: 0.8,
            circuits: vec![
                c(EFIS, "EFIS", Some(3.0), [1.0; 7]),
                c(
                    FIELD_PRI,
                    "Alternator field",
                    Some(3.0),
                    [1., 1., 1., 1., 1., 1., 0.],
                ),
                c(NAV, "Nav lights", None, [0., 0., 0., 0., 1., 1., 1.]),
                c(
                    LANDING,
                    "Landing light",
                    Some(7.5),
                    [0., 1., 1., 0., 0., 1., 0.],
                ),
                c(
                    PITOT,
                    "Pitot heat",
                    Some(12.0),
                    [0., 0., 1., 1., 1., 1., 0.],
                ),
                c(
                    TRIM_P,
                    "Pitch trim",
                    Some(1.0),
                    [0., 0.1, 0.1, 0.1, 0.1, 0.1, 0.1],
                ),
            ],
        };
        (file, vec![(EFIS, 2.5), (NAV, 1.5)])
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn totals_margins_and_endurance_of_a_hand_worked_aircraft() {
        let (file, measured) = aircraft();
        let a = analyse(&file, &measured);
        // Measured replaces typed; typed is used where nothing was measured.
        assert_eq!(a.rows[0].figure, Figure::Measured(2.5));
        assert_eq!(a.rows[0].typed, Some(3.0));
        assert_eq!(a.rows[1].figure, Figure::Typed(3.0));
        assert_eq!(a.rows[2].figure, Figure::Measured(1.5));

        // By hand, alternator 32 A:
        // ground   2.5 + 3.0                                  =  5.5 A, (32 −  5.5)·100/32 = 82.8125 %
        // taxi     2.5 + 3.0 + 7.5 + 0.1·1.0                  = 13.1 A, (32 − 13.1)·100/32 = 59.0625 %
        // take-off 2.5 + 3.0 + 7.5 + 12.0 + 0.1               = 25.1 A, (32 − 25.1)·100/32 = 21.5625 %
        // day      2.5 + 3.0 + 12.0 + 0.1                     = 17.6 A, 45 %
        // night    2.5 + 3.0 + 1.5 + 12.0 + 0.1               = 19.1 A, 40.3125 %
        // landing  2.5 + 3.0 + 1.5 + 7.5 + 12.0 + 0.1         = 26.6 A, 16.875 %  → warning
        let expect = [
            (Phase::Ground, 5.5, 82.8125),
            (Phase::Taxi, 13.1, 59.0625),
            (Phase::TakeOff, 25.1, 21.5625),
            (Phase::CruiseDay, 17.6, 45.0),
            (Phase::CruiseNight, 19.1, 40.3125),
            (Phase::Landing, 26.6, 16.875),
        ];
        for (phase, amps, margin) in expect {
            let p = a.phase(phase);
            assert!(close(p.amps, amps), "{phase:?}: {} A", p.amps);
            assert!(
                close(p.margin_percent.unwrap(), margin),
                "{phase:?}: {:?}",
                p.margin_percent
            );
            assert_eq!(p.endurance_minutes, None);
            let want = if phase == Phase::Landing {
                Level::Warn
            } else {
                Level::Ok
            };
            assert_eq!(p.level, want, "{phase:?}");
        }
        // Emergency, battery only: EFIS 2.5 + Nav 1.5 + trim 0.1 = 4.1 A.
        // 17 Ah × 0.8 = 13.6 Ah usable; 13.6 / 4.1 = 3.3171 h = 199.02 min.
        let e = a.phase(Phase::Emergency);
        assert!(close(e.amps, 4.1), "{}", e.amps);
        assert_eq!(e.margin_percent, None);
        assert!((e.endurance_minutes.unwrap() - 13.6 / 4.1 * 60.0).abs() < 1e-6);
        assert!((e.endurance_minutes.unwrap() - 199.02).abs() < 0.01);
        assert_eq!(e.level, Level::Ok);

        assert_eq!(a.verdict(Phase::Ground), "margin 82 % of 32 A");
        assert_eq!(a.verdict(Phase::Landing), "margin 16 % of 32 A: under 20 %");
        assert_eq!(a.verdict(Phase::Emergency), "endurance 199 min");
        assert_eq!(a.warnings(), ["landing: margin 16 % of 32 A: under 20 %"]);
        assert_eq!(a.level(), Level::Warn);
        assert!(close(a.usable_amp_hours(), 13.6));
    }

    #[test]
    fn twenty_percent_left_is_no_warning_and_less_is() {
        // Alternator 10 A. 8 A leaves (10 − 8)·100/10 = 20 %: just enough.
        let file = |amps| LoadFile {
            alternator_amps: 10.0,
            battery_amp_hours: 10.0,
            battery_usable: 1.0,
            circuits: vec![c(LANDING, "Load", Some(amps), [1., 0., 0., 0., 0., 0., 0.])],
        };
        for (typed, measured, margin, level) in [
            (8.0, None, 20.0, Level::Ok),
            // 8.5 A leaves 15 %.
            (8.5, None, 15.0, Level::Warn),
            // Measured 10.5 A (the typed 8 is replaced) is 0.5 A over: −5 %.
            (8.0, Some(10.5), -5.0, Level::Fail),
        ] {
            let measured: Vec<(u8, f32)> = measured.map(|m| (LANDING, m)).into_iter().collect();
            let a = analyse(&file(typed), &measured);
            let g = a.phase(Phase::Ground);
            let got = (g.margin_percent, g.level);
            assert_eq!(
                got,
                (Some(margin), level),
                "{typed} A, measured {measured:?}"
            );
        }
        let a = analyse(&file(8.0), &[(LANDING, 10.5)]);
        assert_eq!(a.verdict(Phase::Ground), "0.5 A over the alternator's 10 A");
        assert_eq!(a.level(), Level::Fail);
        // An empty phase has its whole rating spare.
        assert_eq!(a.phase(Phase::Taxi).margin_percent, Some(100.0));
    }

    #[test]
    fn thirty_minutes_on_the_battery_is_no_warning_and_less_is() {
        // 10 Ah × 0.5 usable = 5 Ah. At 10 A: 5 / 10 h = 0.5 h = 30 min.
        let file = |amps| LoadFile {
            alternator_amps: 60.0,
            battery_amp_hours: 10.0,
            battery_usable: 0.5,
            circuits: vec![c(LANDING, "Load", Some(amps), [0., 0., 0., 0., 0., 0., 1.])],
        };
        // At 12 A: 5 / 12 h = 25 min. Nothing on: no endurance to give, nothing drawn.
        for (amps, endurance, level, verdict) in [
            (10.0, Some(30.0), Level::Ok, "endurance 30 min"),
            (
                12.0,
                Some(25.0),
                Level::Warn,
                "endurance 25 min: under 30 min",
            ),
            (0.0, None, Level::Ok, "nothing on: no load on the battery"),
        ] {
            let a = analyse(&file(amps), &[]);
            let e = a.phase(Phase::Emergency);
            let got = (e.endurance_minutes, e.level, a.verdict(Phase::Emergency));
            assert_eq!(got, (endurance, level, verdict.to_string()), "{amps} A");
        }
    }

    #[test]
    fn a_circuit_with_no_current_makes_its_phases_a_lower_bound() {
        let file = LoadFile {
            alternator_amps: 40.0,
            battery_amp_hours: 17.0,
            battery_usable: 0.8,
            circuits: vec![
                c(EFIS, "EFIS", Some(2.0), [1.0; 7]),
                c(COM, "Com radio", None, [0., 1., 1., 1., 1., 1., 1.]),
            ],
        };
        let a = analyse(&file, &[(PITOT, 9.0)]);
        let g = a.phase(Phase::Ground);
        assert!(g.missing.is_empty());
        assert_eq!(g.level, Level::Ok);
        let t = a.phase(Phase::Taxi);
        assert_eq!(t.missing, [COM]);
        assert_eq!(t.amps, 2.0);
        assert_eq!(t.level, Level::Warn);
        // (40 − 2)·100/40 = 95 %; 13.6 Ah / 2 A = 6.8 h = 408 min.
        assert_eq!(
            a.verdict(Phase::Taxi),
            "margin 95 % of 40 A; at least: no current for Com radio"
        );
        assert_eq!(
            a.verdict(Phase::Emergency),
            "endurance 408 min; at least: no current for Com radio"
        );
        // The pitot heat was measured but the file leaves it out of every phase.
        assert_eq!(a.unlisted, [(PITOT, 9.0)]);
        // Said once for all six phases it is on in, not once a phase; no phase's
        // figures warn (95 %, 408 min).
        assert_eq!(
            a.warnings(),
            [
                "no current for Com radio: not measured, and no amps in the load file, so \
                 every phase they are on in counts them as 0 A (its total is at least what \
                 it says); type their amps in the file",
                "the 15A-1 pin draws 9 A but is not in the load file: it is in no phase"
            ]
        );
    }

    /// A phase whose figures warn is listed with them alone; the circuits with no
    /// current, whichever phases they are on in, are one line, in pin order.
    #[test]
    fn phases_warn_by_their_figures_and_missing_circuits_are_said_once() {
        let file = LoadFile {
            alternator_amps: 20.0,
            battery_amp_hours: 17.0,
            battery_usable: 0.8,
            // In pin order, as the file keeps them.
            circuits: vec![
                c(FLAPS, "Flaps", None, [0., 0., 0., 0., 0., 1., 0.]),
                c(EFIS, "EFIS", Some(2.0), [1.0; 7]),
                c(COM, "Com radio", None, [1.0; 7]),
                // 15 A in landing only: (20 − 2 − 15)·100/20 = 15 %.
                c(
                    LANDING,
                    "Landing Lt",
                    Some(15.0),
                    [0., 0., 0., 0., 0., 1., 0.],
                ),
            ],
        };
        let a = analyse(&file, &[]);
        assert_eq!(
            a.verdict(Phase::Landing),
            "margin 15 % of 20 A: under 20 %; at least: no current for Flaps, Com radio"
        );
        assert_eq!(
            a.phase_warnings(),
            ["landing: margin 15 % of 20 A: under 20 %"]
        );
        let w = a.file_warnings();
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with("no current for Flaps, Com radio: "),
            "{w:?}"
        );
        assert_eq!(a.warnings().len(), 2);
    }

    #[test]
    fn binary_fractions_do_not_move_a_margin_across_a_whole_percent() {
        // 2.5 + 3 + 12 + 0.1 = 17.6 A of 20 A: (20 − 17.6)·100/20 = 12 %, which the
        // floating-point sum makes 11.99999999999999 unless it is rounded.
        let file = LoadFile {
            alternator_amps: 20.0,
            battery_amp_hours: 10.0,
            battery_usable: 0.8,
            circuits: vec![
                c(EFIS, "EFIS", None, [1.0; 7]),
                c(FIELD_PRI, "Field", Some(3.0), [1.0; 7]),
                c(PITOT, "Pitot", Some(12.0), [1.0; 7]),
                c(TRIM_P, "Trim", Some(1.0), [0.1; 7]),
            ],
        };
        // The measured 4.8 A of an f32 is 4.800000190734863 as it stands.
        let a = analyse(&file, &[(EFIS, 2.5), (NAV, 4.8)]);
        assert_eq!(a.phase(Phase::Ground).amps, 17.6);
        assert_eq!(a.phase(Phase::Ground).margin_percent, Some(12.0));
        assert_eq!(a.verdict(Phase::Ground), "margin 12 % of 20 A: under 20 %");
        assert_eq!(a.unlisted, [(NAV, 4.8)]);
    }

    #[test]
    fn figures_are_written_as_the_page_writes_them() {
        assert_eq!(amps_text(40.0), "40");
        assert_eq!(amps_text(7.54), "7.5");
        assert_eq!(amps_text(0.05), "0.1");
        assert_eq!(percent_text(19.99), "19");
        assert_eq!(minutes_text(29.9), "29");
    }
}

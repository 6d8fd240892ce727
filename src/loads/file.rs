//! The load-analysis file: TOML the builder edits by hand.
//!
//! ```toml
//! alternator_amps = 40        # the alternator's rated output, A
//! battery_amp_hours = 17      # the battery's rated capacity, Ah (its 20-hour rate)
//! battery_usable = 0.8        # the fraction of it counted on (optional, 0.8)
//!
//! [circuit.5A-7]              # one VP-X output, by its pin (ICD Appendix B)
//! name = "Landing Lt"         # what it feeds (optional; the pin if absent)
//! amps = 7.5                  # its current if the check cannot measure it (optional)
//! ground = false              # on in that phase: true, false, or the fraction of the
//! taxi = true                 #   time it is on (0.1 for trim: a tenth of the time)
//! take_off = true
//! cruise_day = false
//! cruise_night = false
//! landing = true
//! emergency = false           # on the battery alone, the alternator failed
//! wire = "16 AWG"             # its wire: an AWG gauge, or "1.0 mm2" (optional)
//! wire_length = "12 ft"       # from the VP-X pin to the load, ft or m (optional)
//! return_length = "4 ft"      # the load's ground back to a ground block (optional;
//!                             #   absent: grounded at the load)
//! ```
//!
//! A phase a circuit does not mention is off in it. Every problem is named with its
//! line and field, so the builder can go straight to it. The circuits are kept in
//! pin order, whatever order the file lists them in.

use std::collections::BTreeMap;
use std::fmt::Write;

use serde::Deserialize;
use toml::Spanned;

use crate::toml_lines::{self, Problem, Value};

use super::wire::{self, Wire};
use super::wiring::WireRun;
use super::{Phase, guess};
use crate::model::Circuit;
use crate::protocol::device;

/// Without a figure in the file, the share of the battery's rated capacity counted
/// on in an emergency: 80 %, the capacity below which a battery is due for
/// replacement (the usual capacity-test limit for aircraft batteries), so the
/// endurance holds for a battery on the last day it would still pass.
pub const DEFAULT_BATTERY_USABLE: f64 = 0.8;

/// One circuit's line in the file.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadCircuit {
    /// The device id of its pin (Appendix B).
    pub id: u8,
    pub name: String,
    /// The current the builder typed, used when the check did not measure one.
    pub amps: Option<f64>,
    /// Per phase (indexed by [`Phase::index`]), the fraction of the time it is on:
    /// 1 for on, 0 for off.
    pub duty: [f64; 7],
    /// Its wire, held against its breaker and its current ([`super::wiring`]).
    pub wire: WireRun,
}

impl LoadCircuit {
    /// The Appendix B system name of its pin.
    pub fn pin(&self) -> &'static str {
        device::device(self.id).map_or("?", |d| d.system_name)
    }

    pub fn duty(&self, phase: Phase) -> f64 {
        self.duty[phase.index()]
    }
}

/// The whole file, read.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadFile {
    pub alternator_amps: f64,
    pub battery_amp_hours: f64,
    /// The fraction of `battery_amp_hours` counted on in an emergency, 0 < x ≤ 1.
    pub battery_usable: f64,
    /// In pin order.
    pub circuits: Vec<LoadCircuit>,
}

#[derive(Deserialize)]
struct Raw {
    alternator_amps: Option<Value>,
    battery_amp_hours: Option<Value>,
    battery_usable: Option<Value>,
    #[serde(default)]
    circuit: BTreeMap<Spanned<String>, RawCircuit>,
}

/// The file's own keys, beside the `[circuit.PIN]` sections.
const RATINGS: [&str; 3] = ["alternator_amps", "battery_amp_hours", "battery_usable"];
/// A circuit's keys but its phases.
const CIRCUIT_KEYS: [&str; 5] = ["name", "amps", "wire", "wire_length", "return_length"];

#[derive(Deserialize)]
struct RawCircuit {
    name: Option<Value>,
    amps: Option<Value>,
    ground: Option<Value>,
    taxi: Option<Value>,
    take_off: Option<Value>,
    cruise_day: Option<Value>,
    cruise_night: Option<Value>,
    landing: Option<Value>,
    emergency: Option<Value>,
    wire: Option<Value>,
    wire_length: Option<Value>,
    return_length: Option<Value>,
}

impl RawCircuit {
    fn phases(&self) -> [(Phase, Option<&Value>); 7] {
        [
            (Phase::Ground, self.ground.as_ref()),
            (Phase::Taxi, self.taxi.as_ref()),
            (Phase::TakeOff, self.take_off.as_ref()),
            (Phase::CruiseDay, self.cruise_day.as_ref()),
            (Phase::CruiseNight, self.cruise_night.as_ref()),
            (Phase::Landing, self.landing.as_ref()),
            (Phase::Emergency, self.emergency.as_ref()),
        ]
    }
}

/// Reads the file's text, listing every problem, each with its line and field
/// ([`toml_lines`]).
pub fn parse(text: &str) -> Result<LoadFile, Vec<Problem>> {
    let raw: Raw = toml_lines::parse(text).map_err(|p| vec![p])?;
    let mut problems = unknown_keys(text);
    let at = |v: &Value| Some(toml_lines::line(text, v));

    let mut required = |key: &str, v: Option<Value>, what: &str| match v {
        None => {
            problems.push(Problem::new(
                None,
                key,
                format!("missing: write {key} = {what}"),
            ));
            None
        }
        Some(v) => match number(&v) {
            Ok(n) if n > 0.0 => Some(n),
            Ok(n) => {
                problems.push(Problem::new(
                    at(&v),
                    key,
                    format!("{n} must be more than 0 ({what})"),
                ));
                None
            }
            Err(why) => {
                problems.push(Problem::new(at(&v), key, why));
                None
            }
        },
    };
    let alternator_amps = required(
        "alternator_amps",
        raw.alternator_amps,
        "the alternator's rated output in amperes",
    );
    let battery_amp_hours = required(
        "battery_amp_hours",
        raw.battery_amp_hours,
        "the battery's rated capacity in ampere-hours",
    );
    let battery_usable = match raw.battery_usable {
        None => Some(DEFAULT_BATTERY_USABLE),
        Some(v) => match number(&v) {
            Ok(n) if n > 0.0 && n <= 1.0 => Some(n),
            Ok(n) => {
                problems.push(Problem::new(
                    at(&v),
                    "battery_usable",
                    format!(
                        "{n} is no share of the battery; write a number more than 0 and at \
                         most 1 (0.8 for 80 %)"
                    ),
                ));
                None
            }
            Err(why) => {
                problems.push(Problem::new(at(&v), "battery_usable", why));
                None
            }
        },
    };
    let circuits = read_circuits(text, raw.circuit, &mut problems);
    match (alternator_amps, battery_amp_hours, battery_usable) {
        (Some(alternator_amps), Some(battery_amp_hours), Some(battery_usable))
            if problems.is_empty() =>
        {
            Ok(LoadFile {
                alternator_amps,
                battery_amp_hours,
                battery_usable,
                circuits,
            })
        }
        _ => Err(in_line_order(problems)),
    }
}

/// Reads only the circuits, not the ratings: for `vpx-efis wires`, which needs the
/// wires and not the alternator or the battery, so a file still without its ratings
/// (the template as written) is read for its wires.
pub fn parse_circuits(text: &str) -> Result<Vec<LoadCircuit>, Vec<Problem>> {
    let raw: Raw = toml_lines::parse(text).map_err(|p| vec![p])?;
    let mut problems = unknown_keys(text);
    let circuits = read_circuits(text, raw.circuit, &mut problems);
    if problems.is_empty() {
        Ok(circuits)
    } else {
        Err(in_line_order(problems))
    }
}

/// A missing key (no line) first, then the rest as the file has them.
fn in_line_order(mut problems: Vec<Problem>) -> Vec<Problem> {
    problems.sort_by_key(|p| p.line);
    problems
}

/// Every key the file does not have, with what it has instead.
fn unknown_keys(text: &str) -> Vec<Problem> {
    let phases: Vec<&str> = Phase::ALL.iter().map(|p| p.key()).collect();
    let circuit_key = |k: &str| CIRCUIT_KEYS.contains(&k) || phases.contains(&k);
    toml_lines::Keys::of(text)
        .unknown(|p| match p {
            [k] => RATINGS.contains(&k.as_str()) || k == "circuit",
            [c, _] => c == "circuit",
            [c, _, k] => c == "circuit" && circuit_key(k),
            _ => false,
        })
        .into_iter()
        .map(|(path, line)| match &path[..] {
            [c, pin, k] if c == "circuit" => Problem::new(
                Some(line),
                format!("[circuit.{pin}] {k}"),
                format!(
                    "unknown key; a circuit's keys are name, amps, {}, wire, wire_length \
                     and return_length",
                    phases.join(", ")
                ),
            ),
            _ => Problem::new(
                Some(line),
                path.join("."),
                "unknown key; the file's keys are alternator_amps, battery_amp_hours, \
                 battery_usable and [circuit.PIN] sections",
            ),
        })
        .collect()
}

/// Every `[circuit.PIN]` section that reads, in pin order; what does not read is in
/// `problems`.
fn read_circuits(
    text: &str,
    raw: BTreeMap<Spanned<String>, RawCircuit>,
    problems: &mut Vec<Problem>,
) -> Vec<LoadCircuit> {
    let at = |v: &Value| Some(toml_lines::line(text, v));
    let mut circuits: Vec<(LoadCircuit, usize)> = Vec::new();
    for (key, rc) in raw {
        let key_line = toml_lines::line(text, &key);
        let key = key.into_inner();
        let Some(dev) = device::DEVICES
            .iter()
            .find(|d| d.system_name.eq_ignore_ascii_case(&key))
        else {
            problems.push(Problem::new(
                Some(key_line),
                format!("[circuit.{key}]"),
                format!(
                    "{key:?} is no pin of the VP-X; the pins are {}",
                    device::DEVICES
                        .iter()
                        .map(|d| d.system_name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
            continue;
        };
        if let Some((_, first)) = circuits.iter().find(|(c, _)| c.id == dev.id) {
            problems.push(Problem::new(
                Some(key_line),
                format!("[circuit.{key}]"),
                format!("{} is listed twice, first on line {first}", dev.system_name),
            ));
            continue;
        }
        let before = problems.len();
        let field = |f: &str| format!("[circuit.{}] {f}", dev.system_name);
        let mut bad = |v: &Value, f: &str, why: String| {
            problems.push(Problem::new(at(v), field(f), why));
        };
        let name = match &rc.name {
            None => dev.system_name.to_string(),
            Some(v) => match v.get_ref() {
                toml::Value::String(s) => s.clone(),
                other => {
                    bad(
                        v,
                        "name",
                        format!(
                            "{} where text in quotes was expected",
                            toml_lines::kind(other)
                        ),
                    );
                    String::new()
                }
            },
        };
        let amps = rc.amps.as_ref().and_then(|v| match number(v) {
            Err(why) => {
                bad(v, "amps", why);
                None
            }
            Ok(n) if n < 0.0 => {
                bad(
                    v,
                    "amps",
                    format!("{n} A is below zero; write the current the circuit draws"),
                );
                None
            }
            Ok(n) if n > f64::from(dev.amps_max) => {
                bad(
                    v,
                    "amps",
                    format!(
                        "{n} A is more than the {} pin can carry ({} A at most, ICD \
                         Appendix B)",
                        dev.system_name, dev.amps_max
                    ),
                );
                None
            }
            Ok(n) => Some(n),
        });
        let mut duty = [0.0; 7];
        for (phase, v) in rc.phases() {
            let Some(v) = v else { continue };
            match fraction(v) {
                Ok(d) => duty[phase.index()] = d,
                Err(why) => bad(v, phase.key(), why),
            }
        }
        let text_of = |v: &Value| match v.get_ref() {
            toml::Value::String(s) => Ok(s.clone()),
            other => Err(format!(
                "{} where text in quotes was expected (\"16 AWG\", \"12 ft\")",
                toml_lines::kind(other)
            )),
        };
        let gauge = rc.wire.as_ref().and_then(|v| {
            let got = text_of(v).and_then(|t| Wire::parse(&t));
            got.map_err(|why| bad(v, "wire", why)).ok()
        });
        let mut length = |key: &str, v: &Option<Value>| {
            let v = v.as_ref()?;
            let got = text_of(v).and_then(|t| wire::parse_length(&t));
            got.map_err(|why| bad(v, key, why)).ok()
        };
        let wire = WireRun {
            wire: gauge,
            feed_feet: length("wire_length", &rc.wire_length),
            return_feet: length("return_length", &rc.return_length),
        };
        if problems.len() == before {
            circuits.push((
                LoadCircuit {
                    id: dev.id,
                    name,
                    amps,
                    duty,
                    wire,
                },
                key_line,
            ));
        }
    }
    let mut circuits: Vec<LoadCircuit> = circuits.into_iter().map(|(c, _)| c).collect();
    circuits.sort_by_key(|c| c.id);
    circuits
}

/// A number, whole or decimal.
fn number(v: &Value) -> Result<f64, String> {
    match v.get_ref() {
        toml::Value::Integer(i) => Ok(*i as f64),
        toml::Value::Float(f) if f.is_finite() => Ok(*f),
        toml::Value::Float(f) => Err(format!("{f} is no number")),
        other => Err(format!(
            "{} where a number was expected",
            toml_lines::kind(other)
        )),
    }
}

/// A phase's value: on, off, or the fraction of the time the circuit is on.
fn fraction(v: &Value) -> Result<f64, String> {
    let why = |shown: String| {
        format!(
            "{shown} is not on, off or a fraction of the time; write true, false, or a \
             number from 0 to 1 (0.25 for a quarter of the time)"
        )
    };
    match v.get_ref() {
        toml::Value::Boolean(b) => Ok(if *b { 1.0 } else { 0.0 }),
        toml::Value::Integer(i) if (0..=1).contains(i) => Ok(*i as f64),
        toml::Value::Float(f) if (0.0..=1.0).contains(f) => Ok(*f),
        toml::Value::Integer(i) => Err(why(i.to_string())),
        toml::Value::Float(f) => Err(why(f.to_string())),
        other => Err(why(toml_lines::kind(other).to_string())),
    }
}

/// What the template says on top: how to fill the file in.
const HEADER: &str = "\
# vpx-efis electrical load analysis
#
# The installation check reads this file each time it runs; vpx-efis never writes
# over it. Every current the check measures is used instead of a typed one.
#
# alternator_amps    the alternator's rated output, in amperes
# battery_amp_hours  the battery's rated capacity, in ampere-hours (its 20-hour rate)
# battery_usable     the share of that capacity counted on in an emergency, 0 to 1;
#                    0.8 if absent: a battery is due for replacement below 80 %
#
# Each [circuit.PIN] is one output of the VP-X, by its pin (ICD Appendix B):
#   name      what it feeds
#   amps      the current it draws, in amperes, if the check cannot measure it
#   ground, taxi, take_off, cruise_day, cruise_night, landing, emergency
#             whether it is on in that phase: true or false, or the fraction of the
#             time it is on (0.1 for a trim motor: a tenth of the time)
#   wire           its wire: \"22 AWG\" (a gauge of AC 43.13-1B), or metric, \"1.0 mm2\"
#   wire_length    from the VP-X pin to the load: \"12 ft\" or \"3.6 m\"
#   return_length  the load's ground wire back to a ground block, where it has one;
#                  absent, it is taken as grounded at the load
#             `vpx-efis wires` holds each breaker against its wire (AC 43.13-1B
#             Table 11-3) and each current against its voltage drop (Table 11-6).
# A phase a circuit does not mention is off in it. The emergency phase runs on the
# battery alone: the alternator has failed, and its field is off.
";

/// What the template adds: where it starts from.
const TEMPLATE_NOTE: &str = "\
#
# This is a template. Each circuit's phases are guessed from its name (a landing light
# on to taxi, take off and land; nav lights at night; strobes and beacons from taxi
# on; pitot heat off; flaps and trims a tenth of the time; on the battery, the
# avionics and one light) and every guessed line says \"# guess: check\". The starter
# draws only while cranking, an alternator field not on the battery. Correct each
# guess, type a current for each circuit the check cannot measure, and write the
# alternator's rating and the battery's capacity below (without the #).
";

/// A number as TOML reads it back, exactly: Rust's shortest form ("40", "2.25"),
/// except where that form is an integer TOML cannot hold. Past 2^63 "{}" writes all
/// the digits of a whole number ("10000000000000000000"), which TOML takes for an
/// integer and refuses; there (from 2^53 on, where f64 has no fractions left) the
/// exponent form ("1e19") is a TOML float that reads back as the same f64.
fn number_text(v: f64) -> String {
    if !v.is_finite() {
        // Refused by `parse` anyway; written as TOML spells them, not as Rust does.
        return if v.is_nan() {
            "nan".into()
        } else if v > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let text = format!("{v}");
    if text.contains(['.', 'e']) || v.abs() < 9_007_199_254_740_992.0 {
        text
    } else {
        format!("{v:e}")
    }
}

/// The file's text for `file`, commented as the template is: what
/// [`parse`] reads back as the same file.
pub fn to_toml(file: &LoadFile) -> String {
    let mut out = String::from(HEADER);
    out.push('\n');
    let _ = writeln!(
        out,
        "alternator_amps = {}",
        number_text(file.alternator_amps)
    );
    let _ = writeln!(
        out,
        "battery_amp_hours = {}",
        number_text(file.battery_amp_hours)
    );
    let _ = writeln!(out, "battery_usable = {}", number_text(file.battery_usable));
    write_circuits(&mut out, &file.circuits);
    out
}

/// The template written on the first run: every circuit of the unit, its phases
/// guessed from its name and marked as guesses (`guess`), and the two ratings left
/// for the builder to write (so that an unedited template is refused, not analysed
/// with made-up ratings).
pub fn template(circuits: &[Circuit]) -> String {
    let mut out = String::from(HEADER);
    out.push_str(TEMPLATE_NOTE);
    out.push('\n');
    out.push_str("# alternator_amps = 40\n");
    out.push_str("# battery_amp_hours = 17\n");
    let _ = writeln!(out, "battery_usable = {DEFAULT_BATTERY_USABLE}");
    let mut sorted: Vec<&Circuit> = circuits.iter().collect();
    sorted.sort_by_key(|c| c.id);
    let owned: Vec<Circuit> = sorted.into_iter().cloned().collect();
    let guesses = guess::guesses(&owned);
    let loads = template_circuits(&owned);
    for (c, g) in loads.iter().zip(&guesses) {
        write_circuit(&mut out, c, g.why.as_deref());
    }
    out
}

/// The template's circuits, in pin order: each with the phases its name suggests
/// ([`guess`]).
pub fn template_circuits(circuits: &[Circuit]) -> Vec<LoadCircuit> {
    let mut sorted: Vec<&Circuit> = circuits.iter().collect();
    sorted.sort_by_key(|c| c.id);
    let owned: Vec<Circuit> = sorted.into_iter().cloned().collect();
    owned
        .iter()
        .zip(guess::guesses(&owned))
        .map(|(c, g)| LoadCircuit {
            id: c.id,
            name: c.name.clone(),
            amps: None,
            duty: g.duty,
            wire: WireRun::default(),
        })
        .collect()
}

fn write_circuits(out: &mut String, circuits: &[LoadCircuit]) {
    let mut sorted: Vec<&LoadCircuit> = circuits.iter().collect();
    sorted.sort_by_key(|c| c.id);
    for c in sorted {
        write_circuit(out, c, None);
    }
}

/// A circuit's wire lines; each one not entered is written commented, saying so.
fn write_wire(out: &mut String, run: &WireRun) {
    match run.wire {
        Some(w) => {
            let _ = writeln!(out, "wire = \"{}\"", w.file_text());
        }
        None => out.push_str(
            "# wire = \"\"            # not entered: a gauge (\"22 AWG\") or metric (\"1.0 mm2\")\n",
        ),
    }
    for (key, feet, what) in [
        (
            "wire_length",
            run.feed_feet,
            "pin to load, \"12 ft\" or \"3.6 m\"",
        ),
        (
            "return_length",
            run.return_feet,
            "load to ground block, if not grounded at the load",
        ),
    ] {
        match feet {
            Some(f) => {
                let _ = writeln!(out, "{key} = \"{} ft\"", number_text(f));
            }
            None => {
                let _ = writeln!(
                    out,
                    "{:<23}# not entered: {what}",
                    format!("# {key} = \"\"")
                );
            }
        }
    }
}

/// One `[circuit.PIN]` section; `guess`: what its phases were guessed from, said
/// above them and marked beside each.
fn write_circuit(out: &mut String, c: &LoadCircuit, guess: Option<&str>) {
    let _ = writeln!(out, "\n[circuit.{}]", c.pin());
    let _ = writeln!(out, "name = {}", toml::Value::String(c.name.clone()));
    match c.amps {
        Some(a) => {
            let _ = writeln!(out, "amps = {}", number_text(a));
        }
        None => out.push_str("# amps = 0.0\n"),
    }
    write_wire(out, &c.wire);
    if let Some(why) = guess {
        let _ = writeln!(out, "# guessed from the name: {why}");
    }
    for p in Phase::ALL {
        let d = c.duty(p);
        let value = if d == 1.0 {
            "true".to_string()
        } else if d == 0.0 {
            "false".to_string()
        } else {
            number_text(d)
        };
        let line = format!("{} = {value}", p.key());
        let _ = if guess.is_some() {
            writeln!(out, "{line:<21}# guess: check")
        } else {
            writeln!(out, "{line}")
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loads::test_circuit as circuit;
    use crate::model::CircuitKind;
    use crate::protocol::device::{EFIS, FIELD_PRI, FLAPS, STARTER, TRIM_P};

    fn unit() -> Vec<Circuit> {
        vec![
            circuit(FLAPS, "Flaps", CircuitKind::Flaps),
            circuit(STARTER, "Starter", CircuitKind::Starter),
            circuit(EFIS, "EFIS \"left\"", CircuitKind::Device),
            circuit(
                FIELD_PRI,
                "Alternator",
                CircuitKind::Alternator { primary: true },
            ),
            circuit(0x0A, "Landing Lt", CircuitKind::Device),
            circuit(
                TRIM_P,
                "Trim_P",
                CircuitKind::Trim(crate::model::TrimKind::Pitch),
            ),
        ]
    }

    fn sample() -> LoadFile {
        LoadFile {
            alternator_amps: 40.0,
            battery_amp_hours: 17.5,
            battery_usable: 0.75,
            circuits: vec![
                LoadCircuit {
                    id: EFIS,
                    name: "EFIS \"left\" # 1".into(),
                    amps: Some(2.25),
                    duty: [1.0; 7],
                    wire: WireRun {
                        wire: Some(Wire::parse("1.0 mm²").unwrap()),
                        feed_feet: Some(12.5),
                        return_feet: None,
                    },
                },
                LoadCircuit {
                    id: 0x0A,
                    name: "Landing Lt".into(),
                    amps: None,
                    duty: [0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0],
                    wire: WireRun {
                        wire: Some(Wire::parse("16 AWG").unwrap()),
                        feed_feet: Some(14.0),
                        return_feet: Some(3.25),
                    },
                },
                LoadCircuit {
                    id: TRIM_P,
                    name: "Pitch trim".into(),
                    amps: Some(1.0),
                    duty: [0.0, 0.05, 0.1, 0.1, 0.1, 0.1, 0.1],
                    wire: WireRun::default(),
                },
            ],
        }
    }

    #[test]
    fn a_file_written_is_read_back_the_same() {
        let f = sample();
        let text = to_toml(&f);
        assert_eq!(parse(&text), Ok(f));
    }

    /// Ratings past 2^63 were written as integer digits TOML refuses; and the sizes
    /// either side of where the exponent form takes over.
    #[test]
    fn huge_ratings_are_written_as_toml_reads_them_back() {
        for v in [
            40.0,
            0.1,
            9_007_199_254_740_991.0,
            9_007_199_254_740_992.0,
            9.3e18,
            1e19,
            1.5e300,
            f64::MAX,
        ] {
            let mut f = sample();
            f.alternator_amps = v;
            f.battery_amp_hours = v;
            let text = to_toml(&f);
            assert_eq!(parse(&text), Ok(f), "{v}: {text}");
        }
        assert_eq!(number_text(40.0), "40");
        assert_eq!(number_text(2.25), "2.25");
        assert_eq!(number_text(1e19), "1e19");
        assert_eq!(number_text(f64::INFINITY), "inf");
    }

    #[test]
    fn the_template_lists_every_circuit_and_reads_back_once_the_ratings_are_written() {
        let text = template(&unit());
        for pin in ["Flaps", "Starter", "EFIS", "Field_Pri", "5A-7", "Trim_P"] {
            assert!(
                text.contains(&format!("\n[circuit.{pin}]\n")),
                "{pin} missing"
            );
        }
        // Unedited, it is refused for its missing rating, not analysed with a guess.
        assert_eq!(
            problem(&text),
            "alternator_amps: missing: write alternator_amps = the alternator's rated \
             output in amperes\n\
             battery_amp_hours: missing: write battery_amp_hours = the battery's rated \
             capacity in ampere-hours"
        );
        let edited = text
            .replace("# alternator_amps = 40", "alternator_amps = 60")
            .replace("# battery_amp_hours = 17", "battery_amp_hours = 18");
        let f = parse(&edited).unwrap();
        assert_eq!(f.alternator_amps, 60.0);
        assert_eq!(f.battery_amp_hours, 18.0);
        assert_eq!(f.battery_usable, DEFAULT_BATTERY_USABLE);
        assert_eq!(f.circuits, template_circuits(&unit()));
        let by_id = |id| f.circuits.iter().find(|c| c.id == id).unwrap();
        assert_eq!(by_id(STARTER).duty, [0.0; 7]);
        assert_eq!(by_id(FIELD_PRI).duty, [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0]);
        assert_eq!(by_id(EFIS).duty, [1.0; 7]);
        assert_eq!(by_id(EFIS).name, "EFIS \"left\"");
        assert_eq!(by_id(EFIS).amps, None);
    }

    /// Every problem, one a line.
    fn problem(text: &str) -> String {
        let p: Vec<String> = parse(text)
            .unwrap_err()
            .iter()
            .map(|p| p.to_string())
            .collect();
        p.join("\n")
    }

    const RATINGS: &str = "alternator_amps = 40\nbattery_amp_hours = 17\n";

    #[test]
    fn a_bad_phase_value_is_named_with_its_line_and_field() {
        let text = format!("{RATINGS}\n[circuit.5A-7]\nname = \"Landing\"\ntaxi = 1.5\n");
        assert_eq!(
            problem(&text),
            "line 6: [circuit.5A-7] taxi: 1.5 is not on, off or a fraction of the time; \
             write true, false, or a number from 0 to 1 (0.25 for a quarter of the time)"
        );
        let text = format!("{RATINGS}[circuit.EFIS]\nlanding = \"yes\"\n");
        assert_eq!(
            problem(&text),
            "line 4: [circuit.EFIS] landing: text is not on, off or a fraction of the time; \
             write true, false, or a number from 0 to 1 (0.25 for a quarter of the time)"
        );
    }

    #[test]
    fn an_unknown_pin_a_misspelt_phase_and_a_twice_listed_pin_are_named() {
        let text = format!("{RATINGS}\n[circuit.5A-99]\ntaxi = true\n");
        let p = problem(&text);
        assert!(
            p.starts_with("line 4: [circuit.5A-99]: \"5A-99\" is no pin of the VP-X; the pins are Flaps, Starter, EFIS,"),
            "{p}"
        );
        let text = format!("{RATINGS}[circuit.EFIS]\ntakeoff = true\n");
        let p = problem(&text);
        assert!(
            p.starts_with("line 4: [circuit.EFIS] takeoff: unknown key; a circuit's keys are"),
            "{p}"
        );
        assert!(p.contains("take_off"), "{p}");
        let text = format!("{RATINGS}[circuit.efis]\ntaxi = true\n[circuit.EFIS]\n");
        let p = problem(&text);
        assert!(p.contains("EFIS is listed twice, first on line"), "{p}");
    }

    #[test]
    fn ratings_and_currents_out_of_range_are_refused_in_words() {
        assert_eq!(
            problem("alternator_amps = 0\nbattery_amp_hours = 17\n"),
            "line 1: alternator_amps: 0 must be more than 0 (the alternator's rated output \
             in amperes)"
        );
        assert_eq!(
            problem("alternator_amps = \"40 A\"\nbattery_amp_hours = 17\n"),
            "line 1: alternator_amps: text where a number was expected"
        );
        assert_eq!(
            problem("alternator_amps = 40\n"),
            "battery_amp_hours: missing: write battery_amp_hours = the battery's rated \
             capacity in ampere-hours"
        );
        assert_eq!(
            problem(&format!("{RATINGS}battery_usable = 1.2\n")),
            "line 3: battery_usable: 1.2 is no share of the battery; write a number more \
             than 0 and at most 1 (0.8 for 80 %)"
        );
        assert_eq!(
            problem(&format!("{RATINGS}[circuit.5A-1]\namps = 6\n")),
            "line 4: [circuit.5A-1] amps: 6 A is more than the 5A-1 pin can carry (5 A at \
             most, ICD Appendix B)"
        );
        assert_eq!(
            problem(&format!("{RATINGS}[circuit.5A-1]\namps = -1\n")),
            "line 4: [circuit.5A-1] amps: -1 A is below zero; write the current the \
             circuit draws"
        );
    }

    /// Each bad wire line is named by its line and field; a good one read in feet.
    #[test]
    fn wire_lines_are_read_and_bad_ones_named_with_line_and_field() {
        let at = |lines: &str| format!("{RATINGS}[circuit.5A-3]\nname = \"Strobe\"\n{lines}");
        let f = parse(&at(
            "wire = \"22 awg\"\nwire_length = \"3.6 m\"\nreturn_length = \"4 ft\"\n",
        ))
        .unwrap();
        let w = f.circuits[0].wire;
        assert_eq!(w.wire.map(|w| w.awg), Some(22));
        // 3.6 m / 0.3048 = 11.811 ft, and 4 ft of return: 15.811 ft.
        assert!((w.run_feet().unwrap() - 15.811).abs() < 0.001);
        let p = problem(&at("wire = \"21 AWG\"\n"));
        assert!(
            p.starts_with("line 5: [circuit.5A-3] wire: \"21 AWG\": there is no 21 AWG in AC 43.13-1B Table 11-9"),
            "{p}"
        );
        assert_eq!(
            problem(&at("wire_length = \"0 ft\"\n")),
            "line 5: [circuit.5A-3] wire_length: \"0 ft\": a wire's length is more than 0"
        );
        assert_eq!(
            problem(&at("return_length = \"-2 m\"\n")),
            "line 5: [circuit.5A-3] return_length: \"-2 m\": a wire's length is more than 0"
        );
        let p = problem(&at("wire_length = \"500 ft\"\n"));
        assert!(
            p.starts_with("line 5: [circuit.5A-3] wire_length: \"500 ft\" is implausible"),
            "{p}"
        );
        let p = problem(&at("wire_length = \"12 yd\"\n"));
        assert!(
            p.starts_with("line 5: [circuit.5A-3] wire_length: \"12 yd\": say the unit"),
            "{p}"
        );
        let p = problem(&at("wire = 22\n"));
        assert!(
            p.starts_with("line 5: [circuit.5A-3] wire: a whole number where text in quotes"),
            "{p}"
        );
    }

    /// The template writes the wire lines commented, as not entered, and they read
    /// back as nothing entered.
    #[test]
    fn the_template_writes_the_wire_lines_commented_as_not_entered() {
        let text = template(&unit());
        assert!(
            text.contains("\n[circuit.5A-7]\nname = \"Landing Lt\"\n# amps = 0.0\n# wire = \"\"            # not entered"),
            "{text}"
        );
        assert!(
            text.contains("# wire_length = \"\"     # not entered"),
            "{text}"
        );
        assert!(
            text.contains("# return_length = \"\"   # not entered"),
            "{text}"
        );
    }

    #[test]
    fn broken_toml_is_named_with_its_line() {
        let p = parse(&format!("{RATINGS}[circuit.EFIS\ntaxi = true\n")).unwrap_err();
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].line, Some(3));
    }

    /// A file with a mistake in each part: every one listed, in the file's order, each
    /// with its line and field, and a missing rating first.
    #[test]
    fn every_mistake_is_listed_at_once_with_line_and_field() {
        let text = "alternator_amps = \"40 A\"\nbatery = 17\n\n\
                    [circuit.5A-7]\ntaxi = 1.5\nwire = \"21 AWG\"\n\
                    [circuit.5A-99]\ntaxi = true\n\
                    [circuit.EFIS]\ntakeoff = true\namps = -1\n";
        let got: Vec<(Option<usize>, String)> = parse(text)
            .unwrap_err()
            .into_iter()
            .map(|p| (p.line, p.field))
            .collect();
        let want: Vec<(Option<usize>, String)> = [
            (None, "battery_amp_hours"),
            (Some(1), "alternator_amps"),
            (Some(2), "batery"),
            (Some(5), "[circuit.5A-7] taxi"),
            (Some(6), "[circuit.5A-7] wire"),
            (Some(7), "[circuit.5A-99]"),
            (Some(10), "[circuit.EFIS] takeoff"),
            (Some(11), "[circuit.EFIS] amps"),
        ]
        .into_iter()
        .map(|(l, f)| (l, f.to_string()))
        .collect();
        assert_eq!(got, want);
        // Without the ratings, the rest still: a typo is a typo.
        assert_eq!(parse_circuits(text).unwrap_err().len(), want.len() - 2);
    }

    #[test]
    fn whole_numbers_and_missing_phases_are_read_as_meant() {
        let f = parse(&format!(
            "{RATINGS}[circuit.Trim_P]\nname = \"Pitch\"\namps = 2\ntaxi = 1\ncruise_day = 0\nlanding = 0.25\n"
        ))
        .unwrap();
        assert_eq!(f.circuits.len(), 1);
        assert_eq!(f.circuits[0].amps, Some(2.0));
        assert_eq!(f.circuits[0].duty, [0.0, 1.0, 0.0, 0.0, 0.0, 0.25, 0.0]);
        assert_eq!(f.circuits[0].pin(), "Trim_P");
    }
}

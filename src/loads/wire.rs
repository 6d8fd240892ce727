//! The wire rules: FAA AC 43.13-1B (CHG 1), chapter 11, the figures a breaker and a
//! wire are held against, each constant citing its table. Everything here is pure
//! arithmetic on those tables; [`super::wiring`] applies it to the aircraft's circuits.
//!
//! Decisions, made here and shown in the report:
//! - **The chart.** Table 11-3 is a guide "prepared for the conditions specified"
//!   (its basis: copper wire in bundles, the bundle's ambient and altitude) and "in
//!   general conservative" (¶11-49). A wire run alone in open air "may possibly" be
//!   protected by the next higher breaker; we say so, and hold the chart's figure.
//! - **A metric wire** counts as the largest AWG gauge whose cross-section (Table
//!   11-9's circular mils) it is at least: conservative, since its own copper is never
//!   less than the gauge it is counted as. Both its breaker (Table 11-3) and its
//!   resistance (Table 11-9) are that gauge's. A wire thinner than 24 AWG is refused.
//! - **The system** (14 V or 28 V, Table 11-6) is told by the live bus voltage when
//!   there is one, else by SYSTEM_SPEC's overvoltage limit (ICD Table 14: 16 V for a
//!   14 V system, 32 V for a 28 V one). Where the two disagree, the bus decides, and
//!   [`SystemVoltage::note`] says so.
//! - **The run** is the feed from the VP-X pin to the load plus the load's ground
//!   return (¶11-67); a return not entered is taken as grounded at the load (0 ft).
//! - **The formula** (¶11-66: resistance per foot × run × current) stands where a
//!   figure printed in the AC's examples disagrees with it (see the tests).
//! - **Temperature.** Table 11-9 is at 20 °C; ¶11-66(4) shortens the run for a hotter
//!   conductor (L2 = 254.5 × L1 / (234.5 + T2)). We know no conductor's temperature,
//!   so the drop is the 20 °C one, and the report says so.

use std::fmt;

use crate::protocol::message::OvervoltageLimit;

/// Table 11-3 (DC wire and circuit protector chart, copper): the largest circuit
/// breaker, in amperes, for each AN gauge. Gauges 1 and 0 have no breaker in the
/// chart (fuses only), nor has 24 (not in the chart).
pub const CHART_BREAKER_AMPS: [(u8, f64); 11] = [
    (22, 5.0),
    (20, 7.5),
    (18, 10.0),
    (16, 15.0),
    (14, 20.0),
    (12, 30.0),
    (10, 40.0),
    (8, 50.0),
    (6, 80.0),
    (4, 100.0),
    (2, 125.0),
];

/// Table 11-3's "basis of chart", in the report's words.
pub const CHART_BASIS: &str = "AC 43.13-1B Table 11-3 is drawn for copper wire in \
    bundles (its basis of chart: bundled wires at the stated ambient and altitude) and is \
    \"in general conservative\" (¶11-49); a wire run alone in open air may possibly be \
    protected by the next higher breaker, but the chart's figure is what is held here";

/// Table 11-9 (tin-plated copper): per AWG gauge, the maximum resistance at 20 °C in
/// ohms per 1000 ft, and the cross-section in circular mils.
pub const RESISTANCE_AND_AREA: [(u8, f64, f64); 14] = [
    (24, 28.40, 475.0),
    (22, 16.20, 755.0),
    (20, 9.88, 1_216.0),
    (18, 6.23, 1_900.0),
    (16, 4.81, 2_426.0),
    (14, 3.06, 3_831.0),
    (12, 2.02, 5_874.0),
    (10, 1.26, 9_354.0),
    (8, 0.70, 16_983.0),
    (6, 0.44, 26_818.0),
    (4, 0.28, 42_615.0),
    (2, 0.18, 66_500.0),
    (1, 0.15, 81_700.0),
    (0, 0.12, 104_500.0),
];

/// Circular mils in one square millimetre (Table 11-9's note): 1 mm² = 1,973.5 cmil.
pub const CIRCULAR_MILS_PER_MM2: f64 = 1_973.5;

/// Table 11-6: the allowable continuous voltage drop, bus to equipment, on a 14 V
/// system.
pub const DROP_14V_CONTINUOUS: f64 = 0.5;
/// Table 11-6: the same on a 28 V system.
pub const DROP_28V_CONTINUOUS: f64 = 1.0;

/// The bus voltage from which a system counts as a 28 V one: a 14 V system's bus runs
/// 12–15 V, a 28 V system's 24–29 V, and the unit's two overvoltage limits, 16 V and
/// 32 V, are one for each (ICD Table 14 notes 1 and 2).
pub const SYSTEM_28V_FROM: f32 = 20.0;

/// A run longer than this, one way, is no light aircraft's: refused as implausible (a
/// slip of the unit, metres typed as feet or a digit too many). A long-wing homebuilt's
/// wingtip is about 25 ft from the panel.
pub const MAX_PLAUSIBLE_FEET: f64 = 100.0;

/// Metres in a foot, exactly (the international foot).
pub const METRES_PER_FOOT: f64 = 0.3048;

/// What a wire was written as.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Size {
    /// An AWG (AN) gauge, 24 to 0.
    Awg(u8),
    /// A metric cross-section in mm².
    Mm2(f64),
}

/// A wire: its size as written, and the AWG gauge the rules count it as.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wire {
    pub size: Size,
    /// The AWG gauge the tables are read at: the size itself, or for a metric wire the
    /// largest gauge whose cross-section it is at least.
    pub awg: u8,
}

/// The gauges Table 11-9 lists, thinnest first, in words.
fn gauges_in_words() -> String {
    let g: Vec<String> = RESISTANCE_AND_AREA
        .iter()
        .map(|(g, _, _)| g.to_string())
        .collect();
    g.join(", ")
}

impl Wire {
    /// Reads "22 AWG" (any case, space optional, "AN" too), "1.0 mm2" or "1.0 mm²".
    pub fn parse(text: &str) -> Result<Wire, String> {
        let t = text.trim();
        let lower = t.to_ascii_lowercase();
        let number_and = |suffixes: &[&str]| {
            suffixes
                .iter()
                .find_map(|s| lower.strip_suffix(s).map(|n| n.trim().to_string()))
        };
        if let Some(n) = number_and(&["awg", "an"]) {
            let n = if n == "1/0" { "0".to_string() } else { n };
            let Ok(g) = n.parse::<u8>() else {
                return Err(format!(
                    "{t:?} is no wire size; write a gauge as \"22 AWG\" or a metric wire \
                     as \"1.0 mm2\""
                ));
            };
            if !RESISTANCE_AND_AREA.iter().any(|(a, _, _)| *a == g) {
                return Err(format!(
                    "{t:?}: there is no {g} AWG in AC 43.13-1B Table 11-9; its gauges are {}",
                    gauges_in_words()
                ));
            }
            return Ok(Wire {
                size: Size::Awg(g),
                awg: g,
            });
        }
        if let Some(n) = number_and(&["mm2", "mm²", "mm^2", "sq mm"]) {
            let mm2: f64 = n
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| format!("{t:?}: {n:?} is no number of square millimetres"))?;
            if mm2 <= 0.0 {
                return Err(format!("{t:?}: a wire's cross-section is more than 0 mm²"));
            }
            let Some(awg) = awg_at_most(mm2 * CIRCULAR_MILS_PER_MM2) else {
                return Err(format!(
                    "{t:?} is thinner than 24 AWG, the thinnest wire in AC 43.13-1B \
                     Table 11-9 (0.24 mm²); no breaker can be held against it"
                ));
            };
            return Ok(Wire {
                size: Size::Mm2(mm2),
                awg,
            });
        }
        Err(format!(
            "{t:?} is no wire size; write a gauge as \"22 AWG\" or a metric wire as \"1.0 \
             mm2\""
        ))
    }

    /// Table 11-3: the largest breaker that protects it, or `None` where the chart
    /// gives none (24 AWG; 1 and 0, fuses only).
    pub fn max_breaker_amps(&self) -> Option<f64> {
        CHART_BREAKER_AMPS
            .iter()
            .find(|(g, _)| *g == self.awg)
            .map(|(_, a)| *a)
    }

    /// Table 11-9: ohms per foot at 20 °C.
    pub fn ohms_per_foot(&self) -> f64 {
        RESISTANCE_AND_AREA
            .iter()
            .find(|(g, _, _)| *g == self.awg)
            .map_or(f64::INFINITY, |(_, r, _)| r / 1000.0)
    }

    /// As the load file writes it, read back as the same wire: "22 AWG", "1 mm2".
    pub fn file_text(&self) -> String {
        match self.size {
            Size::Awg(g) => format!("{g} AWG"),
            Size::Mm2(mm) => format!("{mm} mm2"),
        }
    }

    /// Whether a `breaker_amps` breaker protects it (¶11-48, Table 11-3).
    pub fn protected_by(&self, breaker_amps: f64) -> bool {
        self.max_breaker_amps().is_some_and(|m| breaker_amps <= m)
    }
}

impl fmt::Display for Wire {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.size {
            Size::Awg(g) => write!(f, "{g} AWG"),
            Size::Mm2(mm) => write!(f, "{mm} mm² (as {} AWG)", self.awg),
        }
    }
}

/// The largest AWG gauge (Table 11-9) whose area is at most `cmil` circular mils.
fn awg_at_most(cmil: f64) -> Option<u8> {
    RESISTANCE_AND_AREA
        .iter()
        .rev()
        .find(|(_, _, area)| *area <= cmil)
        .map(|(g, _, _)| *g)
}

/// Reads a length, "12 ft", "12 feet", "12'" or "3.6 m", as feet. Zero, negative and
/// implausibly long lengths are refused in words.
pub fn parse_length(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let lower = t.to_ascii_lowercase();
    let units: [(&str, f64); 7] = [
        ("feet", 1.0),
        ("foot", 1.0),
        ("ft", 1.0),
        ("'", 1.0),
        ("metres", 1.0 / METRES_PER_FOOT),
        ("meters", 1.0 / METRES_PER_FOOT),
        ("m", 1.0 / METRES_PER_FOOT),
    ];
    let Some((n, per)) = units
        .iter()
        .find_map(|(u, per)| lower.strip_suffix(u).map(|n| (n.trim(), *per)))
    else {
        return Err(format!(
            "{t:?}: say the unit; write a length as \"12 ft\" or \"3.6 m\""
        ));
    };
    let v: f64 = n
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite())
        .ok_or_else(|| {
            format!("{t:?}: {n:?} is no number; write a length as \"12 ft\" or \"3.6 m\"")
        })?;
    if v <= 0.0 {
        return Err(format!("{t:?}: a wire's length is more than 0"));
    }
    let feet = v * per;
    if feet > MAX_PLAUSIBLE_FEET {
        return Err(format!(
            "{t:?} is implausible for a light aircraft's wire (over {MAX_PLAUSIBLE_FEET} ft \
             one way); check the figure and its unit"
        ));
    }
    Ok(feet)
}

/// Feet in words, to a tenth.
pub fn feet_text(feet: f64) -> String {
    format!("{feet:.1} ft")
}

/// Table 11-6's two nominal systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum System {
    V14,
    V28,
}

impl System {
    /// Table 11-6: the allowable continuous drop, bus to equipment.
    pub fn allowed_drop(self) -> f64 {
        match self {
            System::V14 => DROP_14V_CONTINUOUS,
            System::V28 => DROP_28V_CONTINUOUS,
        }
    }

    pub fn words(self) -> &'static str {
        match self {
            System::V14 => "14 V",
            System::V28 => "28 V",
        }
    }
}

/// The system the drop is held against, and how it was told.
#[derive(Debug, Clone, PartialEq)]
pub struct SystemVoltage {
    pub system: System,
    /// Where the overvoltage limit and the bus disagreed (the bus decided), in words.
    pub note: Option<String>,
}

/// The system from SYSTEM_SPEC's overvoltage limit in volts (16 or 32, ICD Table 14)
/// and the live bus voltage: the bus decides where both are known and disagree.
pub fn system(
    overvoltage_limit_volts: Option<u8>,
    bus_volts: Option<f32>,
) -> Option<SystemVoltage> {
    let by_limit = overvoltage_limit_volts.and_then(|v| match v {
        16 => Some(System::V14),
        32 => Some(System::V28),
        _ => None,
    });
    let by_bus = bus_volts.map(|v| {
        if v >= SYSTEM_28V_FROM {
            System::V28
        } else {
            System::V14
        }
    });
    match (by_limit, by_bus) {
        (Some(l), Some(b)) if l != b => Some(SystemVoltage {
            system: b,
            note: Some(format!(
                "the overvoltage limit ({} V) is for a {} system but the bus reads {:.1} V: \
                 the bus decides, so the drop is held to the {} system's limit (and the \
                 overvoltage limit wants checking)",
                overvoltage_limit_volts.unwrap_or(0),
                l.words(),
                bus_volts.unwrap_or(0.0),
                b.words()
            )),
        }),
        (_, Some(b)) => Some(SystemVoltage {
            system: b,
            note: None,
        }),
        (Some(l), None) => Some(SystemVoltage {
            system: l,
            note: None,
        }),
        (None, None) => None,
    }
}

/// SYSTEM_SPEC's overvoltage limit in volts (ICD Table 14: 0 is 16 V, 1 is 32 V).
pub fn limit_volts(l: OvervoltageLimit) -> Option<u8> {
    match l {
        OvervoltageLimit::V16 => Some(16),
        OvervoltageLimit::V32 => Some(32),
        _ => None,
    }
}

/// ¶11-66: the voltage drop of `amps` through `run_feet` of `wire` (feed and return).
pub fn drop_volts(wire: &Wire, run_feet: f64, amps: f64) -> f64 {
    wire.ohms_per_foot() * run_feet * amps
}

/// ¶11-66 turned round: the longest run of `wire` that keeps `amps` within
/// `limit_volts`.
pub fn longest_run_feet(wire: &Wire, amps: f64, limit_volts: f64) -> f64 {
    limit_volts / (wire.ohms_per_foot() * amps)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn awg(g: u8) -> Wire {
        Wire::parse(&format!("{g} AWG")).unwrap()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 0.005
    }

    /// Table 11-3, read off the chart by hand.
    #[test]
    fn the_largest_breaker_per_gauge_is_table_11_3s() {
        let want = [
            (22, Some(5.0)),
            (20, Some(7.5)),
            (18, Some(10.0)),
            (16, Some(15.0)),
            (14, Some(20.0)),
            (12, Some(30.0)),
            (10, Some(40.0)),
            (8, Some(50.0)),
            (6, Some(80.0)),
            (4, Some(100.0)),
            (2, Some(125.0)),
            (1, None),
            (0, None),
            (24, None),
        ];
        for (g, amps) in want {
            assert_eq!(awg(g).max_breaker_amps(), amps, "{g} AWG");
        }
        // ¶11-48: the breaker opens before the wire's rating is exceeded.
        assert!(awg(22).protected_by(5.0));
        assert!(!awg(22).protected_by(6.0));
        assert!(awg(20).protected_by(7.0));
        assert!(!awg(20).protected_by(8.0));
        assert!(!awg(24).protected_by(1.0));
    }

    #[test]
    fn gauges_are_read_in_any_case_and_a_missing_one_is_named() {
        for t in ["22 AWG", "22 awg", "22awg", " 22 Awg ", "22 AN"] {
            assert_eq!(Wire::parse(t), Ok(awg(22)), "{t}");
        }
        assert_eq!(Wire::parse("1/0 AWG").unwrap().awg, 0);
        let e = Wire::parse("21 AWG").unwrap_err();
        assert!(
            e.starts_with("\"21 AWG\": there is no 21 AWG in AC 43.13-1B Table 11-9; its gauges are 24, 22, 20,"),
            "{e}"
        );
        assert!(Wire::parse("22").unwrap_err().contains("no wire size"));
        assert!(Wire::parse("thick").unwrap_err().contains("no wire size"));
        assert!(Wire::parse("x AWG").unwrap_err().contains("no wire size"));
    }

    /// 1 mm² = 1,973.5 cmil (Table 11-9's note), held against Table 11-9's areas by
    /// hand: 18 AWG is 1,900 cmil ≤ 1,973.5 < 16 AWG's 2,426, so 1.0 mm² counts as 18.
    #[test]
    fn a_metric_wire_counts_as_the_largest_gauge_it_is_at_least() {
        let cases = [
            ("1.0 mm2", 18),  // 1,973.5 cmil
            ("1.0 mm²", 18),  // the same, with the superscript
            ("0.5 mm2", 22),  // 986.75: under 20 AWG's 1,216
            ("0.75 MM2", 20), // 1,480.1
            ("1.5 mm2", 16),  // 2,960.3: under 14 AWG's 3,831
            ("2.5 mm2", 14),  // 4,933.8: under 12 AWG's 5,874
            ("0.25 mm2", 24), // 493.4: over 24 AWG's 475
            ("6 mm2", 10),    // 11,841: under 8 AWG's 16,983
        ];
        for (t, g) in cases {
            let w = Wire::parse(t).unwrap();
            assert_eq!(w.awg, g, "{t}");
            assert_eq!(w.max_breaker_amps(), awg(g).max_breaker_amps(), "{t}");
            assert_eq!(w.ohms_per_foot(), awg(g).ohms_per_foot(), "{t}");
        }
        assert_eq!(
            Wire::parse("1.0 mm²").unwrap().to_string(),
            "1 mm² (as 18 AWG)"
        );
        assert!(
            Wire::parse("0.2 mm2")
                .unwrap_err()
                .contains("thinner than 24 AWG")
        );
        assert!(Wire::parse("0 mm2").unwrap_err().contains("more than 0"));
        assert!(Wire::parse("-1 mm2").unwrap_err().contains("more than 0"));
    }

    #[test]
    fn lengths_in_feet_and_metres_and_the_implausible_refused() {
        assert_eq!(parse_length("12 ft"), Ok(12.0));
        assert_eq!(parse_length("12ft"), Ok(12.0));
        assert_eq!(parse_length("4 feet"), Ok(4.0));
        // 3.6 m / 0.3048 m per ft = 11.811 ft.
        assert!(close(parse_length("3.6 m").unwrap(), 11.811));
        assert!(close(parse_length("3.6 M").unwrap(), 11.811));
        assert!(parse_length("0 ft").unwrap_err().contains("more than 0"));
        assert!(parse_length("-3 ft").unwrap_err().contains("more than 0"));
        let e = parse_length("500 ft").unwrap_err();
        assert!(e.contains("implausible"), "{e}");
        // 31 m is 101.7 ft: implausible too.
        assert!(parse_length("31 m").unwrap_err().contains("implausible"));
        assert!(parse_length("12").unwrap_err().contains("say the unit"));
        assert!(parse_length("12 yd").unwrap_err().contains("say the unit"));
        assert!(parse_length("twelve ft").unwrap_err().contains("no number"));
    }

    /// Table 11-8: 10 AWG at 20 A, 39 ft for a 1 V drop, 19.5 ft for 0.5 V, 156 ft
    /// for 4 V and 273 ft for 7 V. Worked by hand: 1.26 Ω/1000 ft (Table 11-9) × 39
    /// × 20 = 0.9828 V; × 156 × 20 = 3.9312 V; × 273 × 20 = 6.8796 V; × 19.5 × 20 =
    /// 0.4914 V. The AC prints 0.366 V for the 19.5 ft line, which its own formula
    /// does not give: the formula stands.
    #[test]
    fn table_11_8s_runs_give_their_drops_by_the_formula() {
        let w = awg(10);
        assert!(close(drop_volts(&w, 39.0, 20.0), 0.9828));
        assert!(close(drop_volts(&w, 156.0, 20.0), 3.9312));
        assert!(close(drop_volts(&w, 273.0, 20.0), 6.8796));
        assert!(close(drop_volts(&w, 19.5, 20.0), 0.4914));
        // And turned round, each limit's longest run (1 / (0.00126 × 20) = 39.68 ft).
        assert!((longest_run_feet(&w, 20.0, 1.0) - 39.68).abs() < 0.01);
        assert!((longest_run_feet(&w, 20.0, 0.5) - 19.84).abs() < 0.01);
        assert!(longest_run_feet(&w, 20.0, 4.0) >= 156.0);
        assert!(longest_run_feet(&w, 20.0, 7.0) >= 273.0);
    }

    /// Table 11-7's check figures: 6 AWG, 107 ft, 20 A: 0.00044 × 107 × 20 = 0.9416 V;
    /// 4 AWG, 90 ft: 0.504 V; 14 AWG, 100 ft: 6.12 V. The AC prints 3.60 V for 88 ft
    /// of 12 AWG, where 0.00202 × 88 × 20 = 3.5552 V: the formula stands.
    #[test]
    fn table_11_7s_check_figures_by_the_formula() {
        assert!(close(drop_volts(&awg(6), 107.0, 20.0), 0.9416));
        assert!(close(drop_volts(&awg(4), 90.0, 20.0), 0.504));
        assert!(close(drop_volts(&awg(14), 100.0, 20.0), 6.12));
        assert!(close(drop_volts(&awg(12), 88.0, 20.0), 3.5552));
    }

    /// ¶11-67's example 1: 50 ft, 28 V, 20 A, within 1 V: 10 AWG gives 0.00126 × 50 ×
    /// 20 = 1.26 V (over), 8 AWG 0.0007 × 50 × 20 = 0.70 V (under): the larger wire.
    #[test]
    fn paragraph_11_67s_example_takes_the_larger_wire() {
        let limit = System::V28.allowed_drop();
        assert_eq!(limit, 1.0);
        assert!(close(drop_volts(&awg(10), 50.0, 20.0), 1.26));
        assert!(drop_volts(&awg(10), 50.0, 20.0) > limit);
        assert!(close(drop_volts(&awg(8), 50.0, 20.0), 0.70));
        assert!(drop_volts(&awg(8), 50.0, 20.0) <= limit);
    }

    /// Table 11-6 by system; the bus decides over the overvoltage limit.
    #[test]
    fn the_system_is_told_by_the_bus_over_the_overvoltage_limit() {
        assert_eq!(System::V14.allowed_drop(), 0.5);
        assert_eq!(System::V28.allowed_drop(), 1.0);
        let s = |l, b| system(l, b).map(|s| s.system);
        assert_eq!(s(Some(16), None), Some(System::V14));
        assert_eq!(s(Some(32), None), Some(System::V28));
        assert_eq!(s(None, Some(13.8)), Some(System::V14));
        assert_eq!(s(None, Some(27.9)), Some(System::V28));
        assert_eq!(s(None, None), None);
        assert_eq!(system(Some(16), Some(14.1)).unwrap().note, None);
        // The miswired case: a 32 V limit on a 14 V bus.
        let m = system(Some(32), Some(14.2)).unwrap();
        assert_eq!(m.system, System::V14);
        let note = m.note.unwrap();
        assert!(note.contains("bus reads 14.2 V: the bus decides"), "{note}");
    }
}

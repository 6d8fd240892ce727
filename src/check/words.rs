//! The check's one vocabulary: every result as a mark and plain words, what is left
//! to fix, what to do with a circuit the check left held. The screen shows them, and
//! the headless run and the report print the same words, so a finding reads the same
//! wherever it is seen. A mark is never shown without its word (colour is a bonus).

use std::time::Duration;

use super::state::{
    CheckView, CircuitFinding, CircuitResult, LeftBehind, LitEnd, LoadsView, Mark, MotorFinding,
    MotorResult, NEAR_BREAKER_PERCENT, NotFollowed, Outcome, SwitchFinding, SwitchResult,
};
use crate::protocol::device;
use crate::protocol::fault::FaultCode;
use crate::protocol::message::SwitchId;

/// "✓ PASS": the symbol and the word, always together.
pub fn badge(mark: Mark) -> String {
    format!("{} {}", mark.symbol(), mark.word())
}

/// "switch 4", "always on", "always off": what a circuit's DEVICE_SPEC assigns it to.
pub fn switch_id(s: SwitchId) -> String {
    match s {
        SwitchId::Off => "always off".into(),
        SwitchId::Input(n) => format!("switch {n}"),
        SwitchId::AlwaysOn => "always on".into(),
        SwitchId::Unknown(n) => format!("switch code {n} (not in the ICD)"),
    }
}

/// "a" or "an" before a number said aloud: "an 8 A breaker", "an 11 A", "an 18 A",
/// "a 5 A". (Eight, eleven, eighteen, eighty… begin with a vowel sound.)
pub fn article(n: u32) -> &'static str {
    let digits = n.to_string();
    // Eleven and eighteen, alone or leading a group of thousands (11 000, 18 500).
    let lead = match digits.len() % 3 {
        2 => &digits[..2],
        _ => "",
    };
    if digits.starts_with('8') || lead == "11" || lead == "18" {
        "an"
    } else {
        "a"
    }
}

/// "an 8 A breaker".
fn breaker(b: u8) -> String {
    format!("{} {b} A breaker", article(u32::from(b)))
}

/// What the person does to end a hold by DEVICE_POWER: the unit holds a circuit the
/// page (or the check) switched until its switch is cycled (ICD Appendix A). Said as
/// a flip to the other position and back, so a switch found off is left off.
pub fn cycle(s: SwitchId) -> String {
    match s {
        SwitchId::Input(n) => format!("flip switch {n} to the other position and back"),
        other => format!("{}: there is no switch to flip", switch_id(other)),
    }
}

/// The ICD's place for the hold rule, as the words cite it.
pub const HOLD_RULE: &str = "ICD Appendix A";

/// "flip the switch to the other position and back": what ends a DEVICE_POWER hold
/// (ICD Appendix A), said so a switch found off is left off.
const RELEASE: &str = "flip the switch to the other position and back to release it";

impl NotFollowed {
    /// Said after the circuit's name: "Landing Lt is held off by DEVICE_POWER…".
    pub fn words(&self) -> String {
        match self {
            NotFollowed::HeldByPage { on, sent_at, ago } => {
                let state = if *on { "on" } else { "off" };
                let when = match sent_at {
                    // 2026-12-01T21:40:12.345Z: the time of day, to the second, in UTC.
                    Some(t) => format!("at {} UTC", &crate::utc::utc_text(*t)[11..19]),
                    None => format!("{} before", duration(*ago)),
                };
                format!(
                    "is held {state} by DEVICE_POWER sent from this page {when} \
                     ({HOLD_RULE}): {RELEASE}"
                )
            }
            NotFollowed::NotHeldByPage => format!(
                "did not follow its input, and no DEVICE_POWER from this page holds it: \
                 another display may hold it ({HOLD_RULE}): {RELEASE}"
            ),
            NotFollowed::AssignedTo(SwitchId::Off) => {
                "is assigned to no switch (always off)".into()
            }
            NotFollowed::AssignedTo(s) => format!("is assigned to {}", switch_id(*s)),
            NotFollowed::FollowedOther(input) => format!(
                "changed with {} instead: the unit has it on that switch",
                input.label()
            ),
            NotFollowed::Faulted(code) => format!("faulted with {}", code.name()),
            NotFollowed::Unexplained => {
                "could not be seen: no live DEVICE_STATUS while the switch was flipped".into()
            }
        }
    }
}

/// "switch 4, switch 6": inputs by their labels.
fn labels(inputs: &[super::state::Input]) -> String {
    inputs
        .iter()
        .map(|i| i.label())
        .collect::<Vec<_>>()
        .join(", ")
}

impl SwitchFinding {
    /// The finding in words; `name_of` names a circuit by id.
    pub fn words(&self, name_of: &dyn Fn(u8) -> String) -> String {
        match self {
            SwitchFinding::Passed => "the input changed, and its circuits followed".into(),
            SwitchFinding::Changed => "the input changed (no circuit is assigned to it)".into(),
            SwitchFinding::NeverChanged => {
                "input never changed: a broken wire, a bad switch, or the wrong pin".into()
            }
            SwitchFinding::OtherChanged(inputs) => {
                format!("{} changed instead: switches crossed", labels(inputs))
            }
            SwitchFinding::CircuitsDidNotFollow(list) => format!(
                "circuits did not follow: {}",
                list.iter()
                    .map(|(id, why)| format!("{} {}", name_of(*id), why.words()))
                    .collect::<Vec<_>>()
                    .join("; ")
            ),
        }
    }
}

impl CircuitFinding {
    pub fn words(&self) -> String {
        match self {
            CircuitFinding::Within { amps, breaker: b } => {
                format!("draws {amps:.1} A of {}", breaker(*b))
            }
            CircuitFinding::NoCurrent => {
                "no current while on: an open circuit, a blown bulb, a load not connected".into()
            }
            CircuitFinding::NearBreaker { amps, breaker: b } => format!(
                "draws {amps:.1} A of {} (≥ {NEAR_BREAKER_PERCENT} %): the breaker is \
                 tight and will trip in flight",
                breaker(*b)
            ),
            CircuitFinding::Faulted(code) => fault(*code),
            CircuitFinding::DidNotSwitch => {
                "did not switch on: the unit never showed it on after DEVICE_POWER".into()
            }
        }
    }
}

impl MotorFinding {
    pub fn words(&self) -> String {
        match self {
            MotorFinding::Moves => "it moves the commanded way".into(),
            MotorFinding::Reversed => {
                "reversed: the motor's polarity is swapped, or the sensor is wired backwards".into()
            }
            MotorFinding::NoMovement => "no movement: the motor, the sensor or a limit".into(),
            MotorFinding::AgainstLimit => "runs against a limit".into(),
            MotorFinding::Faulted(code) => fault(*code),
        }
    }
}

/// A fault's name with its Appendix E (Table 43) action and how it clears.
pub fn fault(code: FaultCode) -> String {
    match code.info() {
        Some(i) if !i.action.is_empty() => {
            // The table's description ends with its own full stop.
            format!(
                "faulted: {} ({}). {} {}",
                i.name,
                i.description.trim_end_matches('.'),
                i.action,
                i.clears
            )
        }
        _ => format!("faulted: {}", code.name()),
    }
}

/// How "Is it lit?" ended, and so when the light went back off: "you saw it lit; off
/// at your answer", "no answer in 60 s; switched off then", …. `switched`: the check
/// had switched it on (else it is on by its switch and stays so).
pub fn lit_ended(lit: Option<bool>, ended: LitEnd, switched: bool) -> String {
    let seen = match lit {
        Some(true) => "you saw it lit",
        Some(false) => "you saw it dark",
        None => "not answered",
    };
    let off = |when: &str| {
        if switched {
            format!("switched back off {when}")
        } else {
            "left on by its switch".to_string()
        }
    };
    match ended {
        LitEnd::Answer => format!("{seen}; {}", off("at your answer")),
        LitEnd::Cap(held) => format!("no answer in {} s; {}", held.as_secs(), off("then")),
        LitEnd::Skipped => format!("{seen} (you skipped the question); {}", off("then")),
        LitEnd::NobodyToAnswer => {
            "not asked if it is lit: nobody could answer (standard input ended)".into()
        }
    }
}

/// What the person saw of a light (`lit`: lit or dark) beside what the unit measured:
/// the words for beside its current, and, when the two disagree, what that means.
/// "No current" and "lit" disagree; so do a current and "dark".
pub fn lit_seen(c: &CircuitResult, lit: bool) -> (String, Option<String>) {
    let seen = if lit { "seen lit" } else { "seen dark" };
    let disagree = match (&c.outcome, lit) {
        (Outcome::Found(CircuitFinding::NoCurrent), true) => Some(
            "you saw it lit, yet the unit read no current: the two disagree (the lamp may \
             be fed from another pin, or the unit's current reading is wrong)"
                .to_string(),
        ),
        (
            Outcome::Found(
                CircuitFinding::Within { amps, .. } | CircuitFinding::NearBreaker { amps, .. },
            ),
            false,
        ) => Some(format!(
            "the unit read {amps:.1} A, yet you saw it dark: the two disagree (a lamp out \
             with another load on its pin, or another lamp wired to it)"
        )),
        _ => None,
    };
    (seen.to_string(), disagree)
}

/// An outcome's words: the finding's own, or why there is none.
fn outcome<F>(o: &Outcome<F>, found: impl Fn(&F) -> String) -> String {
    match o {
        Outcome::Found(f) => found(f),
        Outcome::Skipped(why) if why.is_empty() => "skipped".into(),
        Outcome::Skipped(why) => why.clone(),
        Outcome::NotRun => "not run: the check stopped before it".into(),
    }
}

/// A switch input's result in words; `name` gives a circuit's name from its id.
pub fn switch(r: &SwitchResult, name: impl Fn(u8) -> String) -> String {
    outcome(&r.outcome, |f| f.words(&name))
}

pub fn circuit(r: &CircuitResult) -> String {
    outcome(&r.outcome, CircuitFinding::words)
}

pub fn motor(r: &MotorResult) -> String {
    outcome(&r.outcome, MotorFinding::words)
}

impl CheckView {
    /// The findings to fix, one line each: each result that failed or warned.
    pub fn to_fix(&self) -> Vec<String> {
        let name_of = |id| self.name_of(id);
        let mut out = Vec::new();
        for s in &self.switches {
            if let Outcome::Found(f) = &s.outcome
                && f.mark() != Mark::Pass
            {
                out.push(format!("{}: {}", s.input.label(), f.words(&name_of)));
            }
        }
        for c in &self.circuits {
            if let Outcome::Found(f) = &c.outcome
                && f.mark() != Mark::Pass
            {
                out.push(format!("{} ({}): {}", c.name, c.pin, f.words()));
            }
        }
        for m in &self.motors {
            if let Outcome::Found(f) = &m.outcome
                && f.mark() != Mark::Pass
            {
                out.push(format!("{}: {}", m.motor.name(), f.words()));
            }
        }
        out
    }

    /// What releases a hold on a circuit of switch `sw`: flipping it, unless the check
    /// found that switch dead or crossed. Then flipping it cannot reach its input, so
    /// the words say to fix it first, and that meanwhile only a display switches the
    /// circuit (ICD Appendix A: a soft key overrides the switch until it is cycled).
    pub fn release(&self, sw: SwitchId) -> String {
        let SwitchId::Input(n) = sw else {
            return cycle(sw);
        };
        let found = self.switches.iter().find_map(|s| match &s.outcome {
            Outcome::Found(f) if s.input == super::state::Input::Switch(n) => Some(f),
            _ => None,
        });
        let broken = match found {
            Some(SwitchFinding::NeverChanged) => format!("switch {n} never changed in the check"),
            Some(SwitchFinding::OtherChanged(others)) => {
                format!("switch {n} is crossed with {}", labels(others))
            }
            _ => return cycle(sw),
        };
        format!(
            "{broken}: fix it, then flip it to the other position and back; until then \
             only a display switches it (o and f on the page)"
        )
    }

    /// Everything left to fix, one line each, the same in the headless summary and
    /// the report: [`CheckView::to_fix`], then the load analysis' warnings (or its
    /// missing or refused file), each switch to flip for a circuit the check left
    /// held, and each circuit an interrupted check left changed.
    pub fn left_to_fix(&self) -> Vec<String> {
        let mut out = self.to_fix();
        match &self.loads {
            Some(LoadsView::Analysed { analysis, .. }) => out.extend(
                analysis
                    .warnings()
                    .into_iter()
                    .map(|w| format!("Load analysis, {w}")),
            ),
            Some(LoadsView::TemplateWritten(path)) => out.push(format!(
                "Load analysis: fill in the load file {} and run the check again",
                path.display()
            )),
            // One item a problem of the file, each with its path, line and field.
            Some(LoadsView::Refused(why)) => {
                out.extend(why.lines().map(|p| format!("Load analysis: {p}")));
            }
            None => {}
        }
        for r in self.wires.iter().flat_map(|w| &w.rows) {
            if let Some(t) = r.unprotected_words() {
                out.push(format!(
                    "Wires, {t}: lower the breaker to what its wire allows, or fit a \
                     thicker wire"
                ));
            } else if let Some(t) = r.drop_words() {
                out.push(format!("Wires, {t}"));
            }
        }
        for (_, name, switch) in &self.to_cycle {
            out.push(format!(
                "{name}: {} (the check left it held by DEVICE_POWER)",
                self.release(*switch)
            ));
        }
        if let Some(i) = &self.interrupted {
            for LeftBehind { id, name, state } in &i.left {
                let pin = device::device(*id).map_or("?", |d| d.system_name);
                out.push(format!(
                    "{name} ({pin}), left by the interrupted check: {state}"
                ));
            }
        }
        out
    }
}

/// "Report written: vpx-check-2026-12-01T1830Z.md and .csv in /home/me/reports": the
/// file names whole, then the folder they share.
pub fn report_written(markdown: &std::path::Path, csv: &std::path::Path) -> String {
    let name = |p: &std::path::Path| {
        p.file_name().map_or_else(
            || p.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    };
    let (md, csv_name) = (name(markdown), name(csv));
    // The CSV shares the Markdown's stem: said as ".csv" after it.
    let csv_said = match (md.strip_suffix(".md"), csv_name.strip_suffix(".csv")) {
        (Some(a), Some(b)) if a == b => ".csv".to_string(),
        _ => csv_name,
    };
    match markdown.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => format!("Report written: {md} and {csv_said} in {}", dir.display()),
        None => format!("Report written: {md} and {csv_said}"),
    }
}

/// Where a motor was, as percent of its travel from the up (left) end (`ends`: the
/// up and down ends in sensor counts), clamped: a sensor can read past an end.
pub fn percent_of_travel(ends: (u8, u8), v: u8) -> u8 {
    let (from, to) = ends;
    if from == to {
        return 0;
    }
    let frac = (f64::from(v) - f64::from(from)) / (f64::from(to) - f64::from(from));
    (frac.clamp(0.0, 1.0) * 100.0).round() as u8
}

/// "50 % → 62 % → 50 % of travel": the positions a motor went through (raw
/// FLAP_TRIM_STATUS counts) on its travel; `None` when its ends are not known (or the
/// same).
pub fn travel(raw: &[u8], ends: Option<(u8, u8)>) -> Option<String> {
    let ends = ends.filter(|(a, b)| a != b)?;
    let p: Vec<String> = raw
        .iter()
        .map(|&v| format!("{} %", percent_of_travel(ends, v)))
        .collect();
    Some(format!("{} of travel", p.join(" → ")))
}

/// "128 → 159 → 128 counts": the raw sensor readings.
pub fn counts(raw: &[u8]) -> String {
    let p: Vec<String> = raw.iter().map(u8::to_string).collect();
    format!("{} counts", p.join(" → "))
}

/// The positions as the screen shows them: on the travel where its ends are known,
/// else in counts.
pub fn positions(raw: &[u8], ends: Option<(u8, u8)>) -> String {
    travel(raw, ends).unwrap_or_else(|| counts(raw))
}

/// A duration as a person says it: "800 ms", "3 s", "1 min 30 s".
pub fn duration(d: Duration) -> String {
    let ms = d.as_millis();
    if ms < 1000 {
        return format!("{ms} ms");
    }
    // Whole seconds, rounded up: "time left" must never read less than there is.
    let s = d.as_secs() + u64::from(d.subsec_nanos() > 0);
    if s < 60 {
        format!("{s} s")
    } else if s.is_multiple_of(60) {
        format!("{} min", s / 60)
    } else {
        format!("{} min {} s", s / 60, s % 60)
    }
}

/// "1 warning", "2 warnings".
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circuit held on a switch the check found dead, or crossed, is not to be
    /// released by flipping that switch: the words say what will release it. A
    /// switch that worked keeps the plain words.
    #[test]
    fn a_dead_or_crossed_switch_is_not_offered_to_release_a_hold() {
        use super::super::state::{Input, SwitchResult};
        let found = |n: u8, f: SwitchFinding| SwitchResult {
            input: Input::Switch(n),
            circuits: vec![],
            outcome: Outcome::Found(f),
        };
        let view = CheckView {
            switches: vec![
                found(2, SwitchFinding::Passed),
                found(5, SwitchFinding::OtherChanged(vec![Input::Switch(6)])),
                found(7, SwitchFinding::NeverChanged),
            ],
            to_cycle: vec![
                (4, "Nav Lt".into(), SwitchId::Input(2)),
                (17, "Landing Lt".into(), SwitchId::Input(5)),
                (23, "Standby Alt".into(), SwitchId::Input(7)),
            ],
            ..CheckView::default()
        };
        assert_eq!(
            view.left_to_fix()[2..],
            [
                "Nav Lt: flip switch 2 to the other position and back (the check left it held \
                 by DEVICE_POWER)",
                "Landing Lt: switch 5 is crossed with switch 6: fix it, then flip it to the \
                 other position and back; until then only a display switches it (o and f on the page) \
                 (the check left it held by DEVICE_POWER)",
                "Standby Alt: switch 7 never changed in the check: fix it, then flip it to \
                 the other position and back; until then only a display switches it (o and f on the page) \
                 (the check left it held by DEVICE_POWER)",
            ]
        );
    }

    #[test]
    fn every_mark_has_its_symbol_and_its_word() {
        assert_eq!(badge(Mark::Pass), "✓ PASS");
        assert_eq!(badge(Mark::Fail), "✗ FAIL");
        assert_eq!(badge(Mark::Warn), "⚠ WARN");
        assert_eq!(badge(Mark::Skipped), "– SKIPPED");
        assert_eq!(badge(Mark::NotRun), "? NOT RUN");
    }

    #[test]
    fn an_outcome_without_a_finding_says_why() {
        let r = |outcome| SwitchResult {
            input: super::super::state::Input::Switch(3),
            circuits: vec![7],
            outcome,
        };
        let name = |id: u8| format!("dev{id}");
        assert_eq!(
            switch(&r(Outcome::Skipped("excluded: --exclude".into())), name),
            "excluded: --exclude"
        );
        assert_eq!(switch(&r(Outcome::Skipped(String::new())), name), "skipped");
        assert_eq!(
            switch(&r(Outcome::NotRun), name),
            "not run: the check stopped before it"
        );
        assert_eq!(
            switch(&r(Outcome::Found(SwitchFinding::NeverChanged)), name),
            "input never changed: a broken wire, a bad switch, or the wrong pin"
        );
    }

    #[test]
    fn a_report_written_says_the_names_whole_then_the_folder() {
        use std::path::Path;
        assert_eq!(
            report_written(
                Path::new("/r/vpx-check-2026-12-02T0028Z.md"),
                Path::new("/r/vpx-check-2026-12-02T0028Z.csv")
            ),
            "Report written: vpx-check-2026-12-02T0028Z.md and .csv in /r"
        );
    }

    #[test]
    fn time_left_never_reads_less_than_there_is() {
        assert_eq!(duration(Duration::from_millis(800)), "800 ms");
        assert_eq!(duration(Duration::from_millis(1001)), "2 s");
        assert_eq!(duration(Duration::from_secs(14)), "14 s");
        assert_eq!(duration(Duration::from_secs(120)), "2 min");
        assert_eq!(duration(Duration::from_secs(90)), "1 min 30 s");
    }

    #[test]
    fn positions_have_their_units() {
        // Travel from 0 (up) to 200 (down): 100 counts are half way.
        assert_eq!(
            positions(&[100, 124, 100], Some((0, 200))),
            "50 % → 62 % → 50 % of travel"
        );
        // A sensor past an end reads as the end.
        assert_eq!(percent_of_travel((20, 220), 5), 0);
        assert_eq!(percent_of_travel((220, 20), 5), 100);
        assert_eq!(positions(&[100, 124], None), "100 → 124 counts");
        assert_eq!(positions(&[100, 124], Some((7, 7))), "100 → 124 counts");
        assert_eq!(counts(&[20]), "20 counts");
    }

    #[test]
    fn numbers_take_their_article_as_they_are_said() {
        for n in [8, 11, 18, 80, 83, 800, 8000, 11_000, 18_500] {
            assert_eq!(article(n), "an", "{n}");
        }
        for n in [1, 2, 5, 10, 15, 20, 25, 30, 110, 180, 1100, 1800, 111_000] {
            assert_eq!(article(n), "a", "{n}");
        }
        assert_eq!(
            CircuitFinding::NearBreaker {
                amps: 6.4,
                breaker: 8
            }
            .words(),
            "draws 6.4 A of an 8 A breaker (≥ 80 %): the breaker is tight and will trip \
             in flight"
        );
        assert_eq!(
            CircuitFinding::Within {
                amps: 1.0,
                breaker: 5
            }
            .words(),
            "draws 1.0 A of a 5 A breaker"
        );
        assert_eq!(count(1, "warning", "warnings"), "1 warning");
        assert_eq!(count(2, "warning", "warnings"), "2 warnings");
        assert_eq!(count(0, "warning", "warnings"), "0 warnings");
    }

    #[test]
    fn a_circuit_that_did_not_follow_is_said_without_brackets_in_brackets() {
        let name = |id: u8| format!("dev{id}");
        let w = SwitchFinding::CircuitsDidNotFollow(vec![
            (
                4,
                NotFollowed::HeldByPage {
                    on: false,
                    sent_at: None,
                    ago: Duration::from_secs(90),
                },
            ),
            (5, NotFollowed::AssignedTo(SwitchId::Input(3))),
        ])
        .words(&name);
        assert_eq!(
            w,
            "circuits did not follow: dev4 is held off by DEVICE_POWER sent from this page \
             1 min 30 s before (ICD Appendix A): flip the switch to the other position and \
             back to release it; dev5 is assigned to switch 3"
        );
        assert_eq!(
            cycle(SwitchId::Input(5)),
            "flip switch 5 to the other position and back"
        );
    }
}

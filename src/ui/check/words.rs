//! Every result of the check as a mark and plain words: the screen shows them, and the
//! headless run and the report may print the same words, so a finding reads the same
//! wherever it is seen. A mark is never shown without its word (colour is a bonus).

use std::time::Duration;

use super::state::{
    CircuitFinding, CircuitResult, Mark, MotorFinding, MotorResult, Outcome, SwitchFinding,
    SwitchResult,
};
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

/// An outcome's mark: its finding's, or skipped / not run.
pub fn switch_mark(o: &Outcome<SwitchFinding>) -> Mark {
    o.mark_with(SwitchFinding::mark)
}

pub fn circuit_mark(o: &Outcome<CircuitFinding>) -> Mark {
    o.mark_with(CircuitFinding::mark)
}

pub fn motor_mark(o: &Outcome<MotorFinding>) -> Mark {
    o.mark_with(MotorFinding::mark)
}

/// An outcome's words: the finding's own (the vocabulary's, shared with the report
/// and the headless run), or why there is none.
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

/// "57 % → 62 % → 50 % → 57 %": the positions a motor went through.
pub fn positions(p: &[u8]) -> String {
    p.iter()
        .map(|v| format!("{v} %"))
        .collect::<Vec<_>>()
        .join(" → ")
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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn time_left_never_reads_less_than_there_is() {
        assert_eq!(duration(Duration::from_millis(800)), "800 ms");
        assert_eq!(duration(Duration::from_millis(1001)), "2 s");
        assert_eq!(duration(Duration::from_secs(14)), "14 s");
        assert_eq!(duration(Duration::from_secs(120)), "2 min");
        assert_eq!(duration(Duration::from_secs(90)), "1 min 30 s");
        assert_eq!(positions(&[57, 62, 50, 57]), "57 % → 62 % → 50 % → 57 %");
    }
}

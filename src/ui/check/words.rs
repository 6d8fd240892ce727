//! Every result of the check as a mark and plain words: the screen shows them, and the
//! headless run and the report may print the same words, so a finding reads the same
//! wherever it is seen. A mark is never shown without its word (colour is a bonus).

use std::time::Duration;

use super::state::{
    CircuitFinding, CircuitResult, Input, Mark, MotorFinding, MotorResult, NotFollowed, Outcome,
    SwitchFinding, SwitchResult,
};
use crate::protocol::fault::FaultCode;
use crate::protocol::message::SwitchId;

/// The share of its breaker at which a circuit's draw is called tight (issue 14: ≥ 80 %).
pub const NEAR_BREAKER: f32 = 0.8;

/// "✓ PASS": the symbol and the word, always together.
pub fn badge(mark: Mark) -> String {
    format!("{} {}", mark.symbol(), mark.word())
}

fn outcome_mark<F>(o: &Outcome<F>, found: impl Fn(&F) -> Mark) -> Mark {
    match o {
        Outcome::Found(f) => found(f),
        Outcome::Skipped(_) => Mark::Skipped,
        Outcome::NotRun => Mark::NotRun,
    }
}

pub fn switch_mark(o: &Outcome<SwitchFinding>) -> Mark {
    outcome_mark(o, |f| match f {
        SwitchFinding::Passed => Mark::Pass,
        _ => Mark::Fail,
    })
}

pub fn circuit_mark(o: &Outcome<CircuitFinding>) -> Mark {
    outcome_mark(o, |f| match f {
        CircuitFinding::Within { .. } => Mark::Pass,
        CircuitFinding::NearBreaker { .. } => Mark::Warn,
        _ => Mark::Fail,
    })
}

pub fn motor_mark(o: &Outcome<MotorFinding>) -> Mark {
    outcome_mark(o, |f| match f {
        MotorFinding::Moves => Mark::Pass,
        MotorFinding::AgainstLimit => Mark::Warn,
        _ => Mark::Fail,
    })
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

/// A fault with Appendix E's description and action, as far as Table 43 has them.
pub fn fault(code: FaultCode) -> String {
    match code.info() {
        Some(i) if !i.description.is_empty() => {
            format!("{}: {} {}", code.name(), i.description, i.action)
        }
        _ => format!("{}: a code Appendix E does not list", code.name()),
    }
}

fn not_followed(why: &NotFollowed) -> String {
    match why {
        NotFollowed::HeldByDevicePower => "held by DEVICE_POWER until its switch is cycled".into(),
        NotFollowed::AssignedTo(s) => format!("assigned to {}", switch_id(*s)),
        NotFollowed::Faulted(code) => format!("faulted, {}", code.name()),
        NotFollowed::Unexplained => "no reason the page can see".into(),
    }
}

fn inputs(list: &[Input]) -> String {
    let labels: Vec<String> = list.iter().map(|i| i.label()).collect();
    match labels.as_slice() {
        [] => "another input".into(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

fn skipped_or_not_run<F>(o: &Outcome<F>, found: impl Fn(&F) -> String) -> String {
    match o {
        Outcome::Found(f) => found(f),
        Outcome::Skipped(why) if why.is_empty() => "skipped".into(),
        Outcome::Skipped(why) => why.clone(),
        Outcome::NotRun => "not run: the check stopped before it".into(),
    }
}

/// A switch input's result in words; `name` gives a circuit's name from its id.
pub fn switch(r: &SwitchResult, name: impl Fn(u8) -> String) -> String {
    skipped_or_not_run(&r.outcome, |f| match f {
        SwitchFinding::Passed => "the input changed, and its circuits followed".into(),
        SwitchFinding::NeverChanged => {
            "input never changed: a broken wire, a bad switch, or the wrong pin".into()
        }
        SwitchFinding::OtherChanged(others) => {
            format!("{} changed instead: switches crossed", inputs(others))
        }
        SwitchFinding::CircuitsDidNotFollow(list) => {
            let each: Vec<String> = list
                .iter()
                .map(|(id, why)| format!("{} {}", name(*id), not_followed(why)))
                .collect();
            format!("circuits did not follow: {}", each.join("; "))
        }
    })
}

/// "4.2 A of a 5 A breaker".
fn of_breaker(amps: f32, breaker: u8) -> String {
    format!("{amps:.1} A of a {breaker} A breaker")
}

pub fn circuit(r: &CircuitResult) -> String {
    skipped_or_not_run(&r.outcome, |f| match f {
        CircuitFinding::Within { amps, breaker } => {
            format!("{}, within it", of_breaker(*amps, *breaker))
        }
        CircuitFinding::NoCurrent => {
            "no current while on: an open circuit, a blown bulb, a load not connected".into()
        }
        CircuitFinding::NearBreaker { amps, breaker } => format!(
            "draws {} (≥ 80 %): the breaker is tight and will trip in flight",
            of_breaker(*amps, *breaker)
        ),
        CircuitFinding::Faulted(code) => fault(*code),
        CircuitFinding::DidNotSwitch => {
            "did not switch on: no answer, or no two fresh DEVICE_STATUS".into()
        }
    })
}

pub fn motor(r: &MotorResult) -> String {
    skipped_or_not_run(&r.outcome, |f| match f {
        MotorFinding::Moves => "moves the commanded way".into(),
        MotorFinding::Reversed => {
            "reversed: the motor's polarity is swapped, or the sensor is wired backwards".into()
        }
        MotorFinding::NoMovement => "no movement: the motor, the sensor or a limit".into(),
        MotorFinding::AgainstLimit => "runs against a limit".into(),
        MotorFinding::Faulted(code) => fault(*code),
    })
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
    fn findings_get_the_issue_words_and_their_marks() {
        let r = |outcome| SwitchResult {
            input: Input::Switch(3),
            circuits: vec![7],
            outcome,
        };
        let name = |id: u8| format!("dev{id}");
        let crossed = r(Outcome::Found(SwitchFinding::OtherChanged(vec![
            Input::Switch(4),
        ])));
        assert_eq!(
            switch(&crossed, name),
            "switch 4 changed instead: switches crossed"
        );
        assert_eq!(switch_mark(&crossed.outcome), Mark::Fail);
        let held = r(Outcome::Found(SwitchFinding::CircuitsDidNotFollow(vec![
            (7, NotFollowed::HeldByDevicePower),
            (8, NotFollowed::AssignedTo(SwitchId::Input(5))),
        ])));
        assert_eq!(
            switch(&held, name),
            "circuits did not follow: dev7 held by DEVICE_POWER until its switch is cycled; \
             dev8 assigned to switch 5"
        );
        let c = CircuitResult {
            id: 7,
            name: "Landing Lt".into(),
            pin: "10A-1",
            breaker: Some(5),
            switch: None,
            outcome: Outcome::Found(CircuitFinding::NearBreaker {
                amps: 4.4,
                breaker: 5,
            }),
        };
        assert_eq!(
            circuit(&c),
            "draws 4.4 A of a 5 A breaker (≥ 80 %): the breaker is tight and will trip in flight"
        );
        assert_eq!(circuit_mark(&c.outcome), Mark::Warn);
        let f = CircuitResult {
            outcome: Outcome::Found(CircuitFinding::Faulted(FaultCode::ShortCircuit)),
            ..c
        };
        assert_eq!(
            circuit(&f),
            "SHORT_CIRCUIT: Device short circuit. Device faulted and disabled, \
             FAULT_STATUS message broadcast."
        );
        assert_eq!(
            motor_mark(&Outcome::Found(MotorFinding::AgainstLimit)),
            Mark::Warn
        );
        assert_eq!(motor_mark(&Outcome::NotRun), Mark::NotRun);
        assert_eq!(
            motor_mark(&Outcome::<MotorFinding>::Skipped("by you".into())),
            Mark::Skipped
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

//! What the installation check shows, and what its report records: the step it is on,
//! what the person must do and what the page is watching, and every result so far.
//! Pure data and the verdicts (marks); the words for it are in [`super::words`]. The
//! flow owns it and changes it; the screen (`ui::check`) and the report
//! ([`super::report`]) only read it.

use std::time::Duration;

use super::calls::Command;
use crate::model::Motor;
use crate::protocol::fault::FaultCode;
use crate::protocol::message::{SwitchId, SwitchInputs, Tenths};

/// The check's steps, in the order they run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum Step {
    /// Before anything is powered: what will be switched on, for how long, and what
    /// is excluded; the person confirms the aircraft is safe to power them.
    #[default]
    Confirm,
    Switches,
    Circuits,
    Motors,
    Loads,
    /// The report is written; the summary and what is left to fix.
    Done,
}

impl Step {
    /// The steps a person may skip (`--skip`), with the word for each.
    pub const SKIPPABLE: [(Step, &'static str); 4] = [
        (Step::Switches, "switches"),
        (Step::Circuits, "circuits"),
        (Step::Motors, "motors"),
        (Step::Loads, "loads"),
    ];

    pub fn title(self) -> &'static str {
        match self {
            Step::Confirm => "Before power",
            Step::Switches => "Switch inputs",
            Step::Circuits => "Circuits",
            Step::Motors => "Motors",
            Step::Loads => "Load analysis",
            Step::Done => "Report",
        }
    }
}

/// A result's verdict. Never shown by colour alone: each has its symbol and word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    Pass,
    Fail,
    Warn,
    /// The person skipped it, or it was excluded.
    Skipped,
    /// The check was interrupted before it got a result.
    NotRun,
}

impl Mark {
    pub fn symbol(self) -> &'static str {
        match self {
            Mark::Pass => "✓",
            Mark::Fail => "✗",
            Mark::Warn => "⚠",
            Mark::Skipped => "–",
            Mark::NotRun => "?",
        }
    }

    pub fn word(self) -> &'static str {
        match self {
            Mark::Pass => "PASS",
            Mark::Fail => "FAIL",
            Mark::Warn => "WARN",
            Mark::Skipped => "SKIPPED",
            Mark::NotRun => "NOT RUN",
        }
    }
}

/// A switch input the check asks the person to flip: one of the ten external inputs,
/// or one of the flap and trim switch inputs of SYSTEM_STATUS byte 8 (ICD Table 24).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Input {
    /// 1–10.
    Switch(u8),
    FlapUp,
    FlapDown,
    PitchTrimUp,
    PitchTrimDown,
    RollTrimUp,
    RollTrimDown,
}

impl Input {
    /// Whether the input reads closed in a live SYSTEM_STATUS.
    pub fn is_on(self, s: &SwitchInputs) -> bool {
        match self {
            Input::Switch(n @ 1..=10) => s.switch[usize::from(n - 1)],
            Input::Switch(_) => false,
            Input::FlapUp => s.flap_up,
            Input::FlapDown => s.flap_down,
            Input::PitchTrimUp => s.pitch_trim_up,
            Input::PitchTrimDown => s.pitch_trim_down,
            Input::RollTrimUp => s.roll_trim_up,
            Input::RollTrimDown => s.roll_trim_down,
        }
    }

    pub fn label(self) -> String {
        match self {
            Input::Switch(n) => format!("switch {n}"),
            Input::FlapUp => "flap switch UP".into(),
            Input::FlapDown => "flap switch DOWN".into(),
            Input::PitchTrimUp => "pitch trim switch UP".into(),
            Input::PitchTrimDown => "pitch trim switch DOWN".into(),
            // The roll switch's UP and DOWN inputs (ICD Table 24) are left and right,
            // as the live row draws them (`roll ←`, `→`).
            Input::RollTrimUp => "roll trim switch LEFT".into(),
            Input::RollTrimDown => "roll trim switch RIGHT".into(),
        }
    }
}

/// Why a circuit did not follow its switch, as far as the page can see.
#[derive(Debug, Clone, PartialEq)]
pub enum NotFollowed {
    /// This page sent DEVICE_POWER on it (its soft keys, this check, the gateway
    /// forwarding another display's command), which the unit holds against the switch
    /// until the switch is cycled (ICD Appendix A). `sent_at` is the wall-clock time
    /// when the check knows it; `ago` is how long before the finding it was sent.
    HeldByPage {
        on: bool,
        sent_at: Option<std::time::SystemTime>,
        ago: Duration,
    },
    /// It did not follow its own input (its DEVICE_SPEC says this switch) and no
    /// DEVICE_POWER from this page holds it: another display may hold it.
    NotHeldByPage,
    /// The freshest DEVICE_SPEC the page has assigns it to another switch (or always
    /// on / off).
    AssignedTo(SwitchId),
    /// It changed when this other input changed during the step, not with this one.
    FollowedOther(Input),
    /// It faulted when switched.
    Faulted(FaultCode),
    /// The page could not see it: no live DEVICE_STATUS while the input was flipped.
    Unexplained,
}

/// Step 2's result for one input.
#[derive(Debug, Clone, PartialEq)]
pub enum SwitchFinding {
    /// The input changed, and its circuits followed.
    Passed,
    /// The input changed; no circuit is assigned to it (a flap or trim switch: its
    /// motor is the motors step's), so nothing else was there to see.
    Changed,
    /// "input never changed": a broken wire, a bad switch, or the wrong pin.
    NeverChanged,
    /// "input M changed instead": switches crossed.
    OtherChanged(Vec<Input>),
    /// "circuits did not follow", each with the reason.
    CircuitsDidNotFollow(Vec<(u8, NotFollowed)>),
}

/// The share of its breaker, in percent, at which a circuit's draw is called tight
/// (80 % and over).
pub const NEAR_BREAKER_PERCENT: u16 = 80;

/// What a circuit's current is against its breaker. Judged on the unit's own tenths
/// of an amp (ICD Table 26), in integers: in `f32`, 80 % of a 9 A breaker is
/// 7.2000003 while 72 tenths are 7.1999998, so a draw of exactly 80 % of a 9, 13, 18,
/// 21 or 26 A breaker would read as "within". The flow's finding and the screen's bar
/// both come from here, so they cannot disagree.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BreakerLoad {
    Within,
    /// At or above [`NEAR_BREAKER_PERCENT`], up to the breaker's rating.
    Tight,
    /// More than the breaker's rating.
    Over,
}

impl BreakerLoad {
    pub fn of(current: Tenths, breaker: u8) -> BreakerLoad {
        // tenths × 100 against percent × amps × 10, in u32: no rounding anywhere.
        let tenths = u32::from(current.0) * 100;
        let rating = u32::from(breaker) * 10;
        if breaker == 0 || tenths > rating * 100 {
            BreakerLoad::Over
        } else if tenths >= rating * u32::from(NEAR_BREAKER_PERCENT) {
            BreakerLoad::Tight
        } else {
            BreakerLoad::Within
        }
    }
}

/// Step 3's result for one circuit.
#[derive(Debug, Clone, PartialEq)]
pub enum CircuitFinding {
    /// A current within the breaker.
    Within { amps: f32, breaker: u8 },
    /// "no current while on": an open circuit, a blown bulb, a load not connected.
    NoCurrent,
    /// "draws X A of a Y A breaker (≥ 80 %)": will trip in flight.
    NearBreaker { amps: f32, breaker: u8 },
    /// The circuit faulted; the report gives the Appendix E action.
    Faulted(FaultCode),
    /// The unit never showed it on (no answer, or two fresh DEVICE_STATUS never came).
    DidNotSwitch,
}

/// Step 4's result for one motor.
#[derive(Debug, Clone, PartialEq)]
pub enum MotorFinding {
    /// It moves the commanded way.
    Moves,
    /// The motor's polarity is swapped, or the sensor is wired backwards.
    Reversed,
    /// The motor, the sensor or a limit.
    NoMovement,
    /// It runs against a limit.
    AgainstLimit,
    Faulted(FaultCode),
}

/// What became of one item: its finding, or why there is none.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome<F> {
    Found(F),
    /// Skipped by the person, excluded, or the step was skipped; the words say which.
    Skipped(String),
    /// The check stopped before this item got a result.
    NotRun,
}

/// One switch input's line in the results.
#[derive(Debug, Clone, PartialEq)]
pub struct SwitchResult {
    pub input: Input,
    /// The circuits assigned to it (device ids).
    pub circuits: Vec<u8>,
    pub outcome: Outcome<SwitchFinding>,
}

/// One circuit's line in the results.
#[derive(Debug, Clone, PartialEq)]
pub struct CircuitResult {
    pub id: u8,
    pub name: String,
    pub pin: &'static str,
    pub breaker: Option<u8>,
    pub switch: Option<SwitchId>,
    pub outcome: Outcome<CircuitFinding>,
}

/// One motor's line in the results, with the positions it went through.
#[derive(Debug, Clone, PartialEq)]
pub struct MotorResult {
    pub motor: Motor,
    /// Position (raw FLAP_TRIM_STATUS counts, 0–255) before, after the first
    /// direction, after the second, and after it was run back, as far as the step got.
    pub positions: Vec<u8>,
    pub outcome: Outcome<MotorFinding>,
}

/// What the person must do now, and what the page watches meanwhile.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Prompt {
    /// Plain words: "Flip switch 3 on, then off."
    pub todo: String,
    /// "Watching switch 3 and Landing Light, Taxi Light."
    pub watching: String,
    /// Time left before the item times out, if it can.
    pub time_left: Option<Duration>,
    /// The keys that act now, with their words: ("Enter", "confirm"), ("s", "skip").
    pub keys: Vec<(&'static str, &'static str)>,
}

/// How the check ended, if it did not finish.
#[derive(Debug, Clone, PartialEq)]
pub struct Interruption {
    /// "quit", "communication lost", "the link failed: …", "Landing Light faulted".
    pub cause: String,
    /// Each circuit (or motor) the check left not as it found it.
    pub left: Vec<LeftBehind>,
}

/// A circuit or motor the check left not as it found it, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct LeftBehind {
    /// Its device id.
    pub id: u8,
    pub name: String,
    /// In words, the state it was left in: "ON, held by DEVICE_POWER", "unknown: no
    /// answer", "stopped at position 40, it was at 20: not run back".
    pub state: String,
}

impl LeftBehind {
    pub fn new(id: u8, name: String, state: String) -> LeftBehind {
        LeftBehind { id, name, state }
    }
}

/// A circuit the check will switch on, and for how long.
#[derive(Debug, Clone, PartialEq)]
pub struct Planned {
    pub id: u8,
    pub name: String,
    pub pin: &'static str,
    pub breaker: Option<u8>,
    pub switch: Option<SwitchId>,
    pub on_for: Duration,
}

/// A circuit the check leaves alone, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Excluded {
    pub id: u8,
    pub name: String,
    /// The VP-X pin, its breaker and its switch, as for a planned circuit: the report
    /// lists every circuit with them, the ones left alone too.
    pub pin: &'static str,
    pub breaker: Option<u8>,
    pub switch: Option<SwitchId>,
    /// "never touched: the starter", "suggested: the name has \"pitot\"", "--exclude".
    pub why: String,
    /// Only a suggested exclusion may be taken back by the person.
    pub may_include: bool,
}

/// A switch input the check will not ask the person to flip: flipping it would power
/// a circuit the check leaves alone (excluded, the starter, an alternator field), or
/// drive an excluded motor. The plan decides it; the confirm screen shows it and the
/// input's result carries `why` as its skip reason.
#[derive(Debug, Clone, PartialEq)]
pub struct Unasked {
    pub input: Input,
    /// Every circuit on the input (device ids), planned or not.
    pub circuits: Vec<u8>,
    /// "switch 4 also powers Pitot Heat (excluded): not asked".
    pub why: String,
}

/// The whole check as the screen and the report see it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CheckView {
    pub step: Step,
    /// Steps the person chose to skip (`--skip`, or on the screen).
    pub skipped_steps: Vec<Step>,
    pub plan: Vec<Planned>,
    pub planned_motors: Vec<(Motor, Duration)>,
    pub excluded: Vec<Excluded>,
    /// Switch inputs the person will not be asked to flip, and why.
    pub unasked: Vec<Unasked>,
    pub prompt: Option<Prompt>,
    /// The item under test now: an index into the current step's results. Before
    /// power (`Step::Confirm`), the selected row: an index into `plan`, then
    /// `excluded` (`plan.len() + i`). Every item has its line in the results from the
    /// confirmation on; one not reached yet (or under test) is `Outcome::NotRun`.
    pub current: Option<usize>,
    pub switches: Vec<SwitchResult>,
    pub circuits: Vec<CircuitResult>,
    pub motors: Vec<MotorResult>,
    /// Circuits put back by DEVICE_POWER, which stay held by the page until their
    /// switch is flipped (ICD Appendix A): id, name, and the switch to flip.
    pub to_cycle: Vec<(u8, String, SwitchId)>,
    /// One line of news: "Landing Light: 4.2 A", "report written to …".
    pub message: Option<String>,
    pub interrupted: Option<Interruption>,
    /// Where the report went, once written.
    pub report: Option<std::path::PathBuf>,
    /// Why the report could not be written (the folder and the system's error): the
    /// results are still here, and `w` writes them again.
    pub report_error: Option<String>,
    /// Once the check has ended: the results scrolled this many lines down (the app
    /// keeps it within the list, `ui::check::results_scroll_max`).
    pub scroll: usize,
    /// Once the check has ended: the load analysis (table, bar chart, circuits)
    /// shown instead of the results (`l`).
    pub show_loads: bool,
    /// Step 5, once reached: the load analysis, or why there is none.
    pub loads: Option<LoadsView>,
    /// Step 5, with the load file read: each circuit's wire against its breaker and
    /// the current measured (`crate::loads::wiring`).
    pub wires: Option<WiresView>,
    /// What the person saw of each light while the check had it on ("Is it lit?").
    pub lit: Vec<LitAnswer>,
    /// The aircraft's last check (from the logbook, handed in by the app), for each
    /// circuit's current beside the last one ([`CheckView::trend`]).
    pub last_check: Option<super::trend::LastCheck>,
}

/// "Is it lit?" for a light (`super::lights`): what the person said, and what ended
/// the question.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LitAnswer {
    /// The circuit's device id.
    pub id: u8,
    /// Seen lit (`true`) or dark; `None`: not answered.
    pub lit: Option<bool>,
    pub ended: LitEnd,
    /// The check switched it on (so it went back off when the question ended); else
    /// it was on by its switch and left so.
    pub switched: bool,
}

/// What ended "Is it lit?": the light was held on until then.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LitEnd {
    /// The person's answer.
    Answer,
    /// No answer within the cap ([`super::Timing::lit_for`]), or, for a light on by
    /// its switch (not held), while it was measured.
    Cap(std::time::Duration),
    /// The person went on (s) without answering.
    Skipped,
    /// Nobody could answer (standard input ended): not held for one.
    NobodyToAnswer,
}

/// An answer the prompt offers now, as plain data for any front end (the page's
/// keys, the phone remote): its id ("go_on", "skip", "retry", "lit_yes", "lit_no"),
/// the page's key for it, its words, and the command it gives the flow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Answer {
    pub id: &'static str,
    pub key: &'static str,
    pub words: &'static str,
    pub command: Command,
}

/// Step 5's result: the load analysis of the builder's file, or why there is none.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadsView {
    /// The builder's file (its path), analysed with the check's measured currents
    /// ([`CheckView::measured_amps`]).
    Analysed {
        path: std::path::PathBuf,
        analysis: crate::loads::Analysis,
    },
    /// There was no file: the template was written here, for the builder to fill in
    /// before the next check.
    TemplateWritten(std::path::PathBuf),
    /// The file could not be used: every problem, one a line, each with its path,
    /// line, field and what is wrong, in words.
    Refused(String),
}

/// The wires of the load file held against the unit's breakers and the check's
/// currents: an unprotected wire is a failure, a drop over the limit a warning.
#[derive(Debug, Clone, PartialEq)]
pub struct WiresView {
    pub rows: Vec<crate::loads::wiring::Row>,
    pub system: Option<crate::loads::wire::SystemVoltage>,
}

impl WiresView {
    /// One mark per circuit with a wire entered.
    pub fn marks(&self) -> impl Iterator<Item = Mark> + '_ {
        use crate::loads::wiring::Verdict;
        self.rows.iter().filter_map(|r| match r.verdict {
            Verdict::Unprotected => Some(Mark::Fail),
            Verdict::Drop => Some(Mark::Warn),
            Verdict::Ok => Some(Mark::Pass),
            Verdict::NotEntered => None,
        })
    }
}

impl Mark {
    /// The mark a load-analysis phase is shown with.
    pub fn of(level: crate::loads::Level) -> Mark {
        match level {
            crate::loads::Level::Ok => Mark::Pass,
            crate::loads::Level::Warn => Mark::Warn,
            crate::loads::Level::Fail => Mark::Fail,
        }
    }
}

impl CheckView {
    /// The answers the prompt offers now (see [`Answer`]): the prompt's own keys,
    /// those a person away from the keyboard can give. Stopping the check and
    /// skipping a whole step stay with the keyboard.
    pub fn prompt_answers(&self) -> Vec<Answer> {
        let Some(p) = &self.prompt else {
            return Vec::new();
        };
        p.keys
            .iter()
            .filter_map(|&(key, words)| {
                // The id by the prompt's words, the command by its key: the same key
                // means "go on" in one prompt and "retry" in another (`r`).
                let id = match words {
                    "go on" | "confirm" => "go_on",
                    "skip" => "skip",
                    "retry" => "retry",
                    "lit" => "lit_yes",
                    "not lit" => "lit_no",
                    _ => return None,
                };
                let command = match key {
                    "Enter" => Command::Enter,
                    "s" => Command::SkipItem,
                    "r" => Command::Retry,
                    "y" => Command::Lit(true),
                    "n" => Command::Lit(false),
                    _ => return None,
                };
                Some(Answer {
                    id,
                    key,
                    words,
                    command,
                })
            })
            .collect()
    }

    /// What the person said of light `id`, if asked and answered.
    pub fn lit_of(&self, id: u8) -> Option<bool> {
        self.lit.iter().find(|l| l.id == id).and_then(|l| l.lit)
    }

    /// "Is it lit?" for light `id`, if it was asked.
    pub fn lit_answer(&self, id: u8) -> Option<LitAnswer> {
        self.lit.iter().find(|l| l.id == id).copied()
    }

    /// Circuit result `c`'s current against the last check's. A current is known
    /// when the circuit was measured: "no current while on" is 0 A, a circuit that
    /// faulted or did not switch has none.
    pub fn trend(&self, c: &CircuitResult) -> super::trend::Trend {
        super::trend::trend(self.last_check.as_ref(), c.pin, &c.name, c.tenths())
    }

    /// The currents step 3 measured, for the load analysis: device id and amperes.
    /// Only a real reading counts: "no current while on" is a fault to fix, not the
    /// circuit's load, and a faulted circuit gave none.
    pub fn measured_amps(&self) -> Vec<(u8, f32)> {
        self.circuits
            .iter()
            .filter_map(|c| match c.outcome {
                Outcome::Found(CircuitFinding::Within { amps, .. })
                | Outcome::Found(CircuitFinding::NearBreaker { amps, .. }) => Some((c.id, amps)),
                _ => None,
            })
            .collect()
    }
}

impl CheckView {
    /// Marks each of `step`'s rows not run yet as skipped with `why`: whether any was.
    pub fn skip_rest(&mut self, step: Step, why: &str) -> bool {
        fn skip<'a, F: 'a>(outcomes: impl Iterator<Item = &'a mut Outcome<F>>, why: &str) -> bool {
            let mut any = false;
            for o in outcomes.filter(|o| matches!(o, Outcome::NotRun)) {
                *o = Outcome::Skipped(why.into());
                any = true;
            }
            any
        }
        match step {
            Step::Switches => skip(self.switches.iter_mut().map(|r| &mut r.outcome), why),
            Step::Circuits => skip(self.circuits.iter_mut().map(|r| &mut r.outcome), why),
            Step::Motors => skip(self.motors.iter_mut().map(|r| &mut r.outcome), why),
            _ => false,
        }
    }

    /// The first of `step`'s rows from `from` on that has not run yet.
    pub fn next_not_run(&self, step: Step, from: usize) -> Option<usize> {
        let rows: Vec<bool> = match step {
            Step::Switches => self
                .switches
                .iter()
                .map(|r| r.outcome == Outcome::NotRun)
                .collect(),
            Step::Circuits => self
                .circuits
                .iter()
                .map(|r| r.outcome == Outcome::NotRun)
                .collect(),
            Step::Motors => self
                .motors
                .iter()
                .map(|r| r.outcome == Outcome::NotRun)
                .collect(),
            _ => Vec::new(),
        };
        (from..rows.len()).find(|&i| rows[i])
    }
}

impl SwitchFinding {
    pub fn mark(&self) -> Mark {
        match self {
            SwitchFinding::Passed | SwitchFinding::Changed => Mark::Pass,
            _ => Mark::Fail,
        }
    }
}

impl CircuitFinding {
    pub fn mark(&self) -> Mark {
        match self {
            CircuitFinding::Within { .. } => Mark::Pass,
            CircuitFinding::NearBreaker { .. } => Mark::Warn,
            _ => Mark::Fail,
        }
    }
}

impl MotorFinding {
    pub fn mark(&self) -> Mark {
        match self {
            MotorFinding::Moves => Mark::Pass,
            MotorFinding::AgainstLimit => Mark::Warn,
            _ => Mark::Fail,
        }
    }
}

impl<F> Outcome<F> {
    /// The mark, given the finding's own.
    pub fn mark_with(&self, mark: impl Fn(&F) -> Mark) -> Mark {
        match self {
            Outcome::Found(f) => mark(f),
            Outcome::Skipped(_) => Mark::Skipped,
            Outcome::NotRun => Mark::NotRun,
        }
    }
}

impl SwitchResult {
    pub fn mark(&self) -> Mark {
        self.outcome.mark_with(SwitchFinding::mark)
    }
}

impl CircuitResult {
    pub fn mark(&self) -> Mark {
        self.outcome.mark_with(CircuitFinding::mark)
    }

    /// The current measured, in the unit's tenths: 0 for "no current while on";
    /// `None` when the circuit gave no reading.
    pub fn tenths(&self) -> Option<u16> {
        match &self.outcome {
            Outcome::Found(CircuitFinding::Within { amps, .. })
            | Outcome::Found(CircuitFinding::NearBreaker { amps, .. }) => {
                Some(super::trend::tenths(*amps))
            }
            Outcome::Found(CircuitFinding::NoCurrent) => Some(0),
            _ => None,
        }
    }
}

impl MotorResult {
    pub fn mark(&self) -> Mark {
        self.outcome.mark_with(MotorFinding::mark)
    }
}

impl CheckView {
    /// Every result's mark, switches then circuits then motors.
    pub fn marks(&self) -> impl Iterator<Item = Mark> + '_ {
        self.switches
            .iter()
            .map(SwitchResult::mark)
            .chain(self.circuits.iter().map(CircuitResult::mark))
            .chain(self.motors.iter().map(MotorResult::mark))
            .chain(self.wires.iter().flat_map(WiresView::marks))
    }

    /// Whether anything failed (a warning is not a failure).
    pub fn any_failed(&self) -> bool {
        self.marks().any(|m| m == Mark::Fail)
    }

    /// A circuit's name by id, from the results or the plan.
    pub fn name_of(&self, id: u8) -> String {
        self.circuits
            .iter()
            .find(|c| c.id == id)
            .map(|c| c.name.clone())
            .or_else(|| {
                self.plan
                    .iter()
                    .find(|p| p.id == id)
                    .map(|p| p.name.clone())
            })
            .or_else(|| {
                self.excluded
                    .iter()
                    .find(|e| e.id == id)
                    .map(|e| e.name.clone())
            })
            .unwrap_or_else(|| format!("device {id}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exactly 80 % of every breaker size from 1 to 30 A is tight, one tenth less is
    /// within, one tenth over the rating is over (worked by hand: 80 % of 9 A is 7.2 A,
    /// 72 tenths).
    #[test]
    fn a_draw_of_exactly_80_percent_is_tight_for_every_breaker() {
        assert_eq!(BreakerLoad::of(Tenths(72), 9), BreakerLoad::Tight);
        assert_eq!(BreakerLoad::of(Tenths(71), 9), BreakerLoad::Within);
        assert_eq!(BreakerLoad::of(Tenths(90), 9), BreakerLoad::Tight);
        assert_eq!(BreakerLoad::of(Tenths(91), 9), BreakerLoad::Over);
        for b in 1..=30u8 {
            let at = u16::from(b) * 8;
            assert_eq!(BreakerLoad::of(Tenths(at), b), BreakerLoad::Tight, "{b} A");
            assert_eq!(
                BreakerLoad::of(Tenths(at - 1), b),
                BreakerLoad::Within,
                "{b} A"
            );
            let rating = u16::from(b) * 10;
            assert_eq!(
                BreakerLoad::of(Tenths(rating), b),
                BreakerLoad::Tight,
                "{b} A"
            );
            assert_eq!(
                BreakerLoad::of(Tenths(rating + 1), b),
                BreakerLoad::Over,
                "{b} A"
            );
        }
        // A 0 A breaker: any current is over it.
        assert_eq!(BreakerLoad::of(Tenths(1), 0), BreakerLoad::Over);
    }

    fn circuit(id: u8, outcome: Outcome<CircuitFinding>) -> CircuitResult {
        CircuitResult {
            id,
            name: format!("c{id}"),
            pin: "?",
            breaker: Some(5),
            switch: None,
            outcome,
        }
    }

    #[test]
    fn only_real_readings_are_measurements() {
        let view = CheckView {
            circuits: vec![
                circuit(
                    4,
                    Outcome::Found(CircuitFinding::Within {
                        amps: 1.5,
                        breaker: 5,
                    }),
                ),
                circuit(5, Outcome::Found(CircuitFinding::NoCurrent)),
                circuit(
                    6,
                    Outcome::Found(CircuitFinding::NearBreaker {
                        amps: 4.5,
                        breaker: 5,
                    }),
                ),
                circuit(7, Outcome::Found(CircuitFinding::DidNotSwitch)),
                circuit(8, Outcome::Skipped("excluded".into())),
                circuit(9, Outcome::NotRun),
            ],
            ..CheckView::default()
        };
        assert_eq!(view.measured_amps(), [(4, 1.5), (6, 4.5)]);
    }
}

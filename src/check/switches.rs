//! Step 2, switch inputs: the person flips each input on and off; the page watches
//! the live inputs (SYSTEM_STATUS bytes 8–9, ICD Table 24) and the circuits assigned
//! to it (DEVICE_STATUS, Table 26).
//!
//! An input passes when it changed and each of its circuits changed with it. Both
//! broadcasts come once a second, so the prompt asks the person to wait for the
//! circuits before flipping back, and the circuits get [`Timing::follow_wait`] from
//! the input's first change. Another input changing and changing back while the one
//! asked for never did is a crossed pair, said at once. Nothing at all by
//! [`Timing::switch_timeout`] is "never changed"; the person may retry.
//!
//! [`Timing::follow_wait`]: super::flow::Timing::follow_wait
//! [`Timing::switch_timeout`]: super::flow::Timing::switch_timeout

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use super::calls::Command;
use super::plan;
use super::state::{CheckView, Input, NotFollowed, Outcome, Prompt, SwitchFinding, SwitchResult};
use super::step::{Call, CallContext, Item, Next, StepRun, Stopped, circuit_on, result_line};
use crate::control::StopReason;
use crate::model::{CircuitState, Hold, Model, Motor, TrimKind};
use crate::protocol::message::{SwitchId, SwitchInputs};

/// Every input SYSTEM_STATUS reports, for spotting one that changed instead.
const ALL_INPUTS: [Input; 16] = [
    Input::Switch(1),
    Input::Switch(2),
    Input::Switch(3),
    Input::Switch(4),
    Input::Switch(5),
    Input::Switch(6),
    Input::Switch(7),
    Input::Switch(8),
    Input::Switch(9),
    Input::Switch(10),
    Input::FlapUp,
    Input::FlapDown,
    Input::PitchTrimUp,
    Input::PitchTrimDown,
    Input::RollTrimUp,
    Input::RollTrimDown,
];

/// One line per input: the inputs 1–10 with circuits assigned, then the flap and
/// trim inputs of the motors the plan runs or excludes. An input the plan does not
/// ask for (it would power a circuit left alone, `plan::unasked`) is skipped with
/// the plan's words, before anything is asked.
pub(super) fn rows(view: &CheckView, model: &Model, now: Instant) -> Vec<SwitchResult> {
    let circuits = model.circuits(now);
    let unasked = |input: Input| view.unasked.iter().find(|u| u.input == input);
    let mut out = Vec::new();
    for n in 1..=10u8 {
        let on = plan::on_input(&circuits, n);
        if on.is_empty() {
            continue;
        }
        let input = Input::Switch(n);
        out.push(match unasked(input) {
            Some(u) => SwitchResult {
                input,
                circuits: u.circuits.clone(),
                outcome: Outcome::Skipped(u.why.clone()),
            },
            None => SwitchResult {
                input,
                circuits: on.iter().map(|c| c.id).collect(),
                outcome: Outcome::NotRun,
            },
        });
    }
    let planned = |m: Motor| view.planned_motors.iter().any(|(p, _)| *p == m);
    for motor in [
        Motor::Flaps,
        Motor::Trim(TrimKind::Pitch),
        Motor::Trim(TrimKind::Roll),
    ] {
        let inputs = match motor {
            Motor::Flaps => [Input::FlapUp, Input::FlapDown],
            Motor::Trim(TrimKind::Pitch) => [Input::PitchTrimUp, Input::PitchTrimDown],
            Motor::Trim(TrimKind::Roll) => [Input::RollTrimUp, Input::RollTrimDown],
        };
        for input in inputs {
            let outcome = match unasked(input) {
                Some(u) => Outcome::Skipped(u.why.clone()),
                None if planned(motor) => Outcome::NotRun,
                None => continue,
            };
            out.push(SwitchResult {
                input,
                circuits: Vec::new(),
                outcome,
            });
        }
    }
    out
}

/// The input under test.
#[derive(Debug, Clone)]
pub(super) struct SwitchItem {
    pub idx: usize,
    input: Input,
    circuits: Vec<u8>,
    deadline: Instant,
    /// The inputs and the circuits as they were when the item started.
    base: Option<(SwitchInputs, Vec<(u8, bool)>)>,
    changed_at: Option<Instant>,
    returned: bool,
    followed: BTreeSet<u8>,
    /// Circuits seen changed while another input (the first here) was away from
    /// where it started and this one was not: the circuit follows that input.
    moved_with: BTreeMap<u8, Input>,
    /// DEVICE_POWER holds of this page seen on the circuits during the item (the
    /// model's, `model::hold`), the latest of each.
    holds: BTreeMap<u8, Hold>,
    /// Other inputs that changed, and whether each changed back.
    others: Vec<(Input, bool)>,
    /// Timed out with its finding recorded: waiting for retry or go on.
    timed_out: bool,
    follow_wait: std::time::Duration,
}

impl Item for SwitchItem {
    fn deadline(&self) -> Option<Instant> {
        if self.timed_out {
            return None;
        }
        let follow = self.changed_at.map(|at| at + self.follow_wait);
        Some(follow.map_or(self.deadline, |d| d.min(self.deadline)))
    }

    fn under_test(&self) -> Vec<u8> {
        self.circuits.clone()
    }

    #[cfg(test)]
    fn stage(&self) -> &'static str {
        match (self.timed_out, self.changed_at.is_some()) {
            (true, _) => "timed out",
            (false, true) => "input changed",
            (false, false) => "waiting for the flip",
        }
    }
}

/// The input changed: did its circuits follow, and if not, why, from what the page
/// saw: a fault; the freshest DEVICE_SPEC naming another switch; the circuit changing
/// with another input during the item; a DEVICE_POWER hold this page sent; and
/// otherwise a state that did not follow its own input with no hold of this page
/// known (another display's, which the page cannot see). `wall` gives the time of
/// day of an instant, when the check has a clock.
fn follow_finding(
    item: &SwitchItem,
    model: &Model,
    now: Instant,
    wall: &dyn Fn(Instant) -> Option<std::time::SystemTime>,
) -> SwitchFinding {
    let circuits = model.circuits(now);
    let live = model.live_devices(now).is_some();
    let missing: Vec<(u8, NotFollowed)> = item
        .circuits
        .iter()
        .filter(|id| !item.followed.contains(id))
        .map(|&id| {
            let c = circuits.iter().find(|c| c.id == id);
            let why = match c.map(|c| (c.state, c.switch)) {
                Some((CircuitState::Fault(code) | CircuitState::ResetSent(code), _)) => {
                    NotFollowed::Faulted(code)
                }
                Some((_, Some(s))) if Some(s) != input_switch(item.input) => {
                    NotFollowed::AssignedTo(s)
                }
                _ if item.moved_with.contains_key(&id) => {
                    NotFollowed::FollowedOther(item.moved_with[&id])
                }
                _ if item.holds.contains_key(&id) => {
                    let h = item.holds[&id];
                    NotFollowed::HeldByPage {
                        on: h.on,
                        sent_at: wall(h.at),
                        ago: now.saturating_duration_since(h.at),
                    }
                }
                _ if live && item.base.is_some() => NotFollowed::NotHeldByPage,
                _ => NotFollowed::Unexplained,
            };
            (id, why)
        })
        .collect();
    if missing.is_empty() && item.circuits.is_empty() {
        SwitchFinding::Changed
    } else if missing.is_empty() {
        SwitchFinding::Passed
    } else {
        SwitchFinding::CircuitsDidNotFollow(missing)
    }
}

fn input_switch(input: Input) -> Option<SwitchId> {
    match input {
        Input::Switch(n) => Some(SwitchId::Input(n)),
        _ => None,
    }
}

fn record(view: &mut CheckView, idx: usize, f: SwitchFinding, cx: &mut CallContext) {
    let name_of = |id| view.name_of(id);
    let words = f.words(&name_of);
    let mark = f.mark();
    let label = view.switches[idx].input.label();
    cx.out.progress.push(result_line(mark, &label, &words));
    view.message = Some(format!("{label}: {words}"));
    view.switches[idx].outcome = Outcome::Found(f);
}

/// Step 2: the switch inputs, one at a time.
#[derive(Debug, Default)]
pub(super) struct Switches {
    item: Option<SwitchItem>,
}

impl StepRun for Switches {
    fn says_skip_midway(&self) -> bool {
        false
    }

    /// What will not be asked, and why, before the first thing that is.
    fn begin(&mut self, c: &mut Call) {
        for u in &c.view.unasked {
            c.cx.out.progress.push(format!("– {}", u.why));
        }
    }

    fn start(&mut self, idx: usize, c: &mut Call) -> Next {
        let row = &mut c.view.switches[idx];
        row.outcome = Outcome::NotRun;
        let item = SwitchItem {
            idx,
            input: row.input,
            circuits: row.circuits.clone(),
            deadline: c.cx.now + c.shared.timing.switch_timeout,
            base: None,
            changed_at: None,
            returned: false,
            followed: BTreeSet::new(),
            moved_with: BTreeMap::new(),
            holds: BTreeMap::new(),
            others: Vec::new(),
            timed_out: false,
            follow_wait: c.shared.timing.follow_wait,
        };
        let names: Vec<String> = item.circuits.iter().map(|&i| c.view.name_of(i)).collect();
        let label = item.input.label();
        c.view.prompt = Some(Prompt {
            todo: if names.is_empty() {
                format!("Move the {label} on, then back off.")
            } else {
                format!("Flip {label} on, wait until its circuits show ON, then flip it off.")
            },
            watching: if names.is_empty() {
                format!("{label} (SYSTEM_STATUS)")
            } else {
                format!("{label} and {}", names.join(", "))
            },
            time_left: Some(c.shared.timing.switch_timeout),
            keys: vec![("s", "skip"), ("S", "skip step"), ("Esc", "stop")],
        });
        c.cx.out.progress.push(format!(
            "Switch inputs: {} (you have {} s)",
            c.view.prompt.as_ref().map_or("", |p| p.todo.as_str()),
            c.shared.timing.switch_timeout.as_secs()
        ));
        self.item = Some(item);
        self.tick(c)
    }

    fn tick(&mut self, c: &mut Call) -> Next {
        let wall = |at| c.shared.wall(at);
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        if item.timed_out {
            return Next::Stay;
        }
        let now = c.cx.now;
        let Some(sys) = c.cx.model.live_system(now) else {
            return Next::Stay;
        };
        let cur = sys.switches;
        let Some((base, base_on)) = &item.base else {
            let on = item
                .circuits
                .iter()
                .map(|&id| (id, circuit_on(c.cx.model, now, id).unwrap_or(false)))
                .collect();
            item.base = Some((cur, on));
            return Next::Stay;
        };
        if item.input.is_on(&cur) != item.input.is_on(base) {
            item.changed_at.get_or_insert(now);
        } else if item.changed_at.is_some() {
            item.returned = true;
        }
        for other in ALL_INPUTS.into_iter().filter(|&i| i != item.input) {
            let differs = other.is_on(&cur) != other.is_on(base);
            match item.others.iter_mut().find(|(i, _)| *i == other) {
                Some((_, back)) if !differs => *back = true,
                Some(_) => {}
                None if differs => item.others.push((other, false)),
                None => {}
            }
        }
        // Which input a circuit's change belongs to: this one, when it is away from
        // where it started (whatever else is); another, when that one is away and this
        // one is not. A circuit seen changed before its input's SYSTEM_STATUS (the two
        // broadcasts need not come together) counts once the input shows changed.
        let this_away = item.input.is_on(&cur) != item.input.is_on(base);
        let other_away = ALL_INPUTS
            .into_iter()
            .find(|&i| i != item.input && i.is_on(&cur) != i.is_on(base));
        for (id, was) in base_on {
            if let Some(h) = c.cx.model.hold(*id) {
                item.holds.insert(*id, h);
            }
            if circuit_on(c.cx.model, now, *id).is_none_or(|on| on == *was) {
                continue;
            }
            match (this_away, other_away) {
                (true, _) => {
                    item.followed.insert(*id);
                }
                (false, Some(other)) => {
                    item.moved_with.entry(*id).or_insert(other);
                }
                (false, None) => {}
            }
        }
        if let Some(p) = c.view.prompt.as_mut() {
            p.time_left = Some(item.deadline.saturating_duration_since(now));
        }
        let all_followed = item.followed.len() == item.circuits.len();
        let finding = match item.changed_at {
            Some(at)
                if item.returned && (all_followed || now >= at + c.shared.timing.follow_wait) =>
            {
                Some(follow_finding(item, c.cx.model, now, &wall))
            }
            None if item.others.iter().any(|(_, back)| *back) => Some(SwitchFinding::OtherChanged(
                item.others.iter().map(|(i, _)| *i).collect(),
            )),
            _ => None,
        };
        if let Some(f) = finding {
            let idx = item.idx;
            record(c.view, idx, f, c.cx);
            return Next::From(idx + 1);
        }
        if now >= item.deadline {
            let f = if item.changed_at.is_some() {
                follow_finding(item, c.cx.model, now, &wall)
            } else if !item.others.is_empty() {
                SwitchFinding::OtherChanged(item.others.iter().map(|(i, _)| *i).collect())
            } else {
                SwitchFinding::NeverChanged
            };
            item.timed_out = true;
            let idx = item.idx;
            let label = item.input.label();
            record(c.view, idx, f, c.cx);
            c.view.prompt = Some(Prompt {
                todo: format!("Time is up for {label}. r: try it again; Enter: go on to the next."),
                watching: String::new(),
                time_left: None,
                keys: vec![
                    ("r", "retry"),
                    ("Enter", "next"),
                    ("S", "skip step"),
                    ("Esc", "stop"),
                ],
            });
            c.cx.out
                .progress
                .push(format!("  {label}: time is up (r: retry, Enter: next)"));
        }
        Next::Stay
    }

    fn command(&mut self, cmd: Command, c: &mut Call) -> Next {
        let Some(item) = &self.item else {
            return Next::Stay;
        };
        let (idx, timed_out) = (item.idx, item.timed_out);
        match cmd {
            Command::SkipItem => {
                c.view.switches[idx].outcome = Outcome::Skipped("you skipped it".into());
                c.cx.out
                    .progress
                    .push(format!("– {}: skipped", c.view.switches[idx].input.label()));
                Next::From(idx + 1)
            }
            Command::Retry => self.start(idx, c),
            Command::Enter if timed_out => Next::From(idx + 1),
            _ => Next::Stay,
        }
    }

    /// Nothing of a switch input is powered by the check: nothing to stop.
    fn stop(&mut self, _reason: StopReason, _view: &CheckView, _io: &mut CallContext) -> Stopped {
        Stopped::default()
    }

    fn item(&self) -> Option<&dyn Item> {
        self.item.as_ref().map(|i| i as &dyn Item)
    }
}

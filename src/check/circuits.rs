//! Step 3, circuits: each planned circuit switched on by DEVICE_POWER (ICD §6.4.1),
//! its current read from the second DEVICE_STATUS (Table 26) heard after the command,
//! then switched back off.
//!
//! DEVICE_POWER has no answer of its own; the unit's DEVICE_STATUS showing the new
//! state is the answer, so the request is judged by an [`exchange::Try`] on that.
//! The second fresh broadcast, not the first: the first may have been made before the
//! unit acted on the command, or in the load's inrush. A circuit already on (its
//! switch is on) is measured as it is and nothing is sent, so nothing of it is held.
//! A circuit put back by DEVICE_POWER stays held by the unit until its switch is
//! cycled (ICD Appendix A): it goes on the list of switches to cycle.
//!
//! [`exchange::Try`]: crate::exchange::Try

use std::time::Instant;

use super::calls::Command;
use super::lights;
use super::state::{
    BreakerLoad, CheckView, CircuitFinding, CircuitResult, LeftBehind, LitAnswer, LitEnd, Outcome,
    Prompt,
};
use super::step::{
    Call, CallContext, Item, Next, Powered, StepRun, Stopped, put_back, result_line,
    view_or_model_name,
};
use super::words;
use crate::control::{Refusal, StopReason};
use crate::exchange::{Try, Verdict};
use crate::model::{CircuitState, Model};
use crate::protocol::message::Tenths;

/// One line per circuit, in pin order: the planned ones to run, the ones left alone
/// with why (motors have their own step).
pub(super) fn rows(view: &CheckView, model: &Model, now: Instant) -> Vec<CircuitResult> {
    model
        .circuits(now)
        .into_iter()
        .filter_map(|c| {
            let outcome = if view.plan.iter().any(|p| p.id == c.id) {
                Outcome::NotRun
            } else {
                let e = view.excluded.iter().find(|e| e.id == c.id)?;
                if view
                    .planned_motors
                    .iter()
                    .any(|(m, _)| m.device_id() == c.id)
                    || matches!(
                        c.kind,
                        crate::model::CircuitKind::Flaps | crate::model::CircuitKind::Trim(_)
                    )
                {
                    return None;
                }
                Outcome::Skipped(e.why.clone())
            };
            Some(CircuitResult {
                id: c.id,
                name: c.name,
                pin: c.pin,
                breaker: c.breaker,
                switch: c.switch,
                outcome,
            })
        })
        .collect()
}

/// What a circuit's current, as the unit sent it, says against its breaker: none at
/// all (the unit's smallest step is a tenth), tight or over ([`BreakerLoad`]), within.
pub fn judge(current: Tenths, breaker: Option<u8>) -> CircuitFinding {
    let breaker_a = breaker.unwrap_or(0);
    let amps = current.value();
    if current.0 == 0 {
        CircuitFinding::NoCurrent
    } else if breaker.is_some_and(|b| BreakerLoad::of(current, b) != BreakerLoad::Within) {
        CircuitFinding::NearBreaker {
            amps,
            breaker: breaker_a,
        }
    } else {
        CircuitFinding::Within {
            amps,
            breaker: breaker_a,
        }
    }
}

#[derive(Debug, Clone)]
enum Stage {
    /// Switched on (or found on), waiting for two fresh DEVICE_STATUS.
    Measure {
        statuses_at_send: u64,
        /// `None`: it was on already, nothing sent.
        request: Option<Try>,
    },
    /// A light measured and still on, held so until the person says whether it is
    /// lit, or `until` (the cap, [`super::Timing::lit_for`] after it was switched on).
    Asking { sent: bool, until: Instant },
    /// DEVICE_POWER off sent, waiting to see it off.
    PutBack { request: Try },
    /// The page could not be seen (the terminal too small, or not focused) when the
    /// circuit was to be switched on: nothing was sent, and nothing is until the
    /// person is back and says to go on (r), or skips it. Decision: no circuit is
    /// powered unseen, as no motor runs unseen; a person who cannot see the page
    /// cannot see what the check is doing to the aircraft.
    Waiting,
}

/// The circuit under test.
#[derive(Debug, Clone)]
pub(super) struct CircuitItem {
    pub idx: usize,
    pub id: u8,
    started: Instant,
    stage: Stage,
    on_for: std::time::Duration,
}

impl CircuitItem {
    /// The check stops here: switch it off if the check switched it on. Returns the
    /// circuit to watch go off, or why the off could not be sent.
    pub fn stop(&self, cx: &mut CallContext) -> Result<Option<Powered>, Refusal> {
        match &self.stage {
            Stage::Measure {
                request: Some(_), ..
            }
            | Stage::Asking { sent: true, .. }
            | Stage::PutBack { .. } => {
                cx.power_off(self.id)?;
                Ok(Some(Powered { id: self.id }))
            }
            Stage::Measure { request: None, .. }
            | Stage::Asking { sent: false, .. }
            | Stage::Waiting => Ok(None),
        }
    }
}

impl Item for CircuitItem {
    fn deadline(&self) -> Option<Instant> {
        Some(match &self.stage {
            Stage::Measure {
                request: Some(t), ..
            } => t.deadline().min(self.started + self.on_for),
            Stage::Measure { request: None, .. } => self.started + self.on_for,
            Stage::Asking { until, .. } => *until,
            Stage::PutBack { request } => request.deadline(),
            Stage::Waiting => return None,
        })
    }

    fn under_test(&self) -> Vec<u8> {
        vec![self.id]
    }

    #[cfg(test)]
    fn stage(&self) -> &'static str {
        match &self.stage {
            Stage::Measure {
                request: Some(_), ..
            } => "measure, switched on",
            Stage::Measure { request: None, .. } => "measure, as it is",
            Stage::Asking { .. } => "asking if it is lit",
            Stage::PutBack { .. } => "put back",
            Stage::Waiting => "waiting to be seen",
        }
    }
}

fn state(model: &Model, now: Instant, id: u8) -> CircuitState {
    model
        .circuits(now)
        .into_iter()
        .find(|c| c.id == id)
        .map_or(CircuitState::Unknown, |c| c.state)
}

impl Circuits {
    /// The prompt while a measured light is held on for its answer, with the time
    /// left before it goes off unanswered.
    fn asking_prompt(&mut self, view: &mut CheckView, now: Instant) -> Next {
        let Some(item) = &self.item else {
            return Next::Stay;
        };
        let Stage::Asking { sent, until } = item.stage else {
            return Next::Stay;
        };
        let name = view.circuits[item.idx].name.clone();
        let off = if sent {
            "it goes back off at your answer"
        } else {
            "it is on by its switch and stays so"
        };
        view.prompt = Some(Prompt {
            todo: format!("{name} is on and measured.{LIT_QUESTION} ({off}; s: skip the question)"),
            watching: format!("{name}'s state (DEVICE_STATUS)"),
            time_left: Some(until.saturating_duration_since(now)),
            keys: keys(true),
        });
        Next::Stay
    }

    /// The light's question is over (or was never held): put it back off if the
    /// check switched it on, else on to the next.
    fn after_light(&mut self, idx: usize, sent: bool, c: &mut Call) -> Next {
        if sent {
            self.put_back_item(c)
        } else {
            Next::From(idx + 1)
        }
    }

    fn put_back_item(&mut self, c: &mut Call) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        if let Err(why) = c.cx.power_off(item.id) {
            c.shared.trouble_ahead = Some(format!(
                "{} could not be switched back off: {why}",
                c.view.circuits[item.idx].name
            ));
        }
        item.stage = Stage::PutBack {
            request: Try::with(
                c.cx.now,
                c.shared.timing.power_timeout,
                c.shared.timing.power_tries,
            ),
        };
        if let Some(p) = c.view.prompt.as_mut() {
            let row = &c.view.circuits[item.idx];
            p.todo = format!("Switching {} back off.", row.name);
            p.keys.retain(|(k, _)| *k != "y" && *k != "n");
        }
        Next::Stay
    }

    /// Circuit `idx` waits, not switched on, because the page cannot be seen (`why`):
    /// see [`Stage::Waiting`]. Asked again (r) while still unseen, it waits again.
    fn wait(&mut self, idx: usize, why: &str, c: &mut Call) -> Next {
        let row = &c.view.circuits[idx];
        let (id, name) = (row.id, row.name.clone());
        let todo = format!(
            "Paused before switching {name} on: {why}; nothing is switched on while the \
             page cannot be seen. r: go on; s: skip it."
        );
        c.cx.out.progress.push(format!("  {todo}"));
        c.view.prompt = Some(Prompt {
            todo,
            watching: format!("{name}'s state (DEVICE_STATUS)"),
            time_left: None,
            keys: vec![("r", "go on"), ("s", "skip"), ("Esc", "stop")],
        });
        self.item = Some(CircuitItem {
            idx,
            id,
            started: c.cx.now,
            stage: Stage::Waiting,
            on_for: c.shared.timing.on_for,
        });
        Next::Stay
    }

    /// The page's rule refused to switch the circuit on: that is its line, in
    /// control's words, and the next circuit.
    fn not_switched(
        &mut self,
        idx: usize,
        why: Refusal,
        view: &mut CheckView,
        cx: &mut CallContext,
    ) -> Next {
        let why = format!("not switched: {why}");
        let row = &mut view.circuits[idx];
        cx.out
            .progress
            .push(format!("– {} ({}): {why}", row.name, row.pin));
        view.message = Some(format!("{}: {why}", row.name));
        row.outcome = Outcome::Skipped(why);
        Next::From(idx + 1)
    }
}

fn record(view: &mut CheckView, idx: usize, f: CircuitFinding, cx: &mut CallContext) {
    let row = &mut view.circuits[idx];
    let what = format!("{} ({})", row.name, row.pin);
    let mut words = f.words();
    let (mark, message) = (f.mark(), format!("{}: {}", row.name, f.words()));
    row.outcome = Outcome::Found(f);
    // The headless check's line has the trend too, as the screen's row has.
    if let Some(t) = view.trend(&view.circuits[idx]).words() {
        words = format!("{words}; {t}");
    }
    cx.out.progress.push(result_line(mark, &what, &words));
    view.message = Some(message);
}

/// Step 3: the circuits, one at a time.
#[derive(Debug, Default)]
pub(super) struct Circuits {
    item: Option<CircuitItem>,
}

impl StepRun for Circuits {
    fn start(&mut self, idx: usize, c: &mut Call) -> Next {
        let id = c.view.circuits[idx].id;
        let name = c.view.circuits[idx].name.clone();
        let now = c.cx.now;
        let st = state(c.cx.model, now, id);
        if let CircuitState::Fault(code) = st {
            // Faulted before the check touched it: that is its finding.
            c.shared.known_faults.insert(id);
            record(c.view, idx, CircuitFinding::Faulted(code), c.cx);
            return Next::From(idx + 1);
        }
        let was_on = st == CircuitState::On;
        if !was_on && let Some(unseen) = c.cx.ctl.unseen() {
            return self.wait(idx, &unseen.describe(), c);
        }
        if !was_on && let Err(why) = c.cx.power_on(id) {
            // Refused by the page's own rule: nothing sent, and the words say why.
            return self.not_switched(idx, why, c.view, c.cx);
        }
        let request = (!was_on).then(|| {
            Try::with(
                now,
                c.shared.timing.power_timeout,
                c.shared.timing.power_tries,
            )
        });
        let light = lights::is_light(&name) && !c.shared.nobody_to_answer;
        let mut todo = if was_on {
            format!("{name} is on already: measuring it as it is.")
        } else {
            format!("Switching {name} on to measure it, then back off.")
        };
        if light {
            // Only a person looking can say a lamp shines: asked while it is on, and
            // the check waits for the answer, up to the cap. One on by its own switch
            // is held too: the person may be walking to it, and an answer typed late
            // must not be taken for the next light asked.
            todo.push_str(LIT_QUESTION);
            c.cx.out.progress.push(format!(
                "  {name}: is it lit? Type y (lit), n (not lit) or s (skip the question); it \
                 stays on until you answer, {} s at most.",
                c.shared.timing.lit_for.as_secs()
            ));
        } else if lights::is_light(&name) {
            c.view.lit.retain(|l| l.id != id);
            c.view.lit.push(LitAnswer {
                id,
                lit: None,
                ended: LitEnd::NobodyToAnswer,
                switched: !was_on,
            });
        }
        c.view.prompt = Some(Prompt {
            todo,
            watching: format!("{name}'s state and current (DEVICE_STATUS, once a second)"),
            time_left: Some(c.shared.timing.on_for),
            keys: keys(light),
        });
        self.item = Some(CircuitItem {
            idx,
            id,
            started: now,
            stage: Stage::Measure {
                statuses_at_send: c.cx.statuses(),
                request,
            },
            on_for: c.shared.timing.on_for,
        });
        Next::Stay
    }

    fn tick(&mut self, c: &mut Call) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        let (idx, id, now) = (item.idx, item.id, c.cx.now);
        let st = state(c.cx.model, now, id);
        if let Some(p) = c.view.prompt.as_mut() {
            p.time_left = item.deadline().map(|d| d.saturating_duration_since(now));
        }
        match &mut item.stage {
            Stage::Measure {
                statuses_at_send,
                request,
            } => {
                let finding = if let CircuitState::Fault(code) = st {
                    c.shared.known_faults.insert(id);
                    Some(CircuitFinding::Faulted(code))
                } else if c.cx.statuses() >= *statuses_at_send + 2 && st == CircuitState::On {
                    let current =
                        c.cx.model
                            .live_devices(now)
                            .map_or(Tenths(0), |d| d.current[id as usize]);
                    Some(judge(current, c.view.circuits[idx].breaker))
                } else if now >= item.started + item.on_for {
                    Some(CircuitFinding::DidNotSwitch)
                } else {
                    match request
                        .as_mut()
                        .map(|t| t.judge(st == CircuitState::On, now))
                    {
                        Some(Verdict::Resend) => match c.cx.power_on(id) {
                            Ok(()) => None,
                            Err(why) => {
                                // The first on went out: put it back all the same.
                                let why = format!("not switched: {why}");
                                c.view.circuits[idx].outcome = Outcome::Skipped(why.clone());
                                c.cx.out
                                    .progress
                                    .push(format!("– {}: {why}", c.view.circuits[idx].name));
                                return self.put_back_item(c);
                            }
                        },
                        Some(Verdict::NoAnswer) => Some(CircuitFinding::DidNotSwitch),
                        _ => None,
                    }
                };
                let Some(f) = finding else {
                    return Next::Stay;
                };
                let sent = request.is_some();
                let lit_on = matches!(
                    f,
                    CircuitFinding::Within { .. }
                        | CircuitFinding::NearBreaker { .. }
                        | CircuitFinding::NoCurrent
                );
                record(c.view, idx, f, c.cx);
                let asking = asks_lit(c.view, idx);
                // Measured: held on until the person answers, up to the cap; one the
                // check switched on goes back off at the answer, one on by its switch
                // stays so.
                if asking && lit_on && now < item.started + c.shared.timing.lit_for {
                    item.stage = Stage::Asking {
                        sent,
                        until: item.started + c.shared.timing.lit_for,
                    };
                    return self.asking_prompt(c.view, now);
                }
                return self.after_light(idx, sent, c);
            }
            Stage::Asking { sent, until } => {
                let (sent, until) = (*sent, *until);
                if now >= until {
                    let held = until.saturating_duration_since(item.started);
                    end_lit(idx, None, LitEnd::Cap(held), sent, c.view, c.cx);
                    return self.after_light(idx, sent, c);
                }
                if let CircuitState::Fault(_) | CircuitState::Off = st {
                    // It went off by itself (a fault, or its switch): nothing to hold.
                    return self.after_light(idx, sent, c);
                }
            }
            Stage::Waiting => {}
            Stage::PutBack { request } => {
                // A faulted pin is off (Appendix E), its reset answered or not.
                let off = matches!(
                    st,
                    CircuitState::Off | CircuitState::Fault(_) | CircuitState::ResetSent(_)
                );
                match request.judge(off, now) {
                    Verdict::Answered => {
                        put_back(id, c.view, c.cx.model, now);
                        return Next::From(idx + 1);
                    }
                    Verdict::Resend => {
                        if let Err(why) = c.cx.power_off(id) {
                            c.shared.trouble_ahead = Some(format!(
                                "{} could not be switched back off: {why}",
                                c.view.circuits[idx].name
                            ));
                        }
                    }
                    Verdict::NoAnswer => {
                        c.shared.trouble_ahead = Some(format!(
                            "{} did not switch back off",
                            c.view.circuits[idx].name
                        ));
                    }
                    Verdict::Waiting => {}
                }
            }
        }
        Next::Stay
    }

    fn command(&mut self, cmd: Command, c: &mut Call) -> Next {
        let Some(item) = &self.item else {
            return Next::Stay;
        };
        let idx = item.idx;
        if matches!(item.stage, Stage::Waiting) && matches!(cmd, Command::Retry | Command::Enter) {
            return self.start(idx, c);
        }
        let on_hold = match item.stage {
            Stage::Asking { sent, .. } => Some(sent),
            _ => None,
        };
        let sent_on = matches!(
            item.stage,
            Stage::Measure {
                request: Some(_),
                ..
            }
        );
        if let Command::Lit(lit) = cmd {
            // While it is on: what the person saw. Measured, it goes off now.
            if matches!(item.stage, Stage::Measure { .. } | Stage::Asking { .. })
                && asks_lit(c.view, idx)
            {
                end_lit(
                    idx,
                    Some(lit),
                    LitEnd::Answer,
                    on_hold.unwrap_or(sent_on),
                    c.view,
                    c.cx,
                );
                if let Some(sent) = on_hold {
                    return self.after_light(idx, sent, c);
                }
            }
            return Next::Stay;
        }
        if cmd == Command::NobodyToAnswer {
            if let Some(sent) = on_hold {
                end_lit(idx, None, LitEnd::NobodyToAnswer, sent, c.view, c.cx);
                return self.after_light(idx, sent, c);
            }
            if matches!(item.stage, Stage::Measure { .. }) && asks_lit(c.view, idx) {
                end_lit(idx, None, LitEnd::NobodyToAnswer, sent_on, c.view, c.cx);
            }
            return Next::Stay;
        }
        if cmd != Command::SkipItem {
            return Next::Stay;
        }
        match &item.stage {
            Stage::Asking { sent, .. } => {
                let sent = *sent;
                end_lit(idx, None, LitEnd::Skipped, sent, c.view, c.cx);
                return self.after_light(idx, sent, c);
            }
            Stage::Measure { request, .. } => {
                let sent = request.is_some();
                if c.view.circuits[idx].outcome == Outcome::NotRun {
                    c.view.circuits[idx].outcome = Outcome::Skipped("you skipped it".into());
                    c.cx.out
                        .progress
                        .push(format!("– {}: skipped", c.view.circuits[idx].name));
                }
                if sent {
                    return self.put_back_item(c);
                } else {
                    return Next::From(idx + 1);
                }
            }
            // Already going back off: the skip takes effect once it is.
            Stage::PutBack { .. } => {}
            Stage::Waiting => {
                c.view.circuits[idx].outcome = Outcome::Skipped("you skipped it".into());
                c.cx.out
                    .progress
                    .push(format!("– {}: skipped", c.view.circuits[idx].name));
                return Next::From(idx + 1);
            }
        }
        Next::Stay
    }

    fn stop(&mut self, _reason: StopReason, view: &CheckView, cx: &mut CallContext) -> Stopped {
        let Some(item) = &self.item else {
            return Stopped::default();
        };
        match item.stop(cx) {
            Ok(powered) => Stopped {
                powered,
                left: None,
            },
            Err(why) => Stopped {
                powered: None,
                left: Some(LeftBehind::new(
                    item.id,
                    view_or_model_name(view, cx.model, item.id),
                    format!("ON when the check stopped: DEVICE_POWER off not sent: {why}"),
                )),
            },
        }
    }

    fn item(&self) -> Option<&dyn Item> {
        self.item.as_ref().map(|i| i as &dyn Item)
    }
}

/// The question put to the person for a light while it is on.
const LIT_QUESTION: &str = " Is it lit? y: yes, n: no.";

/// The keys while a circuit is under test: y and n too while a light's question is open.
fn keys(light: bool) -> Vec<(&'static str, &'static str)> {
    let mut keys = vec![("s", "skip"), ("S", "skip step"), ("Esc", "stop")];
    if light {
        keys.splice(0..0, [("y", "lit"), ("n", "not lit")]);
    }
    keys
}

/// Whether light `idx`'s question is still open: a light, asked, not yet ended.
fn asks_lit(view: &CheckView, idx: usize) -> bool {
    let row = &view.circuits[idx];
    lights::is_light(&row.name) && view.lit_answer(row.id).is_none()
}

/// "Is it lit?" for light `idx` ended: the person's answer (`lit`) and what ended it,
/// kept beside its current for the report. `switched`: the check had switched it on,
/// so it goes back off now.
fn end_lit(
    idx: usize,
    lit: Option<bool>,
    ended: LitEnd,
    switched: bool,
    view: &mut CheckView,
    cx: &mut CallContext,
) {
    let row = &view.circuits[idx];
    let (id, name) = (row.id, row.name.clone());
    view.lit.retain(|l| l.id != id);
    view.lit.push(LitAnswer {
        id,
        lit,
        ended,
        switched,
    });
    let said = words::lit_ended(lit, ended, switched);
    cx.out.progress.push(format!("  {name}: {said}"));
    view.message = Some(format!("{name}: {said}"));
    if let Some(p) = view.prompt.as_mut() {
        p.todo = p.todo.replace(LIT_QUESTION, "");
        p.keys.retain(|(k, _)| *k != "y" && *k != "n");
    }
}

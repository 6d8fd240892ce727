//! What every step of the check (switch inputs, circuits, motors) gives the flow, and
//! what the flow lends each step: the one interface ([`StepRun`]) that `flow.rs`
//! drives with its one loop over the items. A step knows its own items; the flow
//! knows the order of the steps, skipping, interruption and the end. The steps import
//! this module, never the flow.

use std::collections::BTreeSet;
use std::time::{Instant, SystemTime};

use super::calls::{CheckEffects, Command};
use super::state::{CheckView, LeftBehind, Mark};
use super::timing::Timing;
use crate::control::{Controller, Refusal, StopReason, device_power, put_back_off};
use crate::model::{Model, Motor};
use crate::protocol::message::{Message, Packet, SwitchId};

/// Where the step loop goes after a step's call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Next {
    /// The item under test goes on: wait for the next tick or command.
    Stay,
    /// The item is done: the next one not done yet from this index (or the next step).
    From(usize),
}

/// One step of the check, one item at a time. The flow starts the step's first item
/// not done yet, ticks and commands the item under test, and on `Next::From` starts
/// the next one; the step never moves the check on by itself.
pub(super) trait StepRun: std::fmt::Debug {
    /// Whether the step's skipped line is also said when the person skips the rest of
    /// the step midway (the switch inputs say each skipped input instead).
    fn says_skip_midway(&self) -> bool {
        true
    }

    /// Before the first item, when the step is not skipped.
    fn begin(&mut self, _c: &mut Call) {}

    /// Starts item `idx` (its row is not done yet).
    fn start(&mut self, idx: usize, c: &mut Call) -> Next;

    /// Time passed or packets arrived.
    fn tick(&mut self, c: &mut Call) -> Next;

    /// A command from the person for the item under test (not Stop, not SkipStep).
    fn command(&mut self, cmd: Command, c: &mut Call) -> Next;

    /// The check stops during this item: stop what it runs (for `reason`), and say
    /// what it leaves.
    fn stop(&mut self, reason: StopReason, view: &CheckView, cx: &mut CallContext) -> Stopped;

    /// The item under test, if one is started.
    fn item(&self) -> Option<&dyn Item>;

    /// When the item must be ticked next, if it waits on a clock.
    fn deadline(&self) -> Option<Instant> {
        self.item().and_then(Item::deadline)
    }

    /// The devices whose fault is a finding of this item rather than an interruption.
    fn under_test(&self) -> Vec<u8> {
        self.item().map_or_else(Vec::new, Item::under_test)
    }

    /// The item's own stage, for the tests that stop the check at every stage.
    #[cfg(test)]
    fn stage(&self) -> String {
        self.item().map_or("", Item::stage).into()
    }
}

/// What the flow asks of the item under test (a switch input, a circuit, a motor),
/// whatever its step.
pub(super) trait Item {
    /// When it must be ticked next, if it waits on a clock.
    fn deadline(&self) -> Option<Instant>;

    /// The devices whose fault is a finding of this item rather than an interruption.
    fn under_test(&self) -> Vec<u8>;

    /// Its own stage, for the tests that stop the check at every stage.
    #[cfg(test)]
    fn stage(&self) -> &'static str;
}

/// What an item left when the check stopped during it.
#[derive(Debug, Default)]
pub(super) struct Stopped {
    /// A circuit switched back off now, to watch go off.
    pub powered: Option<Powered>,
    /// Its line in the list of what the check left.
    pub left: Option<LeftBehind>,
}

/// A circuit the check switched on and has not yet seen back off.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Powered {
    pub id: u8,
}

/// What the flow keeps between calls that the steps read and add to.
#[derive(Debug, Clone)]
pub(super) struct Shared {
    pub timing: Timing,
    /// Faults present when the check started (or found on the item under test):
    /// only a new fault elsewhere interrupts.
    pub known_faults: BTreeSet<u8>,
    /// A step found something that ends the check (a circuit that will not go back
    /// off, a motor stopped by lost communication): handled at the end of the tick.
    pub trouble_ahead: Option<String>,
    /// The wall-clock time at `made_at`, if the caller gave it.
    pub clock: Option<SystemTime>,
    /// The `now` the flow was made with.
    pub made_at: Instant,
    /// [`super::Command::NobodyToAnswer`] came: nothing is held for a person.
    pub nobody_to_answer: bool,
}

impl Shared {
    /// The wall-clock time of an instant, if the caller gave the flow its clock.
    pub fn wall(&self, at: Instant) -> Option<SystemTime> {
        let clock = self.clock?;
        if at >= self.made_at {
            clock.checked_add(at - self.made_at)
        } else {
            clock.checked_sub(self.made_at - at)
        }
    }
}

/// What one call into a step is lent: the view it changes, the model, controller and
/// effects ([`CallContext`]), and what the flow keeps between calls ([`Shared`]).
pub(super) struct Call<'c, 'a> {
    pub view: &'c mut CheckView,
    pub cx: &'c mut CallContext<'a>,
    pub shared: &'c mut Shared,
}

/// What the calls share: the model, the controller and where the packets go.
pub(super) struct CallContext<'a> {
    pub model: &'a Model,
    pub ctl: &'a mut Controller,
    pub now: Instant,
    pub out: &'a mut CheckEffects,
}

impl CallContext<'_> {
    /// Switches circuit `id` on by the rule of the page's own power keys
    /// ([`device_power`]: never the starter or a motor, not a faulted pin, not a state
    /// the page does not know); on a refusal nothing is sent and the words say why.
    pub fn power_on(&mut self, id: u8) -> Result<(), Refusal> {
        let message = device_power(self.model, self.now, id, true)?;
        self.send(message);
        Ok(())
    }

    /// Switches back off a circuit this check switched on ([`put_back_off`]).
    pub fn power_off(&mut self, id: u8) -> Result<(), Refusal> {
        let message = put_back_off(self.model, id)?;
        self.send(message);
        Ok(())
    }

    /// Stops the motor run, if any, for `reason`, its stop on the wire.
    pub fn stop_run(&mut self, reason: StopReason) {
        let packets = self.ctl.stop(self.now, reason);
        self.out.packets.extend(packets);
    }

    fn send(&mut self, message: Message) {
        let cnt = self.ctl.next_cnt();
        self.out.packets.push(Packet::request(cnt, message));
    }

    /// How many DEVICE_STATUS broadcasts the page has heard so far.
    pub fn statuses(&self) -> u64 {
        self.model
            .link
            .rx
            .get("DEVICE_STATUS")
            .map_or(0, |s| s.count)
    }
}

/// `id` was switched back off by DEVICE_POWER: the unit holds it off until its
/// switch is cycled (ICD Appendix A, §6.4.1), so the person is told which.
pub(super) fn put_back(id: u8, view: &mut CheckView, model: &Model, now: Instant) {
    let spec = model.circuits(now).into_iter().find(|c| c.id == id);
    if let Some(SwitchId::Input(n)) = spec.and_then(|c| c.switch)
        && !view.to_cycle.iter().any(|(i, ..)| *i == id)
    {
        view.to_cycle
            .push((id, view_or_model_name(view, model, id), SwitchId::Input(n)));
    }
}

pub(super) fn view_or_model_name(view: &CheckView, model: &Model, id: u8) -> String {
    view.circuits
        .iter()
        .find(|c| c.id == id)
        .map(|c| c.name.clone())
        .unwrap_or_else(|| model.display_name(id))
}

/// Whether `id` is on in the live DEVICE_STATUS (`None`: no live status).
pub(super) fn circuit_on(model: &Model, now: Instant, id: u8) -> Option<bool> {
    model.live_devices(now).map(|d| d.on[id as usize])
}

/// The motor's name as the results show it.
pub(super) fn motor_name(m: Motor) -> String {
    let n = m.name();
    let mut c = n.chars();
    c.next()
        .map(|f| f.to_uppercase().collect::<String>() + c.as_str())
        .unwrap_or_default()
}

/// A result as a headless run prints it: "✓ PASS switch 3: …".
pub(super) fn result_line(mark: Mark, what: &str, words: &str) -> String {
    format!("{} {} {what}: {words}", mark.symbol(), mark.word())
}

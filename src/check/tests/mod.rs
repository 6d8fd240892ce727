//! The flow on a fake clock against the virtual VP-X's sans-IO unit: every packet the
//! flow and the page's controller give back goes into the unit, every frame the unit
//! writes is decoded into the model, 10 ms at a time. Nothing here sleeps.

use std::time::{Duration, Instant};

mod against;

use super::flow::{Cause, CheckFlow, Options};
use super::plan::Choices;
use super::{Command, Timing};
use crate::check::state::{
    CheckView, CircuitFinding, Input, LeftBehind, Mark, MotorFinding, NotFollowed, Outcome, Step,
    SwitchFinding,
};
use crate::control::{Controller, StopReason};
use crate::model::{Model, Motor, Setting, Source, TrimKind};
use crate::protocol::FaultCode;
use crate::protocol::decoder::{Decoder, Event};
use crate::protocol::message::{Message, Packet, SwitchId};
use crate::sim::{Scenario, SimCommand, Unit, UnitOptions};

/// A small aircraft: one circuit of each kind the findings need.
fn scenario() -> String {
    let mut s = String::from(
        r#"
description = "check tests"
[electrical]
battery_volts = 12.6
[system]
secondary_alternator = 23
[[device]]
id = 2
name = "EFIS"
breaker = 5
switch = 11
load = 2.0
[[device]]
id = 3
name = "Main Alt"
switch = 1
load = 2.0
[[device]]
id = 4
name = "Nav Lt"
breaker = 3
switch = 2
load = 1.5
[[device]]
id = 5
name = "Strobe"
breaker = 4
switch = 2
load = 0.0
[[device]]
id = 17
name = "Landing Lt"
breaker = 8
switch = 3
load = 7.0
[[device]]
id = 7
name = "Pitot Heat"
breaker = 5
switch = 4
load = 3.0
[[device]]
id = 18
name = "Boost Pump"
breaker = 5
switch = 0
load = 3.0
short = true
[[device]]
id = 23
name = "Standby Alt"
breaker = 5
switch = 7
load = 2.0
[flap]
enabled = true
up = 20
down = 220
position = 20
[pitch_trim]
enabled = true
up = 30
down = 220
neutral = 125
power = 100
position = 125
[roll_trim]
enabled = false
up = 0
down = 0
neutral = 0
"#,
    );
    for id in (6..=28).filter(|i| ![7, 17, 18, 23].contains(i)) {
        s.push_str(&format!("[[device]]\nid = {id}\nenabled = false\n"));
    }
    s
}

struct Rig {
    unit: Unit,
    rx: Decoder,
    model: Model,
    ctl: Controller,
    flow: CheckFlow,
    view: CheckView,
    t0: Instant,
    now: Instant,
    /// Every packet that went to the unit, with when.
    sent: Vec<(Duration, Packet)>,
    progress: Vec<String>,
    /// How many times the flow said the check ended (the app writes a report each).
    ended: u32,
    /// Drop DEVICE_POWER on the way (a unit that does not act on it).
    deaf_to_power: bool,
    /// The link is cut: nothing goes in or out.
    cut: bool,
}

impl Rig {
    fn new(opts: Options) -> Rig {
        Rig::with(&scenario(), opts)
    }

    /// Nobody looks at the lights here: each goes back off once measured, as if "Is
    /// it lit?" were not held ([`Rig::holding_lights`] holds it).
    fn with(toml: &str, opts: Options) -> Rig {
        let timing = Timing {
            lit_for: Duration::ZERO,
            ..opts.timing
        };
        Rig::build(toml, Options { timing, ..opts })
    }

    /// A light is held on until "Is it lit?" is answered, up to its cap.
    fn holding_lights(opts: Options) -> Rig {
        Rig::build(&scenario(), opts)
    }

    fn build(toml: &str, opts: Options) -> Rig {
        let t0 = Instant::now();
        let s = Scenario::from_toml(toml).unwrap();
        let unit = Unit::with_memory_eeprom(&s, UnitOptions::default(), t0);
        let mut model = Model::new(Source::Simulated {
            scenario: "check".into(),
        });
        model.note_connected(t0, "test".into());
        let mut r = Rig {
            unit,
            rx: Decoder::new(),
            model,
            ctl: Controller::default(),
            flow: CheckFlow::new(
                opts.clone(),
                &mut CheckView::default(),
                &Model::new(Source::Simulated {
                    scenario: "x".into(),
                }),
                t0,
            ),
            view: CheckView::default(),
            t0,
            now: t0,
            sent: Vec::new(),
            progress: Vec::new(),
            ended: 0,
            deaf_to_power: false,
            cut: false,
        };
        // The page's connect-time queries.
        let queries: Vec<Packet> = Setting::all()
            .enumerate()
            .map(|(i, s)| Packet::request(i as u8, s.query()))
            .collect();
        r.send(queries);
        r.idle(1500);
        r.flow = CheckFlow::new(opts, &mut r.view, &r.model, r.now);
        r
    }

    fn send(&mut self, packets: Vec<Packet>) {
        for p in packets {
            self.sent.push((self.now - self.t0, p));
            if self.cut {
                continue;
            }
            // Written: the page's model records it as the app does on its Tx event
            // (a DEVICE_POWER starts a hold, `model::hold`).
            self.model.note_sent(self.now, &p);
            if self.deaf_to_power && matches!(p.message, Message::DevicePower(_)) {
                continue;
            }
            self.unit.feed(&p.to_bytes(), self.now);
        }
    }

    fn collect(&mut self) {
        self.collect_but(None);
    }

    /// What the unit wrote, into the model, but the messages named `drop`.
    fn collect_but(&mut self, drop: Option<&str>) {
        let out = self.unit.take_output();
        if self.cut {
            return;
        }
        let mut frames = Vec::new();
        self.rx.push(&out, |e| {
            if let Event::Frame(f) = e {
                frames.push(Packet::parse(&f).unwrap());
            }
        });
        for p in frames
            .into_iter()
            .filter(|p| Some(p.message.name()) != drop)
        {
            self.model.apply_packet(self.now, &p);
        }
    }

    /// Time passes without the flow (before it is made).
    fn idle(&mut self, ms: u64) {
        for _ in 0..ms / 10 {
            self.now += Duration::from_millis(10);
            self.unit.tick(self.now);
            self.collect();
        }
    }

    /// `ms` of the page's loop: unit, model, controller, flow.
    fn run(&mut self, ms: u64) {
        self.run_but(ms, None);
    }

    /// [`Rig::run`], but the messages named `drop` are lost on the way from the unit.
    fn run_but(&mut self, ms: u64, drop: Option<&str>) {
        for _ in 0..ms / 10 {
            self.now += Duration::from_millis(10);
            self.unit.tick(self.now);
            self.collect_but(drop);
            let p = self.ctl.tick(&self.model, self.now);
            self.send(p);
            let out = self
                .flow
                .tick(&mut self.view, &self.model, &mut self.ctl, self.now);
            self.take(out);
        }
    }

    /// What a call gave back: its progress and packets; a load file to open is
    /// opened here, as the app does, and the flow told in the same turn.
    fn take(&mut self, mut out: crate::check::CheckEffects) {
        if let Some(req) = out.open_loads.take() {
            let opened = crate::loads::disk::open_or_create(&req.path, &req.circuits);
            out.absorb(self.flow.loads_opened(
                opened,
                &mut self.view,
                &self.model,
                &mut self.ctl,
                self.now,
            ));
        }
        self.progress.extend(out.progress);
        self.ended += u32::from(out.ended);
        self.send(out.packets);
    }

    /// Runs until `done` holds, at most `ms`.
    fn run_until(&mut self, ms: u64, done: impl Fn(&Rig) -> bool) {
        for _ in 0..ms / 10 {
            if done(self) {
                return;
            }
            self.run(10);
        }
        assert!(
            done(self),
            "not done after {ms} ms: {:#?}",
            self.view.prompt
        );
    }

    fn cmd(&mut self, c: Command) {
        let out = self
            .flow
            .command(c, &mut self.view, &self.model, &mut self.ctl, self.now);
        self.take(out);
    }

    fn interrupt(&mut self, cause: Cause, may_wait: bool) {
        let out = self.flow.interrupt_for(
            cause,
            may_wait,
            &mut self.view,
            &self.model,
            &mut self.ctl,
            self.now,
        );
        self.take(out);
    }

    fn flip(&mut self, n: u8, on: bool) {
        self.unit
            .apply(SimCommand::Switch { switch: n, on }, self.now);
    }

    /// A person flips switch `n` on, waits `hold` ms, flips it off.
    fn flip_on_off(&mut self, n: u8, hold: u64) {
        self.flip(n, true);
        self.run(hold);
        self.flip(n, false);
    }

    fn circuit(&self, id: u8) -> &Outcome<CircuitFinding> {
        &self
            .view
            .circuits
            .iter()
            .find(|c| c.id == id)
            .unwrap()
            .outcome
    }

    fn switch(&self, input: Input) -> &Outcome<SwitchFinding> {
        &self
            .view
            .switches
            .iter()
            .find(|s| s.input == input)
            .unwrap()
            .outcome
    }

    /// The DEVICE_POWER commands sent for `id`, in order.
    fn powers(&self, id: u8) -> Vec<bool> {
        self.sent
            .iter()
            .filter_map(|(_, p)| match p.message {
                Message::DevicePower(d) if d.device_id == id => Some(d.on),
                _ => None,
            })
            .collect()
    }

    fn on(&self, id: u8) -> bool {
        self.model.live_devices(self.now).unwrap().on[id as usize]
    }

    /// Only `steps` run: the others are skipped.
    fn only(steps: &[Step]) -> Options {
        Options {
            skip: Step::SKIPPABLE
                .iter()
                .map(|&(s, _)| s)
                .filter(|s| !steps.contains(s))
                .collect(),
            ..Options::default()
        }
    }

    /// The switch step with the motors step after it, so the flap and trim inputs
    /// are asked (with the motors skipped they are not: `plan::unasked`).
    fn switches_then_motors() -> Options {
        Rig::only(&[Step::Switches, Step::Motors])
    }

    fn start(&mut self) {
        self.cmd(Command::Enter);
        assert_ne!(self.view.step, Step::Confirm, "{:?}", self.view.message);
    }

    /// Until the flaps, parked at their up endpoint, have shown their way in probes
    /// and run the rest of their first test run (a probe moves them one count at most).
    fn past_probes(&mut self) {
        self.run_until(3000, |r| {
            r.ctl.running().is_some_and(|m| m.motor == Motor::Flaps) && flaps_at(r) >= 22
        });
    }
}

// ----- before power -----

#[test]
fn the_plan_never_touches_the_starter_or_the_alternator_fields_and_suggests_pitot_heat() {
    let r = Rig::new(Options::default());
    let v = &r.view;
    assert_eq!(v.step, Step::Confirm);
    let planned: Vec<u8> = v.plan.iter().map(|p| p.id).collect();
    assert_eq!(
        planned,
        vec![2, 4, 5, 17, 18],
        "EFIS, Nav, Strobe, Landing, Boost"
    );
    let why = |id: u8| v.excluded.iter().find(|e| e.id == id).unwrap().clone();
    assert_eq!(why(1).why, "never touched: the starter");
    assert!(!why(1).may_include);
    assert_eq!(why(3).why, "never touched: an alternator field");
    assert_eq!(
        why(23).why,
        "never touched: an alternator field",
        "secondary"
    );
    assert_eq!(why(7).why, "suggested: the name has \"pitot\"");
    assert!(why(7).may_include);
    let motors: Vec<Motor> = v.planned_motors.iter().map(|(m, _)| *m).collect();
    assert_eq!(motors, vec![Motor::Flaps, Motor::Trim(TrimKind::Pitch)]);
    assert!(v.plan.iter().all(|p| p.on_for == Duration::from_secs(5)));
    assert!(v.prompt.as_ref().unwrap().todo.contains("safe to power"));
    assert!(
        r.sent
            .iter()
            .all(|(_, p)| !matches!(p.message, Message::DevicePower(_)))
    );
}

#[test]
fn exclusions_by_name_or_pin_and_a_suggestion_taken_back_on_the_screen() {
    let mut r = Rig::new(excluding(&["landing lt", "5A-1"], Options::default()));
    let planned: Vec<u8> = r.view.plan.iter().map(|p| p.id).collect();
    assert_eq!(planned, vec![2, 5, 18]);
    // Select Pitot Heat among the excluded and take the suggestion back.
    let at = r.view.plan.len() + r.view.excluded.iter().position(|e| e.id == 7).unwrap();
    for _ in 0..at {
        r.cmd(Command::Down);
    }
    r.cmd(Command::Toggle);
    assert!(
        r.view.plan.iter().any(|p| p.id == 7),
        "{:?}",
        r.view.message
    );
    // Excluded here with x: said as excluded on this screen, not by --exclude; and
    // taken back with x again.
    r.view.current = Some(r.view.plan.iter().position(|p| p.id == 7).unwrap());
    r.cmd(Command::Toggle);
    let e = r.view.excluded.iter().find(|e| e.id == 7).unwrap();
    assert_eq!(e.why, "excluded by you (x on this screen)");
    r.view.current =
        Some(r.view.plan.len() + r.view.excluded.iter().position(|e| e.id == 7).unwrap());
    r.cmd(Command::Toggle);
    assert!(
        r.view.plan.iter().any(|p| p.id == 7),
        "{:?}",
        r.view.message
    );
    // The starter cannot be taken back.
    r.view.current =
        Some(r.view.plan.len() + r.view.excluded.iter().position(|e| e.id == 1).unwrap());
    r.cmd(Command::Toggle);
    assert!(!r.view.plan.iter().any(|p| p.id == 1));
    assert_eq!(
        super::plan::unmatched(&r.model, r.now, &["nope".into(), "EFIS".into()]),
        vec!["nope".to_string()]
    );
}

#[test]
fn nothing_starts_until_the_settings_are_heard_and_yes_confirms_by_itself() {
    let t0 = Instant::now();
    let mut view = CheckView::default();
    let model = Model::new(Source::Simulated {
        scenario: "x".into(),
    });
    let mut ctl = Controller::default();
    let mut flow = CheckFlow::new(Options::default(), &mut view, &model, t0);
    let out = flow.command(Command::Enter, &mut view, &model, &mut ctl, t0);
    assert!(out.packets.is_empty());
    assert_eq!(view.step, Step::Confirm);
    assert!(
        view.message.as_ref().unwrap().starts_with("not yet"),
        "{:?}",
        view.message
    );

    let mut r = Rig::new(Options {
        yes: true,
        ..Rig::only(&[Step::Circuits])
    });
    r.run(20);
    assert_eq!(
        r.view.step,
        Step::Circuits,
        "--yes confirms once the unit is heard"
    );
}

// ----- switch inputs -----

#[test]
fn a_switch_that_works_passes_once_its_circuits_followed() {
    let mut r = Rig::new(Rig::only(&[Step::Switches]));
    r.start();
    assert_eq!(r.view.step, Step::Switches);
    let inputs: Vec<Input> = r.view.switches.iter().map(|s| s.input).collect();
    assert_eq!(
        inputs,
        vec![
            Input::Switch(1),
            Input::Switch(2),
            Input::Switch(3),
            Input::Switch(4),
            Input::Switch(7),
            Input::FlapUp,
            Input::FlapDown,
            Input::PitchTrimUp,
            Input::PitchTrimDown
        ]
    );
    // Switch 1 has only the alternator field, switch 4 the pitot heat, switch 7 the
    // standby alternator: nothing to watch, so nothing to flip.
    assert!(matches!(r.switch(Input::Switch(1)), Outcome::Skipped(w) if w.contains("Main Alt")));
    assert!(matches!(r.switch(Input::Switch(4)), Outcome::Skipped(_)));
    assert_eq!(r.view.current, Some(1));
    assert!(r.view.prompt.as_ref().unwrap().todo.contains("switch 2"));
    assert!(
        r.view
            .prompt
            .as_ref()
            .unwrap()
            .watching
            .contains("Nav Lt, Strobe")
    );
    r.run(100);
    r.flip_on_off(2, 1500);
    r.run_until(4000, |r| r.view.current == Some(2));
    assert_eq!(
        r.switch(Input::Switch(2)),
        &Outcome::Found(SwitchFinding::Passed)
    );
    assert!(
        r.progress.iter().any(|n| n.starts_with("✓ PASS switch 2")),
        "{:?}",
        r.progress
    );
    assert!(r.powers(4).is_empty(), "the switch step sends nothing");
}

#[test]
fn a_switch_never_flipped_times_out_and_can_be_retried() {
    let mut r = Rig::new(Rig::switches_then_motors());
    r.start();
    r.run(30_100);
    assert_eq!(
        r.switch(Input::Switch(2)),
        &Outcome::Found(SwitchFinding::NeverChanged)
    );
    assert_eq!(r.view.current, Some(1), "waits for retry or go on");
    assert!(r.flow.next_deadline().is_none());
    r.cmd(Command::Retry);
    assert_eq!(r.switch(Input::Switch(2)), &Outcome::NotRun);
    r.run(100);
    r.flip_on_off(2, 1500);
    r.run_until(4000, |r| r.view.current == Some(2));
    assert_eq!(
        r.switch(Input::Switch(2)),
        &Outcome::Found(SwitchFinding::Passed)
    );
    // Time out again on switch 3 and go on with Enter.
    r.run(30_100);
    assert_eq!(
        r.switch(Input::Switch(3)),
        &Outcome::Found(SwitchFinding::NeverChanged)
    );
    r.cmd(Command::Enter);
    assert_eq!(
        r.view.switches[r.view.current.unwrap()].input,
        Input::FlapUp
    );
    // The flap switch has no circuit: its result says only what was seen.
    assert_eq!(
        r.prompt(),
        "Move the flap switch UP on, then back off.",
        "no circuits to wait for"
    );
    r.unit.apply(
        SimCommand::PressMotorSwitch {
            motor: crate::sim::MotorId::Flap,
            direction: crate::sim::MotorDirection::Up,
            hold: Duration::from_millis(1500),
        },
        r.now,
    );
    r.run_until(6000, |r| r.switch(Input::FlapUp) != &Outcome::NotRun);
    assert_eq!(
        r.switch(Input::FlapUp),
        &Outcome::Found(SwitchFinding::Changed)
    );
    let words = crate::check::words::switch(&r.view.switches[r.view.current.unwrap() - 1], |id| {
        r.view.name_of(id)
    });
    assert_eq!(words, "the input changed (no circuit is assigned to it)");
}

/// The roll trim switch is asked for by its directions, left and right, as the live
/// row draws them (`roll ←`, `→`; ICD Table 30 note 2), never UP and DOWN.
#[test]
fn the_roll_trim_switch_is_asked_left_and_right() {
    assert_eq!(Input::RollTrimUp.label(), "roll trim switch LEFT");
    assert_eq!(Input::RollTrimDown.label(), "roll trim switch RIGHT");
    let toml = scenario().replace(
        "[roll_trim]\nenabled = false\nup = 0\ndown = 0\nneutral = 0",
        "[roll_trim]\nenabled = true\nup = 30\ndown = 220\nneutral = 125\nposition = 125",
    );
    let mut r = Rig::with(&toml, Rig::switches_then_motors());
    r.start();
    r.run(100);
    // Skipped, input by input, to the roll trim switch.
    let roll = |r: &Rig| {
        r.view
            .current
            .is_some_and(|i| r.view.switches[i].input == Input::RollTrimUp)
    };
    for _ in 0..20 {
        if roll(&r) {
            break;
        }
        r.cmd(Command::SkipItem);
        r.run(10);
    }
    assert!(roll(&r), "{:?}", r.view.prompt);
    assert_eq!(
        r.prompt(),
        "Move the roll trim switch LEFT on, then back off."
    );
}

#[test]
fn another_input_changing_instead_is_a_crossed_pair() {
    let mut r = Rig::new(Rig::only(&[Step::Switches]));
    r.start();
    r.run(100);
    r.flip_on_off(3, 1500); // asked for 2, the person's switch 2 is wired to input 3
    r.run(1500);
    assert_eq!(
        r.switch(Input::Switch(2)),
        &Outcome::Found(SwitchFinding::OtherChanged(vec![Input::Switch(3)]))
    );
    assert!(
        r.progress
            .iter()
            .any(|n| n.contains("switch 3 changed instead: switches crossed"))
    );
}

#[test]
fn circuits_that_do_not_follow_say_why() {
    // Nav Lt held off by an earlier DEVICE_POWER (the check's own put-back), Strobe
    // shorted: flipping switch 2 turns on neither.
    let toml = scenario().replace("name = \"Strobe\"", "name = \"Strobe\"\nshort = true");
    let mut r = Rig::with(&toml, Rig::only(&[Step::Switches]));
    r.send(vec![Packet::request(
        9,
        crate::protocol::message::DevicePower {
            device_id: 4,
            on: false,
        },
    )]);
    r.start();
    r.run(100);
    r.flip(2, true);
    // The override ends when the switch changes (ICD Appendix A), so the sim
    // turns Nav Lt on with it; hold it with a DEVICE_POWER off again, as another EFIS
    // would.
    r.send(vec![Packet::request(
        10,
        crate::protocol::message::DevicePower {
            device_id: 4,
            on: false,
        },
    )]);
    r.run(1500);
    r.flip(2, false);
    r.run_until(5000, |r| r.view.current != Some(1));
    let Outcome::Found(SwitchFinding::CircuitsDidNotFollow(why)) = r.switch(Input::Switch(2))
    else {
        panic!("{:?}", r.switch(Input::Switch(2)));
    };
    assert!(
        matches!(
            why.as_slice(),
            [
                (
                    4,
                    NotFollowed::HeldByPage {
                        on: false,
                        sent_at: None,
                        ..
                    }
                ),
                (5, NotFollowed::Faulted(FaultCode::ShortCircuit)),
            ]
        ),
        "{why:?}"
    );
    assert!(
        r.view.interrupted.is_none(),
        "a watched circuit's fault is a finding"
    );
    let words = r.view.switches[1].outcome.clone();
    let Outcome::Found(f) = words else { panic!() };
    let w = f.words(&|id| r.view.name_of(id));
    assert!(
        w.contains("Nav Lt is held off by DEVICE_POWER sent from this page"),
        "{w}"
    );
    assert!(w.contains("Strobe faulted with SHORT_CIRCUIT"), "{w}");
}

#[test]
fn skipping_an_input_and_the_rest_of_the_step() {
    let mut r = Rig::new(Rig::only(&[Step::Switches]));
    r.start();
    r.cmd(Command::SkipItem);
    assert!(matches!(r.switch(Input::Switch(2)), Outcome::Skipped(w) if w == "you skipped it"));
    assert_eq!(r.view.current, Some(2));
    r.cmd(Command::SkipStep);
    assert!(
        r.view.switches[2..]
            .iter()
            .all(|s| matches!(s.outcome, Outcome::Skipped(_))),
        "{:?}",
        r.view.switches
    );
    assert_eq!(r.view.step, Step::Done);
    assert!(r.view.skipped_steps.contains(&Step::Switches));
    assert!(
        r.view
            .circuits
            .iter()
            .all(|c| matches!(c.outcome, Outcome::Skipped(_)))
    );
}

// ----- circuits -----

#[test]
fn each_circuit_is_measured_judged_and_put_back() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    r.start();
    r.run_until(40_000, |r| r.view.step == Step::Done);
    // EFIS is on already (always on): measured as it is, nothing sent.
    assert_eq!(
        r.circuit(2),
        &Outcome::Found(CircuitFinding::Within {
            amps: 2.0,
            breaker: 5
        })
    );
    assert!(r.powers(2).is_empty());
    assert_eq!(
        r.circuit(4),
        &Outcome::Found(CircuitFinding::Within {
            amps: 1.5,
            breaker: 3
        })
    );
    assert_eq!(r.circuit(5), &Outcome::Found(CircuitFinding::NoCurrent));
    assert!(
        matches!(
            r.circuit(17),
            Outcome::Found(CircuitFinding::NearBreaker { amps, breaker: 8 }) if (6.4..=8.0).contains(amps)
        ),
        "about 7 A is ≥ 80 % of 8 A: {:?}",
        r.circuit(17)
    );
    assert_eq!(
        r.circuit(18),
        &Outcome::Found(CircuitFinding::Faulted(FaultCode::ShortCircuit))
    );
    assert!(matches!(r.circuit(7), Outcome::Skipped(w) if w.contains("pitot")));
    assert!(matches!(r.circuit(3), Outcome::Skipped(w) if w.contains("alternator")));
    // Each one on, then off; and off it is.
    for id in [4, 5, 17, 18] {
        assert_eq!(r.powers(id), vec![true, false], "device {id}");
        assert!(!r.on(id), "device {id} left on");
    }
    assert_eq!(
        r.view.to_cycle,
        vec![
            (4, "Nav Lt".to_string(), SwitchId::Input(2)),
            (5, "Strobe".to_string(), SwitchId::Input(2)),
            (17, "Landing Lt".to_string(), SwitchId::Input(3)),
        ],
        "Boost Pump has no switch to cycle"
    );
    assert!(r.view.interrupted.is_none());
    let fix = r.view.to_fix();
    assert_eq!(fix.len(), 3, "{fix:?}");
    assert!(fix[2].contains("SHORT_CIRCUIT") && fix[2].contains("remains off until cleared"));
    assert!(fix[1].contains("A of an 8 A breaker (≥ 80 %)"), "{fix:?}");
    assert!(r.view.any_failed());
    // Each circuit was on no longer than its plan says.
    let sent_at = |on| {
        let sent = Message::DevicePower(power(17, on));
        r.sent.iter().find(|(_, p)| p.message == sent).unwrap().0
    };
    let (on_at, off_at) = (sent_at(true), sent_at(false));
    assert!(
        off_at - on_at <= Duration::from_secs(5),
        "{:?}",
        off_at - on_at
    );
    assert!(
        off_at - on_at >= Duration::from_millis(900),
        "two fresh statuses"
    );
}

/// "Tight" is 80 % and over, 80 % itself included, for the breaker sizes where 0.8 × the
/// rating is not exact in binary (worked by hand: 80 % of 13 A is 10.4 A, 104 tenths).
#[test]
fn a_draw_of_exactly_80_percent_of_the_breaker_is_tight() {
    use super::circuits::judge;
    use crate::protocol::message::Tenths;
    for b in [9u8, 13, 18, 21, 26] {
        let at = u16::from(b) * 8;
        assert_eq!(
            judge(Tenths(at), Some(b)),
            CircuitFinding::NearBreaker {
                amps: Tenths(at).value(),
                breaker: b
            },
            "{b} A"
        );
        assert_eq!(
            judge(Tenths(at - 1), Some(b)),
            CircuitFinding::Within {
                amps: Tenths(at - 1).value(),
                breaker: b
            },
            "{b} A"
        );
    }
    assert!(
        judge(Tenths(104), Some(13))
            .words()
            .starts_with("draws 10.4 A of a 13 A breaker (≥ 80 %)")
    );
    assert_eq!(judge(Tenths(0), Some(13)), CircuitFinding::NoCurrent);
    assert_eq!(judge(Tenths(1), Some(13)).mark(), Mark::Pass);
}

#[test]
fn a_unit_that_never_switches_the_circuit_on_is_said_so() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    r.deaf_to_power = true;
    r.start();
    r.run_until(10_000, |r| r.circuit(4) != &Outcome::NotRun);
    assert_eq!(r.circuit(4), &Outcome::Found(CircuitFinding::DidNotSwitch));
    assert_eq!(
        r.powers(4),
        vec![true, true, false],
        "tried twice, then put back"
    );
}

#[test]
fn skipping_a_circuit_while_it_is_on_still_puts_it_back() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    r.start();
    r.run_until(10_000, |r| {
        r.view.current == r.view.circuits.iter().position(|c| c.id == 4) && r.on(4)
    });
    r.cmd(Command::SkipItem);
    assert!(matches!(r.circuit(4), Outcome::Skipped(_)));
    r.run(2000);
    assert_eq!(r.powers(4), vec![true, false]);
    assert!(!r.on(4));
}

// ----- motors -----

#[test]
fn motors_run_each_way_through_the_controller_and_go_back() {
    let mut r = Rig::new(Rig::only(&[Step::Motors]));
    r.start();
    r.run_until(20_000, |r| r.view.step == Step::Done);
    for m in &r.view.motors {
        assert_eq!(m.outcome, Outcome::Found(MotorFinding::Moves), "{m:?}");
        let p = &m.positions;
        assert!(p.len() >= 3, "{p:?}");
        let back = (i32::from(*p.last().unwrap()) - i32::from(p[0])).abs();
        assert!(back <= super::motors::BACK_WITHIN, "{p:?}");
    }
    // Flaps at their up endpoint: the first run is down, away from it.
    assert!(r.view.motors[0].positions[1] > r.view.motors[0].positions[0]);
    // Every run ended with its stop on the wire.
    let moves: Vec<&Packet> = r
        .sent
        .iter()
        .map(|(_, p)| p)
        .filter(|p| matches!(p.message, Message::FlapMove(_) | Message::TrimMove(_)))
        .collect();
    let last = moves.last().unwrap();
    assert!(matches!(last.message, Message::TrimMove(t) if !t.on));
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::RunDone);
    // No gap over 250 ms inside a run.
    let mut prev: Option<Duration> = None;
    for (at, p) in &r.sent {
        let on = match p.message {
            Message::FlapMove(f) => f.on,
            Message::TrimMove(t) => t.on,
            _ => continue,
        };
        if let Some(pv) = prev {
            assert!(*at - pv <= Duration::from_millis(250), "gap {:?}", *at - pv);
        }
        prev = on.then_some(*at);
    }
}

fn flaps_at(r: &Rig) -> u8 {
    r.model.live_flap_trim(r.now).unwrap().flap_position
}

impl Rig {
    /// The check goes on to its end: the flaps move the commanded way and are run
    /// back to 20, where the check found them (`what` happened on the way).
    fn flaps_pass_and_are_back_at_20(&mut self, what: &str) {
        self.run_until(20_000, |r| r.view.step == Step::Done);
        assert_eq!(
            self.view.motors[0].outcome,
            Outcome::Found(MotorFinding::Moves)
        );
        let back = flaps_at(self);
        assert!(
            (i32::from(back) - 20).abs() <= super::motors::BACK_WITHIN,
            "left at {back}, the check found it at 20, {what}"
        );
    }
}

/// Skipped in the middle of its first run, the flaps are still run back to where the
/// check found them (20, their up endpoint), and the result says it was skipped.
#[test]
fn a_motor_skipped_during_its_first_run_is_run_back() {
    let mut r = Rig::new(Rig::only(&[Step::Motors]));
    r.start();
    r.past_probes();
    r.run(400);
    assert_eq!(r.ctl.running().unwrap().motor, Motor::Flaps);
    r.run(100);
    let out = flaps_at(&r);
    assert!(out >= 20 + 6, "it moved: {out}");
    r.cmd(Command::SkipItem);
    r.run_until(20_000, |r| r.view.step == Step::Done);
    let back = flaps_at(&r);
    assert!(
        (i32::from(back) - 20).abs() <= super::motors::BACK_WITHIN,
        "left at {back}, was at 20, skipped at {out}"
    );
    assert!(
        matches!(&r.view.motors[0].outcome, Outcome::Skipped(w) if w == "you skipped it"),
        "{:?}",
        r.view.motors[0].outcome
    );
}

/// A run cut short (focus lost) and tried again still ends where the check found the
/// flaps, not where the first try was cut.
#[test]
fn a_retry_after_a_pause_returns_the_motor_to_where_the_check_found_it() {
    let mut r = Rig::new(Rig::only(&[Step::Motors]));
    r.start();
    r.past_probes();
    r.run(300);
    assert_eq!(r.ctl.running().unwrap().motor, Motor::Flaps);
    let p = r.ctl.on_focus_lost(r.now);
    r.send(p);
    r.run(600);
    let paused_at = flaps_at(&r);
    assert!(
        paused_at >= 20 + 6,
        "it moved before the pause: {paused_at}"
    );
    assert!(
        r.view
            .prompt
            .as_ref()
            .unwrap()
            .todo
            .contains("r: run the test again")
    );
    // Back at the page, the person asks for it again.
    r.ctl.on_focus_gained(r.now);
    r.cmd(Command::Retry);
    r.flaps_pass_and_are_back_at_20(&format!("paused at {paused_at}"));
    assert_eq!(r.view.motors[0].positions[0], 20);
}

#[test]
fn the_motor_findings_from_positions() {
    use super::motors::judge;
    use crate::control::Direction::{Down, Up};
    let r = Rig::new(Rig::only(&[Step::Motors]));
    let ft = *r.model.live_flap_trim(r.now).unwrap(); // flaps up 20, down 220
    let f = Motor::Flaps;
    assert_eq!(
        judge(f, [Down, Up], [20, 32], [12, -12], &ft),
        MotorFinding::Moves
    );
    assert_eq!(
        judge(f, [Down, Up], [100, 88], [-12, 12], &ft),
        MotorFinding::Reversed
    );
    assert_eq!(
        judge(f, [Down, Up], [100, 100], [0, 1], &ft),
        MotorFinding::NoMovement
    );
    // Down at the down endpoint does not move; up does.
    assert_eq!(
        judge(f, [Down, Up], [219, 219], [0, -12], &ft),
        MotorFinding::AgainstLimit
    );
    // The same stall mid-travel is no movement.
    assert_eq!(
        judge(f, [Down, Up], [120, 120], [0, -12], &ft),
        MotorFinding::NoMovement
    );
    assert_eq!(MotorFinding::AgainstLimit.mark(), Mark::Warn);
    // A run stopped at the other endpoint is reversed only if its
    // position went that way: one that went its own way (or nowhere) is not.
    use super::motors::judge_runs;
    assert_ne!(
        judge_runs(f, [Down, Up], [20, 60], [0, -40], [Some(20), None], &ft),
        MotorFinding::Reversed
    );
    assert_ne!(
        judge_runs(f, [Down, Up], [20, 60], [1, -40], [Some(20), None], &ft),
        MotorFinding::Reversed
    );
    assert_eq!(
        judge_runs(f, [Down, Up], [21, 60], [-1, -40], [Some(20), None], &ft),
        MotorFinding::Reversed
    );
}

#[test]
fn a_motor_fault_mid_run_is_its_finding_and_the_stop_goes_out() {
    let mut r = Rig::new(Rig::only(&[Step::Motors]));
    r.start();
    r.past_probes();
    r.run(200);
    assert!(r.ctl.running().is_some());
    r.unit.apply(
        SimCommand::Fault {
            device: 0,
            code: FaultCode::FlapRunaway,
        },
        r.now,
    );
    r.run_until(2000, |r| r.view.motors[0].outcome != Outcome::NotRun);
    assert_eq!(
        r.view.motors[0].outcome,
        Outcome::Found(MotorFinding::Faulted(FaultCode::FlapRunaway))
    );
    assert!(matches!(
        r.ctl.last_stop().unwrap().reason,
        StopReason::MotorFault(_)
    ));
    assert!(
        r.sent
            .iter()
            .any(|(_, p)| matches!(p.message, Message::FlapMove(f) if !f.on))
    );
    assert!(r.view.interrupted.is_none());
    r.run_until(20_000, |r| r.view.step == Step::Done);
    assert_eq!(
        r.view.motors[1].outcome,
        Outcome::Found(MotorFinding::Moves)
    );
}

// ----- interruptions -----

impl Rig {
    /// EFIS (device 2, not under test) shorts; the check runs until it has ended.
    fn efis_faults(&mut self) {
        let short = SimCommand::Short {
            device: 2,
            on: true,
        };
        self.unit.apply(short, self.now);
        self.run_until(5000, |r| r.flow.finished());
    }
}

/// Runs the circuit step until Landing Lt (17) is on, under test.
fn landing_light_on(r: &mut Rig) {
    r.start();
    r.run_until(30_000, |r| {
        r.view.current == r.view.circuits.iter().position(|c| c.id == 17) && r.on(17)
    });
}

#[test]
fn quit_mid_circuit_switches_it_back_off_and_waits_to_see_it() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    landing_light_on(&mut r);
    r.interrupt(Cause::Quit, true);
    assert_eq!(r.powers(17), vec![true, false]);
    assert!(!r.flow.finished(), "waits to see it off");
    r.run_until(3000, |r| r.flow.finished());
    let i = r.view.interrupted.clone().unwrap();
    assert_eq!(i.cause, "stopped by you");
    assert_eq!(i.left, vec![], "seen off: nothing left changed");
    assert!(r.view.to_cycle.iter().any(|(id, ..)| *id == 17));
    assert_eq!(r.circuit(18), &Outcome::NotRun, "never reached");
    assert_eq!(
        r.view.step,
        Step::Circuits,
        "stopped there, the report not reached"
    );
}

/// The check ends with Landing Lt on and cannot see it go back off (a signal it cannot
/// wait after, silence, a link that cannot send): its off is sent all the same, and
/// it is listed as left, in words that say why it is not known off.
#[test]
fn a_circuit_the_check_cannot_see_off_is_listed_as_left() {
    type End = fn(&mut Rig);
    let cases: [(&str, End, &str, &str); 3] = [
        (
            "a signal",
            |r| r.interrupt(Cause::Signal("SIGTERM".into()), false),
            "ended by a signal (SIGTERM)",
            "ON when the check stopped: DEVICE_POWER off sent, not confirmed",
        ),
        (
            "communication lost",
            |r| {
                r.unit
                    .apply(SimCommand::Silent(Duration::from_secs(10)), r.now);
                r.run_until(4000, |r| r.flow.finished());
            },
            "COMMUNICATION LOST",
            "unknown: it was ON; DEVICE_POWER off sent, not confirmed (COMMUNICATION LOST)",
        ),
        (
            "a link that cannot send",
            |r| {
                r.model.note_write_error(r.now, "Input/output error".into());
                r.cut = true;
                r.run(10);
            },
            "the link could not send: Input/output error",
            "unknown: it was ON; DEVICE_POWER off sent, not confirmed (the link could not send)",
        ),
    ];
    for (what, end, cause, state) in cases {
        let mut r = Rig::new(Rig::only(&[Step::Circuits]));
        landing_light_on(&mut r);
        end(&mut r);
        assert!(r.flow.finished(), "{what}");
        let i = r.view.interrupted.clone().unwrap();
        assert_eq!(i.cause, cause, "{what}");
        assert_eq!(
            i.left,
            vec![LeftBehind::new(17, "Landing Lt".into(), state.into())],
            "{what}"
        );
        assert_eq!(r.powers(17), vec![true, false], "{what}: the off is sent");
    }
}

#[test]
fn a_fault_elsewhere_mid_step_stops_the_check_and_puts_the_circuit_back() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    landing_light_on(&mut r);
    // EFIS (measured already, on by its switch) faults while Landing Lt is on.
    r.efis_faults();
    let i = r.view.interrupted.clone().unwrap();
    assert_eq!(i.cause, "EFIS faulted (SHORT_CIRCUIT)");
    assert_eq!(i.left, vec![], "Landing Lt seen back off");
    assert!(!r.on(17));
    assert_eq!(r.powers(17), vec![true, false]);
    assert_eq!(r.circuit(18), &Outcome::NotRun);
}

/// The check ends mid motor run (the person quits, a fault elsewhere, a panic): the
/// run is stopped for that reason, not as a quit the person never asked for; its stop
/// goes out and nothing after it, and the motor is listed where it was left.
#[test]
fn a_check_ended_mid_motor_run_stops_it_for_its_reason() {
    type End = fn(&mut Rig);
    let cases: [(&str, End, StopReason, &str); 3] = [
        (
            "quit",
            |r| r.interrupt(Cause::Quit, true),
            StopReason::Quit,
            "stopped by you",
        ),
        (
            "a fault elsewhere",
            |r| {
                r.efis_faults();
            },
            StopReason::UnitFault,
            "EFIS faulted (SHORT_CIRCUIT)",
        ),
        (
            "a panic",
            |r| r.interrupt(Cause::Panic, false),
            StopReason::Panic,
            "the program failed",
        ),
    ];
    // The move messages sent since the `from`th, on or off.
    let moves_since = |r: &Rig, from: usize| -> Vec<bool> {
        r.moves()[from..].iter().map(|&(_, on)| on).collect()
    };
    for (what, end, reason, cause) in cases {
        // A run long enough for the fault's broadcast to come during it.
        let mut opts = Rig::only(&[Step::Motors]);
        opts.timing.motor_run = Duration::from_secs(4);
        let mut r = Rig::new(opts);
        r.start();
        r.past_probes();
        r.run(300);
        assert_eq!(r.ctl.running().unwrap().motor, Motor::Flaps, "{what}");
        let before = r.moves().len();
        end(&mut r);
        assert!(r.ctl.running().is_none(), "{what}");
        assert_eq!(r.ctl.last_stop().unwrap().reason, reason, "{what}");
        assert!(
            moves_since(&r, before).contains(&false),
            "{what}: the stop went out"
        );
        let stopped = r.moves().len();
        r.run(300);
        assert!(
            !moves_since(&r, stopped).contains(&true),
            "{what}: nothing after the stop"
        );
        let i = r.view.interrupted.clone().unwrap();
        assert_eq!(i.cause, cause, "{what}");
        assert_eq!(i.left.len(), 1, "{what}: {:?}", i.left);
        assert_eq!(i.left[0].id, 0, "{what}");
        assert!(
            i.left[0].state.contains("it was at 20: not run back"),
            "{what}: {:?}",
            i.left
        );
    }
}

#[test]
fn communication_lost_mid_motor_run_is_an_interruption() {
    let mut r = Rig::new(Rig::only(&[Step::Motors]));
    r.start();
    r.run(300);
    r.unit
        .apply(SimCommand::Silent(Duration::from_secs(10)), r.now);
    r.run_until(4000, |r| r.flow.finished());
    assert!(r.ctl.running().is_none());
    let i = r.view.interrupted.clone().unwrap();
    // The controller's own tick stops the run first (FLAP_TRIM_STATUS goes quiet
    // after 1 s, before COMMUNICATION LOST at 2.5 s).
    assert!(
        i.cause.contains("no live flap/trim status") || i.cause == "COMMUNICATION LOST",
        "{}",
        i.cause
    );
    assert!(
        r.sent
            .iter()
            .any(|(_, p)| matches!(p.message, Message::FlapMove(f) if !f.on))
    );
}

#[test]
fn the_whole_check_in_order_with_results_as_they_come() {
    let mut r = Rig::new(Options {
        skip: vec![Step::Switches],
        ..Options::default()
    });
    r.start();
    r.run_until(60_000, |r| r.flow.finished());
    assert!(r.view.interrupted.is_none());
    assert_eq!(r.view.step, Step::Done);
    let order: Vec<&str> = r
        .progress
        .iter()
        .filter_map(|n| {
            if n.contains("Landing Lt (10A-1)") {
                Some("circuit")
            } else if n.contains("Flaps:") {
                Some("motor")
            } else if n.contains("Load analysis") {
                Some("loads")
            } else {
                None
            }
        })
        .collect();
    assert_eq!(order, vec!["circuit", "motor", "loads"], "{:?}", r.progress);
    assert!(r.progress.last().unwrap().starts_with("Check complete"));
}

// ===== check-motors: DEVICE_POWER through control's rules, motors at their endpoints =====

impl Rig {
    /// `ms` of the page's loop, as [`Rig::run`], with every message named `drop`
    /// lost on the way from the unit.
    fn run_dropping(&mut self, ms: u64, drop: &str) {
        self.run_but(ms, Some(drop));
    }
}

/// The check switches a circuit on only by the page's own rule
/// (`control::device_power`). A unit whose DEVICE_STATUS went quiet (SYSTEM_STATUS
/// still comes, so communication is not lost) leaves each circuit's state unknown,
/// which the page's power key refuses: the circuit's line says so in control's
/// words, and no DEVICE_POWER goes out for it.
#[test]
fn a_circuit_the_page_may_not_switch_is_not_switched_and_says_why() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    r.start();
    // EFIS (always on) is measured first, nothing sent; from now on no DEVICE_STATUS.
    r.run_dropping(9000, "DEVICE_STATUS");
    assert!(!r.model.comm_lost(r.now));
    let words = "not switched: Nav Lt's state is not known yet";
    assert_eq!(r.circuit(4), &Outcome::Skipped(words.to_string()));
    assert!(r.powers(4).is_empty(), "nothing on the wire for it");
    assert!(
        r.progress.iter().any(|n| n.contains(words)),
        "{:?}",
        r.progress
    );
    for id in [5, 17, 18] {
        assert!(
            matches!(r.circuit(id), Outcome::Skipped(w) if w.starts_with("not switched: ")),
            "device {id}: {:?}",
            r.circuit(id)
        );
        assert!(r.powers(id).is_empty(), "device {id}");
    }
    assert!(
        !r.sent
            .iter()
            .any(|(_, p)| matches!(p.message, Message::DevicePower(_))),
        "no DEVICE_POWER at all"
    );
}

/// The test aircraft with the pitch trim parked at `pos` (endpoints up 30, down 220),
/// its leads swapped if `reversed`.
fn pitch_at(pos: u8, reversed: bool) -> String {
    scenario().replace(
        "power = 100\nposition = 125",
        &format!("power = 100\nposition = {pos}\nreversed = {reversed}"),
    )
}

/// `opts`, with the circuits or motors `names` excluded (`--exclude`).
fn excluding(names: &[&str], opts: Options) -> Options {
    Options {
        choices: Choices {
            exclude: names.iter().map(|n| n.to_string()).collect(),
            ..Choices::default()
        },
        ..opts
    }
}

/// The test aircraft with the flaps at `pos`, between endpoints `up` and `down`.
fn flaps_at_between(pos: u8, up: u8, down: u8) -> String {
    scenario().replace(
        "[flap]\nenabled = true\nup = 20\ndown = 220\nposition = 20",
        &format!("[flap]\nenabled = true\nup = {up}\ndown = {down}\nposition = {pos}"),
    )
}

impl Rig {
    /// Runs `ms` as [`Rig::run`], keeping the unit's own position of `motor` (its
    /// sensor, not what the page heard) every 10 ms.
    fn run_watching(&mut self, ms: u64, motor: Motor) -> Vec<u8> {
        let mut seen = Vec::new();
        for _ in 0..ms / 10 {
            self.run(10);
            seen.push(self.unit_at(motor));
        }
        seen
    }

    /// The unit's own position of `motor`: its sensor, not what the page heard.
    fn unit_at(&self, motor: Motor) -> u8 {
        let s = self.unit.snapshot(self.now);
        match motor {
            Motor::Flaps => s.flap_position,
            Motor::Trim(TrimKind::Pitch) => s.pitch_trim_position,
            Motor::Trim(TrimKind::Roll) => s.roll_trim_position,
        }
    }

    /// `motor` was run back to `at`, where the check found it.
    fn assert_back_at(&self, motor: Motor, at: u8) {
        let back = self.unit_at(motor);
        assert!(
            (i32::from(back) - i32::from(at)).abs() <= super::motors::BACK_WITHIN,
            "left at {back}, the check found it at {at}; {:?}",
            self.progress
        );
    }

    /// Starts the check and runs it to its end (at most `limit` × 10 ms), keeping
    /// the unit's own position of `motor` every 10 ms.
    fn check_watching(&mut self, motor: Motor, limit: usize) -> Vec<u8> {
        self.start();
        let mut seen = Vec::new();
        while self.view.step != Step::Done && seen.len() < limit {
            seen.extend(self.run_watching(10, motor));
        }
        seen
    }

    /// The TRIM_MOVEs sent from `from` on, as (time since start, on).
    fn timed_trim_moves_since(&self, from: usize) -> Vec<(Duration, bool)> {
        self.sent[from..]
            .iter()
            .filter_map(|(at, p)| match p.message {
                Message::TrimMove(t) => Some((*at, t.on)),
                _ => None,
            })
            .collect()
    }

    /// The move messages sent, as (ms since start, on).
    fn moves(&self) -> Vec<(u128, bool)> {
        self.sent
            .iter()
            .filter_map(|(at, p)| match p.message {
                Message::FlapMove(f) => Some((at.as_millis(), f.on)),
                Message::TrimMove(t) => Some((at.as_millis(), t.on)),
                _ => None,
            })
            .collect()
    }
}

const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

impl Rig {
    /// A run of the check's: the pitch trim up for `ms`.
    fn pitch_up_for(&mut self, ms: u64) -> Result<Vec<Packet>, crate::control::run::MotorRefusal> {
        self.ctl.start(
            crate::audit::Origin::Check,
            &self.model,
            PITCH,
            crate::control::Direction::Up,
            crate::control::How::For {
                length: Duration::from_millis(ms),
                way: None,
            },
            self.now,
        )
    }

    /// The pitch trim, the second motor, was found `finding`.
    fn assert_pitch_found(&self, finding: MotorFinding) {
        let m = &self.view.motors[1];
        assert_eq!(
            m.outcome,
            Outcome::Found(finding),
            "{m:?} {:?}",
            self.progress
        );
    }
}

/// The unit does not stop TRIM_MOVE at the endpoints (Table 15 note
/// 4), so the page does. A timed run (the check's) of the pitch trim 5 counts from its
/// up endpoint, heading up for 1.5 s (37 counts at 25 a second), ends at the endpoint
/// with its stop on the wire, and the trim never passes it.
#[test]
fn a_run_heading_up_5_counts_from_the_up_endpoint_stops_there() {
    let mut r = Rig::with(&pitch_at(35, false), Rig::only(&[Step::Motors]));
    let p = r.pitch_up_for(1500).unwrap();
    let t_start = (r.now - r.t0).as_millis();
    r.send(p);
    let seen = r.run_watching(2000, PITCH);
    let lowest = *seen.iter().min().unwrap();
    assert!(lowest >= 30, "passed the up endpoint 30: down to {lowest}");
    assert!(lowest <= 33, "stopped short of the endpoint: {lowest}");
    let stop = *r.ctl.last_stop().unwrap();
    assert_eq!(stop.reason, StopReason::AtEndpoint(30));
    assert!(stop.ran_for < Duration::from_millis(500), "{stop:?}");
    // The stop went out as a TRIM_MOVE off, and nothing after it.
    let moves = r.moves();
    let last = *moves.last().unwrap();
    assert!(!last.1, "the last move is a stop: {moves:?}");
    assert!(last.0 - t_start < 500);
    assert_eq!(moves.iter().filter(|(_, on)| !on).count(), 1);
    // And from there it does not start up again: no room.
    let refused = r.pitch_up_for(600);
    assert!(
        matches!(&refused, Err(w) if w.words.contains("at its up endpoint")),
        "{refused:?}"
    );
}

/// The keys' context with the pitch trim's row selected: on the device list, or on
/// the setup screens (`setup`), where motor keys run past the endpoints.
fn pitch_ctx(setup: bool) -> crate::control::KeyContext {
    use crate::control::Selected;
    use crate::model::{CircuitKind, CircuitState};
    crate::control::KeyContext {
        selected: Some(Selected {
            id: PITCH.device_id(),
            kind: CircuitKind::Trim(TrimKind::Pitch),
            state: CircuitState::Off,
        }),
        overlay_open: false,
        past_endpoints: setup,
    }
}

/// The same rule for the page's own motor key on the device list: held up from 5
/// counts below the endpoint, the trim stops there (the key still held). On the setup
/// screens, where endpoints are found by running past them, the same hold goes on.
#[test]
fn a_motor_key_on_the_device_list_stops_at_the_endpoint_but_not_on_the_setup_screens() {
    use crate::control::StreamerConfig;
    use crate::control::run_state::ReleaseMode;
    use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
    for setup in [false, true] {
        let mut r = Rig::with(&pitch_at(35, false), Rig::only(&[Step::Motors]));
        r.ctl = Controller::new(StreamerConfig {
            release_mode: ReleaseMode::KeyRelease,
            ..StreamerConfig::default()
        });
        let ctx = pitch_ctx(setup);
        let mut lowest = 255;
        for i in 0..60 {
            let kind = if i == 0 {
                KeyEventKind::Press
            } else {
                KeyEventKind::Repeat
            };
            let key = KeyEvent::new_with_kind(KeyCode::Char('u'), KeyModifiers::NONE, kind);
            let out = r.ctl.handle_key(key, &ctx, &r.model, r.now);
            r.send(out.packets);
            lowest = lowest.min(*r.run_watching(30, PITCH).iter().min().unwrap());
        }
        if setup {
            assert!(lowest < 25, "the setup screen runs past it: {lowest}");
            assert!(r.ctl.running().is_some());
        } else {
            assert!((30..=33).contains(&lowest), "device list: {lowest}");
            assert_eq!(
                r.ctl.last_stop().unwrap().reason,
                StopReason::AtEndpoint(30)
            );
            assert!(
                r.ctl.running().is_none(),
                "the held key does not restart it"
            );
            assert!(!r.moves().last().unwrap().1, "its stop on the wire");
        }
    }
}

/// The first run goes toward the side with more room, whichever that is: from 200
/// (20 counts from the down endpoint 220, 170 from up 30) the first run is up.
#[test]
fn the_first_direction_is_toward_the_side_with_more_room() {
    for (pos, first_down) in [(200u8, false), (60, true)] {
        let mut r = Rig::with(&pitch_at(pos, false), Rig::only(&[Step::Motors]));
        r.start();
        r.run_until(20_000, |r| r.view.step == Step::Done);
        let m = &r.view.motors[1];
        assert_eq!(m.motor, PITCH);
        assert_eq!(m.outcome, Outcome::Found(MotorFinding::Moves), "{m:?}");
        let p = &m.positions;
        assert_eq!(p[0], pos);
        assert_eq!(p[1] > p[0], first_down, "from {pos}: {p:?}");
    }
}

/// A reversed pitch trim 5 (or 8) counts below its up endpoint: the first run is
/// "down" (more room), but the motor goes up, toward 30. It is stopped as moving
/// against its command, never past 30, found reversed, and put back: the run back is "up", which on this motor
/// moves away from 30, so the endpoint it keeps off is the down one.
#[test]
fn a_reversed_motor_near_an_endpoint_is_stopped_there_and_found_reversed() {
    for at in [35, 38] {
        let mut r = Rig::with(&pitch_at(at, true), Rig::only(&[Step::Motors]));
        let seen = r.check_watching(PITCH, 2000);
        let lowest = *seen.iter().min().unwrap();
        assert!(
            lowest >= 30,
            "from {at}: passed the up endpoint 30: {lowest}"
        );
        let m = &r.view.motors[1];
        assert_eq!(m.outcome, Outcome::Found(MotorFinding::Reversed), "{m:?}");
        assert!(
            r.progress.iter().any(|n| n.contains(
                "pitch trim moved up when asked down: its leads or its \
                                     sensor may be swapped; stopped"
            )),
            "{:?}",
            r.progress
        );
        r.assert_back_at(PITCH, at);
    }
}

/// A pitch trim with its leads swapped, parked exactly at its up
/// endpoint 30 (or one count off it): the check's first run is "down" (all the room),
/// but the trim really goes up. Its way is not known yet and the endpoint behind it
/// is near, so the run starts as probes short enough that, at the fastest motor
/// speed, it passes 30 by less than the sensor's one count of noise: it never reads
/// below 29 from 30 (nor below 30 from 31), every probe ends with its stop on the
/// wire, it is found reversed and it is not run on toward 28.
#[test]
fn a_reversed_motor_parked_at_its_endpoint_is_probed_not_driven_past_it() {
    for (at, floor) in [(30u8, 29u8), (31, 30)] {
        let mut r = Rig::with(&pitch_at(at, true), Rig::only(&[Step::Motors]));
        let seen = r.check_watching(PITCH, 3000);
        let lowest = *seen.iter().min().unwrap();
        assert!(
            lowest >= floor,
            "from {at}: down to {lowest}; {:?}",
            r.progress
        );
        r.assert_pitch_found(MotorFinding::Reversed);
        // Every TRIM_MOVE on is followed by its off: no run ended by starving.
        let moves = r.timed_trim_moves_since(0);
        assert!(!moves.is_empty() && !moves.last().unwrap().1, "{moves:?}");
        assert_eq!(r.unit.snapshot(r.now).pitch_trim_starvations, 0);
    }
}

/// The same probes on a trim wired right: from its up endpoint it shows its way
/// within a probe or two, runs the rest of the test run, and passes.
#[test]
fn a_motor_parked_at_its_endpoint_probes_then_runs_and_passes() {
    let mut r = Rig::with(&pitch_at(30, false), Rig::only(&[Step::Motors]));
    let seen = r.check_watching(PITCH, 3000);
    assert!(*seen.iter().min().unwrap() >= 30, "passed its up endpoint");
    r.assert_pitch_found(MotorFinding::Moves);
    let m = &r.view.motors[1];
    assert!(m.positions[1] >= 40, "the rest of the run was made: {m:?}");
    r.assert_back_at(PITCH, 30);
}

/// Flaps between close endpoints (up 20, down 50) at 38, with 1.5 s runs (30 counts
/// at 20 a second): each run ends at its endpoint, the flaps never leave 20..=50, and
/// having moved they pass.
#[test]
fn flap_runs_longer_than_their_room_stop_at_both_endpoints() {
    let toml = flaps_at_between(38, 20, 50);
    let mut opts = Rig::only(&[Step::Motors]);
    opts.timing.motor_run = Duration::from_millis(1500);
    let mut r = Rig::with(&toml, opts);
    r.start();
    let mut seen = Vec::new();
    while r.view.motors[0].outcome == Outcome::NotRun && seen.len() < 2000 {
        seen.extend(r.run_watching(10, Motor::Flaps));
    }
    let (lo, hi) = (*seen.iter().min().unwrap(), *seen.iter().max().unwrap());
    assert!(lo >= 20 && hi <= 50, "left 20..=50: {lo}..={hi}");
    assert!(lo <= 23, "ran up to the endpoint: {lo}");
    assert_eq!(
        r.view.motors[0].outcome,
        Outcome::Found(MotorFinding::Moves)
    );
    assert!(
        r.progress
            .iter()
            .any(|n| n.contains("stopped at its endpoint (20)")),
        "{:?}",
        r.progress
    );
    r.run_until(20_000, |r| r.view.step == Step::Done);
    r.assert_back_at(Motor::Flaps, 38);
}

/// Endpoints 2 counts apart with the flaps between: no run could show a movement
/// without reaching one, so none is made, and the line says why.
#[test]
fn a_motor_with_no_room_either_way_is_not_run_and_says_why() {
    let toml = flaps_at_between(21, 20, 22);
    let mut r = Rig::with(&toml, Rig::only(&[Step::Motors]));
    r.start();
    r.run_until(20_000, |r| r.view.step == Step::Done);
    assert_eq!(
        r.view.motors[0].outcome,
        Outcome::Skipped(
            "not run: no room to move it either way (position 21, up endpoint 20, down \
             endpoint 22)"
                .into()
        )
    );
    assert!(
        !r.sent
            .iter()
            .any(|(_, p)| matches!(p.message, Message::FlapMove(_))),
        "no FLAP_MOVE at all"
    );
}

/// FLAP_TRIM_STATUS stops coming in the middle of a run (everything else still
/// comes): the run is stopped once the position is 0.4 s old, not at the model's
/// second for "no live status", and the check waits with the reason in words.
#[test]
fn a_stale_position_mid_run_stops_the_motor_and_says_why() {
    let mut opts = Rig::only(&[Step::Motors]);
    opts.timing.motor_run = Duration::from_millis(2000);
    let mut r = Rig::new(opts);
    r.start();
    r.past_probes();
    r.run(300);
    assert_eq!(r.ctl.running().unwrap().motor, Motor::Flaps);
    let last_heard = r.model.flap_trim.unwrap().at;
    r.run_dropping(1000, "FLAP_TRIM_STATUS");
    let stop = *r.ctl.last_stop().unwrap();
    assert_eq!(stop.reason, StopReason::PositionStale);
    let late = stop.at - last_heard;
    assert!(
        late > super::super::control::endpoints::POSITION_FRESH
            && late <= super::super::control::endpoints::POSITION_FRESH + Duration::from_millis(20),
        "stopped {late:?} after the last position"
    );
    assert!(!r.moves().last().unwrap().1, "its stop on the wire");
    let todo = &r.view.prompt.as_ref().unwrap().todo;
    assert!(
        todo.contains("The flaps stopped: its position is not fresh")
            && todo.contains("r: run the test again"),
        "{todo}"
    );
    // Positions again: retried, it finishes and is put back.
    r.run(300);
    r.cmd(Command::Retry);
    r.flaps_pass_and_are_back_at_20("retried after the position went stale");
}

// ===== check-switches: the switch step never powers what is left alone, and says
// truthfully why circuits did not follow =====

/// The scenario with Strobe moved to switch 4 beside Pitot Heat, and Landing Lt to
/// switch 1 beside the alternator field.
fn shared_switches() -> String {
    scenario()
        .replace(
            "name = \"Strobe\"\nbreaker = 4\nswitch = 2",
            "name = \"Strobe\"\nbreaker = 4\nswitch = 4",
        )
        .replace(
            "name = \"Landing Lt\"\nbreaker = 8\nswitch = 3",
            "name = \"Landing Lt\"\nbreaker = 8\nswitch = 1",
        )
}

fn skip_words(r: &Rig, input: Input) -> String {
    match r.switch(input) {
        Outcome::Skipped(w) => w.clone(),
        o => panic!("{input:?}: {o:?}"),
    }
}

#[test]
fn an_input_that_also_powers_something_left_alone_is_never_asked() {
    let mut r = Rig::with(&shared_switches(), Rig::switches_then_motors());
    // Before power, the plan says which inputs it will not ask for, and why.
    let unasked: Vec<(Input, &str)> = r
        .view
        .unasked
        .iter()
        .map(|u| (u.input, u.why.as_str()))
        .collect();
    assert_eq!(
        unasked,
        vec![
            (
                Input::Switch(1),
                "switch 1 also powers Main Alt (an alternator field): not asked"
            ),
            (
                Input::Switch(4),
                "switch 4 also powers Pitot Heat (excluded): not asked"
            ),
            (
                Input::Switch(7),
                "switch 7 powers only Standby Alt (an alternator field): not asked"
            ),
        ]
    );
    r.start();
    for n in [1, 4, 7] {
        assert_eq!(
            skip_words(&r, Input::Switch(n)),
            r.view
                .unasked
                .iter()
                .find(|u| u.input == Input::Switch(n))
                .unwrap()
                .why
        );
    }
    assert!(
        r.progress
            .iter()
            .any(|n| n == "– switch 4 also powers Pitot Heat (excluded): not asked"),
        "{:?}",
        r.progress
    );
    // The person does every input asked for; none of them is 1, 4 or 7, and nothing
    // on those switches is ever switched.
    let mut asked = Vec::new();
    while r.view.step == Step::Switches {
        let i = r.view.current.unwrap();
        let input = r.view.switches[i].input;
        asked.push(input);
        let todo = r.view.prompt.as_ref().unwrap().todo.clone();
        assert!(
            !["switch 1 ", "switch 4 ", "switch 7 "]
                .iter()
                .any(|s| todo.contains(s)),
            "{todo}"
        );
        r.run(100);
        match input {
            Input::Switch(n) => r.flip_on_off(n, 1500),
            _ => r.cmd(Command::SkipItem),
        }
        r.run_until(6000, |r| {
            r.view.current != Some(i) || r.view.step != Step::Switches
        });
    }
    assert_eq!(
        asked,
        vec![
            Input::Switch(2),
            Input::FlapUp,
            Input::FlapDown,
            Input::PitchTrimUp,
            Input::PitchTrimDown
        ]
    );
    assert_eq!(
        r.switch(Input::Switch(2)),
        &Outcome::Found(SwitchFinding::Passed)
    );
    for id in [3, 5, 7, 17, 23] {
        assert!(r.powers(id).is_empty(), "device {id}");
        assert!(!r.on(id), "device {id} never powered");
    }
}

#[test]
fn a_circuit_excluded_by_name_takes_its_switch_out_and_an_excluded_motor_its_inputs() {
    let mut r = Rig::new(excluding(&["Nav Lt", "Flaps"], Rig::switches_then_motors()));
    r.start();
    for (input, words) in [
        (Input::Switch(2), "switch 2 also powers Nav Lt (excluded)"),
        (Input::FlapUp, "flap switch UP drives Flaps (excluded)"),
        (Input::FlapDown, "flap switch DOWN drives Flaps (excluded)"),
    ] {
        assert_eq!(skip_words(&r, input), format!("{words}: not asked"));
    }
    // The first input asked is switch 3; the pitch trim's inputs are still asked.
    assert_eq!(
        r.view.switches[r.view.current.unwrap()].input,
        Input::Switch(3)
    );
    assert!(
        r.view
            .switches
            .iter()
            .any(|s| s.input == Input::PitchTrimUp && s.outcome == Outcome::NotRun)
    );
    // Taking the exclusion back on the screen asks switch 2 again.
    let mut r = Rig::new(excluding(&["Nav Lt"], Rig::only(&[Step::Switches])));
    assert!(r.view.unasked.iter().any(|u| u.input == Input::Switch(2)));
    r.view.current =
        Some(r.view.plan.len() + r.view.excluded.iter().position(|e| e.id == 4).unwrap());
    r.cmd(Command::Toggle);
    assert!(!r.view.unasked.iter().any(|u| u.input == Input::Switch(2)));
    r.start();
    assert_eq!(
        r.view.switches[r.view.current.unwrap()].input,
        Input::Switch(2)
    );
}

/// 1_764_000_000 s after the epoch is 2025-11-24T16:00:00Z (20416 days of 86400 s,
/// and 57600 s = 16 h): the check's wall clock when the flow is made.
fn at_four_pm() -> Options {
    Options {
        clock: Some(std::time::UNIX_EPOCH + Duration::from_secs(1_764_000_000)),
        ..Rig::only(&[Step::Switches])
    }
}

impl Rig {
    /// Another display on the unit's bus sends `message`: the unit acts on it, this
    /// page's model never hears of it.
    fn sent_by_another_display(&mut self, message: impl Into<Message>) {
        self.unit
            .feed(&Packet::request(99, message).to_bytes(), self.now);
    }

    fn not_followed(&self, input: Input) -> Vec<(u8, NotFollowed)> {
        match self.switch(input) {
            Outcome::Found(SwitchFinding::CircuitsDidNotFollow(v)) => v.clone(),
            o => panic!("{input:?}: {o:?}"),
        }
    }
}

fn power(id: u8, on: bool) -> crate::protocol::message::DevicePower {
    crate::protocol::message::DevicePower { device_id: id, on }
}

/// Switch 2 (Nav Lt, Strobe) flipped on; at once (before the unit's broadcasts show
/// it) `hold` holds Nav Lt off against it; 1.5 s later flipped off.
fn flip_two_while(r: &mut Rig, hold: impl FnOnce(&mut Rig)) {
    r.start();
    r.run(100);
    r.flip(2, true);
    r.run(10);
    hold(r);
    r.run(1500);
    r.flip(2, false);
    r.run_until(5000, |r| r.view.current != Some(1));
}

#[test]
fn a_circuit_held_by_this_page_says_when_the_page_sent_it_and_how_to_release_it() {
    let mut r = Rig::with(&scenario(), at_four_pm());
    let made = r.now;
    // The gateway forwarding another display's command goes out through the page's
    // own send path: the model records the hold.
    flip_two_while(&mut r, |r| {
        r.send(vec![Packet::request(9, power(4, false))])
    });
    let sent = r.sent.last().unwrap().0;
    assert!(
        r.sent
            .iter()
            .any(|(at, p)| *at == sent && p.message == Message::DevicePower(power(4, false)))
    );
    let why = r.not_followed(Input::Switch(2));
    assert_eq!(why.len(), 1, "{why:?}: Strobe followed");
    let (4, NotFollowed::HeldByPage { on, sent_at, .. }) = why[0].clone() else {
        panic!("{why:?}")
    };
    assert!(!on);
    // Sent 0.11 s after the flow was made at 16:00:00.
    assert_eq!(made + Duration::from_millis(110) - r.t0, sent);
    let w = why[0].1.words();
    assert_eq!(
        w,
        "is held off by DEVICE_POWER sent from this page at 16:00:00 UTC (ICD Appendix \
         A): flip the switch to the other position and back to release it"
    );
    assert!(sent_at.is_some());
    // The person's flip off ended that hold too: the model knows none now.
    assert_eq!(r.model.hold(4), None);
}

#[test]
fn a_circuit_held_by_another_display_says_no_hold_from_this_page_is_known() {
    let mut r = Rig::with(&scenario(), at_four_pm());
    flip_two_while(&mut r, |r| r.sent_by_another_display(power(4, false)));
    let why = r.not_followed(Input::Switch(2));
    assert_eq!(why, vec![(4, NotFollowed::NotHeldByPage)]);
    assert_eq!(
        why[0].1.words(),
        "did not follow its input, and no DEVICE_POWER from this page holds it: another \
         display may hold it (ICD Appendix A): flip the switch to the other position and \
         back to release it"
    );
}

#[test]
fn a_circuit_that_follows_another_switch_names_it() {
    // The unit has Landing Lt on switch 3; the page's freshest spec says switch 2 (a
    // spec changed on the unit since the page read it). The person flips switch 2,
    // then switch 3: Landing Lt changes with 3.
    let mut r = Rig::with(
        &scenario(),
        Options {
            timing: Timing {
                follow_wait: Duration::from_secs(8),
                ..Default::default()
            },
            ..Rig::only(&[Step::Switches])
        },
    );
    let stale = crate::protocol::message::DeviceSpec {
        device_id: 17,
        circuit_breaker: 8,
        switch_id: SwitchId::Input(2),
        current_fault: true,
        switch_raw: None,
    };
    r.model.apply_packet(r.now, &Packet::from_vpx(0, stale));
    r.flow = CheckFlow::new(
        Options {
            timing: Timing {
                follow_wait: Duration::from_secs(8),
                ..Default::default()
            },
            ..Rig::only(&[Step::Switches])
        },
        &mut r.view,
        &r.model,
        r.now,
    );
    r.start();
    assert_eq!(r.view.switches[1].circuits, vec![4, 5, 17]);
    r.run(100);
    r.flip_on_off(2, 1500);
    r.run(500);
    r.flip_on_off(3, 1500);
    r.run_until(9000, |r| r.view.current != Some(1));
    assert_eq!(
        r.not_followed(Input::Switch(2)),
        vec![(17, NotFollowed::FollowedOther(Input::Switch(3)))]
    );
    assert_eq!(
        NotFollowed::FollowedOther(Input::Switch(3)).words(),
        "changed with switch 3 instead: the unit has it on that switch"
    );
}

#[test]
fn a_circuit_whose_freshest_spec_names_another_switch_says_which() {
    // The page's spec changes mid-item (the page's minute re-read): Nav Lt is now on
    // switch 5, and it does not follow switch 2.
    let mut r = Rig::new(Rig::only(&[Step::Switches]));
    r.start();
    r.run(100);
    let moved = crate::protocol::message::DeviceSpec {
        device_id: 4,
        circuit_breaker: 3,
        switch_id: SwitchId::Input(5),
        current_fault: true,
        switch_raw: None,
    };
    r.send(vec![
        Packet::request(9, moved),
        Packet::request(10, Setting::DeviceSpec(4).query()),
    ]);
    r.run(200);
    assert_eq!(
        r.model.device_specs[4].unwrap().value.switch_id,
        SwitchId::Input(5)
    );
    r.flip_on_off(2, 1500);
    r.run_until(5000, |r| r.view.current != Some(1));
    assert_eq!(
        r.not_followed(Input::Switch(2)),
        vec![(4, NotFollowed::AssignedTo(SwitchId::Input(5)))]
    );
}

#[test]
fn the_steps_after_the_switches_run_once_when_skipped() {
    let mut r = Rig::new(Rig::only(&[Step::Switches]));
    r.start();
    r.cmd(Command::SkipStep);
    assert_eq!(r.view.step, Step::Done);
    let count = |s: &str| r.progress.iter().filter(|n| n.starts_with(s)).count();
    assert_eq!(count("Check complete"), 1, "{:?}", r.progress);
    assert_eq!(count("– Circuits: skipped"), 1, "{:?}", r.progress);
    assert_eq!(count("– Motors: skipped"), 1, "{:?}", r.progress);
    assert_eq!(count("– Load analysis: skipped"), 1, "{:?}", r.progress);
}

// ----- the page unseen -----

impl Rig {
    /// The DEVICE_POWER on and the motor moves sent after `from`.
    fn acts_since(&self, from: Duration) -> Vec<Message> {
        self.sent
            .iter()
            .filter(|(at, _)| *at > from)
            .map(|(_, p)| p.message)
            .filter(|m| match m {
                Message::DevicePower(d) => d.on,
                Message::FlapMove(f) => f.on,
                Message::TrimMove(t) => t.on,
                _ => false,
            })
            .collect()
    }

    fn prompt(&self) -> String {
        self.view
            .prompt
            .as_ref()
            .map_or(String::new(), |p| p.todo.clone())
    }
}

/// The terminal loses focus while a circuit is on: that one is still measured and put
/// back, but the next is not switched on until the person is back and says to go on
/// (focus alone coming back is not enough); then the step ends as it would have.
#[test]
fn no_circuit_is_switched_on_while_the_terminal_has_lost_focus() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    r.start();
    // Nav Lt (4) is the first circuit the check switches on.
    r.run_until(3000, |r| r.powers(4) == vec![true]);
    let p = r.ctl.on_focus_lost(r.now);
    r.send(p);
    let lost = r.now - r.t0;
    r.run(15_000);
    assert_eq!(r.powers(4), vec![true, false], "Nav Lt put back");
    assert!(!r.on(4));
    assert!(r.acts_since(lost).is_empty(), "{:?}", r.acts_since(lost));
    assert!(
        r.prompt()
            .starts_with("Paused before switching Strobe on: the terminal lost focus"),
        "{}",
        r.prompt()
    );
    assert_eq!(r.circuit(5), &Outcome::NotRun);
    r.ctl.on_focus_gained(r.now);
    r.run(3000);
    assert!(r.acts_since(lost).is_empty(), "went on without being asked");
    r.cmd(Command::Retry);
    assert_eq!(r.powers(5), vec![true]);
    r.run_until(40_000, |r| r.view.step == Step::Done);
    assert_eq!(r.circuit(5), &Outcome::Found(CircuitFinding::NoCurrent));
    for id in [4, 5, 17, 18] {
        assert!(!r.on(id), "device {id} left on");
    }
}

/// Asked to go on while the page is still too small, a waiting circuit waits again;
/// skipped, it is skipped with nothing sent.
#[test]
fn a_circuit_waiting_for_the_page_waits_again_or_is_skipped() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    let p = r.ctl.set_page_hidden(r.now, true);
    r.send(p);
    r.start();
    r.run(2000);
    assert!(r.powers(4).is_empty());
    assert!(
        r.prompt()
            .contains("the terminal is too small to show the page"),
        "{}",
        r.prompt()
    );
    r.cmd(Command::Retry);
    r.run(1000);
    assert!(r.powers(4).is_empty(), "switched on unseen");
    r.cmd(Command::SkipItem);
    assert_eq!(r.circuit(4), &Outcome::Skipped("you skipped it".into()));
    assert!(r.powers(5).is_empty(), "the next one waits too");
    assert!(r.prompt().starts_with("Paused before switching Strobe on"));
    let p = r.ctl.set_page_hidden(r.now, false);
    r.send(p);
    r.cmd(Command::Retry);
    assert_eq!(r.powers(5), vec![true]);
}

/// The page hidden between two runs of a motor (the first ended by itself, the next
/// not started): the next run is not started, nor the run back, until the page is
/// seen and the person asks; then the motor ends where the check found it.
#[test]
fn no_motor_run_starts_while_the_page_is_hidden() {
    let mut r = Rig::new(Rig::only(&[Step::Motors]));
    r.start();
    r.past_probes();
    // Until the first test run has ended by itself (its stop is on the wire).
    r.run_until(3000, |r| {
        r.ctl.running().is_none()
            && r.ctl
                .last_stop()
                .is_some_and(|s| s.reason == StopReason::RunDone)
    });
    let p = r.ctl.set_page_hidden(r.now, true);
    r.send(p);
    let hidden = r.now - r.t0;
    let out_at = flaps_at(&r);
    r.run(5000);
    assert!(
        r.acts_since(hidden).is_empty(),
        "{:?}",
        r.acts_since(hidden)
    );
    assert!(r.ctl.running().is_none());
    assert!(
        r.prompt()
            .contains("did not start: the terminal is too small"),
        "{}",
        r.prompt()
    );
    assert!(r.prompt().contains("r: run the test again"));
    // Asked while still hidden: still nothing.
    r.cmd(Command::Retry);
    r.run(1000);
    assert!(r.acts_since(hidden).is_empty());
    assert!((i32::from(flaps_at(&r)) - i32::from(out_at)).abs() <= 1);
    let p = r.ctl.set_page_hidden(r.now, false);
    r.send(p);
    r.cmd(Command::Retry);
    assert!(!r.acts_since(hidden).is_empty(), "went on once asked");
    r.flaps_pass_and_are_back_at_20("hidden between runs");
}

/// With the motors step skipped, the flap and trim switches are not asked for either:
/// flipping one runs its motor from the cockpit. The plan says so, in its words.
#[test]
fn with_the_motors_skipped_their_switch_inputs_are_not_asked() {
    let mut r = Rig::new(Rig::only(&[Step::Switches]));
    for input in [
        Input::FlapUp,
        Input::FlapDown,
        Input::PitchTrimUp,
        Input::PitchTrimDown,
    ] {
        let u = r.view.unasked.iter().find(|u| u.input == input);
        assert!(u.is_some(), "{input:?} asked");
    }
    r.start();
    for (input, words) in [
        (Input::FlapUp, "flap switch UP drives Flaps"),
        (Input::PitchTrimDown, "pitch trim switch DOWN drives Trim_P"),
    ] {
        assert_eq!(
            skip_words(&r, input),
            format!("{words} (the motors step is skipped): not asked")
        );
    }
    // Not skipped, they are asked.
    let r = Rig::new(Rig::switches_then_motors());
    assert!(
        !r.view
            .unasked
            .iter()
            .any(|u| matches!(u.input, Input::FlapUp | Input::PitchTrimUp))
    );
}

// ----- the report, whenever the check ends -----

/// The person stops the check (Esc or q: `Command::Stop`) at every stage of every
/// step, and the flow says the check ended exactly once each time (the app writes the
/// report on that, marked INCOMPLETE), with what it left. Before power is a stage
/// too: the flow ends there as well (the page's Esc there goes back to the list
/// before anything was touched, Ctrl-C writes the report).
#[test]
fn stopped_at_every_stage_the_check_ends_once_and_says_so() {
    type Reach = fn(&mut Rig);
    let short_switch = || Options {
        timing: Timing {
            switch_timeout: Duration::from_secs(2),
            ..Default::default()
        },
        ..Rig::only(&[Step::Switches])
    };
    let flip_current = |r: &mut Rig| {
        let v = &r.view;
        let Input::Switch(n) = v.switches[v.current.unwrap()].input else {
            panic!("a numbered switch first");
        };
        r.flip(n, true);
    };
    let hide = |r: &mut Rig| {
        let p = r.ctl.set_page_hidden(r.now, true);
        r.send(p);
    };
    let start: Reach = |r| r.start();
    let on_already: Reach = |r| {
        // Nav Lt and Strobe's switch on: they are measured as they are.
        r.flip(2, true);
        r.run(1500);
        r.start();
    };
    let [sw, ci, mo] = [Step::Switches, Step::Circuits, Step::Motors].map(|s| Rig::only(&[s]));
    let cases: Vec<(&str, Options, Reach)> = vec![
        ("before power", sw.clone(), |_| {}),
        ("switches: waiting for the flip", sw.clone(), start),
        ("switches: input changed", sw.clone(), start),
        ("switches: timed out", short_switch(), start),
        ("circuits: measure, switched on", ci.clone(), start),
        ("circuits: measure, as it is", ci.clone(), on_already),
        ("circuits: put back", ci.clone(), start),
        ("circuits: waiting to be seen", ci.clone(), start),
        ("stopping", ci.clone(), start),
        ("motors: start", mo.clone(), start),
        ("motors: running", mo.clone(), start),
        ("motors: settle", mo.clone(), start),
        ("motors: paused", mo.clone(), start),
    ];
    for (stage, opts, begin) in cases {
        let mut r = Rig::new(opts);
        if stage == "motors: start" {
            // No live position yet: the motor waits at its start.
            r.run_dropping(1500, "FLAP_TRIM_STATUS");
            r.cmd(Command::Enter);
            r.run_dropping(100, "FLAP_TRIM_STATUS");
        } else {
            if stage == "circuits: waiting to be seen" {
                hide(&mut r);
            }
            begin(&mut r);
        }
        match stage {
            "switches: input changed" => {
                r.run(200);
                flip_current(&mut r);
            }
            "stopping" => {
                r.run_until(30_000, |r| {
                    r.flow.stage() == "circuits: measure, switched on"
                });
                // The first stop waits to see the circuit off; the second ends it.
                r.cmd(Command::Stop);
                assert_eq!(r.flow.stage(), "stopping");
                assert_eq!(r.ended, 0, "not ended while waiting");
            }
            "motors: paused" => {
                r.run_until(30_000, |r| r.flow.stage() == "motors: running");
                r.run(200);
                hide(&mut r);
            }
            _ => {}
        }
        if stage != "motors: start" {
            r.run_until(60_000, |r| r.flow.stage() == stage);
        }
        assert_eq!(r.flow.stage(), stage);
        assert_eq!(r.ended, 0, "{stage}: not ended before the stop");
        r.cmd(Command::Stop);
        r.run_until(6000, |r| r.flow.finished());
        assert_eq!(r.ended, 1, "{stage}: ended once");
        let i = r.view.interrupted.clone().expect("interrupted");
        assert_eq!(i.cause, "stopped by you", "{stage}");
        // Nothing more ends it.
        r.cmd(Command::Stop);
        r.run(500);
        assert_eq!(r.ended, 1, "{stage}: ended once only");
    }
}

/// A check that runs to its end ends once.
#[test]
fn a_check_that_finishes_ends_once() {
    let mut r = Rig::new(Rig::only(&[Step::Circuits]));
    r.start();
    r.run_until(60_000, |r| r.flow.finished());
    assert_eq!(r.ended, 1);
    assert!(r.view.interrupted.is_none());
    r.cmd(Command::Stop);
    r.run(500);
    assert_eq!(r.ended, 1);
}

/// Each light (Nav Lt, Strobe, Landing Lt here; not EFIS or the alternators) is
/// asked "Is it lit?" while the check has it on, the answers offered as plain data,
/// and it is held on until the answer, or the cap (a minute) with none, with the time
/// left shown. The answer goes into the report beside the current, and where it
/// disagrees with the current (Strobe draws nothing yet is seen lit; Nav Lt draws
/// 1.5 A yet is seen dark) the report says so in words; so does how the light went
/// off (at the answer, or at the cap for Landing Lt, which nobody answers).
#[test]
fn each_light_is_asked_if_it_is_lit_and_the_report_says_where_that_disagrees() {
    use std::collections::BTreeSet;
    let mut r = Rig::holding_lights(Rig::only(&[Step::Circuits]));
    r.start();
    let said = |id: u8| match id {
        4 => Some(false),
        5 => Some(true),
        _ => None,
    };
    // The first time_left seen while Landing Lt is held, measured and on.
    let mut held_left = None;
    let (mut asked, mut on_test, mut answered) =
        (BTreeSet::new(), BTreeSet::new(), BTreeSet::new());
    let mut nav_prompt = None;
    for _ in 0..12_000 {
        if r.view.step != Step::Circuits {
            break;
        }
        if let Some(c) = r.view.current.and_then(|i| r.view.circuits.get(i)).cloned() {
            on_test.insert(c.id);
            let ids: Vec<&str> = r.view.prompt_answers().iter().map(|a| a.id).collect();
            if ids.contains(&"lit_yes") && ids.contains(&"lit_no") {
                asked.insert(c.id);
                if c.id == 4 && nav_prompt.is_none() {
                    let p = r.view.prompt.clone().unwrap();
                    nav_prompt = Some(format!(
                        "todo: {}\nkeys: {:?}\nanswers: {:?}",
                        p.todo,
                        p.keys,
                        r.view.prompt_answers()
                    ));
                }
                if c.id == 17
                    && held_left.is_none()
                    && r.view
                        .prompt
                        .as_ref()
                        .is_some_and(|p| p.todo.contains("measured"))
                {
                    held_left = r.view.prompt.as_ref().and_then(|p| p.time_left);
                }
                // Answered once the unit shows it on, as a person would.
                if !answered.contains(&c.id)
                    && r.model
                        .live_devices(r.now)
                        .is_some_and(|d| d.on[c.id as usize])
                    && let Some(lit) = said(c.id)
                {
                    r.cmd(Command::Lit(lit));
                    answered.insert(c.id);
                }
            } else if !asked.contains(&c.id) {
                // Not a light: a "lit" answer is not taken.
                r.cmd(Command::Lit(true));
            }
        }
        r.run(10);
    }
    assert!(on_test.contains(&2), "EFIS was tested: {on_test:?}");
    assert_eq!(asked, BTreeSet::from([4, 5, 17]));
    assert_eq!(r.view.lit_of(4), Some(false));
    assert_eq!(r.view.lit_of(5), Some(true));
    assert_eq!(r.view.lit_of(17), None);
    assert_eq!(r.view.lit.len(), 3, "{:?}", r.view.lit);
    assert_eq!(
        r.view.lit_answer(17).map(|a| a.ended),
        Some(super::state::LitEnd::Cap(Duration::from_secs(60)))
    );
    for line in [
        "  Nav Lt: you saw it dark; switched back off at your answer",
        "  Landing Lt: no answer in 60 s; switched back off then",
    ] {
        assert!(
            r.progress.iter().any(|l| l == line),
            "{line}: {:?}",
            r.progress
        );
    }
    // Landing Lt was held on for the whole minute and then switched off; the time
    // left was shown while it was held.
    let sent_at = |on: bool| {
        r.sent
            .iter()
            .find(|(_, p)| p.message == Message::DevicePower(power(17, on)))
            .map(|(at, _)| *at)
            .unwrap()
    };
    let held = sent_at(false) - sent_at(true);
    assert!(
        held >= Duration::from_secs(60) && held < Duration::from_millis(60_200),
        "{held:?}"
    );
    let left = held_left.expect("time left shown while held");
    assert!(
        left > Duration::from_secs(50) && left < Duration::from_secs(60),
        "{left:?}"
    );
    insta::assert_snapshot!("nav_light_is_it_lit_prompt", nav_prompt.unwrap());

    r.run_until(20_000, |r| r.flow.finished());
    let about = super::report::tests::about();
    let md = super::report::markdown(&r.view, &about);
    let row = |name: &str| {
        md[md.find("## Circuits").unwrap()..]
            .lines()
            .find(|l| l.starts_with(&format!("| {name} |")))
            .unwrap_or_else(|| panic!("no row for {name}:\n{md}"))
            .to_string()
    };
    let nav = row("Nav Lt");
    assert!(nav.contains("| 1.5 A, seen dark |"), "{nav}");
    assert!(
        nav.contains("the unit read 1.5 A, yet you saw it dark: the two disagree"),
        "{nav}"
    );
    let strobe = row("Strobe");
    assert!(strobe.contains("| 0 A, seen lit |"), "{strobe}");
    assert!(
        strobe.contains("you saw it lit, yet the unit read no current: the two disagree"),
        "{strobe}"
    );
    assert!(
        nav.contains("you saw it dark; switched back off at your answer"),
        "{nav}"
    );
    let landing = row("Landing Lt");
    assert!(!landing.contains("seen"), "{landing}");
    assert!(
        landing.contains("no answer in 60 s; switched back off then"),
        "{landing}"
    );
    let efis = row("EFIS");
    assert!(!efis.contains("seen"), "{efis}");
    let csv = super::report::csv(&r.view, &about);
    assert!(
        csv.lines()
            .any(|l| l.contains(",Strobe,") && l.contains("seen lit; you saw it lit, yet")),
        "{csv}"
    );
}

/// A light on by its own switch is held for "Is it lit?" as one the check switched on
/// is: the person may still be walking to it, and an answer typed late must not be
/// taken for the next light asked. Its answer is its own, and nothing is switched.
#[test]
fn a_light_on_by_its_switch_is_held_for_its_own_answer_and_left_on() {
    let mut r = Rig::holding_lights(Rig::only(&[Step::Circuits]));
    // Switch 2 powers Nav Lt (4) and Strobe (5): both on before the check.
    r.flip(2, true);
    r.run(2000);
    r.start();
    r.run_until(15_000, |r| {
        r.view.current.is_some_and(|i| r.view.circuits[i].id == 4)
    });
    let asked = r
        .progress
        .iter()
        .find(|l| l.starts_with("  Nav Lt: is it lit?"))
        .expect("Nav Lt is asked");
    assert!(asked.contains("until you answer, 60 s at most"), "{asked}");
    // Half a minute on, still asking Nav Lt: nothing recorded for it, nothing moved on.
    r.run(30_000);
    assert_eq!(
        r.view.current.map(|i| r.view.circuits[i].id),
        Some(4),
        "{:?}",
        r.progress
    );
    assert!(r.view.lit_answer(4).is_none());
    r.cmd(Command::Lit(true));
    r.run(500);
    let a = r.view.lit_answer(4).expect("Nav Lt answered");
    assert_eq!(
        (a.lit, a.switched, a.ended),
        (Some(true), false, super::state::LitEnd::Answer)
    );
    assert_eq!(r.powers(4), Vec::<bool>::new(), "nothing sent for Nav Lt");
    assert!(
        r.view.lit_answer(5).is_none(),
        "Strobe not answered by Nav Lt's y"
    );
}

/// The flow writes no file. Reaching the load analysis it asks the app to
/// open the load file (`CheckEffects::open_loads`, with the circuits its template lists)
/// and waits, the file untouched; handed the result, it goes on to the report.
#[test]
fn the_load_analysis_asks_the_app_to_open_the_file_and_writes_nothing_itself() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("loads.toml");
    let mut r = Rig::new(Options {
        skip: vec![Step::Switches, Step::Circuits, Step::Motors],
        loads_file: Some(path.clone()),
        ..Options::default()
    });
    let out = r
        .flow
        .command(Command::Enter, &mut r.view, &r.model, &mut r.ctl, r.now);
    let req = out
        .open_loads
        .clone()
        .expect("the flow asks for the load file");
    assert_eq!(req.path, path);
    assert!(req.circuits.iter().any(|c| c.name == "Landing Lt"));
    assert!(!out.ended && !r.flow.finished());
    assert!(!path.exists(), "the flow wrote the load file itself");
    assert_eq!(r.flow.next_deadline(), None);
    let opened = crate::loads::disk::open_or_create(&req.path, &req.circuits);
    let done = r
        .flow
        .loads_opened(opened, &mut r.view, &r.model, &mut r.ctl, r.now);
    assert!(done.ended && r.flow.finished());
    assert_eq!(
        r.view.loads,
        Some(crate::check::state::LoadsView::TemplateWritten(
            path.clone()
        ))
    );
    assert!(
        done.progress.iter().any(|l| l.contains("its template")),
        "{:?}",
        done.progress
    );
}

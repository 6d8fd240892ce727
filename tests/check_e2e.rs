//! The installation check end to end: the real `App` (and the headless
//! `vpx-efis check` runner) on the slave of a real pseudo-terminal, the virtual VP-X
//! with the `install` scenario on its master, a test playing the person at the
//! switches. What the check says is held against what the sim really did.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

use crossbeam_channel::unbounded;
use crossterm::event::KeyCode;
use vpx_efis::app::{AppOptions, CheckEnd, HeadlessCheck, run_headless_with};
use vpx_efis::check::state::{
    CircuitFinding, Input, LeftBehind, MotorFinding, Outcome, Step, SwitchFinding,
};
use vpx_efis::check::{Options, Timing};
use vpx_efis::model::{Motor, TrimKind};
use vpx_efis::sim::{self, MotorDirection, MotorId, SimCommand, SimHandle, SimOptions};
use vpx_efis::ui::state::Screen;

mod common;
use common::rig::Rig;

/// A test that panicked sets the page's panic flag for the whole process (the hook
/// that `run_headless_with` installs: a panic anywhere stops every motor, and the
/// page stops ticking for good). Every later rig here would then wait out its limits
/// on a page that no longer acts: fail at once instead, naming the cause.
fn no_earlier_panic() {
    assert!(
        !vpx_efis::app::panicked(),
        "an earlier test in this binary panicked, and the page's panic flag is \
         process-wide: this rig's page would not act"
    );
}

impl Rig {
    fn new() -> Rig {
        Rig::with(|_| {})
    }

    /// The `install` scenario as `change` leaves it.
    fn with(change: impl FnOnce(&mut sim::Scenario)) -> Rig {
        let mut scenario = sim::load_scenario("install").unwrap();
        change(&mut scenario);
        let mut r = Rig::alone(SimOptions::new(scenario), AppOptions::default());
        no_earlier_panic();
        let end = Instant::now() + Duration::from_secs(20);
        loop {
            let ready = vpx_efis::check::plan::ready(&r.app.model(), Instant::now());
            let Err(why) = ready else { break };
            assert!(Instant::now() < end, "the unit's settings: {why}");
            r.pump(20);
        }
        r
    }

    fn options(&self) -> Options {
        Options {
            loads_file: Some(self.dir.path().join("loads.toml")),
            timing: Timing {
                switch_timeout: Duration::from_secs(6),
                // Nobody looks at the lights here: none is held for "Is it lit?".
                lit_for: Duration::ZERO,
                ..Timing::default()
            },
            ..Options::default()
        }
    }

    /// [`Rig::options`], the steps `skip` skipped.
    fn skipping(&self, skip: &[Step]) -> Options {
        Options {
            skip: skip.to_vec(),
            ..self.options()
        }
    }

    /// The headless check of the `install` scenario on this rig's port, `options`
    /// (on top of the rig's) said yes to, its report in `report` in the rig's folder.
    /// The rig's page is closed first: one program on the port at a time.
    fn headless(self, options: Options, report: Option<&str>) -> (HeadlessCheck, Closed) {
        let h = HeadlessCheck {
            port: Some(self.path.parse().unwrap()),
            baud: 57_600,
            scenario: "install".into(),
            options: Options {
                yes: true,
                ..options
            },
            report: report.map(|r| self.dir.path().join(r)),
        };
        let Rig { app, sim, dir, .. } = self;
        app.shutdown();
        (h, Closed { sim, dir })
    }

    /// The person moves a flap or trim switch one way for a while, then lets go.
    fn hold_motor_switch(&mut self, motor: MotorId, direction: MotorDirection) {
        self.sim.inject(SimCommand::MotorSwitch {
            motor,
            direction: Some(direction),
        });
        self.pump(1500);
        self.sim.inject(SimCommand::MotorSwitch {
            motor,
            direction: None,
        });
    }

    /// Plays the person through the switch step: each input asked for is flipped on
    /// and off (switch 7's wire is dead, 5 and 6 are crossed: the person cannot tell).
    fn do_the_switches(&mut self) {
        let mut done = 0;
        let end = Instant::now() + Duration::from_secs(180);
        while self.app.check_view().step == Step::Switches {
            assert!(Instant::now() < end, "the switch step never ended");
            let v = self.app.check_view();
            let Some(i) = v.current else {
                self.pump(20);
                continue;
            };
            let input = v.switches[i].input;
            let waiting = v.switches[i].outcome != Outcome::NotRun;
            if waiting {
                // Timed out: go on to the next.
                self.key(KeyCode::Enter);
                continue;
            }
            if i < done {
                self.pump(20);
                continue;
            }
            done = i + 1;
            match input {
                Input::Switch(n) => {
                    self.sim.flip_switch(n, Duration::from_millis(1500));
                }
                Input::FlapUp => self.hold_motor_switch(MotorId::Flap, MotorDirection::Up),
                Input::FlapDown => self.hold_motor_switch(MotorId::Flap, MotorDirection::Down),
                Input::PitchTrimUp => self.hold_motor_switch(MotorId::Pitch, MotorDirection::Up),
                Input::PitchTrimDown => {
                    self.hold_motor_switch(MotorId::Pitch, MotorDirection::Down)
                }
                Input::RollTrimUp => self.hold_motor_switch(MotorId::Roll, MotorDirection::Up),
                Input::RollTrimDown => self.hold_motor_switch(MotorId::Roll, MotorDirection::Down),
            }
            self.until("the input's result", Duration::from_secs(12), |app| {
                let v = app.check_view();
                v.current != Some(i) || v.switches[i].outcome != Outcome::NotRun
            });
        }
    }
}

/// What is left of a rig once its page is closed: the unit and the test's folder.
struct Closed {
    sim: SimHandle,
    dir: tempfile::TempDir,
}

/// The install scenario's six faults, as the list of what is left to fix says them.
fn injected() -> Vec<String> {
    [
        "switch 5: switch 6 changed instead: switches crossed",
        "switch 6: switch 5 changed instead: switches crossed",
        "switch 7: input never changed: a broken wire, a bad switch, or the wrong pin",
        "Beacon (5A-3): no current while on: an open circuit, a blown bulb, a load not connected",
        "pitch trim: reversed: the motor's polarity is swapped, or the sensor is wired backwards",
        "roll trim: no movement: the motor, the sensor or a limit",
    ]
    .map(String::from)
    .to_vec()
}

#[test]
fn the_install_scenario_finds_each_injected_fault_and_puts_everything_back() {
    let mut r = Rig::new();
    let before = r.sim.stats();
    // `i` on the device list opens the check; leave it, and open one with a shorter
    // switch timeout (the dead switch 7 waits it out).
    r.key(KeyCode::Char('i'));
    assert_eq!(r.app.view().screen, Screen::Check);
    assert_eq!(r.app.check_view().step, Step::Confirm);
    r.key(KeyCode::Esc);
    assert_eq!(r.app.view().screen, Screen::Devices);
    let opts = r.options();
    r.app.open_check(opts, Instant::now());
    let v = r.app.check_view();
    assert!(
        v.excluded
            .iter()
            .any(|e| e.name == "Pitot Heat" && e.may_include)
    );
    assert!(!v.plan.iter().any(|p| [1, 3, 20].contains(&p.id)));
    r.key(KeyCode::Enter);
    assert_eq!(r.app.check_view().step, Step::Switches);
    r.do_the_switches();
    r.until("the end of the check", Duration::from_secs(120), |app| {
        app.check_finished()
    });
    let v = r.app.check_view().clone();
    assert!(v.interrupted.is_none(), "{:?}", v.interrupted);

    // Each injected fault found and named; the Landing Lt's tight breaker too.
    let fix = v.to_fix();
    for f in injected() {
        assert!(fix.contains(&f), "missing {f:?} in {fix:#?}");
    }
    let landing: Vec<&String> = fix.iter().filter(|f| f.starts_with("Landing Lt")).collect();
    assert_eq!(landing.len(), 1, "{fix:#?}");
    assert!(
        landing[0].contains("of an 8 A breaker (≥ 80 %)"),
        "{fix:#?}"
    );
    assert_eq!(
        fix.len(),
        injected().len() + 1,
        "exactly the faults: {fix:#?}"
    );

    // The good ones pass.
    let switch = |n| {
        v.switches
            .iter()
            .find(|s| s.input == Input::Switch(n))
            .unwrap()
            .outcome
            .clone()
    };
    for n in [2, 3, 4] {
        assert_eq!(
            switch(n),
            Outcome::Found(SwitchFinding::Passed),
            "switch {n}"
        );
    }
    for s in v
        .switches
        .iter()
        .filter(|s| !matches!(s.input, Input::Switch(_)))
    {
        // A flap or trim switch has no circuit: all the check sees is the input.
        assert_eq!(s.outcome, Outcome::Found(SwitchFinding::Changed), "{s:?}");
    }
    for c in &v.circuits {
        match c.id {
            6 => assert_eq!(c.outcome, Outcome::Found(CircuitFinding::NoCurrent)),
            17 => assert!(matches!(
                c.outcome,
                Outcome::Found(CircuitFinding::NearBreaker { breaker: 8, .. })
            )),
            1 | 3 | 20 => assert!(matches!(c.outcome, Outcome::Skipped(_)), "{c:?}"),
            _ => assert!(
                matches!(c.outcome, Outcome::Found(CircuitFinding::Within { .. })),
                "{c:?}"
            ),
        }
    }
    let motor = |m| {
        v.motors
            .iter()
            .find(|r| r.motor == m)
            .unwrap()
            .outcome
            .clone()
    };
    assert_eq!(motor(Motor::Flaps), Outcome::Found(MotorFinding::Moves));
    assert_eq!(
        motor(Motor::Trim(TrimKind::Pitch)),
        Outcome::Found(MotorFinding::Reversed)
    );
    assert_eq!(
        motor(Motor::Trim(TrimKind::Roll)),
        Outcome::Found(MotorFinding::NoMovement)
    );

    // Every circuit is as it was, and the moving motors are back where they were.
    r.pump(1200);
    let after = r.sim.stats();
    assert_eq!(after.powered, before.powered, "every circuit put back");
    // (The person's flap and trim switches moved them in the switch step; the motor
    // step puts them back where it found them.)
    let found = |m| v.motors.iter().find(|r| r.motor == m).unwrap().positions[0];
    for (a, b) in [
        (after.flap_position, found(Motor::Flaps)),
        (
            after.pitch_trim_position,
            found(Motor::Trim(TrimKind::Pitch)),
        ),
    ] {
        assert!((i32::from(a) - i32::from(b)).abs() <= 4, "{a} vs {b}");
    }
    assert_eq!(
        (
            after.flap_starvations,
            after.pitch_trim_starvations,
            after.roll_trim_starvations
        ),
        (0, 0, 0),
        "every run ended with its stop, never by starving the unit"
    );
    assert_eq!(
        (after.flap_late, after.pitch_trim_late, after.roll_trim_late),
        (0, 0, 0),
        "no gap over 250 ms between move messages (the unit forgives up to 300 ms)"
    );
    // Circuits switched back off by DEVICE_POWER are held until their switch cycles.
    assert!(v.to_cycle.iter().any(|(id, ..)| *id == 6));
    // The template of the load file was written for next time.
    assert!(r.dir.path().join("loads.toml").exists());
}

/// Starts a check of the circuits only and waits until Landing Lt (17) is on.
fn landing_light_on(r: &mut Rig) {
    let opts = r.skipping(&[Step::Switches, Step::Motors, Step::Loads]);
    r.app.open_check(opts, Instant::now());
    r.key(KeyCode::Enter);
    let at = r
        .app
        .check_view()
        .circuits
        .iter()
        .position(|c| c.id == 17)
        .unwrap();
    r.until("Landing Lt on", Duration::from_secs(90), |app| {
        app.check_view().current == Some(at)
            && app
                .model()
                .live_devices(Instant::now())
                .is_some_and(|d| d.on[17])
    });
}

#[test]
fn quit_mid_circuit_puts_it_back_and_says_nothing_is_left() {
    let mut r = Rig::new();
    landing_light_on(&mut r);
    assert!(r.sim.stats().powered[17]);
    r.key(KeyCode::Esc);
    r.until("the check to stop", Duration::from_secs(5), |app| {
        app.check_finished()
    });
    let i = r.app.check_view().interrupted.clone().unwrap();
    assert_eq!(i.cause, "stopped by you");
    assert_eq!(i.left, vec![]);
    assert!(!r.sim.stats().powered[17], "Landing Lt back off");
    let v = r.app.check_view();
    let not_run: Vec<u8> = v
        .circuits
        .iter()
        .filter(|c| c.outcome == Outcome::NotRun)
        .map(|c| c.id)
        .collect();
    assert_eq!(
        not_run,
        vec![17, 18, 19],
        "the one under test and those after it have no result"
    );
    r.key(KeyCode::Esc);
    assert_eq!(r.app.view().screen, Screen::Devices);
}

#[test]
fn communication_lost_mid_circuit_says_the_state_is_unknown() {
    let mut r = Rig::new();
    landing_light_on(&mut r);
    r.sim.inject(SimCommand::Silent(Duration::from_secs(6)));
    r.until("the check to stop", Duration::from_secs(8), |app| {
        app.check_finished()
    });
    let i = r.app.check_view().interrupted.clone().unwrap();
    assert_eq!(i.cause, "COMMUNICATION LOST");
    assert_eq!(
        i.left,
        vec![LeftBehind::new(
            17,
            "Landing Lt".to_string(),
            "unknown: it was ON; DEVICE_POWER off sent, not confirmed (COMMUNICATION LOST)"
                .to_string()
        )]
    );
    // The off was sent all the same, and a silent unit still hears: it is off (once
    // the bytes crossed the pty and the sim's thread read them: on a loaded machine
    // that is not at the instant the check ended).
    let end = Instant::now() + Duration::from_secs(3);
    while r.sim.stats().powered[17] && Instant::now() < end {
        r.pump(20);
    }
    assert!(!r.sim.stats().powered[17]);
}

#[test]
fn a_fault_mid_step_stops_the_check_and_the_circuit_goes_back_off() {
    let mut r = Rig::new();
    landing_light_on(&mut r);
    // The EFIS (measured already, on by its switch) shorts while Landing Lt is on.
    r.sim.inject(SimCommand::Short {
        device: 2,
        on: true,
    });
    r.until("the check to stop", Duration::from_secs(8), |app| {
        app.check_finished()
    });
    let i = r.app.check_view().interrupted.clone().unwrap();
    assert_eq!(i.cause, "EFIS faulted (SHORT_CIRCUIT)");
    assert_eq!(i.left, vec![], "Landing Lt seen back off");
    assert!(!r.sim.stats().powered[17]);
}

#[test]
fn quit_mid_motor_run_puts_the_stop_on_the_wire() {
    let mut r = Rig::new();
    let opts = r.skipping(&[Step::Switches, Step::Circuits, Step::Loads]);
    let before = r.sim.stats().flap_starvations;
    r.app.open_check(opts, Instant::now());
    r.key(KeyCode::Enter);
    r.until("the flaps running", Duration::from_secs(5), |app| {
        app.motor_run().is_some()
    });
    // Until they have clearly moved from 20 (the up endpoint), down.
    let end = Instant::now() + Duration::from_secs(10);
    while r.sim.stats().flap_position < 26 {
        assert!(Instant::now() < end, "the flaps never moved down");
        r.pump(20);
    }
    assert!(r.sim.stats().flap_running);
    r.key(KeyCode::Esc);
    r.pump(150);
    let s = r.sim.stats();
    assert!(!s.flap_running, "stopped within 150 ms");
    assert_eq!(
        s.flap_starvations, before,
        "by its stop message, not by starving"
    );
    assert_eq!(s.flap_late, 0, "no gap over 250 ms between move messages");
    r.until("the check to stop", Duration::from_secs(5), |app| {
        app.check_finished()
    });
    let i = r.app.check_view().interrupted.clone().unwrap();
    assert_eq!(i.left.len(), 1, "{:?}", i.left);
    assert_eq!(i.left[0].id, 0, "the flaps");
    assert!(i.left[0].state.contains("not run back"), "{:?}", i.left);
}

#[test]
fn headless_check_prints_results_and_exits_by_what_it_found() {
    let r = Rig::new();
    let (_tx, lines) = unbounded();
    let (_ttx, terminations) = unbounded();
    let mut out = Vec::new();
    let options = Options {
        choices: vpx_efis::check::Choices {
            exclude: vec!["Landing Lt".into(), "5A-2".into()],
            ..Default::default()
        },
        ..r.skipping(&[Step::Switches, Step::Motors])
    };
    let (h, Closed { sim, dir }) = r.headless(options, Some("reports"));
    let end = run_headless_with(h, &lines, &terminations, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(end, CheckEnd::Failed, "{text}");
    for said in [
        "✗ FAIL Beacon (5A-3): no current while on",
        "✓ PASS Nav Lt (5A-1): draws",
        "Landing Lt: excluded by you (--exclude)",
        "Strobe Lt: excluded by you (--exclude)",
        "– Switch inputs: skipped",
        "Left to fix:\n  - Beacon (5A-3)",
        "  - Beacon: flip switch 3 to the other position and back",
    ] {
        assert!(text.contains(said), "no {said:?} in\n{text}");
    }
    assert!(
        !text.contains("Landing Lt (10A-1)"),
        "never powered: {text}"
    );
    assert!(!sim.stats().powered[6], "Beacon back off");
    // The check's own files; the audit log of what was sent lives beside them.
    let folder = dir.path().join("reports");
    let reports: Vec<String> = common::files::names_in(&folder)
        .into_iter()
        .filter(|n| n.starts_with("vpx-check-"))
        .collect();
    assert_eq!(reports.len(), 2, "Markdown and CSV: {reports:?}");
    let md = reports.iter().find(|n| n.ends_with(".md")).unwrap();
    let md = std::fs::read_to_string(folder.join(md)).unwrap();
    assert!(md.contains("Beacon"), "{md}");
    assert!(text.contains("Report written: "), "{text}");
}

#[test]
fn headless_check_stopped_by_a_signal_puts_back_and_exits_interrupted() {
    let r = Rig::new();
    let (_tx, lines) = unbounded();
    let (ttx, terminations) = unbounded();
    let options = r.skipping(&[Step::Switches, Step::Motors]);
    let (h, Closed { sim, dir: _dir }) = r.headless(options, None);
    // SIGTERM once the Nav Lt (the first circuit the check switches on) is on.
    let stats = std::sync::Arc::new(sim);
    let watcher = {
        let sim = stats.clone();
        std::thread::spawn(move || {
            let end = Instant::now() + Duration::from_secs(30);
            while !sim.stats().powered[4] && Instant::now() < end {
                std::thread::sleep(Duration::from_millis(20));
            }
            let _ = ttx.send(vpx_efis::app::Termination::Terminate);
        })
    };
    let mut out = Vec::new();
    let end = run_headless_with(h, &lines, &terminations, &mut out).unwrap();
    watcher.join().unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(end, CheckEnd::Interrupted, "{text}");
    assert!(
        text.contains("Interrupted: ended by a signal (SIGTERM)"),
        "{text}"
    );
    // Back as it was, but held so by DEVICE_POWER: said, with the switch to flip.
    assert!(
        text.contains(
            "Every circuit it touched is back as it found it, but held there by \
             DEVICE_POWER: flip the switches listed above."
        ),
        "{text}"
    );
    assert!(
        text.contains("  - Nav Lt: flip switch 2 to the other position and back"),
        "{text}"
    );
    assert!(!stats.stats().powered[4], "Nav Lt back off");
}

#[test]
fn headless_check_refuses_an_exclude_that_names_no_circuit() {
    let r = Rig::new();
    let (_tx, lines) = unbounded();
    let (_ttx, terminations) = unbounded();
    let options = Options {
        choices: vpx_efis::check::Choices {
            exclude: vec!["Pitot Heeat".into()],
            ..Default::default()
        },
        ..r.options()
    };
    let (h, Closed { sim, dir: _dir }) = r.headless(options, None);
    let mut out = Vec::new();
    let e = run_headless_with(h, &lines, &terminations, &mut out).unwrap_err();
    let words = e.to_string();
    assert!(
        words.starts_with("--exclude Pitot Heeat: no circuit has that name or pin"),
        "{words}"
    );
    assert!(words.contains("Pitot Heat (10A-4)"), "{words}");
    assert!(
        !sim.stats().log.iter().any(|l| l.contains("DEVICE_POWER")),
        "nothing was powered"
    );
}

/// Through the real parts: the install scenario's reversed pitch trim
/// parked 5 counts from its up endpoint (30). The check's first run is "down", the
/// side with more room, but the swapped leads drive it up, toward 30: the page stops
/// it there with its stop message, and the sim's own sensor never reads past 30.
#[test]
fn a_reversed_trim_parked_near_its_endpoint_never_passes_it() {
    let mut r = Rig::with(|s| {
        let pitch = s.pitch_trim.as_mut().expect("install has a pitch trim");
        assert!(pitch.reversed && pitch.up == 30 && pitch.down == 220);
        pitch.position = Some(35);
    });
    let opts = r.skipping(&[Step::Switches, Step::Circuits, Step::Loads]);
    let before = r.sim.stats();
    assert_eq!(before.pitch_trim_position, 35);
    r.app.open_check(opts, Instant::now());
    r.key(KeyCode::Enter);
    let end = Instant::now() + Duration::from_secs(60);
    let mut lowest = 255;
    while !r.app.check_finished() {
        assert!(Instant::now() < end, "{:#?}", r.app.check_view().prompt);
        r.pump(20);
        lowest = lowest.min(r.sim.stats().pitch_trim_position);
    }
    assert!(
        lowest >= 30,
        "the pitch trim passed its up endpoint 30: {lowest}"
    );
    assert!(lowest <= 33, "it did run toward it: {lowest}");
    let v = r.app.check_view().clone();
    let pitch = v
        .motors
        .iter()
        .find(|m| m.motor == Motor::Trim(TrimKind::Pitch))
        .unwrap();
    assert_eq!(
        pitch.outcome,
        Outcome::Found(MotorFinding::Reversed),
        "{pitch:?}"
    );
    let after = r.sim.stats();
    assert_eq!(
        after.pitch_trim_starvations, before.pitch_trim_starvations,
        "stopped by its stop message, not by starving the unit"
    );
    assert_eq!(
        after.pitch_trim_late, before.pitch_trim_late,
        "no gap over 250 ms between move messages"
    );
    assert!(!after.pitch_trim_running);
    // Put back (the check's tolerance, 3 counts): the run back is "up", which on
    // these swapped leads moves away from 30.
    assert!(
        (i32::from(after.pitch_trim_position) - 35).abs() <= 3,
        "put back: {} ({:?})",
        after.pitch_trim_position,
        pitch.positions
    );
}

/// The motor test pauses for r (retry) or s (skip) when the flap position stops
/// coming; with standard input at its end (a closed channel here) nobody can type
/// either: the headless check says so and skips, and the check ends.
#[test]
fn headless_a_motor_pause_after_stdin_ended_is_said_and_skipped() {
    let r = Rig::new();
    let (tx, lines) = unbounded::<String>();
    drop(tx);
    let (_ttx, terminations) = unbounded();
    let options = r.skipping(&[Step::Switches, Step::Circuits, Step::Loads]);
    let (h, Closed { sim, dir: _dir }) = r.headless(options, None);
    // The unit falls silent for 1.6 s as the check is confirmed: the flaps' first
    // run stops on a stale position and pauses, as does what follows while it is
    // silent; never long enough (2.5 s) to lose communication.
    let sim = std::sync::Arc::new(sim);
    let mut out = SilenceAt {
        text: Vec::new(),
        at: "Confirmed:",
        sim: Some(sim.clone()),
    };
    let started = Instant::now();
    let end = run_headless_with(h, &lines, &terminations, &mut out).unwrap();
    let text = String::from_utf8(out.text).unwrap();
    assert!(
        text.contains(
            "Standard input is at its end (no terminal, /dev/null, a closed pipe): nobody \
             can answer here. The check was waiting for r (retry) or s (skip), which nobody \
             can type now: skipped."
        ),
        "{text}"
    );
    assert!(started.elapsed() < Duration::from_secs(60), "{text}");
    assert_ne!(end, CheckEnd::Interrupted, "{text}");
}

/// The headless check's output, which silences the unit the first time a line with
/// `at` is written.
struct SilenceAt {
    text: Vec<u8>,
    at: &'static str,
    sim: Option<std::sync::Arc<SimHandle>>,
}

impl std::io::Write for SilenceAt {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.text.extend_from_slice(buf);
        if String::from_utf8_lossy(buf).contains(self.at)
            && let Some(sim) = self.sim.take()
        {
            sim.inject(SimCommand::Silent(Duration::from_millis(1600)));
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

//! A motor that moves against its command is stopped within a few counts,
//! whoever runs it (the device list's keys, the setup screens' capture, the
//! installation check, the XFSp gateway), and then refused to every origin until the
//! person confirms a run at the keys (`control::against`). On the fake clock, against
//! the virtual VP-X's pitch trim with its leads swapped (up 30, down 220).

use std::time::Duration;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::{PITCH, Rig, pitch_at, pitch_ctx};
use crate::check::state::{MotorFinding, Step};
use crate::control::run_state::ReleaseMode;
use crate::control::{Controller, Direction, Handled, StopReason, StreamerConfig};
use crate::protocol::message::Message;

const STOPPED: &str =
    "pitch trim moved down when asked up: its leads or its sensor may be swapped; stopped";

fn rig(at: u8) -> Rig {
    let mut r = Rig::with(&pitch_at(at, true), Rig::only(&[Step::Motors]));
    r.ctl = Controller::new(StreamerConfig {
        release_mode: ReleaseMode::KeyRelease,
        ..StreamerConfig::default()
    });
    r
}

impl Rig {
    fn pitch_pos(&self) -> u8 {
        self.unit.snapshot(self.now).pitch_trim_position
    }

    fn key(&mut self, c: char, kind: KeyEventKind, setup: bool) -> Handled {
        let key = KeyEvent::new_with_kind(KeyCode::Char(c), KeyModifiers::NONE, kind);
        let out = self
            .ctl
            .handle_key(key, &pitch_ctx(setup), &self.model, self.now);
        self.send(out.packets.clone());
        out
    }

    /// Holds `c` for `ms` (a terminal that reports repeats every 40 ms and the
    /// release), the unit's own positions every 10 ms, and every notice shown.
    fn hold(&mut self, c: char, ms: u64, setup: bool) -> (Vec<u8>, Vec<String>) {
        let mut seen = vec![self.pitch_pos()];
        let mut notices: Vec<String> = self
            .key(c, KeyEventKind::Press, setup)
            .notice
            .into_iter()
            .collect();
        for _ in 0..ms / 40 {
            seen.extend(self.run_watching(40, PITCH));
            notices.extend(self.key(c, KeyEventKind::Repeat, setup).notice);
            notices.extend(self.ctl.take_notice());
        }
        notices.extend(self.key(c, KeyEventKind::Release, setup).notice);
        seen.extend(self.run_watching(300, PITCH));
        notices.extend(self.ctl.take_notice());
        (seen, notices)
    }

    /// The TRIM_MOVEs sent from `from` on: each one's on.
    fn trim_moves_since(&self, from: usize) -> Vec<bool> {
        self.timed_trim_moves_since(from)
            .into_iter()
            .map(|(_, on)| on)
            .collect()
    }
}

/// The keys: `u` held from 128 runs the trim down; stopped within a few counts with
/// the words and its stop on the wire. Then `u` and `d` are refused with nothing
/// sent; `u` again within 3 s runs it, knowing its way, to the down endpoint 220 and
/// not past it; `u` there is refused; `d` confirmed runs it back up.
#[test]
fn a_key_run_moving_against_its_command_stops_and_then_needs_a_confirmation() {
    let mut r = rig(128);
    let from = r.sent.len();
    let (seen, notices) = r.hold('u', 2000, false);
    let most = *seen.iter().max().unwrap();
    assert!((131..=134).contains(&most), "went down to {most}: {seen:?}");
    assert!(*seen.iter().min().unwrap() >= 127, "{seen:?}");
    assert_eq!(
        r.ctl.last_stop().unwrap().reason,
        StopReason::MovedAgainst(Direction::Up)
    );
    assert!(notices.iter().any(|n| n == STOPPED), "{notices:?}");
    let moves = r.trim_moves_since(from);
    assert!(moves[0] && !moves.last().unwrap(), "{moves:?}");
    assert_eq!(
        moves.iter().filter(|on| !**on).count(),
        1,
        "one run, one stop"
    );

    // Refused both ways, nothing on the wire.
    r.run(4000); // past any confirmation window
    let from = r.sent.len();
    let at = r.pitch_pos();
    let refused = r.key('u', KeyEventKind::Press, false).notice.unwrap();
    assert_eq!(
        refused,
        "pitch trim moved down when asked up: its leads or its sensor may be swapped; let go, \
         then press u again within 3 s to run it up anyway, watching the motor"
    );
    r.key('u', KeyEventKind::Release, false);
    r.run(3100);
    let late = r.key('u', KeyEventKind::Press, false).notice.unwrap();
    assert!(
        late.starts_with("pitch trim moved down"),
        "3.1 s is too late: {late}"
    );
    r.key('u', KeyEventKind::Release, false);
    r.run(100);
    let d = r.key('d', KeyEventKind::Press, false).notice.unwrap();
    assert!(d.contains("press d again"), "{d}");
    r.key('d', KeyEventKind::Release, false);
    r.run(300);
    assert!(
        r.trim_moves_since(from).is_empty(),
        "a refused key sent nothing"
    );
    assert_eq!(r.pitch_pos(), at);

    // Confirmed: u, then u again within 3 s, held: down to 220, never past.
    r.key('u', KeyEventKind::Press, false);
    r.key('u', KeyEventKind::Release, false);
    r.run(500);
    let (seen, _) = r.hold('u', 8000, false);
    let most = *seen.iter().max().unwrap();
    assert!((216..=220).contains(&most), "confirmed run to {most}");
    assert_eq!(
        r.ctl.last_stop().unwrap().reason,
        StopReason::AtEndpoint(220)
    );
    // Confirmed again and again, held each time: never past 220, and at it, u is
    // refused by the endpoint the way it really moves, confirmed or not.
    for _ in 0..3 {
        r.run(400);
        r.key('u', KeyEventKind::Press, false);
        r.key('u', KeyEventKind::Release, false);
        r.run(200);
        let (seen, _) = r.hold('u', 1500, false);
        assert!(seen.iter().all(|&p| p <= 220), "{seen:?}");
    }
    r.run(400);
    for words in ["down endpoint", "down endpoint"] {
        let out = r.key('u', KeyEventKind::Press, false);
        assert!(
            out.notice.as_deref().unwrap_or("").contains(words),
            "{out:?}"
        );
        assert!(out.packets.is_empty());
        r.key('u', KeyEventKind::Release, false);
        r.run(200);
    }
    // d, confirmed, runs it up, away from 220.
    r.key('d', KeyEventKind::Press, false);
    r.key('d', KeyEventKind::Release, false);
    r.run(200);
    let (seen, _) = r.hold('d', 1000, false);
    assert!(*seen.iter().min().unwrap() < most - 10, "{seen:?}");
    assert!(seen.iter().all(|&p| p <= 220), "{seen:?}");
}

/// The bug as reproduced, at the down endpoint with nothing known yet: each hold of
/// `u` went on past 220 (to 223). Now the first such hold starts as a probe, is
/// stopped within the one count of noise, and the next is refused.
#[test]
fn at_the_endpoint_a_hold_that_goes_further_past_it_is_stopped_there() {
    let mut r = rig(220);
    let (seen, notices) = r.hold('u', 1500, false);
    let most = *seen.iter().max().unwrap();
    assert!(most <= 221, "past 220 to {most}: {seen:?}");
    assert!(notices.iter().any(|n| n == STOPPED), "{notices:?}");
    let (seen, notices) = r.hold('u', 1500, false);
    assert!(*seen.iter().max().unwrap() <= most, "{seen:?}");
    // Known to go down, it is at the endpoint that way: refused before any
    // confirmation is even offered.
    assert!(
        notices[0].contains("at its down endpoint (position 22"),
        "{notices:?}"
    );
}

/// The `install` scenario, its pitch trim (leads swapped) parked at or near its down
/// endpoint 220, nothing known of its way: a hold of `u` (away from that endpoint,
/// as the page believes) starts as short probes, each with its stop on the wire, and
/// never takes the unit's own position past 220 + NOISE (1). Before the probes the
/// first position past the noise stopped it: up to 4 counts past.
#[test]
fn a_reversed_trim_held_away_from_the_endpoint_behind_it_never_passes_it() {
    for at in [220u8, 219, 217, 214, 211] {
        let install = include_str!("../../../assets/scenarios/install.toml").replace(
            "position = 125\nreversed = true",
            &format!("position = {at}\nreversed = true"),
        );
        assert!(install.contains(&format!("position = {at}\n")));
        let mut r = Rig::with(&install, Rig::only(&[Step::Motors]));
        r.ctl = Controller::new(StreamerConfig {
            release_mode: ReleaseMode::KeyRelease,
            ..StreamerConfig::default()
        });
        let from = r.sent.len();
        let (seen, notices) = r.hold('u', 1500, false);
        let most = *seen.iter().max().unwrap();
        assert!(most <= 221, "from {at}: past 220 to {most}: {seen:?}");
        assert_eq!(
            r.ctl.last_stop().unwrap().reason,
            StopReason::MovedAgainst(Direction::Up),
            "from {at}"
        );
        assert!(
            notices
                .iter()
                .any(|n| n == "pitch trim near its down endpoint: trying a short run first"),
            "from {at}: {notices:?}"
        );
        assert!(notices.iter().any(|n| n == STOPPED), "{notices:?}");
        // Every probe ended with its stop, and the run ended stopped.
        let moves = r.trim_moves_since(from);
        assert!(moves[0] && !moves.last().unwrap(), "{moves:?}");
        assert!(moves.len() <= 12, "from {at}: {moves:?}");
    }
}

/// The same probes on a trim wired right, parked at its down endpoint: held `u`, it
/// shows its way within a probe or two and then runs on as any run, streaming with
/// no gap over 250 ms, to where the person lets go (75 counts in 3 s).
#[test]
fn a_trim_wired_right_at_its_endpoint_probes_then_runs_smoothly() {
    let mut r = Rig::with(&pitch_at(220, false), Rig::only(&[Step::Motors]));
    r.ctl = Controller::new(StreamerConfig {
        release_mode: ReleaseMode::KeyRelease,
        ..StreamerConfig::default()
    });
    let from = r.sent.len();
    let (seen, notices) = r.hold('u', 3000, false);
    assert!(
        notices
            .iter()
            .any(|n| n == "pitch trim near its down endpoint: trying a short run first"),
        "{notices:?}"
    );
    assert!(seen.iter().all(|&p| p <= 220), "{seen:?}");
    let last = *seen.last().unwrap();
    assert!(last <= 160, "only to {last}");
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::Released);
    // At most a few probes' stops before the run streams on, then one stop at the end.
    let moves = r.timed_trim_moves_since(from);
    let stops = moves.iter().filter(|(_, on)| !on).count();
    assert!((2..=4).contains(&stops), "{moves:?}");
    let resumed = moves.iter().rposition(|(_, on)| !on).unwrap();
    let streaming = &moves[moves[..resumed].iter().rposition(|(_, on)| !on).unwrap() + 1..];
    assert!(streaming.len() > 15, "{moves:?}");
    for w in streaming.windows(2) {
        assert!(w[1].0 - w[0].0 <= Duration::from_millis(250), "{moves:?}");
    }
}

/// The setup screens' capture runs past the endpoints, but not against its command:
/// the same words, the same stop, the same refusal after.
#[test]
fn the_setup_capture_stops_a_motor_moving_against_its_command() {
    let mut r = rig(128);
    let (seen, notices) = r.hold('u', 2000, true);
    let most = *seen.iter().max().unwrap();
    assert!((131..=134).contains(&most), "went down to {most}");
    assert!(notices.iter().any(|n| n == STOPPED), "{notices:?}");
    r.run(500);
    let out = r.key('u', KeyEventKind::Press, true);
    assert!(out.packets.is_empty());
    assert!(out.notice.unwrap().contains("press u again"));
    // Confirmed, the capture goes on past the endpoint (it finds new ones).
    r.key('u', KeyEventKind::Release, true);
    let (seen, _) = r.hold('u', 5000, true);
    assert!(*seen.iter().max().unwrap() > 220, "{seen:?}");
}

/// The installation check: its first run (up, toward more room from 128) is
/// stopped within a few counts; the second is not made; it is found reversed, put
/// back, and the keys then refuse it until confirmed.
#[test]
fn the_check_stops_its_run_and_the_keys_then_refuse_it() {
    let mut r = rig(128);
    let seen = r.check_watching(PITCH, 3000);
    let lo = *seen.iter().min().unwrap();
    let hi = *seen.iter().max().unwrap();
    assert!(lo >= 123 && hi <= 133, "{lo}..{hi}: {:?}", r.progress);
    r.assert_pitch_found(MotorFinding::Reversed);
    assert!(
        r.progress.iter().any(|n| n.contains(
            "pitch trim moved down when asked up: its leads or its sensor may be swapped; stopped"
        )),
        "{:?}",
        r.progress
    );
    r.run(500);
    let out = r.key('d', KeyEventKind::Press, false);
    assert!(out.packets.is_empty());
    assert!(out.notice.unwrap().contains("press d again"));
    assert!(r.ctl.running().is_none());
}

/// The check after the keys saw it: no test run is made, nothing moves, and the
/// finding is "reversed".
#[test]
fn the_check_refuses_a_motor_the_keys_saw_moving_against_its_command() {
    let mut r = rig(128);
    r.hold('u', 1000, false);
    r.run(500);
    let from = r.sent.len();
    let at = r.pitch_pos();
    r.start();
    r.run_until(20_000, |r| r.view.step == Step::Done);
    assert!(r.trim_moves_since(from).is_empty(), "{:?}", r.progress);
    assert_eq!(r.pitch_pos(), at);
    r.assert_pitch_found(MotorFinding::Reversed);
    let refused = r.pitch_up_for(1000).unwrap_err();
    assert_eq!(
        refused.reason,
        crate::control::run::Refused::Against(Direction::Up)
    );
    assert!(
        refused
            .words
            .contains("not run: confirm a run on the page's device list"),
        "{refused}"
    );
}

/// A terminal with no key release: a key held through the refusal never confirms it
/// (its repeats are not presses); let go, a press after the repeat gap does.
#[test]
fn a_held_key_never_confirms_only_a_fresh_press_does() {
    let mut r = Rig::with(&pitch_at(128, true), Rig::only(&[Step::Motors]));
    r.ctl.against().record(PITCH, Direction::Up);
    let from = r.sent.len();
    let out = r.key('u', KeyEventKind::Press, false);
    assert!(out.notice.unwrap().contains("let go, then press u again"));
    // Held: the terminal sends the same press every 40 ms after its first delay.
    r.run(500);
    for _ in 0..30 {
        let out = r.key('u', KeyEventKind::Press, false);
        assert!(out.packets.is_empty(), "a held key ran it: {out:?}");
        r.run(40);
    }
    assert!(r.trim_moves_since(from).is_empty());
    // Let go (no more repeats), then a fresh press, 2.3 s after the refusal: it runs.
    r.run(600);
    let out = r.key('u', KeyEventKind::Press, false);
    assert!(
        out.packets
            .iter()
            .any(|p| matches!(p.message, Message::TrimMove(t) if t.on)),
        "{out:?}"
    );
}

/// The decision for a motor that never shows its way near the endpoint behind it
/// (the `install` scenario's roll trim: driven, its position never moves): it is
/// probed again, each probe with its stop on the wire, for as long as its key is
/// held; let go, the run ends as any run does. Nothing ran it for longer than a
/// probe at a time.
#[test]
fn a_motor_that_never_shows_its_way_is_only_probed_while_held() {
    use crate::control::Selected;
    use crate::model::{CircuitKind, CircuitState, Motor, TrimKind};
    const ROLL: Motor = Motor::Trim(TrimKind::Roll);
    let install = include_str!("../../../assets/scenarios/install.toml").replace(
        "position = 125\nstuck = true",
        "position = 205\nstuck = true",
    );
    assert!(install.contains("position = 205\nstuck"));
    let mut r = Rig::with(&install, Rig::only(&[Step::Motors]));
    r.ctl = Controller::new(StreamerConfig {
        release_mode: ReleaseMode::KeyRelease,
        ..StreamerConfig::default()
    });
    let ctx = crate::control::KeyContext {
        selected: Some(Selected {
            id: ROLL.device_id(),
            kind: CircuitKind::Trim(TrimKind::Roll),
            state: CircuitState::Off,
        }),
        overlay_open: false,
        past_endpoints: false,
    };
    let from = r.sent.len();
    let key = |kind| KeyEvent::new_with_kind(KeyCode::Char(','), KeyModifiers::NONE, kind);
    let out = r
        .ctl
        .handle_key(key(KeyEventKind::Press), &ctx, &r.model, r.now);
    assert_eq!(
        out.notice.as_deref(),
        Some("roll trim near its right endpoint: trying a short run first")
    );
    r.send(out.packets);
    for _ in 0..50 {
        r.run_watching(40, ROLL);
        let out = r
            .ctl
            .handle_key(key(KeyEventKind::Repeat), &ctx, &r.model, r.now);
        r.send(out.packets);
    }
    let ons = r.timed_trim_moves_since(from);
    // 5 counts from the endpoint behind it, each probe runs 220 ms (5.5 counts at
    // the fastest motor's 25 a second), then is stopped until the next: 2 s held
    // makes several, and none ran longer.
    let probes: Vec<&[(Duration, bool)]> = ons.split_inclusive(|(_, on)| !on).collect();
    assert!(probes.len() >= 4, "{ons:?}");
    for p in &probes {
        let (last, moves) = p.split_last().unwrap();
        assert!(!last.1 && moves.iter().all(|(_, on)| *on), "{ons:?}");
        assert!(last.0 - moves[0].0 <= Duration::from_millis(230), "{ons:?}");
    }
    assert!(r.ctl.running().is_some(), "still held, still probing");
    let out = r
        .ctl
        .handle_key(key(KeyEventKind::Release), &ctx, &r.model, r.now);
    r.send(out.packets);
    r.run(300);
    assert!(r.ctl.running().is_none());
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::Released);
    assert_eq!(r.unit.snapshot(r.now).roll_trim_position, 205);
}

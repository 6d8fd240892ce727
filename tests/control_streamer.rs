//! The motor stream on a fake clock: every way a run ends, in both release modes,
//! sends the exact stop message, and no gap between move messages exceeds 250 ms even
//! when the main loop wakes late.

mod common;
#[path = "common/selection.rs"]
mod selection;

use common::live_unit::{self, Unit};
use selection::selected;
use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use vpx_efis::audit::Origin;
use vpx_efis::control::{
    Action, Controller, Direction, How, KeyContext, MAX_WIRE_INTERVAL, MotorStreamer, StopReason,
    StreamerConfig,
};
use vpx_efis::model::{CircuitKind, CircuitState, Model, Motor, Source, TrimKind};
use vpx_efis::protocol::device::{FLAPS, TRIM_P, TRIM_R};
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::protocol::frame::Node;
use vpx_efis::protocol::message::{
    FaultStatus, FlapDirection, FlapMove, Message, Packet, TrimDirection, TrimMove, TrimType,
};
use vpx_efis::ui::state::ReleaseMode;

const MODES: [ReleaseMode; 2] = [ReleaseMode::KeyRelease, ReleaseMode::AutoRepeat];
const PITCH: Motor = Motor::Trim(TrimKind::Pitch);
const ROLL: Motor = Motor::Trim(TrimKind::Roll);

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

// ----- the unit's side: broadcasts that keep the model live -----

fn feed(model: &mut Model, unit: Unit, now: Instant) {
    live_unit::feed(model, unit, 50, now);
}

fn live_model(now: Instant) -> Model {
    let mut m = Model::new(Source::Simulated {
        scenario: "test".into(),
    });
    feed(&mut m, Unit::Healthy, now);
    m
}

// ----- keys -----

fn ctx_for(motor: Motor) -> KeyContext {
    let (id, kind) = match motor {
        Motor::Flaps => (FLAPS, CircuitKind::Flaps),
        Motor::Trim(TrimKind::Pitch) => (TRIM_P, CircuitKind::Trim(TrimKind::Pitch)),
        Motor::Trim(TrimKind::Roll) => (TRIM_R, CircuitKind::Trim(TrimKind::Roll)),
    };
    selected(id, kind, CircuitState::Off)
}

fn key(code: KeyCode, kind: KeyEventKind) -> KeyEvent {
    KeyEvent::new_with_kind(code, KeyModifiers::NONE, kind)
}

/// What a terminal sends while the key `code` is held from `from` for `hold`:
/// a press, repeats after `delay` every `rate`, and a release only if it reports them.
fn held_key(
    mode: ReleaseMode,
    code: KeyCode,
    from: Instant,
    hold: Duration,
    delay: Duration,
    rate: Duration,
) -> Vec<(Instant, Ev)> {
    let repeat_kind = match mode {
        ReleaseMode::KeyRelease => KeyEventKind::Repeat,
        ReleaseMode::AutoRepeat => KeyEventKind::Press,
    };
    let mut out = vec![(from, Ev::Key(key(code, KeyEventKind::Press)))];
    let mut t = from + delay;
    while t < from + hold {
        out.push((t, Ev::Key(key(code, repeat_kind))));
        t += rate;
    }
    if mode == ReleaseMode::KeyRelease {
        out.push((from + hold, Ev::Key(key(code, KeyEventKind::Release))));
    }
    out
}

// ----- the main loop -----

#[derive(Clone, Debug)]
enum Ev {
    Key(KeyEvent),
    FocusLost,
    FocusGained,
    LinkError,
    Quit,
    Unit(UnitChange),
    /// A packet from the unit beyond its usual broadcasts.
    Packet(Packet),
    /// The terminal became too small to show the page.
    PageHidden,
}

#[derive(Clone, Copy, Debug)]
enum UnitChange {
    Healthy,
    StatusSilent,
    PitchFault,
}

struct Loop {
    ctl: Controller,
    model: Model,
    unit: Unit,
    ctx: KeyContext,
    wire: Vec<(Instant, Packet)>,
    actions: Vec<Action>,
    /// The latest any wake-up came after the time it was due.
    worst_lateness: Duration,
}

impl Loop {
    fn new(mode: ReleaseMode, motor: Motor, t0: Instant) -> Loop {
        Loop {
            ctl: Controller::new(StreamerConfig {
                release_mode: mode,
                ..Default::default()
            }),
            model: live_model(t0),
            unit: Unit::Healthy,
            ctx: ctx_for(motor),
            wire: Vec::new(),
            actions: Vec::new(),
            worst_lateness: Duration::ZERO,
        }
    }

    /// Runs the loop until `until`: it wakes at the controller's deadline (late by
    /// whatever `late` says) or at the next event, feeds the model at every wake like
    /// the reader thread would, and records every packet with the time it was sent.
    fn run(
        &mut self,
        mut events: Vec<(Instant, Ev)>,
        until: Instant,
        mut late: impl FnMut() -> Duration,
    ) {
        events.sort_by_key(|e| e.0);
        let mut events = events.into_iter().peekable();
        let mut last = None;
        for wakes in 0.. {
            // A streamer that keeps asking for a deadline already past would spin
            // this loop forever; fail instead of hanging.
            assert!(wakes < 1_000_000, "the loop never got past {last:?}");
            let tick_at = self.ctl.next_deadline().map(|d| (d, d + late()));
            let ev_at = events.peek().map(|e| e.0);
            let now = match (tick_at.map(|t| t.1), ev_at) {
                (Some(a), Some(b)) => a.min(b),
                (a, b) => match a.or(b) {
                    Some(t) => t,
                    None => break,
                },
            };
            let now = last.map_or(now, |l: Instant| now.max(l));
            last = Some(now);
            if now > until {
                break;
            }
            if let Some((due, _)) = tick_at
                && now >= due
            {
                self.worst_lateness = self.worst_lateness.max(now - due);
            }
            feed(&mut self.model, self.unit, now);
            if ev_at == Some(now) {
                let (_, ev) = events.next().unwrap();
                let p = match ev {
                    Ev::Key(k) => {
                        let o = self.ctl.handle_key(k, &self.ctx, &self.model, now);
                        self.actions.extend(o.action);
                        o.packets
                    }
                    Ev::FocusLost => self.ctl.on_focus_lost(now),
                    Ev::FocusGained => {
                        self.ctl.on_focus_gained(now);
                        Vec::new()
                    }
                    Ev::LinkError => self.ctl.stop(now, StopReason::LinkError),
                    Ev::Quit => self.ctl.stop(now, StopReason::Quit),
                    Ev::Unit(c) => {
                        self.unit = match c {
                            UnitChange::Healthy => Unit::Healthy,
                            UnitChange::StatusSilent => Unit::StatusSilent,
                            UnitChange::PitchFault => Unit::PitchFault,
                        };
                        feed(&mut self.model, self.unit, now);
                        self.ctl.tick(&self.model, now)
                    }
                    Ev::Packet(p) => {
                        self.model.apply_packet(now, &p);
                        self.ctl.tick(&self.model, now)
                    }
                    Ev::PageHidden => self.ctl.stop(now, StopReason::PageHidden),
                };
                self.send(now, p);
            }
            // After applying received packets and handling input, the loop ticks
            // (the module's contract).
            let p = self.ctl.tick(&self.model, now);
            self.send(now, p);
        }
    }

    fn send(&mut self, now: Instant, packets: Vec<Packet>) {
        self.wire.extend(packets.into_iter().map(|p| (now, p)));
    }

    fn moves(&self) -> Vec<(Instant, Packet)> {
        self.wire
            .iter()
            .filter(|(_, p)| matches!(p.message, Message::TrimMove(_) | Message::FlapMove(_)))
            .copied()
            .collect()
    }
}

fn is_on(p: &Packet) -> bool {
    match p.message {
        Message::TrimMove(m) => m.on,
        Message::FlapMove(m) => m.on,
        _ => false,
    }
}

/// Each run on the wire as (times of its move messages, its stop), checking that
/// every run ends in a stop. The largest gap inside any run is returned.
fn runs(moves: &[(Instant, Packet)]) -> (Vec<Vec<(Instant, Packet)>>, Duration) {
    let mut runs = Vec::new();
    let mut cur: Vec<(Instant, Packet)> = Vec::new();
    let mut worst = Duration::ZERO;
    for &(t, p) in moves {
        if let Some(&(prev, _)) = cur.last() {
            worst = worst.max(t - prev);
        }
        cur.push((t, p));
        if !is_on(&p) {
            runs.push(std::mem::take(&mut cur));
        }
    }
    assert!(
        cur.is_empty(),
        "a run was left streaming without a stop: {cur:?}"
    );
    (runs, worst)
}

fn pitch_stop(direction: TrimDirection) -> Message {
    Message::TrimMove(TrimMove {
        trim_type: TrimType::Pitch,
        on: false,
        direction,
    })
}

/// The one run of `what`: its stop is exactly `stop`, sent to the VP-X as a request,
/// no gap exceeds 250 ms, and it ended for `reason` at `ended` or at most `within` after.
fn assert_one_run(
    what: &str,
    l: &Loop,
    stop: Message,
    reason: StopReason,
    ended: Instant,
    within: Duration,
) {
    let (runs, worst) = runs(&l.moves());
    assert_eq!(runs.len(), 1, "{what}: expected one run: {:?}", l.moves());
    let run = &runs[0];
    let (t_stop, p_stop) = *run.last().unwrap();
    assert_eq!(p_stop, Packet::request(p_stop.cnt, stop), "{what}");
    assert_eq!(
        (p_stop.src, p_stop.dst),
        (Node::External, Node::Vpx),
        "{what}"
    );
    assert!(
        worst <= MAX_WIRE_INTERVAL,
        "{what}: gap of {worst:?} on the wire"
    );
    assert!(run.len() >= 2, "{what}: {run:?}");
    assert_eq!(l.ctl.last_stop().unwrap().reason, reason, "{what}");
    assert!(l.ctl.running().is_none(), "{what}");
    assert!(
        t_stop >= ended && t_stop <= ended + within,
        "{what}: stop at {:?}, expected at {:?} or up to {within:?} after",
        t_stop - run[0].0,
        ended - run[0].0
    );
}

/// A late-waking loop: 0–30 ms after each deadline, from a fixed-seed generator so a
/// failure reproduces.
fn jitter(seed: u64) -> impl FnMut() -> Duration {
    let mut x = seed;
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        ms(x % 31)
    }
}

const DELAY: Duration = Duration::from_millis(500);
const RATE: Duration = Duration::from_millis(33);

// ----- each end of a run, in both modes -----

/// What the held key's own events do once a run's cause has happened.
#[derive(Clone, Copy, Debug)]
enum HeldKey {
    /// Still held: its repeats (and, where reported, its release) go on.
    Held,
    /// Gone from the cause on: let go, or a terminal that repeats only the newest key.
    Gone,
    /// Silent from the cause until this long after the press, then held again: focus
    /// away and back, as X11 repeats a held key into whichever window has focus.
    AwayUntil(Duration),
}

/// One way a run of the page's keys ends: a key held for `hold` from the press,
/// `cause` at `at`, and the one run the wire must then carry.
struct Ending {
    name: &'static str,
    modes: &'static [ReleaseMode],
    motor: Motor,
    key: char,
    hold: Duration,
    at: Instant,
    /// None: the run ends on its own clock (a window, the cap).
    cause: Option<Ev>,
    held: HeldKey,
    /// Anything else that happens, at its time.
    later: Vec<(Instant, Ev)>,
    /// The stop is due this long after `at`...
    after: Duration,
    /// ...and goes out at most this long after it is due: none for a stop decided
    /// at an event, one resend period plus the loop's lateness for one found by a tick.
    within: Duration,
    reason: StopReason,
    stop: Message,
    /// Every action the page took meanwhile beyond the motor keys' own: a key that
    /// stops a motor does nothing else.
    actions: Vec<Action>,
    /// The words the stop leaves for the person, if the cause has its own.
    notice: Option<&'static str>,
}

/// A pitch trim held up with `u` for 3 s, ended by `cause` at `at`: the shape of most rows.
fn pitch_up(name: &'static str, at: Instant, cause: Option<Ev>, reason: StopReason) -> Ending {
    Ending {
        name,
        modes: &MODES,
        motor: PITCH,
        key: 'u',
        hold: ms(3000),
        at,
        cause,
        held: HeldKey::Held,
        later: Vec::new(),
        after: Duration::ZERO,
        within: Duration::ZERO,
        reason,
        stop: pitch_stop(TrimDirection::UpOrLeft),
        actions: Vec::new(),
        notice: None,
    }
}

fn flap_stop(direction: FlapDirection) -> Message {
    Message::FlapMove(FlapMove {
        on: false,
        direction,
    })
}

/// Up to one resend period and the loop's lateness after a stop is due.
const BY_A_TICK: Duration = Duration::from_millis(125 + 30);

/// Every way a run of the page's keys ends in `mode`, for a press at `start`.
fn endings(mode: ReleaseMode, start: Instant) -> Vec<Ending> {
    let press = |c| Ev::Key(key(KeyCode::Char(c), KeyEventKind::Press));
    let released = held_key(mode, KeyCode::Char('u'), start, ms(1500), DELAY, RATE);
    let last_key_event = released.last().unwrap().0;
    let fault = FaultStatus::with_faults(&[(FLAPS, FaultCode::FlapRunaway)]);
    let cap = start + ms(10_000);
    vec![
        match mode {
            ReleaseMode::KeyRelease => Ending {
                hold: ms(1500),
                ..pitch_up("release", last_key_event, None, StopReason::Released)
            },
            // The last repeat plus the gap learned from this hold: 3 × 33 ms.
            ReleaseMode::AutoRepeat => Ending {
                hold: ms(1500),
                after: ms(99),
                within: ms(30),
                ..pitch_up(
                    "repeats stop",
                    last_key_event,
                    None,
                    StopReason::RepeatsStopped,
                )
            },
        },
        Ending {
            modes: &[ReleaseMode::AutoRepeat],
            key: 'd',
            hold: ms(1),
            after: ms(700),
            within: ms(30),
            stop: pitch_stop(TrimDirection::DownOrRight),
            ..pitch_up(
                "no repeat within the first window of 700 ms",
                start,
                None,
                StopReason::RepeatsStopped,
            )
        },
        pitch_up(
            "another key",
            start + ms(1207),
            Some(press('j')),
            StopReason::OtherKey,
        ),
        // The other direction pressed while up is still held, then held itself.
        Ending {
            held: HeldKey::Gone,
            later: held_key(
                mode,
                KeyCode::Char('d'),
                start + ms(805),
                ms(2000),
                DELAY,
                RATE,
            )
            .into_iter()
            .skip(1)
            .collect(),
            ..pitch_up(
                "another motor key",
                start + ms(805),
                Some(press('d')),
                StopReason::OtherKey,
            )
        },
        Ending {
            held: HeldKey::Gone,
            actions: vec![Action::Quit],
            ..pitch_up("q", start + ms(1503), Some(press('q')), StopReason::Quit)
        },
        // The app leaving another way: Ctrl-C, the window closed.
        Ending {
            held: HeldKey::Gone,
            ..pitch_up("quit", start + ms(1503), Some(Ev::Quit), StopReason::Quit)
        },
        Ending {
            hold: ms(4000),
            held: HeldKey::AwayUntil(ms(2000)),
            ..pitch_up(
                "focus loss",
                start + ms(1004),
                Some(Ev::FocusLost),
                StopReason::FocusLost,
            )
        },
        Ending {
            motor: ROLL,
            key: ',',
            stop: Message::TrimMove(TrimMove {
                trim_type: TrimType::Roll,
                on: false,
                direction: TrimDirection::UpOrLeft,
            }),
            ..pitch_up(
                "a link write error",
                start + ms(1309),
                Some(Ev::LinkError),
                StopReason::LinkError,
            )
        },
        // The model calls it lost once 2.5 s pass without status (Appendix A); the run
        // ends at the first tick after that.
        Ending {
            hold: ms(6000),
            after: ms(2500) + Duration::from_nanos(1),
            within: BY_A_TICK,
            ..pitch_up(
                "communication lost",
                start + ms(500),
                Some(Ev::Unit(UnitChange::StatusSilent)),
                StopReason::CommLost,
            )
        },
        // The runaway clears itself on the unit's side later; the held key must not
        // start the motor again.
        Ending {
            key: 'd',
            later: vec![(start + ms(2000), Ev::Unit(UnitChange::Healthy))],
            stop: pitch_stop(TrimDirection::DownOrRight),
            ..pitch_up(
                "a motor fault",
                start + ms(1102),
                Some(Ev::Unit(UnitChange::PitchFault)),
                StopReason::MotorFault(FaultCode::TrimRunaway),
            )
        },
        Ending {
            motor: Motor::Flaps,
            key: 'd',
            stop: flap_stop(FlapDirection::Down),
            ..pitch_up(
                "a fault in FAULT_STATUS alone",
                start + ms(1000),
                Some(Ev::Packet(Packet::from_vpx(0, fault))),
                StopReason::MotorFault(FaultCode::FlapRunaway),
            )
        },
        // Held 5 s past the cap, repeats flowing all along. Repeat events can never
        // start a run, so they alone would prove nothing: a Press of the still-held key
        // (a terminal that mislabels one) must not restart it either.
        Ending {
            motor: Motor::Flaps,
            key: 'd',
            hold: ms(15_000),
            later: vec![(start + ms(12_000), press('d'))],
            within: ms(30),
            stop: flap_stop(FlapDirection::Down),
            ..pitch_up("the run cap", cap, None, StopReason::MaxRunTime)
        },
        // Without release reports a tap cannot be told from a repeat: until a gap longer
        // than the repeat window (3 × 33 ms, learned from the hold), key events only
        // keep the key "held".
        Ending {
            modes: &[ReleaseMode::AutoRepeat],
            hold: ms(10_500),
            later: (1..=19)
                .map(|i| (start + ms(10_500 + 80 * i), press('u')))
                .collect(),
            within: ms(30),
            ..pitch_up(
                "the run cap, taps within the repeat window after it",
                cap,
                None,
                StopReason::MaxRunTime,
            )
        },
        Ending {
            held: HeldKey::Gone,
            notice: Some("too small"),
            ..pitch_up(
                "a page too small to see",
                start + ms(1200),
                Some(Ev::PageHidden),
                StopReason::PageHidden,
            )
        },
    ]
}

/// Runs `e` in `mode` from `t0` on a loop waking up to 30 ms late, checks its one run,
/// and returns the loop for what comes next.
fn end_a_run(mode: ReleaseMode, e: &Ending, t0: Instant, seed: u64) -> Loop {
    let what = format!("{} ({mode:?})", e.name);
    let mut l = Loop::new(mode, e.motor, t0);
    let start = t0 + ms(100);
    let mut events = held_key(mode, KeyCode::Char(e.key), start, e.hold, DELAY, RATE);
    match e.held {
        HeldKey::Held => {}
        HeldKey::Gone => events.retain(|ev| ev.0 < e.at),
        HeldKey::AwayUntil(back) => events.retain(|ev| ev.0 <= e.at || ev.0 >= start + back),
    }
    events.extend(e.cause.clone().map(|c| (e.at, c)));
    events.extend(e.later.iter().cloned());
    l.run(events, start + e.hold + ms(2000), jitter(seed));
    assert_one_run(&what, &l, e.stop, e.reason, e.at + e.after, e.within);
    let others: Vec<Action> = (l.actions.iter())
        .filter(|a| !matches!(a, Action::Motor { .. } | Action::KeyReleased))
        .cloned()
        .collect();
    assert_eq!(others, e.actions, "{what}: the page's actions");
    if let Some(words) = e.notice {
        let notice = l.ctl.take_notice();
        assert!(
            notice.as_deref().is_some_and(|n| n.contains(words)),
            "{what}: the stop says why: {notice:?}"
        );
    }
    l
}

#[test]
fn every_end_of_a_run_sends_its_stop_in_time_in_both_modes() {
    for mode in MODES {
        let t0 = Instant::now();
        for (seed, e) in (1..).zip(endings(mode, t0 + ms(100))) {
            if e.modes.contains(&mode) {
                end_a_run(mode, &e, t0, seed);
            }
        }
    }
}

#[test]
fn after_the_cap_a_fresh_press_runs_again() {
    for mode in MODES {
        let t0 = Instant::now();
        let start = t0 + ms(100);
        let cap = endings(mode, start)
            .into_iter()
            .find(|e| e.name == "the run cap")
            .unwrap();
        let mut l = end_a_run(mode, &cap, t0, 11);
        // Let go, press again.
        let again = start + ms(16_500);
        l.run(
            held_key(mode, KeyCode::Char('d'), again, ms(1000), DELAY, RATE),
            again + ms(2000),
            jitter(12),
        );
        let (runs, worst) = runs(&l.moves());
        assert_eq!(
            runs.len(),
            2,
            "{mode:?}: a fresh press after the gap runs again"
        );
        assert_eq!(runs[1][0].0, again);
        assert!(worst <= MAX_WIRE_INTERVAL);
    }
}

/// Focus back with the key held through the change: its repeats start nothing. Focus
/// back and the key let go: the next press starts a run at once, not at its first
/// repeat (which made every first hold after switching windows start 0.66 s late).
#[test]
fn after_focus_returns_a_held_key_stays_stopped_and_a_new_press_starts_at_once() {
    for held_through in [true, false] {
        let t0 = Instant::now();
        let mut l = Loop::new(ReleaseMode::AutoRepeat, PITCH, t0);
        let start = t0 + ms(100);
        let mut events = held_key(
            ReleaseMode::AutoRepeat,
            KeyCode::Char('u'),
            start,
            ms(3000),
            DELAY,
            RATE,
        );
        let lost = start + ms(1000) + ms(4);
        let back = start + ms(2000);
        events.retain(|e| !(e.0 > lost && e.0 < back + ms(5)));
        events.push((lost, Ev::FocusLost));
        events.push((back, Ev::FocusGained));
        if !held_through {
            // Let go while away; pressed again a second after coming back.
            events.retain(|e| e.0 <= back);
            events.extend(held_key(
                ReleaseMode::AutoRepeat,
                KeyCode::Char('u'),
                back + ms(1000),
                ms(2000),
                DELAY,
                RATE,
            ));
        }
        l.run(events, t0 + ms(7000), || Duration::ZERO);
        let (runs, _) = runs(&l.moves());
        if held_through {
            assert_eq!(
                runs.len(),
                1,
                "the repeats after focus came back started nothing"
            );
        } else {
            assert_eq!(runs.len(), 2);
            assert_eq!(
                runs[1][0].0,
                back + ms(1000),
                "the press itself starts the run"
            );
        }
    }
}

#[test]
fn a_refused_press_is_not_started_later_by_its_repeats() {
    for mode in MODES {
        let t0 = Instant::now();
        let mut l = Loop::new(mode, PITCH, t0);
        l.unit = Unit::PitchFault;
        feed(&mut l.model, l.unit, t0);
        let start = t0 + ms(100);
        let mut events = held_key(mode, KeyCode::Char('u'), start, ms(3000), DELAY, RATE);
        events.push((start + ms(1000), Ev::Unit(UnitChange::Healthy)));
        l.run(events, t0 + ms(5000), jitter(14));
        assert!(l.moves().is_empty(), "{mode:?}: {:?}", l.moves());
    }
}

#[test]
fn a_motor_does_not_start_while_communication_is_lost() {
    let t0 = Instant::now();
    let mut ctl = Controller::default();
    let model = live_model(t0);
    let later = t0 + ms(3000);
    let o = ctl.handle_key(
        key(KeyCode::Char('u'), KeyEventKind::Press),
        &ctx_for(PITCH),
        &model,
        later,
    );
    assert!(o.packets.is_empty());
    assert!(o.notice.unwrap().contains("COMMUNICATION LOST"));
    assert!(ctl.running().is_none());
}

/// A page that cannot stream (its motor thread did not start) refuses the press that
/// would otherwise start the trim, in the words it was given.
#[test]
fn a_motor_does_not_start_where_motors_are_refused() {
    let t0 = Instant::now();
    let model = live_model(t0);
    let press = key(KeyCode::Char('u'), KeyEventKind::Press);
    let mut fine = Controller::default();
    let o = fine.handle_key(press, &ctx_for(PITCH), &model, t0);
    assert_eq!(o.packets.len(), 1, "a healthy page starts the trim");
    assert!(fine.running().is_some());

    let mut ctl = Controller::default();
    ctl.refuse_motors("motors unavailable: no thread".into());
    assert_eq!(ctl.motors_refused(), Some("motors unavailable: no thread"));
    let o = ctl.handle_key(press, &ctx_for(PITCH), &model, t0);
    assert!(o.packets.is_empty(), "{:?}", o.packets);
    assert!(ctl.running().is_none());
    assert_eq!(o.notice.as_deref(), Some("motors unavailable: no thread"));
}

/// The installation check's timed runs go through the same refusal: a page that
/// cannot stream must not start a run nothing resends.
#[test]
fn a_timed_run_does_not_start_where_motors_are_refused() {
    let t0 = Instant::now();
    let model = live_model(t0);
    let check_run = |ctl: &mut Controller| {
        let how = How::For {
            length: ms(600),
            way: None,
        };
        ctl.start(Origin::Check, &model, PITCH, Direction::Up, how, t0)
    };
    let mut fine = Controller::default();
    let p = check_run(&mut fine).expect("a healthy page runs the trim");
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(fine.running().is_some());

    let mut ctl = Controller::default();
    ctl.refuse_motors("motors unavailable: no thread".into());
    let r = check_run(&mut ctl);
    assert_eq!(r.unwrap_err().words, "motors unavailable: no thread");
    assert!(ctl.running().is_none());
    assert!(
        ctl.tick(&model, t0 + ms(250)).is_empty(),
        "nothing to resend"
    );
}

#[test]
fn no_gap_exceeds_250_ms_when_the_loop_wakes_up_to_30_ms_late() {
    let mut worst_seen = Duration::ZERO;
    for mode in MODES {
        for (seed, motor, code) in [
            (21, PITCH, KeyCode::Char('u')),
            (22, ROLL, KeyCode::Char('.')),
            (23, Motor::Flaps, KeyCode::Char('d')),
        ] {
            let t0 = Instant::now();
            let mut l = Loop::new(mode, motor, t0);
            let start = t0 + ms(50);
            // Several presses of different lengths, each a separate run.
            let mut events = Vec::new();
            let mut at = start;
            for hold in [300, 900, 2500, 9000, 700] {
                events.extend(held_key(mode, code, at, ms(hold), DELAY, RATE));
                at += ms(hold + 1500);
            }
            l.run(events, at + ms(2000), jitter(seed));
            let (runs, worst) = runs(&l.moves());
            assert_eq!(runs.len(), 5, "{mode:?} {motor:?}");
            assert!(l.worst_lateness >= ms(25), "the test must actually be late");
            assert!(
                worst <= MAX_WIRE_INTERVAL,
                "{mode:?} {motor:?}: gap {worst:?}"
            );
            worst_seen = worst_seen.max(worst);
        }
    }
    // Not an assertion on the exact value: it shows the margin in the test output.
    eprintln!("worst interval between move messages: {worst_seen:?}");
    assert!(worst_seen <= ms(125 + 30));
}

#[test]
fn emergency_stop_covers_flaps_pitch_and_roll() {
    let packets = MotorStreamer::emergency_stop_packets();
    let messages: Vec<Message> = packets.iter().map(|p| p.message).collect();
    assert!(messages.contains(&Message::FlapMove(FlapMove {
        on: false,
        direction: FlapDirection::Up
    })));
    assert!(messages.contains(&pitch_stop(TrimDirection::DownOrRight)));
    assert!(messages.contains(&Message::TrimMove(TrimMove {
        trim_type: TrimType::Roll,
        on: false,
        direction: TrimDirection::DownOrRight
    })));
    for p in packets {
        assert_eq!((p.src, p.dst), (Node::External, Node::Vpx));
        // The hook writes raw frames: they must encode.
        assert_eq!(Packet::parse_bytes(&p.to_bytes()).unwrap(), p);
    }
}

#[test]
fn the_stream_goes_out_on_press_and_then_every_125_ms() {
    let t0 = Instant::now();
    let mut l = Loop::new(ReleaseMode::KeyRelease, PITCH, t0);
    let start = t0 + ms(100);
    l.run(
        held_key(
            ReleaseMode::KeyRelease,
            KeyCode::Char('u'),
            start,
            ms(1000),
            DELAY,
            RATE,
        ),
        t0 + ms(2000),
        || Duration::ZERO,
    );
    let times: Vec<Duration> = l.moves().iter().map(|(t, _)| *t - start).collect();
    assert_eq!(
        times,
        [0, 125, 250, 375, 500, 625, 750, 875, 1000].map(ms),
        "press, seven resends, the stop at the release"
    );
    let first = l.moves()[0].1;
    assert_eq!(
        first,
        Packet::request(
            first.cnt,
            TrimMove {
                trim_type: TrimType::Pitch,
                on: true,
                direction: TrimDirection::UpOrLeft
            }
        )
    );
}

/// Key-release mode's second dead man: the kitty protocol also sends Repeat events
/// while a key is held, so a release that never arrives still ends the run well
/// before the 10 s cap.
#[test]
fn key_release_mode_ends_a_run_whose_release_is_lost() {
    use vpx_efis::control::Direction;
    let cfg = StreamerConfig {
        release_mode: ReleaseMode::KeyRelease,
        ..Default::default()
    };
    let (first, between) = cfg.key_release_repeat_guard.expect("on by default");
    let is_off = |p: &Packet| matches!(p.message, Message::TrimMove(m) if !m.on);

    // Held with repeats (first after 500 ms, then every 33 ms) for 2 s: it keeps
    // running; then the repeats stop and no release comes.
    let t0 = Instant::now();
    let mut s = MotorStreamer::new(cfg);
    assert_eq!(s.press(t0, PITCH, Direction::Up).len(), 1);
    let mut last_repeat = t0;
    let mut stopped_at = None;
    for step in 1..=400u64 {
        let now = t0 + ms(step * 10);
        let repeating = now >= t0 + ms(500) && now <= t0 + ms(2000);
        let mut out = Vec::new();
        if repeating && now.duration_since(last_repeat) >= ms(33) {
            out.extend(s.repeat(now, PITCH, Direction::Up));
            last_repeat = now;
        }
        out.extend(s.tick(now));
        if out.iter().any(is_off) && stopped_at.is_none() {
            stopped_at = Some(now);
        }
        if now <= t0 + ms(2000) {
            assert!(
                s.running().is_some(),
                "stopped at {:?} while repeats flowed",
                now - t0
            );
        }
    }
    let stopped_at = stopped_at.expect("a stop message without any release");
    assert!(
        stopped_at <= last_repeat + between + ms(10),
        "{:?} after the last repeat",
        stopped_at - last_repeat
    );
    assert_eq!(
        s.last_stop().map(|r| r.reason),
        Some(StopReason::RepeatsStopped)
    );

    // Pressed once, then nothing at all (a terminal that took the protocol but sends
    // neither repeats nor releases): it ends after the first window, not the cap.
    let mut s = MotorStreamer::new(cfg);
    s.press(t0, PITCH, Direction::Up);
    let mut off = None;
    for step in 1..=300u64 {
        let now = t0 + ms(step * 10);
        if s.tick(now).iter().any(is_off) {
            off = Some(now);
            break;
        }
    }
    let off = off.expect("a stop without release or repeats");
    assert!(off - t0 <= first + ms(10), "{:?}", off - t0);
}

// ----- learning the terminal's auto-repeat -----

/// A terminal's auto-repeat: the delay to the first repeat, the repeat rate, and the
/// `--repeat-delay` a person would give for it (only a terminal slower than 700 ms
/// needs one).
#[derive(Clone, Copy, Debug)]
struct Profile {
    delay_ms: u64,
    hz: f64,
    repeat_delay_ms: Option<u64>,
}

impl Profile {
    fn interval(&self) -> Duration {
        Duration::from_secs_f64(1.0 / self.hz)
    }

    fn config(&self) -> StreamerConfig {
        let mut c = StreamerConfig {
            release_mode: ReleaseMode::AutoRepeat,
            ..Default::default()
        };
        if let Some(d) = self.repeat_delay_ms {
            c.first_repeat_timeout = ms(d);
            c.first_repeat_fixed = true;
        }
        c
    }
}

/// X's default, KDE and sway, GNOME, a slow one with `--repeat-delay`, a fast one.
const PROFILES: [Profile; 5] = [
    Profile {
        delay_ms: 660,
        hz: 25.0,
        repeat_delay_ms: None,
    },
    Profile {
        delay_ms: 600,
        hz: 30.0,
        repeat_delay_ms: None,
    },
    Profile {
        delay_ms: 500,
        hz: 33.0,
        repeat_delay_ms: None,
    },
    Profile {
        delay_ms: 1000,
        hz: 25.0,
        repeat_delay_ms: Some(1100),
    },
    Profile {
        delay_ms: 250,
        hz: 50.0,
        repeat_delay_ms: None,
    },
];

/// The interval a gap of `3 × interval` is clamped into (the module's 90–250 ms).
fn expected_gap(interval: Duration) -> Duration {
    (interval * 3).clamp(ms(90), ms(250))
}

/// One hold of `hold` with `p`'s repeats, on a loop that wakes `late` after each
/// deadline; returns the times of the repeats sent.
fn hold_with(
    l: &mut Loop,
    p: Profile,
    start: Instant,
    hold: Duration,
    late: impl FnMut() -> Duration,
) -> Vec<Instant> {
    let events = held_key(
        ReleaseMode::AutoRepeat,
        KeyCode::Char('u'),
        start,
        hold,
        ms(p.delay_ms),
        p.interval(),
    );
    let times = events.iter().map(|e| e.0).collect();
    l.run(events, start + hold + ms(2000), late);
    times
}

/// For each profile, on a loop that wakes on time and on one up to 30 ms late: a 3 s
/// hold is one run, with no stop while repeats flow, every gap between move messages
/// at most 220 ms, and the stop within the learned gap after the last repeat.
#[test]
fn each_repeat_profile_holds_one_run_for_three_seconds_and_stops_within_the_learned_gap() {
    for p in PROFILES {
        for (lateness, seed) in [(false, 0), (true, 31)] {
            let t0 = Instant::now();
            let mut l = Loop::new(ReleaseMode::AutoRepeat, PITCH, t0);
            l.ctl = Controller::new(p.config());
            let start = t0 + ms(100);
            let mut j = jitter(seed);
            let late = move || if lateness { j() } else { Duration::ZERO };
            let keys = hold_with(&mut l, p, start, ms(3000), late);
            let last_repeat = *keys.last().unwrap();

            let (runs, worst) = runs(&l.moves());
            assert_eq!(runs.len(), 1, "{p:?}: one run, no stutter");
            assert!(worst <= ms(220), "{p:?}: a gap of {worst:?} on the wire");
            let (t_stop, _) = *runs[0].last().unwrap();
            assert!(
                t_stop > last_repeat,
                "{p:?}: stopped while the key was held"
            );

            let learned = l.ctl.repeat_timing();
            let gap = expected_gap(p.interval());
            assert_eq!(learned.interval, Some(p.interval()), "{p:?}");
            assert_eq!(learned.delay, Some(ms(p.delay_ms)), "{p:?}");
            assert_eq!(learned.end_gap, gap, "{p:?}");
            let allowed = gap + if lateness { l.worst_lateness } else { ms(0) };
            assert!(
                t_stop - last_repeat <= allowed,
                "{p:?}: the stop came {:?} after the last repeat, the gap is {gap:?}",
                t_stop - last_repeat
            );
            assert_eq!(
                l.ctl.last_stop().unwrap().reason,
                StopReason::RepeatsStopped
            );
        }
    }
}

/// The first hold waits 700 ms for the first repeat and teaches 500 ms / 30 ms; the
/// second hold uses that: a tap is a 600 ms nudge, and a hold ends 91 ms after its
/// last repeat instead of 200.
#[test]
fn a_first_hold_teaches_the_repeat_and_the_second_hold_uses_it() {
    let p = PROFILES[2];
    let t0 = Instant::now();
    let mut l = Loop::new(ReleaseMode::AutoRepeat, PITCH, t0);
    let before = l.ctl.repeat_timing();
    assert_eq!(
        (before.first_window, before.delay, before.interval),
        (ms(700), None, None)
    );
    assert_eq!(before.end_gap, ms(200));

    // First hold: taught.
    let start = t0 + ms(100);
    hold_with(&mut l, p, start, ms(3000), || Duration::ZERO);
    let learned = l.ctl.repeat_timing();
    assert_eq!(learned.delay, Some(ms(500)));
    assert_eq!(learned.first_window, ms(600), "500 ms + the 100 ms margin");
    assert_eq!(learned.end_gap, expected_gap(p.interval()));

    // A tap: a press and no repeat runs the motor for the learned window, not 700 ms.
    let tap = start + ms(6000);
    l.run(
        vec![(tap, Ev::Key(key(KeyCode::Char('u'), KeyEventKind::Press)))],
        tap + ms(2000),
        || Duration::ZERO,
    );
    let (runs_now, _) = runs(&l.moves());
    assert_eq!(runs_now.len(), 2);
    let tap_run = &runs_now[1];
    assert_eq!(tap_run[0].0, tap);
    assert_eq!(tap_run.last().unwrap().0 - tap, ms(600), "a bounded nudge");

    // A second hold: one run, ended one learned gap after its last repeat.
    let second = tap + ms(3000);
    let keys = hold_with(&mut l, p, second, ms(3000), || Duration::ZERO);
    let (runs_now, worst) = runs(&l.moves());
    assert_eq!(runs_now.len(), 3);
    assert!(worst <= ms(220));
    let stop = runs_now[2].last().unwrap().0;
    assert_eq!(stop - *keys.last().unwrap(), expected_gap(p.interval()));
}

/// A person tapping a motor key is not an auto-repeat: taps 250 ms apart teach
/// nothing, so a later hold still gets the 700 ms first window.
#[test]
fn taps_teach_nothing() {
    let t0 = Instant::now();
    let mut l = Loop::new(ReleaseMode::AutoRepeat, PITCH, t0);
    let events = (0..8)
        .map(|i| {
            (
                t0 + ms(100 + 250 * i),
                Ev::Key(key(KeyCode::Char('u'), KeyEventKind::Press)),
            )
        })
        .collect();
    l.run(events, t0 + ms(4000), || Duration::ZERO);
    let t = l.ctl.repeat_timing();
    assert_eq!((t.delay, t.interval), (None, None));
    assert_eq!(t.first_window, ms(700));
}

/// `--repeat-delay` is kept: learning measures the terminal but does not replace a
/// window set by hand.
#[test]
fn a_repeat_delay_set_by_hand_is_kept_after_learning() {
    let p = PROFILES[3];
    let t0 = Instant::now();
    let mut l = Loop::new(ReleaseMode::AutoRepeat, PITCH, t0);
    l.ctl = Controller::new(p.config());
    hold_with(&mut l, p, t0 + ms(100), ms(3000), || Duration::ZERO);
    let t = l.ctl.repeat_timing();
    assert!(t.set_by_hand);
    assert_eq!(t.first_window, ms(1100));
    assert_eq!(t.delay, Some(ms(1000)));
    // Without it the same terminal stutters: its first repeat comes after 700 ms.
    let mut l = Loop::new(ReleaseMode::AutoRepeat, PITCH, t0);
    hold_with(&mut l, p, t0 + ms(100), ms(3000), || Duration::ZERO);
    assert_eq!(runs(&l.moves()).0.len(), 2, "why the option exists");
}

/// A page too small to be seen: `f`, `o`, `r` and the motor keys send nothing (and
/// a held motor key stays held, so its repeats cannot start the motor once the page
/// is back); quit and help still act.
#[test]
fn keys_on_a_page_too_small_to_see_send_nothing_but_quit_and_help_act() {
    let t0 = Instant::now();
    let model = live_model(t0);
    let mut ctl = Controller::new(StreamerConfig::default());
    let device = selected(9, CircuitKind::Device, CircuitState::On);
    for (c, ctx) in [
        ('f', device),
        ('o', device),
        ('r', device),
        ('w', device),
        ('R', device),
        ('u', ctx_for(PITCH)),
        ('d', ctx_for(Motor::Flaps)),
        ('.', ctx_for(ROLL)),
    ] {
        let o = ctl.handle_key_hidden(key(KeyCode::Char(c), KeyEventKind::Press), &ctx, t0);
        assert!(o.packets.is_empty(), "{c}: sent {:?}", o.packets);
        assert_eq!(o.action, None, "{c}");
    }
    assert!(ctl.running().is_none());
    // A `u` held while hidden stays held: its repeat, once the page is back, starts
    // nothing.
    let u = key(KeyCode::Char('u'), KeyEventKind::Press);
    assert!(
        ctl.handle_key_hidden(u, &ctx_for(PITCH), t0)
            .packets
            .is_empty()
    );
    let o = ctl.handle_key(
        key(KeyCode::Char('u'), KeyEventKind::Press),
        &ctx_for(PITCH),
        &model,
        t0 + ms(30),
    );
    assert!(o.packets.is_empty(), "{:?}", o.packets);
    assert_eq!(
        ctl.handle_key_hidden(key(KeyCode::Char('q'), KeyEventKind::Press), &device, t0)
            .action,
        Some(Action::Quit)
    );
    assert_eq!(
        ctl.handle_key_hidden(key(KeyCode::Char('?'), KeyEventKind::Press), &device, t0)
            .action,
        Some(Action::ToggleHelp)
    );
}

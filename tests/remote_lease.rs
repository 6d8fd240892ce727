//! The walk-around remote's hold-to-run lease in `control`, on a fake clock, as the
//! key streams are tested: a run lives only while renewed (300 ms), ends with its
//! stop message when the lease runs out, when the remote lets go, and on every stop
//! cause a key's run has; a run that ended is not restarted by renewals.

mod common;

use common::live_unit::{self, Unit};
use std::time::{Duration, Instant};

use vpx_efis::control::{
    Controller, Direction, LEASE, MAX_WIRE_INTERVAL, StopReason, StreamerConfig,
};
use vpx_efis::model::{Model, Motor, Source, TrimKind};
use vpx_efis::protocol::message::{Message, Packet, TrimDirection, TrimMove, TrimType};

const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// The controller, a model fed as the link's reader would, and the wire on a fake
/// clock.
struct Rig {
    ctl: Controller,
    model: Model,
    now: Instant,
    wire: Vec<(Instant, Packet)>,
    unit: Unit,
    fed: Instant,
    /// Where the pitch trim stands (it never moves here).
    pitch_position: u8,
}

impl Rig {
    fn new(config: StreamerConfig) -> Rig {
        let now = Instant::now();
        let mut r = Rig {
            ctl: Controller::new(config),
            model: Model::new(Source::Simulated {
                scenario: "test".into(),
            }),
            now,
            wire: Vec::new(),
            unit: Unit::Healthy,
            fed: now,
            pitch_position: 50,
        };
        r.feed();
        r
    }

    fn feed(&mut self) {
        live_unit::feed(&mut self.model, self.unit, self.pitch_position, self.now);
        self.fed = self.now;
    }

    fn put(&mut self, packets: Vec<Packet>) {
        let now = self.now;
        self.wire.extend(packets.into_iter().map(|p| (now, p)));
    }

    /// The remote's POST with a direction.
    fn lease(&mut self, direction: Direction) -> Result<(), String> {
        let (p, r) = self.ctl.lease(&self.model, PITCH, direction, self.now);
        self.put(p);
        r.map_err(|e| e.words)
    }

    /// The remote's `{"stop":true}`.
    fn let_go(&mut self) {
        let p = self.ctl.lease_stop(self.now, StopReason::RemoteStop);
        self.put(p);
    }

    /// Runs the loop to `until`: ticks at every deadline of the controller (and the
    /// 10 Hz status), as the page's motor thread and loop do.
    fn run_to(&mut self, until: Instant) {
        loop {
            let status = self.fed + ms(100);
            let next = self
                .ctl
                .next_deadline()
                .map_or(status, |d| d.min(status))
                .min(until);
            if next <= self.now && self.now >= until {
                return;
            }
            self.now = next.max(self.now);
            if self.now >= status {
                self.feed();
            }
            let p = self.ctl.tick(&self.model, self.now);
            self.put(p);
            if self.now >= until {
                return;
            }
        }
    }

    fn moves(&self) -> Vec<(Instant, Packet)> {
        self.wire
            .iter()
            .filter(|(_, p)| matches!(p.message, Message::TrimMove(_)))
            .copied()
            .collect()
    }

    /// The time of the one stop on the wire, checking that the run before it never
    /// left a gap over 250 ms.
    fn the_stop(&self) -> (Instant, Packet) {
        let moves = self.moves();
        let stops: Vec<_> = moves.iter().filter(|(_, p)| !is_on(p)).collect();
        assert_eq!(stops.len(), 1, "one stop expected: {moves:?}");
        for w in moves.windows(2) {
            assert!(w[1].0 - w[0].0 <= MAX_WIRE_INTERVAL, "a gap over 250 ms");
        }
        assert_eq!(
            moves.last().unwrap(),
            stops[0],
            "nothing moves after the stop"
        );
        *stops[0]
    }
}

fn is_on(p: &Packet) -> bool {
    matches!(p.message, Message::TrimMove(m) if m.on)
}

/// ICD Table 30: TRIM_MOVE, pitch, power off, direction as the run's.
fn pitch_stop_up() -> Message {
    Message::TrimMove(TrimMove {
        trim_type: TrimType::Pitch,
        on: false,
        direction: TrimDirection::UpOrLeft,
    })
}

#[test]
fn a_lease_left_to_expire_stops_the_motor_at_300_ms() {
    let mut r = Rig::new(StreamerConfig::default());
    let t0 = r.now;
    assert_eq!(r.lease(Direction::Up), Ok(()));
    assert_eq!(r.ctl.remote_running(), Some((PITCH, Direction::Up)));
    r.run_to(t0 + ms(1000));
    let (at, stop) = r.the_stop();
    assert_eq!(stop.message, pitch_stop_up());
    assert_eq!(at - t0, LEASE, "the stop goes out when the lease runs out");
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::LeaseExpired);
    assert!(r.ctl.running().is_none());
}

#[test]
fn renewals_every_100_ms_keep_it_running_and_letting_go_stops_it_at_once() {
    let mut r = Rig::new(StreamerConfig::default());
    let t0 = r.now;
    for i in 0..20 {
        r.run_to(t0 + ms(100 * i));
        assert_eq!(r.lease(Direction::Up), Ok(()), "renewal {i}");
    }
    r.run_to(t0 + ms(2050));
    assert!(r.ctl.running().is_some(), "still held: still running");
    assert!(r.moves().iter().all(|(_, p)| is_on(p)));
    let released = r.now;
    r.let_go();
    let (at, stop) = r.the_stop();
    assert_eq!(at, released, "the stop is decided with the request");
    assert_eq!(stop.message, pitch_stop_up());
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::RemoteStop);
    // Let go and pressed again: a new run.
    r.run_to(released + ms(200));
    assert_eq!(r.lease(Direction::Up), Ok(()));
    assert!(r.ctl.running().is_some());
}

#[test]
fn a_run_cut_short_is_not_restarted_by_its_renewals() {
    let config = StreamerConfig {
        max_run: ms(1000),
        ..StreamerConfig::default()
    };
    let mut r = Rig::new(config);
    let t0 = r.now;
    for i in 0..15 {
        r.run_to(t0 + ms(100 * i));
        let got = r.lease(Direction::Up);
        if i < 10 {
            assert_eq!(got, Ok(()), "renewal {i}");
        } else {
            let why = got.expect_err("renewed after the run cap");
            assert!(
                why.contains("maximum run time")
                    && why.contains("let go of the button and press it again"),
                "{why}"
            );
        }
    }
    let (at, _) = r.the_stop();
    assert_eq!(at - t0, ms(1000));
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::MaxRunTime);
    // The finger lifts: the next press runs again.
    r.let_go();
    assert_eq!(r.lease(Direction::Up), Ok(()));
}

#[test]
fn communication_lost_ends_a_leased_run() {
    let mut r = Rig::new(StreamerConfig::default());
    let t0 = r.now;
    r.unit = Unit::StatusSilent;
    for i in 0..40 {
        r.run_to(t0 + ms(100 * i));
        let _ = r.lease(Direction::Up);
    }
    let (at, _) = r.the_stop();
    assert_eq!(r.ctl.last_stop().unwrap().reason, StopReason::CommLost);
    assert!(at - t0 > ms(2500) && at - t0 <= ms(2700), "{:?}", at - t0);
    assert!(r.ctl.running().is_none());
}

#[test]
fn a_motor_fault_ends_a_leased_run_and_refuses_the_next() {
    let mut r = Rig::new(StreamerConfig::default());
    let t0 = r.now;
    assert_eq!(r.lease(Direction::Up), Ok(()));
    r.run_to(t0 + ms(100));
    r.unit = Unit::PitchFault;
    r.run_to(t0 + ms(250));
    assert!(matches!(
        r.ctl.last_stop().unwrap().reason,
        StopReason::MotorFault(_)
    ));
    r.the_stop();
    r.let_go();
    let why = r.lease(Direction::Up).expect_err("started on a fault");
    assert!(why.contains("fault"), "{why}");
}

#[test]
fn another_direction_stops_the_run_before_its_own_starts() {
    let mut r = Rig::new(StreamerConfig::default());
    assert_eq!(r.lease(Direction::Up), Ok(()));
    r.run_to(r.now + ms(100));
    assert_eq!(r.lease(Direction::Down), Ok(()));
    let moves = r.moves();
    let n = moves.len();
    assert_eq!(moves[n - 2].1.message, pitch_stop_up());
    assert!(is_on(&moves[n - 1].1));
    assert_eq!(r.ctl.remote_running(), Some((PITCH, Direction::Down)));
}

#[test]
fn a_lease_is_refused_in_controls_words_while_communication_is_lost() {
    let mut r = Rig::new(StreamerConfig::default());
    r.unit = Unit::StatusSilent;
    r.run_to(r.now + ms(3000));
    let why = r
        .lease(Direction::Up)
        .expect_err("started without the unit");
    assert!(why.contains("COMMUNICATION LOST"), "{why}");
    assert!(r.moves().is_empty());
}

#[test]
fn near_the_endpoint_behind_it_a_leased_run_goes_as_probes() {
    let mut r = Rig::new(StreamerConfig::default());
    // Three counts from the up endpoint (0), driven down: a motor wired the wrong
    // way would pass that endpoint, so the run probes until the position moves.
    r.pitch_position = 3;
    r.feed();
    let t0 = r.now;
    for i in 0..10 {
        r.run_to(t0 + ms(100 * i));
        assert_eq!(r.lease(Direction::Down), Ok(()), "renewal {i}");
    }
    r.run_to(t0 + ms(1000));
    let moves = r.moves();
    let first_stop = moves
        .iter()
        .find(|(_, p)| !is_on(p))
        .expect("a probe's stop while the button is held");
    assert!(
        first_stop.0 - t0 < ms(200),
        "the probe ran {:?}",
        first_stop.0 - t0
    );
    assert!(r.ctl.remote_running().is_some(), "the run goes on, paused");
    // Each probe ends with its stop while the button is still held.
    let stops = moves.iter().filter(|(_, p)| !is_on(p)).count();
    assert!(stops >= 2, "streamed as if its way were known: {moves:?}");
}

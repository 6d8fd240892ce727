//! A network run (XFSp FLAPREQ with `--xfsp-control`) is a run of the one controller
//! (`control::How::Target`): it ends, with its stop on the wire, on every cause that
//! applies to it, and each is said in the event log. On a fake clock, against a
//! plant that moves the flaps as the move messages on the wire say (one count every
//! 40 ms, up endpoint 40, down 200), reported at 10 Hz.

mod common;

use common::live_unit::{device_status, system_status};
use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use vpx_efis::control::run_state::ReleaseMode;
use vpx_efis::control::{
    Controller, Direction, KeyContext, MAX_WIRE_INTERVAL, Selected, StopReason, StreamerConfig,
};
use vpx_efis::model::{CircuitKind, CircuitState, Model, Motor, Source};
use vpx_efis::protocol::device::FLAPS;
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::protocol::message::{FlapDirection, FlapFlags, FlapTrimStatus, Message, Packet};
use vpx_efis::xfsp::gateway::{Control, Gateway, GatewayConfig};
use vpx_efis::xfsp::{Confidence, Expire, Parameter, Sender, Value, idents};

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// The page's loop on a fake clock, 10 ms a pass: the plant, the model, the one
/// controller and the gateway, and every packet that went on the wire.
struct Rig {
    m: Model,
    ctl: Controller,
    gw: Gateway,
    peer: Sender,
    t0: Instant,
    now: Instant,
    pos: u8,
    /// The plant's motor: `Some(down)` while a move message holds it on.
    moving: Option<bool>,
    /// Leads swapped: it moves up when told down.
    reversed: bool,
    /// A travel of one count takes this long.
    per_count: Duration,
    moved_at: Instant,
    fault: FaultCode,
    /// No SYSTEM_STATUS or DEVICE_STATUS (FLAP_TRIM_STATUS still comes).
    status_lost: bool,
    /// Nothing at all from the unit.
    silent: bool,
    wire: Vec<(Instant, bool, FlapDirection)>,
}

fn rig(pos: u8, config: StreamerConfig) -> Rig {
    let t0 = Instant::now();
    let mut r = Rig {
        m: Model::new(Source::Simulated {
            scenario: "xfsp run ends".into(),
        }),
        ctl: Controller::new(config),
        gw: Gateway::new(
            GatewayConfig {
                control: Control::Any,
                ..GatewayConfig::default()
            },
            t0,
        ),
        peer: Sender::new(0x0042, 1),
        t0,
        now: t0,
        pos,
        moving: None,
        reversed: false,
        per_count: ms(40),
        moved_at: t0,
        fault: FaultCode::NoFault,
        status_lost: false,
        silent: false,
        wire: Vec::new(),
    };
    r.report();
    r
}

impl Rig {
    fn report(&mut self) {
        if self.silent {
            return;
        }
        let at = self.now;
        if !self.status_lost {
            self.m.apply_packet(at, &system_status());
            self.m.apply_packet(at, &device_status());
        }
        let ft = FlapTrimStatus {
            flap: FlapFlags {
                enabled: true,
                ..Default::default()
            },
            flap_position: self.pos,
            flap_fault: self.fault,
            flap_up: 40,
            flap_down: 200,
            ..Default::default()
        };
        self.m.apply_packet(at, &Packet::from_vpx(3, ft));
    }

    fn wire(&mut self, packets: Vec<Packet>) {
        for p in packets {
            if let Message::FlapMove(f) = p.message {
                self.wire.push((self.now, f.on, f.direction));
                self.moving = f.on.then_some(f.direction == FlapDirection::Down);
            }
        }
    }

    /// A FLAPREQ to `target` on the draft's scale, valid for `expire`.
    fn request(&mut self, target: i32, expire: Option<Duration>) {
        let mut p =
            Parameter::new(idents::FLAPREQ, Value::Sint(target)).confidence(Confidence::UserSel);
        if let Some(e) = expire {
            p = p.expire(Expire::at_least(e));
        }
        let d = self.peer.pack(
            vpx_efis::xfsp::MsgKind::flight_data(vpx_efis::xfsp::CertLevel::Experimental),
            &[p],
        );
        for d in d.expect("a request") {
            let out = self.gw.receive(&d, &mut self.m, &mut self.ctl, self.now);
            self.wire(out);
        }
    }

    /// One 10 ms pass: the plant moves, reports every 100 ms, and the loop ticks
    /// the controller (as the App does) and the gateway.
    fn pass(&mut self) {
        self.now += ms(10);
        match self.moving {
            Some(down) if self.now - self.moved_at >= self.per_count => {
                self.moved_at = self.now;
                let up = down == self.reversed;
                self.pos = if up {
                    self.pos.saturating_sub(1)
                } else {
                    self.pos.saturating_add(1)
                };
            }
            Some(_) => {}
            None => self.moved_at = self.now,
        }
        if (self.now - self.t0).as_millis().is_multiple_of(100) {
            self.report();
        }
        let out = self.ctl.tick(&self.m, self.now);
        self.wire(out);
        let out = self.gw.tick(&mut self.m, &mut self.ctl, self.now).to_unit;
        self.wire(out);
    }

    /// Runs for up to `secs`, the peer repeating `target` every 250 ms while
    /// `repeat` says so, until the flaps stop on the wire; returns why, when.
    fn run(
        &mut self,
        target: i32,
        secs: u64,
        mut repeat: impl FnMut(&mut Rig) -> bool,
    ) -> (StopReason, Instant) {
        self.request(target, Some(ms(600)));
        assert_eq!(
            self.wire.first().map(|w| (w.1, w.2)),
            Some((true, FlapDirection::Down)),
            "started: {:#?}",
            self.m.events
        );
        let end = self.now + Duration::from_secs(secs);
        while self.now < end {
            self.pass();
            if self.wire.last().is_some_and(|w| !w.1) {
                let s = *self.ctl.last_stop().expect("a stop");
                assert_eq!(s.motor, Motor::Flaps);
                return (s.reason, self.now);
            }
            if (self.now - self.t0).as_millis().is_multiple_of(250) && repeat(self) {
                self.request(target, Some(ms(600)));
            }
        }
        panic!("not stopped: {:#?}", self.m.events);
    }

    /// As [`Rig::run`] to [`FAR`], repeated, with `act` on every pass from `after`.
    fn run_acting(
        &mut self,
        after: Duration,
        mut act: impl FnMut(&mut Rig),
    ) -> (StopReason, Instant) {
        self.run(FAR, 5, |r| {
            if r.now - r.t0 >= after {
                act(r);
            }
            true
        })
    }

    /// After the stop: for a second, with the requests for the same target still
    /// coming (`Some`) or not, nothing moves the flaps again; the stream had no gap
    /// over 250 ms; the event log says why.
    fn settled(&mut self, target: Option<i32>, words: &str) {
        let stops = self.wire.iter().filter(|w| !w.1).count();
        assert_eq!(stops, 1, "{:?}", self.wire);
        for i in 0..100 {
            if let Some(target) = target.filter(|_| i % 25 == 0) {
                self.request(target, Some(ms(600)));
            }
            self.pass();
        }
        let stop = self.wire.iter().position(|w| !w.1).unwrap();
        assert!(
            self.wire[stop..].iter().all(|w| !w.1),
            "moved again after its stop: {:?}",
            self.wire
        );
        assert_eq!(self.moving, None);
        let ons: Vec<Instant> = self.wire.iter().filter(|w| w.1).map(|w| w.0).collect();
        for w in ons.windows(2) {
            assert!(
                w[1] - w[0] <= MAX_WIRE_INTERVAL,
                "gap {:?}: {:?} {:#?}",
                w[1] - w[0],
                self.wire,
                self.m.events
            );
        }
        let said = format!("XFSp: flaps stopped: {words}");
        assert!(
            self.m.events.iter().any(|e| e.text == said),
            "{said}: {:#?}",
            self.m.events
        );
    }
}

const FAR: i32 = 100_000;

#[test]
fn a_network_run_ends_at_its_target() {
    let mut r = rig(80, StreamerConfig::default());
    // 50 % of 40..200 is raw 120.
    let (why, _) = r.run(50_000, 5, |_| true);
    assert_eq!(why, StopReason::TargetReached);
    assert!((118..=121).contains(&r.pos), "stopped at raw {}", r.pos);
    r.settled(Some(50_000), "target reached");
}

#[test]
fn a_network_run_ends_when_its_requests_stop() {
    let mut r = rig(60, StreamerConfig::default());
    let t0 = r.now;
    // One request, 600 ms of Expire, never repeated.
    let (why, at) = r.run(FAR, 3, |_| false);
    assert_eq!(why, StopReason::RequestsStopped);
    assert!(at - t0 >= ms(600) && at - t0 <= ms(610), "{:?}", at - t0);
    r.settled(None, "requests stopped or expired");
}

/// A request with no Expire is held 1.2 s (`xfsp::drive::REQUEST_HOLD`): a source
/// gone stale does not run a motor for longer.
#[test]
fn a_network_run_ends_when_its_source_goes_stale() {
    let mut r = rig(60, StreamerConfig::default());
    let t0 = r.now;
    r.request(FAR, None);
    let mut stopped = None;
    while r.now < t0 + ms(3000) && stopped.is_none() {
        r.pass();
        if r.wire.last().is_some_and(|w| !w.1) {
            stopped = Some(r.now);
        }
    }
    let at = stopped.expect("stopped");
    assert_eq!(
        r.ctl.last_stop().unwrap().reason,
        StopReason::RequestsStopped
    );
    assert!(at - t0 >= ms(1200) && at - t0 <= ms(1210), "{:?}", at - t0);
}

#[test]
fn a_network_run_ends_on_lost_communication() {
    let mut r = rig(60, StreamerConfig::default());
    r.status_lost = true;
    let t0 = r.now;
    let (why, at) = r.run(FAR, 5, |_| true);
    assert_eq!(why, StopReason::CommLost);
    // 2.5 s after the last SYSTEM_STATUS/DEVICE_STATUS (model::COMM_LOST_AFTER).
    assert!(at - t0 > ms(2500) && at - t0 <= ms(2520), "{:?}", at - t0);
    r.settled(Some(FAR), "COMMUNICATION LOST");
}

/// Total silence: the position goes stale first (0.4 s), which ends the run before
/// lost communication would.
#[test]
fn a_network_run_ends_when_the_unit_goes_silent() {
    let mut r = rig(60, StreamerConfig::default());
    let (why, at) = r.run_acting(ms(500), |r| {
        r.silent = true;
    });
    assert_eq!(why, StopReason::PositionStale);
    // The last report at 500 ms.
    assert!(
        at - r.t0 > ms(900) && at - r.t0 <= ms(1000),
        "{:?}",
        at - r.t0
    );
}

#[test]
fn a_network_run_ends_on_a_motor_fault() {
    let mut r = rig(60, StreamerConfig::default());
    let (why, _) = r.run_acting(ms(700), |r| {
        r.fault = FaultCode::FlapRunaway;
    });
    assert_eq!(why, StopReason::MotorFault(FaultCode::FlapRunaway));
    r.settled(Some(FAR), &why.describe());
}

/// Faster than the reports can follow (a count every 10 ms), toward its target at
/// the down endpoint: the endpoint watch stops it before it passes 200.
#[test]
fn a_network_run_ends_at_its_endpoint() {
    let mut r = rig(120, StreamerConfig::default());
    r.per_count = ms(10);
    let (why, _) = r.run(FAR, 5, |_| true);
    assert!(matches!(why, StopReason::AtEndpoint(200)), "{why:?}");
    r.settled(Some(FAR), &why.describe());
    assert!(r.pos <= 200, "passed the endpoint to {}", r.pos);
}

/// Leads swapped: asked down, it goes up; stopped as moving against its command,
/// and recorded, so every origin refuses the flaps afterwards.
#[test]
fn a_network_run_ends_when_it_moves_the_wrong_way() {
    let mut r = rig(120, StreamerConfig::default());
    r.reversed = true;
    let (why, _) = r.run(FAR, 5, |_| true);
    assert_eq!(why, StopReason::MovedAgainst(Direction::Down));
    assert!(r.pos >= 115, "went up to {}", r.pos);
    assert_eq!(r.ctl.against().seen(Motor::Flaps), Some(Direction::Down));
    r.settled(Some(FAR), &why.describe());
    // A new target is refused, in the network's words.
    r.request(FAR - 1, Some(ms(600)));
    r.pass();
    assert!(r.wire.last().is_some_and(|w| !w.1));
    assert!(
        r.m.events
            .iter()
            .any(|e| e.text.contains("not run on a network request")),
        "{:#?}",
        r.m.events
    );
}

#[test]
fn a_network_run_ends_at_the_run_cap() {
    let config = StreamerConfig {
        max_run: ms(1500),
        ..StreamerConfig::default()
    };
    let mut r = rig(60, config);
    let t0 = r.now;
    let (why, at) = r.run(FAR, 5, |_| true);
    assert_eq!(why, StopReason::MaxRunTime);
    assert!(at - t0 >= ms(1500) && at - t0 <= ms(1510), "{:?}", at - t0);
    r.settled(Some(FAR), "maximum run time reached");
}

/// A person at the keys comes first: any key ends a network run, even the very key
/// of its motor and direction (`d` on the flaps), which then takes nothing over: its
/// auto-repeats, which come as presses in a terminal without release reports, do not
/// start a run of their own.
#[test]
fn a_network_run_ends_on_a_key_at_the_page() {
    let config = StreamerConfig {
        release_mode: ReleaseMode::AutoRepeat,
        ..StreamerConfig::default()
    };
    let mut r = rig(60, config);
    let ctx = KeyContext {
        selected: Some(Selected {
            id: FLAPS,
            kind: CircuitKind::Flaps,
            state: CircuitState::On,
        }),
        overlay_open: false,
        past_endpoints: false,
    };
    let d = KeyEvent::new(KeyCode::Char('d'), KeyModifiers::NONE);
    let (why, _) = r.run_acting(ms(1000), |r| {
        let o = r.ctl.handle_key(d, &ctx, &r.m, r.now);
        r.wire(o.packets);
    });
    assert_eq!(why, StopReason::OtherKey);
    // The key held on: its repeats every 30 ms start nothing.
    for _ in 0..10 {
        for _ in 0..3 {
            r.pass();
        }
        let o = r.ctl.handle_key(d, &ctx, &r.m, r.now);
        r.wire(o.packets);
    }
    r.settled(Some(FAR), "another key was pressed");
}

#[test]
fn a_network_run_ends_on_a_link_error() {
    let mut r = rig(60, StreamerConfig::default());
    let (why, _) = r.run_acting(ms(1000), |r| {
        let p = r.ctl.stop(r.now, StopReason::LinkError);
        r.wire(p);
    });
    assert_eq!(why, StopReason::LinkError);
    r.settled(Some(FAR), "the link could not send");
}

/// The walk-around remote comes before the network too: its hold-to-run ends a
/// network run and goes on; the network's requests neither renew nor take it over,
/// and wait until it ends.
#[test]
fn the_remote_comes_before_a_network_run() {
    let mut r = rig(60, StreamerConfig::default());
    r.request(FAR, Some(ms(600)));
    for _ in 0..30 {
        r.pass();
    }
    assert_eq!(r.gw.running_motor(&r.ctl), Some(Motor::Flaps));
    let (p, got) = r.ctl.lease(&r.m, Motor::Flaps, Direction::Up, r.now);
    r.wire(p);
    assert!(got.is_ok(), "{got:?}");
    assert_eq!(
        r.ctl.last_stop().map(|s| (s.direction, s.reason)),
        Some((Direction::Down, StopReason::OtherKey))
    );
    assert_eq!(r.ctl.remote_running(), Some((Motor::Flaps, Direction::Up)));
    assert_eq!(r.gw.running_motor(&r.ctl), None);
    // The network keeps asking; the remote keeps renewing for 0.5 s.
    for i in 0..50 {
        if i % 10 == 0 {
            let (p, got) = r.ctl.lease(&r.m, Motor::Flaps, Direction::Up, r.now);
            r.wire(p);
            assert!(got.is_ok(), "{got:?}");
        }
        if i % 25 == 0 {
            r.request(FAR - 1, Some(ms(600)));
        }
        r.pass();
        assert_eq!(r.ctl.remote_running(), Some((Motor::Flaps, Direction::Up)));
    }
    let downs = r
        .wire
        .iter()
        .filter(|w| w.1 && w.2 == FlapDirection::Down)
        .count();
    let first_up = r
        .wire
        .iter()
        .position(|w| w.2 == FlapDirection::Up)
        .unwrap();
    assert!(
        r.wire[first_up..].iter().all(|w| w.2 == FlapDirection::Up),
        "the network moved the flaps during the remote's run: {:?}",
        r.wire
    );
    assert!(downs > 0);
    // The remote lets go: the network's waiting request starts.
    let p = r.ctl.lease_stop(r.now, StopReason::RemoteStop);
    r.wire(p);
    r.pass();
    assert_eq!(r.gw.running_motor(&r.ctl), Some(Motor::Flaps));
    assert_eq!(
        r.wire.last().map(|w| (w.1, w.2)),
        Some((true, FlapDirection::Down))
    );
}

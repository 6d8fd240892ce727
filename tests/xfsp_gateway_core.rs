//! The gateway's pure core on a fake clock: a model fed hand-made VP-X packets, datagrams
//! built with the codec's Sender, and what comes out decoded with the codec.

use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use proptest::prelude::*;
use vpx_efis::audit::Origin;
use vpx_efis::control::{Controller, Direction, How, KeyContext, StopReason};
use vpx_efis::model::{Model, Motor, Source, TrimKind};
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::protocol::message::{
    DeviceStatus, FaultStatus, Message, Packet, SignedTenths, SystemStatus, Tenths,
};
use vpx_efis::xfsp::gateway::{Control, Gateway, GatewayConfig, TickOutput};

#[path = "common/events.rs"]
#[allow(dead_code)]
mod events;
#[path = "common/live_unit.rs"]
#[allow(dead_code)]
mod live_unit;
#[path = "common/xfsp_request.rs"]
mod xfsp_request;
use vpx_efis::xfsp::publish::{CAS_UNIT_COMM_LOST, LIFETIME};
use vpx_efis::xfsp::{
    Body, Boolean, Bus, CasLevel, CertLevel, Confidence, EcbState, Expire, Message as XMessage,
    MsgKind, Parameter, Sender, Value, idents,
};
use xfsp_request::ecb_request;

const ME: u16 = 0x5650;
const PEER: u16 = 0x0042;

/// A gateway that takes commands from any source (`--xfsp-control`): what most of
/// these tests exercise. Without it commands are refused (see the tests near the end).
fn commanded() -> GatewayConfig {
    GatewayConfig {
        control: Control::Any,
        ..GatewayConfig::default()
    }
}

/// A model and a gateway taking commands, made at `t0`, and the one controller they
/// share with the page.
fn commanded_gateway() -> (Instant, Model, Gateway, Controller) {
    let t0 = Instant::now();
    (
        t0,
        model(),
        Gateway::new(commanded(), t0),
        Controller::default(),
    )
}

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn model() -> Model {
    Model::new(Source::Simulated {
        scenario: "test".into(),
    })
}

/// SYSTEM_STATUS + DEVICE_STATUS with `on` powered at 2.5 A each.
fn status(m: &mut Model, at: Instant, on: &[u8]) {
    let mut d = DeviceStatus::default();
    for &id in on {
        d.on[id as usize] = true;
        d.current[id as usize] = Tenths(25);
    }
    let s = SystemStatus {
        system_current: Tenths(123),
        main_bus_volts: SignedTenths(138),
        aux_battery_volts: Tenths(126),
        internal_temp: 30,
        ..Default::default()
    };
    m.apply_packet(at, &Packet::from_vpx(0, s));
    m.apply_packet(at, &Packet::from_vpx(1, d));
}

fn fault(m: &mut Model, at: Instant, id: u8, code: FaultCode) {
    let f = FaultStatus::with_faults(&[(id, code)]);
    m.apply_packet(at, &Packet::from_vpx(2, f));
}

/// Flaps enabled, up endpoint 40, down 200, at `flap`.
fn flaps(m: &mut Model, at: Instant, flap: u8) {
    flap_trim(m, at, flap, None);
}

/// As [`flaps`] at 40, and the pitch trim enabled at `pos`, its endpoints as the
/// `install` scenario's: up (nose-up) 30, down 220, neutral 125.
fn pitch(m: &mut Model, at: Instant, pos: u8) {
    flap_trim(m, at, 40, Some(pos));
}

fn flap_trim(m: &mut Model, at: Instant, flap: u8, pitch: Option<u8>) {
    let mut ft = live_unit::flaps_at(flap);
    if let Some(pitch) = pitch {
        ft.pitch_trim.enabled = true;
        ft.pitch_trim_position = pitch;
        ft.pitch_trim_up = 30;
        ft.pitch_trim_down = 220;
        ft.pitch_trim_neutral = 125;
    }
    m.apply_packet(at, &Packet::from_vpx(3, ft));
}

fn params(step: &TickOutput) -> Vec<Parameter> {
    step.datagrams
        .iter()
        .flat_map(|d| {
            let m = XMessage::parse(d).expect("our datagrams parse");
            assert_eq!(m.src_id, ME);
            match m.body {
                Body::Params(p) => p,
                Body::Raw(_) => panic!("we send parameters"),
            }
        })
        .collect()
}

fn find(ps: &[Parameter], ident: vpx_efis::xfsp::Ident, unit: u16) -> Option<&Parameter> {
    ps.iter().find(|p| p.ident == ident && p.unit == unit)
}

fn bus(p: &Parameter) -> &Bus {
    match &p.value {
        Value::Bus(b) => b,
        v => panic!("not a BUS: {v:?}"),
    }
}

/// The CASMSG unit we send: GatewayConfig::default()'s source id.
const OUR_CAS: u16 = 0x5650;

fn cas(ps: &[Parameter]) -> Vec<(u16, CasLevel, String)> {
    ps.iter()
        .filter(|p| p.ident == idents::CASMSG)
        .map(|p| match &p.value {
            Value::CasMsg(c) => (p.unit, c.level, vpx_efis::xfsp::format::latin1(&c.label)),
            v => panic!("{v:?}"),
        })
        .collect()
}

/// MSTRCAUTN as published in `ps`, if it was.
fn master(ps: &[Parameter]) -> Option<bool> {
    master_of(ps, idents::MSTRCAUTN)
}

fn master_of(ps: &[Parameter], ident: vpx_efis::xfsp::Ident) -> Option<bool> {
    find(ps, ident, 0).map(|p| p.value == Value::Bool(Boolean::True))
}

fn request(sender: &mut Sender, ps: Vec<Parameter>) -> Vec<u8> {
    sender
        .pack(MsgKind::flight_data(CertLevel::Experimental), &ps)
        .unwrap()
        .remove(0)
}

/// FLAPREQ to `target` as a person asks it, valid for `expire_ms`.
fn flap_request(target: i32, expire_ms: u64) -> Parameter {
    target_request(idents::FLAPREQ, target, Confidence::UserSel, expire_ms)
}

/// A motor's target request (FLAPREQ, PTRIMREQ, RTRIMREQ), valid for `expire_ms`.
fn target_request(
    ident: vpx_efis::xfsp::Ident,
    target: i32,
    conf: Confidence,
    expire_ms: u64,
) -> Parameter {
    Parameter::new(ident, Value::Sint(target))
        .confidence(conf)
        .expire(Expire::at_least(ms(expire_ms)))
}

/// The event log's latest line.
fn last_said(m: &Model) -> &str {
    &m.events.back().expect("an event").text
}

/// A datagram from `sender` asking for circuit `unit` in `state`.
fn ecb_datagram(sender: &mut Sender, unit: u16, state: EcbState, conf: Confidence) -> Vec<u8> {
    request(sender, vec![ecb_request(unit, state, conf)])
}

#[test]
fn circuits_and_buses_are_published_with_state_amps_breaker_and_label() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    let ps = params(&gw.tick(&mut m, &mut ctl, t0));
    let efis = find(&ps, idents::ECBSTAT, 2).expect("EFIS published");
    let b = bus(efis);
    assert_eq!(b.state, EcbState::On);
    assert_eq!(b.draw_amps, 25, "2.5 A in tenths");
    // Draft Table 18: "Label for BUS Message (System/Item)".
    assert_eq!(b.label, b"VP-X/EFIS");
    assert_eq!(efis.expire, Expire::at_least(LIFETIME));
    assert!(efis.expire.millis().unwrap() >= 2500);
    assert_eq!(
        bus(find(&ps, idents::ECBSTAT, 5).unwrap()).state,
        EcbState::Off
    );
    let main = bus(find(&ps, idents::BUSSTAT, 0).unwrap());
    assert_eq!((main.out_volts, main.draw_amps), (138, 123));
    assert_eq!(main.label, b"VP-X/MAIN BUS");
    let aux = bus(find(&ps, idents::BUSSTAT, 1).unwrap());
    assert_eq!((aux.state, aux.out_volts), (EcbState::On, 126));
    assert_eq!(aux.label, b"VP-X/AUX BATTERY");
    assert_eq!(master(&ps), Some(false));
    assert_eq!(master_of(&ps, idents::MSTRWARN), Some(false));
    assert!(cas(&ps).is_empty());
}

#[test]
fn every_item_is_refreshed_at_least_once_a_second_and_not_resent_unchanged_sooner() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    let mut seen: Vec<(Instant, Parameter)> = Vec::new();
    let mut now = t0;
    while now < t0 + ms(3000) {
        // The unit broadcasts at 1 Hz; the gateway is ticked when it asks to be.
        status(&mut m, now - ms((now - t0).as_millis() as u64 % 1000), &[2]);
        seen.extend(
            params(&gw.tick(&mut m, &mut ctl, now))
                .into_iter()
                .map(|p| (now, p)),
        );
        let next = gw.next_deadline();
        assert!(
            next > now && next <= now + ms(100),
            "deadline in (now, now+100ms]"
        );
        now = next;
    }
    let efis: Vec<Instant> = seen
        .iter()
        .filter(|(_, p)| p.ident == idents::ECBSTAT && p.unit == 2)
        .map(|(t, _)| *t)
        .collect();
    assert!(efis.len() >= 3, "{efis:?}");
    for w in efis.windows(2) {
        let gap = w[1] - w[0];
        assert!(gap <= ms(1000), "refresh gap {gap:?}");
        assert!(gap >= ms(100), "unchanged item re-sent after {gap:?}");
    }
}

#[test]
fn a_short_circuit_raises_cas_and_master_warning_then_clear_three_times() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    gw.tick(&mut m, &mut ctl, t0);
    // Later than the 100 ms minimum interval, so ECBSTAT goes out with the CAS.
    fault(&mut m, t0 + ms(200), 5, FaultCode::ShortCircuit);
    let ps = params(&gw.tick(&mut m, &mut ctl, t0 + ms(200)));
    // Unit: "CAS System ID" (draft CASMSG), ours = our source id; the label tells
    // alerts apart.
    assert_eq!(
        cas(&ps),
        [(
            OUR_CAS,
            CasLevel::Warning,
            "5A-2: SHORT CIRCUIT".to_string()
        )]
    );
    assert_eq!(
        bus(find(&ps, idents::ECBSTAT, 5).unwrap()).state,
        EcbState::Shorted
    );
    assert_eq!(master_of(&ps, idents::MSTRWARN), Some(true));
    assert_eq!(master(&ps), None, "a warning leaves Master Caution FALSE");
    assert_eq!(gw.standing_cas().len(), 1);
    // Status keeps coming without FAULT_STATUS: after 2.5 s the fault has cleared.
    let mut clears = Vec::new();
    let mut now = t0 + ms(200);
    let mut master_seen = Vec::new();
    while now < t0 + ms(7000) {
        now = gw.next_deadline();
        status(&mut m, now, &[]);
        let ps = params(&gw.tick(&mut m, &mut ctl, now));
        master_seen.extend(master_of(&ps, idents::MSTRWARN));
        for (u, level, label) in cas(&ps) {
            if level == CasLevel::Clear {
                clears.push((now, u, label));
            }
        }
    }
    assert_eq!(clears.len(), 3, "{clears:?}");
    assert!(
        clears
            .iter()
            .all(|(_, u, l)| *u == OUR_CAS && l == "5A-2: SHORT CIRCUIT")
    );
    assert!(clears[1].0 - clears[0].0 >= ms(1000));
    assert_eq!(master_seen.last(), Some(&false));
    assert!(gw.standing_cas().is_empty());
}

#[test]
fn every_appendix_e_code_maps_to_a_fault_state_and_a_level() {
    use vpx_efis::xfsp::publish::{cas_level, fault_ecb_state};
    for b in 1..=0x20u8 {
        let code = FaultCode::from_byte(b);
        let s = fault_ecb_state(code);
        assert!(u8::from(s) >= 128, "{code:?} -> {s:?} is not a fault state");
        assert!(matches!(
            cas_level(code),
            CasLevel::Caution | CasLevel::Warning
        ));
    }
    assert_eq!(fault_ecb_state(FaultCode::OverCurrent), EcbState::OverCur);
    assert_eq!(fault_ecb_state(FaultCode::OverVoltage), EcbState::OverVol);
    assert_eq!(fault_ecb_state(FaultCode::TrimRunaway), EcbState::Runaway);
    assert_eq!(fault_ecb_state(FaultCode::FlapDisabled), EcbState::Disabled);
}

#[test]
fn lost_communication_publishes_unknown_and_says_so_once_past_the_start_grace() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    flaps(&mut m, t0, 120);
    let ps = params(&gw.tick(&mut m, &mut ctl, t0));
    assert_eq!(
        find(&ps, idents::FLAPPOS, 0).map(|p| p.value.clone()),
        Some(Value::Sint(50_000))
    );
    let later = t0 + ms(2600);
    let ps = params(&gw.tick(&mut m, &mut ctl, later));
    let efis = find(&ps, idents::ECBSTAT, 2).expect("republished on change");
    assert_eq!(bus(efis).state, EcbState::Unknown0);
    assert_eq!(bus(efis).draw_amps, 0, "no stale amps");
    assert_eq!(efis.confidence, Confidence::Useless);
    assert_eq!(
        bus(find(&ps, idents::BUSSTAT, 0).unwrap()).state,
        EcbState::Unknown0
    );
    assert!(find(&ps, idents::FLAPPOS, 0).is_none(), "no stale position");
    assert_eq!(
        cas(&ps),
        [(OUR_CAS, CasLevel::Caution, "VP-X COMM LOST".into())]
    );
    assert_eq!(master(&ps), Some(true));
    assert_eq!(gw.standing_cas()[0].0, CAS_UNIT_COMM_LOST, "our key inside");
    // Heard again: the message is withdrawn.
    status(&mut m, later + ms(500), &[2]);
    let ps = params(&gw.tick(&mut m, &mut ctl, later + ms(500)));
    assert_eq!(cas(&ps)[0].1, CasLevel::Clear);
    assert_eq!(
        bus(find(&ps, idents::ECBSTAT, 2).unwrap()).state,
        EcbState::On
    );
}

#[test]
fn a_gateway_that_never_heard_the_unit_waits_before_crying_comm_lost() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    assert!(cas(&params(&gw.tick(&mut m, &mut ctl, t0 + ms(1000)))).is_empty());
    let ps = params(&gw.tick(&mut m, &mut ctl, t0 + ms(2600)));
    assert_eq!(cas(&ps).len(), 1);
}

#[test]
fn forwarded_air_data_is_valid_only_while_fresh() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    assert!(
        gw.tick(&mut m, &mut ctl, t0).to_unit.is_empty(),
        "no air data heard, none sent"
    );
    let mut peer = Sender::new(PEER, 1);
    let d = request(
        &mut peer,
        vec![
            Parameter::new(idents::IAS, Value::Sint(88)).expire(Expire::at_least(ms(1500))),
            Parameter::new(idents::ENGRPM, Value::Uint(2400)),
        ],
    );
    assert!(gw.receive(&d, &mut m, &mut ctl, t0 + ms(100)).is_empty());
    let ext = |s: &TickOutput| {
        s.to_unit.iter().find_map(|p| match p.message {
            Message::ExternalData(e) => Some(e),
            _ => None,
        })
    };
    let e = ext(&gw.tick(&mut m, &mut ctl, t0 + ms(100))).expect("sent at once");
    assert_eq!((e.indicated_airspeed, e.rpm), (88, 2400));
    assert!(e.valid.indicated_airspeed && e.valid.rpm && !e.valid.baro_altitude);
    assert!(
        ext(&gw.tick(&mut m, &mut ctl, t0 + ms(600))).is_none(),
        "1 Hz, not faster"
    );
    let e = ext(&gw.tick(&mut m, &mut ctl, t0 + ms(2100))).unwrap();
    assert!(!e.valid.indicated_airspeed, "past its 1.5 s expire");
    assert!(e.valid.rpm, "2.0 s old is still fresh");
    let e = ext(&gw.tick(&mut m, &mut ctl, t0 + ms(3100))).unwrap();
    assert!(!e.valid.rpm, "never-expiring data is still at most 2 s old");
    let f = gw.forwarding(t0 + ms(3100));
    assert_eq!(f[0].last.map(|s| s.value), Some(88));
    assert!(f.iter().all(|f| !f.fresh));
}

#[test]
fn circuit_requests_follow_the_key_rules_and_only_usersel_or_syssel_count() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    let mut peer = Sender::new(PEER, 100);
    let on5 = ecb_datagram(&mut peer, 5, EcbState::On, Confidence::UserSel);
    let out = gw.receive(&on5, &mut m, &mut ctl, t0);
    assert!(matches!(
        out.as_slice(),
        [Packet {
            message: Message::DevicePower(p),
            ..
        }] if p.device_id == 5 && p.on
    ));
    assert!(last_said(&m).contains("5A-2 ON -> DEVICE_POWER"));
    // The same bytes again, and an older message: both ignored by number.
    assert!(gw.receive(&on5, &mut m, &mut ctl, t0 + ms(1500)).is_empty());
    let mut old = Sender::new(PEER, 50);
    let off2 = ecb_datagram(&mut old, 2, EcbState::Off, Confidence::SysSel);
    assert!(
        gw.receive(&off2, &mut m, &mut ctl, t0 + ms(1600))
            .is_empty()
    );
    assert_eq!(gw.stats().rx.duplicate, 1);
    assert_eq!(gw.stats().rx.out_of_order, 1);
    // Status-only confidence is another node's report, not a request.
    let high = ecb_datagram(&mut peer, 2, EcbState::Off, Confidence::High);
    assert!(
        gw.receive(&high, &mut m, &mut ctl, t0 + ms(1700))
            .is_empty()
    );
    // The starter cannot be switched; reset only when faulted; both logged.
    let starter = ecb_datagram(&mut peer, 1, EcbState::On, Confidence::UserSel);
    assert!(
        gw.receive(&starter, &mut m, &mut ctl, t0 + ms(1800))
            .is_empty()
    );
    assert!(last_said(&m).contains("refused: the starter"));
    let reset = ecb_datagram(&mut peer, 2, EcbState::Reset, Confidence::UserSel);
    assert!(
        gw.receive(&reset, &mut m, &mut ctl, t0 + ms(1900))
            .is_empty()
    );
    assert!(last_said(&m).contains("no fault to reset"));
    fault(&mut m, t0 + ms(1950), 2, FaultCode::OverCurrent);
    let reset = ecb_datagram(&mut peer, 2, EcbState::Reset, Confidence::UserSel);
    let out = gw.receive(&reset, &mut m, &mut ctl, t0 + ms(2000));
    assert!(
        matches!(out.as_slice(), [Packet { message: Message::DeviceClear(c), .. }] if c.device_id == 2)
    );
    // Our own messages, heard back through the multicast loop, are ignored.
    let mut me = Sender::new(ME, 0);
    let own = ecb_datagram(&mut me, 2, EcbState::Off, Confidence::UserSel);
    assert!(gw.receive(&own, &mut m, &mut ctl, t0 + ms(2100)).is_empty());
    assert_eq!(gw.stats().own, 1);
    // A unit and a label that name different circuits: refused, in words, counted.
    let refused = gw.stats().commands_refused;
    let mut other = ecb_request(2, EcbState::Off, Confidence::UserSel);
    if let Value::Bus(b) = &mut other.value {
        b.label = b"LANDING LT".to_vec();
    }
    assert!(
        gw.receive(
            &request(&mut peer, vec![other]),
            &mut m,
            &mut ctl,
            t0 + ms(2200)
        )
        .is_empty()
    );
    assert!(last_said(&m).contains("unit 2 is \"EFIS\", not \"LANDING LT\""));
    assert_eq!(gw.stats().commands_refused, refused + 1);
}

/// control's reason reaches the gateway as a type: a refusal no retry can change (the
/// starter is never switched) is answered once a repeat window, as a request naming no
/// circuit is; one a retry may pass (a reset before any fault) is answered each time.
#[test]
fn a_refusal_no_retry_can_change_is_answered_once_a_window() {
    let t0 = Instant::now();
    let mut m = model();
    status(&mut m, t0, &[2]);
    let mut gw = Gateway::new(commanded(), t0);
    let mut ctl = Controller::default();
    let mut peer = Sender::new(PEER, 100);
    let mut refusals_after = |gw: &mut Gateway, m: &mut Model, id: u16, state, at| {
        let bytes = ecb_datagram(&mut peer, id, state, Confidence::UserSel);
        assert!(gw.receive(&bytes, m, &mut ctl, at).is_empty());
        gw.stats().commands_refused
    };
    assert_eq!(refusals_after(&mut gw, &mut m, 1, EcbState::On, t0), 1);
    assert_eq!(
        refusals_after(&mut gw, &mut m, 1, EcbState::On, t0 + ms(300)),
        1,
        "the starter's refusal again within the window"
    );
    assert_eq!(
        refusals_after(&mut gw, &mut m, 1, EcbState::On, t0 + ms(1100)),
        2
    );
    assert_eq!(
        refusals_after(&mut gw, &mut m, 2, EcbState::Reset, t0 + ms(1200)),
        3
    );
    assert_eq!(
        refusals_after(&mut gw, &mut m, 2, EcbState::Reset, t0 + ms(1300)),
        4
    );
    let said = m
        .events
        .iter()
        .filter(|e| e.text.contains("refused"))
        .count();
    assert_eq!(said, 4, "each refusal counted is logged");
}

fn flap_moves(ps: &[Packet]) -> Vec<(bool, vpx_efis::protocol::message::FlapDirection)> {
    ps.iter()
        .filter_map(|p| match p.message {
            Message::FlapMove(f) => Some((f.on, f.direction)),
            _ => None,
        })
        .collect()
}

/// A gateway taking commands, its unit heard, the flaps at raw 60 and a peer to ask
/// it. 20 counts off the up endpoint: a run within endpoints::NEAR of the endpoint
/// behind it starts as probes, which these positions (moved by the test, not by the
/// stream) would not answer.
fn flaps_off_the_up_endpoint() -> (Instant, Model, Gateway, Controller, Sender) {
    let (t0, mut m, gw, ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    flaps(&mut m, t0, 60);
    (t0, m, gw, ctl, Sender::new(PEER, 1))
}

#[test]
fn a_flap_request_streams_toward_the_target_and_stops_there() {
    use vpx_efis::protocol::message::FlapDirection::{Down, Up};
    let (t0, mut m, mut gw, mut ctl, mut peer) = flaps_off_the_up_endpoint();
    let req = |peer: &mut Sender, target| request(peer, vec![flap_request(target, 600)]);
    // 50 % of 40..200 is raw 120.
    let out = gw.receive(&req(&mut peer, 50_000), &mut m, &mut ctl, t0);
    assert_eq!(flap_moves(&out), [(true, Down)]);
    let mut now = t0;
    let mut sends = vec![t0];
    let mut pos = 60u8;
    let mut stopped = None;
    while now < t0 + ms(5000) && stopped.is_none() {
        now = gw.next_deadline();
        pos = pos.saturating_add(4);
        status(&mut m, now, &[]);
        flaps(&mut m, now, pos);
        let mut out = Vec::new();
        if (now - t0).as_millis() % 400 < 100 {
            out.extend(gw.receive(&req(&mut peer, 50_000), &mut m, &mut ctl, now));
        }
        out.extend(gw.tick(&mut m, &mut ctl, now).to_unit);
        for (on, dir) in flap_moves(&out) {
            assert_eq!(dir, Down);
            if on {
                sends.push(now);
            } else {
                stopped = Some((now, pos));
            }
        }
    }
    let (_, at) = stopped.unwrap_or_else(|| panic!("not stopped: {:#?}", m.events));
    assert!((118..=121).contains(&at), "stopped at raw {at}");
    for w in sends.windows(2) {
        assert!(w[1] - w[0] <= ms(250), "stream gap {:?}", w[1] - w[0]);
    }
    // Requests for the same target keep coming: it is not restarted.
    let out = gw.receive(&req(&mut peer, 50_000), &mut m, &mut ctl, now + ms(50));
    assert!(flap_moves(&out).is_empty());
    // A new target goes the other way.
    let out = gw.receive(&req(&mut peer, 0), &mut m, &mut ctl, now + ms(60));
    assert_eq!(flap_moves(&out), [(true, Up)]);
}

#[test]
fn a_flap_request_that_is_not_repeated_stops_at_its_expiry() {
    use vpx_efis::protocol::message::FlapDirection::Down;
    let (t0, mut m, mut gw, mut ctl, mut peer) = flaps_off_the_up_endpoint();
    let d = request(
        &mut peer,
        vec![target_request(
            idents::FLAPREQ,
            FULL,
            Confidence::SysSel,
            300,
        )],
    );
    const FULL: i32 = 100_000;
    assert_eq!(
        flap_moves(&gw.receive(&d, &mut m, &mut ctl, t0)),
        [(true, Down)]
    );
    let mut now = t0;
    let mut stop_at = None;
    while now < t0 + ms(2000) && stop_at.is_none() {
        now = gw.next_deadline();
        flaps(&mut m, now, 60);
        if flap_moves(&gw.tick(&mut m, &mut ctl, now).to_unit).contains(&(false, Down)) {
            stop_at = Some(now);
        }
    }
    let at = stop_at.expect("stopped");
    // 300 ms expire encodes as exactly 300 ms.
    assert!(
        at - t0 >= ms(300) && at - t0 <= ms(400),
        "stopped after {:?}",
        at - t0
    );
    assert!(
        m.events
            .iter()
            .any(|e| e.text.contains("requests stopped or expired"))
    );
}

#[test]
fn motor_requests_need_live_status_and_log_their_refusal() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    let mut peer = Sender::new(PEER, 1);
    let d = request(
        &mut peer,
        vec![Parameter::new(idents::FLAPREQ, Value::Sint(50_000)).confidence(Confidence::UserSel)],
    );
    assert!(gw.receive(&d, &mut m, &mut ctl, t0).is_empty());
    assert!(last_said(&m).contains("request refused"));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn arbitrary_datagrams_never_panic_the_gateway(
        datagrams in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..200), 1..8),
        ecb in any::<bool>(),
    ) {
        let t0 = Instant::now();
        let mut m = model();
        status(&mut m, t0, &[2]);
        let mut gw = Gateway::new(commanded(), t0);
        let mut ctl = Controller::default();
        for (i, mut d) in datagrams.into_iter().enumerate() {
            if ecb && d.len() >= 24 {
                // Steer some inputs into a valid-looking header and an ECBSTAT ident.
                d[4] = 3;
                d[11] = (d.len() - 12) as u8;
                d[17] &= 0xF0;
                d[18] = 0;
                d[19] = 0x40; // ECBSTAT
                d[20] = 10; // BUS
                d[21] = 128; // USERSEL
            }
            let now = t0 + ms(i as u64 * 10);
            let _ = gw.receive(&d, &mut m, &mut ctl, now);
            let _ = gw.tick(&mut m, &mut ctl, now);
        }
    }
}

/// One motor stream at a time on the link: while the page's keys run a motor the
/// network's requests wait, a key at the page stops a network run, and a network
/// target the person overrode is not started again.
#[test]
fn the_pages_keys_come_before_network_motor_requests() {
    use vpx_efis::protocol::message::FlapDirection::Down;
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    pitch(&mut m, t0, 100);
    let mut peer = Sender::new(PEER, 1);
    let req = |peer: &mut Sender, target| request(peer, vec![flap_request(target, 600)]);
    // The page's keys run a motor (on the one controller): a network request does
    // not start.
    let pitch = Motor::Trim(TrimKind::Pitch);
    let keys = ctl.start(Origin::Key, &m, pitch, Direction::Up, How::Press, t0);
    assert!(!keys.expect("the key's run").is_empty());
    assert!(flap_moves(&gw.receive(&req(&mut peer, 50_000), &mut m, &mut ctl, t0)).is_empty());
    assert!(flap_moves(&gw.tick(&mut m, &mut ctl, t0 + ms(100)).to_unit).is_empty());
    assert_eq!(gw.running_motor(&ctl), None);
    assert_eq!(
        ctl.running().map(|r| r.motor),
        Some(pitch),
        "the key's run goes on"
    );
    // The page's run ends: the waiting request starts.
    ctl.stop(t0 + ms(150), StopReason::Released);
    let out = gw.receive(&req(&mut peer, 60_000), &mut m, &mut ctl, t0 + ms(150));
    let mut moves = flap_moves(&out);
    moves.extend(flap_moves(&gw.tick(&mut m, &mut ctl, t0 + ms(160)).to_unit));
    assert!(moves.contains(&(true, Down)), "{moves:?}");
    assert_eq!(gw.running_motor(&ctl), Some(Motor::Flaps));
    // A key at the page stops it, with the stop message: a person comes first.
    let any = KeyEvent::new(KeyCode::Char('j'), KeyModifiers::NONE);
    let o = ctl.handle_key(any, &no_selection(), &m, t0 + ms(200));
    assert_eq!(flap_moves(&o.packets), [(false, Down)]);
    assert_eq!(gw.running_motor(&ctl), None);
    let out = gw.tick(&mut m, &mut ctl, t0 + ms(210)).to_unit;
    assert!(flap_moves(&out).is_empty());
    // The same target repeated is not restarted.
    let out = gw.receive(&req(&mut peer, 60_000), &mut m, &mut ctl, t0 + ms(250));
    assert!(flap_moves(&out).is_empty());
    // And a key's run (here setup's, which any origin's start would do alike) ends a
    // network run at once: the network's waits, the person's goes.
    let out = gw.receive(&req(&mut peer, 90_000), &mut m, &mut ctl, t0 + ms(300));
    assert_eq!(flap_moves(&out), [(true, Down)]);
    let o = ctl.handle_key(any, &no_selection(), &m, t0 + ms(320));
    assert_eq!(flap_moves(&o.packets), [(false, Down)]);
    let said = |m: &Model| {
        m.events
            .iter()
            .filter(|e| e.text == "XFSp: flaps stopped: another key was pressed")
            .count()
    };
    assert_eq!(said(&m), 1, "the first stop, said on its next tick");
    gw.tick(&mut m, &mut ctl, t0 + ms(330));
    assert_eq!(said(&m), 2, "{:#?}", m.events);
}

fn no_selection() -> KeyContext {
    KeyContext {
        selected: None,
        overlay_open: false,
        past_endpoints: false,
    }
}

fn named(m: &mut Model, at: Instant, id: u8, name: &str) {
    use vpx_efis::protocol::message::DeviceName;
    m.apply_packet(
        at,
        &Packet::from_vpx(9, DeviceName::new(id, name).expect("a valid name")),
    );
}

fn labelled(unit: u16, label: &str, state: EcbState) -> Parameter {
    let mut p = ecb_request(unit, state, Confidence::UserSel);
    if let Value::Bus(b) = &mut p.value {
        b.label = label.as_bytes().to_vec();
    }
    p
}

fn power(out: &[Packet]) -> Vec<(u8, bool)> {
    out.iter()
        .filter_map(|p| match p.message {
            Message::DevicePower(d) => Some((d.device_id, d.on)),
            _ => None,
        })
        .collect()
}

/// What a circuit request comes to: the circuit switched, or a refusal in these words.
#[derive(Debug)]
enum Comes {
    Power(u8, bool),
    Refused(&'static str),
}

/// Circuit requests by label, by unit or both, in order from one requester.
/// Draft Table 18: a BUS label is "System/Item". A request labelled with our system
/// ("VP-X/LANDING LT", as we publish it) or plainly ("LANDING LT") names our circuit;
/// one for another system never does, even when the item matches one of ours. The
/// draft's ECBSTAT has "Unit Usage: None", so the label alone must do; our unit numbers
/// work too, and both together must agree.
#[test]
fn circuit_requests_match_by_label_by_unit_or_both_and_a_mismatch_is_refused() {
    use Comes::{Power, Refused};
    use EcbState::{Off, On};
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    let names = [
        (5, "LANDING LT"),
        (6, "TAXI LT"),
        (7, "SPARE"),
        (8, "Spare"),
        (9, "NAV/STROBE"),
    ];
    for (id, name) in names {
        named(&mut m, t0, id, name);
    }
    let mut peer = Sender::new(PEER, 1);
    let mut at = t0;
    let mut send = |gw: &mut Gateway, m: &mut Model, p: Parameter| {
        at += ms(10);
        gw.receive(&request(&mut peer, vec![p]), m, &mut ctl, at)
    };
    #[rustfmt::skip]
    let labels = [
        ("label only, unit 0 as the draft sends it, any case", 0, "landing lt", On, Power(5, true)),
        ("unit only", 6, "", On, Power(6, true)),
        ("both agreeing, the label NUL-padded as the draft allows", 2, "EFIS\0\0\0", Off, Power(2, false)),
        ("both disagreeing", 5, "TAXI LT", Off, Refused("XFSp 0x0042 (USERSEL): ECBSTAT OFF refused: unit 5 is \"LANDING LT\", not \"TAXI LT\"")),
        ("a label no circuit has", 0, "PITOT HEAT", On, Refused("no circuit is named \"PITOT HEAT\"")),
        ("a label two circuits share", 0, "spare", On, Refused("2 circuits are named \"spare\" (units 7, 8)")),
        ("a unit no circuit has", 300, "", On, Refused("unit 300 is no circuit")),
        ("a unit past the circuits, with a label one has", 40, "EFIS", On, Refused("unit 40 is no circuit")),
        ("a unit with the label that tells two spares apart", 8, "SPARE", On, Power(8, true)),
        ("our system and the item", 0, "VP-X/LANDING LT", Off, Power(5, false)),
        ("our system and the item, spaced and in any case", 6, " vp-x / taxi lt ", Off, Power(6, false)),
        ("one of our names holding a '/', whole", 0, "NAV/STROBE", On, Power(9, true)),
        ("one of our names holding a '/', with our system", 0, "VP-X/NAV/STROBE", Off, Power(9, false)),
        ("another system's breaker with an item of ours", 0, "ECU/LANDING LT", Off, Refused("\"ECU/LANDING LT\" is for system \"ECU\", not VP-X")),
    ];
    let (mut taken, mut refused) = (0, 0);
    for (what, unit, label, state, comes) in labels {
        let out = send(&mut gw, &mut m, labelled(unit, label, state));
        let words = match comes {
            Comes::Power(id, on) => {
                assert_eq!(power(&out), [(id, on)], "{what}");
                taken += 1;
                "-> DEVICE_POWER"
            }
            Comes::Refused(words) => {
                assert!(out.is_empty(), "{what}: {out:?}");
                refused += 1;
                words
            }
        };
        let said = last_said(&m);
        assert!(said.contains(words), "{what}: said {said:?}");
        let s = gw.stats();
        assert_eq!(
            (s.commands_taken, s.commands_refused),
            (taken, refused),
            "{what}"
        );
    }
    // The same refused request repeated within the window is one request.
    assert!(send(&mut gw, &mut m, labelled(0, "PITOT HEAT", EcbState::On)).is_empty());
    assert_eq!(gw.stats().commands_refused, refused);
    // Every refusal is in the event log as a warning.
    let refusals = m
        .events
        .iter()
        .filter(|e| e.text.contains("refused"))
        .count();
    assert_eq!(refusals as u64, refused);
}

/// A datagram from `sender` setting `ident` (MSTRCAUTN or MSTRWARN) to `value`.
fn master_datagram(
    sender: &mut Sender,
    ident: vpx_efis::xfsp::Ident,
    value: bool,
    conf: Confidence,
) -> Vec<u8> {
    let p = Parameter::new(ident, Value::Bool(Boolean::from(value))).confidence(conf);
    request(sender, vec![p])
}

/// A gateway taking commands whose unit has broadcast `faults` for a second, by when
/// they have raised `ident`.
fn raised_by(
    faults: &[(u8, FaultCode)],
    ident: vpx_efis::xfsp::Ident,
) -> (Instant, Model, Gateway, Controller) {
    let (t0, mut m, mut gw, ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    let (now, seen) = run_masters(&mut gw, &mut m, t0, 1, faults, ident);
    assert_eq!(seen.last(), Some(&true), "{faults:?} raise it");
    (now, m, gw, ctl)
}

/// Drives the gateway for `secs` seconds with the unit broadcasting `faults`, and
/// returns every value of `ident` it published.
fn run_masters(
    gw: &mut Gateway,
    m: &mut Model,
    from: Instant,
    secs: u64,
    faults: &[(u8, FaultCode)],
    ident: vpx_efis::xfsp::Ident,
) -> (Instant, Vec<bool>) {
    let mut now = from;
    let mut seen = Vec::new();
    while now < from + ms(secs * 1000) {
        status(m, now, &[]);
        for &(id, code) in faults {
            fault(m, now, id, code);
        }
        seen.extend(master_of(
            &params(&gw.tick(m, &mut Controller::default(), now)),
            ident,
        ));
        now = gw.next_deadline();
    }
    (now, seen)
}

#[test]
fn master_caution_reset_by_usersel_false_stays_false_until_a_new_caution() {
    let oc = [(5, FaultCode::OverCurrent)];
    let (now, mut m, mut gw, mut ctl) = raised_by(&oc, idents::MSTRCAUTN);
    // A display resets it.
    let mut display = Sender::new(PEER, 1);
    let reset = master_datagram(&mut display, idents::MSTRCAUTN, false, Confidence::UserSel);
    gw.receive(&reset, &mut m, &mut ctl, now);
    assert!(last_said(&m).contains("USERSEL): Master Caution reset (1 message acknowledged)"));
    // The fault still stands, refreshed every second: FALSE for good.
    let (now, seen) = run_masters(&mut gw, &mut m, now, 4, &oc, idents::MSTRCAUTN);
    assert!(seen.len() >= 4, "{seen:?}");
    assert!(seen.iter().all(|&v| !v), "came back: {seen:?}");
    // A new caution raises it again; SYSSEL resets it too.
    let two = [(5, FaultCode::OverCurrent), (6, FaultCode::CurrentFault)];
    let (now, seen) = run_masters(&mut gw, &mut m, now, 1, &two, idents::MSTRCAUTN);
    assert_eq!(seen.first(), Some(&true), "{seen:?}");
    let reset = master_datagram(&mut display, idents::MSTRCAUTN, false, Confidence::SysSel);
    gw.receive(&reset, &mut m, &mut ctl, now);
    let (_, seen) = run_masters(&mut gw, &mut m, now, 2, &two, idents::MSTRCAUTN);
    assert!(seen.iter().all(|&v| !v), "{seen:?}");
    // Status confidence is another node's report, not a reset; TRUE is refused.
    let before = gw.stats();
    let high = master_datagram(&mut display, idents::MSTRCAUTN, false, Confidence::High);
    gw.receive(&high, &mut m, &mut ctl, now + ms(2100));
    assert_eq!(gw.stats().commands_taken, before.commands_taken);
    let set = master_datagram(&mut display, idents::MSTRCAUTN, true, Confidence::UserSel);
    gw.receive(&set, &mut m, &mut ctl, now + ms(2200));
    assert_eq!(gw.stats().commands_refused, before.commands_refused + 1);
    assert!(last_said(&m).contains("only FALSE resets it"));
    assert_eq!(gw.stats().commands_taken, 2, "the two resets");
}

#[test]
fn master_warning_rises_on_a_short_and_resets_the_same_way() {
    let short = [(5, FaultCode::ShortCircuit)];
    let (now, mut m, mut gw, mut ctl) = raised_by(&short, idents::MSTRWARN);
    assert!(!gw.master_active(vpx_efis::xfsp::publish::Master::Caution));
    let mut display = Sender::new(PEER, 1);
    let reset = master_datagram(&mut display, idents::MSTRWARN, false, Confidence::SysSel);
    gw.receive(&reset, &mut m, &mut ctl, now);
    assert!(last_said(&m).contains("Master Warning reset (1 message acknowledged)"));
    let (now, seen) = run_masters(&mut gw, &mut m, now, 4, &short, idents::MSTRWARN);
    assert!(!seen.is_empty() && seen.iter().all(|&v| !v), "{seen:?}");
    // The short clears (no FAULT_STATUS for 2.5 s) and comes back: a new warning.
    let (now, _) = run_masters(&mut gw, &mut m, now, 3, &[], idents::MSTRWARN);
    assert!(gw.standing_cas().is_empty());
    let (_, seen) = run_masters(&mut gw, &mut m, now, 1, &short, idents::MSTRWARN);
    assert_eq!(seen.first(), Some(&true), "{seen:?}");
}

/// The exit summary's counts come from these: a refused RTRIMREQ is a refusal.
#[test]
fn refused_and_expired_motor_requests_are_counted() {
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[]);
    flaps(&mut m, t0, 40); // roll trim not configured: no scale
    let mut peer = Sender::new(PEER, 1);
    let roll = request(
        &mut peer,
        vec![Parameter::new(idents::RTRIMREQ, Value::Sint(20_000)).confidence(Confidence::UserSel)],
    );
    assert!(gw.receive(&roll, &mut m, &mut ctl, t0).is_empty());
    assert_eq!(
        (gw.stats().commands_taken, gw.stats().commands_refused),
        (0, 1)
    );
    assert!(last_said(&m).contains("roll trim request refused"));
    // Not a SINT.
    let wrong = request(
        &mut peer,
        vec![Parameter::new(idents::PTRIMREQ, Value::Uint(5)).confidence(Confidence::UserSel)],
    );
    gw.receive(&wrong, &mut m, &mut ctl, t0 + ms(10));
    assert_eq!(gw.stats().commands_refused, 2);
    // A flap request waiting behind the page's keys until it expires.
    pitch(&mut m, t0 + ms(20), 100);
    let keys = ctl.start(
        Origin::Check,
        &m,
        Motor::Trim(TrimKind::Pitch),
        Direction::Up,
        How::For {
            length: ms(2000),
            way: None,
        },
        t0 + ms(20),
    );
    assert!(keys.is_ok(), "{keys:?}");
    let flap = request(&mut peer, vec![flap_request(50_000, 300)]);
    gw.receive(&flap, &mut m, &mut ctl, t0 + ms(20));
    let mut now = t0 + ms(20);
    while now < t0 + ms(1000) {
        status(&mut m, now, &[]);
        flaps(&mut m, now, 40);
        gw.tick(&mut m, &mut ctl, now);
        now = gw.next_deadline();
    }
    assert_eq!(
        (gw.stats().commands_taken, gw.stats().commands_refused),
        (0, 3)
    );
    assert!(m.events.iter().any(|e| {
        e.text.contains(
            "expired while another run (the page's keys, the check or the remote) was going on",
        )
    }));
}

/// The loop's contract: after a tick, the next deadline is in the future, whatever the
/// unit's enable flags, with motor requests, air data and faults coming and going.
#[test]
fn after_every_tick_the_gateway_deadline_is_in_the_future() {
    use vpx_efis::protocol::message::{DeviceEnable, EnableFlag};
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    flaps(&mut m, t0, 40);
    gw.tick(&mut m, &mut ctl, t0);
    for id in 4..=28u8 {
        let e = DeviceEnable {
            device_id: id,
            flag: if id == 5 {
                EnableFlag::Enabled
            } else {
                EnableFlag::Disabled
            },
        };
        m.apply_packet(t0 + ms(30), &Packet::from_vpx(8, e));
    }
    let mut peer = Sender::new(PEER, 1);
    let mut now = t0 + ms(30);
    let mut ticks = 0;
    while now < t0 + ms(20_000) {
        let s = (now - t0).as_secs();
        if s % 5 != 4 {
            // The unit broadcasts, except for one second in five (faults clear,
            // positions go stale).
            status(&mut m, now, &[2]);
            if s.is_multiple_of(3) {
                fault(&mut m, now, 5, FaultCode::OverCurrent);
            }
            if (now - t0).as_millis() % 1000 < 500 {
                flaps(&mut m, now, 40 + (s as u8 % 10) * 8);
            }
        }
        if s % 4 == 1 {
            let d = request(
                &mut peer,
                vec![
                    flap_request(60_000, 300),
                    Parameter::new(idents::IAS, Value::Sint(70)),
                ],
            );
            gw.receive(&d, &mut m, &mut ctl, now);
        }
        gw.tick(&mut m, &mut ctl, now);
        ticks += 1;
        let next = gw.next_deadline();
        assert!(next > now, "tick at +{:?}: deadline not ahead", now - t0);
        now = next;
    }
    // 10 Hz polling at most, plus the motor stream's 5 Hz while it runs.
    assert!(ticks <= 20 * 16, "{ticks} ticks in 20 s");
}

/// We send FLIGHTDATA (see `xfsp::gateway`'s notes); a request sent as DEVSTATUS, the
/// draft's other operation, is read all the same.
#[test]
fn a_request_sent_as_devstatus_is_taken() {
    use vpx_efis::xfsp::MsgOp;
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    let kind = MsgKind {
        op: MsgOp::DevStatus,
        ..MsgKind::flight_data(CertLevel::Experimental)
    };
    let d = Sender::new(PEER, 1)
        .pack(kind, &[ecb_request(5, EcbState::On, Confidence::UserSel)])
        .unwrap()
        .remove(0);
    assert_eq!(d[5], 3, "the header says DEVSTATUS");
    assert_eq!(power(&gw.receive(&d, &mut m, &mut ctl, t0)), [(5, true)]);
}

/// Draft §4.4: a message numbered below the last one from its source "MUST be
/// discarded". Our decision: a source silent for 10 s (FORGET_SOURCE_AFTER) is
/// forgotten, so a node that restarted and numbers from scratch is heard at once.
#[test]
fn an_older_number_is_discarded_until_its_source_was_silent_for_10_s() {
    use vpx_efis::xfsp::gateway::FORGET_SOURCE_AFTER;
    assert_eq!(FORGET_SOURCE_AFTER, Duration::from_secs(10));
    let (t0, mut m, mut gw, mut ctl) = commanded_gateway();
    status(&mut m, t0, &[2]);
    let before = Sender::new(PEER, 100)
        .pack(
            MsgKind::flight_data(CertLevel::Experimental),
            &[ecb_request(5, EcbState::On, Confidence::UserSel)],
        )
        .unwrap()
        .remove(0);
    assert_eq!(
        power(&gw.receive(&before, &mut m, &mut ctl, t0)),
        [(5, true)]
    );
    // The node restarts and numbers from 7: within 10 s of its last message, discarded.
    let restarted = |n| {
        Sender::new(PEER, n)
            .pack(
                MsgKind::flight_data(CertLevel::Experimental),
                &[ecb_request(6, EcbState::On, Confidence::UserSel)],
            )
            .unwrap()
            .remove(0)
    };
    assert!(
        gw.receive(&restarted(7), &mut m, &mut ctl, t0 + ms(9_000))
            .is_empty()
    );
    assert_eq!(gw.stats().rx.out_of_order, 1);
    // Heard again 9 s later (18 s after its last fresh message but only 9 s after the
    // discarded one): still within 10 s of hearing it, so still discarded.
    status(&mut m, t0 + ms(18_000), &[2, 5]);
    assert!(
        gw.receive(&restarted(8), &mut m, &mut ctl, t0 + ms(18_000))
            .is_empty()
    );
    assert_eq!(gw.stats().rx.out_of_order, 2);
    // More than 10 s of silence: forgotten, and its low number is taken.
    status(&mut m, t0 + ms(28_500), &[2, 5]);
    let out = gw.receive(&restarted(9), &mut m, &mut ctl, t0 + ms(28_500));
    assert_eq!(power(&out), [(6, true)]);
}

// ----- network motor runs under the endpoint rule -----

/// How long a decided move or stop takes to act on the motor: the serial write at
/// 57600 baud and the unit's own loop.
const ACT_AFTER: Duration = Duration::from_millis(20);

/// A pitch trim on the fake clock against the gateway: while the last TRIM_MOVE that
/// reached it (each [`ACT_AFTER`] after it was sent) said on, its position changes
/// `travel` counts a second whichever way it was driven (negative: toward the up
/// endpoint 30, as a run "down" does with its leads swapped). FLAP_TRIM_STATUS comes
/// every 100 ms from `phase`, until `status_until`; the request is repeated every
/// 250 ms, as a requester should.
struct TrimRun {
    /// The true position at each 5 ms step, and when.
    track: Vec<(Duration, f32)>,
    /// TRIM_MOVE on/off as sent, and when.
    moves: Vec<(Duration, bool)>,
    events: Vec<String>,
    refused: u64,
}

impl TrimRun {
    fn go(start: u8, target: i32, travel: f32, phase: u64, status_until: Duration) -> TrimRun {
        let t0 = Instant::now();
        let mut m = model();
        status(&mut m, t0, &[]);
        pitch(&mut m, t0, start);
        let mut gw = Gateway::new(commanded(), t0);
        let mut ctl = Controller::default();
        let mut peer = Sender::new(PEER, 1);
        let mut pos = f32::from(start);
        let mut on = false;
        let mut pending: Vec<(Duration, bool)> = Vec::new();
        let mut run = TrimRun {
            track: Vec::new(),
            moves: Vec::new(),
            events: Vec::new(),
            refused: 0,
        };
        for step in 0..800u64 {
            let t = ms(step * 5);
            let now = t0 + t;
            pending.retain(|&(at, o)| {
                if at <= t {
                    on = o;
                }
                at > t
            });
            if on {
                pos = (pos + travel * 0.005).clamp(0.0, 255.0);
            }
            run.track.push((t, pos));
            let mut out = Vec::new();
            if step % 50 == 0 {
                let d = request(
                    &mut peer,
                    vec![target_request(
                        idents::PTRIMREQ,
                        target,
                        Confidence::UserSel,
                        600,
                    )],
                );
                out.extend(gw.receive(&d, &mut m, &mut ctl, now));
            }
            let heard = (step * 5) % 100 == phase % 100;
            if heard {
                status(&mut m, now, &[]);
                if t < status_until {
                    pitch(&mut m, now, pos.round() as u8);
                }
            }
            if heard || now >= gw.next_deadline() {
                out.extend(gw.tick(&mut m, &mut ctl, now).to_unit);
            }
            for p in &out {
                if let Message::TrimMove(tm) = p.message {
                    run.moves.push((t, tm.on));
                    pending.push((t + ACT_AFTER, tm.on));
                }
            }
        }
        run.events = m.events.iter().map(|e| e.text.clone()).collect();
        run.refused = gw.stats().commands_refused;
        run
    }

    /// When the first stop went out, and the lowest and highest the trim went.
    fn stopped(&self) -> Option<Duration> {
        self.moves.iter().find(|(_, on)| !on).map(|(t, _)| *t)
    }

    fn range(&self) -> (f32, f32) {
        let lo = self.track.iter().map(|p| p.1).fold(f32::MAX, f32::min);
        let hi = self.track.iter().map(|p| p.1).fold(f32::MIN, f32::max);
        (lo, hi)
    }

    fn said(&self, what: &str) -> bool {
        self.events.iter().any(|e| e.contains(what))
    }
}

/// A trim sent nose-down (PTRIMREQ −80000, raw 201 from 125) whose leads are
/// swapped runs nose-up, away from its target: the run ends within a few counts,
/// its stop on the wire, says why, and the repeated request does not start it again:
/// it does not run on to the run cap (10 s, some 250 counts) past its endpoint.
#[test]
fn a_network_run_going_away_from_its_target_stops_within_a_few_counts() {
    for phase in (0..100).step_by(10) {
        let run = TrimRun::go(125, -80_000, -25.0, phase, ms(4000));
        let stop = run
            .stopped()
            .unwrap_or_else(|| panic!("never stopped: {:#?}", run.events));
        let (lo, _) = run.range();
        let away = 125.0 - lo;
        assert!(
            away <= (vpx_efis::control::endpoints::MOVED + 3) as f32,
            "phase {phase}: went {away} counts the wrong way"
        );
        assert!(stop <= ms(400), "phase {phase}: stopped after {stop:?}");
        // As every origin's run: moving against its command (`control::against`).
        assert!(
            run.said("it moved up when asked down: its leads or its sensor may be swapped"),
            "{:#?}",
            run.events
        );
        // One run, one stop: the same target is latched.
        let ons = run.moves.iter().filter(|m| m.1).count();
        assert_eq!(ons, run.moves.iter().position(|m| !m.1).unwrap());
        assert!(run.moves.iter().skip_while(|m| m.1).all(|m| !m.1));
    }
    // The same trim wired right gets there and stops on "target reached".
    let run = TrimRun::go(125, -80_000, 25.0, 30, ms(4000));
    let (_, hi) = run.range();
    assert!((199.0..=202.0).contains(&hi), "ended at {hi}");
    assert!(run.said("target reached"), "{:#?}", run.events);
}

/// Sent to its nose-up endpoint (PTRIMREQ +100000 is raw 30), the trim stops just
/// before it at its rate rather than a count short of it by "target reached": it
/// never passes 30, whatever the phase of the 10 Hz positions.
#[test]
fn a_network_run_to_the_endpoint_stops_before_passing_it() {
    for phase in (0..100).step_by(10) {
        let run = TrimRun::go(60, 100_000, -25.0, phase, ms(4000));
        let (lo, _) = run.range();
        assert!(lo >= 30.0, "phase {phase}: passed the endpoint to {lo}");
        assert!(lo <= 34.0, "phase {phase}: stopped short at {lo}");
        assert!(
            run.said("at its endpoint (position 30)") || run.said("target reached"),
            "{:#?}",
            run.events
        );
    }
}

/// A run with swapped leads started two counts off the endpoint behind it is stopped
/// by position as it reaches that endpoint, before it has gone `MOVED` counts: as
/// moving against its command.
/// (It can still pass by up to one 10 Hz position's travel: 2.5 counts at 25 a
/// second; the installation check probes there, the gateway does not yet.)
#[test]
fn a_reversed_network_run_near_the_endpoint_behind_stops_there() {
    for phase in (0..100).step_by(10) {
        let run = TrimRun::go(32, -50_000, -25.0, phase, ms(4000));
        assert!(run.stopped().is_some(), "{:#?}", run.events);
        let (lo, _) = run.range();
        assert!(lo >= 27.0, "phase {phase}: passed the endpoint to {lo}");
        assert!(
            run.said("it moved up when asked down: its leads or its sensor may be swapped"),
            "{:#?}",
            run.events
        );
    }
}

/// Within START_ROOM of the endpoint it heads for, a run does not start, and the
/// refusal says why and is counted.
#[test]
fn a_network_run_at_its_endpoint_is_refused() {
    let room = vpx_efis::control::endpoints::START_ROOM;
    let at = 30 + room as u8;
    // +100000 is raw 30; from `at` that is `room` counts away, more than STOP_MARGIN.
    let run = TrimRun::go(at, 100_000, -25.0, 0, ms(4000));
    assert!(run.moves.is_empty(), "{:?}", run.moves);
    assert!(run.said("at its up endpoint"), "{:#?}", run.events);
    assert_eq!(run.refused, 1);
    // One count more room, and it runs.
    let run = TrimRun::go(at + 1, 100_000, -25.0, 0, ms(4000));
    assert!(!run.moves.is_empty(), "{:#?}", run.events);
}

/// When FLAP_TRIM_STATUS stops coming (SYSTEM_STATUS still does), a network run ends
/// once its position is older than 0.4 s, the page's rule, not the model's 1 s.
#[test]
fn a_network_run_stops_on_a_position_older_than_0_4_s() {
    let run = TrimRun::go(125, -80_000, 25.0, 0, ms(500));
    let stop = run.stopped().expect("stopped");
    // The last position was heard at 400 ms (statuses at 0, 100, ... 400).
    assert!(
        stop > ms(800) && stop <= ms(900),
        "stopped at {stop:?}: {:#?}",
        run.events
    );
    assert!(run.said("its position is not fresh"), "{:#?}", run.events);
}

/// Without `--xfsp-control` every kind of command (ECBSTAT, a motor
/// request, a master reset) is refused: nothing for the unit, the reason in the event
/// log once (not once a datagram), and each counted. Air data is still forwarded.
#[test]
fn without_control_commands_are_refused_logged_once_and_counted() {
    let t0 = Instant::now();
    let mut m = model();
    status(&mut m, t0, &[2]);
    pitch(&mut m, t0, 125);
    let mut gw = Gateway::new(GatewayConfig::default(), t0);
    let mut ctl = Controller::default();
    assert_eq!(gw.config().control, Control::Off, "off by default");
    let mut peer = Sender::new(PEER, 100);
    let commands = vec![
        ecb_request(2, EcbState::Off, Confidence::UserSel),
        Parameter::new(idents::PTRIMREQ, Value::Sint(-50_000)).confidence(Confidence::UserSel),
        Parameter::new(idents::MSTRCAUTN, Value::Bool(Boolean::False))
            .confidence(Confidence::SysSel),
        Parameter::new(idents::IAS, Value::Sint(88)),
    ];
    let mut to_unit = Vec::new();
    for i in 0..8u64 {
        let d = request(&mut peer, commands.clone());
        let at = t0 + ms(250 * i);
        to_unit.extend(gw.receive(&d, &mut m, &mut ctl, at));
        to_unit.extend(gw.tick(&mut m, &mut ctl, at).to_unit);
    }
    assert!(
        to_unit
            .iter()
            .all(|p| matches!(p.message, Message::ExternalData(_))),
        "only air data may reach the unit: {to_unit:?}"
    );
    assert!(
        to_unit
            .iter()
            .any(|p| matches!(p.message, Message::ExternalData(_))),
        "air data is still forwarded"
    );
    assert_eq!(gw.running_motor(&ctl), None);
    let s = gw.stats();
    assert_eq!(s.commands_not_allowed, 24, "3 commands x 8 datagrams");
    assert_eq!((s.commands_taken, s.commands_refused), (0, 0));
    let said = events::containing(&m, "refused: commands from the network are off");
    assert_eq!(said.len(), 1, "one line per source per 10 s: {said:?}");
    assert!(
        said[0].starts_with("XFSp 0x0042 (USERSEL): ECBSTAT refused"),
        "{said:?}"
    );
    assert!(said[0].contains("--xfsp-control"), "{said:?}");
    // Ten seconds on, the same source is said again, with the count so far.
    let d = request(&mut peer, commands[..1].to_vec());
    assert!(gw.receive(&d, &mut m, &mut ctl, t0 + ms(12_000)).is_empty());
    let last = last_said(&m);
    assert!(
        last.contains("25 network commands refused so far"),
        "{last}"
    );
}

/// `--xfsp-control-from`: a listed source commands, any other is refused with its id
/// and the list in the words.
#[test]
fn only_listed_sources_may_command() {
    let t0 = Instant::now();
    let mut m = model();
    status(&mut m, t0, &[2]);
    let cfg = GatewayConfig {
        control: Control::From(vec![0x1234]),
        ..GatewayConfig::default()
    };
    let mut gw = Gateway::new(cfg, t0);
    let mut ctl = Controller::default();
    let mut stranger = Sender::new(PEER, 100);
    let off = |s: &mut Sender| request(s, vec![ecb_request(2, EcbState::Off, Confidence::UserSel)]);
    assert!(
        gw.receive(&off(&mut stranger), &mut m, &mut ctl, t0)
            .is_empty()
    );
    let last = last_said(&m);
    assert!(
        last.contains("0x0042 is not in --xfsp-control-from (0x1234)"),
        "{last}"
    );
    let mut listed = Sender::new(0x1234, 7);
    let out = gw.receive(&off(&mut listed), &mut m, &mut ctl, t0 + ms(10));
    assert!(
        matches!(out.as_slice(), [Packet { message: Message::DevicePower(p), .. }] if p.device_id == 2 && !p.on),
        "{out:?}"
    );
    let s = gw.stats();
    assert_eq!((s.commands_not_allowed, s.commands_taken), (1, 1));
}

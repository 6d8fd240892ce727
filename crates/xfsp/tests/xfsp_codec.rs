//! The XFSp codec through its public API, the way the gateway will use it.

use std::time::Instant;

use proptest::prelude::*;
use xfsp::{
    Body, Bus, CasLevel, CasMsg, CertLevel, Confidence, EcbFlags, EcbState, Error, Expire,
    FormatId, Message, MessageView, MsgKind, Parameter, Received, Receiver, Sender, Value, idents,
};

/// The §5.1 "Adjust radio" datagram, typed in byte by byte from Figures 4, 5 and 6,
/// with `len` = 0x20 (the bytes that follow) per icd-reading X3.
const ADJUST_RADIO: &[u8] = &[
    0x03, 0xE9, // src id 1001
    0x00, 0x14, // message number 20
    0x03, // OP
    0x02, // FLIGHTDATA
    0x00, 0x05, // flags LEVEL-A
    0x00, 0x00, // tcid NONE
    0x00, 0x20, // len
    0x00, 0x02, 0x00, 0x00, // unit 2, subunit 0
    0x00, 0x40, 0x00, 0x24, // data len 4, ident COMFREQKHZ
    0x02, 0x80, 0xFF, 0x05, // UINT, USERSEL, never expires, LEVEL-A
    0x00, 0x01, 0xDF, 0x7E, // 122750
    0x00, 0x02, 0x00, 0x00, // unit 2, subunit 0
    0x00, 0x40, 0x00, 0x28, // data len 4, ident COMSQL
    0x02, 0x80, 0xFF, 0x05, // UINT, USERSEL, never expires, LEVEL-A
    0x00, 0x00, 0x00, 0x35, // 53
];

#[test]
fn adjust_radio_example_decodes() {
    let v = MessageView::parse(ADJUST_RADIO).unwrap();
    assert_eq!(v.header().src_id, 1001);
    assert_eq!(v.header().msg_num, 20);
    assert_eq!(v.header().cert(), CertLevel::LevelA);
    let got: Vec<_> = v
        .params()
        .map(|p| {
            (
                p.header.ident,
                p.header.unit,
                p.header.confidence,
                p.header.expire,
                p.value(),
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            (
                idents::COMFREQKHZ,
                2,
                Confidence::UserSel,
                Expire::NEVER,
                Ok(Value::Uint(122_750))
            ),
            (
                idents::COMSQL,
                2,
                Confidence::UserSel,
                Expire::NEVER,
                Ok(Value::Uint(53))
            ),
        ]
    );
}

#[test]
fn adjust_radio_example_encodes() {
    let p = |ident, v| {
        Parameter::new(ident, Value::Uint(v))
            .unit(2)
            .confidence(Confidence::UserSel)
            .cert(CertLevel::LevelA)
    };
    let mut s = Sender::new(1001, 20);
    let d = s
        .pack(
            MsgKind::flight_data(CertLevel::LevelA),
            &[p(idents::COMFREQKHZ, 122_750), p(idents::COMSQL, 53)],
        )
        .unwrap();
    assert_eq!(d, [ADJUST_RADIO.to_vec()]);
}

#[test]
fn the_printed_len_0x28_is_malformed_by_our_reading() {
    let mut b = ADJUST_RADIO.to_vec();
    b[11] = 0x28;
    let mut r = Receiver::default();
    assert_eq!(
        r.receive(&b, Instant::now()),
        Received::Malformed(Error::LenPastEnd {
            declared: 0x28,
            available: 32
        })
    );
    assert_eq!(r.stats().malformed, 1);
}

/// What the gateway publishes for a VP-X: bus, a circuit, flaps, an alert.
fn vpx_status() -> Vec<Parameter> {
    let bus = Bus {
        state: EcbState::On,
        flags: EcbFlags(EcbFlags::INPUTVOLTS),
        in_volts: Bus::to_tenths(14.2),
        out_volts: Bus::to_tenths(13.9),
        draw_amps: Bus::to_tenths(18.3),
        label: b"MAIN".to_vec(),
        ..Bus::default()
    };
    let landing_light = Bus {
        state: EcbState::OverCur,
        draw_amps: Bus::to_tenths(9.7),
        max_amps: Bus::to_tenths(7.0),
        label: b"LANDING LT".to_vec(),
        ..Bus::default()
    };
    let q = |p: Parameter| {
        p.confidence(Confidence::High)
            .expire(Expire::at_least_millis(2_000))
            .cert(CertLevel::Experimental)
    };
    vec![
        q(Parameter::new(idents::BUSSTAT, Value::Bus(bus))),
        q(Parameter::new(idents::ECBSTAT, Value::Bus(landing_light)).subunit(7)),
        q(Parameter::new(idents::FLAPPOS, Value::Sint(50_000))),
        q(Parameter::new(
            idents::CASMSG,
            Value::CasMsg(CasMsg::new(CasLevel::Caution, "LANDING LT OVERCURRENT")),
        )),
        q(Parameter::new(idents::MSTRCAUTN, Value::Bool(true.into()))),
    ]
}

#[test]
fn gateway_round_trip_through_sender_and_receiver() {
    let mut s = Sender::new(0x5650, 65535);
    let mut r = Receiver::default();
    let mut seen = Vec::new();
    for _ in 0..3 {
        for d in s
            .pack(MsgKind::flight_data(CertLevel::Experimental), &vpx_status())
            .unwrap()
        {
            let Received::Fresh(v) = r.receive(&d, Instant::now()) else {
                panic!("fresh datagram rejected");
            };
            for p in v.params() {
                let info = idents::lookup(p.header.ident, p.header.format).unwrap();
                seen.push((info.name, p.value().unwrap()));
            }
            assert!(matches!(
                r.receive(&d, Instant::now()),
                Received::Duplicate(_)
            ));
        }
    }
    assert_eq!(seen.len(), 15);
    assert_eq!(seen[0].0, "BUSSTAT");
    let Value::Bus(b) = &seen[0].1 else {
        panic!("BUSSTAT is BUS")
    };
    assert_eq!((b.out_volts, b.draw_amps), (139, 183), "tenths on the wire");
    assert_eq!(seen[3].0, "CASMSG");
    assert_eq!(r.stats().fresh, 3);
    assert_eq!(r.stats().duplicate, 3);
}

#[test]
fn an_unknown_format_is_skippable_but_not_decodable() {
    let mut d = Sender::new(1, 0)
        .pack(
            MsgKind::flight_data(CertLevel::LevelE),
            &[
                Parameter::new(idents::IAS, Value::Sint(1200)),
                Parameter::new(idents::ENGRPM, Value::Uint(2400)),
            ],
        )
        .unwrap()
        .remove(0);
    d[12 + 8] = 99; // first parameter's format
    let v = MessageView::parse(&d).unwrap();
    let vals: Vec<_> = v.params().map(|p| p.value()).collect();
    assert_eq!(vals, [Err(Error::UnknownFormat(99)), Ok(Value::Uint(2400))]);
    assert_eq!(Message::parse(&d), Err(Error::UnknownFormat(99)));
    assert_eq!(FormatId::from(99), FormatId::Unknown(99));
}

#[test]
fn owned_message_round_trip() {
    let m = Message::flight_data(0x5650, 7, CertLevel::LevelD, vpx_status());
    let b = m.emit().unwrap();
    let back = Message::parse(&b).unwrap();
    assert_eq!(back, m);
    let Body::Params(ps) = back.body else {
        panic!("OP carries parameters")
    };
    assert_eq!(ps.len(), 5);
}

proptest! {
    #[test]
    fn arbitrary_datagrams_never_panic_the_receiver(
        ds in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..200), 1..20),
    ) {
        let mut r = Receiver::default();
        let t0 = Instant::now();
        for d in &ds {
            if let Received::Fresh(v) = r.receive(d, t0) {
                for p in v.params() {
                    let _ = p.value();
                }
            }
        }
        let s = r.stats();
        prop_assert_eq!(s.fresh + s.duplicate + s.out_of_order + s.malformed, ds.len() as u64);
        prop_assert!(r.tracked_sources() <= ds.len());
    }
}

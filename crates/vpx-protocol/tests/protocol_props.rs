//! Properties of the codec and the streaming decoder.
//!
//! Round trip: every typed message emits bytes that parse back to the same value.
//! Where the ICD maps two byte values to one typed value, the strategies generate
//! only the canonical typed value, because the other one cannot come back:
//! - enumerations are built with `from_byte` (so `SwitchId` 255 appears as
//!   `AlwaysOn`, which is sent as 11 — icd-reading R10);
//! - one-bit fields (trim type in TRIM_SPEC, wig-wag mode in SYSTEM_STATUS) are only
//!   the two values the bit can hold;
//! - `Option<u8>` device ids whose `None` is sent as 255 are never `Some(255)`, and
//!   "error/integrity code 0 = none" is never `Some(code 0)`;
//! - FAULT_STATUS codes are a prefix of `Some`s followed by `None`s, which is all a
//!   payload length can express (icd-reading R9).

// The codec's no-panic lints (Cargo.toml) are for the library. clippy.toml lifts them
// inside #[test] functions, not in the helpers beside them, which index their own
// fixtures here.
#![allow(clippy::indexing_slicing, clippy::unwrap_used)]

use proptest::prelude::*;
use vpx_protocol::decoder::DecoderStats;
use vpx_protocol::describe::{describe, to_json};
use vpx_protocol::device::DEVICE_COUNT;
use vpx_protocol::frame::{MAX_FRAME, SYNC1};
use vpx_protocol::message::*;
use vpx_protocol::{Decoder, Event, FaultCode, FrameRef, LenRule, MessageId, Node, Packet};

fn node() -> impl Strategy<Value = Node> {
    any::<u8>().prop_map(Node::from_byte)
}

fn tenths() -> impl Strategy<Value = Tenths> {
    any::<u16>().prop_map(Tenths)
}

fn fault_code() -> impl Strategy<Value = FaultCode> {
    any::<u8>().prop_map(FaultCode::from_byte)
}

fn polarity() -> impl Strategy<Value = Polarity> {
    prop_oneof![Just(Polarity::Standard), Just(Polarity::Inverted)]
}

/// A device id whose absence is sent as 255.
fn opt_id() -> impl Strategy<Value = Option<u8>> {
    prop::option::of(0u8..=254)
}

fn ping() -> impl Strategy<Value = Ping> {
    any::<bool>().prop_map(|ack| Ping { ack })
}

fn version() -> impl Strategy<Value = Version> {
    (any::<u8>(), any::<u8>(), any::<u8>()).prop_map(|(h, a, b)| Version {
        hardware_version: HardwareVersion::from_byte(h),
        software_major: a,
        software_minor: b,
    })
}

fn eeprom_erase() -> impl Strategy<Value = EepromErase> {
    any::<u8>().prop_map(|response_code| EepromErase { response_code })
}

fn device_spec() -> impl Strategy<Value = DeviceSpec> {
    (any::<u8>(), any::<u8>(), any::<u8>(), any::<bool>()).prop_map(|(d, cb, sw, cf)| DeviceSpec {
        device_id: d,
        circuit_breaker: cb,
        switch_id: SwitchId::from_byte(sw),
        current_fault: cf,
        switch_raw: None,
    })
}

fn system_spec() -> impl Strategy<Value = SystemSpec> {
    (any::<u8>(), opt_id()).prop_map(|(o, s)| SystemSpec {
        overvoltage_limit: OvervoltageLimit::from_byte(o),
        secondary_alternator: s,
    })
}

fn trim_spec() -> impl Strategy<Value = TrimSpec> {
    (
        prop_oneof![Just(TrimType::Pitch), Just(TrimType::Roll)],
        any::<bool>(),
        polarity(),
        any::<[u8; 4]>(),
        any::<u16>(),
    )
        .prop_map(|(t, enabled, polarity, b, speed)| TrimSpec {
            trim_type: t,
            enabled,
            polarity,
            up: b[0],
            down: b[1],
            neutral: b[2],
            power: b[3],
            speed,
        })
}

fn flap_spec() -> impl Strategy<Value = FlapSpec> {
    (
        prop_oneof![Just(FlapMode::Momentary), Just(FlapMode::PositionBased)],
        any::<bool>(),
        polarity(),
        any::<[u8; 6]>(),
        any::<u16>(),
        tenths(),
    )
        .prop_map(|(mode, enabled, polarity, b, max_speed, d)| FlapSpec {
            mode,
            enabled,
            polarity,
            up: b[0],
            down: b[1],
            midpoint_1: b[2],
            midpoint_2: b[3],
            circuit_breaker: b[4],
            overspeed_position: b[5],
            max_speed,
            endpoint_duration: d,
        })
}

fn wig_wag_spec() -> impl Strategy<Value = WigWagSpec> {
    (opt_id(), opt_id(), any::<u8>(), any::<u8>()).prop_map(|(a, b, w, s)| WigWagSpec {
        device_one: a,
        device_two: b,
        warm_up_period: w,
        speed: s,
    })
}

fn spec_ack() -> impl Strategy<Value = SpecAck> {
    (
        any::<u8>(),
        prop::option::of((1u8..=255).prop_map(SpecAckError::from_byte)),
    )
        .prop_map(|(device_id, error)| SpecAck { device_id, error })
}

fn device_name() -> impl Strategy<Value = DeviceName> {
    (any::<u8>(), any::<[u8; 16]>()).prop_map(|(device_id, name)| DeviceName { device_id, name })
}

fn device_enable() -> impl Strategy<Value = DeviceEnable> {
    (any::<u8>(), any::<u8>()).prop_map(|(device_id, f)| DeviceEnable {
        device_id,
        flag: EnableFlag::from_byte(f),
    })
}

fn system_status() -> impl Strategy<Value = SystemStatus> {
    (
        (tenths(), any::<i16>(), tenths(), any::<u8>()),
        any::<u16>(),
        (
            any::<bool>(),
            prop_oneof![
                Just(WigWagModeSetting::Auto),
                Just(WigWagModeSetting::Steady)
            ],
            any::<bool>(),
            any::<bool>(),
        ),
        any::<[bool; 5]>(),
        prop::option::of((1u8..=255).prop_map(DataIntegrityCode::from_byte)),
    )
        .prop_map(
            |((cur, bus, aux, temp), sw, (st, ww, su, wa), f, code)| SystemStatus {
                system_current: cur,
                main_bus_volts: SignedTenths(bus),
                aux_battery_volts: aux,
                internal_temp: temp,
                // Bits 8 and 9 of the switch word are switches 9 and 10; every bit of
                // the word has a meaning, so any word is canonical.
                switches: SwitchInputs::from_word(sw),
                misc: MiscFlags {
                    starter_annunciator: st,
                    wig_wag_mode: ww,
                    software_update: su,
                    wig_wag_active: wa,
                },
                faults: SystemFaultFlags {
                    current_over_48a: f[0],
                    current_over_60a: f[1],
                    warm_reset: f[2],
                    data_integrity_failure: f[3],
                    external_data_missing: f[4],
                },
                data_integrity_code: code,
            },
        )
}

fn device_status() -> impl Strategy<Value = DeviceStatus> {
    (
        prop::array::uniform::<_, DEVICE_COUNT>(any::<bool>()),
        prop::array::uniform::<_, DEVICE_COUNT>(tenths()),
    )
        .prop_map(|(on, current)| DeviceStatus { on, current })
}

fn flap_trim_status() -> impl Strategy<Value = FlapTrimStatus> {
    (
        any::<[bool; 5]>(),
        any::<[bool; 6]>(),
        any::<[u8; 13]>(),
        (fault_code(), fault_code(), fault_code()),
    )
        .prop_map(|(ff, tf, b, (f1, f2, f3))| FlapTrimStatus {
            flap: FlapFlags {
                enabled: ff[0],
                motor_running: ff[1],
                fault: ff[2],
                overspeed_alarm: ff[3],
                down_switch_inhibited: ff[4],
            },
            pitch_trim: TrimFlags {
                enabled: tf[0],
                motor_running: tf[1],
                fault: tf[2],
            },
            roll_trim: TrimFlags {
                enabled: tf[3],
                motor_running: tf[4],
                fault: tf[5],
            },
            flap_position: b[0],
            pitch_trim_position: b[1],
            roll_trim_position: b[2],
            flap_fault: f1,
            pitch_trim_fault: f2,
            roll_trim_fault: f3,
            flap_up: b[3],
            flap_down: b[4],
            flap_midpoint_1: b[5],
            flap_midpoint_2: b[6],
            pitch_trim_up: b[7],
            pitch_trim_down: b[8],
            pitch_trim_neutral: b[9],
            roll_trim_up: b[10],
            roll_trim_down: b[11],
            roll_trim_neutral: b[12],
        })
}

fn fault_status() -> impl Strategy<Value = FaultStatus> {
    (
        prop::array::uniform::<_, DEVICE_COUNT>(any::<bool>()),
        any::<bool>(),
        prop::array::uniform::<_, DEVICE_COUNT>(fault_code()),
        0..=DEVICE_COUNT,
    )
        .prop_map(|(faulted, system_fault, all, carried)| {
            let mut codes = [None; DEVICE_COUNT];
            for (c, &a) in codes.iter_mut().zip(&all).take(carried) {
                *c = Some(a);
            }
            FaultStatus {
                faulted,
                system_fault,
                codes,
            }
        })
}

fn device_power() -> impl Strategy<Value = DevicePower> {
    (any::<u8>(), any::<bool>()).prop_map(|(device_id, on)| DevicePower { device_id, on })
}

fn trim_move() -> impl Strategy<Value = TrimMove> {
    (any::<u8>(), any::<bool>(), any::<u8>()).prop_map(|(t, on, d)| TrimMove {
        trim_type: TrimType::from_byte(t),
        on,
        direction: TrimDirection::from_byte(d),
    })
}

fn flap_move() -> impl Strategy<Value = FlapMove> {
    (any::<bool>(), any::<u8>()).prop_map(|(on, d)| FlapMove {
        on,
        direction: FlapDirection::from_byte(d),
    })
}

fn wig_wag_mode() -> impl Strategy<Value = WigWagMode> {
    any::<u8>().prop_map(|m| WigWagMode {
        mode: WigWagModeSetting::from_byte(m),
    })
}

fn external_data() -> impl Strategy<Value = ExternalData> {
    (
        any::<u16>(),
        any::<u16>(),
        any::<i32>(),
        any::<i16>(),
        any::<u16>(),
        any::<[bool; 5]>(),
    )
        .prop_map(|(ias, gs, alt, fp, rpm, v)| ExternalData {
            indicated_airspeed: ias,
            ground_speed: gs,
            baro_altitude: alt,
            fuel_pressure: fp,
            rpm,
            valid: ExternalValidity {
                indicated_airspeed: v[0],
                ground_speed: v[1],
                baro_altitude: v[2],
                fuel_pressure: v[3],
                rpm: v[4],
            },
        })
}

/// Any message of the ICD, each type equally likely.
fn message() -> impl Strategy<Value = Message> {
    prop_oneof![
        ping().prop_map(Message::from),
        version().prop_map(Message::from),
        Just(Message::from(SoftwareUpdate)),
        eeprom_erase().prop_map(Message::from),
        device_spec().prop_map(Message::from),
        system_spec().prop_map(Message::from),
        trim_spec().prop_map(Message::from),
        flap_spec().prop_map(Message::from),
        wig_wag_spec().prop_map(Message::from),
        any::<u8>().prop_map(|device_id| Message::from(DeviceSpecQuery { device_id })),
        spec_ack().prop_map(Message::from),
        device_name().prop_map(Message::from),
        any::<u8>().prop_map(|device_id| Message::from(DeviceNameQuery { device_id })),
        device_enable().prop_map(Message::from),
        system_status().prop_map(Message::from),
        device_status().prop_map(Message::from),
        flap_trim_status().prop_map(Message::from),
        fault_status().prop_map(Message::from),
        Just(Message::from(DeviceStatusQuery)),
        device_power().prop_map(Message::from),
        trim_move().prop_map(Message::from),
        flap_move().prop_map(Message::from),
        wig_wag_mode().prop_map(Message::from),
        any::<u8>().prop_map(|device_id| Message::from(DeviceClear { device_id })),
        external_data().prop_map(Message::from),
    ]
}

fn packet() -> impl Strategy<Value = Packet> {
    (any::<u8>(), node(), node(), message()).prop_map(|(cnt, src, dst, message)| Packet {
        cnt,
        src,
        dst,
        message,
    })
}

/// Garbage that cannot start a candidate frame, so the frames around it are the only
/// frames in the stream.
fn quiet_garbage() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(
        any::<u8>().prop_filter("no sync byte", |&b| b != SYNC1),
        0..40,
    )
}

/// `stream` with each packet's frame, then each false header, put in at its place.
fn spliced(
    mut stream: Vec<u8>,
    frames: &[(prop::sample::Index, Packet)],
    headers: &[(prop::sample::Index, Vec<u8>)],
) -> Vec<u8> {
    for (at, p) in frames {
        let i = at.index(stream.len() + 1);
        stream.splice(i..i, p.to_bytes());
    }
    for (at, h) in headers {
        let i = at.index(stream.len() + 1);
        stream.splice(i..i, h.iter().copied());
    }
    stream
}

/// The whole frames among `events`, in order.
fn frames_of(events: &[Seen]) -> Vec<Vec<u8>> {
    events
        .iter()
        .filter_map(|s| match s {
            Seen::Frame(f) => Some(f.clone()),
            _ => None,
        })
        .collect()
}

/// Cuts `bytes` at the given positions (taken modulo the length).
fn split_at(bytes: &[u8], cuts: &[prop::sample::Index]) -> Vec<Vec<u8>> {
    let mut at: Vec<usize> = cuts.iter().map(|i| i.index(bytes.len() + 1)).collect();
    at.push(0);
    at.push(bytes.len());
    at.sort_unstable();
    at.dedup();
    at.windows(2).map(|w| bytes[w[0]..w[1]].to_vec()).collect()
}

/// What the decoder reported, owned, with adjacent skipped runs merged: where a run
/// of garbage is cut depends on the chunking, what was skipped does not.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Seen {
    Frame(Vec<u8>),
    Skipped(Vec<u8>),
    BadChecksum(Vec<u8>),
    BadLength(Vec<u8>),
    Unknown(Vec<u8>),
    Truncated(Vec<u8>),
}

fn seen(seen: &mut Vec<Seen>, e: Event<'_>) {
    let s = match e {
        Event::Frame(f) => {
            // Every frame the decoder passes on must be safe to parse.
            let _ = Packet::parse(&f);
            Seen::Frame(f.as_bytes().to_vec())
        }
        Event::Skipped(b) => {
            assert!(!b.is_empty(), "empty skipped run");
            if let Some(Seen::Skipped(prev)) = seen.last_mut() {
                prev.extend_from_slice(b);
                return;
            }
            Seen::Skipped(b.to_vec())
        }
        Event::BadChecksum(b) => Seen::BadChecksum(b.to_vec()),
        Event::BadLength(b) => Seen::BadLength(b.to_vec()),
        Event::UnknownMessage(b) => Seen::Unknown(b.to_vec()),
        Event::Truncated(b) => Seen::Truncated(b.to_vec()),
    };
    seen.push(s);
}

fn feed(chunks: &[Vec<u8>]) -> (Vec<Seen>, DecoderStats, usize) {
    let mut dec = Decoder::new();
    let mut out: Vec<Seen> = Vec::new();
    for c in chunks {
        dec.push(c, |e| seen(&mut out, e));
        assert!(dec.pending() <= MAX_FRAME);
    }
    (out, dec.stats(), dec.pending())
}

/// As [`feed`], then the end of the input: what `finish` reported, and the stats after.
fn feed_to_end(chunks: &[Vec<u8>]) -> (Vec<Seen>, usize, Vec<Seen>, DecoderStats) {
    let mut dec = Decoder::new();
    let mut out: Vec<Seen> = Vec::new();
    for c in chunks {
        dec.push(c, |e| seen(&mut out, e));
    }
    let pending = dec.pending();
    let mut end = Vec::new();
    dec.finish(|e| seen(&mut end, e));
    assert_eq!(dec.pending(), 0);
    (out, pending, end, dec.stats())
}

/// Bytes the events account for: whole frames and unknown messages, skipped runs and
/// truncated frames, and the first byte of each rejected candidate.
fn accounted(events: &[Seen]) -> u64 {
    events
        .iter()
        .map(|s| match s {
            Seen::Frame(b) | Seen::Skipped(b) | Seen::Unknown(b) | Seen::Truncated(b) => {
                b.len() as u64
            }
            Seen::BadChecksum(_) | Seen::BadLength(_) => 1,
        })
        .sum()
}

/// The header of a frame that is not there: `E7 7E`, an id and a length that are
/// possible or not, and arbitrary count and addresses (which may hold sync bytes too).
fn false_header() -> impl Strategy<Value = Vec<u8>> {
    (0u8..4, any::<prop::sample::Index>(), any::<[u8; 5]>()).prop_map(|(kind, i, b)| {
        let [minor, cnt, src, dst, raw] = b;
        let known = ALL_IDS[i.index(ALL_IDS.len())];
        let rule = lookup(known).unwrap().1;
        let (major, minor, len) = match kind {
            // A known id with a length its table allows.
            0 => {
                let len = match rule {
                    LenRule::Exact(n) => n,
                    LenRule::Between(lo, hi) => lo + raw as usize % (hi - lo + 1),
                };
                (known.major, known.minor, len as u8)
            }
            // A known id with a length its table does not allow.
            1 => {
                let len = (0..=255u8)
                    .map(|k| raw.wrapping_add(k))
                    .find(|&l| !rule.allows(l as usize))
                    .unwrap();
                (known.major, known.minor, len)
            }
            // An id the ICD does not define (majors are 0x10-0x15, icd-reading R5),
            // with a length some message can have, then with one none can.
            2 => (0x20 | minor, minor, raw % (MAX_MESSAGE_LEN as u8 + 1)),
            _ => (
                0x20 | minor,
                minor,
                MAX_MESSAGE_LEN as u8 + 1 + raw % (255 - MAX_MESSAGE_LEN as u8),
            ),
        };
        vec![SYNC1, 0x7E, major, minor, cnt, src, dst, len]
    })
}

/// Whether a candidate starting at `at` that is not a real frame happens to be an
/// intact frame (possible header, good checksum): then it is a frame the stream holds,
/// by chance, and may rightly take the place of real ones. One in 256 false headers.
fn intact_by_chance(stream: &[u8], at: usize) -> bool {
    let rest = &stream[at..];
    if rest.len() < 9 || rest[1] != 0x7E {
        return false;
    }
    let len = rest[7] as usize;
    let possible = match lookup(MessageId::new(rest[2], rest[3])) {
        Some((_, rule)) => rule.allows(len),
        None => len <= MAX_MESSAGE_LEN,
    };
    possible && rest.len() >= 9 + len && FrameRef::parse(&rest[..9 + len]).is_ok()
}

proptest! {
    #[test]
    fn every_message_round_trips(p in packet()) {
        let bytes = p.to_bytes();
        prop_assert_eq!(Packet::parse_bytes(&bytes), Ok(p));
        // The length byte agrees with what was written, and the frame is 8 + len + 1
        // (icd-reading R1).
        prop_assert_eq!(bytes.len(), 8 + bytes[7] as usize + 1);
    }

    #[test]
    fn describe_and_json_cover_every_message(m in message()) {
        let text = describe(&m);
        prop_assert!(!text.is_empty());
        let j = to_json(&m);
        prop_assert!(j.is_object());
        // decode --json puts the header and the capture's columns beside these fields;
        // nothing may shadow them.
        for k in ["name", "cnt", "src", "dst", "time", "dir"] {
            prop_assert!(j.get(k).is_none(), "{} has a {} field", m.name(), k);
        }
    }

    #[test]
    fn decoder_yields_exactly_the_frames_among_quiet_garbage(
        items in prop::collection::vec((quiet_garbage(), packet()), 0..12),
        tail in quiet_garbage(),
        cuts in prop::collection::vec(any::<prop::sample::Index>(), 0..24),
    ) {
        let mut stream = Vec::new();
        let mut frames = Vec::new();
        let mut garbage = 0;
        for (g, p) in &items {
            stream.extend_from_slice(g);
            garbage += g.len();
            let f = p.to_bytes();
            stream.extend_from_slice(&f);
            frames.push(f);
        }
        stream.extend_from_slice(&tail);
        garbage += tail.len();

        let (seen, stats, pending) = feed(&split_at(&stream, &cuts));
        prop_assert_eq!(frames_of(&seen), frames.clone());
        prop_assert!(
            seen.iter().all(|s| matches!(s, Seen::Frame(_) | Seen::Skipped(_))),
            "{:?}", seen
        );
        prop_assert_eq!(pending, 0);
        prop_assert_eq!(stats.frames, frames.len() as u64);
        prop_assert_eq!(stats.skipped_bytes, garbage as u64);
        prop_assert_eq!(stats.bytes_in, stream.len() as u64);
        prop_assert_eq!(stats.errors(), 0);
    }

    #[test]
    fn decoder_survives_anything_and_accounts_for_every_byte(
        bytes in prop::collection::vec(any::<u8>(), 0..2000),
        sprinkle in prop::collection::vec((any::<prop::sample::Index>(), packet()), 0..4),
        cuts in prop::collection::vec(any::<prop::sample::Index>(), 0..24),
    ) {
        // Real frames dropped into the noise give the decoder something to find;
        // sync pairs make candidate headers likely.
        let stream = spliced(bytes, &sprinkle, &[]);
        let (seen, stats, pending) = feed(&split_at(&stream, &cuts));

        let mut frame_bytes = 0u64;
        let mut unknown_bytes = 0u64;
        let mut skipped = 0u64;
        let (mut frames, mut bad_sum, mut bad_len, mut unknown) = (0u64, 0u64, 0u64, 0u64);
        for s in &seen {
            match s {
                Seen::Frame(f) => {
                    frames += 1;
                    frame_bytes += f.len() as u64;
                }
                Seen::Unknown(f) => {
                    unknown += 1;
                    unknown_bytes += f.len() as u64;
                }
                Seen::Skipped(b) => skipped += b.len() as u64,
                // Only the first byte of a rejected candidate is consumed.
                Seen::BadChecksum(_) => {
                    bad_sum += 1;
                    skipped += 1;
                }
                Seen::BadLength(_) => {
                    bad_len += 1;
                    skipped += 1;
                }
                Seen::Truncated(_) => prop_assert!(false, "only finish reports a truncated frame"),
            }
        }
        // A candidate is never held longer than the longest message (rule 1).
        prop_assert!(pending <= 8 + MAX_MESSAGE_LEN + 1);
        prop_assert_eq!(stats.bytes_in, stream.len() as u64);
        prop_assert_eq!(
            stats.bytes_in,
            frame_bytes + stats.skipped_bytes + pending as u64 + unknown_bytes
        );
        prop_assert_eq!(
            (stats.frames, stats.bad_checksum, stats.bad_length, stats.unknown_message),
            (frames, bad_sum, bad_len, unknown)
        );
        prop_assert_eq!(stats.skipped_bytes, skipped);
    }

    #[test]
    fn chunking_does_not_change_what_is_found(
        bytes in prop::collection::vec(
            prop_oneof![4 => any::<u8>(), 1 => Just(0xE7u8), 1 => Just(0x7Eu8)],
            0..1500,
        ),
        sprinkle in prop::collection::vec((any::<prop::sample::Index>(), packet()), 0..4),
        headers in prop::collection::vec((any::<prop::sample::Index>(), false_header()), 0..4),
        cuts in prop::collection::vec(any::<prop::sample::Index>(), 1..24),
    ) {
        let stream = spliced(bytes, &sprinkle, &headers);
        let whole = feed_to_end(std::slice::from_ref(&stream));
        let split = feed_to_end(&split_at(&stream, &cuts));
        prop_assert_eq!(whole, split);
    }

    #[test]
    fn false_headers_never_hide_or_hold_back_a_frame(
        items in prop::collection::vec(
            (quiet_garbage(), prop::option::of((false_header(), any::<prop::sample::Index>())), packet()),
            0..10,
        ),
        tail in quiet_garbage(),
        last in prop::option::of((false_header(), 1usize..=8)),
        cuts in prop::collection::vec(any::<prop::sample::Index>(), 0..24),
    ) {
        // Frames among quiet garbage, false headers put anywhere in the garbage, and
        // the last bytes of the stream possibly a false header or the start of one.
        let mut stream = Vec::new();
        let mut frames = Vec::new();
        let mut starts = Vec::new();
        for (g, fh, p) in &items {
            let mut g = g.clone();
            if let Some((h, at)) = fh {
                let i = at.index(g.len() + 1);
                g.splice(i..i, h.iter().copied());
            }
            stream.extend_from_slice(&g);
            let f = p.to_bytes();
            starts.push(stream.len());
            stream.extend_from_slice(&f);
            frames.push(f);
        }
        stream.extend_from_slice(&tail);
        if let Some((h, n)) = &last {
            stream.extend_from_slice(&h[..*n]);
        }
        // A false header whose claimed bytes happen to check is an intact frame on the
        // wire: nothing can tell it from a real one.
        prop_assume!(!(0..stream.len()).any(|at| {
            stream[at] == SYNC1 && !starts.contains(&at) && intact_by_chance(&stream, at)
        }));

        let chunks = split_at(&stream, &cuts);
        let (events, pending, end, stats) = feed_to_end(&chunks);
        // Every intact frame comes out, in order, while the stream is still live: none
        // waits for the end of the input.
        prop_assert_eq!(&frames_of(&events), &frames);
        prop_assert!(end.iter().all(|s| matches!(s, Seen::Skipped(_) | Seen::Truncated(_))), "{:?}", end);
        prop_assert!(!events.iter().chain(&end).any(|s| matches!(s, Seen::Unknown(_))));
        // Every byte accounted for, and only what is not a frame dropped.
        prop_assert_eq!(accounted(&events) + pending as u64, stream.len() as u64);
        prop_assert_eq!(accounted(&events) + accounted(&end), stream.len() as u64);
        let frame_bytes: usize = frames.iter().map(Vec::len).sum();
        prop_assert_eq!(
            stats.skipped_bytes + stats.truncated_bytes,
            (stream.len() - frame_bytes) as u64
        );
        // What is held at the end is at most the last false header.
        prop_assert!(pending <= last.as_ref().map_or(0, |(_, n)| *n), "{} held", pending);
    }

    #[test]
    fn nothing_pending_hides_a_frame_at_the_end_of_input(
        bytes in prop::collection::vec(
            prop_oneof![4 => any::<u8>(), 1 => Just(0xE7u8), 1 => Just(0x7Eu8)],
            0..600,
        ),
        sprinkle in prop::collection::vec((any::<prop::sample::Index>(), packet()), 0..4),
        headers in prop::collection::vec((any::<prop::sample::Index>(), false_header()), 0..4),
        cut_last in 0usize..80,
        cuts in prop::collection::vec(any::<prop::sample::Index>(), 0..24),
    ) {
        // Noise, real frames and false headers anywhere, and the stream cut short
        // anywhere in its last 80 bytes. After the last read, the held bytes hold no
        // intact known frame; after `finish` nothing is held and every byte is counted.
        let mut stream = spliced(bytes, &sprinkle, &headers);
        stream.truncate(stream.len().saturating_sub(cut_last));
        let chunks = split_at(&stream, &cuts);
        let mut dec = Decoder::new();
        let mut events = Vec::new();
        for c in &chunks {
            dec.push(c, |e| seen(&mut events, e));
        }
        let held = &stream[stream.len() - dec.pending()..];
        let mut inner = Vec::new();
        let mut probe = Decoder::new();
        // The held bytes minus their first, which is the candidate itself, read by a
        // fresh decoder to their end: no known frame among them.
        if held.len() > 1 {
            probe.push(&held[1..], |e| seen(&mut inner, e));
        }
        probe.finish(|e| seen(&mut inner, e));
        prop_assert!(!inner.iter().any(|s| matches!(s, Seen::Frame(_))), "{:02X?} hides {:?}", held, inner);
        let mut end = Vec::new();
        dec.finish(|e| seen(&mut end, e));
        prop_assert_eq!(dec.pending(), 0);
        prop_assert_eq!(accounted(&events) + accounted(&end), stream.len() as u64);
        prop_assert!(end.iter().filter(|s| matches!(s, Seen::Truncated(_))).count() <= 1);
    }
}

//! Throughput of the streaming decoder on what a real unit broadcasts.
//!
//! Each simulated second carries what ICD Table 6 says the VP-X sends: one
//! SYSTEM_STATUS, one DEVICE_STATUS, one FAULT_STATUS (only while a fault exists, so
//! this is the busier case) and ten FLAP_TRIM_STATUS. The bytes arrive in 64-byte
//! chunks because that is roughly what one serial read returns, and chunk edges are
//! where the decoder has to hold a partial frame.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use vpx_efis::protocol::message::{
    DeviceStatus, FaultStatus, FlapTrimStatus, SystemStatus, Tenths,
};
use vpx_efis::protocol::{Decoder, Event, FaultCode, FrameRef, Node, Packet};

/// About 4 MB: large enough that the buffer does not sit in L1/L2 and the figure is
/// the decoder's, not the cache's.
const SECONDS: usize = 10_000;
const CHUNK: usize = 64;

fn capture() -> Vec<u8> {
    let mut out = Vec::new();
    let mut cnt = 0u8;
    let mut push = |out: &mut Vec<u8>, msg: vpx_efis::protocol::Message, i: usize| {
        cnt = cnt.wrapping_add(1);
        // Alternate the two destinations a unit may use for broadcasts (icd-reading R22).
        let dst = if i.is_multiple_of(2) {
            Node::External
        } else {
            Node::Broadcast
        };
        let p = Packet {
            cnt,
            src: Node::Vpx,
            dst,
            message: msg,
        };
        out.extend_from_slice(&p.to_bytes());
    };
    for s in 0..SECONDS {
        let v = (s % 500) as u16;
        push(
            &mut out,
            SystemStatus {
                system_current: Tenths(120 + v),
                main_bus_volts: vpx_efis::protocol::message::SignedTenths(138),
                aux_battery_volts: Tenths(125),
                internal_temp: 31,
                misc: vpx_efis::protocol::message::MiscFlags {
                    wig_wag_active: s.is_multiple_of(3),
                    ..Default::default()
                },
                ..Default::default()
            }
            .into(),
            s,
        );
        let mut on = [false; 31];
        let mut current = [Tenths(0); 31];
        for d in 0..31 {
            on[d] = (d + s) % 4 != 0;
            current[d] = Tenths(((d as u16) * 7 + v) % 150);
        }
        push(&mut out, DeviceStatus { on, current }.into(), s);
        push(
            &mut out,
            FaultStatus::with_faults(&[(9, FaultCode::ShortCircuit)]).into(),
            s,
        );
        for t in 0..10u8 {
            push(
                &mut out,
                FlapTrimStatus {
                    flap_position: 100 + t,
                    pitch_trim_position: 128,
                    roll_trim_position: 127,
                    flap_up: 20,
                    flap_down: 220,
                    flap_midpoint_1: 80,
                    flap_midpoint_2: 160,
                    pitch_trim_up: 240,
                    pitch_trim_down: 10,
                    pitch_trim_neutral: 128,
                    roll_trim_up: 240,
                    roll_trim_down: 10,
                    roll_trim_neutral: 127,
                    ..Default::default()
                }
                .into(),
                s,
            );
        }
    }
    out
}

/// Feeds the capture in `CHUNK`-byte reads; counts the frames `take` accepts.
fn decode(bytes: &[u8], mut take: impl FnMut(FrameRef<'_>) -> bool) -> u64 {
    let mut dec = Decoder::new();
    let mut taken = 0u64;
    for chunk in black_box(bytes).chunks(CHUNK) {
        dec.push(chunk, |e| {
            if let Event::Frame(f) = e
                && take(f)
            {
                taken += 1;
            }
        });
    }
    taken
}

fn bench(c: &mut Criterion) {
    let bytes = capture();
    let frames_per_pass = (SECONDS * 13) as u64;

    let mut g = c.benchmark_group("decoder");
    g.throughput(Throughput::Bytes(bytes.len() as u64));

    // A decoder that silently dropped frames would look fast; each pass refuses that.
    g.bench_function("frames_64B_chunks", |b| {
        b.iter(|| {
            let frames = decode(&bytes, |f| {
                black_box(f);
                true
            });
            assert_eq!(frames, frames_per_pass);
        })
    });

    g.bench_function("frames_and_typed_parse_64B_chunks", |b| {
        b.iter(|| {
            let parsed = decode(&bytes, |f| Packet::parse(&f).map(black_box).is_ok());
            assert_eq!(parsed, frames_per_pass);
        })
    });

    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

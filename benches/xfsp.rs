//! Cost of one full XFSp datagram (as close to 1460 parameter bytes as the mix allows)
//! in each direction.
//!
//! The mix is what the gateway publishes for a VP-X: one BUSSTAT and one ECBSTAT per
//! circuit (BUS format with a short label, 44 bytes each on the wire) and the flap and
//! trim positions (SINT, 16 bytes each). Measured: framing only (`MessageView`, what a
//! receiver that skips most parameters pays), full decode to owned values, emitting a
//! prepared `Message` into a reused buffer, and `Sender::pack` from parameters.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use vpx_efis::xfsp::{
    Bus, CertLevel, EcbFlags, EcbState, Message, MessageView, MsgKind, Parameter, Sender, Value,
    idents,
};

fn vpx_params() -> Vec<Parameter> {
    let mut ps = vec![
        Parameter::new(
            idents::BUSSTAT,
            Value::Bus(Bus {
                state: EcbState::On,
                flags: EcbFlags(EcbFlags::INPUTVOLTS),
                in_volts: 142,
                out_volts: 139,
                draw_amps: 183,
                label: b"MAIN BUS".to_vec(),
                ..Bus::default()
            }),
        ),
        Parameter::new(idents::FLAPPOS, Value::Sint(50_000)),
        Parameter::new(idents::PTRIMPOS, Value::Sint(-1_200)),
        Parameter::new(idents::RTRIMPOS, Value::Sint(300)),
    ];
    let mut circuit = 0u16;
    loop {
        let p = Parameter::new(
            idents::ECBSTAT,
            Value::Bus(Bus {
                state: EcbState::On,
                draw_amps: 10 + i16::try_from(circuit).unwrap_or(0),
                max_amps: 50,
                label: format!("CKT {circuit:02}  ").into_bytes(),
                ..Bus::default()
            }),
        )
        .subunit(circuit);
        let used: usize = ps.iter().map(Parameter::wire_len).sum();
        if used + p.wire_len() > 1460 {
            break;
        }
        ps.push(p);
        circuit += 1;
    }
    ps
}

fn bench(c: &mut Criterion) {
    let params = vpx_params();
    let kind = MsgKind::flight_data(CertLevel::Experimental);
    let datagrams = Sender::new(0x5650, 0).pack(kind, &params).unwrap();
    assert_eq!(datagrams.len(), 1, "the mix must fit one datagram");
    let datagram = datagrams.into_iter().next().unwrap();
    let message = Message::parse(&datagram).unwrap();
    eprintln!(
        "datagram: {} bytes, {} parameters ({} parameter bytes)",
        datagram.len(),
        params.len(),
        datagram.len() - 12
    );

    let mut g = c.benchmark_group("xfsp");
    g.throughput(Throughput::Bytes(datagram.len() as u64));
    g.bench_function("frame (MessageView::parse + walk params)", |b| {
        b.iter(|| {
            let v = MessageView::parse(black_box(&datagram)).unwrap();
            v.params().map(|p| p.data.len()).sum::<usize>()
        })
    });
    g.bench_function("decode (Message::parse, owned values)", |b| {
        b.iter(|| Message::parse(black_box(&datagram)).unwrap())
    });
    let mut out = Vec::with_capacity(1500);
    g.bench_function("emit (Message::emit_into, reused buffer)", |b| {
        b.iter(|| {
            out.clear();
            black_box(&message).emit_into(&mut out).unwrap();
            out.len()
        })
    });
    let mut sender = Sender::new(0x5650, 0);
    g.bench_function("pack (Sender::pack from parameters)", |b| {
        b.iter(|| sender.pack(kind, black_box(&params)).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

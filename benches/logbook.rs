//! The logbook of a busy shop's year: 50 aircraft, 500 checks (30 circuits each) and
//! 200,000 audit entries, written through the real writer thread, then:
//!
//! - an aircraft's latest 50 entries (what `vpx-efis log` lists with no options),
//!   for aircraft picked across the list;
//! - one circuit's current at every check of an aircraft (`log --circuit`).
//!
//! The first should take under 100 ms. The queries are the schema's reference
//! ones (`entries_aircraft_time`, `check_circuits_name`); the set-up prints how long
//! the year took to write.

use std::hint::black_box;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use criterion::{Criterion, criterion_group, criterion_main};
use vpx_efis::audit::Origin;
use vpx_efis::logbook::record::{Check, CheckCircuit, Unit};
use vpx_efis::logbook::{Entry, Logbook, Mode, Recorder, What};
use vpx_efis::protocol::message::{DevicePower, Packet};

const AIRCRAFT: usize = 50;
const CHECKS: usize = 500;
const AUDIT: usize = 200_000;
const CIRCUITS: u8 = 30;

fn registration(i: usize) -> String {
    format!("N{:03}AB", i)
}

fn circuit_name(c: u8) -> String {
    format!("Circuit {c}")
}

/// Writes the year into `path`, aircraft by aircraft (one recorder each, as one
/// page session per aircraft would): its share of checks and audit entries.
fn fill(path: &std::path::Path) {
    let year = UNIX_EPOCH + Duration::from_secs(1_767_225_600); // 2026-01-01
    for a in 0..AIRCRAFT {
        let (r, thread) = Recorder::start(path.to_path_buf(), Some(registration(a))).unwrap();
        r.unit(Unit {
            hardware: "VP-X Pro".into(),
            software: "2.1".into(),
            names: (0..CIRCUITS).map(circuit_name).collect(),
        });
        let t = |i: usize| year + Duration::from_secs((i as u64) * 150 + a as u64);
        for c in 0..CHECKS / AIRCRAFT {
            r.record(Entry {
                at: t(c * 2000),
                origin: Origin::Check.word(),
                summary: "check: 30 passed".into(),
                what: What::Check(Box::new(Check {
                    tally: "30 passed".into(),
                    circuits: (0..CIRCUITS)
                        .map(|d| CheckCircuit {
                            device: d,
                            name: circuit_name(d),
                            pin: format!("{d}A"),
                            amps: Some(f64::from(d) / 4.0 + c as f64 / 10.0),
                            verdict: "passed".into(),
                            finding: "within its breaker".into(),
                            ..CheckCircuit::default()
                        })
                        .collect(),
                    ..Check::default()
                })),
            });
        }
        let power = |n: usize| {
            Packet::request(
                (n % 256) as u8,
                DevicePower {
                    device_id: (n % 30) as u8,
                    on: n.is_multiple_of(2),
                },
            )
        };
        for n in 0..AUDIT / AIRCRAFT {
            r.command(Origin::Key, &power(n), Ok(()));
        }
        assert!(r.flush(Duration::from_secs(600)));
        drop(r);
        thread.join();
    }
    let _ = SystemTime::now();
}

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    let started = Instant::now();
    fill(&path);
    let book = Logbook::open(&path, Mode::ReadOnly).unwrap();
    let n: i64 = book
        .conn()
        .query_row("SELECT count(*) FROM entries", [], |r| r.get(0))
        .unwrap();
    let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    eprintln!(
        "logbook: {n} entries written in {:.1} s; the file is {:.1} MB",
        started.elapsed().as_secs_f64(),
        bytes as f64 / 1e6
    );
    assert_eq!(n as usize, CHECKS + AUDIT);

    let mut latest = book
        .conn()
        .prepare(
            "SELECT time, origin, kind, summary FROM entries
             WHERE aircraft = ?1 ORDER BY time DESC, id DESC LIMIT 50",
        )
        .unwrap();
    let mut i = 0usize;
    c.bench_function("logbook: an aircraft's latest 50 entries", |b| {
        b.iter(|| {
            i = (i + 17) % AIRCRAFT;
            let rows: Vec<(String, String, String, String)> = latest
                .query_map([registration(i)], |r| {
                    Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?))
                })
                .unwrap()
                .map(Result::unwrap)
                .collect();
            assert_eq!(rows.len(), 50);
            black_box(rows)
        })
    });

    let mut circuit = book
        .conn()
        .prepare(
            "SELECT e.time, c.amps FROM check_circuits c JOIN entries e ON e.id = c.entry
             WHERE c.name = ?1 AND e.aircraft = ?2 ORDER BY e.time",
        )
        .unwrap();
    c.bench_function("logbook: a circuit's current at every check", |b| {
        b.iter(|| {
            i = (i + 17) % AIRCRAFT;
            let rows: Vec<(String, Option<f64>)> = circuit
                .query_map([circuit_name(12), registration(i)], |r| {
                    Ok((r.get(0)?, r.get(1)?))
                })
                .unwrap()
                .map(Result::unwrap)
                .collect();
            assert_eq!(rows.len(), CHECKS / AIRCRAFT);
            black_box(rows)
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(Duration::from_secs(5));
    targets = bench
}
criterion_main!(benches);

//! The laptop's cost of one signed request from the phone (under 50 µs):
//! the verifier's whole check of a typical command (MAC in constant time, age,
//! counter), and of a refused forgery, which costs the same MAC.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use vpx_efis::remote::signing::{Claim, Request, Verifier, sign};

const KEY: [u8; 16] = *b"0123456789abcdef";
const SESSION: &str = "00112233445566778899aabbccddeeff";
const PATH: &str = "/api/device/17/power";
const BODY: &[u8] = b"{\"on\":true}";
const REQUEST: Request = Request {
    method: "POST",
    path: PATH,
    body: BODY,
};

fn claim(counter: u64) -> Claim {
    Claim {
        session: SESSION.into(),
        counter,
        time_ms: 1_000,
        mac: sign(&KEY, SESSION, counter, 1_000, REQUEST),
    }
}

fn verify(c: &mut Criterion) {
    // Signed ahead: the bench times the check, not the phone's signing.
    let claims: Vec<Claim> = (1..=200_000).map(claim).collect();
    c.bench_function("remote: verify a signed command", |b| {
        let mut v = Verifier::new(&KEY);
        let mut next = claims.iter().cycle();
        let mut fresh = 0u64;
        b.iter(|| {
            let c = next.next().unwrap();
            // Past the end of the list the counters repeat: a new verifier takes them.
            if c.counter == 1 && fresh > 0 {
                v = Verifier::new(&KEY);
            }
            fresh += 1;
            black_box(v.verify(black_box(c), REQUEST, 1_050))
        })
    });
    let forged = Claim {
        mac: "0".repeat(64),
        ..claim(1)
    };
    c.bench_function("remote: refuse a forged command", |b| {
        let mut v = Verifier::new(&KEY);
        b.iter(|| black_box(v.verify(black_box(&forged), REQUEST, 1_050)))
    });
}

criterion_group!(benches, verify);
criterion_main!(benches);

//! The page's end-to-end timings through a real pseudo-terminal with the virtual VP-X
//! on the other side (the same rig as `tests/page_e2e.rs`):
//!
//! - key-to-wire: from handing a key to the page until its DEVICE_POWER frame has
//!   crossed the pty (goal ≤ 5 ms);
//! - move-stream interval: the gap between consecutive TRIM_MOVE frames on the wire
//!   while a trim key is held (must never exceed 250 ms; the streamer aims at 200 ms).
//!   Criterion's per-iteration statistics are the interval distribution.
//!
//! The rig needs a pseudo-terminal, which only Unix has: elsewhere this bench is empty.
#![cfg_attr(not(unix), allow(unused_imports))]

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use crossterm::event::{KeyCode, KeyEventKind};
use vpx_efis::protocol::message::Message;
use vpx_efis::ui::state::ReleaseMode;

#[cfg(unix)]
#[path = "../tests/page_rig/mod.rs"]
mod page_rig;
#[cfg(unix)]
use page_rig::Rig;

#[cfg(unix)]
fn wait_for_frame(rig: &Rig, from: usize, pick: impl Fn(&Message) -> bool) -> Instant {
    let end = Instant::now() + Duration::from_secs(2);
    loop {
        if let Some((at, _)) = rig.sent(from).into_iter().find(|(_, p)| pick(&p.message)) {
            return at;
        }
        assert!(Instant::now() < end, "the frame never reached the wire");
        std::thread::yield_now();
    }
}

#[cfg(unix)]
fn key_to_wire(c: &mut Criterion) {
    let mut rig = Rig::new(ReleaseMode::KeyRelease);
    rig.select(9);
    let mut on = false;
    c.bench_function("key to wire: DEVICE_POWER through a pty", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                on = !on;
                let from = rig.wire_len();
                let pressed = Instant::now();
                rig.key(
                    KeyCode::Char(if on { 'o' } else { 'f' }),
                    KeyEventKind::Press,
                );
                let at = wait_for_frame(&rig, from, |m| matches!(m, Message::DevicePower(_)));
                total += at.saturating_duration_since(pressed);
            }
            total
        })
    });
}

#[cfg(unix)]
fn move_stream_interval(c: &mut Criterion) {
    let mut rig = Rig::new(ReleaseMode::KeyRelease);
    rig.select(30);
    let mut group = c.benchmark_group("move stream");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(8));
    group.bench_function("interval between TRIM_MOVEs on the wire", |b| {
        b.iter_custom(|iters| {
            // A fresh press per batch keeps each run well under the 10 s cap.
            let from = rig.wire_len();
            rig.key(KeyCode::Char('u'), KeyEventKind::Press);
            let moves_on = |rig: &Rig| {
                rig.sent(from)
                    .into_iter()
                    .filter(|(_, p)| matches!(p.message, Message::TrimMove(m) if m.on))
                    .map(|(at, _)| at)
                    .collect::<Vec<_>>()
            };
            let end = Instant::now() + Duration::from_secs(30);
            let mut seen = moves_on(&rig);
            let mut last_repeat = Instant::now();
            while seen.len() < iters as usize + 1 {
                assert!(Instant::now() < end, "the stream stopped");
                // As a kitty-protocol terminal does while the key is held.
                if last_repeat.elapsed() >= Duration::from_millis(33) {
                    rig.key(KeyCode::Char('u'), KeyEventKind::Repeat);
                    last_repeat = Instant::now();
                }
                rig.app
                    .pump_until(Instant::now() + Duration::from_millis(10));
                seen = moves_on(&rig);
            }
            rig.key(KeyCode::Char('u'), KeyEventKind::Release);
            rig.app
                .pump_until(Instant::now() + Duration::from_millis(300));
            let worst = seen
                .windows(2)
                .map(|w| w[1] - w[0])
                .max()
                .unwrap_or_default();
            assert!(
                worst <= Duration::from_millis(250),
                "interval {worst:?} on the wire"
            );
            seen[iters as usize] - seen[0]
        })
    });
    group.finish();
}

#[cfg(unix)]
criterion_group!(benches, key_to_wire, move_stream_interval);
#[cfg(unix)]
criterion_main!(benches);
#[cfg(not(unix))]
fn main() {}

//! The page's end-to-end timings through a real pseudo-terminal with the virtual VP-X
//! on the other side (the same rig as `tests/page_e2e.rs`):
//!
//! - key-to-wire: from handing a key to the page until its DEVICE_POWER frame has
//!   crossed the pty (goal ≤ 5 ms);
//! - move-stream interval: the gap between consecutive TRIM_MOVE frames on the wire
//!   while a trim key is held with X's default auto-repeat and the page redraws as it
//!   would (must never exceed 250 ms; the streamer resends every 125 ms and aims at
//!   no interval over 220 ms), once on a quiet machine and once with two busy
//!   processes competing for the cores. Criterion gives the mean; the distribution
//!   (p50, p90, p99, max) is printed after each.
//!
//! The rig needs a pseudo-terminal, which only Unix has: elsewhere this bench is empty.
#![cfg_attr(not(unix), allow(unused_imports))]

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use crossterm::event::{KeyCode, KeyEventKind};
#[cfg(unix)]
use ratatui::Terminal;
#[cfg(unix)]
use ratatui::backend::TestBackend;
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
/// Two processes that only burn CPU, one per core of a 2-core machine, so the page's
/// threads have to compete for every wake-up. Killed (by their own ids) on drop.
struct Busy(Vec<std::process::Child>);

#[cfg(unix)]
impl Busy {
    fn start(n: usize) -> Busy {
        Busy(
            (0..n)
                .map(|_| {
                    std::process::Command::new("sh")
                        .args(["-c", "while :; do :; done"])
                        .spawn()
                        .expect("a busy loop")
                })
                .collect(),
        )
    }
}

#[cfg(unix)]
impl Drop for Busy {
    fn drop(&mut self) {
        for c in &mut self.0 {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

#[cfg(unix)]
/// Prints the distribution of the intervals seen (the figures the README quotes).
fn report(label: &str, intervals: &mut [Duration]) {
    if intervals.is_empty() {
        return;
    }
    intervals.sort();
    let at = |q: f64| intervals[((intervals.len() - 1) as f64 * q).round() as usize];
    let over = |ms| {
        intervals
            .iter()
            .filter(|d| **d > Duration::from_millis(ms))
            .count()
    };
    eprintln!(
        "\n{label}: {} intervals, min {:.1?} p50 {:.1?} p90 {:.1?} p99 {:.1?} max {:.1?}, over 220 ms: {}, over 250 ms: {}",
        intervals.len(),
        at(0.0),
        at(0.5),
        at(0.9),
        at(0.99),
        intervals[intervals.len() - 1],
        over(220),
        over(250),
    );
}

#[cfg(unix)]
/// What one hold put on the wire.
struct Hold {
    /// Gaps between consecutive move messages of the same run.
    intervals: Vec<Duration>,
    /// Stops that went out while the key was still held (a stutter).
    stutters: usize,
}

#[cfg(unix)]
/// Holds pitch-trim the way X's default auto-repeat does (660 ms, then every 40 ms)
/// while the page redraws as often as it would, for at least `n` intervals on the wire
/// and at least 2.4 s (as a person trims), then lets go and waits for the stop. It
/// trims toward the side with more room: the page stops a run at the trim's endpoint
/// (`control::endpoints`), which would end a hold before its `n` intervals.
fn hold_for(rig: &mut Rig, n: usize) -> Hold {
    let key = {
        let m = rig.app.model();
        let ft = m
            .live_flap_trim(Instant::now())
            .expect("a live trim position");
        let up_room = ft.pitch_trim_position.abs_diff(ft.pitch_trim_up);
        let down_room = ft.pitch_trim_position.abs_diff(ft.pitch_trim_down);
        if up_room > down_room { 'u' } else { 'd' }
    };
    let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
    let from = rig.wire_len();
    let moves = |rig: &Rig| {
        rig.sent(from)
            .into_iter()
            .filter_map(|(at, p)| match p.message {
                Message::TrimMove(m) => Some((at, m.on)),
                _ => None,
            })
            .collect::<Vec<_>>()
    };
    let pressed = Instant::now();
    rig.key(KeyCode::Char(key), KeyEventKind::Press);
    let end = pressed + Duration::from_secs(30);
    let mut next_repeat = pressed + Duration::from_millis(660);
    while moves(rig).len() < n.max(16) + 1 {
        assert!(Instant::now() < end, "the stream stopped");
        if Instant::now() >= next_repeat {
            rig.key(KeyCode::Char(key), KeyEventKind::Press);
            next_repeat += Duration::from_millis(40);
        }
        // The UI loop's own work: a full redraw whenever one is due.
        let _ = rig.app.draw_if_needed(&mut term, Instant::now());
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(5));
    }
    let held = moves(rig);
    // Let go, and wait for the stop before the next hold.
    let let_go = Instant::now();
    while moves(rig).len() == held.len() || moves(rig).last().is_some_and(|m| m.1) {
        assert!(let_go.elapsed() < Duration::from_secs(2), "no stop");
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(10));
    }
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(100));
    Hold {
        intervals: held
            .windows(2)
            .filter(|w| w[0].1)
            .map(|w| w[1].0 - w[0].0)
            .collect(),
        stutters: held.iter().filter(|m| !m.1).count(),
    }
}

#[cfg(unix)]
fn move_stream_interval(c: &mut Criterion) {
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.select(30);
    let mut group = c.benchmark_group("move stream");
    group.sample_size(10);
    for busy in [0, 2] {
        let mut all = Vec::new();
        let (mut stutters, mut holds) = (0, 0);
        let name = if busy == 0 {
            "interval between TRIM_MOVEs on the wire".to_string()
        } else {
            format!("interval between TRIM_MOVEs on the wire, {busy} busy processes")
        };
        let load = Busy::start(busy);
        group.bench_function(&name, |b| {
            b.iter_custom(|iters| {
                // A fresh hold per batch (at most 20 moves, about 3.2 s) keeps each
                // run under the 10 s cap, and within the 79 counts the trim travels
                // in that time from any position toward its side with more room
                // (95 counts or more of its 190). Every interval of every hold goes into the
                // distribution; criterion times the first `iters` of them.
                let mut total = Duration::ZERO;
                let mut left = iters as usize;
                while left > 0 {
                    let n = left.min(20);
                    // Not asserted here: the fake-clock tests hold the 250 ms rule;
                    // this measures what a real, loaded machine does, over 250 ms
                    // included (counted in the report).
                    let hold = hold_for(&mut rig, n);
                    let taken = hold.intervals.len().min(n);
                    total += hold.intervals.iter().take(n).sum::<Duration>();
                    all.extend(hold.intervals);
                    stutters += hold.stutters;
                    holds += 1;
                    left -= taken.max(1);
                }
                total
            })
        });
        drop(load);
        report(&name, &mut all);
        eprintln!("{holds} holds, {stutters} stopped while the key was held");
    }
    group.finish();
}

#[cfg(unix)]
criterion_group!(benches, key_to_wire, move_stream_interval);
#[cfg(unix)]
criterion_main!(benches);
#[cfg(not(unix))]
fn main() {}

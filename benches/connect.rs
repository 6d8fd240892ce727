//! The page's connect time at the real line rate: from opening the port to a fully
//! named and configured device list (a DEVICE_STATUS heard, and every DEVICE_SPEC,
//! DEVICE_NAME, DEVICE_ENABLE, FLAP/TRIM/SYSTEM/WIG_WAG spec answered:
//! `Setting::all()`), against `vpx-efis sim --pty` as a user runs it, a second
//! process paced at 5760 bytes a second each way (57600 baud, 8N1). The goal is
//! under 1 s; the answers alone take 0.28 s of line (`app::queries`).
//! Each sample is a fresh sim process and a fresh page; the distribution (min,
//! median, max) is printed after the run.
//!
//! `cargo bench --bench connect -- --warm-up-time 1 --measurement-time 3`
//!
//! The rig needs a pseudo-terminal, which only Unix has: elsewhere this bench is empty.
#![cfg_attr(not(unix), allow(unused_imports, dead_code))]

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use vpx_efis::app::{App, AppOptions};
use vpx_efis::link;
use vpx_efis::model::{Model, Setting, Source};

// `vpx-efis sim` as its own process, as the tests start it.
#[path = "../tests/common/process.rs"]
#[allow(dead_code)]
mod process;

/// What the device list needs before it is whole: live device states and every
/// setting the page reads at connect.
fn named_and_configured(m: &Model, now: Instant) -> bool {
    m.live_devices(now).is_some() && Setting::all().all(|s| m.setting_heard(s).is_some())
}

/// One connect: a fresh sim, then the page opens its port; the time until the list
/// is whole.
fn connect_once(extra: &[&str]) -> Duration {
    let sim = process::sim(&[&["--pty", "--scenario", "install"][..], extra].concat());
    // The unit is up and broadcasting before the page comes, as in an aircraft.
    std::thread::sleep(Duration::from_millis(300));
    let opened = Instant::now();
    let mut app = App::new(
        Source::Serial {
            path: sim.line.clone(),
        },
        link::serial_connector(sim.line.clone().into(), 57_600),
        AppOptions::default(),
    );
    let end = opened + Duration::from_secs(10);
    loop {
        let now = Instant::now();
        if named_and_configured(&app.model(), now) {
            return now - opened;
        }
        assert!(now < end, "no whole device list within 10 s");
        app.pump_until(now + Duration::from_millis(2));
    }
}

fn report(name: &str, all: &mut [Duration]) {
    all.sort();
    let at = |q: f64| all[((all.len() - 1) as f64 * q).round() as usize];
    eprintln!(
        "{name}: {} connects, min {:?}, median {:?}, max {:?}",
        all.len(),
        all[0],
        at(0.5),
        all[all.len() - 1]
    );
}

fn connect(c: &mut Criterion) {
    let mut group = c.benchmark_group("connect");
    group.sample_size(10);
    for (name, extra) in [
        ("open port to named, configured list, paced sim", &[][..]),
        (
            "open port to named, configured list, --no-pace",
            &["--no-pace"][..],
        ),
    ] {
        let mut all = Vec::new();
        group.bench_function(name, |b| {
            b.iter_custom(|iters| {
                (0..iters)
                    .map(|_| {
                        let d = connect_once(extra);
                        all.push(d);
                        d
                    })
                    .sum()
            })
        });
        report(name, &mut all);
    }
    group.finish();
}

#[cfg(unix)]
criterion_group!(benches, connect);
#[cfg(unix)]
criterion_main!(benches);
#[cfg(not(unix))]
fn main() {}

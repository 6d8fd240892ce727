//! Every loop in the product that sleeps until a computed deadline, checked on a fake
//! clock: after the poll it makes at `now`, the next deadline is later than `now`. A
//! deadline at or before `now` makes a `select!` with `default(deadline - now)` return
//! at once, forever: a loop spinning a whole core.
//!
//! The loops, and where each is checked:
//! - the virtual VP-X's run loop (`sim::run_loop`): [`sim_unit`] here;
//! - the query pacer (page and gateway): [`query_pacer`] here;
//! - the motor streamer (page keys and network requests): [`motor_streamer`] here;
//! - the gateway's air data and motor drive: [`air_data`], [`motor_drive`] here;
//! - the page's re-reads of settings left unknown (`model::Rereader`):
//!   [`rereader`] here;
//! - the XFSp publisher: `xfsp::publish` unit tests (disabled pins, stale positions);
//! - the gateway (`Gateway::next_deadline`, headless loop and page):
//!   `tests/xfsp_gateway_core.rs`, `after_every_tick_the_gateway_deadline_is_in_the_future`;
//! - the page's own loop (`App::next_deadline`: redraw, notice, controller, pacer,
//!   setup, gateway): `tests/page_xfsp.rs`, against a unit with most pins disabled.

use std::time::{Duration, Instant};

use vpx_efis::app::QueryPacer;
use vpx_efis::control::{Direction, MotorStreamer, StreamerConfig};
use vpx_efis::model::{Model, Motor, Source, TrimKind};
use vpx_efis::sim::{self, SimOptions};
use vpx_efis::ui::state::ReleaseMode;

#[path = "common/live_unit.rs"]
#[allow(dead_code)]
mod live_unit;

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// The sim's unit over a simulated minute and a half of every shipped scenario (their
/// timelines fire, loop, go silent and power-cycle), fed nothing.
#[test]
fn sim_unit() {
    for (name, _) in sim::scenario::BUILT_IN {
        let t0 = Instant::now();
        let opts = SimOptions::new(sim::load_scenario(name).unwrap());
        let mut unit = sim::build_unit(&opts, t0);
        let mut now = t0;
        let mut ticks = 0u32;
        while now < t0 + ms(90_000) {
            unit.tick(now);
            unit.take_output();
            ticks += 1;
            let next = unit.next_deadline();
            assert!(
                next > now,
                "{name}: tick at +{:?} left a deadline not ahead",
                now - t0
            );
            now = next;
        }
        // 10 Hz FLAP_TRIM_STATUS, 1 Hz status, and the timeline's events.
        assert!(ticks < 90 * 12, "{name}: {ticks} ticks in 90 s");
    }
}

#[test]
fn query_pacer() {
    let t0 = Instant::now();
    let mut p = QueryPacer::default();
    assert_eq!(
        p.next_deadline(),
        None,
        "nothing to ask before a connection"
    );
    p.start(t0);
    // A unit that answers nothing: every request waits out its time.
    let m = model();
    let mut now = t0;
    let mut cnt = 0u8;
    let mut polls = 0;
    while now < t0 + ms(150_000) {
        p.due(now, &m, || {
            cnt = cnt.wrapping_add(1);
            cnt
        });
        polls += 1;
        let next = p.next_deadline().expect("the refresh is always scheduled");
        assert!(next > now, "poll at +{:?}", now - t0);
        now = next;
    }
    // Three rounds (connect and two refreshes) of four requests per wait, then
    // nothing but waiting.
    assert!(polls < 3 * 30, "{polls} polls");
    p.stop();
    assert_eq!(p.next_deadline(), None);
}

fn model() -> Model {
    Model::new(Source::Simulated {
        scenario: "test".into(),
    })
}

/// A run held on both kinds of keyboard, to its cap; and one whose key stops repeating.
#[test]
fn motor_streamer() {
    for mode in [ReleaseMode::KeyRelease, ReleaseMode::AutoRepeat] {
        for keep_repeating in [true, false] {
            let t0 = Instant::now();
            let mut s = MotorStreamer::new(StreamerConfig {
                release_mode: mode,
                max_run: Duration::from_secs(3),
                ..StreamerConfig::default()
            });
            s.press(t0, Motor::Trim(TrimKind::Pitch), Direction::Up);
            assert!(s.running_key().is_some());
            let mut now = t0;
            let mut last_repeat = t0;
            while let Some(deadline) = s.next_deadline() {
                assert!(deadline > now, "{mode:?}: at +{:?}", now - t0);
                now = deadline;
                if keep_repeating && now >= last_repeat + ms(30) {
                    // The terminal's auto-repeat (or kitty's repeat events).
                    s.repeat(now, Motor::Trim(TrimKind::Pitch), Direction::Up);
                    last_repeat = now;
                }
                s.tick(now);
                assert!(now < t0 + ms(5000), "{mode:?}: the run never ended");
            }
            assert!(s.running_key().is_none());
        }
    }
}

#[test]
fn air_data() {
    use vpx_efis::xfsp::consume::AirData;
    use vpx_efis::xfsp::{Parameter, Value, idents};
    let t0 = Instant::now();
    let mut a = AirData::default();
    assert_eq!(a.next_deadline(), None, "nothing heard, nothing scheduled");
    a.offer(7, &Parameter::new(idents::IAS, Value::Sint(90)), t0);
    let mut now = t0;
    while now < t0 + ms(10_000) {
        a.due(now);
        let next = a.next_deadline().unwrap();
        assert!(next > now);
        // Late by a random-ish amount, as a loaded machine would be.
        now = next + ms((now - t0).as_millis() as u64 % 170);
    }
}

#[test]
fn motor_drive() {
    use vpx_efis::protocol::message::{DeviceStatus, Packet};
    use vpx_efis::protocol::{device::DEVICE_COUNT, message::Tenths};
    use vpx_efis::xfsp::drive::MotorDrive;
    let t0 = Instant::now();
    let mut m = model();
    let mut drive = MotorDrive::default();
    let mut ctl = vpx_efis::control::Controller::default();
    let feed = |m: &mut Model, at: Instant, pos: u8| {
        let d = DeviceStatus {
            on: [false; DEVICE_COUNT],
            current: [Tenths(0); DEVICE_COUNT],
        };
        m.apply_packet(at, &Packet::from_vpx(1, d));
        m.apply_packet(at, &Packet::from_vpx(3, live_unit::flaps_at(pos)));
    };
    feed(&mut m, t0, 40);
    drive.request(Motor::Flaps, 100_000, 1, Some(ms(600)), t0);
    drive.request(Motor::Trim(TrimKind::Pitch), 10_000, 1, Some(ms(900)), t0);
    let mut now = t0;
    let mut ticks = 0;
    while now < t0 + ms(3000) {
        feed(&mut m, now, 40 + ((now - t0).as_millis() / 50) as u8);
        drive.tick(&mut ctl, &mut m, now);
        ticks += 1;
        // The page's loop sleeps until the first of the two.
        match [drive.next_deadline(), ctl.next_deadline()]
            .into_iter()
            .flatten()
            .min()
        {
            Some(next) => {
                assert!(next > now, "tick at +{:?}", now - t0);
                now = next;
            }
            None => break,
        }
    }
    assert!(ticks > 2, "the flaps ran");
    assert!(
        drive.running(&ctl).is_none() && ctl.running().is_none(),
        "stopped once the requests expired"
    );
    assert_eq!(
        drive.counts().refused,
        1,
        "the pitch trim had no scale: {:#?}",
        m.events
    );
}

/// A restore cut short leaves many settings unknown: they are asked a batch at a time
/// with a gap between batches, then paced, and the deadline is always ahead.
#[test]
fn rereader() {
    use vpx_efis::model::Setting;
    use vpx_efis::model::{REREAD_BATCH, REREAD_BATCH_GAP, Rereader};
    let t0 = Instant::now();
    let mut m = model();
    for id in 4..=20u8 {
        m.mark_unknown(Setting::DeviceSpec(id), t0);
    }
    let mut r = Rereader::default();
    let mut now = t0;
    let mut sent: Vec<(Instant, usize)> = Vec::new();
    while now < t0 + ms(20_000) {
        let q = r.due(&m, now);
        if !q.is_empty() {
            sent.push((now, q.len()));
        }
        let next = r.next_deadline(&m, now).expect("settings still unknown");
        assert!(next > now, "poll at +{:?}", now - t0);
        now = next;
    }
    assert!(sent.iter().all(|&(_, n)| n <= REREAD_BATCH), "{sent:?}");
    for w in sent.windows(2) {
        assert!(w[1].0 - w[0].0 >= REREAD_BATCH_GAP, "{sent:?}");
    }
    // All seventeen asked within the first half second, then every few seconds.
    let first: usize = sent
        .iter()
        .filter(|(t, _)| *t < t0 + ms(500))
        .map(|(_, n)| n)
        .sum();
    assert_eq!(first, 17, "{sent:?}");
}

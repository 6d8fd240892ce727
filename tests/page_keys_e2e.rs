//! Motor keys end to end, through a real pseudo-terminal with the virtual VP-X (see
//! `page_rig`): X's default auto-repeat, and a terminal too small to show the page.
//!
//! These measure real time, so they live in a binary of their own and take turns (a
//! lock), instead of competing with `page_e2e`'s rigs for a loaded machine's cores.
//! The rig needs a pseudo-terminal, which only Unix has.
#![cfg(unix)]

use std::sync::Mutex;
use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEventKind};
use vpx_efis::protocol::Packet;
use vpx_efis::protocol::message::{Message, TrimMove};
use vpx_efis::ui::state::ReleaseMode;

mod page_rig;
use page_rig::*;

mod common;
use common::screen::{line_of, text};

static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn trim_moves(rig: &Rig, from: usize) -> Vec<(Instant, TrimMove)> {
    rig.sent(from)
        .into_iter()
        .filter_map(|(at, p)| match p.message {
            Message::TrimMove(m) => Some((at, m)),
            _ => None,
        })
        .collect()
}

/// The pitch trim's moves since `from` hold a stop within `limit` of `cause` (at
/// `since`), and nothing after the stop.
#[track_caller]
fn assert_stopped_within(rig: &Rig, from: usize, cause: &str, since: Instant, limit: Duration) {
    let moves = trim_moves(rig, from);
    let (stop_at, _) = *moves
        .iter()
        .find(|(_, m)| !m.on)
        .unwrap_or_else(|| panic!("no stop after {cause}: {moves:?}"));
    assert!(
        stop_at - since <= limit,
        "stop {:?} after {cause}",
        stop_at - since
    );
    assert!(
        moves.last().is_some_and(|(_, m)| !m.on),
        "nothing after the stop: {moves:?}"
    );
}

/// Repeats 40 ms apart delivered at worst this far apart: the machine woke the test's
/// own thread within 20 ms, and will have woken the page's as promptly.
const QUIET_DELIVERY: Duration = Duration::from_millis(60);

/// What one hold through the pty gave.
struct Hold {
    moves: Vec<(Instant, TrimMove)>,
    last_repeat: Instant,
    /// The longest gap between the repeats this test actually delivered. A loaded
    /// machine can hold the test's own thread back; past the page's end gap that is a
    /// key let go, not a terminal's auto-repeat.
    worst_delivery: Duration,
    /// How long after the press this test delivered the first repeat.
    first_delivery: Duration,
    /// Every repeat came within the page's wait for it as it stood then (the
    /// first-repeat window, then the end gap it was learning), and none over 100 ms
    /// after the one before: as X delivers them, as far as the page can tell.
    delivered: bool,
}

/// Less than the two threads' readings of the clock for one key could be apart.
const CLOCK_SLACK: Duration = Duration::from_millis(10);

/// Holds `u` on the pitch-trim row as X's default auto-repeat does: the first repeat
/// 660 ms after the press, then one every 40 ms, for 2.5 s.
fn hold_x_default(rig: &mut Rig) -> Hold {
    let from = rig.wire_len();
    // How long the page waits for the next key before it takes the key as let go.
    let waits = |rig: &Rig, first: bool| {
        let t = rig
            .app
            .control_state()
            .repeat
            .expect("a live page judges repeats");
        if first { t.first_window } else { t.end_gap }
    };
    let mut wait = waits(rig, true);
    let start = Instant::now();
    rig.key(KeyCode::Char('u'), KeyEventKind::Press);
    let mut next = start + Duration::from_millis(660);
    let mut last_repeat = start;
    let mut worst_delivery = Duration::ZERO;
    let mut first_delivery = Duration::ZERO;
    let mut delivered = true;
    while next < start + Duration::from_millis(2500) {
        rig.app.pump_until(next);
        rig.key(KeyCode::Char('u'), KeyEventKind::Press);
        let now = Instant::now();
        let gap = now - last_repeat;
        if last_repeat > start {
            worst_delivery = worst_delivery.max(gap);
            delivered &= gap <= Duration::from_millis(100);
        } else {
            first_delivery = gap;
        }
        delivered &= gap + CLOCK_SLACK <= wait;
        last_repeat = now;
        next += Duration::from_millis(40);
        // What the page learned from this repeat is in force for the next.
        rig.app.tick(Instant::now());
        wait = waits(rig, false);
    }
    rig.app.pump_until(last_repeat + Duration::from_millis(500));
    Hold {
        moves: trim_moves(rig, from),
        last_repeat,
        worst_delivery,
        first_delivery,
        delivered,
    }
}

/// X's default auto-repeat through the pty, on a page that has learned nothing yet:
/// the first repeat after 660 ms, then one every 40 ms. One continuous run, no gap
/// over 220 ms, and the stop within 150 ms of the last repeat, because the page
/// learned the 40 ms interval during the hold. The page then shows what it learned.
///
/// A hold during which this test itself could not deliver the repeats on time (a
/// gap over 100 ms between them, or a repeat later than the page waited for it) did not
/// test the page and is tried again, up to five times; the page is judged on a hold
/// that was delivered as X delivers it.
#[test]
fn x_default_repeat_is_one_run_and_stops_within_150_ms_of_the_last_repeat() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.select(30);
    let mut hold = hold_x_default(&mut rig);
    for _ in 0..4 {
        if hold.delivered {
            break;
        }
        eprintln!(
            "the test delivered repeats up to {:?} apart, the first after {:?}, later than \
             the page waits for them; holding again",
            hold.worst_delivery, hold.first_delivery
        );
        hold = hold_x_default(&mut rig);
    }
    assert!(
        hold.delivered,
        "the machine is too loaded to deliver repeats every 40 ms: {:?} apart, the first \
         after {:?}",
        hold.worst_delivery, hold.first_delivery
    );
    let Hold {
        ref moves,
        last_repeat,
        ..
    } = hold;
    let stops: Vec<_> = moves.iter().filter(|(_, m)| !m.on).collect();
    assert_eq!(stops.len(), 1, "one run, one stop: {moves:?}");
    let (stop_at, _) = *stops[0];
    assert!(stop_at > last_repeat, "stopped while the key was held");
    assert!(
        moves.last().is_some_and(|(_, m)| !m.on),
        "the stop is the last move"
    );
    let worst = moves.windows(2).map(|w| w[1].0 - w[0].0).max().unwrap();
    // When the page wrote the stop to the port (its link's own record), and when the
    // rig's tap on the far side of the pty read it: the tap's thread is the test's,
    // and on a loaded machine it adds its own wake-up to the figure.
    let written = {
        let m = rig.app.model();
        m.traffic
            .entries()
            .filter(|e| e.dir == vpx_efis::link::Crossing::Tx && e.at > last_repeat)
            .find(|e| {
                Packet::parse_bytes(&e.raw)
                    .is_ok_and(|p| matches!(p.message, Message::TrimMove(m) if !m.on))
            })
            .map(|e| e.at)
            .expect("the stop in the page's traffic log")
    };
    let after = written - last_repeat;
    eprintln!(
        "660/40 ms through the pty: worst interval {worst:?}, stop written {after:?} after the \
         last repeat, read by the tap {:?} after it",
        stop_at - last_repeat
    );
    assert!(worst <= Duration::from_millis(220), "interval {worst:?}");
    // The learned gap is 3 × 40 ms = 120 ms, and the stop is written ~120.2 ms after
    // the last repeat (measured with other builds running, load average ~5): the
    // promise is 150 ms, and a hold on a machine that woke this test's own
    // thread on time is held to it. Where every hold found the machine saturated (4
    // busy loops on 2 cores put the stop at 128–178 ms: the motor thread and the
    // link's writer each wait for a core after the deadline) the bound is 175 ms;
    // the old fixed 200 ms gap fails both.
    let bound = if hold.worst_delivery <= QUIET_DELIVERY {
        Duration::from_millis(150)
    } else {
        Duration::from_millis(175)
    };
    assert!(
        after <= bound,
        "stop written {after:?} after the last repeat (bound {bound:?}, repeats delivered \
         at worst {:?} apart)",
        hold.worst_delivery
    );
    page_rig::assert_the_trim_stopped_by_its_message(&rig.sim);

    // The page says what it now uses.
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(50));
    let screen = text(&rig.render());
    let (_, line) = line_of(&rig.render(), "keys: auto-repeat · ").expect(&screen);
    let nums: Vec<u64> = line
        .split("keys: auto-repeat · ")
        .nth(1)
        .unwrap()
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .take(2)
        .map(|s| s.parse().unwrap())
        .collect();
    assert!(line.contains(", learned"), "{line}");
    // As delivered: a loaded machine stretches the test's own 40 ms a little, and a
    // key sent late shortens the gap after it (37 ms seen on a loaded machine).
    assert!((655..=800).contains(&nums[0]), "delay {line}");
    assert!((30..=60).contains(&nums[1]), "interval {line}");
    // And the help says what a tap does.
    rig.key(KeyCode::Char('?'), KeyEventKind::Press);
    let help = text(&rig.render());
    assert!(help.contains("a tap (no repeat) runs a motor"), "{help}");
}

/// At 60×20 the page says "Terminal too small" and keys do nothing: `f`, `o`, `r`
/// and the motor keys send nothing; `?` still opens help and `q` still quits. When
/// the page is shown again the selection is where it was. A shrink during a run
/// sends the stop at once.
#[test]
fn a_page_too_small_to_see_ignores_keys_and_a_shrink_stops_the_run() {
    use crossterm::event::Event;
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    let mut rig = Rig::new(ReleaseMode::KeyRelease);
    rig.select(9);
    let resize = |rig: &mut Rig, w, h| {
        rig.app
            .handle_term_event(Event::Resize(w, h), Instant::now())
    };
    let acting = |m: &Message| {
        matches!(
            m,
            Message::DevicePower(_)
                | Message::DeviceClear(_)
                | Message::TrimMove(_)
                | Message::FlapMove(_)
                | Message::WigWagMode(_)
        )
    };

    resize(&mut rig, 60, 20);
    let from = rig.wire_len();
    for c in ['f', 'o', 'r', 'R', 'w', 'j', 'k'] {
        rig.key(KeyCode::Char(c), KeyEventKind::Press);
    }
    assert_eq!(rig.app.view().selected, Some(9), "j/k did not move it");
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(300));
    let sent: Vec<_> = rig
        .sent(from)
        .into_iter()
        .filter(|(_, p)| acting(&p.message))
        .collect();
    assert!(sent.is_empty(), "sent while too small: {sent:?}");
    let buf = {
        let mut term = ratatui::Terminal::new(ratatui::backend::TestBackend::new(60, 20)).unwrap();
        rig.app.draw(&mut term, Instant::now()).unwrap();
        term.backend().buffer().clone()
    };
    assert!(text(&buf).contains("Terminal too small"));
    assert!(text(&buf).contains("Until then keys do nothing; Ctrl-C quits."));
    // Help does not open unseen (it would be there, unasked, once the page fits);
    // quit still quits.
    rig.key(KeyCode::Char('?'), KeyEventKind::Press);
    assert_eq!(rig.app.view().overlay, vpx_efis::ui::state::Overlay::None);
    assert_eq!(
        rig.app.handle_term_event(
            Event::Key(crossterm::event::KeyEvent::new(
                KeyCode::Char('q'),
                crossterm::event::KeyModifiers::NONE
            )),
            Instant::now()
        ),
        vpx_efis::app::Flow::Quit
    );

    // Shown again: the selection is where it was, and keys act.
    resize(&mut rig, 120, 40);
    assert_eq!(rig.app.view().selected, Some(9));

    // A run, then a shrink in the middle of it.
    rig.select(30);
    let from = rig.wire_len();
    let start = Instant::now();
    rig.key(KeyCode::Char('u'), KeyEventKind::Press);
    while start.elapsed() < Duration::from_millis(700) {
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(33));
        rig.key(KeyCode::Char('u'), KeyEventKind::Repeat);
    }
    assert!(rig.app.motor_run().is_some(), "running before the shrink");
    let shrunk = Instant::now();
    resize(&mut rig, 70, 30);
    // The key is still held: its repeats keep coming, and start nothing.
    while shrunk.elapsed() < Duration::from_millis(500) {
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(33));
        rig.key(KeyCode::Char('u'), KeyEventKind::Repeat);
    }
    assert_stopped_within(&rig, from, "the shrink", shrunk, Duration::from_millis(100));
    assert!(rig.app.motor_run().is_none());
    assert!(!rig.sim.stats().pitch_trim_running);
    assert_eq!(rig.app.view().selected, Some(30), "the selection stays");
}

/// The motor-stream thread resends on its own clock, but the model's checks (comm
/// loss, a fault) run in the page's loop. When that loop stalls (here: nobody pumps it,
/// as when a terminal write blocks on a paused tty) the thread stops the run instead
/// of streaming alone, within the stall limit plus one resend.
#[test]
fn a_stalled_page_loop_stops_the_motor_stream() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    let mut rig = Rig::new(ReleaseMode::KeyRelease);
    rig.select(30);
    let from = rig.wire_len();
    rig.key(KeyCode::Char('u'), KeyEventKind::Press);
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(200));
    assert!(rig.app.motor_run().is_some(), "running");
    // The loop stalls while the key is still held (no release ever comes).
    let stalled = Instant::now();
    std::thread::sleep(Duration::from_millis(1500));
    let limit = vpx_efis::app::LOOP_STALL + Duration::from_millis(125 + 150);
    assert_stopped_within(&rig, from, "the stall", stalled, limit);
}

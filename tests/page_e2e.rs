//! The page end to end: the real `App` on one side of a real pseudo-terminal, the
//! virtual VP-X on the other, and a tap in between that records every byte the page
//! puts on the wire (see `page_rig`).
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEventKind};
use ratatui::buffer::Buffer;
use ratatui::style::Color;
use vpx_efis::app::App;
use vpx_efis::model::Connection;
use vpx_efis::protocol::message::{DevicePower, Message, TrimDirection, TrimMove, TrimType};
use vpx_efis::sim::SimCommand;
use vpx_efis::ui::state::ReleaseMode;

mod page_rig;
use page_rig::*;

mod common;
use common::screen::{line_of, text};

fn fg_of(buf: &Buffer, y: u16, line: &str, word: &str) -> Color {
    let col = line.find(word).expect("word on line");
    // Columns are characters; the row is ASCII up to the state column.
    let x = line[..col].chars().count() as u16;
    buf[(x, y)].fg
}

#[test]
fn a_key_reaches_the_wire_as_device_power_and_the_next_status_shows_it_on() {
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.select(9);
    let from = rig.wire_len();
    let pressed = Instant::now();
    rig.key(KeyCode::Char('o'), KeyEventKind::Press);
    let sent_at = {
        let end = Instant::now() + Duration::from_secs(2);
        loop {
            let found = rig.sent(from).into_iter().find(|(_, p)| {
                p.message
                    == Message::DevicePower(DevicePower {
                        device_id: 9,
                        on: true,
                    })
            });
            if let Some((at, p)) = found {
                assert_eq!(
                    (p.src, p.dst),
                    (
                        vpx_efis::protocol::Node::External,
                        vpx_efis::protocol::Node::Vpx
                    )
                );
                break at;
            }
            assert!(
                Instant::now() < end,
                "no DEVICE_POWER 9 on reached the wire"
            );
            rig.app
                .pump_until(Instant::now() + Duration::from_millis(5));
        }
    };
    eprintln!(
        "key-to-wire through the pty: {:?}",
        sent_at.saturating_duration_since(pressed)
    );
    rig.until(
        "DEVICE_STATUS with GPS 1 on",
        Duration::from_secs(3),
        |app, now| app.model().live_devices(now).is_some_and(|d| d.on[9]),
    );
    let buf = rig.render();
    let (y, line) = line_of(&buf, "GPS 1").expect("GPS 1 row");
    assert!(line.contains(" ON "), "{line}");
    assert_eq!(fg_of(&buf, y, &line, "ON "), Color::Green, "{line}");
    assert!(rig.sim.stats().powered[9]);
}

/// Holds pitch-trim up for about two seconds the way `mode` reports it, then lets go.
fn hold_trim_up(rig: &mut Rig, mode: ReleaseMode) {
    rig.select(30);
    let before = rig.sim.stats().pitch_trim_position;
    let from = rig.wire_len();
    let start = Instant::now();
    rig.key(KeyCode::Char('u'), KeyEventKind::Press);
    // Held, a typical terminal repeats the press, a kitty-protocol terminal sends
    // Repeat events and a release at the end; both first after ~500 ms, then ~30 a
    // second.
    let repeat = match mode {
        ReleaseMode::AutoRepeat => KeyEventKind::Press,
        ReleaseMode::KeyRelease => KeyEventKind::Repeat,
    };
    rig.app.pump_until(start + Duration::from_millis(500));
    while start.elapsed() < Duration::from_secs(2) {
        rig.key(KeyCode::Char('u'), repeat);
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(33));
    }
    if mode == ReleaseMode::KeyRelease {
        rig.key(KeyCode::Char('u'), KeyEventKind::Release);
    }
    let let_go = Instant::now();
    rig.app.pump_until(let_go + Duration::from_millis(600));
    let stats = rig.sim.stats();
    assert!(
        stats.pitch_trim_position < before,
        "trim up moved the position from {before} to {}",
        stats.pitch_trim_position
    );
    page_rig::assert_the_trim_stopped_by_its_message(&rig.sim);

    let moves: Vec<(Instant, TrimMove)> = rig
        .sent(from)
        .into_iter()
        .filter_map(|(at, p)| match p.message {
            Message::TrimMove(m) => Some((at, m)),
            _ => None,
        })
        .collect();
    let (on, stop): (Vec<_>, Vec<_>) = moves.iter().partition(|(_, m)| m.on);
    assert!(
        on.len() >= 8,
        "about 2 s of moves at 5 Hz, got {}",
        on.len()
    );
    assert!(
        on.iter()
            .all(|(_, m)| m.trim_type == TrimType::Pitch && m.direction == TrimDirection::UpOrLeft)
    );
    let worst = on.windows(2).map(|w| w[1].0 - w[0].0).max().unwrap();
    eprintln!(
        "{mode:?}: {} moves, worst interval on the wire {worst:?}",
        on.len()
    );
    assert!(worst <= Duration::from_millis(250), "interval {worst:?}");
    let (stop_at, last) = *stop.last().expect("a stop message");
    assert_eq!(last.trim_type, TrimType::Pitch);
    assert!(
        moves.last().is_some_and(|(_, m)| !m.on),
        "the stop is the last move message"
    );
    let latest_allowed = match mode {
        ReleaseMode::KeyRelease => let_go + Duration::from_millis(100),
        ReleaseMode::AutoRepeat => let_go + Duration::from_millis(400),
    };
    assert!(
        stop_at <= latest_allowed,
        "stop came {:?} after letting go",
        stop_at - let_go
    );
}

#[test]
fn a_held_trim_key_moves_the_sims_trim_with_no_starvation_in_auto_repeat_mode() {
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    hold_trim_up(&mut rig, ReleaseMode::AutoRepeat);
}

#[test]
fn a_held_trim_key_moves_the_sims_trim_with_no_starvation_in_key_release_mode() {
    let mut rig = Rig::new(ReleaseMode::KeyRelease);
    hold_trim_up(&mut rig, ReleaseMode::KeyRelease);
}

#[test]
fn a_silent_unit_brings_communication_lost_within_two_and_a_half_seconds() {
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.ready();
    let last_status = |app: &App| {
        let m = app.model();
        m.system_status
            .map(|s| s.at)
            .max(m.device_status.map(|s| s.at))
            .unwrap()
    };
    rig.sim.inject(SimCommand::Silent(Duration::from_secs(6)));
    let lost_at = rig.until("COMMUNICATION LOST", Duration::from_secs(5), |app, now| {
        app.model().comm_lost(now)
    });
    let heard = last_status(&rig.app);
    assert!(
        lost_at - heard <= Duration::from_millis(2500 + 200),
        "lost {:?} after the last status",
        lost_at - heard
    );
    let buf = rig.render();
    assert!(line_of(&buf, "COMMUNICATION LOST").is_some());
    let screen = text(&buf);
    let (_, nav) =
        line_of(&buf, "Nav Lt").unwrap_or_else(|| panic!("rows stay, values go:\n{screen}"));
    assert!(
        !nav.contains(" ON ") && !nav.contains("1.5"),
        "no old data shown: {nav}"
    );
    rig.until(
        "data back after the silence",
        Duration::from_secs(8),
        |app, now| !app.model().comm_lost(now),
    );
    let buf = rig.render();
    assert!(line_of(&buf, "COMMUNICATION LOST").is_none());
}

#[test]
fn a_pulled_cable_is_shown_and_the_same_path_reconnects_when_it_returns() {
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.ready();
    let versions_asked = |rig: &Rig| {
        rig.sent(0)
            .iter()
            .filter(|(_, p)| p.message.name() == "VERSION")
            .count()
    };
    assert_eq!(versions_asked(&rig), 1);

    // Unplug: every handle on the master closes and the device node goes away.
    rig.tap.take().unwrap().unplug();
    std::fs::remove_file(&rig.link_path).unwrap();
    rig.until(
        "the page to notice the pulled cable",
        Duration::from_secs(5),
        |app, _| matches!(app.model().connection, Connection::Lost { .. }),
    );
    rig.app.pump_until(Instant::now() + Duration::from_secs(1));
    assert!(
        matches!(rig.app.model().connection, Connection::Lost { .. }),
        "still lost while unplugged"
    );

    // Plug back in: a new pty behind the same name.
    let tap = Tap::start(rig.to_sim.clone(), rig.from_sim.clone(), rig.wire.clone());
    std::os::unix::fs::symlink(&tap.slave_path, &rig.link_path).unwrap();
    rig.tap = Some(tap);
    rig.until(
        "reconnected with live data",
        Duration::from_secs(6),
        |app, now| {
            matches!(app.model().connection, Connection::Connected { .. })
                && !app.model().comm_lost(now)
        },
    );
    rig.until(
        "the connect queries asked again",
        Duration::from_secs(3),
        |_, _| true,
    );
    let end = Instant::now() + Duration::from_secs(3);
    while versions_asked(&rig) < 2 {
        assert!(
            Instant::now() < end,
            "VERSION was not asked again after reconnecting"
        );
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(50));
    }
}

/// AC 43.13-1B's breaker practice through the real page and the sim: Nav Lt shorts
/// (`short 4 on` on the sim's console); the first `r` resets it, it trips again, the
/// second `r` sends nothing and says why, and `Y` (named on the detail panel and in
/// the notice) sends the reset. The event log holds both.
#[test]
fn a_second_r_after_the_circuit_faulted_again_sends_nothing_until_y() {
    const NAV: u8 = 4;
    let mut rig = Rig::new(ReleaseMode::AutoRepeat);
    rig.select(NAV);
    rig.sim.inject(SimCommand::Short {
        device: NAV,
        on: true,
    });
    let clears = |rig: &Rig, from: usize| {
        rig.sent(from)
            .into_iter()
            .filter(|(_, p)| {
                p.message
                    == Message::DeviceClear(vpx_efis::protocol::message::DeviceClear {
                        device_id: NAV,
                    })
            })
            .count()
    };
    // Pumps the page until the wire holds `n` resets of Nav Lt since `from`.
    let wait_clears = |rig: &mut Rig, from: usize, n: usize, what: &str| {
        let end = Instant::now() + Duration::from_secs(2);
        while clears(rig, from) < n {
            assert!(Instant::now() < end, "no {what} on the wire");
            rig.app
                .pump_until(Instant::now() + Duration::from_millis(10));
        }
    };
    rig.until("Nav Lt faulted", Duration::from_secs(4), |app, now| {
        app.model()
            .circuits(now)
            .iter()
            .any(|c| c.id == NAV && matches!(c.state, vpx_efis::model::CircuitState::Fault(_)))
    });
    let from = rig.wire_len();
    rig.key(KeyCode::Char('r'), KeyEventKind::Press);
    wait_clears(&mut rig, from, 1, "first reset");
    rig.until(
        "Nav Lt faulted again after the reset",
        Duration::from_secs(4),
        |app, now| app.model().faulted_again_after_reset(NAV, now),
    );
    let buf = rig.render();
    let screen = text(&buf);
    // The detail panel's keys are glued with non-breaking spaces.
    let (_, keys) = line_of(&buf, "Y\u{a0}").expect(&screen);
    assert!(
        keys.replace('\u{a0}', " ").contains(" Y  reset again"),
        "{keys}"
    );

    // The second `r`: nothing on the wire, and the words.
    let from = rig.wire_len();
    rig.key(KeyCode::Char('r'), KeyEventKind::Press);
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(300));
    assert_eq!(clears(&rig, from), 0, "the second r sent a reset");
    assert_eq!(
        rig.app.view().notice.as_deref(),
        Some(
            "Nav Lt faulted again after a reset: find the cause before resetting it again \
             (Y: reset it anyway)"
        )
    );
    // `Y` confirms: the reset goes out.
    rig.key(KeyCode::Char('Y'), KeyEventKind::Press);
    wait_clears(&mut rig, from, 1, "confirmed second reset");
    assert_eq!(
        common::events::containing(&rig.app.model(), "reset sent"),
        [
            "Nav Lt: reset sent (DEVICE_CLEAR), the 1st this session",
            "Nav Lt: reset sent after it faulted again (DEVICE_CLEAR), the 2nd this session"
        ]
    );
}

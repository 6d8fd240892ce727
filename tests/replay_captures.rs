//! The captures shipped under `assets/captures/`, replayed through the real page, and
//! the generator that made them.
//!
//! Regenerate with
//! `cargo test --test replay_captures -- --ignored generate_captures` (about 35 s): each
//! is the real `App` recording (`--record`) a session against the built-in virtual VP-X.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::Color;

use vpx_efis::app::{self, App, AppOptions, Capture, Recorder};
use vpx_efis::ui::state::Screen;

mod common;
use common::screen::text;

fn captures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/captures")
}

/// (file, scenario, seconds): a normal session, a fault, a communication loss.
const SHIPPED: &[(&str, &str, u64)] = &[
    ("normal.vpxcap", "demo", 6),
    ("short-circuit.vpxcap", "short-circuit", 8),
    ("comm-loss.vpxcap", "comm-loss", 16),
];

#[test]
#[ignore = "writes assets/captures; run by hand to regenerate them"]
fn generate_captures() {
    std::fs::create_dir_all(captures()).unwrap();
    for &(file, scenario, secs) in SHIPPED {
        let path = captures().join(file);
        let (source, connector, sim) = app::builtin_sim(scenario).unwrap();
        let mut app = App::recording(
            source,
            connector,
            AppOptions::default(),
            Recorder::create(&path).unwrap(),
        );
        app.pump_until(Instant::now() + Duration::from_secs(secs));
        app.shutdown();
        sim.stop();
        let len = std::fs::metadata(&path).unwrap().len();
        eprintln!("{file}: {len} bytes");
        assert!(len < 100_000, "{file} is {len} bytes");
    }
}

fn draw(app: &mut App, now: Instant, w: u16, h: u16) -> Buffer {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    app.draw(&mut term, now).unwrap();
    term.backend().buffer().clone()
}

fn replay(file: &str) -> App {
    let cap = Capture::load(&captures().join(file)).unwrap();
    assert!(cap.problem.is_none(), "{file}: {:?}", cap.problem);
    App::replay(cap, AppOptions::default(), 1.0, true)
}

#[test]
fn the_short_circuit_capture_shows_the_strobe_fault_in_red_at_five_seconds() {
    let mut app = replay("short-circuit.vpxcap");
    let now = app.replay_seek(Duration::from_secs(5)).unwrap();
    let buf = draw(&mut app, now, 120, 40);
    insta::assert_snapshot!(text(&buf));
    let screen = text(&buf);
    let (y, line) = screen
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains("Strobe Lt"))
        .unwrap();
    assert!(line.contains("SHORT"), "{line}");
    let x = line[..line.find("SHORT").unwrap()].chars().count() as u16;
    assert_eq!(buf[(x, y as u16)].fg, Color::Red);
    assert!(screen.contains("REPLAY short-circuit.vpxcap"));
}

#[test]
fn the_comm_loss_capture_shows_communication_lost_in_the_silence_and_noise_in_traffic() {
    let mut app = replay("comm-loss.vpxcap");
    let now = app.replay_seek(Duration::from_millis(9000)).unwrap();
    let screen = text(&draw(&mut app, now, 120, 40));
    assert!(screen.contains("COMMUNICATION LOST"), "{screen}");
    // At 15 s the data is back, and the traffic view shows the 300 bytes of noise
    // injected at 14 s where they happened.
    let now = app.replay_seek(Duration::from_millis(15_000)).unwrap();
    let screen = text(&draw(&mut app, now, 120, 40));
    assert!(!screen.contains("COMMUNICATION LOST"), "{screen}");
    let dropped = app.model().traffic.errors.values().sum::<u64>();
    assert!(dropped > 0, "the noise reached the decoder");
    let key = |c| {
        crossterm::event::Event::Key(crossterm::event::KeyEvent::new(
            crossterm::event::KeyCode::Char(c),
            crossterm::event::KeyModifiers::NONE,
        ))
    };
    app.handle_term_event(key('t'), now);
    assert_eq!(app.view().screen, Screen::Traffic);
    app.handle_term_event(key('e'), now);
    let buf = draw(&mut app, now, 120, 40);
    let screen = text(&buf);
    assert!(
        screen.contains("DROPPED BYTES") || screen.contains("BAD CHECKSUM"),
        "{screen}"
    );
    assert!(
        screen.contains("PAUSED") && screen.contains("read-only"),
        "{screen}"
    );
}

//! Setup asks before a breaker goes over its wire, end to end: the page's
//! `App` on the pty of `vpx-efis sim --pty --scenario wires` run as a process of its
//! own, the load file beside the config file as the page reads it when setup opens.
//! The strobe (10A-1) is wired in 22 AWG, for which AC 43.13-1B Table 11-3 allows a
//! 5 A breaker: setting 7 A asks, naming the wire and the limit, and nothing reaches
//! the unit before `y`. A test file of its own: it sets the process's environment.
#![cfg(unix)]

mod common;

use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use vpx_efis::app::{App, AppOptions};
use vpx_efis::link;
use vpx_efis::model::Source;
use vpx_efis::setup::view::{Dialog, Page};
use vpx_efis::ui::state::Screen;

const STROBE: u8 = 0x11;

fn key(app: &mut App, code: KeyCode) {
    let k = KeyEvent::new_with_kind(code, KeyModifiers::NONE, KeyEventKind::Press);
    app.handle_term_event(Event::Key(k), Instant::now());
}

fn until(app: &mut App, what: &str, limit: Duration, f: impl Fn(&App) -> bool) {
    common::app::until(app, what, limit, |app, _| f(app));
}

/// The screen as text, one line per row, trailing blanks trimmed.
fn screen(app: &mut App) -> String {
    let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
    app.draw(&mut term, Instant::now()).unwrap();
    let buf = term.backend().buffer().clone();
    (0..buf.area.height)
        .map(|y| {
            let line: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
            line.trim_end().to_string() + "\n"
        })
        .collect()
}

fn sent(app: &App, name: &str) -> u64 {
    app.model().link.tx.get(name).map_or(0, |s| s.count)
}

#[test]
fn setup_asks_before_a_breaker_goes_over_its_wire_and_sends_nothing_before_y() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("loads.toml"),
        "[circuit.10A-1]\nname = \"Strobe Lt\"\nwire = \"22 AWG\"\nwire_length = \"6 ft\"\n",
    )
    .unwrap();
    // SAFETY: the only test in this binary, before it starts a thread.
    unsafe { std::env::set_var("VPX_EFIS_CONFIG", dir.path().join("config.toml")) };
    let (_sim, port) = common::process::sim_pty("wires");
    let mut app = App::new(
        Source::Serial { path: port.clone() },
        link::serial_connector(port.into(), 57_600),
        AppOptions::default(),
    );
    until(
        &mut app,
        "the unit's settings",
        Duration::from_secs(8),
        |app| {
            let m = app.model();
            m.names.iter().all(Option::is_some)
                && m.device_specs[28].is_some()
                && !m.comm_lost(Instant::now())
        },
    );
    for _ in 0..40 {
        if app.view().selected == Some(STROBE) {
            break;
        }
        key(&mut app, KeyCode::Char('j'));
    }
    assert_eq!(app.view().selected, Some(STROBE));
    key(&mut app, KeyCode::Char('c'));
    app.pump_until(Instant::now() + Duration::from_millis(50));
    assert_eq!(app.view().screen, Screen::Setup);
    assert_eq!(app.view().setup.page, Page::Device);
    assert_eq!(app.view().setup.forms.device.device_id, STROBE);
    assert_eq!(app.view().setup.forms.device.circuit_breaker, 6);

    key(&mut app, KeyCode::Down); // the breaker
    // The unit's own 6 A is already over the wire's 5 A, and the page says so.
    let over = "its wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A: over it, Enter asks first";
    assert!(screen(&mut app).contains(over), "{}", screen(&mut app));
    key(&mut app, KeyCode::Char('5'));
    assert!(
        screen(&mut app).contains("its wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A\n"),
        "{}",
        screen(&mut app)
    );
    key(&mut app, KeyCode::Backspace);
    key(&mut app, KeyCode::Char('7'));
    assert_eq!(app.view().setup.forms.device.circuit_breaker, 7);
    assert!(screen(&mut app).contains(over), "{}", screen(&mut app));
    key(&mut app, KeyCode::Enter);
    let Dialog::Disarm { consequences } = app.view().setup.dialog.clone() else {
        panic!("no question: {:?}", app.view().setup.message);
    };
    assert_eq!(
        consequences,
        [
            "Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 7 A breaker \
          would not protect it"
        ]
    );
    app.pump_until(Instant::now() + Duration::from_millis(500));
    assert_eq!(sent(&app, "DEVICE_SPEC"), 0, "nothing sent before y");
    key(&mut app, KeyCode::Enter);
    app.pump_until(Instant::now() + Duration::from_millis(200));
    assert_eq!(sent(&app, "DEVICE_SPEC"), 0, "Enter is not y");

    key(&mut app, KeyCode::Char('y'));
    until(
        &mut app,
        "the unit holding 7 A",
        Duration::from_secs(4),
        |app| app.model().device_specs[STROBE as usize].map(|s| s.value.circuit_breaker) == Some(7),
    );
    assert_eq!(sent(&app, "DEVICE_SPEC"), 1);
    app.shutdown();
}

//! A fault reset against the virtual VP-X run as its own process (`vpx-efis sim --pty`),
//! its console faulting a pin as a short in the aircraft would: after `r`, the row
//! says the reset is sent until the unit's next broadcast answers it, and never shows
//! as current a fault the unit has cleared.
// Needs a pseudo-terminal (`sim --pty`), which only Unix has.
#![cfg(unix)]

use std::io::Write;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use vpx_efis::app::{App, AppOptions};
use vpx_efis::link;
use vpx_efis::model::{CircuitState, Source};
use vpx_efis::protocol::FaultCode;

mod common;
use common::process::{Sim, sim};

const LANDING: u8 = 17;
const TAXI: u8 = 18;

struct Page {
    app: App,
    sim: Sim,
}

impl Page {
    fn new() -> Page {
        let sim = sim(&["--pty", "--scenario", "demo"]);
        let path = sim.line.clone();
        let app = App::new(
            Source::Serial { path: path.clone() },
            link::serial_connector(path.into(), 57_600),
            AppOptions::default(),
        );
        let mut p = Page { app, sim };
        p.until("the device list", Duration::from_secs(10), |app, now| {
            let m = app.model();
            m.live_devices(now).is_some() && m.names.iter().all(Option::is_some)
        });
        p
    }

    fn say(&mut self, line: &str) {
        writeln!(self.sim.console, "{line}").unwrap();
        self.sim.console.flush().unwrap();
    }

    fn until(&mut self, what: &str, limit: Duration, f: impl Fn(&App, Instant) -> bool) {
        common::app::until(&mut self.app, what, limit, f);
    }

    fn state(&self, id: u8) -> CircuitState {
        let now = Instant::now();
        self.app
            .model()
            .circuits(now)
            .into_iter()
            .find(|c| c.id == id)
            .map_or(CircuitState::Unknown, |c| c.state)
    }

    fn key(&mut self, c: char) {
        let k = KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE);
        self.app.handle_term_event(Event::Key(k), Instant::now());
    }

    fn select(&mut self, id: u8) {
        for _ in 0..40 {
            if self.app.view().selected == Some(id) {
                return;
            }
            self.key('j');
        }
        panic!("could not select device {id}");
    }

    /// Device `id` (`name`) shorted, then reset from the page: its row shows `state`,
    /// and no fault, within `limit` of the reset.
    fn reset_shows(&mut self, id: u8, name: &str, state: CircuitState, limit: Duration) {
        self.fault(id);
        let (sent, shown) = self.reset_until(id, name, state);
        let took = shown - sent;
        println!("{name}: reset sent, {state:?} shown {took:?} later");
        assert!(took <= limit, "{name}: {took:?}");
        let row = self.row(name);
        let word = match state {
            CircuitState::On => " ON ",
            CircuitState::Off => " OFF ",
            other => panic!("a reset ends ON or OFF, not {other:?}"),
        };
        assert!(
            row.contains(word) && !row.contains("SHORT_CIRCUIT"),
            "{name}: {row}"
        );
    }

    /// The row of device `name` as the page draws it now.
    fn row(&mut self, name: &str) -> String {
        let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
        self.app.draw(&mut term, Instant::now()).unwrap();
        let drawn = common::screen::text(term.backend().buffer());
        drawn
            .lines()
            .find(|l| l.contains(name))
            .unwrap_or_default()
            .to_string()
    }

    fn resets_sent(&self) -> u64 {
        sent_count(&self.app)
    }

    /// Faults `id` from the sim's console and waits until the page shows it.
    fn fault(&mut self, id: u8) {
        self.say(&format!("fault {id} 7"));
        self.until(
            "the fault on the page",
            Duration::from_secs(4),
            |app, now| {
                app.model()
                    .circuits(now)
                    .iter()
                    .any(|c| c.id == id && c.state == CircuitState::Fault(FaultCode::ShortCircuit))
            },
        );
        self.select(id);
    }

    /// Presses `r`, then pumps until the row leaves "reset sent", watching that it
    /// never shows the fault plain meanwhile. Returns when the reset went out and
    /// when the row showed `answer`.
    fn reset_until(&mut self, id: u8, name: &str, answer: CircuitState) -> (Instant, Instant) {
        let before = self.resets_sent();
        self.key('r');
        // The link's writer counts it once it is on the wire.
        self.until("the reset on the wire", Duration::from_secs(1), |app, _| {
            sent_count(app) == before + 1
        });
        let sent = Instant::now();
        assert_eq!(
            self.state(id),
            CircuitState::ResetSent(FaultCode::ShortCircuit)
        );
        let row = self.row(name);
        assert!(row.contains("SHORT_CIRCUIT · reset sent"), "{row}");
        // A second `r` while the unit has not answered sends nothing, and says why.
        self.key('r');
        self.app
            .pump_until(Instant::now() + Duration::from_millis(50));
        assert_eq!(self.resets_sent(), before + 1, "no second reset");
        let notice = self.app.view().notice.clone().unwrap_or_default();
        assert!(
            notice.contains("a reset was sent") && notice.contains("nothing more is sent"),
            "{notice}"
        );
        let end = sent + Duration::from_secs(5);
        loop {
            let st = self.state(id);
            if st == answer {
                return (sent, Instant::now());
            }
            assert_eq!(
                st,
                CircuitState::ResetSent(FaultCode::ShortCircuit),
                "between the reset and its answer"
            );
            assert!(Instant::now() < end, "no answer to the reset: {st:?}");
            self.app
                .pump_until(Instant::now() + Duration::from_millis(5));
        }
    }
}

/// How many DEVICE_CLEAR the page has put on the wire.
fn sent_count(app: &App) -> u64 {
    app.model()
        .link
        .tx
        .get("DEVICE_CLEAR")
        .map_or(0, |s| s.count)
}

/// Its switch on: the unit clears the fault on the reset and powers the pin, and its
/// next DEVICE_STATUS (1 Hz) shows it on: within 1.2 s of the reset.
#[test]
fn a_cleared_fault_with_its_switch_on_shows_on_within_1_2_s() {
    let mut p = Page::new();
    p.say("switch 5 on");
    p.until("switch 5 on", Duration::from_secs(4), |app, now| {
        app.model()
            .live_devices(now)
            .is_some_and(|d| d.on[TAXI as usize])
    });
    p.reset_shows(
        TAXI,
        "Taxi Light",
        CircuitState::On,
        Duration::from_millis(1200),
    );
}

/// Its switch off, no other fault: FAULT_STATUS simply stops, and the row shows OFF
/// once it is overdue (its 1 s period plus 500 ms after the last one): within 1.6 s.
#[test]
fn a_cleared_fault_with_its_switch_off_shows_off_once_fault_status_is_overdue() {
    let mut p = Page::new();
    p.reset_shows(
        LANDING,
        "Landing Lt",
        CircuitState::Off,
        Duration::from_millis(1600),
    );
}

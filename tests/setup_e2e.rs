//! The setup screens end to end: the real `App` driven with keys, on the slave of a
//! real pseudo-terminal, the virtual VP-X on its master. What the screen says is
//! checked against what the sim really holds (`stats().config`).
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

use crossterm::event::KeyCode;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::Color;
use vpx_efis::app::AppOptions;
use vpx_efis::protocol::message::{DeviceSpec, SwitchId};
use vpx_efis::setup::view::{Page, WriteStatus};
use vpx_efis::sim::{Scenario, SimCommand, SimOptions};
use vpx_efis::ui::state::{ReleaseMode, Screen};

mod common;
use common::rig::Rig;
use common::screen::text;

/// A few devices, the flaps fitted.
const SCENARIO: &str = include_str!("data/scenario-setup.toml");

impl Rig {
    /// The page on the setup screen of device `id`, the unit's settings all heard.
    fn on_setup_of(id: u8) -> Rig {
        let mut rig = Rig::with_eeprom(None);
        rig.open_setup_on(id);
        rig
    }

    fn with_eeprom(eeprom: Option<std::path::PathBuf>) -> Rig {
        Rig::with(SCENARIO, eeprom)
    }

    fn with(scenario: &str, eeprom: Option<std::path::PathBuf>) -> Rig {
        let mut options = SimOptions::new(Scenario::from_toml(scenario).unwrap());
        options.eeprom = eeprom;
        Rig::start(
            options,
            AppOptions {
                max_run: Duration::from_secs(10),
                release_mode: ReleaseMode::AutoRepeat,
                ..AppOptions::default()
            },
        )
    }

    fn keys(&mut self, s: &str) {
        for c in s.chars() {
            self.key(KeyCode::Char(c));
        }
    }

    /// Connected, every spec, name and enable flag heard, then `c` from device `id`.
    fn open_setup_on(&mut self, id: u8) {
        self.until(
            "the unit's whole configuration",
            Duration::from_secs(8),
            |app| {
                let m = app.model();
                m.names.iter().all(Option::is_some)
                    && m.wig_wag_spec.is_some()
                    && m.device_specs[28].is_some()
                    && !m.comm_lost(Instant::now())
            },
        );
        for _ in 0..40 {
            if self.app.view().selected == Some(id) {
                break;
            }
            self.key(KeyCode::Char('j'));
        }
        assert_eq!(self.app.view().selected, Some(id));
        self.key(KeyCode::Char('c'));
        self.app
            .pump_until(Instant::now() + Duration::from_millis(50));
        assert_eq!(self.app.view().screen, Screen::Setup);
        assert_eq!(self.app.view().setup.page, Page::Device);
        assert_eq!(self.app.view().setup.forms.device.device_id, id);
    }

    /// Pumps the page until the first write's status is as `f` wants, or fails after
    /// `limit` naming `what`.
    fn until_first_write(&mut self, what: &str, limit: Duration, f: impl Fn(&WriteStatus) -> bool) {
        self.until(what, limit, |app| f(&app.view().setup.writes[0].status));
    }

    /// Tab to the setup page `page`.
    fn tab_to(&mut self, page: Page) {
        for _ in 0..8 {
            if self.app.view().setup.page != page {
                self.key(KeyCode::Tab);
            }
        }
        assert_eq!(self.app.view().setup.page, page);
    }

    /// [`Rig::until_first_write`] saved, within 3 s.
    fn until_saved(&mut self, what: &str) {
        self.until_first_write(what, Duration::from_secs(3), |s| {
            matches!(s, WriteStatus::Saved { .. })
        });
    }

    fn status(&self, i: usize) -> WriteStatus {
        self.app.view().setup.writes[i].status.clone()
    }

    fn render(&mut self) -> Buffer {
        let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
        self.app.draw(&mut term, Instant::now()).unwrap();
        term.backend().buffer().clone()
    }
}

fn fg_of(buf: &Buffer, needle: &str) -> Color {
    for y in 0..buf.area.height {
        let line: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
        if let Some(b) = line.find(needle) {
            return buf[(line[..b].chars().count() as u16, y)].fg;
        }
    }
    panic!("{needle:?} not on screen:\n{}", text(buf));
}

#[test]
fn an_edited_breaker_reaches_the_sim_and_is_saved_only_after_its_spec_ack() {
    let mut rig = Rig::on_setup_of(9);
    rig.key(KeyCode::Down); // breaker
    rig.keys("4");
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Right); // switch 2 → 3
    rig.key(KeyCode::Enter);
    let sv = &rig.app.view().setup;
    assert_eq!(sv.writes.len(), 1, "{:?}", sv.writes);
    assert_eq!(
        rig.status(0),
        WriteStatus::Sending { attempt: 1, of: 3 },
        "not saved before the unit answered"
    );
    rig.until_saved("saved");
    assert_eq!(
        rig.status(0),
        WriteStatus::Saved {
            holds: "4 A, switch 3, current fault off".into(),
            matches: true
        }
    );
    let cfg = rig.sim.stats().config;
    assert_eq!(cfg.devices[9].circuit_breaker, 4);
    assert_eq!(cfg.devices[9].switch_id, SwitchId::Input(3));
    let ack = rig.app.model().last_spec_ack.unwrap().value;
    assert_eq!((ack.device_id, ack.error), (9, None));
    assert_eq!(rig.sent("DEVICE_SPEC"), 1);
    let buf = rig.render();
    assert_eq!(fg_of(&buf, "saved ✓"), Color::Green);
    assert!(!rig.app.view().setup.is_edited(Page::Device));

    // A name typed and the device hidden: DEVICE_NAME acked, DEVICE_ENABLE re-read.
    for _ in 0..2 {
        rig.key(KeyCode::Down);
    }
    for _ in 0..5 {
        rig.key(KeyCode::Backspace);
    }
    rig.keys("Nav 2 GPS");
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Right);
    rig.key(KeyCode::Enter);
    rig.until("both saved", Duration::from_secs(4), |app| {
        let w = &app.view().setup.writes;
        w.len() == 2
            && w.iter()
                .all(|w| matches!(w.status, WriteStatus::Saved { matches: true, .. }))
    });
    let cfg = rig.sim.stats().config;
    assert_eq!(&cfg.names[9][..10], b"Nav 2 GPS\0");
    assert!(!cfg.enabled[9]);
}

#[test]
fn refusals_are_in_words_whether_from_the_unit_or_before_sending() {
    let mut rig = Rig::on_setup_of(9);
    let before = rig.sim.stats().config.devices[9];

    // Typed past the pin's range: refused here, nothing goes out.
    rig.key(KeyCode::Down);
    rig.keys("20");
    rig.key(KeyCode::Enter);
    match rig.status(0) {
        WriteStatus::Refused {
            why,
            by_unit: false,
        } => assert_eq!(
            why,
            "Invalid circuit breaker value: 20 A is outside 1–5 A for 5A-6 (ICD Table 40)"
        ),
        s => panic!("{s:?}"),
    }
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(300));
    assert_eq!(rig.sent("DEVICE_SPEC"), 0);

    // The same value past our own check: the unit's SPEC_ACK code in words, and the
    // re-read shows what it kept.
    rig.app.setup_send_unchecked(
        vec![
            DeviceSpec {
                circuit_breaker: 9,
                ..before
            }
            .into(),
        ],
        Instant::now(),
    );
    rig.until_first_write("refused by the unit", Duration::from_secs(3), |s| {
        matches!(s, WriteStatus::Refused { by_unit: true, .. })
    });
    match rig.status(0) {
        WriteStatus::Refused { why, .. } => {
            assert!(
                why.starts_with(
                    "Invalid circuit breaker value: 9 A is outside 1–5 A for 5A-6 (ICD Table 40)"
                ),
                "{why}"
            );
            assert!(
                why.ends_with("the unit holds 2 A, switch 2, current fault off"),
                "{why}"
            );
        }
        s => panic!("{s:?}"),
    }
    assert_eq!(rig.sim.stats().config.devices[9], before);
    let buf = rig.render();
    assert_eq!(fg_of(&buf, "refused by the unit"), Color::Red);
    assert!(text(&buf).contains("Invalid circuit breaker value"));
}

#[test]
fn a_silent_unit_is_retried_three_times_then_no_answer_and_the_page_keeps_going() {
    let mut rig = Rig::on_setup_of(9);
    rig.sim.inject(SimCommand::Silent(Duration::from_secs(6)));
    rig.key(KeyCode::Down);
    rig.keys("3");
    let start = Instant::now();
    rig.key(KeyCode::Enter);
    // Keys still work while the write waits: the loop never blocks.
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(200));
    let t = Instant::now();
    rig.key(KeyCode::Tab);
    assert!(t.elapsed() < Duration::from_millis(50));
    assert_eq!(rig.app.view().setup.page, Page::System);
    assert!(matches!(rig.status(0), WriteStatus::Sending { .. }));
    rig.until_first_write("no answer", Duration::from_secs(5), |s| {
        *s == WriteStatus::NoAnswer
    });
    let took = start.elapsed();
    assert!(
        took >= Duration::from_millis(2900) && took < Duration::from_millis(4000),
        "three tries a second apart, then give up: {took:?}"
    );
    assert_eq!(rig.sent("DEVICE_SPEC"), 3);
    let buf = rig.render();
    assert_eq!(fg_of(&buf, "no answer after 3 tries"), Color::Red);
    assert!(!text(&buf).contains("saved ✓"));
    // Communication is lost, so the setting stays unknown and keeps being asked for;
    // when the unit talks again the page shows what it stored while silent.
    assert!(
        rig.app
            .model()
            .is_unknown(vpx_efis::model::Setting::DeviceSpec(9))
    );
    rig.until_first_write(
        "the re-read after the silence",
        Duration::from_secs(12),
        |s| matches!(s, WriteStatus::ReadBack { .. }),
    );
    assert_eq!(rig.sim.stats().config.devices[9].circuit_breaker, 3);
    assert_eq!(
        rig.status(0),
        WriteStatus::ReadBack {
            holds: "3 A, switch 2, current fault off".into(),
            matches: true,
            acked: false
        }
    );
    assert!(
        rig.sent("DEVICE_SPEC_QUERY") >= 2,
        "asked while silent, then answered"
    );
}

#[test]
fn a_flap_position_run_to_and_captured_on_the_setup_screen_is_what_flap_spec_carries() {
    let mut rig = Rig::on_setup_of(9);
    rig.tab_to(Page::Flaps);
    rig.until("live flap position", Duration::from_secs(2), |app| {
        app.model().live_flap_trim(Instant::now()).is_some()
    });
    // Hold flaps down about 1.5 s as a terminal without key release reports it.
    let start = Instant::now();
    rig.key(KeyCode::Char('d'));
    assert!(rig.app.motor_run().is_some(), "the motor runs from here");
    rig.app.pump_until(start + Duration::from_millis(500));
    while start.elapsed() < Duration::from_millis(1500) {
        rig.key(KeyCode::Char('d'));
        rig.app
            .pump_until(Instant::now() + Duration::from_millis(33));
    }
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(700));
    let stats = rig.sim.stats();
    assert!(!stats.flap_running, "stopped after the key");
    assert_eq!(
        stats.flap_starvations, 0,
        "the same safe stream as the page"
    );
    assert_eq!(stats.flap_late, 0, "no gap over 250 ms between FLAP_MOVEs");
    let pos = stats.flap_position;
    assert!((30..90).contains(&pos), "flaps ran down to {pos}");
    rig.until(
        "the status to show where it stopped",
        Duration::from_secs(1),
        |app| {
            app.model()
                .live_flap_trim(Instant::now())
                .is_some_and(|f| f.flap_position == pos)
        },
    );

    // Midpoint 1 is the fifth field: capture, then send.
    for _ in 0..4 {
        rig.key(KeyCode::Down);
    }
    rig.key(KeyCode::Char('p'));
    assert_eq!(rig.app.view().setup.forms.flap.midpoint_1, pos);
    rig.key(KeyCode::Enter);
    rig.until("FLAP_SPEC saved", Duration::from_secs(3), |app| {
        matches!(
            app.view().setup.writes.first().map(|w| &w.status),
            Some(WriteStatus::Saved { matches: true, .. })
        )
    });
    assert_eq!(rig.app.view().setup.writes[0].what, "FLAP_SPEC");
    let flap = rig.sim.stats().config.flap;
    assert_eq!(flap.midpoint_1, pos, "the unit holds the captured position");
    assert_eq!((flap.up, flap.midpoint_2, flap.down), (20, 160, 220));
    assert_eq!(rig.app.model().flap_spec.unwrap().value.midpoint_1, pos);
}

#[test]
fn a_backup_saved_from_the_setup_screen_restores_an_edit_and_erase_asks_first() {
    let mut rig = Rig::on_setup_of(9);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("unit.toml");
    rig.key(KeyCode::BackTab);
    assert_eq!(rig.app.view().setup.page, Page::Backup);
    rig.keys(file.to_str().unwrap());
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Enter);
    let (saved, made) = vpx_efis::backup::load_made(&file).expect("a backup file");
    // It says where it came from, as `vpx-efis backup` does.
    let made = made.expect("a [made] section");
    assert!(made.from.starts_with("/dev/"), "{made:?}");
    assert!(
        !made.simulated && made.by.starts_with("vpx-efis "),
        "{made:?}"
    );
    let original = rig.sim.stats().config;
    assert_eq!(
        vpx_efis::backup::normalized(&saved.config),
        vpx_efis::backup::normalized(&original)
    );

    // Change the breaker on the device page, then load the backup back.
    rig.key(KeyCode::Tab);
    rig.key(KeyCode::Down);
    rig.keys("4");
    rig.key(KeyCode::Enter);
    rig.until_saved("the edit saved");
    assert_eq!(rig.sim.stats().config.devices[9].circuit_breaker, 4);
    rig.key(KeyCode::BackTab);
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Enter); // Load a backup
    match &rig.app.view().setup.dialog {
        vpx_efis::setup::view::Dialog::Load {
            changes, writes, ..
        } => {
            assert_eq!(*writes, 1);
            assert!(changes[0].contains("4 A → 2 A"), "{changes:?}");
        }
        d => panic!("{d:?} {:?}", rig.app.view().setup.message),
    }
    rig.keys("y");
    rig.until_saved("the backup applied");
    assert_eq!(rig.sim.stats().config.devices[9].circuit_breaker, 2);

    // EEPROM_ERASE: Esc sends nothing, y erases and the page re-reads.
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Down);
    rig.key(KeyCode::Enter);
    assert!(matches!(
        rig.app.view().setup.dialog,
        vpx_efis::setup::view::Dialog::Erase { .. }
    ));
    let buf = rig.render();
    assert!(text(&buf).contains("b  back up first to"), "{}", text(&buf));
    rig.key(KeyCode::Esc);
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(200));
    assert_eq!(rig.sent("EEPROM_ERASE"), 0);
    assert_eq!(rig.sim.stats().config, original);
    rig.key(KeyCode::Enter);
    rig.keys("y");
    rig.until("the erase answered", Duration::from_secs(4), |app| {
        matches!(
            app.view().setup.erase,
            vpx_efis::setup::view::Diagnostic::Answered { .. }
        )
    });
    assert_eq!(
        rig.sim.stats().config,
        vpx_efis::protocol::config::UnitConfig::default()
    );
    rig.until(
        "the re-read shows the factory breaker",
        Duration::from_secs(4),
        |app| app.model().device_specs[9].is_some_and(|s| s.value.switch_id == SwitchId::Off),
    );
}

/// ICD Table 12: a non-zero EEPROM_ERASE response code means the erase did not
/// complete, so the screen must not say the unit holds the factory settings.
#[test]
fn a_failed_erase_is_said_plainly_and_not_shown_as_factory_settings() {
    let dir = tempfile::tempdir().unwrap();
    let eeprom_dir = dir.path().join("eeprom");
    std::fs::create_dir(&eeprom_dir).unwrap();
    let mut rig = Rig::with_eeprom(Some(eeprom_dir.join("vpx.json")));
    rig.open_setup_on(9);
    // The unit's EEPROM can no longer be written: its erase answers code 1.
    std::fs::remove_dir_all(&eeprom_dir).unwrap();
    rig.key(KeyCode::BackTab);
    assert_eq!(rig.app.view().setup.page, Page::Backup);
    for _ in 0..4 {
        rig.key(KeyCode::Down);
    }
    rig.key(KeyCode::Enter);
    assert!(matches!(
        rig.app.view().setup.dialog,
        vpx_efis::setup::view::Dialog::Erase { .. }
    ));
    rig.keys("y");
    rig.until("the erase answered", Duration::from_secs(4), |app| {
        matches!(
            app.view().setup.erase,
            vpx_efis::setup::view::Diagnostic::Answered { .. }
        )
    });
    let (_, said) = rig.app.view().setup.message.clone().expect("a message");
    assert!(said.contains("failed (response code 1)"), "{said}");
    assert!(!said.contains("factory settings"), "{said}");
    let buf = rig.render();
    assert!(text(&buf).contains("EEPROM_ERASE failed"), "{}", text(&buf));
}

/// The text of the screen row that holds `needle`.
fn row_with(buf: &Buffer, needle: &str) -> String {
    text(buf)
        .lines()
        .find(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("{needle:?} not on screen:\n{}", text(buf)))
        .to_string()
}

impl Rig {
    /// Esc back to the device list, drawn.
    fn back_to_devices(&mut self) -> Buffer {
        for _ in 0..3 {
            if self.app.view().screen == Screen::Devices {
                break;
            }
            self.key(KeyCode::Esc);
        }
        assert_eq!(self.app.view().screen, Screen::Devices);
        self.render()
    }
}

#[test]
fn a_breaker_whose_spec_ack_is_lost_is_unknown_then_reread_and_shown_as_the_unit_holds_it() {
    let mut rig = Rig::on_setup_of(9);
    rig.sim.inject(SimCommand::DropSpecAcks(true));
    let queries_before = rig.sent("DEVICE_SPEC_QUERY");
    rig.key(KeyCode::Down); // breaker 2 A → 4 A
    rig.keys("4");
    rig.key(KeyCode::Enter);
    rig.until("three tries", Duration::from_secs(5), |app| {
        common::app::sent(app, "DEVICE_SPEC") == 3
    });
    rig.until_first_write("the write to end", Duration::from_secs(3), |s| {
        !matches!(s, WriteStatus::Sending { .. })
    });
    // The unit stored it; only its answers were lost.
    assert_eq!(rig.sim.stats().config.devices[9].circuit_breaker, 4);
    assert!(rig.sim.stats().wire.spec_acks_dropped >= 3);
    // The page gave up on the write, said the breaker was unknown, and asked again.
    assert!(
        rig.app.model().events.iter().any(|e| e
            .text
            .contains("DEVICE_SPEC for 5A-6: the write went unanswered")),
        "the breaker was marked unknown"
    );
    rig.until_first_write("the re-read's answer", Duration::from_secs(3), |s| {
        matches!(s, WriteStatus::ReadBack { .. })
    });
    assert!(rig.sent("DEVICE_SPEC_QUERY") > queries_before);
    assert_eq!(
        rig.sent("DEVICE_SPEC"),
        3,
        "the write itself is not sent a fourth time"
    );
    assert_eq!(
        rig.status(0),
        WriteStatus::ReadBack {
            holds: "4 A, switch 2, current fault off".into(),
            matches: true,
            acked: false
        }
    );
    let buf = rig.render();
    let screen = text(&buf);
    assert!(
        screen.contains("no answer to the write; re-read: the unit holds 4 A"),
        "{screen}"
    );
    assert!(
        row_with(&buf, "Circuit breaker").contains("4 A"),
        "{screen}"
    );
    assert!(!screen.contains("? A"), "{screen}");
    let row = row_with(&rig.back_to_devices(), "GPS 1");
    assert!(row.contains(" 4A "), "device list CB column: {row}");
    assert!(!row.contains("2A"), "{row}");
}

#[test]
fn a_name_written_while_the_unit_falls_silent_shows_unknown_until_the_unit_answers() {
    let mut rig = Rig::on_setup_of(9);
    rig.sim.inject(SimCommand::DropSpecAcks(true));
    for _ in 0..4 {
        rig.key(KeyCode::Down); // the name
    }
    for _ in 0..5 {
        rig.key(KeyCode::Backspace);
    }
    rig.keys("Nav 2");
    rig.key(KeyCode::Enter);
    rig.until_first_write("the third try", Duration::from_secs(5), |s| {
        *s == WriteStatus::Sending { attempt: 3, of: 3 }
    });
    // The line goes quiet as the last try times out: the first re-reads are lost too.
    rig.sim
        .inject(SimCommand::Silent(Duration::from_millis(1800)));
    rig.until_first_write("no answer", Duration::from_secs(3), |s| {
        *s == WriteStatus::NoAnswer
    });
    assert!(
        rig.app
            .model()
            .is_unknown(vpx_efis::model::Setting::Name(9))
    );
    let buf = rig.render();
    let screen = text(&buf);
    assert!(row_with(&buf, "Name").contains("? re-reading…"), "{screen}");
    assert!(!row_with(&buf, "Name").contains("GPS 1"), "{screen}");
    assert_eq!(fg_of(&buf, "no answer after 3 tries"), Color::Red);
    rig.until_first_write("the re-read's answer", Duration::from_secs(8), |s| {
        matches!(s, WriteStatus::ReadBack { .. })
    });
    assert!(rig.sent("DEVICE_NAME_QUERY") >= 1);
    assert_eq!(&rig.sim.stats().config.names[9][..6], b"Nav 2\0");
    let buf = rig.render();
    assert!(
        row_with(&buf, "Name").contains("\"Nav 2\""),
        "{}",
        text(&buf)
    );
    let screen = text(&rig.back_to_devices());
    assert!(screen.contains("Nav 2"), "{screen}");
    assert!(!screen.contains("GPS 1"), "{screen}");
}

#[test]
fn a_flap_spec_whose_spec_ack_is_lost_is_reread_and_the_list_shows_the_units_breaker() {
    let mut rig = Rig::on_setup_of(9);
    rig.tab_to(Page::Flaps);
    rig.sim.inject(SimCommand::DropSpecAcks(true));
    for _ in 0..9 {
        rig.key(KeyCode::Down); // the flap breaker, 7 A
    }
    rig.key(KeyCode::Right);
    assert_eq!(rig.app.view().setup.forms.flap.circuit_breaker, 8);
    rig.key(KeyCode::Enter);
    rig.until_first_write("the re-read's answer", Duration::from_secs(8), |s| {
        matches!(s, WriteStatus::ReadBack { .. })
    });
    assert_eq!(rig.sent("FLAP_SPEC"), 3);
    assert_eq!(rig.sim.stats().config.flap.circuit_breaker, 8);
    assert!(matches!(
        rig.status(0),
        WriteStatus::ReadBack {
            matches: true,
            acked: false,
            ..
        }
    ));
    assert_eq!(rig.app.model().flap_spec.unwrap().value.circuit_breaker, 8);
    // The flaps row is below the fold of a 40-line list: its CB cell comes from this.
    let row = rig
        .app
        .model()
        .circuits(Instant::now())
        .into_iter()
        .find(|c| c.id == 0)
        .unwrap();
    assert_eq!((row.breaker, row.spec_unknown), (Some(8), false));
}

/// The page connects while the unit is silent: every connect-time query is lost. The
/// Device page shows nothing as the unit's, Enter sends no DEVICE_SPEC built on
/// Appendix F's values, the settings are asked again long before the minute's
/// refresh, and once the unit answers the form shows what it holds and the write
/// keeps the pin's switch.
#[test]
fn connected_to_a_silent_unit_the_device_page_writes_nothing_until_the_unit_answers() {
    let silent_at_start =
        format!("{SCENARIO}\n[[event]]\nat = 0.0\ndo = \"silent\"\nseconds = 6.0\n");
    let mut rig = Rig::with(&silent_at_start, None);
    rig.until("connected", Duration::from_secs(3), |app| {
        matches!(
            app.model().connection,
            vpx_efis::model::Connection::Connected { .. }
        )
    });
    let connected = Instant::now();
    for _ in 0..40 {
        if rig.app.view().selected == Some(9) {
            break;
        }
        rig.key(KeyCode::Char('j'));
    }
    assert_eq!(rig.app.view().selected, Some(9));
    rig.key(KeyCode::Char('c'));
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(50));
    assert_eq!(rig.app.view().setup.forms.device.device_id, 9);
    let buf = rig.render();
    let screen = text(&buf);
    let row = row_with(&buf, "Switch");
    assert!(row.contains("? not yet read from the unit"), "{screen}");
    assert!(
        !row.contains(" off "),
        "Appendix F's switch is not shown: {screen}"
    );
    // The breaker cannot be typed, and Enter sends nothing.
    rig.key(KeyCode::Down);
    rig.keys("3");
    rig.key(KeyCode::Enter);
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(200));
    let said = rig.app.view().setup.message.clone().unwrap().1;
    assert!(
        said.contains("not yet read from the unit — re-reading; try again when it answers"),
        "{said}"
    );
    assert_eq!(
        rig.sent("DEVICE_SPEC"),
        0,
        "no DEVICE_SPEC before the spec is heard"
    );
    // The connect set (33 DEVICE_SPEC_QUERYs) is lost; the re-reads follow it.
    rig.until("a re-read", Duration::from_secs(6), |app| {
        common::app::sent(app, "DEVICE_SPEC_QUERY") > 33
    });
    assert!(
        connected.elapsed() < Duration::from_secs(6),
        "re-read {:?} after connect, not at the 60 s refresh",
        connected.elapsed()
    );
    assert!(rig.app.model().device_specs[9].is_none(), "still silent");
    rig.key(KeyCode::Enter);
    assert_eq!(rig.sent("DEVICE_SPEC"), 0);
    // The unit talks again and answers: the form shows what it holds.
    rig.until("pin 9's settings", Duration::from_secs(10), |app| {
        let m = app.model();
        m.device_specs[9].is_some() && m.names[9].is_some() && m.enabled[9].is_some()
    });
    rig.app
        .pump_until(Instant::now() + Duration::from_millis(100));
    let unit = DeviceSpec {
        device_id: 9,
        circuit_breaker: 2,
        switch_id: SwitchId::Input(2),
        current_fault: false,
        switch_raw: None,
    };
    assert_eq!(rig.app.view().setup.forms.device, unit);
    let buf = rig.render();
    let screen = text(&buf);
    assert!(
        row_with(&buf, "Circuit breaker").contains("2 A"),
        "{screen}"
    );
    assert!(row_with(&buf, "Switch").contains("switch 2"), "{screen}");
    assert!(row_with(&buf, "Name").contains("GPS 1"), "{screen}");
    // Every setting the unit holds for the pin, all but which pin it is.
    for field in &Page::Device.fields()[1..] {
        let row = row_with(&buf, field.label());
        assert!(!row.contains("not yet read"), "{screen}");
    }
    assert_eq!(rig.sent("DEVICE_SPEC"), 0);
    // Now the breaker goes out with the unit's switch kept.
    rig.keys("3");
    rig.key(KeyCode::Enter);
    rig.until_saved("saved");
    let cfg = rig.sim.stats().config;
    assert_eq!(cfg.devices[9].circuit_breaker, 3);
    assert_eq!(cfg.devices[9].switch_id, SwitchId::Input(2), "switch kept");
}

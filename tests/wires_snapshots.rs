//! The page with the load file's wires: the device list marks a breaker
//! over its wire with a symbol and a word, and the detail pane gives the selected
//! circuit's wire and verdict, at 80×24 and 120×40. The figures are hand-worked from
//! AC 43.13-1B: 22 AWG allows a 5 A breaker (Table 11-3), so the strobe's 6 A is
//! unprotected; the nav lights' 22 AWG run of 24 ft and 10 ft of return at 2.0 A
//! drops 0.0162 Ω/ft × 34 ft × 2.0 A = 1.10 V (Table 11-9), over the 0.5 V a 14 V
//! system allows (Table 11-6), and 0.5 / (0.0162 × 2.0) = 15.4 ft would pass.

use std::time::{Duration, Instant};

use ratatui::buffer::Buffer;
use ratatui::style::Color;

use vpx_efis::loads::LoadCircuit;
use vpx_efis::loads::wire::Wire;
use vpx_efis::loads::wiring::WireRun;
use vpx_efis::model::{Model, Source};
use vpx_efis::protocol::Packet;
use vpx_efis::protocol::device::EFIS;
use vpx_efis::protocol::message::{
    DeviceEnable, DeviceName, DeviceSpec, DeviceStatus, EnableFlag, FaultStatus, HardwareVersion,
    OvervoltageLimit, SignedTenths, SwitchId, SwitchInputs, SystemSpec, SystemStatus, Tenths,
    Version,
};
use vpx_efis::ui::state::ViewState;

mod common;
use common::screen::{find, plain_text, rendered};

const NAV: u8 = 4; // 5A-1
const STROBE: u8 = 0x11; // 10A-1
const LANDING: u8 = 0x12; // 10A-2

/// EFIS, nav lights, strobe and landing light, on a 14.1 V bus with a 16 V limit.
fn unit() -> (Model, Instant) {
    let t0 = Instant::now();
    let mut m = Model::new(Source::Serial {
        path: "/dev/ttyUSB0".into(),
    });
    m.note_connected(t0, "/dev/ttyUSB0".into());
    let mut cnt = 0u8;
    let mut apply = |m: &mut Model, msg: vpx_efis::protocol::Message| {
        cnt = cnt.wrapping_add(1);
        m.apply_packet(t0, &Packet::from_vpx(cnt, msg));
    };
    apply(
        &mut m,
        Version {
            hardware_version: HardwareVersion::VpxPro,
            software_major: 1,
            software_minor: 4,
        }
        .into(),
    );
    apply(
        &mut m,
        SystemSpec {
            overvoltage_limit: OvervoltageLimit::V16,
            secondary_alternator: None,
        }
        .into(),
    );
    let wired = [
        (EFIS, "EFIS", 5),
        (NAV, "Nav Lt", 3),
        (STROBE, "Strobe Lt", 6),
        (LANDING, "Landing Lt", 8),
    ];
    for id in 4..=28u8 {
        let flag = if wired.iter().any(|w| w.0 == id) {
            EnableFlag::Enabled
        } else {
            EnableFlag::Disabled
        };
        apply(
            &mut m,
            DeviceEnable {
                device_id: id,
                flag,
            }
            .into(),
        );
    }
    for (id, name, breaker) in wired {
        apply(&mut m, DeviceName::new(id, name).unwrap().into());
        apply(
            &mut m,
            DeviceSpec {
                device_id: id,
                circuit_breaker: breaker,
                switch_id: SwitchId::Input(2),
                current_fault: true,
                switch_raw: None,
            }
            .into(),
        );
    }
    apply(
        &mut m,
        SystemStatus {
            system_current: Tenths(83),
            main_bus_volts: SignedTenths(141),
            internal_temp: 22,
            switches: SwitchInputs::from_word(0b10),
            ..Default::default()
        }
        .into(),
    );
    let mut d = DeviceStatus::default();
    for (id, tenths) in [(EFIS, 28), (NAV, 20), (STROBE, 35)] {
        d.on[id as usize] = true;
        d.current[id as usize] = Tenths(tenths);
    }
    apply(&mut m, d.into());
    apply(&mut m, FaultStatus::with_faults(&[]).into());
    (m, t0 + Duration::from_millis(300))
}

fn run(w: &str, feed: f64, ret: Option<f64>) -> WireRun {
    WireRun {
        wire: Some(Wire::parse(w).unwrap()),
        feed_feet: Some(feed),
        return_feet: ret,
    }
}

/// The load file's lines for the unit: the strobe's breaker over its wire, the nav
/// lights on a long thin run, the landing light right; the EFIS not entered.
fn wires() -> Vec<LoadCircuit> {
    let c = |id, name: &str, wire| LoadCircuit {
        id,
        name: name.into(),
        amps: None,
        duty: [0.0; 7],
        wire,
    };
    vec![
        c(NAV, "Nav Lt", run("22 AWG", 24.0, Some(10.0))),
        c(STROBE, "Strobe Lt", run("22 AWG", 6.0, None)),
        c(LANDING, "Landing Lt", run("16 AWG", 12.0, None)),
        c(EFIS, "EFIS", WireRun::default()),
    ]
}

fn view(selected: u8) -> ViewState {
    ViewState {
        selected: Some(selected),
        wires: wires(),
        ..Default::default()
    }
}

/// The unit's page, `w`×`h`, with circuit `selected` selected: the buffer and its
/// text.
fn screen_of(selected: u8, w: u16, h: u16) -> (Buffer, String) {
    let (m, now) = unit();
    let buf = rendered(&m, &view(selected), now, w, h);
    let screen = plain_text(&buf);
    (buf, screen)
}

/// `screen`'s words with single spaces, so that a phrase wrapped or padded is found.
fn flat(screen: &str) -> String {
    screen.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The list line of the row whose name starts with `name` (the first line holding it).
fn line_of<'a>(screen: &'a str, name: &str) -> &'a str {
    screen
        .lines()
        .find(|l| l.contains(name))
        .unwrap_or_else(|| panic!("no {name:?} row:\n{screen}"))
}

/// The colour of the first cell of `needle` on the first line holding `on_line`.
fn colour(buf: &Buffer, on_line: &str, needle: &str) -> Color {
    buf[find(buf, on_line, needle)].fg
}

#[test]
fn the_list_marks_an_unprotected_wire_and_the_detail_names_it_80x24() {
    let (buf, screen) = screen_of(STROBE, 80, 24);
    insta::assert_snapshot!(screen);
    // A symbol and a word on the strobe's row, in the fault colour; on no other row.
    assert!(line_of(&screen, "10A-1").contains("⚠WIRE"), "{screen}");
    assert!(!line_of(&screen, "5A-1").contains("⚠WIRE"), "{screen}");
    assert!(!line_of(&screen, "10A-2").contains("⚠WIRE"), "{screen}");
    assert_eq!(colour(&buf, "10A-1", "⚠WIRE"), Color::Red);
    assert!(flat(&screen).contains("⚠ UNPROTECTED"), "{screen}");
}

#[test]
fn the_detail_gives_the_drop_and_the_run_that_would_pass_120x40() {
    let (_, screen) = screen_of(NAV, 120, 40);
    insta::assert_snapshot!(screen);
    let flat = flat(&screen);
    assert!(flat.contains("wire 22 AWG"), "{screen}");
    assert!(flat.contains("run 34.0 ft"), "{screen}");
    assert!(flat.contains("allows 5 A"), "{screen}");
    assert!(flat.contains("drop 1.10 V of 0.5 V"), "{screen}");
    assert!(
        flat.contains("⚠ DROP over the limit: a run of at most 15.4 ft would pass"),
        "{screen}"
    );
    // The strobe is still marked in the list, the nav lights (a warning) are not.
    assert!(line_of(&screen, "10A-1").contains("⚠WIRE"), "{screen}");
    assert!(!line_of(&screen, "5A-1").contains("⚠WIRE"), "{screen}");
}

#[test]
fn the_detail_of_a_right_wire_and_of_one_not_entered() {
    let (_, screen) = screen_of(LANDING, 120, 40);
    let flat = flat(&screen);
    // 16 AWG allows 15 A (Table 11-3) over its 8 A breaker; off, so no drop now.
    assert!(
        flat.contains("wire 16 AWG run 12.0 ft (ground at load) allows 15 A ✓ ok"),
        "{screen}"
    );
    let (_, screen) = screen_of(EFIS, 120, 40);
    assert!(
        screen.contains("wire not entered (the load file's wire lines)"),
        "{screen}"
    );
}

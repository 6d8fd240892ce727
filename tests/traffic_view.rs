//! Snapshots of the traffic view (`t`): the list both ways with bytes, the rate table
//! against the ICD, decoder errors where they happened, filters and search. Colour
//! carries meaning here (a missing broadcast is red, a slow one yellow), so the
//! snapshots are the buffer's Debug form, which lists styles, and key cells are also
//! asserted one by one.

use std::time::{Duration, Instant};

use ratatui::buffer::{Buffer, Cell};
use ratatui::style::Color;

use vpx_efis::link::{Crossing, RxItem};
use vpx_efis::model::{Model, Source};
use vpx_efis::protocol::Packet;
use vpx_efis::protocol::message::{
    DeviceStatus, FlapTrimStatus, HardwareVersion, Payload, Ping, SignedTenths, SwitchInputs,
    SystemStatus, Tenths, Version,
};
use vpx_efis::traffic::{Health, KindFilter};
mod common;
mod themes;

use vpx_efis::ui::{state::Screen, state::ViewState};

fn system() -> SystemStatus {
    SystemStatus {
        system_current: Tenths(84),
        main_bus_volts: SignedTenths(139),
        internal_temp: 25,
        switches: SwitchInputs::from_word(0b11),
        ..Default::default()
    }
}

fn devices() -> DeviceStatus {
    let mut d = DeviceStatus::default();
    d.on[2] = true;
    d.current[2] = Tenths(25);
    d
}

/// The snapshots' configured unit, without its roll trim.
fn flap_trim() -> FlapTrimStatus {
    let mut ft = common::configured::flap_trim((20, 128, 0));
    ft.roll_trim.enabled = false;
    (ft.roll_trim_up, ft.roll_trim_down, ft.roll_trim_neutral) = (0, 0, 0);
    ft
}

struct Session {
    model: Model,
    t0: Instant,
}

impl Session {
    fn at(&self, ms: u64) -> Instant {
        self.t0 + Duration::from_millis(ms)
    }

    fn rx(&mut self, ms: u64, p: Packet) {
        let at = self.at(ms);
        self.model
            .traffic
            .note_rx(at, &RxItem::Packet(p), &p.to_bytes());
        self.model.apply_packet(at, &p);
    }

    fn rx_error(&mut self, ms: u64, item: RxItem, raw: &[u8]) {
        let at = self.at(ms);
        self.model.traffic.note_rx(at, &item, raw);
    }

    fn tx(&mut self, ms: u64, p: Packet) {
        let at = self.at(ms);
        self.model.traffic.note_tx(at, Some(&p), &p.to_bytes());
        self.model.note_sent(at, &p);
    }
}

/// Seven seconds after connecting: SYSTEM_STATUS at 1 Hz, DEVICE_STATUS stopped after
/// 3 s (missing), FLAP_TRIM_STATUS at 5 Hz instead of 10 (slow), the page's VERSION
/// request and its reply, and a burst of line noise at 2.5 s the decoder threw away.
fn session() -> (Model, Instant) {
    let t0 = Instant::now();
    let mut s = Session {
        model: Model::new(Source::Serial {
            path: "/dev/ttyUSB0".into(),
        }),
        t0,
    };
    s.model.note_connected(t0, "/dev/ttyUSB0".into());
    s.model.traffic.note_connected(t0);
    s.tx(20, Packet::request(1, Ping { ack: false }));
    s.rx(35, Packet::from_vpx(1, Ping { ack: true }));
    s.tx(60, Packet::request(2, Version::REQUEST));
    s.rx(
        80,
        Packet::from_vpx(
            2,
            Version {
                hardware_version: HardwareVersion::VpxPro,
                software_major: 1,
                software_minor: 4,
            },
        ),
    );
    // The link reports in time order; so does this.
    let mut rx: Vec<(u64, Packet)> = Vec::new();
    for sec in 0..7u64 {
        rx.push((sec * 1000 + 100, Packet::from_vpx(0, system())));
        if sec < 3 {
            rx.push((sec * 1000 + 150, Packet::from_vpx(0, devices())));
        }
        for k in 0..5u64 {
            rx.push((sec * 1000 + 120 + k * 200, Packet::from_vpx(0, flap_trim())));
        }
    }
    rx.sort_by_key(|(ms, _)| *ms);
    for (ms, p) in rx {
        if ms > 2500 && s.model.traffic.errors.is_empty() {
            s.rx_error(2500, RxItem::Skipped, &[0x13, 0x37, 0x00]);
            s.rx_error(
                2500,
                RxItem::BadChecksum,
                &[0xE7, 0x7E, 0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x55],
            );
        }
        s.rx(ms, p);
    }
    (s.model, t0 + Duration::from_millis(7300))
}

fn traffic_view() -> ViewState {
    ViewState {
        screen: Screen::Traffic,
        ..Default::default()
    }
}

fn draw(model: &Model, now: Instant, w: u16, h: u16) -> Buffer {
    let buf = common::screen::rendered(model, &traffic_view(), now, w, h);
    themes::check_themes("traffic_view", &buf);
    buf
}

fn lines(buf: &Buffer) -> Vec<String> {
    (0..buf.area.height)
        .map(|y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol().to_string())
                .collect()
        })
        .collect()
}

/// The cell where `needle` starts on the first line that has `on_line`.
fn cell<'a>(buf: &'a Buffer, on_line: &str, needle: &str) -> &'a Cell {
    for (y, line) in lines(buf).iter().enumerate() {
        if line.contains(on_line)
            && let Some(i) = line.find(needle)
        {
            return &buf[(line[..i].chars().count() as u16, y as u16)];
        }
    }
    panic!(
        "no line with {on_line:?} and {needle:?}:\n{}",
        lines(buf).join("\n")
    );
}

#[test]
fn normal_rates_against_the_icd_with_colours() {
    let (model, now) = session();
    let log = &model.traffic;
    assert_eq!(
        log.health(Crossing::Rx, SystemStatus::NAME, now),
        Health::Ok
    );
    let buf = draw(&model, now, 140, 40);
    insta::assert_snapshot!(format!("{buf:?}"));
    let fg = |line: &str, word: &str| cell(&buf, line, word).fg;
    assert_eq!(
        fg("SYSTEM_STATUS", " ok"),
        Color::Reset,
        "ok is the word, not the colour"
    );
    assert_eq!(fg("SYSTEM_STATUS ", "SYSTEM_STATUS"), Color::Green);
    assert_eq!(fg("DEVICE_STATUS ", "MISSING"), Color::Red);
    assert_eq!(fg("FLAP_TRIM_STATUS ", "SLOW"), Color::Yellow);
    assert_eq!(fg("FAULT_STATUS", "quiet = no faults"), Color::Gray);
    // The newest frame is at the bottom of the list, and what we sent is cyan.
    let all = lines(&buf);
    let last_row = all.iter().rev().nth(2).unwrap();
    // Its time, its name, and its bytes beside the fields.
    for want in ["6.920", "FLAP_TRIM_STATUS", "E7 7E"] {
        assert!(last_row.contains(want), "no {want:?} in {last_row}");
    }
}

/// The page drawn at 140×40, and the rows of its list.
fn listed(model: &Model, now: Instant) -> (Buffer, Vec<String>) {
    let buf = draw(model, now, 140, 40);
    let rows = list_rows(&buf);
    (buf, rows)
}

fn list_rows(buf: &Buffer) -> Vec<String> {
    let all = lines(buf);
    let head = all
        .iter()
        .position(|l| l.contains("time s"))
        .expect("list header");
    all[head + 1..all.len() - 2]
        .iter()
        .filter(|l| !l.trim().is_empty())
        .cloned()
        .collect()
}

#[test]
fn filtered_by_direction_and_type_shows_only_those_and_says_so() {
    let (mut model, now) = session();
    model.traffic.view.dir = Some(Crossing::Rx);
    model.traffic.view.kind = KindFilter::Message(DeviceStatus::NAME);
    let buf = draw(&model, now, 140, 40);
    insta::assert_snapshot!(lines(&buf).join("\n"));
    let rows = list_rows(&buf);
    assert_eq!(rows.len(), 3, "{rows:#?}");
    assert!(
        rows.iter()
            .all(|r| r.contains(" rx ") && r.contains("DEVICE_STATUS"))
    );
    assert!(
        lines(&buf)
            .iter()
            .any(|l| l.contains("showing rx only, DEVICE_STATUS"))
    );

    // Only what we sent: the two requests, in cyan.
    model.traffic.view.kind = KindFilter::All;
    model.traffic.view.dir = Some(Crossing::Tx);
    let (buf, rows) = listed(&model, now);
    assert!(
        rows.len() == 2 && rows.iter().all(|r| r.contains(" tx ")),
        "{rows:#?}"
    );
    assert_eq!(cell(&buf, "cnt 2", "VERSION").fg, Color::Cyan);
}

#[test]
fn decoder_errors_appear_where_they_happened_in_red_and_yellow() {
    let (mut model, now) = session();
    // Put the cursor on the bad checksum: the list centres on it, among the frames
    // received around it.
    let bad = model
        .traffic
        .entries()
        .find(|e| e.name() == "BAD CHECKSUM")
        .unwrap()
        .seq;
    model.traffic.view.cursor = Some(bad);
    let buf = draw(&model, now, 140, 40);
    insta::assert_snapshot!(format!("{buf:?}"));
    let rows = list_rows(&buf);
    let i = rows
        .iter()
        .position(|r| r.contains("BAD CHECKSUM"))
        .unwrap();
    assert!(rows[i - 1].contains("DROPPED BYTES") && rows[i - 1].contains("13 37 00"));
    assert!(
        rows[i - 2].contains("2.320") && rows[i + 1].contains("2.520"),
        "in time order:\n{}",
        rows[i - 2..=i + 1].join("\n")
    );
    assert_eq!(
        cell(&buf, "DROPPED BYTES", "DROPPED BYTES").fg,
        Color::Yellow
    );
    // The errors line under the rate table counts them even when scrolled away.
    assert!(
        lines(&buf)
            .iter()
            .any(|l| l.contains("bad checksum 1") && l.contains("dropped bytes 1"))
    );
    // Errors only.
    model.traffic.view.cursor = None;
    model.traffic.view.kind = KindFilter::Errors;
    let (buf, rows) = listed(&model, now);
    assert_eq!(rows.len(), 2, "{rows:#?}");
    assert_eq!(cell(&buf, "BAD CHECKSUM", "BAD CHECKSUM").fg, Color::Red);
}

#[test]
fn search_highlights_matches_and_pause_holds_the_list_while_counting() {
    let (mut model, now) = session();
    model.traffic.view.search = "ack flag 1".into();
    model.traffic.view.frozen_at = Some(model.traffic.total());
    let p = Packet::from_vpx(9, Ping { ack: true });
    model
        .traffic
        .note_rx(now, &RxItem::Packet(p), &p.to_bytes());
    let first_ping = model
        .traffic
        .entries()
        .find(|e| e.name() == "PING" && e.dir == Crossing::Rx)
        .map(|e| e.seq);
    model.traffic.view.cursor = first_ping;
    let buf = draw(&model, now, 140, 40);
    let all = lines(&buf);
    assert!(
        all.iter().any(|l| l.contains("PAUSED, 1 new")),
        "{}",
        all.join("\n")
    );
    assert!(
        all.iter()
            .any(|l| l.contains("search ack flag 1 1 match(es)"))
    );
    // The held-back PING is not listed, but its count is.
    assert_eq!(model.traffic.stat(Crossing::Rx, "PING").unwrap().count, 2);
    assert_eq!(
        list_rows(&buf)
            .iter()
            .filter(|r| r.contains("PING"))
            .count(),
        2
    );
    // Another hit is black on yellow (the cursor row is reversed instead).
    let version = model
        .traffic
        .entries()
        .find(|e| e.name() == "VERSION")
        .map(|e| e.seq);
    model.traffic.view.cursor = version;
    let buf = draw(&model, now, 140, 40);
    let hit = cell(&buf, "ack flag 1", "PING");
    assert_eq!((hit.fg, hit.bg), (Color::Black, Color::Yellow));
    assert_ne!(
        cell(&buf, "ack flag 0", "PING").bg,
        Color::Yellow,
        "a non-match is not highlighted"
    );
}

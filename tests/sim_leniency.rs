//! What the virtual VP-X takes from an EFIS that is not ours: every request here is
//! written by hand from the ICD's tables (Table 1 header, §4.1.3 checksum, the
//! message's own table), never produced by our encoder, and fed to the sans-IO unit on
//! a fake clock. "Be liberal in what you accept": each test is one place where an
//! independent EFIS could read the ICD differently from us.

use std::time::{Duration, Instant};

use vpx_efis::protocol::decoder::{Decoder, Event};
use vpx_efis::protocol::message::*;
use vpx_efis::protocol::{Message, Packet};
use vpx_efis::sim::{Scenario, SimCommand, SimStats, Unit, UnitOptions};

/// Flaps and pitch trim configured, both in mid travel; device 9 on switch 3.
const AIRCRAFT: &str = r#"
[[device]]
id = 9
breaker = 2
switch = 3
load = 1.2

[flap]
up = 20
down = 220
position = 100

[pitch_trim]
up = 20
down = 235
neutral = 100
position = 100
"#;

/// A request frame, EFIS (0x01) to VP-X (0x00), from ICD Table 1 and §4.1.3: XOR of
/// every byte before the checksum, sync bytes included, then inverted.
fn frame(major: u8, minor: u8, cnt: u8, payload: &[u8]) -> Vec<u8> {
    let mut f = vec![
        0xE7,
        0x7E,
        major,
        minor,
        cnt,
        0x01,
        0x00,
        payload.len() as u8,
    ];
    f.extend_from_slice(payload);
    let x = f.iter().fold(0u8, |a, b| a ^ b);
    f.push(!x);
    f
}

struct Bench {
    unit: Unit,
    now: Instant,
    rx: Decoder,
    seen: Vec<Packet>,
    raw: Vec<u8>,
}

impl Bench {
    fn new(toml: &str) -> Bench {
        let now = Instant::now();
        let s = Scenario::from_toml(toml).unwrap();
        Bench {
            unit: Unit::with_memory_eeprom(&s, UnitOptions::default(), now),
            now,
            rx: Decoder::new(),
            seen: Vec::new(),
            raw: Vec::new(),
        }
    }

    fn collect(&mut self) {
        let out = self.unit.take_output();
        self.raw.extend_from_slice(&out);
        let seen = &mut self.seen;
        self.rx.push(&out, |e| {
            if let Event::Frame(f) = e {
                seen.push(Packet::parse(&f).unwrap());
            }
        });
    }

    fn feed(&mut self, bytes: &[u8]) {
        self.unit.feed(bytes, self.now);
        self.collect();
    }

    /// SOFTWARE_UPDATE (0x10/0x02, ICD §6.1.3, count `cnt`, no payload): the unit restarts
    /// into its bootloader; what it wrote before is forgotten.
    fn restart_in_bootloader(&mut self, cnt: u8) {
        self.feed(&frame(0x10, 0x02, cnt, &[]));
        self.raw.clear();
    }

    /// Lets `ms` pass in 10 ms ticks.
    fn run(&mut self, ms: u64) {
        for _ in 0..ms / 10 {
            self.now += Duration::from_millis(10);
            self.unit.tick(self.now);
            self.collect();
        }
    }

    fn stats(&self) -> SimStats {
        self.unit.snapshot(self.now)
    }

    /// The reply that echoes command number `cnt` (not a broadcast).
    fn reply_to(&self, cnt: u8) -> Option<Message> {
        self.seen
            .iter()
            .find(|p| p.cnt == cnt && !vpx_efis::sim::unit::is_broadcast(p.message.id()))
            .map(|p| p.message)
    }

    /// The last SYSTEM_STATUS broadcast.
    fn system_status(&self) -> SystemStatus {
        self.seen
            .iter()
            .rev()
            .find_map(|p| match p.message {
                Message::SystemStatus(s) => Some(s),
                _ => None,
            })
            .expect("a SYSTEM_STATUS")
    }
}

/// TRIM_MOVE (0x13/0x01, Table 30): trim type, power, direction.
fn trim_move(cnt: u8, trim_type: u8, on: u8, direction: u8) -> Vec<u8> {
    frame(0x13, 0x01, cnt, &[trim_type, on, direction])
}

/// FLAP_MOVE (0x13/0x02, Table 31): power, direction.
fn flap_move(cnt: u8, on: u8, direction: u8) -> Vec<u8> {
    frame(0x13, 0x02, cnt, &[on, direction])
}

// ------------------------------------------------------------ Section A

#[test]
fn trim_move_at_exactly_4_hz_runs_steadily_and_a_late_one_is_only_counted() {
    // ICD §6.4.2 "at least 4Hz", icd-reading R19: 250 ms apart keeps the motor going.
    let mut b = Bench::new(AIRCRAFT);
    b.run(100);
    for i in 0..8u8 {
        b.feed(&trim_move(i, 0, 1, 0));
        b.run(250);
    }
    let s = b.stats();
    assert!(
        s.pitch_trim_running,
        "running 250 ms after the last message"
    );
    assert_eq!((s.pitch_trim_starvations, s.pitch_trim_late), (0, 0));
    // 30 ms more than 4 Hz allows: the unit forgives it, the diagnostic sees it.
    b.run(30);
    b.feed(&trim_move(9, 0, 1, 0));
    let s = b.stats();
    assert!(s.pitch_trim_running);
    assert_eq!((s.pitch_trim_starvations, s.pitch_trim_late), (0, 1));
    // Nothing for 300 ms: the unit's runaway protection stops it.
    b.run(300);
    let s = b.stats();
    assert!(!s.pitch_trim_running);
    assert_eq!((s.pitch_trim_starvations, s.pitch_trim_late), (1, 1));
}

#[test]
fn version_is_answered_whatever_its_payload() {
    // §6.1.2: "Payload data sent by the external system is ignored by the VP-X."
    let mut b = Bench::new("");
    b.run(100);
    for (cnt, payload) in [(0x21u8, &[][..]), (0x22, &[0x00]), (0x23, &[1, 2, 3, 4, 5])] {
        b.raw.clear();
        b.feed(&frame(0x10, 0x01, cnt, payload));
        // The reply, by hand (Tables 1 and 11): VERSION from the VP-X (0x00) to the
        // EFIS (0x01), cnt echoed, hardware 2 (VP-X Pro), software 2.1.
        let mut want = vec![
            0xE7, 0x7E, 0x10, 0x01, cnt, 0x00, 0x01, 0x03, 0x02, 0x02, 0x01,
        ];
        let x = want.iter().fold(0u8, |a, b| a ^ b);
        want.push(!x);
        assert_eq!(b.raw, want, "VERSION with {} payload bytes", payload.len());
    }
}

#[test]
fn data_integrity_clears_after_a_warm_reset_and_after_an_update() {
    let flag = |b: &Bench| b.system_status().faults.data_integrity_failure;
    let mut b = Bench::new("");
    // EEPROM_ERASE (0x10/0x03, Table 12) with its one byte.
    b.feed(&frame(0x10, 0x03, 5, &[0x00]));
    assert_eq!(
        b.reply_to(5),
        Some(Message::EepromErase(EepromErase { response_code: 0 }))
    );
    b.run(1_100);
    assert!(flag(&b), "set by the erase");
    // §6.1.4: "should clear automatically after resetting or cycling power".
    b.unit.apply(SimCommand::WarmReset, b.now);
    b.run(1_100);
    assert!(!flag(&b), "cleared by the warm reset");
    assert!(b.system_status().faults.warm_reset);

    // An erase without its byte (the request's byte means nothing) is an erase too.
    b.feed(&frame(0x10, 0x03, 6, &[]));
    assert_eq!(
        b.reply_to(6),
        Some(Message::EepromErase(EepromErase { response_code: 0 }))
    );
    b.run(1_100);
    assert!(flag(&b));
    // A software update restarts the processor: cleared too.
    b.restart_in_bootloader(7);
    assert!(b.stats().in_bootloader);
    update_one_page(&mut b, 0x70);
    b.run(1_100);
    assert!(!flag(&b), "cleared by the restart after the update");
    assert!(b.system_status().misc.software_update);
}

/// SERIAL_CONF, FLASH_ERASE, one FLASH_PROG (command character `prog`) and EXIT, by
/// hand from Tables 35–38; checks the bootloader's answers.
fn update_one_page(b: &mut Bench, prog: u8) {
    b.raw.clear();
    b.feed(&[
        0x69, 0x96, b'!', 0x03, 0x00, 0x03, 0x00, 0x75, 0xDB, 0x9C, 0x97,
    ]);
    b.feed(&[0x69, 0x96, b'E', 0x00, 0x00]);
    // 128 words + 1 = 0x81, page 2 low byte first, then 256 bytes.
    let mut p = vec![0x69, 0x96, prog, 0x81, 0x00, 0x02, 0x00];
    p.extend([0x3C; 256]);
    b.feed(&p);
    b.feed(&[0x69, 0x96, b'X', 0x00, 0x00]);
    assert_eq!(b.raw, b"!!!ePx");
    assert!(!b.stats().in_bootloader);
}

// ------------------------------------------------------------ Section B

#[test]
fn a_stop_is_honoured_whatever_its_direction_or_trim_type_byte() {
    let mut b = Bench::new(AIRCRAFT);
    b.run(100);
    // Pitch trim down, then a stop whose direction byte (7) is outside Table 30.
    b.feed(&trim_move(1, 0, 1, 0));
    b.run(100);
    b.feed(&trim_move(2, 0, 0, 7));
    assert!(
        !b.stats().pitch_trim_running,
        "stopped at once, not at timeout"
    );
    // A stop whose trim type (5) is neither pitch nor roll stops the trims.
    b.feed(&trim_move(3, 0, 1, 1));
    b.run(100);
    b.feed(&trim_move(4, 5, 0, 0));
    assert!(!b.stats().pitch_trim_running);
    // Flaps down, then a FLAP_MOVE stop with direction 9 (Table 31: 0 or 1).
    b.feed(&flap_move(5, 1, 1));
    b.run(100);
    assert!(b.stats().flap_running);
    b.feed(&flap_move(6, 0, 9));
    assert!(!b.stats().flap_running);
    let s = b.stats();
    assert_eq!((s.flap_starvations, s.pitch_trim_starvations), (0, 0));
    // A *run* with such a byte is refused: the unit cannot tell which way.
    b.feed(&trim_move(7, 0, 1, 7));
    assert!(!b.stats().pitch_trim_running);
}

#[test]
fn exit_without_programming_does_not_claim_a_software_update() {
    // Table 24 note 1: the flag says the software "was updated".
    let mut b = Bench::new("");
    b.restart_in_bootloader(1);
    b.feed(&[0x69, 0x96, b'Q', 0x00, 0x00]);
    b.feed(&[0x69, 0x96, b'X', 0x00, 0x00]);
    assert_eq!(b.raw, b"VP_AVRBOOTx");
    b.run(1_100);
    assert!(!b.system_status().misc.software_update);
    // Table 36's upper-case 'P' programs a page like §7.5.3's 'p'; then it was updated.
    b.restart_in_bootloader(2);
    update_one_page(&mut b, b'P');
    assert_eq!(b.stats().boot.pages_programmed, 1);
    b.run(1_100);
    assert!(b.system_status().misc.software_update);
}

#[test]
fn the_bootloader_answers_erase_program_and_read_only_after_serial_conf() {
    // Decision (sim::bootloader): FLASH_ERASE, FLASH_PROG and FLASH_READ before a good
    // SERIAL_CONF are refused with silence; QUERY_PORT is answered at any time.
    let mut b = Bench::new("");
    b.restart_in_bootloader(1);
    b.feed(&[0x69, 0x96, b'E', 0x00, 0x00]);
    b.feed(&[0x69, 0x96, b'R', 0x02, 0x00, 0x00, 0x00, 0x00, 0x01]);
    b.feed(&[0x69, 0x96, b'Q', 0x00, 0x00]);
    assert_eq!(b.raw, b"VP_AVRBOOT");
    assert_eq!(b.stats().boot.refused, 2);
}

#[test]
fn device_enable_queries_for_fixed_devices_are_answered() {
    // Table 23 note 1: Starter, EFIS and Field_Pri are always enabled; note 2: the
    // flaps and trims are enabled by their FLAP_SPEC / TRIM_SPEC (here: flaps and
    // pitch configured, roll not).
    let mut b = Bench::new(AIRCRAFT);
    b.run(100);
    let want = [(1u8, 1u8), (2, 1), (3, 1), (0, 1), (30, 1), (29, 0)];
    for (i, &(id, _)) in want.iter().enumerate() {
        b.feed(&frame(0x11, 0x09, 0x40 + i as u8, &[id, 2]));
    }
    for (i, &(id, flag)) in want.iter().enumerate() {
        assert_eq!(
            b.reply_to(0x40 + i as u8),
            Some(Message::DeviceEnable(DeviceEnable {
                device_id: id,
                flag: EnableFlag::from_byte(flag)
            })),
            "device {id}"
        );
    }
    // Setting them is still ignored (range 4–28): the EFIS stays enabled.
    b.feed(&frame(0x11, 0x09, 0x50, &[2, 0]));
    b.feed(&frame(0x11, 0x09, 0x51, &[2, 2]));
    assert_eq!(
        b.reply_to(0x51),
        Some(Message::DeviceEnable(DeviceEnable {
            device_id: 2,
            flag: EnableFlag::Enabled
        }))
    );
}

#[test]
fn a_short_device_name_and_odd_query_payloads_are_taken() {
    let mut b = Bench::new(AIRCRAFT);
    b.run(100);
    // DEVICE_NAME for device 9: "Taxi" and its NUL, 6 bytes (Table 21's 17 is a
    // maximum, §6 intro; shorter names "should be null-terminated").
    b.feed(&frame(0x11, 0x07, 0x30, &[9, b'T', b'a', b'x', b'i', 0]));
    assert_eq!(
        b.reply_to(0x30),
        Some(Message::SpecAck(SpecAck {
            device_id: 9,
            error: None
        }))
    );
    // DEVICE_NAME_QUERY (Table 22) reads it back, sent as Table 21's 17 bytes.
    b.feed(&frame(0x11, 0x08, 0x31, &[9]));
    let Some(Message::DeviceName(n)) = b.reply_to(0x31) else {
        panic!("no DEVICE_NAME");
    };
    assert_eq!(n.text(), "Taxi");
    // DEVICE_STATUS_QUERY (Appendix D 0x12/0x04) with a payload nobody described.
    // DEVICE_STATUS is also a broadcast, so the answer is the one that came at once.
    let before = b.seen.len();
    b.feed(&frame(0x12, 0x04, 0x32, &[0xAA, 0x55]));
    let answer: Vec<_> = b.seen[before..]
        .iter()
        .map(|p| (p.cnt, p.message.name()))
        .collect();
    assert_eq!(answer, vec![(0x32, "DEVICE_STATUS")]);
}

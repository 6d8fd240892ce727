//! The unit on a fake clock, driven through its public face: bytes in, commands,
//! ticks, and the decoded bytes out.

use std::time::{Duration, Instant};

use super::*;
use crate::protocol::decoder::Event;
use crate::protocol::message::*;
use crate::protocol::{Decoder, Message, MessageId, Packet};
use crate::sim::scenario::MotorDirection;

/// A unit on a fake clock, and everything it has sent, decoded.
struct Bench {
    unit: Unit,
    t0: Instant,
    now: Instant,
    rx: Decoder,
    seen: Vec<(Duration, Packet)>,
    /// Every byte the unit sent, as it left.
    raw: Vec<u8>,
    cnt: u8,
}

impl Bench {
    fn new(toml: &str) -> Self {
        let t0 = Instant::now();
        let s = Scenario::from_toml(toml).unwrap();
        let unit = Unit::with_memory_eeprom(&s, UnitOptions::default(), t0);
        Bench {
            unit,
            t0,
            now: t0,
            rx: Decoder::new(),
            seen: Vec::new(),
            raw: Vec::new(),
            cnt: 0,
        }
    }

    fn collect(&mut self) {
        let out = self.unit.take_output();
        self.raw.extend_from_slice(&out);
        let mut frames = Vec::new();
        self.rx.push(&out, |e| {
            if let Event::Frame(f) = e {
                frames.push(Packet::parse(&f).unwrap());
            }
        });
        let at = self.now - self.t0;
        self.seen.extend(frames.into_iter().map(|p| (at, p)));
    }

    /// Lets `ms` milliseconds pass in 10 ms ticks.
    fn run(&mut self, ms: u64) {
        for _ in 0..ms / 10 {
            self.now += Duration::from_millis(10);
            self.unit.tick(self.now);
            self.collect();
        }
    }

    fn send(&mut self, m: impl Into<Message>) -> u8 {
        self.cnt = self.cnt.wrapping_add(1);
        let bytes = Packet::request(self.cnt, m).to_bytes();
        self.unit.feed(&bytes, self.now);
        self.collect();
        self.cnt
    }

    fn apply(&mut self, c: SimCommand) {
        self.unit.apply(c, self.now);
        self.collect();
    }

    /// The cockpit's switch `switch` is turned on or off.
    fn switch(&mut self, switch: u8, on: bool) {
        self.apply(SimCommand::Switch { switch, on });
    }

    /// A short appears on (or leaves) pin `device`.
    fn short(&mut self, device: u8, on: bool) {
        self.apply(SimCommand::Short { device, on });
    }

    /// DEVICE_POWER (ICD Table 24) for `device_id`.
    fn power(&mut self, device_id: u8, on: bool) -> u8 {
        self.send(DevicePower { device_id, on })
    }

    fn count(&self, id: MessageId) -> usize {
        self.seen
            .iter()
            .filter(|(_, p)| p.message.id() == id)
            .count()
    }

    fn last<T>(&self, f: impl Fn(&Message) -> Option<T>) -> Option<T> {
        self.seen.iter().rev().find_map(|(_, p)| f(&p.message))
    }

    fn reply_to(&self, cnt: u8) -> Option<Message> {
        self.seen
            .iter()
            .find(|(_, p)| p.cnt == cnt && !is_broadcast(p.message.id()))
            .map(|(_, p)| p.message)
    }

    fn stats(&self) -> SimStats {
        self.unit.snapshot(self.now)
    }

    fn external(&mut self, ias: Option<u16>, rpm: Option<u16>) {
        self.send(ExternalData {
            indicated_airspeed: ias.unwrap_or(0),
            rpm: rpm.unwrap_or(0),
            valid: ExternalValidity {
                indicated_airspeed: ias.is_some(),
                rpm: rpm.is_some(),
                ..Default::default()
            },
            ..Default::default()
        });
    }
}

const PINS: &str = "
    [system]
    secondary_alternator = 23
    [[device]]
    id = 3
    switch = 1
    load = 2.0
    [[device]]
    id = 9
    breaker = 3
    switch = 2
    load = 1.0
    [[device]]
    id = 10
    breaker = 3
    switch = 11
    load = 1.0
    [[device]]
    id = 23
    breaker = 5
    switch = 4
    load = 2.0
";

#[test]
fn broadcasts_keep_their_rates_and_their_own_count() {
    let mut b = Bench::new("");
    b.run(10_000);
    assert_eq!(b.count(SystemStatus::ID), 10);
    assert_eq!(b.count(DeviceStatus::ID), 10);
    assert_eq!(b.count(FlapTrimStatus::ID), 100);
    assert_eq!(b.count(FaultStatus::ID), 0, "no fault, no FAULT_STATUS");
    let cnts: Vec<u8> = b.seen.iter().map(|(_, p)| p.cnt).collect();
    assert!(cnts.windows(2).all(|w| w[1] == w[0].wrapping_add(1)));
}

#[test]
fn requests_are_answered_with_their_command_number() {
    let mut b = Bench::new("");
    b.cnt = 41;
    let c = b.send(Ping { ack: false });
    assert_eq!(b.reply_to(c), Some(Message::Ping(Ping { ack: true })));
    let c = b.send(DeviceSpecQuery { device_id: 253 });
    assert!(matches!(b.reply_to(c), Some(Message::SystemSpec(_))));
    let c = b.send(DeviceSpecQuery { device_id: 29 });
    assert!(matches!(
        b.reply_to(c),
        Some(Message::TrimSpec(TrimSpec {
            trim_type: TrimType::Roll,
            ..
        }))
    ));
    let c = b.send(DeviceSpecQuery { device_id: 99 });
    assert_eq!(b.reply_to(c), None, "Table 18 note 1: ignored");
}

#[test]
fn dropped_spec_acks_still_apply_the_spec_and_broadcasts_go_on() {
    let mut b = Bench::new("[line]\ndrop_spec_acks = true\n");
    let spec = DeviceSpec {
        device_id: 9,
        circuit_breaker: 3,
        switch_id: SwitchId::Input(2),
        current_fault: false,
        switch_raw: None,
    };
    let cnt = b.send(spec);
    b.run(1100);
    assert_eq!(b.reply_to(cnt), None, "no SPEC_ACK on the wire");
    assert_eq!(b.stats().config.devices[9], spec, "but the spec is stored");
    assert_eq!(b.stats().wire.spec_acks_dropped, 1);
    assert!(b.count(SystemStatus::ID) >= 1, "broadcasts carry on");
    // A query is still answered with what it holds.
    let q = b.send(DeviceSpecQuery { device_id: 9 });
    assert_eq!(b.reply_to(q), Some(Message::DeviceSpec(spec)));
    // Told to stop dropping, it answers again.
    b.apply(SimCommand::DropSpecAcks(false));
    let again = b.send(DeviceSpec {
        circuit_breaker: 4,
        ..spec
    });
    assert_eq!(
        b.reply_to(again),
        Some(Message::SpecAck(SpecAck {
            device_id: 9,
            error: None
        }))
    );
}

#[test]
fn a_spec_that_does_not_decode_gets_out_of_range_for_its_device() {
    let mut b = Bench::new("");
    // DEVICE_SPEC for device 9 with a current-fault flag of 2.
    let mut bytes = Packet::request(
        7,
        DeviceSpec {
            device_id: 9,
            circuit_breaker: 3,
            switch_id: SwitchId::Input(2),
            current_fault: false,
            switch_raw: None,
        },
    )
    .to_bytes();
    bytes[8 + 3] = 2;
    let n = bytes.len();
    bytes[n - 1] = crate::protocol::checksum(&bytes[..n - 1]);
    b.unit.feed(&bytes, b.now);
    b.collect();
    assert_eq!(
        b.reply_to(7),
        Some(Message::SpecAck(SpecAck {
            device_id: 9,
            error: Some(SpecAckError::OutOfRange)
        }))
    );
    assert_eq!(b.stats().wire.malformed, 1);
    assert_eq!(b.stats().config, UnitConfig::default(), "nothing stored");
}

#[test]
fn device_power_overrides_until_the_switch_is_cycled() {
    let mut b = Bench::new(PINS);
    b.power(9, true);
    assert!(b.stats().powered[9], "on although switch 2 is open");
    b.switch(2, true);
    b.switch(2, false);
    assert!(!b.stats().powered[9], "the switch has the last word again");
    b.power(1, true);
    assert!(
        !b.stats().powered[1],
        "the starter cannot be switched from outside"
    );
}

/// The reading of "cycled" (ICD Appendix A) the page's model shares: one change
/// of the input ends the hold; the switch then has the word both ways.
#[test]
fn a_single_change_of_the_input_ends_a_device_power_hold() {
    let mut b = Bench::new(PINS);
    b.switch(2, true);
    // Held ON while switch 2 is on: only the end of the hold can turn it off.
    b.power(9, true);
    assert!(b.stats().powered[9]);
    b.switch(2, false);
    assert!(
        !b.stats().powered[9],
        "one change (on to off) ended the hold: the switch has the word"
    );
}

#[test]
fn a_short_faults_the_pin_when_powered_and_clear_brings_back_the_switch_state() {
    let mut b = Bench::new(PINS);
    b.short(9, true);
    b.switch(2, true);
    let s = b.stats();
    assert!(!s.powered[9]);
    assert_eq!(s.faults[9], FaultCode::ShortCircuit);
    b.run(1_500);
    let f = b.last(|m| match m {
        Message::FaultStatus(f) => Some(*f),
        _ => None,
    });
    let f = f.expect("FAULT_STATUS while a fault exists");
    assert!(f.faulted[9]);
    assert_eq!(f.codes[9], Some(FaultCode::ShortCircuit));
    // Clearing while still shorted: faulted again at once (§6.5.1).
    b.send(DeviceClear { device_id: 9 });
    assert_eq!(b.stats().faults[9], FaultCode::ShortCircuit);
    b.short(9, false);
    // An always-on pin the EFIS switched off comes back on with the clear (note 2).
    b.power(10, false);
    b.send(DeviceClear { device_id: 9 });
    let s = b.stats();
    assert!(s.powered[9], "back to switch 2, which is on");
    assert!(s.powered[10], "switch-11 pin powered again");
    let before = b.count(FaultStatus::ID);
    b.run(2_000);
    assert_eq!(
        b.count(FaultStatus::ID),
        before,
        "no fault, no FAULT_STATUS"
    );
}

#[test]
fn over_current_and_current_fault() {
    let mut b = Bench::new(PINS);
    b.apply(SimCommand::Load {
        device: 10,
        amps: 3.5,
    });
    assert_eq!(b.stats().faults[10], FaultCode::OverCurrent);
    let mut s = b.unit.config.devices[9];
    s.current_fault = true;
    b.send(s);
    b.apply(SimCommand::Load {
        device: 9,
        amps: 0.0,
    });
    b.switch(2, true);
    assert_eq!(b.stats().faults[9], FaultCode::CurrentFault);
}

#[test]
fn one_alternator_at_a_time_and_over_voltage_trips_the_running_one() {
    let mut b = Bench::new(PINS);
    b.switch(1, true);
    b.switch(4, true);
    let s = b.stats();
    assert!(
        s.powered[3] && !s.powered[23],
        "primary runs, secondary waits"
    );
    b.apply(SimCommand::BusVolts(16.4));
    let s = b.stats();
    assert_eq!(s.faults[3], FaultCode::OverVoltage);
    assert!(!s.powered[3] && s.powered[23], "the secondary takes over");
    assert_eq!(s.faults[23], FaultCode::NoFault, "at normal volts");
}

#[test]
fn the_60_a_flag_clears_only_below_48_a() {
    // Nine big pins, always on, whose loads add up to the total under test.
    let pins: Vec<u8> = (17..=25).collect();
    let toml: String = pins
        .iter()
        .map(|id| format!("[[device]]\nid = {id}\nswitch = 11\nbreaker = 10\n"))
        .collect();
    let mut b = Bench::new(&toml);
    let flags = |b: &mut Bench| {
        b.run(1_000);
        b.last(|m| match m {
            Message::SystemStatus(s) => {
                Some((s.faults.current_over_48a, s.faults.current_over_60a))
            }
            _ => None,
        })
        .unwrap()
    };
    for (total, want) in [
        (50.0, (true, false)),
        (61.0, (true, true)),
        (49.0, (true, true)),
        (47.0, (false, false)),
        (49.0, (true, false)),
    ] {
        for &device in &pins {
            b.apply(SimCommand::Load {
                device,
                amps: total / pins.len() as f32,
            });
        }
        assert_eq!(flags(&mut b), want, "{total} A");
    }
    assert!(b.stats().faults.iter().all(|f| !f.is_fault()));
}

#[test]
fn the_starter_cuts_out_above_500_rpm() {
    let mut b = Bench::new("[electrical]\nstarter = true\n");
    assert!(b.stats().powered[1]);
    b.external(None, Some(400));
    assert!(b.stats().powered[1]);
    b.external(None, Some(900));
    assert!(!b.stats().powered[1]);
}

#[test]
fn external_data_missing_after_two_seconds() {
    let mut b = Bench::new("");
    b.run(1_900);
    assert!(!b.stats().external_data_missing);
    b.run(200);
    assert!(b.stats().external_data_missing);
    b.external(Some(90), None);
    assert!(!b.stats().external_data_missing);
    b.run(2_100);
    assert!(b.stats().external_data_missing);
}

#[test]
fn wig_wag_flashes_at_and_above_its_speed_after_warm_up_and_steady_stops_it() {
    let mut b = Bench::new(
        "[[device]]\nid = 17\nswitch = 5\nbreaker = 8\nload = 6\n\
         [[device]]\nid = 18\nswitch = 5\nbreaker = 8\nload = 5\n\
         [wig_wag]\ndevice_one = 17\ndevice_two = 18\nwarm_up = 5\nspeed = 70\n",
    );
    b.switch(5, true);
    let both = |b: &Bench| (b.stats().powered[17], b.stats().powered[18]);
    let patterns = |b: &mut Bench, ias: u16| {
        let mut seen = std::collections::HashSet::new();
        for _ in 0..4 {
            b.external(Some(ias), None);
            b.run(250);
            seen.insert(both(b));
        }
        seen
    };
    // Taxiing at 40 kt, through the warm-up and after it: steady.
    for _ in 0..6 {
        b.external(Some(40), None);
        b.run(1_000);
    }
    assert_eq!(
        patterns(&mut b, 40),
        std::collections::HashSet::from([(true, true)]),
        "below the speed: steady"
    );
    // At 70 kt exactly (Table 17's "speed at which the wig-wag is engaged") and
    // above: one lamp at a time.
    for ias in [70, 120] {
        let p = patterns(&mut b, ias);
        assert!(
            p.contains(&(true, false)) && p.contains(&(false, true)),
            "{ias} kt: {p:?}"
        );
        assert!(!p.contains(&(true, true)), "{ias} kt: {p:?}");
        let active = b.last(|m| match m {
            Message::SystemStatus(s) => Some(s.misc.wig_wag_active),
            _ => None,
        });
        assert_eq!(active, Some(true), "Table 24's Wig-Wag Active at {ias} kt");
    }
    b.send(WigWagMode {
        mode: WigWagModeSetting::Steady,
    });
    assert_eq!(both(&b), (true, true));
    b.send(WigWagMode {
        mode: WigWagModeSetting::Auto,
    });
    b.external(Some(69), None);
    b.run(100);
    assert_eq!(both(&b), (true, true), "below the speed again: steady");
}

#[test]
fn eeprom_erase_restores_defaults_and_flags_integrity_until_power_cycle() {
    let mut b = Bench::new(PINS);
    let c = b.send(EepromErase { response_code: 0 });
    assert_eq!(
        b.reply_to(c),
        Some(Message::EepromErase(EepromErase { response_code: 0 }))
    );
    assert_eq!(b.stats().config, UnitConfig::default());
    b.run(1_000);
    let flag = |b: &Bench| {
        b.last(|m| match m {
            Message::SystemStatus(s) => Some(s.faults.data_integrity_failure),
            _ => None,
        })
    };
    assert_eq!(flag(&b), Some(true));
    b.apply(SimCommand::PowerCycle);
    b.run(1_000);
    assert_eq!(flag(&b), Some(false));
    assert_eq!(b.stats().config, UnitConfig::default(), "still erased");
}

#[test]
fn bootloader_frames_in_the_same_read_as_software_update_are_not_lost() {
    let mut b = Bench::new("");
    let mut bytes = Packet::request(1, SoftwareUpdate).to_bytes();
    bytes.extend(crate::protocol::bootloader::BootCommand::QueryPort.emit());
    b.unit.feed(&bytes, b.now);
    assert_eq!(b.unit.take_output(), b"VP_AVRBOOT");
}

#[test]
fn software_update_enters_the_bootloader_and_exit_sets_the_flag() {
    use crate::protocol::bootloader::{BootCommand, PAGE_SIZE};
    let mut b = Bench::new("");
    b.send(SoftwareUpdate);
    let before = b.seen.len();
    b.run(1_000);
    assert_eq!(b.seen.len(), before, "no broadcasts in the bootloader");
    let mut bytes = BootCommand::serial_conf().emit();
    bytes.extend(BootCommand::FlashErase.emit());
    bytes.extend(
        BootCommand::flash_prog(0, &[0x0C; PAGE_SIZE])
            .unwrap()
            .emit(),
    );
    bytes.extend(BootCommand::Exit.emit());
    b.unit.feed(&bytes, b.now);
    assert_eq!(b.unit.take_output(), b"!!!ePx");
    b.run(1_000);
    let flag = b.last(|m| match m {
        Message::SystemStatus(s) => Some(s.misc.software_update),
        _ => None,
    });
    assert_eq!(flag, Some(true));
    b.apply(SimCommand::PowerCycle);
    assert!(!b.stats().software_update_flag);
}

#[test]
fn a_silent_unit_sends_nothing_then_resumes() {
    let mut b = Bench::new("[[event]]\nat = 1.0\ndo = \"silent\"\nseconds = 3.0\n");
    b.run(1_000);
    let n = b.seen.len();
    b.run(2_900);
    assert_eq!(b.seen.len(), n);
    b.run(1_100);
    assert!(b.seen.len() > n);
    assert!(b.stats().wire.silenced_bytes > 0);
}

/// The payloads of every frame with this major/minor id the unit sent since raw
/// byte `from`, cut out by hand from ICD Table 1 (E7 7E, major, minor, cnt, src,
/// dst, len, data, checksum): independent of our decoder.
fn payloads(b: &Bench, from: usize, major: u8, minor: u8) -> Vec<Vec<u8>> {
    let raw = &b.raw[from..];
    let mut out = Vec::new();
    let mut i = 0;
    while i + 8 <= raw.len() {
        if raw[i] == 0xE7 && raw[i + 1] == 0x7E {
            let len = raw[i + 7] as usize;
            let end = i + 8 + len + 1;
            assert!(end <= raw.len(), "a frame cut short");
            // Source 0x00 (VP-X), destination 0x01 (external system).
            assert_eq!((raw[i + 5], raw[i + 6]), (0x00, 0x01));
            if raw[i + 2] == major && raw[i + 3] == minor {
                out.push(raw[i + 8..i + 8 + len].to_vec());
            }
            i = end;
        } else {
            i += 1;
        }
    }
    out
}

/// The last SYSTEM_STATUS (0x12/0x00) payload after a second more.
fn system_status_bytes(b: &mut Bench) -> Vec<u8> {
    let from = b.raw.len();
    b.run(1_000);
    let p = payloads(b, from, 0x12, 0x00);
    let last = p.last().expect("SYSTEM_STATUS every second").clone();
    assert_eq!(last.len(), 12, "Table 24: 12 bytes");
    last
}

/// The last DEVICE_STATUS (0x12/0x01) payload after a second more.
fn device_status_bytes(b: &mut Bench) -> Vec<u8> {
    let from = b.raw.len();
    b.run(1_000);
    let p = payloads(b, from, 0x12, 0x01);
    let last = p.last().expect("DEVICE_STATUS every second").clone();
    assert_eq!(last.len(), 66, "Table 26: 66 bytes");
    last
}

/// Table 26: device `id`'s current, tenths of amps, big-endian at bytes 5 + 2·id.
fn current_tenths(payload: &[u8], id: usize) -> u16 {
    u16::from_be_bytes([payload[4 + 2 * id], payload[5 + 2 * id]])
}

/// FLAP_TRIM_STATUS (0x12/0x02) payloads after `ms` more milliseconds.
fn flap_trim_bytes(b: &mut Bench, ms: u64) -> Vec<Vec<u8>> {
    let from = b.raw.len();
    b.run(ms);
    payloads(b, from, 0x12, 0x02)
}

const WIRING: &str = "
    [electrical]
    dead_switches = [7]
    crossed_switches = [[5, 6]]
    [[device]]
    id = 4
    breaker = 3
    switch = 3
    load = 1.5
    [[device]]
    id = 6
    breaker = 2
    switch = 3
    load = 1.1
    open_circuit = true
    [[device]]
    id = 17
    breaker = 8
    switch = 5
    load = 7.2
    [[device]]
    id = 18
    breaker = 7
    switch = 6
    load = 4.0
    [[device]]
    id = 19
    breaker = 6
    switch = 7
    load = 3.5
";

fn person_sets(b: &mut Bench, switch: u8, on: bool) {
    b.switch(switch, on);
}

#[test]
fn an_open_circuit_is_on_and_draws_nothing() {
    let mut b = Bench::new(WIRING);
    person_sets(&mut b, 3, true);
    let d = device_status_bytes(&mut b);
    // Table 26 byte 1: device 7 is the MSB, device 0 the LSB; 4 and 6 are on.
    // The EFIS (2) is on too: always on by default (Appendix F).
    assert_eq!(d[0], 0b0101_0100);
    assert_eq!(
        current_tenths(&d, 6),
        0,
        "the beacon's load is not connected"
    );
    let nav = current_tenths(&d, 4);
    assert!(
        (14..=16).contains(&nav),
        "the good circuit draws 1.5 A: {nav}"
    );
    // Switched on by DEVICE_POWER instead, the same: on, and 0 A.
    person_sets(&mut b, 3, false);
    b.power(6, true);
    let d = device_status_bytes(&mut b);
    assert_eq!(d[0], 0b0100_0100);
    assert_eq!(current_tenths(&d, 6), 0);
}

#[test]
fn an_open_circuit_with_current_fault_detection_faults() {
    // The unit's own check (Table 13 note): a pin that should draw and does not.
    let mut b = Bench::new(
        "[[device]]\nid = 6\nswitch = 3\nload = 1.1\nopen_circuit = true\n\
         current_fault = true\n",
    );
    person_sets(&mut b, 3, true);
    assert_eq!(b.stats().faults[6], FaultCode::CurrentFault);
}

#[test]
fn a_load_near_its_breaker_draws_close_to_it_without_tripping() {
    let mut b = Bench::new(WIRING);
    let from = b.raw.len();
    person_sets(&mut b, 5, true);
    person_sets(&mut b, 6, true);
    let d = device_status_bytes(&mut b);
    // Byte 3 holds devices 16–23: 17 is bit 1, 18 bit 2.
    assert_eq!(d[2], 0b0000_0110);
    let amps = current_tenths(&d, 17);
    // 7.2 A ± 3 % noise, of an 8 A breaker: 87–93 %.
    assert!((70..=74).contains(&amps), "{amps} tenths");
    b.run(2_000);
    assert!(
        payloads(&b, from, 0x12, 0x03).is_empty(),
        "no FAULT_STATUS: the breaker holds"
    );
}

#[test]
fn a_dead_switch_input_never_changes() {
    let mut b = Bench::new(WIRING);
    person_sets(&mut b, 7, true);
    let s = system_status_bytes(&mut b);
    // Table 24 byte 9: switch 8 is the MSB … switch 1 the LSB. Nothing closed.
    assert_eq!((s[7], s[8]), (0x00, 0x00));
    assert!(!b.stats().powered[19], "the boost pump stays off");
    // The switch next to it works, and the person's switch 7 is still on.
    person_sets(&mut b, 4, true);
    let s = system_status_bytes(&mut b);
    assert_eq!((s[7], s[8]), (0x00, 0b0000_1000));
    person_sets(&mut b, 7, false);
    let s = system_status_bytes(&mut b);
    assert_eq!((s[7], s[8]), (0x00, 0b0000_1000));
}

#[test]
fn crossed_switches_close_each_others_input_and_power_each_others_circuits() {
    let mut b = Bench::new(WIRING);
    person_sets(&mut b, 5, true);
    let s = system_status_bytes(&mut b);
    // Switch 5 is bit 4 (0x10), switch 6 bit 5 (0x20): input 6 closed.
    assert_eq!(s[8], 0b0010_0000);
    let d = device_status_bytes(&mut b);
    assert_eq!(
        d[2], 0b0000_0100,
        "the taxi light (18) on, not the landing light"
    );
    person_sets(&mut b, 5, false);
    person_sets(&mut b, 6, true);
    let s = system_status_bytes(&mut b);
    assert_eq!(s[8], 0b0001_0000, "switch 6 closes input 5");
    let d = device_status_bytes(&mut b);
    assert_eq!(d[2], 0b0000_0010, "the landing light (17) on");
}

#[test]
fn a_switch_change_through_the_wiring_still_ends_a_device_power_hold() {
    let mut b = Bench::new(WIRING);
    // The page switched the taxi light off; cycling its input ends the hold.
    b.power(18, false);
    person_sets(&mut b, 5, true);
    assert!(
        b.stats().powered[18],
        "input 6 changed, so the hold is gone"
    );
}

const MOTORS: &str = "
    [flap]
    up = 20
    down = 220
    position = 100
    [pitch_trim]
    up = 30
    down = 220
    neutral = 125
    position = 125
    reversed = true
    [roll_trim]
    up = 40
    down = 210
    neutral = 125
    position = 125
    stuck = true
";

/// Streams TRIM_MOVE every 100 ms for `ms` (a page's safe stream), then stops.
fn trim_run(b: &mut Bench, axis: TrimType, dir: TrimDirection, ms: u64) -> Vec<Vec<u8>> {
    let mut status = Vec::new();
    for _ in 0..ms / 100 {
        b.send(TrimMove {
            trim_type: axis,
            on: true,
            direction: dir,
        });
        status.extend(flap_trim_bytes(b, 100));
    }
    b.send(TrimMove {
        trim_type: axis,
        on: false,
        direction: dir,
    });
    status
}

#[test]
fn a_reversed_trim_runs_the_other_way_and_its_polarity_setting_undoes_it() {
    let mut b = Bench::new(MOTORS);
    let before = flap_trim_bytes(&mut b, 100).last().unwrap().clone();
    // Table 27 byte 4: pitch position. Down is toward 220, the larger number.
    assert_eq!(before[3], 125);
    let during = trim_run(&mut b, TrimType::Pitch, TrimDirection::DownOrRight, 1_000);
    // Byte 2 MSB first: pitch enabled 0x80, running 0x40; roll enabled 0x10.
    assert!(during.iter().any(|p| p[1] == 0b1101_0000), "running");
    let after = flap_trim_bytes(&mut b, 300).last().unwrap().clone();
    assert_eq!(after[1], 0b1001_0000, "stopped");
    assert!(
        (98..=102).contains(&after[3]),
        "commanded down, went up: {}",
        after[3]
    );
    // The installer sets the polarity to inverted (Table 15 note 3): fixed.
    let spec = TrimSpec {
        polarity: Polarity::Inverted,
        power: 60,
        ..b.unit.config.pitch_trim
    };
    b.send(spec);
    trim_run(&mut b, TrimType::Pitch, TrimDirection::DownOrRight, 1_000);
    let fixed = flap_trim_bytes(&mut b, 300).last().unwrap().clone();
    assert!(
        fixed[3] > after[3] + 20,
        "now down: {} → {}",
        after[3],
        fixed[3]
    );
}

#[test]
fn a_stuck_trim_runs_and_never_moves() {
    let mut b = Bench::new(MOTORS);
    let during = trim_run(&mut b, TrimType::Roll, TrimDirection::UpOrLeft, 1_000);
    // Byte 2: roll enabled 0x10, roll running 0x08 (pitch enabled 0x80).
    assert!(during.iter().any(|p| p[1] == 0b1001_1000), "roll running");
    // Byte 5: roll position, byte 8: roll fault code (none).
    assert!(during.iter().all(|p| p[4] == 125 && p[7] == 0));
    // Flaps, wired right, move as commanded (byte 3; down is the larger number).
    for _ in 0..10 {
        b.send(FlapMove {
            on: true,
            direction: FlapDirection::Down,
        });
        b.run(100);
    }
    b.send(FlapMove {
        on: false,
        direction: FlapDirection::Down,
    });
    let s = flap_trim_bytes(&mut b, 300).last().unwrap().clone();
    assert!((118..=122).contains(&s[2]), "flaps went down: {}", s[2]);
}

#[test]
fn a_flipped_switch_comes_back_after_its_hold() {
    let mut b = Bench::new(WIRING);
    b.apply(SimCommand::FlipSwitch {
        switch: 3,
        hold: Duration::from_millis(2_500),
    });
    // SYSTEM_STATUS leaves at 0.2 s, 1.2 s, 2.2 s, 3.2 s … after power-on.
    for (window, want) in [(1, 0b0000_0100), (2, 0b0000_0100), (3, 0b0000_0100), (4, 0)] {
        let s = system_status_bytes(&mut b);
        assert_eq!(s[8], want, "switch 3 in the broadcast before {window} s");
    }
    // A switch that was on flips off, then on again (at 4 s, back at 5.5 s).
    person_sets(&mut b, 4, true);
    b.apply(SimCommand::FlipSwitch {
        switch: 4,
        hold: Duration::from_millis(1_500),
    });
    for want in [0, 0, 0b0000_1000] {
        let s = system_status_bytes(&mut b);
        assert_eq!(s[8], want);
    }
}

#[test]
fn held_flap_and_trim_switches_show_in_system_status_byte_8() {
    let mut b = Bench::new(MOTORS);
    b.apply(SimCommand::MotorSwitch {
        motor: MotorId::Flap,
        direction: Some(MotorDirection::Down),
    });
    b.apply(SimCommand::MotorSwitch {
        motor: MotorId::Pitch,
        direction: Some(MotorDirection::Up),
    });
    let s = system_status_bytes(&mut b);
    // Table 24 byte 8, MSB first: roll down, roll up, pitch down, pitch up (0x10),
    // flap down (0x08), flap up, switch 10, switch 9.
    assert_eq!(s[7], 0b0001_1000);
    b.apply(SimCommand::MotorSwitch {
        motor: MotorId::Flap,
        direction: None,
    });
    b.apply(SimCommand::MotorSwitch {
        motor: MotorId::Pitch,
        direction: None,
    });
    // Pressed for 1.5 s: roll trim up (0x40) in the next broadcast, gone after.
    b.apply(SimCommand::PressMotorSwitch {
        motor: MotorId::Roll,
        direction: MotorDirection::Up,
        hold: Duration::from_millis(1_500),
    });
    for want in [0b0100_0000, 0b0100_0000, 0] {
        let s = system_status_bytes(&mut b);
        assert_eq!(s[7], want);
    }
}

//! ICD §8's usage scenarios, each played against the virtual VP-X over a real
//! pseudo-terminal by a client built from the `protocol` module.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

mod sim_common;

use sim_common::{Client, scenario, start};
use vpx_efis::protocol::FaultCode;
use vpx_efis::protocol::message::*;
use vpx_efis::sim::{SimCommand, SimHandle};

/// A small aircraft: device 5 on switch 2 with a 3 A breaker, device 9 on switch 3,
/// flaps configured, device 12 with a short behind it.
const AIRCRAFT: &str = r#"
[electrical]
switches = [2]

[[device]]
id = 5
name = "Nav Lt"
breaker = 3
switch = 2
load = 1.5

[[device]]
id = 9
breaker = 2
switch = 3
load = 1.2

[[device]]
id = 10
breaker = 2
switch = 0
load = 0.7

[[device]]
id = 12
breaker = 4
switch = 0
load = 2.0
short = true

[flap]
up = 20
down = 220
midpoint_1 = 90
midpoint_2 = 160
breaker = 6
position = 20
"#;

fn aircraft() -> (SimHandle, Client) {
    start(scenario(AIRCRAFT), |_| {})
}

fn device_status(c: &mut Client) -> DeviceStatus {
    c.next("DEVICE_STATUS", |m| match m {
        Message::DeviceStatus(d) => Some(*d),
        _ => None,
    })
}

/// The first DEVICE_STATUS that shows `want`: a broadcast already on its way when a
/// request was sent may still show the state before it.
fn device_status_showing(c: &mut Client, what: &str, want: impl Fn(&DeviceStatus) -> bool) {
    c.next(what, |m| match m {
        Message::DeviceStatus(d) if want(d) => Some(()),
        _ => None,
    })
}

#[test]
fn s8_1_1_ping() {
    let (_sim, mut c) = aircraft();
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
}

#[test]
fn s8_1_2_version() {
    let (_sim, mut c) = start(scenario(AIRCRAFT), |o| {
        o.hardware_version = 3;
        o.software_version = (4, 7);
    });
    assert_eq!(
        c.request(Version::REQUEST),
        Message::Version(Version {
            hardware_version: HardwareVersion::VpxSport,
            software_major: 4,
            software_minor: 7,
        })
    );
}

#[test]
fn s8_2_1_retrieve_device_settings_device_5() {
    let (_sim, mut c) = aircraft();
    assert_eq!(
        c.request(DeviceSpecQuery { device_id: 5 }),
        Message::DeviceSpec(DeviceSpec {
            device_id: 5,
            circuit_breaker: 3,
            switch_id: SwitchId::Input(2),
            current_fault: false,
            switch_raw: None,
        })
    );
}

#[test]
fn s8_2_2_retrieve_flap_settings() {
    let (_sim, mut c) = aircraft();
    let Message::FlapSpec(f) = c.request(DeviceSpecQuery { device_id: 0 }) else {
        panic!("device 0 answers FLAP_SPEC");
    };
    assert_eq!(
        (f.enabled, f.up, f.down, f.circuit_breaker),
        (true, 20, 220, 6)
    );
    // The other special ids of icd-reading R13.
    assert!(matches!(
        c.request(DeviceSpecQuery { device_id: 30 }),
        Message::TrimSpec(TrimSpec {
            trim_type: TrimType::Pitch,
            ..
        })
    ));
    assert!(matches!(
        c.request(DeviceSpecQuery { device_id: 254 }),
        Message::WigWagSpec(_)
    ));
}

#[test]
fn s8_2_3_configure_device_9() {
    let (sim, mut c) = aircraft();
    let spec = DeviceSpec {
        device_id: 9,
        circuit_breaker: 4,
        switch_id: SwitchId::Input(6),
        current_fault: true,
        switch_raw: None,
    };
    assert_eq!(
        c.request(spec),
        Message::SpecAck(SpecAck {
            device_id: 9,
            error: None
        })
    );
    assert_eq!(
        c.request(DeviceSpecQuery { device_id: 9 }),
        Message::DeviceSpec(spec)
    );
    assert_eq!(sim.stats().config.devices[9], spec);
}

#[test]
fn s8_2_4_configure_device_9_with_an_invalid_breaker() {
    let (sim, mut c) = aircraft();
    let before = sim.stats().config.devices[9];
    assert_eq!(
        c.request(DeviceSpec {
            device_id: 9,
            circuit_breaker: 12,
            switch_id: SwitchId::Input(3),
            current_fault: false,
            switch_raw: None,
        }),
        Message::SpecAck(SpecAck {
            device_id: 9,
            error: Some(SpecAckError::InvalidBreaker)
        })
    );
    assert_eq!(
        sim.stats().config.devices[9],
        before,
        "refused settings are ignored"
    );
}

#[test]
fn s8_2_5_configure_system_parameters() {
    let (sim, mut c) = aircraft();
    let spec = SystemSpec {
        overvoltage_limit: OvervoltageLimit::V32,
        secondary_alternator: None,
    };
    assert_eq!(
        c.request(spec),
        Message::SpecAck(SpecAck {
            device_id: 253,
            error: None
        })
    );
    assert_eq!(sim.stats().config.system, spec);
}

#[test]
fn s8_3_1_monitor_system_status() {
    let (_sim, mut c) = aircraft();
    let s = c.system_status();
    assert!(s.switches.switch[1], "switch 2 is closed in the scenario");
    assert!(!s.switches.switch[0]);
    assert!(s.main_bus_volts.value() > 11.0);
    assert!(s.system_current.value() > 1.0, "the nav light draws");
}

#[test]
fn s8_3_2_monitor_device_status() {
    let (_sim, mut c) = aircraft();
    let d = device_status(&mut c);
    assert!(d.on[5] && !d.on[9]);
    assert!(
        (d.current[5].value() - 1.5).abs() < 0.1,
        "{:?}",
        d.current[5]
    );
    assert_eq!(d.current[9].0, 0);
    // DEVICE_STATUS_QUERY (icd-reading R6) answers at once, echoing the number.
    let cnt = c.send(DeviceStatusQuery);
    c.wait_for("DEVICE_STATUS answering the query", |p| {
        (p.cnt == cnt && matches!(p.message, Message::DeviceStatus(_))).then_some(())
    });
}

#[test]
fn s8_3_3_monitor_fault_status() {
    let (sim, mut c) = aircraft();
    sim.inject(SimCommand::Fault {
        device: 9,
        code: FaultCode::OverCurrent,
    });
    let f = c.next("FAULT_STATUS", |m| match m {
        Message::FaultStatus(f) => Some(*f),
        _ => None,
    });
    assert!(f.faulted[9] && !f.faulted[5] && !f.system_fault);
    assert_eq!(f.codes[9], Some(FaultCode::OverCurrent));
    assert_eq!(
        f.codes[5],
        Some(FaultCode::NoFault),
        "35 bytes, a code for everyone"
    );
    // Cleared: FAULT_STATUS stops (icd-reading R9).
    c.send(DeviceClear { device_id: 9 });
    c.system_status();
    c.system_status();
    let since = c.log.len();
    c.system_status();
    assert!(
        !c.log[since..]
            .iter()
            .any(|(_, p)| matches!(p.message, Message::FaultStatus(_)))
    );
}

#[test]
fn s8_4_1_power_device_single() {
    let (_sim, mut c) = aircraft();
    c.send(DevicePower {
        device_id: 9,
        on: true,
    });
    device_status_showing(&mut c, "device 9 on", |d| d.on[9]);
    c.send(DevicePower {
        device_id: 9,
        on: false,
    });
    device_status_showing(&mut c, "device 9 off", |d| !d.on[9]);
    // No acknowledgement (§8.4.1): the only frames are broadcasts.
    assert!(
        c.log
            .iter()
            .all(|(_, p)| sim_common::is_broadcast(&p.message))
    );
}

#[test]
fn s8_4_2_power_multiple_devices() {
    let (_sim, mut c) = aircraft();
    for (id, on) in [(9, true), (10, true), (5, false)] {
        c.send(DevicePower { device_id: id, on });
    }
    device_status_showing(&mut c, "9 and 10 on, 5 off", |d| {
        (d.on[9], d.on[10], d.on[5]) == (true, true, false)
    });
}

#[test]
fn s8_5_1_device_short_circuit() {
    let (_sim, mut c) = aircraft();
    c.send(DevicePower {
        device_id: 12,
        on: true,
    });
    let f = c.next("FAULT_STATUS", |m| match m {
        Message::FaultStatus(f) => Some(*f),
        _ => None,
    });
    assert!(f.faulted[12]);
    assert_eq!(f.codes[12], Some(FaultCode::ShortCircuit));
    let d = device_status(&mut c);
    assert!(!d.on[12], "a shorted device is off");
    assert_eq!(d.current[12].0, 0);
}

#[test]
fn names_enables_and_eeprom_erase() {
    let (sim, mut c) = aircraft();
    assert_eq!(
        c.request(DeviceName::new(9, "Landing Lt").unwrap()),
        Message::SpecAck(SpecAck {
            device_id: 9,
            error: None
        })
    );
    let Message::DeviceName(n) = c.request(DeviceNameQuery { device_id: 9 }) else {
        panic!("DEVICE_NAME_QUERY answers DEVICE_NAME");
    };
    assert_eq!(n.text(), "Landing Lt");
    let Message::DeviceName(n) = c.request(DeviceNameQuery { device_id: 5 }) else {
        panic!("DEVICE_NAME_QUERY answers DEVICE_NAME");
    };
    assert_eq!(n.text(), "Nav Lt");
    c.send(DeviceEnable {
        device_id: 9,
        flag: EnableFlag::Disabled,
    });
    assert_eq!(
        c.request(DeviceEnable {
            device_id: 9,
            flag: EnableFlag::Query
        }),
        Message::DeviceEnable(DeviceEnable {
            device_id: 9,
            flag: EnableFlag::Disabled
        })
    );
    assert_eq!(
        c.request(EepromErase { response_code: 0 }),
        Message::EepromErase(EepromErase { response_code: 0 })
    );
    let s = c.system_status();
    assert!(s.faults.data_integrity_failure);
    assert_eq!(
        s.data_integrity_code,
        Some(DataIntegrityCode::GeneralEeprom)
    );
    assert_eq!(sim.stats().config, Default::default());
}

#[test]
fn garbage_and_malformed_requests_are_ignored_and_counted_while_broadcasts_go_on() {
    let (sim, mut c) = aircraft();
    c.pump(std::time::Duration::from_millis(300));
    let before = c.log.len();
    // Noise without a sync byte, a frame with a broken checksum, an unknown message,
    // and a DEVICE_POWER whose power byte is 7.
    c.send_raw(&[0x00, 0x11, 0x22, 0x33, 0x44]);
    let mut bad = vpx_efis::protocol::Packet::request(9, Ping { ack: false }).to_bytes();
    *bad.last_mut().unwrap() ^= 0xFF;
    c.send_raw(&bad);
    let mut unknown = vec![0xE7, 0x7E, 0x16, 0x09, 0x01, 0x01, 0x00, 0x00];
    unknown.push(vpx_efis::protocol::checksum(&unknown));
    c.send_raw(&unknown);
    let mut power = vpx_efis::protocol::Packet::request(
        10,
        DevicePower {
            device_id: 9,
            on: true,
        },
    )
    .to_bytes();
    power[9] = 7;
    let n = power.len();
    power[n - 1] = vpx_efis::protocol::checksum(&power[..n - 1]);
    c.send_raw(&power);
    // A good request afterwards still gets its answer.
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
    let s = sim.stats().wire;
    assert!(s.garbage_bytes >= 5, "{s:?}");
    assert!(s.bad_frames >= 2, "{s:?}");
    assert_eq!(s.malformed, 1, "{s:?}");
    assert!(
        !sim.stats().powered[9],
        "the malformed DEVICE_POWER did nothing"
    );
    let d = device_status(&mut c);
    assert!(!d.on[9]);
    assert!(c.log.len() > before, "still broadcasting");
}

//! EEPROM persistence (`--eeprom FILE`): settings survive a restart of the sim; a
//! corrupt file gives the Appendix F defaults, DATA_INTEGRITY and a log line.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

mod sim_common;

use sim_common::{scenario, start};
use vpx_efis::protocol::message::*;

const SPEC: DeviceSpec = DeviceSpec {
    device_id: 9,
    circuit_breaker: 4,
    switch_id: SwitchId::Input(6),
    current_fault: true,
    switch_raw: None,
};

#[test]
fn settings_survive_a_restart_on_the_same_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("vpx.eeprom");
    {
        let (sim, mut c) = start(scenario(""), |o| o.eeprom = Some(file.clone()));
        assert!(matches!(
            c.request(SPEC),
            Message::SpecAck(SpecAck { error: None, .. })
        ));
        assert!(matches!(
            c.request(DeviceName::new(9, "Pitot").unwrap()),
            Message::SpecAck(SpecAck { error: None, .. })
        ));
        sim.stop();
    }
    let (sim, mut c) = start(scenario(""), |o| o.eeprom = Some(file.clone()));
    assert_eq!(
        c.request(DeviceSpecQuery { device_id: 9 }),
        Message::DeviceSpec(SPEC)
    );
    let Message::DeviceName(n) = c.request(DeviceNameQuery { device_id: 9 }) else {
        panic!("DEVICE_NAME_QUERY answers DEVICE_NAME");
    };
    assert_eq!(n.text(), "Pitot");
    let s = sim.stats();
    assert_eq!(s.data_integrity, None);
    assert!(
        s.log.iter().any(|l| l.contains("EEPROM read from")),
        "{:?}",
        s.log
    );
}

#[test]
fn a_corrupt_file_gives_defaults_data_integrity_and_a_log_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("vpx.eeprom");
    std::fs::write(&file, b"{\"format\": 1, \"checksum\": 12, \"config\": tru").unwrap();
    // The scenario would configure device 9; the corrupt EEPROM must win over it.
    let (sim, mut c) = start(
        scenario("[[device]]\nid = 9\nswitch = 3\nbreaker = 4\n"),
        |o| o.eeprom = Some(file.clone()),
    );
    let s = c.system_status();
    assert!(s.faults.data_integrity_failure);
    assert_eq!(
        s.data_integrity_code,
        Some(DataIntegrityCode::GeneralEeprom)
    );
    assert_eq!(
        sim.stats().config,
        Default::default(),
        "Appendix F defaults"
    );
    let log = sim.stats().log;
    assert!(
        log.iter()
            .any(|l| l.contains("corrupt") && l.contains("defaults")),
        "{log:?}"
    );
    assert!(
        file.with_extension("corrupt").exists(),
        "the bad file is kept"
    );
    // The unit answers normally, and the defaults are now a good EEPROM: a power cycle
    // clears the flag (Table 24 note 5).
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
    sim.inject(vpx_efis::sim::SimCommand::PowerCycle);
    c.next("SYSTEM_STATUS without the flag", |m| match m {
        Message::SystemStatus(s) if !s.faults.data_integrity_failure => Some(()),
        _ => None,
    });
}

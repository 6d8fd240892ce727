//! Counters and a snapshot of the unit, for tests and tools.

use std::time::Instant;

use super::{Mode, Unit};
use crate::protocol::FaultCode;
use crate::protocol::config::UnitConfig;
use crate::protocol::device::DEVICE_COUNT;
use crate::protocol::message::DataIntegrityCode;
use crate::sim::bootloader::BootStats;

/// Counters of what crossed the wire.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WireStats {
    pub rx_bytes: u64,
    /// Intact frames of known messages.
    pub rx_frames: u64,
    /// Bytes outside any frame (noise, and the first byte of each bad candidate).
    pub garbage_bytes: u64,
    /// Candidates with a bad checksum or impossible length, and unknown messages.
    pub bad_frames: u64,
    /// Intact frames whose payload does not decode (a field out of range).
    pub malformed: u64,
    /// Well-formed frames the unit does nothing with: messages only a VP-X sends,
    /// requests for devices that do not exist, DEVICE_POWER to the starter or motors.
    pub ignored: u64,
    /// Replies sent (each echoes its request's command number).
    pub replies: u64,
    pub system_status: u64,
    pub device_status: u64,
    pub flap_trim_status: u64,
    pub fault_status: u64,
    pub tx_bytes: u64,
    /// Bytes dropped because the unit was silent.
    pub silenced_bytes: u64,
    /// SPEC_ACKs not sent because they are being dropped (the spec was applied).
    pub spec_acks_dropped: u64,
}

/// A snapshot of the unit for tests and tools.
#[derive(Debug, Clone, PartialEq)]
pub struct SimStats {
    pub wire: WireStats,
    pub boot: BootStats,
    pub in_bootloader: bool,
    /// Motor positions 0–255.
    pub flap_position: u8,
    pub pitch_trim_position: u8,
    pub roll_trim_position: u8,
    pub flap_running: bool,
    pub pitch_trim_running: bool,
    pub roll_trim_running: bool,
    /// Streams that ended because no TRIM_MOVE/FLAP_MOVE came for 300 ms (the 250 ms
    /// of icd-reading R19 plus the unit's margin, see `sim::motors`).
    pub flap_starvations: u64,
    pub pitch_trim_starvations: u64,
    pub roll_trim_starvations: u64,
    /// TRIM_MOVE/FLAP_MOVE messages that came more than 250 ms after the one before
    /// while the run went on: forgiven by the unit, a gap the EFIS should not leave.
    pub flap_late: u64,
    pub pitch_trim_late: u64,
    pub roll_trim_late: u64,
    /// Power state per device id, as DEVICE_STATUS reports it.
    pub powered: [bool; DEVICE_COUNT],
    /// Fault per device id, as FAULT_STATUS reports it.
    pub faults: [FaultCode; DEVICE_COUNT],
    pub system_fault: bool,
    pub config: UnitConfig,
    pub data_integrity: Option<DataIntegrityCode>,
    pub external_data_missing: bool,
    pub software_update_flag: bool,
    pub eeprom_writes: u64,
    /// Broadcast command count (the unit's own, icd-reading R14).
    pub broadcast_cnt: u8,
    /// The last log lines, oldest first.
    pub log: Vec<String>,
}

impl Unit {
    /// A snapshot for tests and tools (`log` is filled in by the runner).
    pub fn snapshot(&self, now: Instant) -> SimStats {
        let [f, p, r] = &self.motors;
        let boot = match &self.mode {
            Mode::Boot(b) => b.stats(),
            Mode::Normal => self.boot_stats,
        };
        SimStats {
            wire: self.wire,
            boot,
            in_bootloader: self.in_bootloader(),
            flap_position: f.position_byte(),
            pitch_trim_position: p.position_byte(),
            roll_trim_position: r.position_byte(),
            flap_running: f.running(now),
            pitch_trim_running: p.running(now),
            roll_trim_running: r.running(now),
            flap_starvations: f.starvations,
            pitch_trim_starvations: p.starvations,
            roll_trim_starvations: r.starvations,
            flap_late: f.late,
            pitch_trim_late: p.late,
            roll_trim_late: r.late,
            powered: self.powered,
            faults: self.fault_codes(),
            system_fault: self.system_fault,
            config: self.config.clone(),
            data_integrity: self.integrity,
            external_data_missing: self.external_missing(now),
            software_update_flag: self.software_update,
            eeprom_writes: self.eeprom.writes,
            broadcast_cnt: self.cnt,
            log: Vec::new(),
        }
    }
}

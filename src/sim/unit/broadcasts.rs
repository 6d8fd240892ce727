//! The unit's broadcasts (ICD §6.3): SYSTEM_STATUS, DEVICE_STATUS and FAULT_STATUS
//! at 1 Hz, FLAP_TRIM_STATUS at 10 Hz, built from its state.

use std::time::Instant;

use super::{Unit, motor_device};
use crate::protocol::device::{DEVICE_COUNT, STARTER};
use crate::protocol::message::{
    DeviceStatus, FaultStatus, FlapFlags, FlapTrimStatus, MiscFlags, Payload, SignedTenths,
    SwitchInputs, SystemFaultFlags, SystemStatus, Tenths, TrimFlags, TrimSpec,
};
use crate::protocol::{FaultCode, Message, MessageId, Packet};
use crate::sim::motors::Motor;
use crate::sim::scenario::{MotorDirection, MotorId};

impl Unit {
    pub(super) fn broadcast_slow(&mut self, now: Instant) {
        let s = self.system_status(now);
        self.broadcast(s, now);
        self.wire.system_status += 1;
        let d = self.device_status();
        self.broadcast(d, now);
        self.wire.device_status += 1;
        // §6.3.4: only while a fault exists (icd-reading R9).
        if let Some(f) = self.fault_status() {
            self.broadcast(f, now);
            self.wire.fault_status += 1;
        }
    }

    pub(super) fn broadcast(&mut self, m: impl Into<Message>, now: Instant) {
        let cnt = self.cnt;
        self.cnt = self.cnt.wrapping_add(1);
        let bytes = Packet::from_vpx(cnt, m).to_bytes();
        self.emit_raw(&bytes, now);
    }

    fn tenths(v: f32) -> u16 {
        (v * 10.0).round().clamp(0.0, u16::MAX as f32) as u16
    }

    pub(super) fn device_status(&mut self) -> DeviceStatus {
        let mut current = [Tenths(0); DEVICE_COUNT];
        for (id, c) in current.iter_mut().enumerate() {
            let a = self.amps(id);
            if a > 0.0 {
                // ±3 % noise so the page has something alive to show.
                let n = 1.0 + 0.03 * self.rng.unit();
                *c = Tenths(Self::tenths(a * n).max(1));
            }
        }
        DeviceStatus {
            on: self.powered,
            current,
        }
    }

    fn system_status(&mut self, now: Instant) -> SystemStatus {
        let noise = 0.05 * self.rng.unit();
        let volts = self.bus_volts(noise);
        let mut switches = SwitchInputs {
            switch: self.switches,
            ..SwitchInputs::default()
        };
        for (m, held) in self.motors.iter().map(|m| (m.id, m.switch_held())) {
            let (up, down) = match m {
                MotorId::Flap => (&mut switches.flap_up, &mut switches.flap_down),
                MotorId::Pitch => (&mut switches.pitch_trim_up, &mut switches.pitch_trim_down),
                MotorId::Roll => (&mut switches.roll_trim_up, &mut switches.roll_trim_down),
            };
            *up = held == Some(MotorDirection::Up);
            *down = held == Some(MotorDirection::Down);
        }
        let total = self.total_amps() * (1.0 + 0.01 * self.rng.unit());
        SystemStatus {
            system_current: Tenths(Self::tenths(total)),
            main_bus_volts: SignedTenths((volts * 10.0).round() as i16),
            aux_battery_volts: Tenths(Self::tenths(self.aux_battery_volts)),
            internal_temp: self.temperature_c,
            switches,
            misc: MiscFlags {
                starter_annunciator: self.powered[STARTER as usize],
                wig_wag_mode: self.wig_wag_mode,
                software_update: self.software_update,
                wig_wag_active: self.wig_wag_active,
            },
            faults: SystemFaultFlags {
                current_over_48a: self.over_48,
                current_over_60a: self.over_60,
                warm_reset: self.warm_reset,
                data_integrity_failure: self.integrity.is_some(),
                external_data_missing: self.external_missing(now),
            },
            data_integrity_code: self.integrity,
        }
    }

    pub(super) fn fault_codes(&self) -> [FaultCode; DEVICE_COUNT] {
        let mut codes = self.faults;
        for m in &self.motors {
            codes[motor_device(m.id) as usize] = m.fault;
        }
        codes
    }

    fn fault_status(&self) -> Option<FaultStatus> {
        let codes = self.fault_codes();
        let faulted: [bool; DEVICE_COUNT] = std::array::from_fn(|i| codes[i].is_fault());
        if !self.system_fault && !faulted.iter().any(|&f| f) {
            return None;
        }
        Some(FaultStatus {
            faulted,
            system_fault: self.system_fault,
            // Table 28: the full 35 bytes, a code for every device.
            codes: std::array::from_fn(|i| Some(codes[i])),
        })
    }

    pub(super) fn flap_trim_status(&self, now: Instant) -> FlapTrimStatus {
        let c = &self.config;
        let [flap, pitch, roll] = &self.motors;
        let fg = self.geometry(MotorId::Flap, now);
        // Table 16 note 5: flaps further down than the overspeed position with the
        // IAS above the max flap speed.
        let overspeed = c.flap.enabled
            && self.flap_down_inhibited(now)
            && fg.extension(flap.position) > fg.extension(c.flap.overspeed_position as f32);
        let trim = |t: &TrimSpec, m: &Motor| TrimFlags {
            enabled: t.enabled,
            motor_running: m.running(now),
            fault: m.faulted(),
        };
        // Table 27 bytes 13–18: zero when that trim is not enabled.
        let points = |t: &TrimSpec| {
            if t.enabled {
                (t.up, t.down, t.neutral)
            } else {
                (0, 0, 0)
            }
        };
        let (pu, pd, pn) = points(&c.pitch_trim);
        let (ru, rd, rn) = points(&c.roll_trim);
        FlapTrimStatus {
            flap: FlapFlags {
                enabled: c.flap.enabled,
                motor_running: flap.running(now),
                fault: flap.faulted(),
                overspeed_alarm: overspeed,
                down_switch_inhibited: c.flap.enabled && self.flap_down_inhibited(now),
            },
            pitch_trim: trim(&c.pitch_trim, pitch),
            roll_trim: trim(&c.roll_trim, roll),
            flap_position: flap.position_byte(),
            pitch_trim_position: pitch.position_byte(),
            roll_trim_position: roll.position_byte(),
            flap_fault: flap.fault,
            pitch_trim_fault: pitch.fault,
            roll_trim_fault: roll.fault,
            flap_up: c.flap.up,
            flap_down: c.flap.down,
            flap_midpoint_1: c.flap.midpoint_1,
            flap_midpoint_2: c.flap.midpoint_2,
            pitch_trim_up: pu,
            pitch_trim_down: pd,
            pitch_trim_neutral: pn,
            roll_trim_up: ru,
            roll_trim_down: rd,
            roll_trim_neutral: rn,
        }
    }
}

/// Messages the unit sends, by id, for callers that sort its output.
pub fn is_broadcast(id: MessageId) -> bool {
    matches!(
        id,
        SystemStatus::ID | DeviceStatus::ID | FlapTrimStatus::ID | FaultStatus::ID
    )
}

//! Status messages, ICD §6.3 (major 0x12). Broadcast by the unit.

use super::types::{DataIntegrityCode, SignedTenths, Tenths, WigWagModeSetting};
use super::{IGNORED_PAYLOAD_MAX, Payload, Reader, Writer, bit, exact};
use crate::device::DEVICE_COUNT;
use crate::error::{Error, LenRule, Result};
use crate::fault::FaultCode;
use crate::frame::MessageId;

/// SYSTEM_STATUS byte 8–9: the external switch inputs, live (ICD Table 24; icd-reading R8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SwitchInputs {
    /// Table 24 byte 8, bit 7 (MSB): roll trim down switch.
    pub roll_trim_down: bool,
    /// Table 24 byte 8, bit 6: roll trim up switch.
    pub roll_trim_up: bool,
    /// Table 24 byte 8, bit 5: pitch trim down switch.
    pub pitch_trim_down: bool,
    /// Table 24 byte 8, bit 4: pitch trim up switch.
    pub pitch_trim_up: bool,
    /// Table 24 byte 8, bit 3: flap down switch.
    pub flap_down: bool,
    /// Table 24 byte 8, bit 2: flap up switch.
    pub flap_up: bool,
    /// `switch[0]` is switch 1, … `switch[9]` is switch 10.
    pub switch: [bool; 10],
}

impl SwitchInputs {
    /// The inputs of Table 24's two switch bytes, read as one big-endian word.
    pub fn from_word(w: u16) -> Self {
        let mut switch = [false; 10];
        for (i, s) in switch.iter_mut().enumerate() {
            *s = w & (1 << i) != 0;
        }
        SwitchInputs {
            roll_trim_down: w & 0x8000 != 0,
            roll_trim_up: w & 0x4000 != 0,
            pitch_trim_down: w & 0x2000 != 0,
            pitch_trim_up: w & 0x1000 != 0,
            flap_down: w & 0x0800 != 0,
            flap_up: w & 0x0400 != 0,
            switch,
        }
    }

    /// The two switch bytes of Table 24 as one big-endian word.
    pub fn to_word(&self) -> u16 {
        let mut w = 0u16;
        for (i, &s) in self.switch.iter().enumerate() {
            if s {
                w |= 1 << i;
            }
        }
        for (on, b) in [
            (self.roll_trim_down, 0x8000),
            (self.roll_trim_up, 0x4000),
            (self.pitch_trim_down, 0x2000),
            (self.pitch_trim_up, 0x1000),
            (self.flap_down, 0x0800),
            (self.flap_up, 0x0400),
        ] {
            if on {
                w |= b;
            }
        }
        w
    }
}

/// SYSTEM_STATUS misc flags byte (ICD Table 24), MSB first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MiscFlags {
    /// Table 24 misc flags, bit 7 (MSB): starter annunciator active.
    pub starter_annunciator: bool,
    /// Table 24 misc flags, bit 6: wig-wag mode, 0 auto, 1 steady.
    pub wig_wag_mode: WigWagModeSetting,
    /// Table 24 misc flags, bit 5: software was updated during the last power cycle (note
    /// 1).
    pub software_update: bool,
    /// Table 24 misc flags, bit 4: wig-wag active.
    pub wig_wag_active: bool,
}

/// SYSTEM_STATUS system fault flags byte (ICD Table 24), MSB first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SystemFaultFlags {
    /// Table 24 system fault flags, bit 7 (MSB): total current over 48 A (note 2).
    pub current_over_48a: bool,
    /// Table 24 system fault flags, bit 6: total current over 60 A (note 3).
    pub current_over_60a: bool,
    /// Table 24 system fault flags, bit 4: CU warm reset at start-up (note 4).
    pub warm_reset: bool,
    /// Table 24 system fault flags, bit 3: an EEPROM area failed its integrity check (note
    /// 5).
    pub data_integrity_failure: bool,
    /// Table 24 system fault flags, bit 0 (LSB): no EXTERNAL_DATA for over two seconds
    /// (note 6).
    pub external_data_missing: bool,
}

/// SYSTEM_STATUS — ICD Table 24 with icd-reading R8: 12 bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SystemStatus {
    /// Total system current, amps in tenths.
    pub system_current: Tenths,
    /// Main bus volts in tenths (signed).
    pub main_bus_volts: SignedTenths,
    /// Aux battery volts in tenths.
    pub aux_battery_volts: Tenths,
    /// Whole degrees Celsius.
    pub internal_temp: u8,
    /// Table 24 bytes 8–9 (icd-reading R8): the external switch inputs.
    pub switches: SwitchInputs,
    /// Table 24 byte 10 (icd-reading R8): misc flags.
    pub misc: MiscFlags,
    /// Table 24 byte 11 (icd-reading R8): system fault flags.
    pub faults: SystemFaultFlags,
    /// 0 is "no error" and decodes as `None` (ICD Table 25).
    pub data_integrity_code: Option<DataIntegrityCode>,
}

/// The all-zero misc flags byte: no starter, wig-wag auto and not active.
impl Default for MiscFlags {
    fn default() -> Self {
        MiscFlags {
            starter_annunciator: false,
            wig_wag_mode: WigWagModeSetting::Auto,
            software_update: false,
            wig_wag_active: false,
        }
    }
}

/// The all-zero payload: 0 A, 0 V, 0 °C, every input open, no flag, no error code.
/// What a test starts from before it sets the fields it is about.
impl Default for SystemStatus {
    fn default() -> Self {
        SystemStatus {
            system_current: Tenths(0),
            main_bus_volts: SignedTenths(0),
            aux_battery_volts: Tenths(0),
            internal_temp: 0,
            switches: SwitchInputs::default(),
            misc: MiscFlags::default(),
            faults: SystemFaultFlags::default(),
            data_integrity_code: None,
        }
    }
}

impl Payload for SystemStatus {
    const ID: MessageId = MessageId::new(0x12, 0x00);
    const NAME: &'static str = "SYSTEM_STATUS";
    const LEN: LenRule = LenRule::Exact(12);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let mut r = Reader::new(p);
        let system_current = Tenths(r.u16());
        let main_bus_volts = SignedTenths(r.u16() as i16);
        let aux_battery_volts = Tenths(r.u16());
        let internal_temp = r.u8();
        let switches = SwitchInputs::from_word(r.u16());
        let m = r.u8();
        let f = r.u8();
        let code = r.u8();
        Ok(SystemStatus {
            system_current,
            main_bus_volts,
            aux_battery_volts,
            internal_temp,
            switches,
            misc: MiscFlags {
                starter_annunciator: bit(m, 7),
                wig_wag_mode: if bit(m, 6) {
                    WigWagModeSetting::Steady
                } else {
                    WigWagModeSetting::Auto
                },
                software_update: bit(m, 5),
                wig_wag_active: bit(m, 4),
            },
            faults: SystemFaultFlags {
                current_over_48a: bit(f, 7),
                current_over_60a: bit(f, 6),
                warm_reset: bit(f, 4),
                data_integrity_failure: bit(f, 3),
                external_data_missing: bit(f, 0),
            },
            data_integrity_code: if code == 0 {
                None
            } else {
                Some(DataIntegrityCode::from_byte(code))
            },
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u16(self.system_current.0);
        w.u16(self.main_bus_volts.0 as u16);
        w.u16(self.aux_battery_volts.0);
        w.u8(self.internal_temp);
        w.u16(self.switches.to_word());
        let m = &self.misc;
        w.u8(bits(&[
            (7, m.starter_annunciator),
            (6, m.wig_wag_mode != WigWagModeSetting::Auto),
            (5, m.software_update),
            (4, m.wig_wag_active),
        ]));
        let f = &self.faults;
        w.u8(bits(&[
            (7, f.current_over_48a),
            (6, f.current_over_60a),
            (4, f.warm_reset),
            (3, f.data_integrity_failure),
            (0, f.external_data_missing),
        ]));
        w.u8(self
            .data_integrity_code
            .map_or(0, DataIntegrityCode::to_byte));
    }
}

/// DEVICE_STATUS — ICD Table 26. Bit i of byte k is device 8k+i (icd-reading R7).

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceStatus {
    /// Indexed by device id.
    pub on: [bool; DEVICE_COUNT],
    /// Current per device, amps in tenths, indexed by device id.
    pub current: [Tenths; DEVICE_COUNT],
}

/// The all-zero payload: every device off, drawing 0 A.
impl Default for DeviceStatus {
    fn default() -> Self {
        DeviceStatus {
            on: [false; DEVICE_COUNT],
            current: [Tenths(0); DEVICE_COUNT],
        }
    }
}

impl Payload for DeviceStatus {
    const ID: MessageId = MessageId::new(0x12, 0x01);
    const NAME: &'static str = "DEVICE_STATUS";
    const LEN: LenRule = LenRule::Exact(66);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 66>(p)?;
        let on = unpack_bits(&p[..4]);
        let mut current = [Tenths(0); DEVICE_COUNT];
        let mut r = Reader::new(&p[4..]);
        for c in current.iter_mut() {
            *c = Tenths(r.u16());
        }
        Ok(DeviceStatus { on, current })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.bytes(&pack_bits(&self.on, false));
        for c in &self.current {
            w.u16(c.0);
        }
    }
}

/// Flap flags byte of FLAP_TRIM_STATUS (ICD Table 27), MSB first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FlapFlags {
    /// Table 27 byte 1, bit 7 (MSB): flaps enabled.
    pub enabled: bool,
    /// Table 27 byte 1, bit 6: flap motor running.
    pub motor_running: bool,
    /// Table 27 byte 1, bit 5: flap fault.
    pub fault: bool,
    /// Table 27 byte 1, bit 4: flap overspeed alarm.
    pub overspeed_alarm: bool,
    /// Table 27 byte 1, bit 3: flap down switch inhibited.
    pub down_switch_inhibited: bool,
}

/// One trim axis's flags in FLAP_TRIM_STATUS (ICD Table 27).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TrimFlags {
    /// Table 27 byte 2: the axis is enabled (pitch bit 7, roll bit 4).
    pub enabled: bool,
    /// Table 27 byte 2: the axis's motor is running (pitch bit 6, roll bit 3).
    pub motor_running: bool,
    /// Table 27 byte 2: the axis has a fault (pitch bit 5, roll bit 2).
    pub fault: bool,
}

/// FLAP_TRIM_STATUS — ICD Table 27, 18 bytes, broadcast at 10 Hz.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FlapTrimStatus {
    /// Table 27 byte 1: flap flags.
    pub flap: FlapFlags,
    /// Table 27 byte 2, bits 7–5: pitch trim flags.
    pub pitch_trim: TrimFlags,
    /// Table 27 byte 2, bits 4–2: roll trim flags.
    pub roll_trim: TrimFlags,
    /// Table 27 byte 3: current flap position, 0–255.
    pub flap_position: u8,
    /// Table 27 byte 4: current pitch trim position, 0–255.
    pub pitch_trim_position: u8,
    /// Table 27 byte 5: current roll trim position, 0–255.
    pub roll_trim_position: u8,
    /// Table 27 byte 6: flap fault code (Table 43).
    pub flap_fault: FaultCode,
    /// Table 27 byte 7: pitch trim fault code (Table 43).
    pub pitch_trim_fault: FaultCode,
    /// Table 27 byte 8: roll trim fault code (Table 43).
    pub roll_trim_fault: FaultCode,
    /// Table 27 byte 9: flap up position, as in FLAP_SPEC.
    pub flap_up: u8,
    /// Table 27 byte 10: flap down position, as in FLAP_SPEC.
    pub flap_down: u8,
    /// Table 27 byte 11: flap midpoint #1, as in FLAP_SPEC.
    pub flap_midpoint_1: u8,
    /// Table 27 byte 12: flap midpoint #2, as in FLAP_SPEC.
    pub flap_midpoint_2: u8,
    /// Table 27 byte 13: pitch trim up position (0 when pitch trim is not enabled).
    pub pitch_trim_up: u8,
    /// Table 27 byte 14: pitch trim down position (0 when pitch trim is not enabled).
    pub pitch_trim_down: u8,
    /// Table 27 byte 15: pitch trim neutral position (0 when pitch trim is not enabled).
    pub pitch_trim_neutral: u8,
    /// Table 27 byte 16: roll trim up position (0 when roll trim is not enabled).
    pub roll_trim_up: u8,
    /// Table 27 byte 17: roll trim down position (0 when roll trim is not enabled).
    pub roll_trim_down: u8,
    /// Table 27 byte 18: roll trim neutral position (0 when roll trim is not enabled).
    pub roll_trim_neutral: u8,
}

/// The all-zero payload: every axis disabled, still and without a fault, every position
/// and endpoint 0. What a test starts from before it sets the fields it is about.
impl Default for FlapTrimStatus {
    fn default() -> Self {
        let none = FaultCode::NoFault;
        FlapTrimStatus {
            flap: FlapFlags::default(),
            pitch_trim: TrimFlags::default(),
            roll_trim: TrimFlags::default(),
            flap_position: 0,
            pitch_trim_position: 0,
            roll_trim_position: 0,
            flap_fault: none,
            pitch_trim_fault: none,
            roll_trim_fault: none,
            flap_up: 0,
            flap_down: 0,
            flap_midpoint_1: 0,
            flap_midpoint_2: 0,
            pitch_trim_up: 0,
            pitch_trim_down: 0,
            pitch_trim_neutral: 0,
            roll_trim_up: 0,
            roll_trim_down: 0,
            roll_trim_neutral: 0,
        }
    }
}

impl Payload for FlapTrimStatus {
    const ID: MessageId = MessageId::new(0x12, 0x02);
    const NAME: &'static str = "FLAP_TRIM_STATUS";
    const LEN: LenRule = LenRule::Exact(18);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let mut r = Reader::new(p);
        let ff = r.u8();
        let tf = r.u8();
        Ok(FlapTrimStatus {
            flap: FlapFlags {
                enabled: bit(ff, 7),
                motor_running: bit(ff, 6),
                fault: bit(ff, 5),
                overspeed_alarm: bit(ff, 4),
                down_switch_inhibited: bit(ff, 3),
            },
            pitch_trim: TrimFlags {
                enabled: bit(tf, 7),
                motor_running: bit(tf, 6),
                fault: bit(tf, 5),
            },
            roll_trim: TrimFlags {
                enabled: bit(tf, 4),
                motor_running: bit(tf, 3),
                fault: bit(tf, 2),
            },
            flap_position: r.u8(),
            pitch_trim_position: r.u8(),
            roll_trim_position: r.u8(),
            flap_fault: FaultCode::from_byte(r.u8()),
            pitch_trim_fault: FaultCode::from_byte(r.u8()),
            roll_trim_fault: FaultCode::from_byte(r.u8()),
            flap_up: r.u8(),
            flap_down: r.u8(),
            flap_midpoint_1: r.u8(),
            flap_midpoint_2: r.u8(),
            pitch_trim_up: r.u8(),
            pitch_trim_down: r.u8(),
            pitch_trim_neutral: r.u8(),
            roll_trim_up: r.u8(),
            roll_trim_down: r.u8(),
            roll_trim_neutral: r.u8(),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        let f = &self.flap;
        w.u8(bits(&[
            (7, f.enabled),
            (6, f.motor_running),
            (5, f.fault),
            (4, f.overspeed_alarm),
            (3, f.down_switch_inhibited),
        ]));
        let (p, r) = (&self.pitch_trim, &self.roll_trim);
        w.u8(bits(&[
            (7, p.enabled),
            (6, p.motor_running),
            (5, p.fault),
            (4, r.enabled),
            (3, r.motor_running),
            (2, r.fault),
        ]));
        for b in [
            self.flap_position,
            self.pitch_trim_position,
            self.roll_trim_position,
            self.flap_fault.to_byte(),
            self.pitch_trim_fault.to_byte(),
            self.roll_trim_fault.to_byte(),
            self.flap_up,
            self.flap_down,
            self.flap_midpoint_1,
            self.flap_midpoint_2,
            self.pitch_trim_up,
            self.pitch_trim_down,
            self.pitch_trim_neutral,
            self.roll_trim_up,
            self.roll_trim_down,
            self.roll_trim_neutral,
        ] {
            w.u8(b);
        }
    }
}

/// One of the three motors FLAP_TRIM_STATUS reports on, in the table's order (ICD
/// Table 27): each has its flags, its position, its fault code and its endpoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The flaps.
    Flap,
    /// The pitch trim.
    PitchTrim,
    /// The roll trim: its "up" is left, its "down" right (Table 30 note 2).
    RollTrim,
}

/// One axis's fields of FLAP_TRIM_STATUS (ICD Table 27), gathered from its bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AxisStatus {
    /// Bytes 1–2: the axis is enabled.
    pub enabled: bool,
    /// Bytes 1–2: the axis's motor is running.
    pub motor_running: bool,
    /// Bytes 1–2: the axis's fault flag.
    pub fault: bool,
    /// Bytes 3–5: its current position, 0–255.
    pub position: u8,
    /// Bytes 6–8: its fault code (Table 43).
    pub fault_code: FaultCode,
    /// Bytes 9, 13, 16: the up endpoint (roll trim: left).
    pub up: u8,
    /// Bytes 10, 14, 17: the down endpoint (roll trim: right).
    pub down: u8,
    /// Bytes 15, 18: a trim's neutral position; `None` for the flaps, whose
    /// midpoints (bytes 11–12) are theirs alone.
    pub neutral: Option<u8>,
}

impl FlapTrimStatus {
    /// The fields of one axis: the one place that says which byte is whose.
    pub fn axis(&self, axis: Axis) -> AxisStatus {
        let f = &self.flap;
        let (flags, position, fault_code, up, down, neutral) = match axis {
            Axis::Flap => (
                TrimFlags {
                    enabled: f.enabled,
                    motor_running: f.motor_running,
                    fault: f.fault,
                },
                self.flap_position,
                self.flap_fault,
                self.flap_up,
                self.flap_down,
                None,
            ),
            Axis::PitchTrim => (
                self.pitch_trim,
                self.pitch_trim_position,
                self.pitch_trim_fault,
                self.pitch_trim_up,
                self.pitch_trim_down,
                Some(self.pitch_trim_neutral),
            ),
            Axis::RollTrim => (
                self.roll_trim,
                self.roll_trim_position,
                self.roll_trim_fault,
                self.roll_trim_up,
                self.roll_trim_down,
                Some(self.roll_trim_neutral),
            ),
        };
        AxisStatus {
            enabled: flags.enabled,
            motor_running: flags.motor_running,
            fault: flags.fault,
            position,
            fault_code,
            up,
            down,
            neutral,
        }
    }

    /// The current position of one axis, 0–255 (Table 27 bytes 3–5).
    pub fn position(&self, axis: Axis) -> u8 {
        self.axis(axis).position
    }
}

/// FAULT_STATUS — ICD Table 28. Bit i of byte k is device 8k+i; the MSB of byte 4 is
/// the system fault (icd-reading R7). icd-reading R9: 35 bytes, but a shorter payload
/// (at least the 4 bit bytes) is accepted and the codes it lacks are `None`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FaultStatus {
    /// Table 28 bytes 1–4: whether device `i` is faulted (bit i mod 8 of byte i / 8,
    /// icd-reading R7).
    pub faulted: [bool; DEVICE_COUNT],
    /// Table 28 byte 4, MSB: the system fault flag (icd-reading R7).
    pub system_fault: bool,
    /// Per device id; `None` where the payload stopped before that device's code.
    pub codes: [Option<FaultCode>; DEVICE_COUNT],
}

impl FaultStatus {
    /// FAULT_STATUS (ICD Table 28) with each device of `faults` faulted with its code,
    /// every other device's code NO FAULT (Table 43, 0x00), and no system fault: all
    /// 31 codes present, as the unit sends them. An id past device 30 has no bit or
    /// code in the table and is left out.
    pub fn with_faults(faults: &[(u8, FaultCode)]) -> FaultStatus {
        let mut f = FaultStatus {
            faulted: [false; DEVICE_COUNT],
            system_fault: false,
            codes: [Some(FaultCode::NoFault); DEVICE_COUNT],
        };
        for &(id, code) in faults {
            let id = usize::from(id);
            if let (Some(bit), Some(c)) = (f.faulted.get_mut(id), f.codes.get_mut(id)) {
                *bit = true;
                *c = Some(code);
            }
        }
        f
    }

    /// The number of codes carried: up to and including the last `Some`.
    fn codes_len(&self) -> usize {
        self.codes
            .iter()
            .rposition(Option::is_some)
            .map_or(0, |i| i + 1)
    }
}

impl Payload for FaultStatus {
    const ID: MessageId = MessageId::new(0x12, 0x03);
    const NAME: &'static str = "FAULT_STATUS";
    const LEN: LenRule = LenRule::Between(4, 35);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let Some((bits, code_bytes)) = p.split_first_chunk::<4>() else {
            return Err(Error::BadLength {
                message: Self::NAME,
                expected: Self::LEN,
                got: p.len(),
            });
        };
        let faulted = unpack_bits(bits);
        let mut codes = [None; DEVICE_COUNT];
        for (c, &b) in codes.iter_mut().zip(code_bytes) {
            *c = Some(FaultCode::from_byte(b));
        }
        Ok(FaultStatus {
            faulted,
            system_fault: bit(bits[3], 7),
            codes,
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.bytes(&pack_bits(&self.faulted, self.system_fault));
        for c in self.codes.iter().take(self.codes_len()) {
            w.u8(c.map_or(0, FaultCode::to_byte));
        }
    }
}

/// DEVICE_STATUS_QUERY — Appendix D only (0x12/0x04); icd-reading R6: no payload, asks
/// for an immediate DEVICE_STATUS. No table describes a payload, so whatever one comes
/// (up to [`IGNORED_PAYLOAD_MAX`] bytes) is ignored; we send none.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceStatusQuery;

impl Payload for DeviceStatusQuery {
    const ID: MessageId = MessageId::new(0x12, 0x04);
    const NAME: &'static str = "DEVICE_STATUS_QUERY";
    const LEN: LenRule = LenRule::Between(0, IGNORED_PAYLOAD_MAX);
    fn parse_payload(_: &[u8]) -> Result<Self> {
        Ok(DeviceStatusQuery)
    }
    fn emit_payload(&self, _: &mut Writer) {}
}

fn bits(set: &[(u8, bool)]) -> u8 {
    set.iter()
        .fold(0, |acc, &(b, on)| if on { acc | (1 << b) } else { acc })
}

fn unpack_bits(p: &[u8]) -> [bool; DEVICE_COUNT] {
    let mut out = [false; DEVICE_COUNT];
    for (id, o) in out.iter_mut().enumerate() {
        *o = p.get(id / 8).is_some_and(|b| b & (1 << (id % 8)) != 0);
    }
    out
}

fn pack_bits(devices: &[bool; DEVICE_COUNT], top_bit: bool) -> [u8; 4] {
    let mut out = [0u8; 4];
    for (id, &on) in devices.iter().enumerate() {
        if on && let Some(byte) = out.get_mut(id / 8) {
            *byte |= 1 << (id % 8);
        }
    }
    if top_bit {
        out[3] |= 0x80;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each axis takes its own bytes of Table 27: every byte a different value, written
    /// by hand from the table, so a byte given to the wrong axis shows.
    #[test]
    fn each_axis_reads_its_own_bytes_of_table_27() {
        let payload = [
            0b1010_0000, // byte 1: flaps enabled, fault; not running
            0b0101_1000, // byte 2: pitch running; roll enabled, running
            11,          // 3: flap position
            12,          // 4: pitch trim position
            13,          // 5: roll trim position
            0x01,        // 6: flap fault code
            0x00,        // 7: pitch trim fault code
            0x02,        // 8: roll trim fault code
            21,          // 9: flap up
            22,          // 10: flap down
            23,          // 11: flap midpoint 1
            24,          // 12: flap midpoint 2
            31,          // 13: pitch trim up
            32,          // 14: pitch trim down
            33,          // 15: pitch trim neutral
            41,          // 16: roll trim up
            42,          // 17: roll trim down
            43,          // 18: roll trim neutral
        ];
        let ft = FlapTrimStatus::parse(&payload).unwrap();
        let at = |a| {
            let s = ft.axis(a);
            (s.enabled, s.motor_running, s.fault, s.position)
        };
        assert_eq!(at(Axis::Flap), (true, false, true, 11));
        assert_eq!(at(Axis::PitchTrim), (false, true, false, 12));
        assert_eq!(at(Axis::RollTrim), (true, true, false, 13));
        let ends = |a| {
            let s = ft.axis(a);
            (s.up, s.down, s.neutral)
        };
        assert_eq!(ends(Axis::Flap), (21, 22, None));
        assert_eq!(ends(Axis::PitchTrim), (31, 32, Some(33)));
        assert_eq!(ends(Axis::RollTrim), (41, 42, Some(43)));
        let codes = [Axis::Flap, Axis::PitchTrim, Axis::RollTrim].map(|a| ft.axis(a).fault_code);
        assert_eq!(
            codes,
            [0x01, 0x00, 0x02].map(FaultCode::from_byte),
            "bytes 6, 7, 8"
        );
        assert_eq!(ft.position(Axis::RollTrim), 13);
    }

    /// Devices 9 and 30 faulted, written by hand from Table 28: device 9 is bit 1 of
    /// byte 2, device 30 bit 6 of byte 4 (its MSB, the system fault, clear); bytes 5–35
    /// are the 31 codes, 0x00 but 0x07 (SHORT_CIRCUIT) for 9 and 0x0E (TRIM_RUNAWAY)
    /// for 30 (Table 43). Device 31 has no place and is left out.
    #[test]
    fn with_faults_sets_each_listed_device_s_bit_and_code_of_table_28() {
        let f = FaultStatus::with_faults(&[
            (9, FaultCode::ShortCircuit),
            (30, FaultCode::TrimRunaway),
            (31, FaultCode::OverCurrent),
        ]);
        let mut payload = [0u8; 35];
        payload[1] = 0b0000_0010;
        payload[3] = 0b0100_0000;
        payload[4 + 9] = 0x07;
        payload[4 + 30] = 0x0E;
        assert_eq!(&f.emit()[..], &payload[..]);
        assert!(!f.system_fault);
        assert_eq!(FaultStatus::with_faults(&[]).emit()[..4], [0, 0, 0, 0]);
        assert_eq!(FaultStatus::with_faults(&[]).emit().len(), 35);
    }
}

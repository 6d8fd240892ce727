//! Data messages, ICD §6.6 (major 0x15).

use super::{Payload, Reader, Writer, bit};
use crate::error::{LenRule, Result};
use crate::frame::MessageId;

/// EXTERNAL_DATA validity flags (ICD Table 34 byte 13), MSB first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExternalValidity {
    /// Table 34 byte 13, bit 7 (MSB): indicated airspeed valid.
    pub indicated_airspeed: bool,
    /// Table 34 byte 13, bit 6: ground speed valid.
    pub ground_speed: bool,
    /// Table 34 byte 13, bit 5: baro altitude valid.
    pub baro_altitude: bool,
    /// Table 34 byte 13, bit 4: fuel pressure valid.
    pub fuel_pressure: bool,
    /// Table 34 byte 13, bit 3: RPM valid.
    pub rpm: bool,
}

/// EXTERNAL_DATA — ICD Table 34, sent by the EFIS at 1 Hz (icd-reading R20). Speeds are
/// in the EFIS's own unit, the same one used in FLAP_SPEC/TRIM_SPEC/WIG_WAG_SPEC.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExternalData {
    /// Table 34 bytes 1–2: indicated airspeed, 0–500, in the EFIS's unit (note 1).
    pub indicated_airspeed: u16,
    /// Table 34 bytes 3–4: ground speed, 0–500, in the EFIS's unit (note 1).
    pub ground_speed: u16,
    /// Feet.
    pub baro_altitude: i32,
    /// PSI.
    pub fuel_pressure: i16,
    /// Table 34 bytes 11–12: engine RPM (the starter is turned off above 500, icd-reading
    /// R18).
    pub rpm: u16,
    /// Table 34 byte 13: which of the fields above are valid.
    pub valid: ExternalValidity,
}

impl Payload for ExternalData {
    const ID: MessageId = MessageId::new(0x15, 0x00);
    const NAME: &'static str = "EXTERNAL_DATA";
    const LEN: LenRule = LenRule::Exact(13);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let mut r = Reader::new(p);
        let indicated_airspeed = r.u16();
        let ground_speed = r.u16();
        let baro_altitude = r.u32() as i32;
        let fuel_pressure = r.u16() as i16;
        let rpm = r.u16();
        let v = r.u8();
        Ok(ExternalData {
            indicated_airspeed,
            ground_speed,
            baro_altitude,
            fuel_pressure,
            rpm,
            valid: ExternalValidity {
                indicated_airspeed: bit(v, 7),
                ground_speed: bit(v, 6),
                baro_altitude: bit(v, 5),
                fuel_pressure: bit(v, 4),
                rpm: bit(v, 3),
            },
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u16(self.indicated_airspeed);
        w.u16(self.ground_speed);
        w.u32(self.baro_altitude as u32);
        w.u16(self.fuel_pressure as u16);
        w.u16(self.rpm);
        let v = &self.valid;
        let mut b = 0u8;
        for (i, on) in [
            v.indicated_airspeed,
            v.ground_speed,
            v.baro_altitude,
            v.fuel_pressure,
            v.rpm,
        ]
        .into_iter()
        .enumerate()
        {
            if on {
                b |= 0x80 >> i;
            }
        }
        w.u8(b);
    }
}

//! Power messages, ICD §6.4 (major 0x13).

use super::types::{FlapDirection, TrimDirection, TrimType, WigWagModeSetting};
use super::{Payload, Writer, exact, flag};
use crate::error::{LenRule, Result};
use crate::frame::MessageId;

/// DEVICE_POWER — ICD Table 29. Overrides the device's switch until it is cycled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DevicePower {
    /// Table 29 byte 1: device id, 0–30.
    pub device_id: u8,
    /// Table 29 byte 2: power state, 0 off, 1 on.
    pub on: bool,
}

impl Payload for DevicePower {
    const ID: MessageId = MessageId::new(0x13, 0x00);
    const NAME: &'static str = "DEVICE_POWER";
    const LEN: LenRule = LenRule::Exact(2);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 2>(p)?;
        Ok(DevicePower {
            device_id: p[0],
            on: flag(Self::NAME, "Power State", p[1])?,
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_id);
        w.u8(self.on as u8);
    }
}

/// TRIM_MOVE — ICD Table 30. Must be repeated at 4 Hz or more while the motor runs
/// (icd-reading R19); `on = false` stops it at once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TrimMove {
    /// Table 30 byte 1: 0 pitch, 1 roll.
    pub trim_type: TrimType,
    /// Table 30 byte 2: power state, 0 off, 1 on (on while repeated at 4 Hz, note 1).
    pub on: bool,
    /// Table 30 byte 3: pitch down / roll right = 0, pitch up / roll left = 1 (note 2).
    pub direction: TrimDirection,
}

impl Payload for TrimMove {
    const ID: MessageId = MessageId::new(0x13, 0x01);
    const NAME: &'static str = "TRIM_MOVE";
    const LEN: LenRule = LenRule::Exact(3);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 3>(p)?;
        Ok(TrimMove {
            trim_type: TrimType::from_byte(p[0]),
            on: flag(Self::NAME, "Power State", p[1])?,
            direction: TrimDirection::from_byte(p[2]),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.trim_type.to_byte());
        w.u8(self.on as u8);
        w.u8(self.direction.to_byte());
    }
}

/// FLAP_MOVE — ICD Table 31. Same 4 Hz rule as TRIM_MOVE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FlapMove {
    /// Table 31 byte 1: power state, 0 off, 1 on (on while repeated at 4 Hz, note 1).
    pub on: bool,
    /// Table 31 byte 2: 0 up, 1 down.
    pub direction: FlapDirection,
}

impl Payload for FlapMove {
    const ID: MessageId = MessageId::new(0x13, 0x02);
    const NAME: &'static str = "FLAP_MOVE";
    const LEN: LenRule = LenRule::Exact(2);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 2>(p)?;
        Ok(FlapMove {
            on: flag(Self::NAME, "Power State", p[0])?,
            direction: FlapDirection::from_byte(p[1]),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.on as u8);
        w.u8(self.direction.to_byte());
    }
}

/// WIG_WAG_MODE — ICD Table 32.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WigWagMode {
    /// Table 32 byte 1: 0 auto, 1 steady.
    pub mode: WigWagModeSetting,
}

impl Payload for WigWagMode {
    const ID: MessageId = MessageId::new(0x13, 0x03);
    const NAME: &'static str = "WIG_WAG_MODE";
    const LEN: LenRule = LenRule::Exact(1);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 1>(p)?;
        Ok(WigWagMode {
            mode: WigWagModeSetting::from_byte(p[0]),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.mode.to_byte());
    }
}

//! Device (configuration) messages, ICD §6.2 (major 0x11).

use alloc::string::String;

use super::types::{
    EnableFlag, FlapMode, OvervoltageLimit, Polarity, SpecAckError, SwitchId, Tenths, TrimType,
};
use super::{Payload, Reader, Writer, bit, exact, flag};
use crate::error::{Error, LenRule, Result};
use crate::frame::MessageId;

/// DEVICE_SPEC — ICD Table 13.
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
pub struct DeviceSpec {
    /// Table 13 byte 1: device id, 0–30 (Appendix B).
    pub device_id: u8,
    /// Electronic circuit breaker, whole amps (range per device, Appendix B).
    pub circuit_breaker: u8,
    /// Table 13 byte 3: the external switch, 0 off, 1–10, 11 or 255 always on (icd-reading
    /// R10).
    pub switch_id: SwitchId,
    /// Table 13 byte 4: current fault checking enabled.
    pub current_fault: bool,
    /// The switch byte as it was on the wire, for a spec decoded from a frame; `None`
    /// for one built here. icd-reading R10 folds 255 into 11 (always on), and a person
    /// checking a real unit needs to see which of the two it uses. Only shown: what is
    /// sent is always `switch_id`'s byte (11 for always on), and two specs that mean
    /// the same setting are equal whichever byte said it.
    #[serde(skip)]
    pub switch_raw: Option<u8>,
}

impl PartialEq for DeviceSpec {
    fn eq(&self, other: &Self) -> bool {
        (
            self.device_id,
            self.circuit_breaker,
            self.switch_id,
            self.current_fault,
        ) == (
            other.device_id,
            other.circuit_breaker,
            other.switch_id,
            other.current_fault,
        )
    }
}

impl Eq for DeviceSpec {}

impl Payload for DeviceSpec {
    const ID: MessageId = MessageId::new(0x11, 0x00);
    const NAME: &'static str = "DEVICE_SPEC";
    const LEN: LenRule = LenRule::Exact(4);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 4>(p)?;
        Ok(DeviceSpec {
            device_id: p[0],
            circuit_breaker: p[1],
            switch_id: SwitchId::from_byte(p[2]),
            current_fault: flag(Self::NAME, "Current Fault", p[3])?,
            switch_raw: Some(p[2]),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_id);
        w.u8(self.circuit_breaker);
        w.u8(self.switch_id.to_byte());
        w.u8(self.current_fault as u8);
    }
}

/// SYSTEM_SPEC — ICD Table 14.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct SystemSpec {
    /// Table 14 byte 1: overvoltage limit, 0 = 16 V, 1 = 32 V.
    pub overvoltage_limit: OvervoltageLimit,
    /// Device id of the secondary alternator; `None` is sent as 255 (disabled).
    pub secondary_alternator: Option<u8>,
}

impl Payload for SystemSpec {
    const ID: MessageId = MessageId::new(0x11, 0x01);
    const NAME: &'static str = "SYSTEM_SPEC";
    const LEN: LenRule = LenRule::Exact(2);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 2>(p)?;
        Ok(SystemSpec {
            overvoltage_limit: OvervoltageLimit::from_byte(p[0]),
            secondary_alternator: opt_id(p[1]),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.overvoltage_limit.to_byte());
        w.u8(self.secondary_alternator.unwrap_or(255));
    }
}

/// TRIM_SPEC — ICD Table 15. Flag bits MSB first: type, enable, polarity (icd-reading R15).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct TrimSpec {
    /// Table 15 byte 1, bit 7: trim type, 0 pitch, 1 roll.
    pub trim_type: TrimType,
    /// Table 15 byte 1, bit 6: trim enabled.
    pub enabled: bool,
    /// Table 15 byte 1, bit 5: polarity, 0 standard, 1 inverted.
    pub polarity: Polarity,
    /// Table 15 byte 2: up endpoint, position sensor 0–255.
    pub up: u8,
    /// Table 15 byte 3: down endpoint, position sensor 0–255.
    pub down: u8,
    /// Table 15 byte 4: neutral point, position sensor 0–255.
    pub neutral: u8,
    /// Percent power above `speed` (pitch only). 40–90; a fresh unit reports 100
    /// (Appendix F, icd-reading R16).
    pub power: u8,
    /// IAS/GS above which power is reduced, in the EFIS's speed unit.
    pub speed: u16,
}

impl Payload for TrimSpec {
    const ID: MessageId = MessageId::new(0x11, 0x02);
    const NAME: &'static str = "TRIM_SPEC";
    const LEN: LenRule = LenRule::Exact(7);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let mut r = Reader::new(p);
        let (kind, enabled, polarity) = spec_flags(r.u8());
        Ok(TrimSpec {
            trim_type: if kind {
                TrimType::Roll
            } else {
                TrimType::Pitch
            },
            enabled,
            polarity,
            up: r.u8(),
            down: r.u8(),
            neutral: r.u8(),
            power: r.u8(),
            speed: r.u16(),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        // An unknown trim type cannot be carried in one bit; anything but pitch is roll.
        w.u8(emit_spec_flags(
            self.trim_type != TrimType::Pitch,
            self.enabled,
            self.polarity,
        ));
        w.u8(self.up);
        w.u8(self.down);
        w.u8(self.neutral);
        w.u8(self.power);
        w.u16(self.speed);
    }
}

/// FLAP_SPEC — ICD Table 16. Flag bits MSB first: mode, enable, polarity (icd-reading R15).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct FlapSpec {
    /// Table 16 byte 1, bit 7: 0 momentary, 1 position-based.
    pub mode: FlapMode,
    /// Table 16 byte 1, bit 6: flaps enabled.
    pub enabled: bool,
    /// Table 16 byte 1, bit 5: polarity, 0 standard, 1 inverted.
    pub polarity: Polarity,
    /// Table 16 byte 2: up position, 0–255.
    pub up: u8,
    /// Table 16 byte 3: down position, 0–255.
    pub down: u8,
    /// Table 16 byte 4: midpoint #1, 0–255.
    pub midpoint_1: u8,
    /// Table 16 byte 5: midpoint #2, 0–255.
    pub midpoint_2: u8,
    /// Whole amps, 1–10.
    pub circuit_breaker: u8,
    /// Table 16 byte 7: the flap position below which the overspeed alarm is triggered
    /// (note 5).
    pub overspeed_position: u8,
    /// Speed above which flap-down is inhibited and the overspeed alarm sounds (EFIS unit).
    pub max_speed: u16,
    /// Extra run time at the endpoints, in tenths of a second (icd-reading R23).
    pub endpoint_duration: Tenths,
}

impl Payload for FlapSpec {
    const ID: MessageId = MessageId::new(0x11, 0x03);
    const NAME: &'static str = "FLAP_SPEC";
    const LEN: LenRule = LenRule::Exact(11);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let mut r = Reader::new(p);
        let (kind, enabled, polarity) = spec_flags(r.u8());
        Ok(FlapSpec {
            mode: if kind {
                FlapMode::PositionBased
            } else {
                FlapMode::Momentary
            },
            enabled,
            polarity,
            up: r.u8(),
            down: r.u8(),
            midpoint_1: r.u8(),
            midpoint_2: r.u8(),
            circuit_breaker: r.u8(),
            overspeed_position: r.u8(),
            max_speed: r.u16(),
            endpoint_duration: Tenths(r.u16()),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(emit_spec_flags(
            self.mode == FlapMode::PositionBased,
            self.enabled,
            self.polarity,
        ));
        w.u8(self.up);
        w.u8(self.down);
        w.u8(self.midpoint_1);
        w.u8(self.midpoint_2);
        w.u8(self.circuit_breaker);
        w.u8(self.overspeed_position);
        w.u16(self.max_speed);
        w.u16(self.endpoint_duration.0);
    }
}

/// WIG_WAG_SPEC — ICD Table 17. `None` is sent as 255 (disabled).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct WigWagSpec {
    /// Table 17 byte 1: wig-wag device #1, 4–28 (255 = disabled).
    pub device_one: Option<u8>,
    /// Table 17 byte 2: wig-wag device #2, 4–28 (255 = disabled).
    pub device_two: Option<u8>,
    /// Seconds, 5–60.
    pub warm_up_period: u8,
    /// Speed below which the lights flash (EFIS unit), 0–200.
    pub speed: u8,
}

impl Payload for WigWagSpec {
    const ID: MessageId = MessageId::new(0x11, 0x04);
    const NAME: &'static str = "WIG_WAG_SPEC";
    const LEN: LenRule = LenRule::Exact(4);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 4>(p)?;
        Ok(WigWagSpec {
            device_one: opt_id(p[0]),
            device_two: opt_id(p[1]),
            warm_up_period: p[2],
            speed: p[3],
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_one.unwrap_or(255));
        w.u8(self.device_two.unwrap_or(255));
        w.u8(self.warm_up_period);
        w.u8(self.speed);
    }
}

device_id_message! {
    /// DEVICE_SPEC_QUERY — ICD Table 18. 0 → FLAP_SPEC, 29/30 → TRIM_SPEC, 253 →
    /// SYSTEM_SPEC, 254 → WIG_WAG_SPEC, others → DEVICE_SPEC (icd-reading R13).
    DeviceSpecQuery = 0x11 / 0x05 "DEVICE_SPEC_QUERY" {
        /// Table 18 byte 1: 0–30, 253 (system) or 254 (wig-wag).
        device_id
    }
}

/// SPEC_ACK — ICD Tables 19 and 20; 0x11/0x06 (icd-reading R4). `error: None` is code 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpecAck {
    /// Table 19 byte 1: the device id of the spec being answered; 253 for SYSTEM_SPEC, 254
    /// for WIG_WAG_SPEC.
    pub device_id: u8,
    /// Table 19 byte 2: the Table 20 error code; `None` for 0, success.
    pub error: Option<SpecAckError>,
}

impl Payload for SpecAck {
    const ID: MessageId = MessageId::new(0x11, 0x06);
    const NAME: &'static str = "SPEC_ACK";
    const LEN: LenRule = LenRule::Exact(2);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 2>(p)?;
        Ok(SpecAck {
            device_id: p[0],
            error: match p[1] {
                0 => None,
                n => Some(SpecAckError::from_byte(n)),
            },
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_id);
        w.u8(self.error.map_or(0, SpecAckError::to_byte));
    }
}

/// DEVICE_NAME — ICD Table 21; 0x11/0x07 (icd-reading R4). Up to 16 ASCII bytes,
/// NUL-terminated when shorter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceName {
    /// Table 21 byte 1: device id, 0–30.
    pub device_id: u8,
    /// Table 21 bytes 2–17: the name, ASCII, NUL-terminated when shorter than 16.
    pub name: [u8; 16],
}

impl DeviceName {
    /// Builds a name from text; `None` when it is not ASCII or longer than 16 bytes.
    pub fn new(device_id: u8, text: &str) -> Option<Self> {
        if !text.is_ascii() || text.len() > 16 {
            return None;
        }
        let mut name = [0u8; 16];
        for (n, &b) in name.iter_mut().zip(text.as_bytes()) {
            *n = b;
        }
        Some(DeviceName { device_id, name })
    }

    /// The name up to its first NUL; non-printable bytes shown as `?`. Empty when unset.
    pub fn text(&self) -> String {
        self.name
            .iter()
            .take_while(|&&b| b != 0)
            .map(|&b| {
                if (0x20..0x7F).contains(&b) {
                    b as char
                } else {
                    '?'
                }
            })
            .collect()
    }
}

/// Table 21's 17 bytes are a maximum (§6 intro: "payload size ... represent the maximum
/// size"; the name is "up to 16 bytes", shorter ones "should be null-terminated").
/// Decision (icd-reading R28): we send 17; we take 2–17 (the id and at least the
/// terminating NUL, or a name cut short), the missing bytes read as NUL.
impl Payload for DeviceName {
    const ID: MessageId = MessageId::new(0x11, 0x07);
    const NAME: &'static str = "DEVICE_NAME";
    const LEN: LenRule = LenRule::Between(2, 17);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let Some((&device_id, given)) = p.split_first() else {
            return Err(Error::BadLength {
                message: Self::NAME,
                expected: Self::LEN,
                got: p.len(),
            });
        };
        let mut name = [0u8; 16];
        for (n, &b) in name.iter_mut().zip(given) {
            *n = b;
        }
        Ok(DeviceName { device_id, name })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_id);
        w.bytes(&self.name);
    }
}

device_id_message! {
    /// DEVICE_NAME_QUERY — ICD Table 22; answered with DEVICE_NAME.
    DeviceNameQuery = 0x11 / 0x08 "DEVICE_NAME_QUERY" {
        /// Table 22 byte 1: device id, 0–30.
        device_id
    }
}

/// DEVICE_ENABLE — ICD Table 23. Flag 2 asks; the unit answers with 0 or 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceEnable {
    /// Table 23 byte 1: device id, 4–28 (Starter, EFIS and Field_Pri are always enabled,
    /// note 1).
    pub device_id: u8,
    /// Table 23 byte 2: 0 disabled, 1 enabled, 2 query.
    pub flag: EnableFlag,
}

impl Payload for DeviceEnable {
    const ID: MessageId = MessageId::new(0x11, 0x09);
    const NAME: &'static str = "DEVICE_ENABLE";
    const LEN: LenRule = LenRule::Exact(2);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 2>(p)?;
        Ok(DeviceEnable {
            device_id: p[0],
            flag: EnableFlag::from_byte(p[1]),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_id);
        w.u8(self.flag.to_byte());
    }
}

/// The first byte of TRIM_SPEC and FLAP_SPEC (ICD Tables 15, 16; icd-reading R15): MSB
/// first, the kind bit (roll trim / position-based flaps), enable, polarity.
fn spec_flags(b: u8) -> (bool, bool, Polarity) {
    let polarity = if bit(b, 5) {
        Polarity::Inverted
    } else {
        Polarity::Standard
    };
    (bit(b, 7), bit(b, 6), polarity)
}

fn emit_spec_flags(kind: bool, enabled: bool, polarity: Polarity) -> u8 {
    (u8::from(kind) << 7)
        | (u8::from(enabled) << 6)
        | (u8::from(polarity == Polarity::Inverted) << 5)
}

fn opt_id(b: u8) -> Option<u8> {
    if b == 255 { None } else { Some(b) }
}

//! BUS (§3.3.7, format 10): a bus or electronic circuit breaker. Carried by ECBSTAT
//! (0x40) and BUSSTAT (0x45).
//!
//! Layout (icd-reading X6): state u8, ecbflags u8, then eleven i16 (involts,
//! drawamps, maxamps, champs, clamps, minamps, outvolts, maxvolts, chvolts, clvolts,
//! minvolts) = 24 bytes, then the label to the end of the data.
//!
//! **Scale (our reading):** the draft names no unit scale, so every volts and amps
//! field is in **tenths**: volts × 10 and amps × 10 ([`BUS_SCALE`]). 13.8 V is sent as
//! 138 and 4.5 A as 45; an i16 then spans ±3276.7 V or A, more than any light
//! aircraft bus needs, while keeping the 0.1 resolution the VP-X itself reports.

use crate::cursor::Reader;
use crate::dict::{EcbFlags, EcbState};

/// Bytes before the label (§3.3.7: "length(data) + 24", icd-reading X6).
pub const BUS_FIXED_LEN: usize = 24;

/// Wire units per volt and per amp: every BUS volts/amps field is in tenths (the draft
/// names no scale; icd-reading X6 asks us to choose one).
pub const BUS_SCALE: f32 = 10.0;

/// A BUS value (§3.3.7, Table 18). Volts and amps fields are in tenths (see
/// [`BUS_SCALE`]).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Bus {
    /// Table 18 `state`: the bus's state in terms of an ECB (Table 19).
    pub state: EcbState,
    /// Table 18 `ecbflags`: which fields are valid (Table 20).
    pub flags: EcbFlags,
    /// Input volts ×10; meaningful only with [`EcbFlags::INPUTVOLTS`].
    pub in_volts: i16,
    /// Current draw, amps ×10.
    pub draw_amps: i16,
    /// Table 18 `maxamps`: max amps on the bus, ×10.
    pub max_amps: i16,
    /// Table 18 `champs`: caution high amps, ×10.
    pub caution_high_amps: i16,
    /// Table 18 `clamps`: caution low amps, ×10.
    pub caution_low_amps: i16,
    /// "Could be -": a bus may show charge current as negative draw.
    pub min_amps: i16,
    /// Table 18 `outvolts`: output volts on the bus, ×10.
    pub out_volts: i16,
    /// Table 18 `maxvolts`: max volts, ×10.
    pub max_volts: i16,
    /// Table 18 `chvolts`: caution high voltage, ×10.
    pub caution_high_volts: i16,
    /// Table 18 `clvolts`: caution low voltage, ×10.
    pub caution_low_volts: i16,
    /// Table 18 `minvolts`: minimum low voltage, ×10.
    pub min_volts: i16,
    /// "System/Item" label, ISO-8859-1, as sent.
    pub label: Vec<u8>,
}

impl Bus {
    /// Volts or amps to tenths, rounded to nearest and clamped into i16 (NaN → 0),
    /// so an absurd sensor value can never wrap around to a plausible one.
    pub fn to_tenths(units: f32) -> i16 {
        let t = (units * BUS_SCALE).round();
        if t.is_nan() {
            0
        } else {
            // `as` saturates for floats, which is exactly the clamp wanted.
            t as i16
        }
    }

    /// Tenths back to volts or amps.
    pub fn from_tenths(tenths: i16) -> f32 {
        f32::from(tenths) / BUS_SCALE
    }

    /// Output volts as volts.
    pub fn out_volts_v(&self) -> f32 {
        Self::from_tenths(self.out_volts)
    }

    /// Current draw as amps.
    pub fn draw_amps_a(&self) -> f32 {
        Self::from_tenths(self.draw_amps)
    }

    /// Table 18 in its order: a struct expression evaluates its fields as written.
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<Bus> {
        Some(Bus {
            state: r.u8()?.into(),
            flags: EcbFlags(r.u8()?),
            in_volts: r.i16()?,
            draw_amps: r.i16()?,
            max_amps: r.i16()?,
            caution_high_amps: r.i16()?,
            caution_low_amps: r.i16()?,
            min_amps: r.i16()?,
            out_volts: r.i16()?,
            max_volts: r.i16()?,
            caution_high_volts: r.i16()?,
            caution_low_volts: r.i16()?,
            min_volts: r.i16()?,
            label: r.rest().to_vec(),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        out.push(self.state.into());
        out.push(self.flags.0);
        for v in [
            self.in_volts,
            self.draw_amps,
            self.max_amps,
            self.caution_high_amps,
            self.caution_low_amps,
            self.min_amps,
            self.out_volts,
            self.max_volts,
            self.caution_high_volts,
            self.caution_low_volts,
            self.min_volts,
        ] {
            out.extend_from_slice(&v.to_be_bytes());
        }
        out.extend_from_slice(&self.label);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{FormatId, Value};

    /// A BUSSTAT body written out by hand: ON, INPUTVOLTS valid, in 14.1 V (141 =
    /// 0x008D), draw 12.5 A (125 = 0x007D), max 30.0 A (300 = 0x012C), caution high
    /// 25.0 A (250 = 0x00FA), caution low 0, min −5.0 A (−50 = 0xFFCE), out 13.8 V (138
    /// = 0x008A), max 16.0 V (160 = 0x00A0), caution high 15.0 V (150 = 0x0096),
    /// caution low 12.5 V (125 = 0x007D), min 11.0 V (110 = 0x006E), label "MAIN".
    const MAIN_BUS: [u8; 28] = [
        0x02, 0x01, 0x00, 0x8D, 0x00, 0x7D, 0x01, 0x2C, 0x00, 0xFA, 0x00, 0x00, 0xFF, 0xCE, 0x00,
        0x8A, 0x00, 0xA0, 0x00, 0x96, 0x00, 0x7D, 0x00, 0x6E, b'M', b'A', b'I', b'N',
    ];

    fn main_bus() -> Bus {
        Bus {
            state: EcbState::On,
            flags: EcbFlags(EcbFlags::INPUTVOLTS),
            in_volts: Bus::to_tenths(14.1),
            draw_amps: Bus::to_tenths(12.5),
            max_amps: Bus::to_tenths(30.0),
            caution_high_amps: Bus::to_tenths(25.0),
            caution_low_amps: 0,
            min_amps: Bus::to_tenths(-5.0),
            out_volts: Bus::to_tenths(13.8),
            max_volts: Bus::to_tenths(16.0),
            caution_high_volts: Bus::to_tenths(15.0),
            caution_low_volts: Bus::to_tenths(12.5),
            min_volts: Bus::to_tenths(11.0),
            label: b"MAIN".to_vec(),
        }
    }

    #[test]
    fn volts_and_amps_are_tenths_on_the_wire() {
        assert_eq!(Value::Bus(main_bus()).to_bytes(), MAIN_BUS);
        let Ok(Value::Bus(b)) = Value::parse(FormatId::Bus, &MAIN_BUS) else {
            panic!("hand-written BUS must parse");
        };
        assert_eq!(b, main_bus());
        assert!((b.out_volts_v() - 13.8).abs() < 1e-4);
        assert!((b.draw_amps_a() - 12.5).abs() < 1e-4);
        assert!(b.flags.has(EcbFlags::INPUTVOLTS));
    }

    #[test]
    fn tenths_conversion_rounds_and_clamps() {
        assert_eq!(Bus::to_tenths(13.84), 138);
        assert_eq!(Bus::to_tenths(13.85), 139);
        assert_eq!(Bus::to_tenths(-0.04), 0);
        assert_eq!(Bus::to_tenths(1e9), i16::MAX);
        assert_eq!(Bus::to_tenths(-1e9), i16::MIN);
        assert_eq!(Bus::to_tenths(f32::NAN), 0);
    }

    #[test]
    fn empty_label_is_exactly_24_bytes() {
        let b = Bus::default();
        assert_eq!(Value::Bus(b).to_bytes().len(), BUS_FIXED_LEN);
    }
}

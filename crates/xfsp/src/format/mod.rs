//! Parameter attribute formats (§3.3): the typed value a parameter carries.
//!
//! Field sizes the draft leaves implicit are derived from each table's stated total
//! "Length:", which every table satisfies exactly with these choices:
//!
//! | Format | Length | Implicit sizes taken |
//! |---|---|---|
//! | WAYPOINT | 80 | `12*12(OCTET)` = 12 bytes, `16*16(OCTET)` = 16; wtype u8, ctype u8, flags u16 |
//! | CASMSG | label + 4 | level u8, rsvd u8, flags u16 |
//! | BUS | label + 24 | state u8, ecbflags u8, eleven i16 (icd-reading X6) |
//! | RANGE | 24 + ticks | units u16 (Table 22 has 16-bit values) |
//! | APP | label + 56 | aircraftid and swrev 16 bytes each |
//! | UPDATE | label + 56 | progflags u32, activity 32 bytes |
//! | SERVO | 8 | servomode u32 (Table 30's ENGAGE is 0x80000000) |
//! | DBASE | 92 | 16-byte names, 12-byte dates |
//!
//! RANGE's `ticks` and WBRANGE's `slices` are of type `starray`, which the draft never
//! defines; they are kept as opaque bytes so they survive a round trip unchanged.
//!
//! Text is ISO-8859-1 and "optionally NUL terminated": it is kept as the raw octets
//! (a round trip is exact) with [`latin1`] to read it and [`latin1_bytes`] to write it.

mod bus;
mod cas;
mod records;
mod waypoint;

pub use bus::{BUS_FIXED_LEN, BUS_SCALE, Bus};
pub use cas::CasMsg;
pub use records::{App, DBase, Gpio, Range, Servo, Update, WbRange};
pub use waypoint::Waypoint;

use super::cursor::Reader;
use super::dict::{Boolean, open_enum};
use super::error::{Error, LengthRule};

open_enum! {
    /// The format octet of a parameter header: which §3.3 format the data has.
    pub enum FormatId: u8 {
        Bool = 1 => "BOOL",
        Uint = 2 => "UINT",
        Waypoint = 3 => "WAYPOINT",
        String = 4 => "STRING",
        CasMsg = 5 => "CASMSG",
        Sint = 9 => "SINT",
        Bus = 10 => "BUS",
        Range = 11 => "RANGE",
        Gpio = 12 => "GPIO",
        App = 13 => "APP",
        WbRange = 14 => "WBRANGE",
        Update = 15 => "UPDATE",
        Servo = 16 => "SERVO",
        DBase = 17 => "DBASE",
    }
}

impl FormatId {
    /// The data length the format needs, or `None` for a format the draft lacks.
    pub fn length_rule(self) -> Option<LengthRule> {
        use LengthRule::{AtLeast, Exactly};
        Some(match self {
            FormatId::Bool | FormatId::Uint | FormatId::Sint => Exactly(4),
            FormatId::Waypoint => Exactly(waypoint::LEN),
            FormatId::String => AtLeast(0),
            FormatId::CasMsg => AtLeast(cas::FIXED_LEN),
            FormatId::Bus => AtLeast(BUS_FIXED_LEN),
            FormatId::Range => AtLeast(records::RANGE_FIXED_LEN),
            FormatId::Gpio => Exactly(records::GPIO_LEN),
            FormatId::App => AtLeast(records::APP_FIXED_LEN),
            FormatId::WbRange => AtLeast(records::WBRANGE_FIXED_LEN),
            FormatId::Update => AtLeast(records::UPDATE_FIXED_LEN),
            FormatId::Servo => Exactly(records::SERVO_LEN),
            FormatId::DBase => Exactly(records::DBASE_LEN),
            FormatId::Unknown(_) => return None,
        })
    }
}

/// A parameter's data, typed by its format (§3.3).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Value {
    /// BOOL, format 1 (§3.3.1, Table 6): a Table 7 boolean in 32 bits.
    Bool(Boolean),
    /// UINT, format 2 (§3.3.2, Table 8): an unsigned 32-bit integer.
    Uint(u32),
    /// WAYPOINT, format 3 (§3.3.3, Table 9): a flight-plan waypoint, 80 bytes.
    Waypoint(Box<Waypoint>),
    /// ISO-8859-1 octets, exactly as sent (a trailing NUL, if any, included).
    String(Vec<u8>),
    /// CASMSG, format 5 (§3.3.5, Table 14): a crew alerting message or checklist item.
    CasMsg(CasMsg),
    /// SINT, format 9 (§3.3.6, Table 17): a signed 32-bit integer.
    Sint(i32),
    /// BUS, format 10 (§3.3.7, Table 18): a bus or electronic circuit breaker.
    Bus(Bus),
    /// RANGE, format 11 (§3.3.8, Table 21): a display range description.
    Range(Range),
    /// GPIO, format 12 (§3.3.9, Table 23): a GPIO summary.
    Gpio(Gpio),
    /// APP, format 13 (§3.3.10, Table 24): application status.
    App(Box<App>),
    /// WBRANGE, format 14 (§3.3.11, Table 26): a weight-and-balance envelope.
    WbRange(WbRange),
    /// UPDATE, format 15 (§3.3.12, Table 27): software update progress.
    Update(Box<Update>),
    /// SERVO, format 16 (§3.3.13, Table 29): a servo position with engagement flags.
    Servo(Servo),
    /// DBASE, format 17 (§3.3.14, Table 31): database information, 92 bytes.
    DBase(Box<DBase>),
}

impl Value {
    /// The format octet this value is sent with.
    pub fn format(&self) -> FormatId {
        match self {
            Value::Bool(_) => FormatId::Bool,
            Value::Uint(_) => FormatId::Uint,
            Value::Waypoint(_) => FormatId::Waypoint,
            Value::String(_) => FormatId::String,
            Value::CasMsg(_) => FormatId::CasMsg,
            Value::Sint(_) => FormatId::Sint,
            Value::Bus(_) => FormatId::Bus,
            Value::Range(_) => FormatId::Range,
            Value::Gpio(_) => FormatId::Gpio,
            Value::App(_) => FormatId::App,
            Value::WbRange(_) => FormatId::WbRange,
            Value::Update(_) => FormatId::Update,
            Value::Servo(_) => FormatId::Servo,
            Value::DBase(_) => FormatId::DBase,
        }
    }

    /// Decodes `data` (unpadded, exactly the parameter's data length) as `format`.
    pub fn parse(format: FormatId, data: &[u8]) -> Result<Value, Error> {
        let need = format
            .length_rule()
            .ok_or(Error::UnknownFormat(format.raw()))?;
        let fits = match need {
            LengthRule::Exactly(n) => data.len() == n,
            LengthRule::AtLeast(n) => data.len() >= n,
        };
        let bad = Error::BadLength {
            format,
            len: data.len(),
            need,
        };
        if !fits {
            return Err(bad);
        }
        let mut r = Reader::new(data);
        let v = match format {
            FormatId::Bool => r.u32().map(|v| Value::Bool(v.into())),
            FormatId::Uint => r.u32().map(Value::Uint),
            FormatId::Sint => r.i32().map(Value::Sint),
            FormatId::String => Some(Value::String(r.rest().to_vec())),
            FormatId::Waypoint => Waypoint::read(&mut r).map(|w| Value::Waypoint(Box::new(w))),
            FormatId::CasMsg => CasMsg::read(&mut r).map(Value::CasMsg),
            FormatId::Bus => Bus::read(&mut r).map(Value::Bus),
            FormatId::Range => Range::read(&mut r).map(Value::Range),
            FormatId::Gpio => Gpio::read(&mut r).map(Value::Gpio),
            FormatId::App => App::read(&mut r).map(|a| Value::App(Box::new(a))),
            FormatId::WbRange => WbRange::read(&mut r).map(Value::WbRange),
            FormatId::Update => Update::read(&mut r).map(|u| Value::Update(Box::new(u))),
            FormatId::Servo => Servo::read(&mut r).map(Value::Servo),
            FormatId::DBase => DBase::read(&mut r).map(|d| Value::DBase(Box::new(d))),
            FormatId::Unknown(raw) => return Err(Error::UnknownFormat(raw)),
        };
        v.ok_or(bad)
    }

    /// The unpadded data length this value emits.
    pub fn data_len(&self) -> usize {
        match self {
            Value::Bool(_) | Value::Uint(_) | Value::Sint(_) => 4,
            Value::Waypoint(_) => waypoint::LEN,
            Value::String(s) => s.len(),
            Value::CasMsg(c) => cas::FIXED_LEN + c.label.len(),
            Value::Bus(b) => BUS_FIXED_LEN + b.label.len(),
            Value::Range(r) => records::RANGE_FIXED_LEN + r.ticks.len(),
            Value::Gpio(_) => records::GPIO_LEN,
            Value::App(a) => records::APP_FIXED_LEN + a.label.len(),
            Value::WbRange(w) => records::WBRANGE_FIXED_LEN + w.slices.len(),
            Value::Update(u) => records::UPDATE_FIXED_LEN + u.label.len(),
            Value::Servo(_) => records::SERVO_LEN,
            Value::DBase(_) => records::DBASE_LEN,
        }
    }

    /// Appends the unpadded data.
    pub fn emit(&self, out: &mut Vec<u8>) {
        match self {
            Value::Bool(b) => out.extend_from_slice(&u32::from(*b).to_be_bytes()),
            Value::Uint(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Sint(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::String(s) => out.extend_from_slice(s),
            Value::Waypoint(w) => w.write(out),
            Value::CasMsg(c) => c.write(out),
            Value::Bus(b) => b.write(out),
            Value::Range(r) => r.write(out),
            Value::Gpio(g) => g.write(out),
            Value::App(a) => a.write(out),
            Value::WbRange(w) => w.write(out),
            Value::Update(u) => u.write(out),
            Value::Servo(s) => s.write(out),
            Value::DBase(d) => d.write(out),
        }
    }

    /// The value's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut v = Vec::with_capacity(self.data_len());
        self.emit(&mut v);
        v
    }

    /// A STRING value from text (characters outside ISO-8859-1 become `?`).
    pub fn string(s: &str) -> Value {
        Value::String(latin1_bytes(s))
    }

    /// The integer of a UINT or SINT value, widened, for callers that take either.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::Uint(v) => Some(i64::from(*v)),
            Value::Sint(v) => Some(i64::from(*v)),
            _ => None,
        }
    }
}

/// Reads ISO-8859-1 octets as text, stopping at the first NUL ("optionally NUL
/// terminated", and fixed-size fields are NUL padded).
pub fn latin1(bytes: &[u8]) -> String {
    bytes
        .iter()
        .take_while(|&&b| b != 0)
        .map(|&b| char::from(b))
        .collect()
}

/// Text as ISO-8859-1 octets; characters outside it become `?`.
pub fn latin1_bytes(s: &str) -> Vec<u8> {
    s.chars().map(|c| u8::try_from(c).unwrap_or(b'?')).collect()
}

/// Text into a fixed-size, NUL-padded field, truncated to fit.
pub fn fixed_field<const N: usize>(s: &str) -> [u8; N] {
    let mut out = [0u8; N];
    for (dst, src) in out.iter_mut().zip(latin1_bytes(s)) {
        *dst = src;
    }
    out
}

#[cfg(test)]
pub(crate) mod strategies {
    //! proptest generators for every format, shared with message-level tests.
    use super::*;
    use crate::dict::*;
    use proptest::collection::vec;
    use proptest::prelude::*;

    fn label() -> impl Strategy<Value = Vec<u8>> {
        vec(any::<u8>(), 0..40)
    }

    prop_compose! {
        fn waypoint()(
            a in any::<([u8; 12], i32, i32, i32, i32, i32, i32, i32)>(),
            b in any::<(u32, u16, u16, u32, u8, u8, u16, u32, u32, [u8; 16])>(),
        ) -> Waypoint {
            Waypoint {
                label: a.0, lat: a.1, lon: a.2, lonlen: a.3, alt: a.4, minalt: a.5,
                maxalt: a.6, speed: a.7, magadj: b.0, inbound: b.1, outbound: b.2,
                freqkhz: b.3, wtype: FmsWaypoint(b.4), ctype: b.5.into(),
                flags: FmsFlags(b.6), cumete: b.7, cumdis: b.8, container: b.9,
            }
        }
    }

    prop_compose! {
        fn bus()(s in any::<u8>(), f in any::<u8>(), v in any::<[i16; 11]>(), label in label()) -> Bus {
            Bus {
                state: s.into(), flags: EcbFlags(f), in_volts: v[0], draw_amps: v[1],
                max_amps: v[2], caution_high_amps: v[3], caution_low_amps: v[4],
                min_amps: v[5], out_volts: v[6], max_volts: v[7], caution_high_volts: v[8],
                caution_low_volts: v[9], min_volts: v[10], label,
            }
        }
    }

    prop_compose! {
        fn app()(
            a in any::<(u8, u8, u16, [u16; 8], u32, [u8; 16], [u8; 16])>(),
            label in label(),
        ) -> App {
            App {
                state: a.0.into(), rsvd: a.1, appflags: a.2, period: a.3[0], avgcpu: a.3[1],
                hwcpu: a.3[2], cpulim: a.3[3], runtime: a.3[4], deadline: a.3[5],
                avgruntime: a.3[6], hwruntime: a.3[7], ivcsw: a.4, aircraftid: a.5,
                swrev: a.6, label,
            }
        }
    }

    prop_compose! {
        fn dbase()(crc in any::<u32>(), n in any::<[[u8; 16]; 4]>(), d in any::<[[u8; 12]; 2]>()) -> DBase {
            DBase { crc, name: n[0], supplier: n[1], region: n[2], cycle: n[3], valid: d[0], expires: d[1] }
        }
    }

    /// Any value of any format.
    pub(crate) fn value() -> impl Strategy<Value = Value> {
        prop_oneof![
            any::<u32>().prop_map(|v| Value::Bool(v.into())),
            any::<u32>().prop_map(Value::Uint),
            any::<i32>().prop_map(Value::Sint),
            label().prop_map(Value::String),
            waypoint().prop_map(|w| Value::Waypoint(Box::new(w))),
            (any::<u8>(), any::<u8>(), any::<u16>(), label()).prop_map(|(l, r, f, label)| {
                Value::CasMsg(CasMsg {
                    level: l.into(),
                    rsvd: r,
                    flags: CasFlags(f),
                    label,
                })
            }),
            bus().prop_map(Value::Bus),
            (any::<(u16, u16, i32, i32, i32, i32, i32)>(), label()).prop_map(|(a, ticks)| {
                Value::Range(Range {
                    numticks: a.0,
                    units: a.1.into(),
                    divisor: a.2,
                    minval: a.3,
                    maxval: a.4,
                    mindisp: a.5,
                    maxdisp: a.6,
                    ticks,
                })
            }),
            any::<(u32, u32, u16, u16)>().prop_map(|(features, outmodes, inmodes, flags)| {
                Value::Gpio(Gpio {
                    features,
                    outmodes,
                    inmodes,
                    flags,
                })
            }),
            app().prop_map(|a| Value::App(Box::new(a))),
            (any::<(u16, u16, u32, u32, u32)>(), label()).prop_map(|(a, slices)| {
                Value::WbRange(WbRange {
                    flags: a.0,
                    numslices: a.1,
                    maxtakeoff: a.2,
                    maxlanding: a.3,
                    maxzerofuel: a.4,
                    slices,
                })
            }),
            (any::<([u8; 16], u32, u32, [u8; 32])>(), label()).prop_map(|(a, label)| {
                Value::Update(Box::new(Update {
                    aircraftid: a.0,
                    progress: a.1,
                    progflags: UpdateFlags(a.2),
                    activity: a.3,
                    label,
                }))
            }),
            any::<(i32, u32)>().prop_map(|(pos, mode)| {
                Value::Servo(Servo {
                    servopos: pos,
                    servomode: ServoMode(mode),
                })
            }),
            dbase().prop_map(|d| Value::DBase(Box::new(d))),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn every_named_format_has_a_length_rule_and_a_generator_covers_it() {
        for f in FormatId::ALL {
            assert!(f.length_rule().is_some(), "{f:?}");
        }
        assert_eq!(FormatId::ALL.len(), 14, "§3.3.1 to §3.3.14");
        assert_eq!(FormatId::from(6).length_rule(), None);
    }

    #[test]
    fn scalar_formats_are_big_endian() {
        assert_eq!(
            Value::parse(FormatId::Uint, &[0x00, 0x01, 0xDF, 0x7E]),
            Ok(Value::Uint(122_750))
        );
        assert_eq!(
            Value::parse(FormatId::Sint, &[0xFF, 0xFF, 0xFF, 0xFE]),
            Ok(Value::Sint(-2))
        );
        assert_eq!(
            Value::parse(FormatId::Bool, &[0, 0, 0, 1]),
            Ok(Value::Bool(Boolean::True))
        );
        assert_eq!(Value::Sint(-100_000).to_bytes(), [0xFF, 0xFE, 0x79, 0x60]);
    }

    #[test]
    fn wrong_length_is_a_specific_error() {
        for (format, len, need) in [
            (FormatId::Uint, 3, LengthRule::Exactly(4)),
            (FormatId::Bus, 23, LengthRule::AtLeast(24)),
            (FormatId::DBase, 93, LengthRule::Exactly(92)),
        ] {
            assert_eq!(
                Value::parse(format, &vec![0x5A; len]),
                Err(Error::BadLength { format, len, need }),
                "{format:?}"
            );
        }
    }

    #[test]
    fn unknown_format_is_a_specific_error() {
        assert_eq!(
            Value::parse(FormatId::from(6), &[0; 4]),
            Err(Error::UnknownFormat(6))
        );
        assert_eq!(
            Value::parse(FormatId::from(200), &[]),
            Err(Error::UnknownFormat(200))
        );
    }

    #[test]
    fn latin1_text_helpers() {
        assert_eq!(latin1(b"MAIN BUS\0\0junk"), "MAIN BUS");
        assert_eq!(latin1(&[0x43, 0xE9]), "Cé");
        assert_eq!(latin1_bytes("Cé€"), vec![0x43, 0xE9, b'?']);
        assert_eq!(fixed_field::<4>("ABCDEF"), *b"ABCD");
        assert_eq!(fixed_field::<4>("AB"), *b"AB\0\0");
    }

    proptest! {
        #[test]
        fn every_format_round_trips(v in strategies::value()) {
            let bytes = v.to_bytes();
            prop_assert_eq!(bytes.len(), v.data_len());
            prop_assert_eq!(Value::parse(v.format(), &bytes), Ok(v));
        }

        #[test]
        fn arbitrary_data_never_panics_and_reparses_identically(
            f in any::<u8>(),
            data in proptest::collection::vec(any::<u8>(), 0..200),
        ) {
            if let Ok(v) = Value::parse(FormatId::from(f), &data) {
                prop_assert_eq!(v.to_bytes(), data, "decoding must lose nothing");
            }
        }
    }
}

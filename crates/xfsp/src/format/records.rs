//! The remaining fixed-layout formats: RANGE, GPIO, APP, WBRANGE, UPDATE, SERVO and
//! DBASE (§3.3.8 to §3.3.14). Each follows its table in order, big-endian.

use crate::cursor::Reader;
use crate::dict::{ScbState, ServoMode, Units, UpdateFlags};

pub(crate) const RANGE_FIXED_LEN: usize = 24;
pub(crate) const GPIO_LEN: usize = 12;
pub(crate) const APP_FIXED_LEN: usize = 56;
pub(crate) const WBRANGE_FIXED_LEN: usize = 16;
pub(crate) const UPDATE_FIXED_LEN: usize = 56;
pub(crate) const SERVO_LEN: usize = 8;
pub(crate) const DBASE_LEN: usize = 92;

fn put16(out: &mut Vec<u8>, v: u16) {
    out.extend_from_slice(&v.to_be_bytes());
}

fn put32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_be_bytes());
}

fn puti32(out: &mut Vec<u8>, v: i32) {
    out.extend_from_slice(&v.to_be_bytes());
}

/// RANGE (format 11, §3.3.8, Table 21): display range description, e.g. for AOAR.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Range {
    /// Table 21 `numticks`: how many valid ticks are in the parameter data.
    pub numticks: u16,
    /// Table 21 `units`: the display unit (Table 22).
    pub units: Units,
    /// Table 21 `divisor`: for display, the logical divisions.
    pub divisor: i32,
    /// Table 21 `minval`: minimum valid value.
    pub minval: i32,
    /// Table 21 `maxval`: maximum valid value.
    pub maxval: i32,
    /// Table 21 `mindisp`: where the display starts; lower values are clipped.
    pub mindisp: i32,
    /// Table 21 `maxdisp`: where the display stops; higher values are clipped.
    pub maxdisp: i32,
    /// `starray` tick data; the draft never defines `starray`, so these are the raw
    /// bytes after the 24-byte fixed part.
    pub ticks: Vec<u8>,
}

impl Range {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<Range> {
        Some(Range {
            numticks: r.u16()?,
            units: r.u16()?.into(),
            divisor: r.i32()?,
            minval: r.i32()?,
            maxval: r.i32()?,
            mindisp: r.i32()?,
            maxdisp: r.i32()?,
            ticks: r.rest().to_vec(),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        put16(out, self.numticks);
        put16(out, self.units.into());
        for v in [
            self.divisor,
            self.minval,
            self.maxval,
            self.mindisp,
            self.maxdisp,
        ] {
            puti32(out, v);
        }
        out.extend_from_slice(&self.ticks);
    }
}

/// GPIO (format 12, §3.3.9, Table 23): I/O module summary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gpio {
    /// Eight 4-bit feature codes.
    pub features: u32,
    /// Eight 4-bit output modes.
    pub outmodes: u32,
    /// Eight 2-bit input modes.
    pub inmodes: u16,
    /// Table 23 `flags`: reserved for future use.
    pub flags: u16,
}

impl Gpio {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<Gpio> {
        Some(Gpio {
            features: r.u32()?,
            outmodes: r.u32()?,
            inmodes: r.u16()?,
            flags: r.u16()?,
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        put32(out, self.features);
        put32(out, self.outmodes);
        put16(out, self.inmodes);
        put16(out, self.flags);
    }
}

/// APP (format 13, §3.3.10, Table 24): application status, for APPSTAT.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct App {
    /// Table 24 `state`: the application's state (Table 25, scb-state).
    pub state: ScbState,
    /// Table 24 `rsvd`: reserved bits, kept as received.
    pub rsvd: u8,
    /// Table 24 `appflags`: flags regarding the app.
    pub appflags: u16,
    /// Table 24 `period`: baseline runtime period.
    pub period: u16,
    /// Table 24 `avgcpu`: average OS CPU time, units per period over the last second.
    pub avgcpu: u16,
    /// Table 24 `hwcpu`: high-water OS CPU time, units per period.
    pub hwcpu: u16,
    /// Table 24 `cpulim`: limit on OS CPU time, units per period.
    pub cpulim: u16,
    /// Table 24 `runtime`: max allocated runtime per period.
    pub runtime: u16,
    /// Table 24 `deadline`: deadline for completion per period.
    pub deadline: u16,
    /// Table 24 `avgruntime`: average runtime over the last second.
    pub avgruntime: u16,
    /// Table 24 `hwruntime`: high-water runtime.
    pub hwruntime: u16,
    /// Table 24 `ivcsw`: involuntary context switches.
    pub ivcsw: u32,
    /// Table 24 `aircraftid`: aircraft identifier, 16 octets.
    pub aircraftid: [u8; 16],
    /// Table 24 `swrev`: software version identifier, 16 octets.
    pub swrev: [u8; 16],
    /// Table 24 `label`: the application's name, ISO-8859-1 as sent.
    pub label: Vec<u8>,
}

impl App {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<App> {
        Some(App {
            state: r.u8()?.into(),
            rsvd: r.u8()?,
            appflags: r.u16()?,
            period: r.u16()?,
            avgcpu: r.u16()?,
            hwcpu: r.u16()?,
            cpulim: r.u16()?,
            runtime: r.u16()?,
            deadline: r.u16()?,
            avgruntime: r.u16()?,
            hwruntime: r.u16()?,
            ivcsw: r.u32()?,
            aircraftid: r.array()?,
            swrev: r.array()?,
            label: r.rest().to_vec(),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        out.push(self.state.into());
        out.push(self.rsvd);
        for v in [
            self.appflags,
            self.period,
            self.avgcpu,
            self.hwcpu,
            self.cpulim,
            self.runtime,
            self.deadline,
            self.avgruntime,
            self.hwruntime,
        ] {
            put16(out, v);
        }
        put32(out, self.ivcsw);
        out.extend_from_slice(&self.aircraftid);
        out.extend_from_slice(&self.swrev);
        out.extend_from_slice(&self.label);
    }
}

/// WBRANGE (format 14, §3.3.11, Table 26): weight-and-balance envelope.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WbRange {
    /// Table 26 `flags`: flags, if any.
    pub flags: u16,
    /// Table 26 `numslices`: number of slices specified.
    pub numslices: u16,
    /// Table 26 `maxtakeoff`: max takeoff weight.
    pub maxtakeoff: u32,
    /// Table 26 `maxlanding`: max landing weight.
    pub maxlanding: u32,
    /// Table 26 `maxzerofuel`: max zero fuel weight.
    pub maxzerofuel: u32,
    /// `starray` slice data, kept as raw bytes (the draft never defines `starray`).
    pub slices: Vec<u8>,
}

impl WbRange {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<WbRange> {
        Some(WbRange {
            flags: r.u16()?,
            numslices: r.u16()?,
            maxtakeoff: r.u32()?,
            maxlanding: r.u32()?,
            maxzerofuel: r.u32()?,
            slices: r.rest().to_vec(),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        put16(out, self.flags);
        put16(out, self.numslices);
        put32(out, self.maxtakeoff);
        put32(out, self.maxlanding);
        put32(out, self.maxzerofuel);
        out.extend_from_slice(&self.slices);
    }
}

/// UPDATE (format 15, §3.3.12, Table 27): software update progress.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Update {
    /// Table 27 `aircraftid`: aircraft identifier, 16 octets.
    pub aircraftid: [u8; 16],
    /// Table 27 `progress`: progress.
    pub progress: u32,
    /// Table 27 `progflags`: progress flags (Table 28).
    pub progflags: UpdateFlags,
    /// Table 27 `activity`: description of the current activity, 32 octets.
    pub activity: [u8; 32],
    /// Table 27 `label`: name of the CPU being updated, as sent.
    pub label: Vec<u8>,
}

impl Update {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<Update> {
        Some(Update {
            aircraftid: r.array()?,
            progress: r.u32()?,
            progflags: UpdateFlags(r.u32()?),
            activity: r.array()?,
            label: r.rest().to_vec(),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.aircraftid);
        put32(out, self.progress);
        put32(out, self.progflags.0);
        out.extend_from_slice(&self.activity);
        out.extend_from_slice(&self.label);
    }
}

/// SERVO (format 16, §3.3.13, Table 29): a servo position with engagement flags.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Servo {
    /// Table 29 `servopos`: the servo position (the draft leaves it undefined).
    pub servopos: i32,
    /// Table 29 `servomode`: engagement flags (Table 30).
    pub servomode: ServoMode,
}

impl Servo {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<Servo> {
        Some(Servo {
            servopos: r.i32()?,
            servomode: ServoMode(r.u32()?),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        puti32(out, self.servopos);
        put32(out, self.servomode.0);
    }
}

/// DBASE (format 17, §3.3.14, Table 31): active database information.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DBase {
    /// Table 31 `crc`: a 32-bit CRC (the draft leaves it undefined).
    pub crc: u32,
    /// Table 31 `name`: name of the database (e.g. com), 16 octets.
    pub name: [u8; 16],
    /// Table 31 `supplier`: who supplied the database, 16 octets.
    pub supplier: [u8; 16],
    /// Table 31 `region`: the region the data is valid for, 16 octets.
    pub region: [u8; 16],
    /// Table 31 `cycle`: the cycle, 16 octets.
    pub cycle: [u8; 16],
    /// "YYYY-MM-DD", NUL padded.
    pub valid: [u8; 12],
    /// Table 31 `expires`: the date after which the data expires, "YYYY-MM-DD", NUL padded.
    pub expires: [u8; 12],
}

impl DBase {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<DBase> {
        Some(DBase {
            crc: r.u32()?,
            name: r.array()?,
            supplier: r.array()?,
            region: r.array()?,
            cycle: r.array()?,
            valid: r.array()?,
            expires: r.array()?,
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        put32(out, self.crc);
        for f in [&self.name, &self.supplier, &self.region, &self.cycle] {
            out.extend_from_slice(f);
        }
        out.extend_from_slice(&self.valid);
        out.extend_from_slice(&self.expires);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{FormatId, Value, fixed_field};

    #[test]
    fn servo_by_hand() {
        let bytes = [0xFF, 0xFF, 0xFF, 0x9C, 0x80, 0x00, 0x00, 0x01];
        let s = Servo {
            servopos: -100,
            servomode: ServoMode(ServoMode::ENGAGE | ServoMode::ENGAGED),
        };
        assert_eq!(Value::Servo(s).to_bytes(), bytes);
        assert_eq!(Value::parse(FormatId::Servo, &bytes), Ok(Value::Servo(s)));
    }

    #[test]
    fn range_units_are_16_bits_after_numticks() {
        let mut bytes = vec![0x00, 0x04, 0x80, 0x07];
        bytes.extend_from_slice(&[0; 20]);
        bytes.extend_from_slice(&[9, 9]);
        let Ok(Value::Range(r)) = Value::parse(FormatId::Range, &bytes) else {
            panic!("RANGE of 26 bytes must parse");
        };
        assert_eq!((r.numticks, r.units), (4, Units::Mph));
        assert_eq!(r.ticks, [9, 9]);
    }

    #[test]
    fn dbase_dates_sit_at_the_end() {
        let d = DBase {
            crc: 0xDEAD_BEEF,
            name: fixed_field("nav"),
            supplier: [0; 16],
            region: [0; 16],
            cycle: fixed_field("2401"),
            valid: fixed_field("2024-01-25"),
            expires: fixed_field("2024-02-22"),
        };
        let b = Value::DBase(Box::new(d)).to_bytes();
        assert_eq!(b.len(), 92);
        assert_eq!(&b[..4], [0xDE, 0xAD, 0xBE, 0xEF]);
        assert_eq!(&b[68..78], b"2024-01-25");
        assert_eq!(&b[80..90], b"2024-02-22");
    }

    #[test]
    fn app_and_update_fixed_parts_are_56() {
        let mut app = vec![2u8, 0];
        app.extend_from_slice(&[0; 54]);
        app.extend_from_slice(b"efis");
        let Ok(Value::App(a)) = Value::parse(FormatId::App, &app) else {
            panic!("APP must parse");
        };
        assert_eq!(
            (a.state, a.label.as_slice()),
            (ScbState::Running, &b"efis"[..])
        );
        let mut upd = vec![0u8; 20];
        upd.extend_from_slice(&[0, 0, 0, 2]);
        upd.extend_from_slice(&[0; 32]);
        let Ok(Value::Update(u)) = Value::parse(FormatId::Update, &upd) else {
            panic!("UPDATE must parse");
        };
        assert!(u.progflags.has(UpdateFlags::ERROR) && u.label.is_empty());
    }
}

//! WAYPOINT (§3.3.3, format 3), 80 bytes. `12*12(OCTET)` is read as 12 octets and
//! `16*16(OCTET)` as 16: with wtype u8, ctype u8 and flags u16 (Table 12 has 16-bit
//! values) that is exactly the stated 80.

use crate::cursor::Reader;
use crate::dict::{FmsContainer, FmsFlags, FmsWaypoint};

pub(crate) const LEN: usize = 80;

/// A WAYPOINT value (§3.3.3, Table 9).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Waypoint {
    /// Name, NUL padded.
    pub label: [u8; 12],
    /// Degrees × 10,000,000.
    pub lat: i32,
    /// Degrees × 10,000,000.
    pub lon: i32,
    /// Metres per degree of longitude at this latitude.
    pub lonlen: i32,
    /// 0.1 ft.
    pub alt: i32,
    /// Table 9 `minalt`: logical minimum altitude for fix crossing, 0.1 ft.
    pub minalt: i32,
    /// Table 9 `maxalt`: logical maximum altitude for fix crossing, 0.1 ft.
    pub maxalt: i32,
    /// Table 9 `speed`: target indicated airspeed.
    pub speed: i32,
    /// 0.01 degrees.
    pub magadj: u32,
    /// 0.01 degrees.
    pub inbound: u16,
    /// Table 9 `outbound`: outbound course, 0.01 degrees.
    pub outbound: u16,
    /// Table 9 `freqkhz`: frequency in kHz if this is a NAVAID.
    pub freqkhz: u32,
    /// Table 9 `wtype`: type of waypoint (Table 10).
    pub wtype: FmsWaypoint,
    /// Table 9 `ctype`: type of container (Table 11).
    pub ctype: FmsContainer,
    /// Table 9 `flags`: flags for the waypoint and leg (Table 12).
    pub flags: FmsFlags,
    /// 0.01 s.
    pub cumete: u32,
    /// 0.001 nm.
    pub cumdis: u32,
    /// E.g. "V431", NUL padded.
    pub container: [u8; 16],
}

impl Waypoint {
    pub(crate) fn read(r: &mut Reader<'_>) -> Option<Waypoint> {
        Some(Waypoint {
            label: r.array()?,
            lat: r.i32()?,
            lon: r.i32()?,
            lonlen: r.i32()?,
            alt: r.i32()?,
            minalt: r.i32()?,
            maxalt: r.i32()?,
            speed: r.i32()?,
            magadj: r.u32()?,
            inbound: r.u16()?,
            outbound: r.u16()?,
            freqkhz: r.u32()?,
            wtype: FmsWaypoint(r.u8()?),
            ctype: r.u8()?.into(),
            flags: FmsFlags(r.u16()?),
            cumete: r.u32()?,
            cumdis: r.u32()?,
            container: r.array()?,
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.label);
        for v in [
            self.lat,
            self.lon,
            self.lonlen,
            self.alt,
            self.minalt,
            self.maxalt,
            self.speed,
        ] {
            out.extend_from_slice(&v.to_be_bytes());
        }
        out.extend_from_slice(&self.magadj.to_be_bytes());
        out.extend_from_slice(&self.inbound.to_be_bytes());
        out.extend_from_slice(&self.outbound.to_be_bytes());
        out.extend_from_slice(&self.freqkhz.to_be_bytes());
        out.push(self.wtype.0);
        out.push(self.ctype.into());
        out.extend_from_slice(&self.flags.0.to_be_bytes());
        out.extend_from_slice(&self.cumete.to_be_bytes());
        out.extend_from_slice(&self.cumdis.to_be_bytes());
        out.extend_from_slice(&self.container);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{FormatId, Value, fixed_field};

    #[test]
    fn field_offsets_by_hand() {
        let w = Waypoint {
            label: fixed_field("KOSH"),
            lat: 0x0102_0304,
            lon: -1,
            lonlen: 0,
            alt: 0,
            minalt: 0,
            maxalt: 0,
            speed: 0,
            magadj: 0,
            inbound: 0xAABB,
            outbound: 0,
            freqkhz: 0,
            wtype: FmsWaypoint(8),
            ctype: FmsContainer::App,
            flags: FmsFlags(0x0400 | 12),
            cumete: 0,
            cumdis: 0,
            container: fixed_field("ILS-36"),
        };
        let b = Value::Waypoint(Box::new(w.clone())).to_bytes();
        assert_eq!(b.len(), 80);
        assert_eq!(&b[0..4], b"KOSH");
        assert_eq!(&b[12..16], [1, 2, 3, 4]);
        assert_eq!(&b[16..20], [0xFF; 4]);
        assert_eq!(
            &b[44..46],
            [0xAA, 0xBB],
            "inbound after seven i32 and magadj"
        );
        assert_eq!(&b[52..56], [8, 12, 0x04, 12], "wtype, ctype, flags");
        assert_eq!(&b[64..70], b"ILS-36");
        assert_eq!(
            Value::parse(FormatId::Waypoint, &b),
            Ok(Value::Waypoint(Box::new(w)))
        );
    }
}

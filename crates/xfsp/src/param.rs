//! One XFSp parameter (§3.2, icd-reading X2): a 12-byte header and data padded with
//! zeros to a multiple of four.
//!
//! ```text
//!  0               1               2               3
//! +---------------+---------------+---------------+---------------+
//! |             unit              |            subunit            |
//! +---------------+---------------+---------------+---------------+
//! |  data len (12 bits)   |             ident (20 bits)           |
//! +---------------+---------------+---------------+---------------+
//! |    format     |  confidence   |    expire     |    pflags     |
//! +---------------+---------------+---------------+---------------+
//! ```

use super::cursor::Reader;
use super::dict::{CertLevel, Confidence};
use super::error::Error;
use super::expire::Expire;
use super::format::{FormatId, Value};
use super::idents::Ident;

/// Size of a parameter header (§3.2, icd-reading X2).
pub const PARAM_HEADER_LEN: usize = 12;
/// Largest data length the 12-bit field can carry (§3.2 Parameter Data Len).
pub const MAX_DATA_LEN: usize = 0xFFF;
/// Largest ident the 20-bit field can carry (§3.2 Ident).
pub const MAX_IDENT: u32 = 0xF_FFFF;

/// `len` rounded up to a multiple of four (§3.2: data is padded to 4 bytes).
pub const fn padded_len(len: usize) -> usize {
    len.div_ceil(4) * 4
}

/// A parameter header as on the wire (§3.2, Figure 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ParamHeader {
    /// §3.2 `Unit`: which unit the parameter applies to, if appropriate (e.g. engine #1).
    pub unit: u16,
    /// §3.2 `SubUnit`: which subunit, if appropriate (e.g. cylinder #3).
    pub subunit: u16,
    /// Unpadded data length, 0..=4095.
    pub data_len: u16,
    /// 20-bit ident.
    pub ident: Ident,
    /// §3.2 `Format`: the attribute format (§3.3).
    pub format: FormatId,
    /// §3.2 `Confidence` (Table 5).
    pub confidence: Confidence,
    /// §3.2 `Expire`: time to live (§3.2.2).
    pub expire: Expire,
    /// Reserved flags; the bottom three bits are the certification level.
    pub pflags: u8,
}

impl ParamHeader {
    /// Parses a parameter header from the first 12 bytes of `buf`.
    pub fn parse(buf: &[u8]) -> Option<ParamHeader> {
        let mut r = Reader::new(buf);
        let unit = r.u16()?;
        let subunit = r.u16()?;
        let len_ident = r.u32()?;
        let [format, confidence, expire, pflags] = r.array()?;
        Some(ParamHeader {
            unit,
            subunit,
            data_len: (len_ident >> 20) as u16,
            ident: Ident(len_ident & MAX_IDENT),
            format: format.into(),
            confidence: confidence.into(),
            expire: Expire(expire),
            pflags,
        })
    }

    /// The header's 12 bytes, or an error if the length or ident overflows its field.
    pub fn to_bytes(&self) -> Result<[u8; PARAM_HEADER_LEN], Error> {
        if usize::from(self.data_len) > MAX_DATA_LEN {
            return Err(Error::DataTooLong {
                len: self.data_len.into(),
            });
        }
        if self.ident.0 > MAX_IDENT {
            return Err(Error::IdentTooLarge(self.ident.0));
        }
        let len_ident = (u32::from(self.data_len) << 20) | self.ident.0;
        let [u0, u1] = self.unit.to_be_bytes();
        let [s0, s1] = self.subunit.to_be_bytes();
        let [l0, l1, l2, l3] = len_ident.to_be_bytes();
        Ok([
            u0,
            u1,
            s0,
            s1,
            l0,
            l1,
            l2,
            l3,
            self.format.into(),
            self.confidence.into(),
            self.expire.0,
            self.pflags,
        ])
    }

    /// Bytes this parameter occupies in a message: header plus padded data.
    pub fn wire_len(&self) -> usize {
        PARAM_HEADER_LEN + padded_len(self.data_len.into())
    }

    /// The certification level from the bottom three bits of `pflags`.
    pub fn cert(&self) -> CertLevel {
        CertLevel::from(self.pflags & 0x7)
    }
}

/// A parameter read in place (§3.2): its header and its unpadded data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParamView<'a> {
    /// The parameter header (§3.2).
    pub header: ParamHeader,
    /// The data, without its padding (§3.2 Parameter Data Len bytes).
    pub data: &'a [u8],
}

impl ParamView<'_> {
    /// Decodes the data according to the header's format.
    pub fn value(&self) -> Result<Value, Error> {
        Value::parse(self.header.format, self.data)
    }

    /// The owned, typed parameter.
    pub fn to_parameter(&self) -> Result<Parameter, Error> {
        let h = &self.header;
        Ok(Parameter {
            unit: h.unit,
            subunit: h.subunit,
            ident: h.ident,
            confidence: h.confidence,
            expire: h.expire,
            pflags: h.pflags,
            value: self.value()?,
        })
    }
}

/// Walks a block of parameters (a message body), checking framing: each header is
/// whole and each padded data block lies inside the block (padding bytes are not
/// looked at: senders pad with zeros, receivers skip them, draft §3.2). Yields
/// the first framing error and then stops. It does not decode values, so a parameter
/// of a format we do not know can still be skipped or relayed.
#[derive(Debug, Clone)]
pub struct Params<'a> {
    rest: &'a [u8],
    /// Offset of `rest` in the datagram, for error messages.
    offset: usize,
    failed: bool,
}

impl<'a> Params<'a> {
    /// `block` starts at `offset` within its datagram (12 after a message header).
    pub fn new(block: &'a [u8], offset: usize) -> Params<'a> {
        Params {
            rest: block,
            offset,
            failed: false,
        }
    }

    fn next_param(&mut self) -> Result<ParamView<'a>, Error> {
        let offset = self.offset;
        let available = self.rest.len();
        let header =
            ParamHeader::parse(self.rest).ok_or(Error::ShortParamHeader { offset, available })?;
        let after_header = self.rest.get(PARAM_HEADER_LEN..).unwrap_or_default();
        let len = usize::from(header.data_len);
        let padded = padded_len(len);
        let past_end = Error::ParamPastEnd {
            offset,
            len: header.data_len,
            padded,
            available: after_header.len(),
        };
        let (block, rest) = after_header.split_at_checked(padded).ok_or(past_end)?;
        // Draft §3.2: data "MUST be padded to a multiple of four bytes"; that the
        // padding is zero is only our sending rule (icd-reading X2), so on
        // receipt its bytes are skipped whatever they hold.
        let data = block.get(..len).ok_or(past_end)?;
        self.rest = rest;
        self.offset += PARAM_HEADER_LEN + padded;
        Ok(ParamView { header, data })
    }
}

impl<'a> Iterator for Params<'a> {
    type Item = Result<ParamView<'a>, Error>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed || self.rest.is_empty() {
            return None;
        }
        let r = self.next_param();
        self.failed = r.is_err();
        Some(r)
    }
}

/// A parameter: who/what it is about, how much to trust it, how long it lives, and
/// its typed value (the format octet follows from the value).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Parameter {
    /// §3.2 `Unit`: which unit the parameter applies to, if appropriate.
    pub unit: u16,
    /// §3.2 `SubUnit`: which subunit, if appropriate.
    pub subunit: u16,
    /// §3.2 `Ident`: the §3.4 parameter id, 20 bits.
    pub ident: Ident,
    /// §3.2 `Confidence` (Table 5).
    pub confidence: Confidence,
    /// §3.2 `Expire`: time to live (§3.2.2).
    pub expire: Expire,
    /// Reserved flags; the bottom three bits are the certification level.
    pub pflags: u8,
    /// The data, typed by its §3.3 format.
    pub value: Value,
}

impl Parameter {
    /// Unit and subunit 0, confidence HIGH, never expires, EXPERIMENTAL.
    pub fn new(ident: Ident, value: Value) -> Parameter {
        Parameter {
            unit: 0,
            subunit: 0,
            ident,
            confidence: Confidence::High,
            expire: Expire::NEVER,
            pflags: 0,
            value,
        }
    }

    /// With §3.2 `Unit` set to `unit`.
    pub fn unit(mut self, unit: u16) -> Self {
        self.unit = unit;
        self
    }

    /// With §3.2 `SubUnit` set to `subunit`.
    pub fn subunit(mut self, subunit: u16) -> Self {
        self.subunit = subunit;
        self
    }

    /// With §3.2 `Confidence` set to `c` (Table 5).
    pub fn confidence(mut self, c: Confidence) -> Self {
        self.confidence = c;
        self
    }

    /// With §3.2 `Expire` set to `e` (§3.2.2).
    pub fn expire(mut self, e: Expire) -> Self {
        self.expire = e;
        self
    }

    /// Sets the certification level, keeping the other (reserved) pflags bits.
    pub fn cert(mut self, level: CertLevel) -> Self {
        self.pflags = (self.pflags & !0x7) | (u8::from(level) & 0x7);
        self
    }

    /// The certification level from the bottom three bits of `pflags`.
    pub fn cert_level(&self) -> CertLevel {
        CertLevel::from(self.pflags & 0x7)
    }

    /// The header this parameter is sent with.
    pub fn header(&self) -> Result<ParamHeader, Error> {
        let len = self.value.data_len();
        let data_len = u16::try_from(len)
            .ok()
            .filter(|&l| usize::from(l) <= MAX_DATA_LEN)
            .ok_or(Error::DataTooLong { len })?;
        Ok(ParamHeader {
            unit: self.unit,
            subunit: self.subunit,
            data_len,
            ident: self.ident,
            format: self.value.format(),
            confidence: self.confidence,
            expire: self.expire,
            pflags: self.pflags,
        })
    }

    /// Bytes this parameter occupies in a message (header plus padded data).
    pub fn wire_len(&self) -> usize {
        PARAM_HEADER_LEN + padded_len(self.value.data_len())
    }

    /// Appends header, data and zero padding. On error nothing is appended.
    pub fn emit(&self, out: &mut Vec<u8>) -> Result<(), Error> {
        let header = self.header()?.to_bytes()?;
        out.reserve(self.wire_len());
        out.extend_from_slice(&header);
        let start = out.len();
        self.value.emit(out);
        let len = out.len() - start;
        out.resize(start + padded_len(len), 0);
        Ok(())
    }

    /// Parses one parameter from the start of `buf`; returns it and the bytes used.
    pub fn parse(buf: &[u8]) -> Result<(Parameter, usize), Error> {
        let mut it = Params::new(buf, 0);
        let view = it.next().unwrap_or(Err(Error::ShortParamHeader {
            offset: 0,
            available: 0,
        }))?;
        Ok((view.to_parameter()?, view.header.wire_len()))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::format::strategies;
    use crate::idents;
    use proptest::prelude::*;

    /// §5.1.2 written out by hand: unit 2, subunit 0, len 4 / ident 0x24 packed as
    /// 0x004_00024, UINT 2, USERSEL 128, expire 0xFF, LEVEL-A 5, 122750 = 0x0001DF7E.
    const FREQUENCY: [u8; 16] = [
        0x00, 0x02, 0x00, 0x00, 0x00, 0x40, 0x00, 0x24, 0x02, 0x80, 0xFF, 0x05, 0x00, 0x01, 0xDF,
        0x7E,
    ];
    /// §5.1.3: the same with COMSQL 0x28 and 53 = 0x00000035.
    const SQUELCH: [u8; 16] = [
        0x00, 0x02, 0x00, 0x00, 0x00, 0x40, 0x00, 0x28, 0x02, 0x80, 0xFF, 0x05, 0x00, 0x00, 0x00,
        0x35,
    ];

    fn radio(ident: Ident, v: u32) -> Parameter {
        Parameter::new(ident, Value::Uint(v))
            .unit(2)
            .confidence(Confidence::UserSel)
            .cert(CertLevel::LevelA)
    }

    #[test]
    fn section_5_1_2_frequency_both_ways() {
        let p = radio(idents::COMFREQKHZ, 122_750);
        let mut out = Vec::new();
        p.emit(&mut out).unwrap();
        assert_eq!(out, FREQUENCY);
        assert_eq!(Parameter::parse(&FREQUENCY), Ok((p, 16)));
    }

    #[test]
    fn section_5_1_3_squelch_both_ways() {
        let p = radio(idents::COMSQL, 53);
        let mut out = Vec::new();
        p.emit(&mut out).unwrap();
        assert_eq!(out, SQUELCH);
        let (q, used) = Parameter::parse(&SQUELCH).unwrap();
        assert_eq!(
            (q.cert_level(), q.expire, used),
            (CertLevel::LevelA, Expire::NEVER, 16)
        );
        assert_eq!(q, p);
    }

    #[test]
    fn length_and_ident_share_one_u32() {
        let h = ParamHeader::parse(&[0, 0, 0, 0, 0xAB, 0xCD, 0xEF, 0x12, 4, 0, 0, 0]).unwrap();
        assert_eq!(h.data_len, 0xABC);
        assert_eq!(h.ident, Ident(0xDEF12));
    }

    #[test]
    fn data_is_padded_with_zeros_to_four() {
        let p = Parameter::new(idents::TAILNUM, Value::string("N123"));
        let mut out = Vec::new();
        p.emit(&mut out).unwrap();
        assert_eq!(out.len(), 16);
        let p = Parameter::new(idents::TAILNUM, Value::string("N12345"));
        out.clear();
        p.emit(&mut out).unwrap();
        assert_eq!(out.len(), 20);
        assert_eq!(out[4] >> 4, 0, "length high nibble");
        assert_eq!(out[5] >> 4, 6, "length 6 in the top 12 bits");
        assert_eq!(&out[12..], b"N12345\0\0");
    }

    #[test]
    fn nonzero_padding_is_skipped_on_receipt() {
        // TAILNUM "N1" (STRING, format 4: §3.3.4 "%d4"), unit 0, subunit 0, written
        // from draft §3.2: data length 2 in the top 12 bits of the fourth field, ident
        // %x00.00.92, then format, confidence, expire, pflags, then "N1" and two
        // padding bytes that are not zero.
        let bytes = [
            0x00, 0x00, 0x00, 0x00, // unit, subunit
            0x00, 0x20, 0x00, 0x92, // length 2, ident
            0x04, 0x00, 0xFF, 0x00, // format STRING, confidence, expire never, pflags
            b'N', b'1', 0x20, 0x7E, // data and non-zero padding
        ];
        let (p, used) = Parameter::parse(&bytes).unwrap();
        assert_eq!((p.value, used), (Value::string("N1"), 16));
    }

    #[test]
    fn overflowing_fields_are_refused_on_emit() {
        let long = Parameter::new(idents::NOTE, Value::String(vec![b'x'; 4096]));
        assert_eq!(
            long.emit(&mut Vec::new()),
            Err(Error::DataTooLong { len: 4096 })
        );
        let big = Parameter::new(Ident(0x10_0000), Value::Uint(0));
        let mut out = Vec::new();
        assert_eq!(big.emit(&mut out), Err(Error::IdentTooLarge(0x10_0000)));
        assert!(out.is_empty(), "a failed emit appends nothing");
        let max = Parameter::new(idents::NOTE, Value::String(vec![b'x'; 4095]));
        assert!(max.emit(&mut out).is_ok());
        assert_eq!(out.len(), 12 + 4096);
    }

    #[test]
    fn short_and_truncated_parameters() {
        assert_eq!(
            Parameter::parse(&FREQUENCY[..11]),
            Err(Error::ShortParamHeader {
                offset: 0,
                available: 11
            })
        );
        assert_eq!(
            Parameter::parse(&FREQUENCY[..14]),
            Err(Error::ParamPastEnd {
                offset: 0,
                len: 4,
                padded: 4,
                available: 2
            })
        );
    }

    #[test]
    fn unknown_format_frames_fine_but_does_not_decode() {
        let mut b = FREQUENCY;
        b[8] = 6;
        let view = Params::new(&b, 0).next().unwrap().unwrap();
        assert_eq!(view.data, &FREQUENCY[12..]);
        assert_eq!(view.value(), Err(Error::UnknownFormat(6)));
        assert_eq!(Parameter::parse(&b), Err(Error::UnknownFormat(6)));
    }

    prop_compose! {
        pub(crate) fn parameter()(
            unit in any::<u16>(), subunit in any::<u16>(), ident in 0..=MAX_IDENT,
            conf in any::<u8>(), exp in any::<u8>(), pflags in any::<u8>(),
            value in strategies::value(),
        ) -> Parameter {
            Parameter {
                unit, subunit, ident: Ident(ident), confidence: conf.into(),
                expire: Expire(exp), pflags, value,
            }
        }
    }

    proptest! {
        #[test]
        fn parameters_round_trip(p in parameter()) {
            let mut out = Vec::new();
            p.emit(&mut out).unwrap();
            prop_assert_eq!(out.len(), p.wire_len());
            prop_assert_eq!(out.len() % 4, 0);
            prop_assert_eq!(Parameter::parse(&out), Ok((p, out.len())));
        }

        #[test]
        fn arbitrary_bytes_never_panic(b in proptest::collection::vec(any::<u8>(), 0..64)) {
            let _ = Parameter::parse(&b);
            for v in Params::new(&b, 0).flatten() {
                let _ = v.to_parameter();
            }
        }
    }
}

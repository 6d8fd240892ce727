//! The 12-byte XFSp message header (§3.1, icd-reading X1), network byte order:
//!
//! ```text
//!  0               1               2               3
//! +---------------+---------------+---------------+---------------+
//! |            src id             |        message number         |
//! +---------------+---------------+---------------+---------------+
//! |   msg class   |  message ID   |             flags             |
//! +---------------+---------------+---------------+---------------+
//! |             tcid              |              len              |
//! +---------------+---------------+---------------+---------------+
//! ```

pub use super::dict::{CertLevel, MsgClass, MsgOp, Tcid};
use super::{cursor::Reader, error::Error};

/// Size of the message header in bytes (§3.1, icd-reading X1).
pub const HEADER_LEN: usize = 12;

/// The message header as it is on the wire (§3.1, Figure 1), `len` included as received.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Header {
    /// §3.1 `src id`: the sender's locally configured source id, unique on the network.
    pub src_id: u16,
    /// §3.1 `message number`: monotonically increasing per source (compared as in icd-reading
    /// X7).
    pub msg_num: u16,
    /// §3.1 `msg class` (Table 1).
    pub class: MsgClass,
    /// §3.1 `message ID` (Table 2, msg-op).
    pub op: MsgOp,
    /// Table 3 (msg-flag-cert) applies to the whole 16-bit field; see [`Header::cert`].
    pub flags: u16,
    /// §3.1 `tcid`: transcoder id (Table 4).
    pub tcid: Tcid,
    /// Bytes after the header (icd-reading X3). A parsed header keeps what the sender
    /// wrote; whether it fits the datagram is checked by the message parser.
    pub len: u16,
}

impl Header {
    /// Parses the first 12 bytes. Does not look at what follows.
    pub fn parse(buf: &[u8]) -> Result<Header, Error> {
        let short = Error::ShortHeader { len: buf.len() };
        let mut r = Reader::new(buf);
        let mut field = || r.u16().ok_or(short);
        let src_id = field()?;
        let msg_num = field()?;
        let class_op = field()?;
        let flags = field()?;
        let tcid = field()?;
        let len = field()?;
        let [class, op] = class_op.to_be_bytes();
        Ok(Header {
            src_id,
            msg_num,
            class: class.into(),
            op: op.into(),
            flags,
            tcid: tcid.into(),
            len,
        })
    }

    /// The header's 12 bytes.
    pub fn to_bytes(&self) -> [u8; HEADER_LEN] {
        let mut b = [0u8; HEADER_LEN];
        let fields = [
            self.src_id,
            self.msg_num,
            u16::from_be_bytes([self.class.into(), self.op.into()]),
            self.flags,
            self.tcid.into(),
            self.len,
        ];
        for (dst, f) in b.chunks_exact_mut(2).zip(fields) {
            dst.copy_from_slice(&f.to_be_bytes());
        }
        b
    }

    /// Appends the header's 12 bytes.
    pub fn emit(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_bytes());
    }

    /// The certification level. Table 3's values fit three bits, the same three bits
    /// that `pflags` uses for it, so the higher bits are left for other flags.
    pub fn cert(&self) -> CertLevel {
        CertLevel::from((self.flags & 0x7) as u8)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// §5.1.1 written out by hand: src 1001 = 0x03E9, number 20 = 0x0014, OP 3,
    /// FLIGHTDATA 2, flags LEVEL-A 5, tcid NONE 0, len 0x28.
    const EXAMPLE: [u8; 12] = [
        0x03, 0xE9, 0x00, 0x14, 0x03, 0x02, 0x00, 0x05, 0x00, 0x00, 0x00, 0x28,
    ];

    #[test]
    fn section_5_1_1_header_both_ways() {
        let h = Header::parse(&EXAMPLE).unwrap();
        assert_eq!(
            h,
            Header {
                src_id: 1001,
                msg_num: 20,
                class: MsgClass::Op,
                op: MsgOp::FlightData,
                flags: 5,
                tcid: Tcid::None,
                len: 0x28,
            }
        );
        assert_eq!(h.cert(), CertLevel::LevelA);
        assert_eq!(h.to_bytes(), EXAMPLE);
    }

    #[test]
    fn short_header_says_how_short() {
        for n in 0..HEADER_LEN {
            assert_eq!(
                Header::parse(&EXAMPLE[..n]),
                Err(Error::ShortHeader { len: n })
            );
        }
    }

    #[test]
    fn unknown_class_and_op_survive() {
        let mut b = EXAMPLE;
        b[4] = 0x77;
        b[5] = 0xEE;
        let h = Header::parse(&b).unwrap();
        assert_eq!(h.class, MsgClass::Unknown(0x77));
        assert_eq!(h.op, MsgOp::Unknown(0xEE));
        assert_eq!(h.to_bytes(), b);
    }

    proptest! {
        #[test]
        fn any_12_bytes_round_trip(b in any::<[u8; 12]>()) {
            let h = Header::parse(&b).unwrap();
            prop_assert_eq!(h.to_bytes(), b);
        }
    }
}

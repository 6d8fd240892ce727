//! A whole XFSp datagram: the message header and its body.
//!
//! MAINT and OP messages carry parameters; RAW messages carry opaque bytes. A class
//! the draft does not define is treated as RAW, since nothing says how to frame it.
//!
//! Header `len` (icd-reading X3): we send the number of bytes after the header. On
//! receipt the datagram's real size is what counts: the whole rest of the datagram is
//! the body, and a `len` that runs past the end is malformed. (The draft's own §5.1
//! example says 0x28 for 32 bytes of parameters; by this reading it is malformed, and a
//! test below says so.)

use super::dict::{CertLevel, MsgClass, MsgOp, Tcid};
use super::error::Error;
use super::header::{HEADER_LEN, Header};
use super::param::{ParamView, Parameter, Params};

/// A datagram checked for framing (§3.1, §3.2) and read in place (no allocation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MessageView<'a> {
    header: Header,
    body: &'a [u8],
}

impl<'a> MessageView<'a> {
    /// Checks the header, `len` against the datagram size, and (for MAINT/OP) that
    /// every parameter is whole (padding is skipped unread). Parameter *values* are not decoded,
    /// so a parameter of an unknown format does not make the datagram malformed.
    pub fn parse(datagram: &'a [u8]) -> Result<MessageView<'a>, Error> {
        let header = Header::parse(datagram)?;
        let body = datagram.get(HEADER_LEN..).unwrap_or_default();
        if usize::from(header.len) > body.len() {
            return Err(Error::LenPastEnd {
                declared: header.len,
                available: body.len(),
            });
        }
        let view = MessageView { header, body };
        if view.has_params() {
            for p in Params::new(body, HEADER_LEN) {
                p?;
            }
        }
        Ok(view)
    }

    /// The message header (§3.1), `len` as received.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// Everything after the header.
    pub fn body(&self) -> &'a [u8] {
        self.body
    }

    /// Whether the body is a parameter list (MAINT or OP) rather than raw data.
    pub fn has_params(&self) -> bool {
        carries_params(self.header.class)
    }

    /// The parameters, in order; empty for RAW. Framing was checked by `parse`.
    pub fn params(&self) -> impl Iterator<Item = ParamView<'a>> + use<'a> {
        let body = if self.has_params() { self.body } else { &[] };
        Params::new(body, HEADER_LEN).map_while(Result::ok)
    }

    /// The owned, fully decoded message. Fails on the first parameter whose value
    /// does not decode (e.g. an unknown format).
    pub fn to_message(&self) -> Result<Message, Error> {
        let h = &self.header;
        let body = if self.has_params() {
            Body::Params(
                self.params()
                    .map(|p| p.to_parameter())
                    .collect::<Result<_, _>>()?,
            )
        } else {
            Body::Raw(self.body.to_vec())
        };
        Ok(Message {
            src_id: h.src_id,
            msg_num: h.msg_num,
            class: h.class,
            op: h.op,
            flags: h.flags,
            tcid: h.tcid,
            body,
        })
    }
}

fn carries_params(class: MsgClass) -> bool {
    matches!(class, MsgClass::Maint | MsgClass::Op)
}

/// What follows the header (§3.1 `data`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Body {
    /// Parameters (§3.2), for the MAINT and OP classes.
    Params(Vec<Parameter>),
    /// Raw octets (§2: 1553, CANbus, samples or serial data), for the other classes.
    Raw(Vec<u8>),
}

/// A whole message (§3.1), owned and typed. `len` is not stored: it is computed on emit.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Message {
    /// §3.1 `src id`: the sender's source id, unique on the network.
    pub src_id: u16,
    /// §3.1 `message number`: monotonically increasing per source.
    pub msg_num: u16,
    /// §3.1 `msg class` (Table 1).
    pub class: MsgClass,
    /// §3.1 `message ID` (Table 2, msg-op).
    pub op: MsgOp,
    /// §3.1 `flags`; the bottom three bits are the certification level (Table 3).
    pub flags: u16,
    /// §3.1 `tcid`: transcoder id (Table 4).
    pub tcid: Tcid,
    /// The parameters or raw data after the header.
    pub body: Body,
}

impl Message {
    /// An OP/FLIGHTDATA message at the given certification level.
    pub fn flight_data(
        src_id: u16,
        msg_num: u16,
        cert: CertLevel,
        params: Vec<Parameter>,
    ) -> Message {
        Message {
            src_id,
            msg_num,
            class: MsgClass::Op,
            op: MsgOp::FlightData,
            flags: u16::from(u8::from(cert)),
            tcid: Tcid::None,
            body: Body::Params(params),
        }
    }

    /// Parses and decodes a whole datagram (see [`MessageView::parse`]).
    pub fn parse(datagram: &[u8]) -> Result<Message, Error> {
        MessageView::parse(datagram)?.to_message()
    }

    /// Bytes after the header.
    pub fn body_len(&self) -> usize {
        match &self.body {
            Body::Params(ps) => ps.iter().map(Parameter::wire_len).sum(),
            Body::Raw(r) => r.len(),
        }
    }

    /// The header this message is sent with.
    pub fn header(&self) -> Result<Header, Error> {
        let len = self.body_len();
        Ok(Header {
            src_id: self.src_id,
            msg_num: self.msg_num,
            class: self.class,
            op: self.op,
            flags: self.flags,
            tcid: self.tcid,
            len: u16::try_from(len).map_err(|_| Error::BodyTooLong { len })?,
        })
    }

    /// Appends the datagram. On error `out` is left as it was.
    pub fn emit_into(&self, out: &mut Vec<u8>) -> Result<(), Error> {
        let header = self.header()?;
        let start = out.len();
        out.reserve(HEADER_LEN + usize::from(header.len));
        header.emit(out);
        let result = match &self.body {
            Body::Params(ps) => ps.iter().try_for_each(|p| p.emit(out)),
            Body::Raw(r) => {
                out.extend_from_slice(r);
                Ok(())
            }
        };
        if result.is_err() {
            out.truncate(start);
        }
        result
    }

    /// The datagram.
    pub fn emit(&self) -> Result<Vec<u8>, Error> {
        let mut out = Vec::new();
        self.emit_into(&mut out)?;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dict::Confidence;
    use crate::format::{FormatId, Value};
    use crate::idents;
    use crate::param::tests::parameter;
    use proptest::prelude::*;

    /// §5.1 written out by hand from Figures 4-6, except `len`: 0x20 (32 bytes of
    /// parameters follow) where the draft prints 0x28 (icd-reading X3).
    const RADIO: [u8; 44] = [
        0x03, 0xE9, 0x00, 0x14, 0x03, 0x02, 0x00, 0x05, 0x00, 0x00, 0x00, 0x20, // header
        0x00, 0x02, 0x00, 0x00, 0x00, 0x40, 0x00, 0x24, 0x02, 0x80, 0xFF, 0x05, // COMFREQKHZ
        0x00, 0x01, 0xDF, 0x7E, // 122750
        0x00, 0x02, 0x00, 0x00, 0x00, 0x40, 0x00, 0x28, 0x02, 0x80, 0xFF, 0x05, // COMSQL
        0x00, 0x00, 0x00, 0x35, // 53
    ];

    fn radio_message() -> Message {
        let p = |ident, v| {
            Parameter::new(ident, Value::Uint(v))
                .unit(2)
                .confidence(Confidence::UserSel)
                .cert(CertLevel::LevelA)
        };
        Message::flight_data(
            1001,
            20,
            CertLevel::LevelA,
            vec![p(idents::COMFREQKHZ, 122_750), p(idents::COMSQL, 53)],
        )
    }

    #[test]
    fn section_5_1_datagram_both_ways() {
        assert_eq!(radio_message().emit().unwrap(), RADIO);
        assert_eq!(Message::parse(&RADIO), Ok(radio_message()));
        let view = MessageView::parse(&RADIO).unwrap();
        let idents: Vec<_> = view.params().map(|p| p.header.ident).collect();
        assert_eq!(idents, [idents::COMFREQKHZ, idents::COMSQL]);
    }

    #[test]
    fn the_drafts_own_len_0x28_runs_past_the_datagram() {
        let mut as_printed = RADIO;
        as_printed[11] = 0x28;
        assert_eq!(
            Message::parse(&as_printed),
            Err(Error::LenPastEnd {
                declared: 0x28,
                available: 32
            })
        );
    }

    #[test]
    fn a_short_len_is_trusted_less_than_the_datagram() {
        let mut b = RADIO;
        b[11] = 0x10;
        assert_eq!(
            Message::parse(&b),
            Ok(radio_message()),
            "both parameters still read"
        );
    }

    #[test]
    fn a_datagram_with_non_zero_padding_is_read_whole() {
        // Written from draft §3.1/§3.2: source 1001, message 20, class FLIGHTDATA (3),
        // id 2, flags 0x0005, tcid 0, len 32; TAILNUM "N1" (STRING, 2 bytes) padded
        // with 0xAA 0x55, then COMSQL 53 as in `RADIO`.
        let bytes: [u8; 44] = [
            0x03, 0xE9, 0x00, 0x14, 0x03, 0x02, 0x00, 0x05, 0x00, 0x00, 0x00, 0x20, // header
            0x00, 0x00, 0x00, 0x00, 0x00, 0x20, 0x00, 0x92, 0x04, 0x00, 0xFF, 0x00, // TAILNUM
            b'N', b'1', 0xAA, 0x55, // "N1" and padding that is not zero
            0x00, 0x02, 0x00, 0x00, 0x00, 0x40, 0x00, 0x28, 0x02, 0x80, 0xFF, 0x05, // COMSQL
            0x00, 0x00, 0x00, 0x35, // 53
        ];
        let Body::Params(params) = Message::parse(&bytes).unwrap().body else {
            panic!("FLIGHTDATA carries parameters");
        };
        let values: Vec<_> = params.into_iter().map(|p| (p.ident, p.value)).collect();
        assert_eq!(
            values,
            vec![
                (idents::TAILNUM, Value::string("N1")),
                (idents::COMSQL, Value::Uint(53))
            ]
        );
    }

    #[test]
    fn malformed_datagrams_each_get_their_own_error() {
        assert_eq!(
            Message::parse(&RADIO[..5]),
            Err(Error::ShortHeader { len: 5 })
        );
        // Cut inside the second parameter's header (len adjusted so it is not the cause).
        let mut cut = RADIO[..34].to_vec();
        cut[11] = 22;
        assert_eq!(
            Message::parse(&cut),
            Err(Error::ShortParamHeader {
                offset: 28,
                available: 6
            })
        );
        // Data length 256 where only 20 bytes follow.
        let mut long = RADIO;
        long[16] = 0x10;
        long[17] = 0x00;
        assert_eq!(
            Message::parse(&long),
            Err(Error::ParamPastEnd {
                offset: 12,
                len: 256,
                padded: 256,
                available: 20
            })
        );
        // Data length 3 for a UINT: its last byte (0x7E) is padding now, skipped
        // unread (draft §3.2), and the UINT is the wrong length.
        let mut pad = RADIO;
        pad[17] = 0x30;
        assert!(MessageView::parse(&pad).is_ok(), "framing is fine");
        assert!(matches!(Message::parse(&pad), Err(Error::BadLength { .. })));
        // Unknown format 6: framing is fine, decoding is not.
        let mut fmt = RADIO;
        fmt[20] = 6;
        assert!(MessageView::parse(&fmt).is_ok());
        assert_eq!(Message::parse(&fmt), Err(Error::UnknownFormat(6)));
        // A UINT whose data length is 8 (with 8 bytes present) is the wrong length.
        let mut wrong = RADIO[..28].to_vec();
        wrong[11] = 20;
        wrong[17] = 0x80;
        wrong.extend_from_slice(&[0, 0, 0, 0]);
        assert_eq!(
            Message::parse(&wrong),
            Err(Error::BadLength {
                format: FormatId::Uint,
                len: 8,
                need: crate::error::LengthRule::Exactly(4)
            })
        );
    }

    #[test]
    fn raw_and_unknown_classes_keep_their_bytes() {
        let mut b = RADIO.to_vec();
        b[4] = 4;
        b.push(0xAA); // raw data need not be a multiple of 4
        let m = Message::parse(&b).unwrap();
        assert_eq!(m.class, MsgClass::Raw);
        assert_eq!(m.body, Body::Raw(b[12..].to_vec()));
        b[11] = 33;
        assert_eq!(m.emit().unwrap(), b);
        b[4] = 9;
        assert_eq!(Message::parse(&b).unwrap().class, MsgClass::Unknown(9));
    }

    #[test]
    fn emit_errors_leave_the_buffer_alone() {
        let mut m = radio_message();
        m.body = Body::Params(vec![Parameter::new(
            idents::NOTE,
            Value::String(vec![0; 5000]),
        )]);
        let mut out = vec![1, 2, 3];
        assert_eq!(m.emit_into(&mut out), Err(Error::DataTooLong { len: 5000 }));
        assert_eq!(out, [1, 2, 3]);
        m.body = Body::Raw(vec![0; 70_000]);
        assert_eq!(m.emit(), Err(Error::BodyTooLong { len: 70_000 }));
    }

    prop_compose! {
        fn message()(
            src in any::<u16>(), num in any::<u16>(), op in any::<u8>(), flags in any::<u16>(),
            tcid in any::<u16>(), maint in any::<bool>(),
            params in proptest::collection::vec(parameter(), 0..6),
        ) -> Message {
            Message {
                src_id: src, msg_num: num,
                class: if maint { MsgClass::Maint } else { MsgClass::Op },
                op: op.into(), flags, tcid: tcid.into(), body: Body::Params(params),
            }
        }
    }

    proptest! {
        #[test]
        fn messages_round_trip(m in message()) {
            let b = m.emit().unwrap();
            prop_assert_eq!(b.len(), HEADER_LEN + m.body_len());
            prop_assert_eq!(usize::from(Header::parse(&b).unwrap().len), m.body_len());
            prop_assert_eq!(Message::parse(&b), Ok(m));
        }

        #[test]
        fn arbitrary_bytes_never_panic(b in proptest::collection::vec(any::<u8>(), 0..300)) {
            if let Ok(v) = MessageView::parse(&b) {
                for p in v.params() {
                    let _ = p.value();
                }
                let _ = v.to_message();
            }
        }

        #[test]
        fn mutated_valid_datagrams_never_panic(
            m in message(), flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8),
        ) {
            let mut b = m.emit().unwrap();
            for (i, x) in flips {
                let n = b.len();
                b[i % n] ^= x;
            }
            let _ = Message::parse(&b);
        }
    }
}

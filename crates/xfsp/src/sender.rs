//! §4.1 composition: parameters with the same class, message id and flags are
//! coalesced into as few datagrams as fit, each with the next message number.
//!
//! The budget is for parameter bytes (after the 12-byte header): 1460 on IPv4, 1440 on
//! IPv6 (§2, icd-reading X9), so a datagram never needs IP fragmentation. Numbers start
//! wherever the caller says ("an arbitrary initial value") and wrap modulo 65536, which
//! receivers handle with serial-number arithmetic.

use super::dict::{CertLevel, MsgClass, MsgOp, Tcid};
use super::error::Error;
use super::header::{HEADER_LEN, Header};
use super::param::Parameter;

/// Parameter bytes per datagram on IPv4: 1500 − 20 (IP) − 8 (UDP) − 12 (XFSp header).
pub const MAX_PARAM_BYTES_V4: usize = 1460;
/// The same on IPv6 (40-byte IP header).
pub const MAX_PARAM_BYTES_V6: usize = 1440;

/// The §3.1 header fields shared by every datagram of one batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MsgKind {
    /// §3.1 `msg class` (Table 1).
    pub class: MsgClass,
    /// §3.1 `message ID` (Table 2, msg-op).
    pub op: MsgOp,
    /// §3.1 `flags`; the bottom three bits are the certification level (Table 3).
    pub flags: u16,
    /// §3.1 `tcid`: transcoder id (Table 4).
    pub tcid: Tcid,
}

impl MsgKind {
    /// OP / FLIGHTDATA at a certification level: what the gateway publishes.
    pub fn flight_data(cert: CertLevel) -> MsgKind {
        MsgKind {
            class: MsgClass::Op,
            op: MsgOp::FlightData,
            flags: u16::from(u8::from(cert)),
            tcid: Tcid::None,
        }
    }
}

/// Numbers and packs outgoing messages for one source id (§4.1).
#[derive(Debug, Clone)]
pub struct Sender {
    src_id: u16,
    next_num: u16,
    budget: usize,
}

impl Sender {
    /// A sender for `src_id` whose first message will carry `first_num`.
    pub fn new(src_id: u16, first_num: u16) -> Sender {
        Sender {
            src_id,
            next_num: first_num,
            budget: MAX_PARAM_BYTES_V4,
        }
    }

    /// Uses a different parameter-byte budget per datagram (e.g. [`MAX_PARAM_BYTES_V6`]).
    pub fn with_budget(mut self, budget: usize) -> Sender {
        self.budget = budget;
        self
    }

    /// The §3.1 `src id` this sender writes.
    pub fn src_id(&self) -> u16 {
        self.src_id
    }

    /// The number the next datagram will carry.
    pub fn next_num(&self) -> u16 {
        self.next_num
    }

    /// Packs `params`, in order, into datagrams of at most the budget of parameter
    /// bytes each, numbering them consecutively. Nothing is numbered if any parameter
    /// fails to encode or alone exceeds the budget.
    pub fn pack(&mut self, kind: MsgKind, params: &[Parameter]) -> Result<Vec<Vec<u8>>, Error> {
        let mut bodies: Vec<Vec<u8>> = Vec::new();
        let mut body = Vec::with_capacity(self.budget);
        for p in params {
            let size = p.wire_len();
            if size > self.budget {
                return Err(Error::ParamTooLarge {
                    size,
                    limit: self.budget,
                });
            }
            if body.len() + size > self.budget {
                bodies.push(std::mem::replace(
                    &mut body,
                    Vec::with_capacity(self.budget),
                ));
            }
            p.emit(&mut body)?;
        }
        if !body.is_empty() {
            bodies.push(body);
        }
        let mut out = Vec::with_capacity(bodies.len());
        for body in bodies {
            let len =
                u16::try_from(body.len()).map_err(|_| Error::BodyTooLong { len: body.len() })?;
            let header = Header {
                src_id: self.src_id,
                msg_num: self.next_num.wrapping_add(out.len() as u16),
                class: kind.class,
                op: kind.op,
                flags: kind.flags,
                tcid: kind.tcid,
                len,
            };
            let mut d = Vec::with_capacity(HEADER_LEN + body.len());
            header.emit(&mut d);
            d.extend_from_slice(&body);
            out.push(d);
        }
        self.next_num = self.next_num.wrapping_add(out.len() as u16);
        Ok(out)
    }

    /// One RAW datagram carrying `data` as is.
    pub fn raw(&mut self, op: MsgOp, flags: u16, data: &[u8]) -> Result<Vec<u8>, Error> {
        let len = u16::try_from(data.len()).map_err(|_| Error::BodyTooLong { len: data.len() })?;
        let header = Header {
            src_id: self.src_id,
            msg_num: self.next_num,
            class: MsgClass::Raw,
            op,
            flags,
            tcid: Tcid::None,
            len,
        };
        let mut d = Vec::with_capacity(HEADER_LEN + data.len());
        header.emit(&mut d);
        d.extend_from_slice(data);
        self.next_num = self.next_num.wrapping_add(1);
        Ok(d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{Bus, Value};
    use crate::idents;
    use crate::message::{Body, Message};
    use crate::param::tests::parameter;
    use crate::receiver::{Receiver, Verdict};
    use proptest::prelude::*;

    fn sint(v: i32) -> Parameter {
        Parameter::new(idents::FLAPPOS, Value::Sint(v))
    }

    #[test]
    fn ninety_one_sixteen_byte_parameters_fill_exactly_1456() {
        // 1460 / 16 = 91.25: 91 parameters (1456 bytes) fit, the 92nd starts a new one.
        let mut s = Sender::new(0x5650, 10);
        let ps: Vec<_> = (0..92).map(sint).collect();
        let d = s
            .pack(MsgKind::flight_data(CertLevel::Experimental), &ps)
            .unwrap();
        assert_eq!(d.len(), 2);
        assert_eq!(d[0].len(), HEADER_LEN + 1456);
        assert_eq!(d[1].len(), HEADER_LEN + 16);
        assert_eq!(s.next_num(), 12);
        let m0 = Message::parse(&d[0]).unwrap();
        let m1 = Message::parse(&d[1]).unwrap();
        assert_eq!((m0.msg_num, m1.msg_num), (10, 11));
        let Body::Params(p1) = m1.body else {
            panic!("params")
        };
        assert_eq!(p1, [sint(91)], "order kept across datagrams");
    }

    #[test]
    fn an_exact_fit_of_1460_stays_in_one_datagram() {
        // 73 parameters of 20 bytes (12 header + "N12345" padded to 8) = 1460 exactly.
        let p = Parameter::new(idents::TAILNUM, Value::string("N12345"));
        assert_eq!(p.wire_len(), 20);
        let mut s = Sender::new(1, 0);
        let d = s
            .pack(MsgKind::flight_data(CertLevel::LevelE), &vec![p; 73])
            .unwrap();
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].len(), HEADER_LEN + MAX_PARAM_BYTES_V4);
    }

    #[test]
    fn numbers_wrap_and_receivers_accept_them_in_order() {
        let mut s = Sender::new(5, 65534);
        let mut r = Receiver::default();
        for _ in 0..4 {
            let d = s
                .pack(MsgKind::flight_data(CertLevel::LevelC), &[sint(0)])
                .unwrap();
            let h = crate::header::Header::parse(&d[0]).unwrap();
            assert_eq!(
                r.check(h.src_id, h.msg_num, std::time::Instant::now()),
                Verdict::Fresh
            );
        }
        assert_eq!(s.next_num(), 2);
    }

    #[test]
    fn an_oversized_parameter_is_refused_and_burns_no_number() {
        let mut s = Sender::new(1, 100);
        let big = Parameter::new(idents::NOTE, Value::String(vec![b'x'; 1449]));
        assert_eq!(big.wire_len(), 1464);
        assert_eq!(
            s.pack(MsgKind::flight_data(CertLevel::LevelE), &[sint(1), big]),
            Err(Error::ParamTooLarge {
                size: 1464,
                limit: 1460
            })
        );
        assert_eq!(s.next_num(), 100);
        let mut v6 = Sender::new(1, 0).with_budget(MAX_PARAM_BYTES_V6);
        let p = Parameter::new(idents::BUSSTAT, Value::Bus(Bus::default()));
        let d = v6
            .pack(MsgKind::flight_data(CertLevel::LevelE), &vec![p; 100])
            .unwrap();
        assert!(d.iter().all(|d| d.len() - HEADER_LEN <= MAX_PARAM_BYTES_V6));
    }

    #[test]
    fn raw_datagrams_take_a_number_too() {
        let mut s = Sender::new(1, 7);
        let d = s.raw(MsgOp::Gdl90, 0, &[1, 2, 3]).unwrap();
        let m = Message::parse(&d).unwrap();
        assert_eq!(
            (m.msg_num, m.class, m.body),
            (7, MsgClass::Raw, Body::Raw(vec![1, 2, 3]))
        );
        assert_eq!(s.next_num(), 8);
    }

    proptest! {
        #[test]
        fn coalescing_never_exceeds_1460_and_loses_nothing(
            ps in proptest::collection::vec(parameter(), 0..120)
                .prop_filter("each fits alone", |ps| ps.iter().all(|p| p.wire_len() <= 1460)),
            first in any::<u16>(),
        ) {
            let mut s = Sender::new(9, first);
            let ds = s.pack(MsgKind::flight_data(CertLevel::LevelB), &ps).unwrap();
            let mut back = Vec::new();
            for (i, d) in ds.iter().enumerate() {
                prop_assert!(d.len() - HEADER_LEN <= MAX_PARAM_BYTES_V4, "{} bytes", d.len());
                let m = Message::parse(d).unwrap();
                prop_assert_eq!(m.msg_num, first.wrapping_add(i as u16));
                let Body::Params(p) = m.body else { panic!("params") };
                prop_assert!(!p.is_empty());
                back.extend(p);
            }
            prop_assert_eq!(back, ps);
        }
    }
}

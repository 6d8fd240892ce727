//! XFSp, the eXtensible Flight System Protocol (draft-guy-xfsp-00): the wire codec.
//!
//! This module turns datagrams into typed values and back, and nothing else: no
//! sockets, no clocks (the gateway owns those). Modelled on smoltcp's `wire` module:
//! each layer has a typed representation with `parse` and `emit`; parsing never panics
//! on any input and says what was wrong through [`Error`].
//!
//! Layers, outside in:
//! - [`message`]: a datagram = 12-byte [`header`] + parameters (or raw bytes);
//!   [`MessageView`] reads in place, [`Message`] is the owned form.
//! - [`param`]: 12-byte parameter header + data padded with zeros to 4 bytes.
//! - [`format`](mod@format): the §3.3 attribute formats as [`Value`]; [`dict`]: the dictionaries.
//! - [`idents`]: the §3.4 parameter table; [`expire`]: the Expire octet.
//! - [`receiver`] (§4.4 ordering/duplicates) and [`sender`] (§4.1 numbering and
//!   coalescing) hold the little state the protocol needs.
//!
//! Readings taken where the draft is silent or contradicts itself (see
//! `shared/spec/READING-NOTES.md`; each has a test):
//! - Header `len` is the number of bytes after the header when sending; on receipt the
//!   datagram's own size is trusted, and a `len` running past it is malformed. The
//!   draft's §5.1 example (len 0x28 for 32 bytes) is therefore malformed (note 3).
//! - Expire: M = upper 5 bits, E = lower 3, 3·(M+1)·10^(E+1) ms, 0xFF never (note 4).
//! - Ident typos: MUX = 0x29, APPSTAT = 0x81; AOA (SINT) and AOAR (RANGE) share 0x77
//!   and are told apart by format (note 5).
//! - BUS: state, ecbflags, eleven i16, label (note 6); volts and amps in **tenths**.
//! - Message numbers compare in RFC 1982 serial arithmetic (note 7).
//! - Field sizes the tables leave implicit come from each format's stated length (see
//!   [`format`](mod@format)); `starray` (RANGE ticks, WBRANGE slices) is undefined and kept opaque.
//! - Certification level: the low three bits of both the header `flags` and `pflags`.
//! - Classes other than MAINT and OP are carried as raw bytes.

#![cfg_attr(
    not(test),
    deny(
        clippy::indexing_slicing,
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic
    )
)]
#![warn(missing_docs)]

mod cursor;
pub mod dict;
pub mod error;
pub mod expire;
pub mod format;
pub mod header;
pub mod idents;
pub mod message;
pub mod param;
pub mod receiver;
pub mod sender;

pub use dict::{
    Boolean, CasFlags, CasLevel, CertLevel, Confidence, EcbFlags, EcbState, MsgClass, MsgOp, Tcid,
    Units,
};
pub use error::{Error, LengthRule};
pub use expire::Expire;
pub use format::{BUS_SCALE, Bus, CasMsg, FormatId, Value};
pub use header::{HEADER_LEN, Header};
pub use idents::{Ident, IdentInfo};
pub use message::{Body, Message, MessageView};
pub use param::{ParamHeader, ParamView, Parameter};
pub use receiver::{Received, Receiver, RxStats, Verdict, serial_newer};
pub use sender::{MAX_PARAM_BYTES_V4, MAX_PARAM_BYTES_V6, MsgKind, Sender};

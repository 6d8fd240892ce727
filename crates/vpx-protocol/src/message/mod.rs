//! Typed messages of ICD Appendix D, one type per message, grouped as in §6.
//!
//! Every type implements [`Payload`]: `parse` checks the payload length against the
//! ICD and never panics; `emit` writes the payload. [`Message`] is the sum of them all
//! and [`Packet`] is a message with its frame header.

/// A message whose whole payload is one device id byte: the struct (its doc, then its
/// byte's doc) and its [`Payload`]. DEVICE_SPEC_QUERY, DEVICE_NAME_QUERY and
/// DEVICE_CLEAR are laid out alike; their ids, names and meanings stay with each.
macro_rules! device_id_message {
    (
        $(#[$doc:meta])*
        $name:ident = $major:literal / $minor:literal $icd:literal {
            $(#[$field_doc:meta])*
            device_id
        }
    ) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub struct $name {
            $(#[$field_doc])*
            pub device_id: u8,
        }

        impl $crate::message::Payload for $name {
            const ID: $crate::frame::MessageId = $crate::frame::MessageId::new($major, $minor);
            const NAME: &'static str = $icd;
            const LEN: $crate::error::LenRule = $crate::error::LenRule::Exact(1);
            fn parse_payload(p: &[u8]) -> $crate::error::Result<Self> {
                let [device_id] = $crate::message::exact::<Self, 1>(p)?;
                Ok($name { device_id })
            }
            fn emit_payload(&self, w: &mut $crate::message::Writer) {
                w.u8(self.device_id);
            }
        }
    };
}

mod data;
mod device;
mod fault;
mod power;
mod status;
mod system;
pub mod types;

pub use data::{ExternalData, ExternalValidity};
pub use device::{
    DeviceEnable, DeviceName, DeviceNameQuery, DeviceSpec, DeviceSpecQuery, FlapSpec, SpecAck,
    SystemSpec, TrimSpec, WigWagSpec,
};
pub use fault::DeviceClear;
pub use power::{DevicePower, FlapMove, TrimMove, WigWagMode};
pub use status::{
    Axis, AxisStatus, DeviceStatus, DeviceStatusQuery, FaultStatus, FlapFlags, FlapTrimStatus,
    MiscFlags, SwitchInputs, SystemFaultFlags, SystemStatus, TrimFlags,
};
pub use system::{EepromErase, Ping, SoftwareUpdate, Version};
pub use types::*;

use alloc::vec::Vec;

use super::error::{Error, LenRule, Result};
use super::frame::{
    FrameHeader, FrameRef, HEADER_LEN, MAX_FRAME, MAX_PAYLOAD, MessageId, Node, emit_frame,
};

/// One message type of the ICD: its id, name, payload length rule, and codec.
pub trait Payload: Sized {
    /// Major and minor id (ICD Table 42).
    const ID: MessageId;
    /// The ICD's name, e.g. `DEVICE_STATUS`.
    const NAME: &'static str;
    /// The payload length the message's ICD table allows.
    const LEN: LenRule;

    /// Decodes a payload whose length `LEN` allows. Called through [`Payload::parse`].
    fn parse_payload(payload: &[u8]) -> Result<Self>;
    /// Writes the payload, big-endian (ICD §3.2.1).
    fn emit_payload(&self, w: &mut Writer);

    /// Checks the length, then decodes. Never panics.
    fn parse(payload: &[u8]) -> Result<Self> {
        if !Self::LEN.allows(payload.len()) {
            return Err(Error::BadLength {
                message: Self::NAME,
                expected: Self::LEN,
                got: payload.len(),
            });
        }
        Self::parse_payload(payload)
    }

    /// The payload bytes.
    fn emit(&self) -> PayloadBuf {
        let mut w = Writer::new();
        self.emit_payload(&mut w);
        w.finish()
    }
}

/// The payload of a message whose `LEN` is `Exact(N)`, as an array its fields are
/// read from. [`Payload::parse`] has checked the length already; this checks it again,
/// with the same error, rather than trust an index.
fn exact<P: Payload, const N: usize>(p: &[u8]) -> Result<[u8; N]> {
    p.try_into().map_err(|_| Error::BadLength {
        message: P::NAME,
        expected: P::LEN,
        got: p.len(),
    })
}

/// A payload on the stack: no message is longer than 255 bytes (ICD Table 1, `<len>`).
#[derive(Clone, Copy)]
pub struct PayloadBuf {
    buf: [u8; MAX_PAYLOAD],
    len: usize,
}

impl PayloadBuf {
    /// The payload bytes.
    pub fn as_slice(&self) -> &[u8] {
        self.buf.get(..self.len).unwrap_or_default()
    }
}

impl core::ops::Deref for PayloadBuf {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        self.as_slice()
    }
}

impl core::fmt::Debug for PayloadBuf {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{:02X?}", self.as_slice())
    }
}

/// Big-endian writer into a fixed payload buffer (ICD §3.2.1: most significant byte
/// first). Every message's payload is far below the buffer, so writes never overflow;
/// a write past the end is dropped rather than panicking.
pub struct Writer {
    buf: [u8; MAX_PAYLOAD],
    len: usize,
}

impl Writer {
    fn new() -> Self {
        Writer {
            buf: [0; MAX_PAYLOAD],
            len: 0,
        }
    }
    /// Appends one byte.
    pub fn u8(&mut self, v: u8) {
        if let Some(b) = self.buf.get_mut(self.len) {
            *b = v;
            self.len += 1;
        }
    }
    /// Appends a 16-bit word, most significant byte first (ICD §3.2.1).
    pub fn u16(&mut self, v: u16) {
        self.bytes(&v.to_be_bytes());
    }
    /// Appends a 32-bit word, most significant byte first (ICD §3.2.1).
    pub fn u32(&mut self, v: u32) {
        self.bytes(&v.to_be_bytes());
    }
    /// Appends bytes as they are.
    pub fn bytes(&mut self, v: &[u8]) {
        for &b in v {
            self.u8(b);
        }
    }
    fn finish(self) -> PayloadBuf {
        PayloadBuf {
            buf: self.buf,
            len: self.len,
        }
    }
}

/// Big-endian reader over a payload whose length was already checked; reading past
/// the end yields zeros instead of panicking.
pub struct Reader<'a> {
    p: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    /// A reader at the start of payload `p`.
    pub fn new(p: &'a [u8]) -> Self {
        Reader { p, at: 0 }
    }
    /// The next byte; 0 past the end.
    pub fn u8(&mut self) -> u8 {
        let v = self.p.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        v
    }
    /// The next 16-bit word, most significant byte first (ICD §3.2.1); 0 past the end.
    pub fn u16(&mut self) -> u16 {
        u16::from_be_bytes([self.u8(), self.u8()])
    }
    /// The next 32-bit word, most significant byte first (ICD §3.2.1); 0 past the end.
    pub fn u32(&mut self) -> u32 {
        u32::from_be_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
}

/// Bit `n` (0 = LSB) of a flags byte.
pub(crate) fn bit(b: u8, n: u8) -> bool {
    b & (1 << n) != 0
}

/// A byte the ICD defines as 0 or 1. Anything else is reported, not guessed at.
pub(crate) fn flag(message: &'static str, field: &'static str, b: u8) -> Result<bool> {
    match b {
        0 => Ok(false),
        1 => Ok(true),
        v => Err(Error::FieldRange {
            message,
            field,
            value: v as u32,
        }),
    }
}

/// The longest payload taken where the request's payload is ignored (VERSION,
/// §6.1.2) or not described at all (DEVICE_STATUS_QUERY, icd-reading R6): the length
/// of DEVICE_STATUS, the longest message of the ICD, so that such a frame never
/// stretches the decoder's bound ([`MAX_MESSAGE_LEN`], checked by a test). A longer
/// one is not a frame of the ICD.
pub const IGNORED_PAYLOAD_MAX: usize = 66;

macro_rules! messages {
    ($($v:ident),+ $(,)?) => {
        /// Any message of ICD Appendix D.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Message {
            $(#[doc = concat!("A [`", stringify!($v), "`] message.")] $v($v),)+
        }

        impl Message {
            /// Decodes the payload of message `id`.
            pub fn parse(id: MessageId, payload: &[u8]) -> Result<Message> {
                $(if id == $v::ID {
                    return $v::parse(payload).map(Message::$v);
                })+
                Err(Error::UnknownMessage(id))
            }

            /// Major and minor id of the message (ICD Table 42).
            pub fn id(&self) -> MessageId {
                match self {
                    $(Message::$v(_) => $v::ID,)+
                }
            }

            /// The ICD's name of the message, e.g. `DEVICE_STATUS`.
            pub fn name(&self) -> &'static str {
                match self {
                    $(Message::$v(_) => $v::NAME,)+
                }
            }

            /// The payload bytes of the message (its ICD table).
            pub fn emit(&self) -> PayloadBuf {
                match self {
                    $(Message::$v(m) => m.emit(),)+
                }
            }
        }

        $(impl From<$v> for Message {
            fn from(m: $v) -> Message {
                Message::$v(m)
            }
        })+

        /// Name and length rule of a message id, if the ICD defines it (Appendix D).
        pub fn lookup(id: MessageId) -> Option<(&'static str, LenRule)> {
            $(if id == $v::ID {
                return Some(($v::NAME, $v::LEN));
            })+
            None
        }

        /// Every message id of Appendix D.
        pub const ALL_IDS: &[MessageId] = &[$($v::ID,)+];

        /// The longest payload any message of Appendix D can carry (DEVICE_STATUS, 66).
        pub const MAX_MESSAGE_LEN: usize = {
            let lens = [$(match $v::LEN {
                LenRule::Exact(n) => n,
                LenRule::Between(_, hi) => hi,
            },)+];
            let mut max = 0;
            let mut rest: &[usize] = &lens;
            while let [len, tail @ ..] = rest {
                if *len > max {
                    max = *len;
                }
                rest = tail;
            }
            max
        };
    };
}

messages!(
    Ping,
    Version,
    SoftwareUpdate,
    EepromErase,
    DeviceSpec,
    SystemSpec,
    TrimSpec,
    FlapSpec,
    WigWagSpec,
    DeviceSpecQuery,
    SpecAck,
    DeviceName,
    DeviceNameQuery,
    DeviceEnable,
    SystemStatus,
    DeviceStatus,
    FlapTrimStatus,
    FaultStatus,
    DeviceStatusQuery,
    DevicePower,
    TrimMove,
    FlapMove,
    WigWagMode,
    DeviceClear,
    ExternalData,
);

/// A message with its frame header: what travels on the wire (ICD Table 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Packet {
    /// Command number (ICD Table 2 byte 5): the EFIS's choice on a request, echoed in the
    /// reply; the unit's own count on broadcasts (icd-reading R14).
    pub cnt: u8,
    /// Source (ICD Table 2 byte 6).
    pub src: Node,
    /// Destination (ICD Table 2 byte 7).
    pub dst: Node,
    /// The typed payload.
    pub message: Message,
}

impl Packet {
    /// A request from the EFIS to the unit.
    pub fn request(cnt: u8, message: impl Into<Message>) -> Self {
        Packet {
            cnt,
            src: Node::External,
            dst: Node::Vpx,
            message: message.into(),
        }
    }

    /// A message from the unit to the EFIS (a reply or a broadcast).
    pub fn from_vpx(cnt: u8, message: impl Into<Message>) -> Self {
        Packet {
            cnt,
            src: Node::Vpx,
            dst: Node::External,
            message: message.into(),
        }
    }

    /// Decodes a checked frame.
    pub fn parse(frame: &FrameRef<'_>) -> Result<Packet> {
        let h = frame.header();
        Ok(Packet {
            cnt: h.cnt,
            src: h.src,
            dst: h.dst,
            message: Message::parse(h.id, frame.payload())?,
        })
    }

    /// Checks and decodes one whole frame from bytes.
    pub fn parse_bytes(bytes: &[u8]) -> Result<Packet> {
        Packet::parse(&FrameRef::parse(bytes)?)
    }

    /// The header of the frame that carries this packet (ICD Table 2).
    pub fn header(&self) -> FrameHeader {
        FrameHeader {
            id: self.message.id(),
            cnt: self.cnt,
            src: self.src,
            dst: self.dst,
        }
    }

    /// Writes the whole frame into `out` and returns its length.
    pub fn emit_into(&self, out: &mut [u8; MAX_FRAME]) -> usize {
        let payload = self.message.emit();
        // Payloads are at most 66 bytes, so the frame always fits `MAX_FRAME`.
        emit_frame(&self.header(), &payload, out).unwrap_or(0)
    }

    /// The whole frame as bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = [0u8; MAX_FRAME];
        let n = self.emit_into(&mut out);
        out.get(..n).unwrap_or_default().to_vec()
    }
}

/// Smallest possible frame: header and checksum with no payload (ICD Table 1).
pub const MIN_FRAME: usize = HEADER_LEN + 1;

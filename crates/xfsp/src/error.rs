//! What can be wrong with XFSp bytes, or with a value we were asked to encode.
//!
//! Every variant names the exact problem so that `xfsp-dump` and the receiver's
//! counters can say *why* a datagram was dropped, not merely that it was.

use super::format::FormatId;

/// An XFSp codec error (§3 message and parameter formats). Parsing and emitting never
/// panic; they return one of these.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// Fewer than 12 bytes: not even a message header.
    #[error("datagram of {len} bytes is shorter than the 12-byte message header")]
    ShortHeader {
        /// The datagram's size.
        len: usize,
    },

    /// The header's `len` promises more bytes than the datagram holds (icd-reading X3).
    #[error("header len {declared} runs past the datagram ({available} bytes after the header)")]
    LenPastEnd {
        /// The header's `len`.
        declared: u16,
        /// Bytes the datagram holds after the header.
        available: usize,
    },

    /// Bytes left at `offset` that cannot hold a 12-byte parameter header.
    #[error(
        "parameter at offset {offset}: only {available} bytes left, a parameter header needs 12"
    )]
    ShortParamHeader {
        /// Where the parameter starts in the datagram (12 for the first).
        offset: usize,
        /// Bytes left from there.
        available: usize,
    },

    /// A parameter's data (padded to 4) runs past the end of the datagram.
    #[error(
        "parameter at offset {offset}: data length {len} (padded {padded}) runs past the datagram ({available} bytes left after its header)"
    )]
    ParamPastEnd {
        /// Where the parameter starts in the datagram (12 for the first).
        offset: usize,
        /// The 12-bit Parameter Data Len (§3.2).
        len: u16,
        /// That length padded to a multiple of 4 (§3.2).
        padded: usize,
        /// Bytes left after the parameter header.
        available: usize,
    },

    /// The format octet names no format of §3.3.
    #[error("unknown attribute format {0}")]
    UnknownFormat(u8),

    /// The parameter data length does not suit the format (§3.3 "Length:").
    #[error("{format:?} data is {len} bytes, the format needs {need}")]
    BadLength {
        /// The parameter's format octet (§3.2, §3.3).
        format: FormatId,
        /// The parameter's data length.
        len: usize,
        /// The length the §3.3 format allows.
        need: LengthRule,
    },

    /// More than the 12-bit parameter length field can say.
    #[error("parameter data of {len} bytes exceeds the 12-bit length field (max 4095)")]
    DataTooLong {
        /// The data's length.
        len: usize,
    },

    /// An ident that does not fit the 20-bit field.
    #[error("ident {0:#x} does not fit in 20 bits")]
    IdentTooLarge(u32),

    /// A message body longer than the 16-bit `len` field.
    #[error("message body of {len} bytes exceeds the 16-bit len field")]
    BodyTooLong {
        /// The body's length.
        len: usize,
    },

    /// One parameter alone is larger than the datagram budget.
    #[error("a single parameter of {size} bytes exceeds the {limit}-byte datagram budget")]
    ParamTooLarge {
        /// The parameter's size with its header and padding.
        size: usize,
        /// The datagram budget for parameters (icd-reading X9: 1460 bytes on IPv4).
        limit: usize,
    },
}

/// How long a format's data must be (the "Length:" line of each §3.3 format).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthRule {
    /// Exactly this many bytes.
    Exactly(usize),
    /// This many fixed bytes followed by a variable tail (a label or array).
    AtLeast(usize),
}

impl std::fmt::Display for LengthRule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LengthRule::Exactly(n) => write!(f, "exactly {n}"),
            LengthRule::AtLeast(n) => write!(f, "at least {n}"),
        }
    }
}

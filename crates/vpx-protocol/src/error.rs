use super::frame::MessageId;

/// How many payload bytes a message may carry (the "Payload Size" of each message, ICD §6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LenRule {
    /// Exactly this many bytes (the "Payload Size" line of the message's ICD section).
    Exact(usize),
    /// Inclusive range; FAULT_STATUS is the only variable-length message (icd-reading R9).
    Between(usize, usize),
}

impl LenRule {
    /// Whether a payload of `len` bytes is allowed.
    pub fn allows(self, len: usize) -> bool {
        match self {
            LenRule::Exact(n) => len == n,
            LenRule::Between(lo, hi) => (lo..=hi).contains(&len),
        }
    }
}

impl core::fmt::Display for LenRule {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LenRule::Exact(n) => write!(f, "{n}"),
            LenRule::Between(lo, hi) => write!(f, "{lo} to {hi}"),
        }
    }
}

/// Everything that can be wrong with bytes that claim to be a VP-X frame (ICD §4) or
/// message (ICD §6).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// Fewer bytes than the frame needs: 8 header bytes, `len` payload bytes and the
    /// checksum (ICD Table 1, icd-reading R1).
    #[error("frame is {got} bytes, shorter than its header and checksum need ({need})")]
    Truncated {
        /// Bytes given.
        got: usize,
        /// Bytes the frame needs.
        need: usize,
    },
    /// The first two bytes are not 0xE7 0x7E (ICD Table 1, bytes 1 and 2).
    #[error("frame does not start with 0xE7 0x7E")]
    BadHeader,
    /// The checksum byte is not the inverted XOR of the bytes before it (ICD §4.1.3,
    /// icd-reading R2).
    #[error("bad checksum: computed {computed:#04x}, frame carries {found:#04x}")]
    BadChecksum {
        /// What the bytes before the checksum give.
        computed: u8,
        /// The frame's last byte.
        found: u8,
    },
    /// An intact frame whose major/minor ICD Table 42 does not define.
    #[error("unknown message {}", .0)]
    UnknownMessage(MessageId),
    /// A payload length the message's ICD section does not give.
    #[error("{message}: payload is {got} bytes, the ICD gives {expected}")]
    BadLength {
        /// The message's ICD name, e.g. `DEVICE_POWER`.
        message: &'static str,
        /// The length the ICD gives.
        expected: LenRule,
        /// The payload's length.
        got: usize,
    },
    /// A field outside the range its ICD table gives (e.g. a 0–1 flag that is 2).
    #[error("{message}: field {field} is {value}, outside its range")]
    FieldRange {
        /// The message's ICD name.
        message: &'static str,
        /// The field's name as in the message's ICD table.
        field: &'static str,
        /// The value received.
        value: u32,
    },
    /// A payload over 255 bytes, more than ICD Table 1's one-byte `<len>` can say.
    #[error("payload of {0} bytes does not fit the one-byte length field")]
    PayloadTooLong(usize),
}

/// A result with this crate's [`Error`].
pub type Result<T> = core::result::Result<T, Error>;

use super::frame::MessageId;

/// How many payload bytes a message may carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LenRule {
    Exact(usize),
    /// Inclusive range; FAULT_STATUS is the only variable-length message (reading note 9).
    Between(usize, usize),
}

impl LenRule {
    pub fn allows(self, len: usize) -> bool {
        match self {
            LenRule::Exact(n) => len == n,
            LenRule::Between(lo, hi) => (lo..=hi).contains(&len),
        }
    }
}

impl std::fmt::Display for LenRule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LenRule::Exact(n) => write!(f, "{n}"),
            LenRule::Between(lo, hi) => write!(f, "{lo} to {hi}"),
        }
    }
}

/// Everything that can be wrong with bytes that claim to be a VP-X frame or message.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    #[error("frame is {got} bytes, shorter than its header and checksum need ({need})")]
    Truncated { got: usize, need: usize },
    #[error("frame does not start with 0xE7 0x7E")]
    BadHeader,
    #[error("bad checksum: computed {computed:#04x}, frame carries {found:#04x}")]
    BadChecksum { computed: u8, found: u8 },
    #[error("unknown message {}", .0)]
    UnknownMessage(MessageId),
    #[error("{message}: payload is {got} bytes, the ICD gives {expected}")]
    BadLength {
        message: &'static str,
        expected: LenRule,
        got: usize,
    },
    #[error("{message}: field {field} is {value}, outside its range")]
    FieldRange {
        message: &'static str,
        field: &'static str,
        value: u32,
    },
    #[error("payload of {0} bytes does not fit the one-byte length field")]
    PayloadTooLong(usize),
}

pub type Result<T> = std::result::Result<T, Error>;

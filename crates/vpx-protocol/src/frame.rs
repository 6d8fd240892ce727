//! The frame of ICD §4 (Table 1/2): an 8-byte header, the payload, a checksum.
//!
//! Readings taken (docs/src/contributing/icd-reading.md): a frame is `8 + len + 1` bytes (icd-reading
//! R1, the "Total Size" lines are ignored); the checksum is the XOR of every byte
//! before it, both header bytes included, then inverted (icd-reading R2); majors run
//! 0x10–0x15 (icd-reading R5).

use super::error::{Error, Result};

/// Header byte #1, always 0xE7 (ICD Table 1, byte 1).
pub const SYNC1: u8 = 0xE7;
/// Header byte #2, always 0x7E (ICD Table 1, byte 2).
pub const SYNC2: u8 = 0x7E;
/// The header's size: sync, major, minor, cnt, src, dst and len (ICD Table 2).
pub const HEADER_LEN: usize = 8;
/// The largest payload ICD Table 1's one-byte `<len>` allows.
pub const MAX_PAYLOAD: usize = 255;
/// The largest frame the one-byte length field allows (ICD Table 1); the decoder never
/// buffers more.
pub const MAX_FRAME: usize = HEADER_LEN + MAX_PAYLOAD + 1;

/// Major/minor command id pair (Table 2 bytes 3 and 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MessageId {
    /// Major command id (Table 2 byte 3): the message group, 0x10–0x15 (ICD Table 3,
    /// icd-reading R5).
    pub major: u8,
    /// Minor command id (Table 2 byte 4): the message within its group (ICD Tables 4–9).
    pub minor: u8,
}

impl MessageId {
    /// The id `major`/`minor` (ICD Table 42).
    pub const fn new(major: u8, minor: u8) -> Self {
        MessageId { major, minor }
    }
}

impl core::fmt::Display for MessageId {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{:#04x}/{:#04x}", self.major, self.minor)
    }
}

/// Source and destination addresses (Table 1 bytes 6 and 7). Unlisted values are kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Node {
    /// 0x00, the VP-X (ICD Table 1).
    Vpx,
    /// 0x01, the external system, e.g. the EFIS (ICD Table 1).
    External,
    /// 0xFE, unknown (ICD Table 1).
    Unknown,
    /// 0xFF, broadcast (ICD Table 1; accepted as the destination of status messages,
    /// icd-reading R22).
    Broadcast,
    /// Any other byte, kept as it was.
    Other(u8),
}

impl Node {
    /// The node of a Table 1 src/dst byte.
    pub fn from_byte(b: u8) -> Self {
        match b {
            0x00 => Node::Vpx,
            0x01 => Node::External,
            0xFE => Node::Unknown,
            0xFF => Node::Broadcast,
            n => Node::Other(n),
        }
    }

    /// The Table 1 src/dst byte.
    pub fn to_byte(self) -> u8 {
        match self {
            Node::Vpx => 0x00,
            Node::External => 0x01,
            Node::Unknown => 0xFE,
            Node::Broadcast => 0xFF,
            Node::Other(n) => n,
        }
    }

    /// A short name for people: `VP-X`, `EFIS`, `unknown`, `broadcast` or `other`.
    pub fn name(self) -> &'static str {
        match self {
            Node::Vpx => "VP-X",
            Node::External => "EFIS",
            Node::Unknown => "unknown",
            Node::Broadcast => "broadcast",
            Node::Other(_) => "other",
        }
    }
}

/// ICD §4.1.3: XOR of all bytes, then inverted.
#[inline]
pub fn checksum(bytes: &[u8]) -> u8 {
    !bytes.iter().fold(0u8, |acc, b| acc ^ b)
}

/// The header fields a caller chooses (ICD Table 2); the sync bytes and length are implied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameHeader {
    /// Major and minor command id (Table 2 bytes 3 and 4).
    pub id: MessageId,
    /// Command number: chosen by the EFIS per request and echoed in the reply;
    /// the VP-X's own running count on broadcasts (icd-reading R14).
    pub cnt: u8,
    /// Source (Table 2 byte 6).
    pub src: Node,
    /// Destination (Table 2 byte 7).
    pub dst: Node,
}

/// A checked frame borrowed from a buffer: sync bytes, length and checksum are known good
/// (ICD Table 1, §4.1.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameRef<'a> {
    bytes: &'a [u8],
}

impl<'a> FrameRef<'a> {
    /// Checks a whole frame. `bytes` must be exactly one frame.
    pub fn parse(bytes: &'a [u8]) -> Result<Self> {
        if bytes.len() < HEADER_LEN + 1 {
            return Err(Error::Truncated {
                got: bytes.len(),
                need: HEADER_LEN + 1,
            });
        }
        let Some(&[sync1, sync2, _, _, _, _, _, len]) = bytes.first_chunk::<HEADER_LEN>() else {
            return Err(Error::Truncated {
                got: bytes.len(),
                need: HEADER_LEN + 1,
            });
        };
        if sync1 != SYNC1 || sync2 != SYNC2 {
            return Err(Error::BadHeader);
        }
        let need = HEADER_LEN + len as usize + 1;
        let Some(bytes) = bytes.get(..need) else {
            return Err(Error::Truncated {
                got: bytes.len(),
                need,
            });
        };
        let (&found, before) = bytes.split_last().ok_or(Error::BadHeader)?;
        let computed = checksum(before);
        if computed != found {
            return Err(Error::BadChecksum { computed, found });
        }
        Ok(FrameRef { bytes })
    }

    /// For the decoder, which has already checked the frame.
    pub(crate) fn new_unchecked(bytes: &'a [u8]) -> Self {
        FrameRef { bytes }
    }

    /// Header byte `i` (0-based). A checked frame always has its 8 header bytes; 0
    /// stands in only for a byte that cannot be missing.
    fn byte(&self, i: usize) -> u8 {
        self.bytes.get(i).copied().unwrap_or(0)
    }

    /// The header fields (ICD Table 2, bytes 3–7).
    pub fn header(&self) -> FrameHeader {
        FrameHeader {
            id: self.id(),
            cnt: self.byte(4),
            src: Node::from_byte(self.byte(5)),
            dst: Node::from_byte(self.byte(6)),
        }
    }

    /// Major and minor command id (ICD Table 2, bytes 3 and 4).
    pub fn id(&self) -> MessageId {
        MessageId::new(self.byte(2), self.byte(3))
    }

    /// The payload: the `<len>` bytes after the header, without the checksum (ICD Table 1,
    /// bytes 9+).
    pub fn payload(&self) -> &'a [u8] {
        self.bytes
            .get(HEADER_LEN..self.bytes.len().saturating_sub(1))
            .unwrap_or_default()
    }

    /// The whole frame, header to checksum.
    pub fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }
}

/// Writes one frame into `out` and returns its length. `out` must hold
/// `HEADER_LEN + payload.len() + 1` bytes.
pub fn emit_frame(header: &FrameHeader, payload: &[u8], out: &mut [u8]) -> Result<usize> {
    if payload.len() > MAX_PAYLOAD {
        return Err(Error::PayloadTooLong(payload.len()));
    }
    let total = HEADER_LEN + payload.len() + 1;
    let truncated = Error::Truncated {
        got: out.len(),
        need: total,
    };
    let Some((head, rest)) = out.split_first_chunk_mut::<HEADER_LEN>() else {
        return Err(truncated);
    };
    let Some((body, [sum, ..])) = rest.split_at_mut_checked(payload.len()) else {
        return Err(truncated);
    };
    *head = [
        SYNC1,
        SYNC2,
        header.id.major,
        header.id.minor,
        header.cnt,
        header.src.to_byte(),
        header.dst.to_byte(),
        payload.len() as u8,
    ];
    body.copy_from_slice(payload);
    *sum = !head.iter().chain(body.iter()).fold(0u8, |acc, b| acc ^ b);
    Ok(total)
}

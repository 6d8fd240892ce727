//! The VP-X bootloader protocol, ICD §7 (Tables 35–39, icd-reading R17 and R24).
//!
//! After SOFTWARE_UPDATE the unit stops speaking the main protocol and listens for
//! frames of its own: `0x69 0x96`, one ASCII command character, `num` (payload size
//! in 16-bit words, Table 35 note 2), a jump byte that is always 0, then the payload.
//! Replies are bare bytes with no framing (Tables 36–39).
//!
//! Host side: [`BootCommand::emit`] and [`BootResponseReader`]. Device side (the
//! virtual unit's bootloader): [`BootCommandDecoder`] and [`BootResponse::emit`].
//!
//! Decisions where the ICD is silent or contradicts itself:
//!
//! * **Frame sizes** come from the tables, not the "Total Size" lines (icd-reading R24):
//!   SERIAL_CONF is 5 + 6 = 11 bytes, not 9.
//! * **FLASH_PROG's command character is lower-case `'p'`** and its reply upper-case
//!   `'P'` (§7.5.3, icd-reading R17): we send `'p'`. Table 35's and Table 36's lists (and
//!   Appendix D) say `P`, so a host written from those tables sends `'P'`; the
//!   device-side decoder takes both as FLASH_PROG (liberal on receipt). Table 35's list
//!   also names an `O` that no section describes; it is not a command here and is
//!   ignored like any unknown one.
//! * **Address unit** (icd-reading R24): the 16-bit address of FLASH_PROG and FLASH_READ is a
//!   **page number** (byte address / 256). The ATmega2560 (SIGNATURE 1E 98 01,
//!   icd-reading R17) has 256 KiB of flash: byte addresses (0–262143) and even word addresses
//!   (0–131071) overflow 16 bits, page numbers (0–1023) do not, and Table 38 calls the
//!   field "Flash Page Address". The same unit is used for FLASH_READ. Callers should
//!   log every address sent; [`byte_address`] and [`page_address`] convert.
//! * **FLASH_READ size** is in bytes: the reply is "<page_size> bytes" (§7.5.5).
//! * **Address and size are little-endian** (low byte first, Tables 38, 39, icd-reading
//!   R3), unlike the main protocol.
//! * **Jump byte other than 0** ("always 0 for the VP-X") is taken as "not a frame"
//!   and the decoder resyncs past it.

use alloc::{format, string::String, vec, vec::Vec};
use core::fmt;

/// Bootloader frame start (ICD Table 35).
pub const HEADER: [u8; 2] = [0x69, 0x96];
/// Header, command, `num` and jump byte (ICD Table 35).
pub const HEADER_LEN: usize = 5;
/// SIGNATURE reply: the ATmega2560's 1E 98 01 in reverse (ICD §7.5.6, icd-reading R17).
pub const SIGNATURE: [u8; 3] = [0x01, 0x98, 0x1E];
/// ATmega2560 flash page: 128 words (icd-reading R17).
pub const PAGE_SIZE: usize = 256;
/// Program flash of the ATmega2560 the SIGNATURE reply names: 256 KiB (ICD §7.5.6, icd-reading
/// R17).
pub const FLASH_SIZE: usize = 256 * 1024;
/// Number of [`PAGE_SIZE`] pages in the flash: 1024, so a page number fits FLASH_PROG's
/// 16-bit address (ICD Table 38).
pub const PAGE_COUNT: usize = FLASH_SIZE / PAGE_SIZE;
/// SERIAL_CONF security code (ICD Table 37).
pub const SECURITY: [u8; 4] = [0x75, 0xDB, 0x9C, 0x97];
/// SERIAL_CONF primary port, "always 3 for the VP-X" (ICD Table 37, revision 1.3).
pub const PRIMARY_PORT: u8 = 3;
/// SERIAL_CONF secondary port, "always 0 for the VP-X" (ICD Table 37).
pub const SECONDARY_PORT: u8 = 0;
/// Replies of ICD §7.5.
pub const SERIAL_CONF_REPLY: &[u8] = b"!!!";
/// FLASH_ERASE reply: `'e'` when the erase is complete (ICD §7.5.2).
pub const FLASH_ERASE_REPLY: &[u8] = b"e";
/// FLASH_PROG reply: upper-case `'P'` when the page is written (ICD §7.5.3, icd-reading
/// R17).
pub const FLASH_PROG_REPLY: &[u8] = b"P";
/// QUERY_PORT reply: `"VP_AVRBOOT"` (ICD §7.5.4).
pub const QUERY_PORT_REPLY: &[u8] = b"VP_AVRBOOT";
/// EXIT reply: `'x'`, then the unit reboots (ICD §7.5.8).
pub const EXIT_REPLY: &[u8] = b"x";
/// Largest payload `num` can describe: 255 words (ICD Table 35 note 2).
pub const MAX_PAYLOAD: usize = 255 * 2;

/// The byte address of page `page` (our address unit; see the module doc).
pub fn byte_address(page: u16) -> u32 {
    page as u32 * PAGE_SIZE as u32
}

/// The page number of a byte address, if it starts a page inside the flash.
pub fn page_address(byte_address: u32) -> Option<u16> {
    if byte_address as usize >= FLASH_SIZE || !(byte_address as usize).is_multiple_of(PAGE_SIZE) {
        return None;
    }
    u16::try_from(byte_address as usize / PAGE_SIZE).ok()
}

/// What a bootloader command or reply got wrong (ICD §7).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BootError {
    /// FLASH_PROG data longer than one 256-byte flash page (ICD Table 38, icd-reading R17).
    #[error("flash page data is {len} bytes; a page is {PAGE_SIZE}")]
    PageTooLong {
        /// Bytes of data given.
        len: usize,
    },
    /// A page number past the end of the 256 KiB flash (ICD Tables 38 and 39, icd-reading
    /// R24).
    #[error("page {page} is outside the {PAGE_COUNT}-page flash")]
    PageOutsideFlash {
        /// The page number asked for.
        page: u16,
    },
    /// SIGNATURE answered with other bytes than 0x01 0x98 0x1E (ICD §7.5.6): the bytes
    /// received.
    #[error(
        "signature {:02X} {:02X} {:02X} is not the VP-X's 01 98 1E; do not erase or program this chip",
        .0[0], .0[1], .0[2]
    )]
    WrongSignature([u8; 3]),
    /// A reply that is not the one ICD §7.5 gives for the command.
    #[error("{command}: expected {expected}, got {got:02X?}")]
    UnexpectedReply {
        /// The command's ICD Table 36 name.
        command: &'static str,
        /// The reply §7.5 gives, in words.
        expected: String,
        /// The bytes that came instead.
        got: Vec<u8>,
    },
}

/// One bootloader command, ICD Table 36.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BootCommand {
    /// `'!'`, ICD Table 37. Use [`BootCommand::serial_conf`] for the VP-X's values.
    SerialConf {
        /// Table 37 byte 5, Primary Port #: always 3 for the VP-X.
        primary_port: u8,
        /// Table 37 byte 6, Secondary Port #: always 0 for the VP-X.
        secondary_port: u8,
        /// Table 37 bytes 7–10, the security code 0x75 0xDB 0x9C 0x97.
        security: [u8; 4],
    },
    /// `'E'`, §7.5.2.
    FlashErase,
    /// `'p'`, ICD Table 38: `address` is a page number (module doc); `data` one page.
    FlashProg {
        /// Table 38 bytes 5–6, "Flash Page Address", low byte first: a page number.
        address: u16,
        /// The page's bytes, at most [`PAGE_SIZE`].
        data: Vec<u8>,
    },
    /// `'Q'`, §7.5.4.
    QueryPort,
    /// `'R'`, ICD Table 39: `address` a page number, `size` in bytes.
    FlashRead {
        /// Table 39 bytes 5–6, "Read Address", low byte first: a page number.
        address: u16,
        /// Table 39 bytes 7–8, "Page Size", low byte first: bytes to read (§7.5.5).
        size: u16,
    },
    /// `'S'`, §7.5.6.
    Signature,
    /// `'V'`, §7.5.7.
    Version,
    /// `'X'`, §7.5.8.
    Exit,
}

impl BootCommand {
    /// SERIAL_CONF as the VP-X wants it (ICD Table 37).
    pub fn serial_conf() -> Self {
        BootCommand::SerialConf {
            primary_port: PRIMARY_PORT,
            secondary_port: SECONDARY_PORT,
            security: SECURITY,
        }
    }

    /// FLASH_PROG of page `page`. Shorter data is padded with 0xFF, the value of erased
    /// flash, so programming the pad changes nothing; longer data or a page past the end
    /// of the flash is refused.
    pub fn flash_prog(page: u16, data: &[u8]) -> Result<Self, BootError> {
        if data.len() > PAGE_SIZE {
            return Err(BootError::PageTooLong { len: data.len() });
        }
        if page as usize >= PAGE_COUNT {
            return Err(BootError::PageOutsideFlash { page });
        }
        let mut page_data = data.to_vec();
        page_data.resize(PAGE_SIZE, 0xFF);
        Ok(BootCommand::FlashProg {
            address: page,
            data: page_data,
        })
    }

    /// FLASH_READ of one whole page.
    pub fn flash_read_page(page: u16) -> Self {
        BootCommand::FlashRead {
            address: page,
            size: PAGE_SIZE as u16,
        }
    }

    /// The command character (ICD Table 36; FLASH_PROG's is lower-case, §7.5.3).
    pub fn code(&self) -> u8 {
        match self {
            BootCommand::SerialConf { .. } => b'!',
            BootCommand::FlashErase => b'E',
            BootCommand::FlashProg { .. } => b'p',
            BootCommand::QueryPort => b'Q',
            BootCommand::FlashRead { .. } => b'R',
            BootCommand::Signature => b'S',
            BootCommand::Version => b'V',
            BootCommand::Exit => b'X',
        }
    }

    /// The ICD's name, e.g. `FLASH_PROG`.
    pub fn name(&self) -> &'static str {
        match self {
            BootCommand::SerialConf { .. } => "SERIAL_CONF",
            BootCommand::FlashErase => "FLASH_ERASE",
            BootCommand::FlashProg { .. } => "FLASH_PROG",
            BootCommand::QueryPort => "QUERY_PORT",
            BootCommand::FlashRead { .. } => "FLASH_READ",
            BootCommand::Signature => "SIGNATURE",
            BootCommand::Version => "VERSION",
            BootCommand::Exit => "EXIT",
        }
    }

    /// The whole frame. FLASH_PROG always carries exactly one page: data is padded with
    /// 0xFF or cut to [`PAGE_SIZE`] so that `num` is the 129 words §7.5.3 asks for;
    /// build it with [`BootCommand::flash_prog`] to have the length checked instead.
    pub fn emit(&self) -> Vec<u8> {
        let payload: Vec<u8> = match self {
            BootCommand::SerialConf {
                primary_port,
                secondary_port,
                security,
            } => {
                let mut p = vec![*primary_port, *secondary_port];
                p.extend_from_slice(security);
                p
            }
            BootCommand::FlashProg { address, data } => {
                let mut p = address.to_le_bytes().to_vec();
                p.extend(
                    data.iter()
                        .copied()
                        .chain(core::iter::repeat(0xFF))
                        .take(PAGE_SIZE),
                );
                p
            }
            BootCommand::FlashRead { address, size } => {
                let mut p = address.to_le_bytes().to_vec();
                p.extend_from_slice(&size.to_le_bytes());
                p
            }
            BootCommand::FlashErase
            | BootCommand::QueryPort
            | BootCommand::Signature
            | BootCommand::Version
            | BootCommand::Exit => Vec::new(),
        };
        // Every payload above is a whole number of words and at most 258 bytes.
        let num = (payload.len() / 2) as u8;
        let mut out = Vec::with_capacity(HEADER_LEN + payload.len());
        out.extend_from_slice(&HEADER);
        out.extend_from_slice(&[self.code(), num, 0]);
        out.extend_from_slice(&payload);
        out
    }

    /// What the unit answers (ICD §7.5).
    pub fn expected_reply(&self) -> ExpectedReply {
        match self {
            BootCommand::SerialConf { .. } => ExpectedReply::Text(SERIAL_CONF_REPLY),
            BootCommand::FlashErase => ExpectedReply::Text(FLASH_ERASE_REPLY),
            BootCommand::FlashProg { .. } => ExpectedReply::Text(FLASH_PROG_REPLY),
            BootCommand::QueryPort => ExpectedReply::Text(QUERY_PORT_REPLY),
            BootCommand::FlashRead { size, .. } => ExpectedReply::Bytes(*size as usize),
            BootCommand::Signature => ExpectedReply::Bytes(SIGNATURE.len()),
            BootCommand::Version => ExpectedReply::Bytes(2),
            BootCommand::Exit => ExpectedReply::Text(EXIT_REPLY),
        }
    }
}

impl fmt::Display for BootCommand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BootCommand::FlashProg { address, data } => write!(
                f,
                "FLASH_PROG page {address} (byte address {:#07x}, {} bytes)",
                byte_address(*address),
                data.len()
            ),
            BootCommand::FlashRead { address, size } => write!(
                f,
                "FLASH_READ page {address} (byte address {:#07x}, {size} bytes)",
                byte_address(*address)
            ),
            c => f.write_str(c.name()),
        }
    }
}

/// The shape of a reply: fixed text, or a number of binary bytes (ICD §7.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExpectedReply {
    /// A fixed reply string: `"!!!"`, `'e'`, `'P'`, `"VP_AVRBOOT"` or `'x'` (ICD §7.5).
    Text(&'static [u8]),
    /// This many raw bytes: FLASH_READ's data, SIGNATURE's 3, VERSION's 2 (ICD
    /// §7.5.5–7.5.7).
    Bytes(usize),
}

/// A bootloader reply, typed (ICD §7.5).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BootResponse {
    /// `"!!!"` to SERIAL_CONF.
    SerialConf,
    /// `"e"`: erase done.
    Erased,
    /// `"P"`: page programmed.
    Programmed,
    /// `"VP_AVRBOOT"` to QUERY_PORT.
    Port,
    /// FLASH_READ's bytes.
    Flash(Vec<u8>),
    /// SIGNATURE's three bytes. Only [`SIGNATURE`] gets past the reader.
    Signature([u8; 3]),
    /// Bootloader version, high byte first (§7.5.7).
    Version(u16),
    /// `"x"`: leaving the bootloader.
    Exit,
}

impl BootResponse {
    /// The reply's bytes, as the unit sends them.
    pub fn emit(&self) -> Vec<u8> {
        match self {
            BootResponse::SerialConf => SERIAL_CONF_REPLY.to_vec(),
            BootResponse::Erased => FLASH_ERASE_REPLY.to_vec(),
            BootResponse::Programmed => FLASH_PROG_REPLY.to_vec(),
            BootResponse::Port => QUERY_PORT_REPLY.to_vec(),
            BootResponse::Flash(b) => b.clone(),
            BootResponse::Signature(s) => s.to_vec(),
            BootResponse::Version(v) => v.to_be_bytes().to_vec(),
            BootResponse::Exit => EXIT_REPLY.to_vec(),
        }
    }

    /// Reads the complete reply `reply` to `command`, which must be exactly the
    /// expected bytes.
    pub fn parse(command: &BootCommand, reply: &[u8]) -> Result<BootResponse, BootError> {
        let unexpected = |expected: String| BootError::UnexpectedReply {
            command: command.name(),
            expected,
            got: reply.to_vec(),
        };
        match command.expected_reply() {
            ExpectedReply::Text(t) if reply != t => {
                return Err(unexpected(format!("{:?}", String::from_utf8_lossy(t))));
            }
            ExpectedReply::Bytes(n) if reply.len() != n => {
                return Err(unexpected(format!("{n} bytes")));
            }
            _ => {}
        }
        Ok(match command {
            BootCommand::SerialConf { .. } => BootResponse::SerialConf,
            BootCommand::FlashErase => BootResponse::Erased,
            BootCommand::FlashProg { .. } => BootResponse::Programmed,
            BootCommand::QueryPort => BootResponse::Port,
            BootCommand::FlashRead { .. } => BootResponse::Flash(reply.to_vec()),
            BootCommand::Signature => {
                let s: [u8; 3] = reply
                    .try_into()
                    .map_err(|_| unexpected(format!("{} bytes", SIGNATURE.len())))?;
                if s != SIGNATURE {
                    return Err(BootError::WrongSignature(s));
                }
                BootResponse::Signature(s)
            }
            BootCommand::Version => BootResponse::Version(u16::from_be_bytes(
                reply.try_into().map_err(|_| unexpected("2 bytes".into()))?,
            )),
            BootCommand::Exit => BootResponse::Exit,
        })
    }
}

/// Host side: collects the reply to one command from the serial port's bytes.
///
/// Text replies are searched for, so bytes before them are skipped and counted (the
/// tail of main-protocol broadcasts still in flight after SOFTWARE_UPDATE, say).
/// Binary replies (FLASH_READ, SIGNATURE, VERSION) carry nothing to search for: they
/// are the first bytes after the command, so empty the port's input before sending.
/// One reader per command; after the reply it takes no more bytes.
#[derive(Debug, Clone)]
pub struct BootResponseReader {
    command: BootCommand,
    buf: Vec<u8>,
    skipped: usize,
    done: bool,
}

impl BootResponseReader {
    /// A reader for the reply to `command` (ICD §7.5).
    pub fn new(command: &BootCommand) -> Self {
        BootResponseReader {
            command: command.clone(),
            buf: Vec::new(),
            skipped: 0,
            done: false,
        }
    }

    /// Takes one byte; the reply once it is complete.
    pub fn push(&mut self, b: u8) -> Option<Result<BootResponse, BootError>> {
        if self.done {
            self.skipped += 1;
            return None;
        }
        self.buf.push(b);
        match self.command.expected_reply() {
            ExpectedReply::Text(t) => {
                while !t.starts_with(&self.buf) {
                    self.buf.remove(0);
                    self.skipped += 1;
                }
                if self.buf.len() < t.len() {
                    return None;
                }
            }
            ExpectedReply::Bytes(n) => {
                if self.buf.len() < n {
                    return None;
                }
            }
        }
        self.done = true;
        Some(BootResponse::parse(&self.command, &self.buf))
    }

    /// Takes bytes up to the end of the reply; the reply and how many bytes it used.
    pub fn feed(&mut self, bytes: &[u8]) -> Option<(Result<BootResponse, BootError>, usize)> {
        for (i, &b) in bytes.iter().enumerate() {
            if let Some(r) = self.push(b) {
                return Some((r, i + 1));
            }
        }
        None
    }

    /// Bytes that were not part of the reply.
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// Whether the reply has been read; after it the reader takes no more bytes.
    pub fn is_done(&self) -> bool {
        self.done
    }
}

/// Counters of a [`BootCommandDecoder`] (frames of ICD Table 35).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BootDecoderStats {
    /// Frames taken as one of ICD Table 36's commands.
    pub commands: u64,
    /// Frames with a command character that is not one of ours (Table 35 note 1).
    pub ignored_frames: u64,
    /// Bytes dropped while looking for a frame start.
    pub skipped_bytes: u64,
}

/// Device side: bytes in, commands out. Holds at most one frame (515 bytes), never
/// panics, and resyncs on `0x69 0x96` one byte at a time.
///
/// A frame is taken only if its command character is one of Table 36's, its `num`
/// fits that command (0 for E/Q/S/V/X, 3 for `!`, 2 for `R`, at least 1 for `p`/`P`) and
/// its jump byte is 0; otherwise its first byte is dropped and the search goes on from
/// the next, so a real frame hidden behind a false start is still found. FLASH_PROG
/// is passed on with whatever data length it carried; the bootloader judges the page.
#[derive(Debug, Clone, Default)]
pub struct BootCommandDecoder {
    buf: Vec<u8>,
    stats: BootDecoderStats,
}

enum Prefix {
    Partial,
    Complete,
    Bad { unknown_command: bool },
}

/// Whether `num` words suit command `code`; `None` for an unknown command.
fn num_fits(code: u8, num: u8) -> Option<bool> {
    Some(match code {
        b'!' => num == 3,
        b'R' => num == 2,
        // FLASH_PROG: 'p' by §7.5.3, 'P' by Tables 35 and 36.
        b'p' | b'P' => num >= 1,
        b'E' | b'Q' | b'S' | b'V' | b'X' => num == 0,
        _ => return None,
    })
}

impl BootCommandDecoder {
    /// An empty decoder.
    pub fn new() -> Self {
        Self::default()
    }

    /// The counters so far.
    pub fn stats(&self) -> BootDecoderStats {
        self.stats
    }

    /// Takes one byte; a command when it completes one. A byte completes at most one
    /// frame, as a false start is always found within the 5 header bytes.
    pub fn push(&mut self, b: u8) -> Option<BootCommand> {
        self.buf.push(b);
        loop {
            match self.prefix() {
                Prefix::Partial => return None,
                Prefix::Complete => {
                    let cmd = parse_frame(&self.buf);
                    self.buf.clear();
                    if cmd.is_some() {
                        self.stats.commands += 1;
                    }
                    return cmd;
                }
                Prefix::Bad { unknown_command } => {
                    if unknown_command {
                        self.stats.ignored_frames += 1;
                    }
                    self.buf.remove(0);
                    self.stats.skipped_bytes += 1;
                }
            }
        }
    }

    /// Takes a chunk of bytes; every command completed in it, in order.
    pub fn feed(&mut self, bytes: &[u8]) -> Vec<BootCommand> {
        bytes.iter().filter_map(|&b| self.push(b)).collect()
    }

    fn prefix(&self) -> Prefix {
        let b = &self.buf;
        let bad = Prefix::Bad {
            unknown_command: false,
        };
        for (i, &want) in HEADER.iter().enumerate() {
            match b.get(i) {
                None => return Prefix::Partial,
                Some(&got) if got != want => return bad,
                Some(_) => {}
            }
        }
        let Some(&cmd) = b.get(2) else {
            return Prefix::Partial;
        };
        if num_fits(cmd, 0).is_none() {
            return Prefix::Bad {
                unknown_command: true,
            };
        }
        let Some(&num) = b.get(3) else {
            return Prefix::Partial;
        };
        if num_fits(cmd, num) != Some(true) {
            return bad;
        }
        match b.get(4) {
            None => return Prefix::Partial,
            Some(0) => {}
            Some(_) => return bad,
        }
        if b.len() >= HEADER_LEN + 2 * num as usize {
            Prefix::Complete
        } else {
            Prefix::Partial
        }
    }
}

/// Decodes a frame whose header `prefix` has already accepted.
fn parse_frame(f: &[u8]) -> Option<BootCommand> {
    let p = f.get(HEADER_LEN..)?;
    let le = |i: usize| Some(u16::from_le_bytes([*p.get(i)?, *p.get(i + 1)?]));
    Some(match *f.get(2)? {
        b'!' => BootCommand::SerialConf {
            primary_port: *p.first()?,
            secondary_port: *p.get(1)?,
            security: p.get(2..6)?.try_into().ok()?,
        },
        b'E' => BootCommand::FlashErase,
        b'p' | b'P' => BootCommand::FlashProg {
            address: le(0)?,
            data: p.get(2..)?.to_vec(),
        },
        b'Q' => BootCommand::QueryPort,
        b'R' => BootCommand::FlashRead {
            address: le(0)?,
            size: le(2)?,
        },
        b'S' => BootCommand::Signature,
        b'V' => BootCommand::Version,
        b'X' => BootCommand::Exit,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Frames written out from ICD Tables 35–39, byte by byte, with the command as
    /// it should decode. Not produced by `emit`.
    fn hand_frames() -> Vec<(Vec<u8>, BootCommand)> {
        let page: Vec<u8> = (0..=255u8).collect();
        let mut prog = vec![0x69, 0x96, 0x70, 0x81, 0x00, 0x02, 0x01];
        prog.extend_from_slice(&page);
        vec![
            // Table 37: '!' = 0x21, 3 words, ports 3 and 0, security 75 DB 9C 97.
            (
                vec![
                    0x69, 0x96, 0x21, 0x03, 0x00, 0x03, 0x00, 0x75, 0xDB, 0x9C, 0x97,
                ],
                BootCommand::serial_conf(),
            ),
            // §7.5.2: 'E' = 0x45, no payload.
            (vec![0x69, 0x96, 0x45, 0x00, 0x00], BootCommand::FlashErase),
            // Table 38: 'p' = 0x70, 128 + 1 = 129 = 0x81 words, page 0x0102 low byte
            // first, then the page.
            (
                prog,
                BootCommand::FlashProg {
                    address: 0x0102,
                    data: page,
                },
            ),
            (vec![0x69, 0x96, 0x51, 0x00, 0x00], BootCommand::QueryPort),
            // Table 39: 'R' = 0x52, 2 words, address 0x03FF and size 0x0100, low first.
            (
                vec![0x69, 0x96, 0x52, 0x02, 0x00, 0xFF, 0x03, 0x00, 0x01],
                BootCommand::FlashRead {
                    address: 0x03FF,
                    size: 256,
                },
            ),
            (vec![0x69, 0x96, 0x53, 0x00, 0x00], BootCommand::Signature),
            (vec![0x69, 0x96, 0x56, 0x00, 0x00], BootCommand::Version),
            (vec![0x69, 0x96, 0x58, 0x00, 0x00], BootCommand::Exit),
        ]
    }

    #[test]
    fn emit_matches_the_tables() {
        for (bytes, cmd) in hand_frames() {
            assert_eq!(cmd.emit(), bytes, "{}", cmd.name());
        }
    }

    #[test]
    fn decoder_reads_the_tables() {
        for (bytes, cmd) in hand_frames() {
            let mut d = BootCommandDecoder::new();
            assert_eq!(d.feed(&bytes), vec![cmd.clone()], "{}", cmd.name());
            assert_eq!(d.stats().skipped_bytes, 0);
        }
    }

    #[test]
    fn serial_conf_is_11_bytes_not_the_total_size_line_9() {
        assert_eq!(BootCommand::serial_conf().emit().len(), 11);
    }

    #[test]
    fn flash_prog_pads_a_short_page_with_erased_bytes() {
        let c = BootCommand::flash_prog(7, &[0xAA, 0xBB, 0xCC]).unwrap();
        let f = c.emit();
        assert_eq!(
            &f[..10],
            &[0x69, 0x96, 0x70, 0x81, 0x00, 0x07, 0x00, 0xAA, 0xBB, 0xCC]
        );
        assert_eq!(f.len(), 5 + 2 + 256);
        assert!(f[10..].iter().all(|&b| b == 0xFF));
        // A hand-built FlashProg with a short page emits one whole page too.
        let raw = BootCommand::FlashProg {
            address: 7,
            data: vec![0xAA, 0xBB, 0xCC],
        };
        assert_eq!(raw.emit(), f);
    }

    #[test]
    fn flash_prog_refuses_what_does_not_fit() {
        assert_eq!(
            BootCommand::flash_prog(0, &[0; 257]),
            Err(BootError::PageTooLong { len: 257 })
        );
        assert_eq!(
            BootCommand::flash_prog(1024, &[0; 256]),
            Err(BootError::PageOutsideFlash { page: 1024 })
        );
        assert!(BootCommand::flash_prog(1023, &[0; 256]).is_ok());
    }

    /// Note 24 decision: the address is a page number, so the last page of 256 KiB
    /// flash (byte 0x3FF00) is address 0x03FF.
    #[test]
    fn address_unit_is_the_page_number() {
        assert_eq!(page_address(0x3FF00), Some(0x03FF));
        assert_eq!(byte_address(0x03FF), 0x3FF00);
        assert_eq!(page_address(0x100), Some(1));
        assert_eq!(page_address(0x101), None, "not page-aligned");
        assert_eq!(page_address(0x40000), None, "past the flash");
        let f = BootCommand::flash_read_page(page_address(0x3FF00).unwrap()).emit();
        assert_eq!(&f[5..7], &[0xFF, 0x03]);
    }

    #[test]
    fn upper_case_p_is_flash_prog_too_and_unknown_characters_are_ignored() {
        let mut d = BootCommandDecoder::new();
        // Table 36's 'P' (0x50): 129 words, page 0x0003 (low byte first), 256 bytes
        // of 0xA5; then 'O' (0x4F), then a real QUERY_PORT.
        let mut bytes = vec![0x69, 0x96, 0x50, 0x81, 0x00, 0x03, 0x00];
        bytes.extend([0xA5; 256]);
        bytes.extend([0x69, 0x96, 0x4F, 0x00, 0x00]);
        bytes.extend([0x69, 0x96, 0x51, 0x00, 0x00]);
        assert_eq!(
            d.feed(&bytes),
            vec![
                BootCommand::FlashProg {
                    address: 3,
                    data: vec![0xA5; 256]
                },
                BootCommand::QueryPort
            ]
        );
        assert_eq!(d.stats().ignored_frames, 1);
        assert_eq!(d.stats().commands, 2);
    }

    #[test]
    fn decoder_resyncs_through_garbage_and_false_starts() {
        let mut bytes = vec![0x00, 0x69, 0x69, 0x96, 0x96, 0x69];
        bytes.extend([0x69, 0x96, 0x45, 0x01, 0x00]); // E with num 1: not a frame
        bytes.extend([0x69, 0x96, 0x53, 0x00, 0x07]); // jump byte 7: not a frame
        bytes.extend([0x69, 0x96, 0x69, 0x96, 0x56, 0x00, 0x00]); // V behind a false start
        bytes.extend([0xE7, 0x7E, 0x12, 0x00]); // main-protocol leftovers
        bytes.extend([0x69, 0x96, 0x58, 0x00, 0x00]);
        let mut d = BootCommandDecoder::new();
        assert_eq!(
            d.feed(&bytes),
            vec![BootCommand::Version, BootCommand::Exit]
        );
        assert_eq!(d.stats().commands, 2);
        assert!(d.stats().skipped_bytes > 0);
    }

    #[test]
    fn decoder_takes_frames_split_anywhere() {
        let stream: Vec<u8> = hand_frames().into_iter().flat_map(|(b, _)| b).collect();
        let want: Vec<BootCommand> = hand_frames().into_iter().map(|(_, c)| c).collect();
        for chunk in [1, 2, 3, 5, 7, 64, 300, stream.len()] {
            let mut d = BootCommandDecoder::new();
            let got: Vec<BootCommand> = stream.chunks(chunk).flat_map(|c| d.feed(c)).collect();
            assert_eq!(got, want, "chunk {chunk}");
        }
    }

    #[test]
    fn flash_prog_payload_may_hold_a_header() {
        // Page data containing a whole EXIT frame must not be taken for one.
        let mut page = vec![0u8; 256];
        page[10..15].copy_from_slice(&[0x69, 0x96, 0x58, 0x00, 0x00]);
        let cmd = BootCommand::flash_prog(3, &page).unwrap();
        let mut d = BootCommandDecoder::new();
        assert_eq!(d.feed(&cmd.emit()), vec![cmd]);
    }

    // ---- replies

    #[test]
    fn replies_from_section_7_5() {
        let cases: Vec<(BootCommand, Vec<u8>, BootResponse)> = vec![
            (
                BootCommand::serial_conf(),
                vec![0x21, 0x21, 0x21],
                BootResponse::SerialConf,
            ),
            (BootCommand::FlashErase, vec![0x65], BootResponse::Erased),
            (
                BootCommand::flash_prog(0, &[]).unwrap(),
                vec![0x50],
                BootResponse::Programmed,
            ),
            (
                BootCommand::QueryPort,
                vec![0x56, 0x50, 0x5F, 0x41, 0x56, 0x52, 0x42, 0x4F, 0x4F, 0x54],
                BootResponse::Port,
            ),
            (
                BootCommand::FlashRead {
                    address: 0,
                    size: 4,
                },
                vec![1, 2, 3, 4],
                BootResponse::Flash(vec![1, 2, 3, 4]),
            ),
            (
                BootCommand::Signature,
                vec![0x01, 0x98, 0x1E],
                BootResponse::Signature(SIGNATURE),
            ),
            (
                BootCommand::Version,
                vec![0x01, 0x02],
                BootResponse::Version(0x0102),
            ),
            (BootCommand::Exit, vec![0x78], BootResponse::Exit),
        ];
        for (cmd, bytes, want) in cases {
            assert_eq!(BootResponse::parse(&cmd, &bytes), Ok(want.clone()), "{cmd}");
            assert_eq!(want.emit(), bytes, "{cmd}");
            let mut r = BootResponseReader::new(&cmd);
            assert_eq!(r.feed(&bytes), Some((Ok(want), bytes.len())), "{cmd}");
        }
    }

    #[test]
    fn wrong_signature_is_an_error() {
        // The ATmega2560's signature in the forward order is not what the VP-X sends.
        assert_eq!(
            BootResponse::parse(&BootCommand::Signature, &[0x1E, 0x98, 0x01]),
            Err(BootError::WrongSignature([0x1E, 0x98, 0x01]))
        );
    }

    #[test]
    fn wrong_text_reply_is_an_error() {
        // FLASH_PROG answers upper-case 'P'; lower-case is not it.
        assert!(matches!(
            BootResponse::parse(&BootCommand::flash_prog(0, &[]).unwrap(), b"p"),
            Err(BootError::UnexpectedReply { .. })
        ));
        assert!(matches!(
            BootResponse::parse(&BootCommand::Version, &[1]),
            Err(BootError::UnexpectedReply { .. })
        ));
    }

    #[test]
    fn reader_skips_noise_before_text_and_stops_after() {
        let mut r = BootResponseReader::new(&BootCommand::QueryPort);
        let mut bytes = vec![0xE7, 0x7E, b'V', b'P', 0x00];
        bytes.extend_from_slice(b"VP_AVRBOOT");
        bytes.extend_from_slice(b"tail");
        assert_eq!(r.feed(&bytes[..7]), None);
        // "_AVRBOOT" completes it; "tail" is left for the caller.
        assert_eq!(r.feed(&bytes[7..]), Some((Ok(BootResponse::Port), 8)));
        assert_eq!(r.skipped(), 5);
        assert!(r.is_done());
        assert_eq!(r.push(b'x'), None);
    }

    #[test]
    fn reader_takes_binary_replies_as_they_come() {
        let mut r = BootResponseReader::new(&BootCommand::flash_read_page(1));
        let page: Vec<u8> = (0..=255u8).rev().collect();
        assert_eq!(r.feed(&page[..100]), None);
        assert_eq!(
            r.feed(&page[100..]),
            Some((Ok(BootResponse::Flash(page.clone())), 156))
        );
    }

    fn any_command() -> impl Strategy<Value = BootCommand> {
        prop_oneof![
            (any::<u8>(), any::<u8>(), any::<[u8; 4]>()).prop_map(|(a, b, s)| {
                BootCommand::SerialConf {
                    primary_port: a,
                    secondary_port: b,
                    security: s,
                }
            }),
            Just(BootCommand::FlashErase),
            (
                0..1024u16,
                proptest::collection::vec(any::<u8>(), PAGE_SIZE)
            )
                .prop_map(|(a, data)| BootCommand::FlashProg { address: a, data }),
            Just(BootCommand::QueryPort),
            (any::<u16>(), any::<u16>())
                .prop_map(|(address, size)| BootCommand::FlashRead { address, size }),
            Just(BootCommand::Signature),
            Just(BootCommand::Version),
            Just(BootCommand::Exit),
        ]
    }

    proptest! {
        #[test]
        fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..4096)) {
            let mut d = BootCommandDecoder::new();
            let _ = d.feed(&bytes);
            prop_assert!(d.buf.len() <= HEADER_LEN + MAX_PAYLOAD);
            for cmd in [BootCommand::QueryPort, BootCommand::Signature, BootCommand::flash_read_page(0)] {
                let mut r = BootResponseReader::new(&cmd);
                let _ = r.feed(&bytes);
            }
        }

        #[test]
        fn commands_survive_garbage_without_a_header_byte(
            cmd in any_command(),
            pre in proptest::collection::vec(any::<u8>().prop_filter("no 0x69", |b| *b != 0x69), 0..64),
            cut in 1usize..300,
        ) {
            let mut bytes = pre;
            bytes.extend(cmd.emit());
            let mut d = BootCommandDecoder::new();
            let got: Vec<BootCommand> = bytes.chunks(cut).flat_map(|c| d.feed(c)).collect();
            prop_assert_eq!(got, vec![cmd]);
        }
    }
}

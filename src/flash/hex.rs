//! Intel HEX firmware images, read whole and checked before anything touches the unit.
//!
//! Records are parsed one line at a time with the `ihex` crate (so every complaint can
//! name its line); the full addresses are built here from the extended address
//! records, following the Intel HEX specification:
//!
//! * after an Extended Segment Address record (type 02) a data byte goes to
//!   `segment * 16 + ((offset + i) mod 64 KiB)`;
//! * after an Extended Linear Address record (type 04) it goes to
//!   `(upper << 16) + offset + i`;
//! * before either, the base is 0.
//!
//! Refused, each with the line that shows it: a line that is not a record (bad
//! checksum, bad characters, wrong length), a data record that would wrap inside its
//! 64 KiB segment (the specification defines the wrap, but no tool writes it on purpose
//! and readers disagree on it, so it is taken for a damaged file), data outside the
//! 256 KiB flash, data written twice (overlapping records), anything after the
//! end-of-file record, a missing end-of-file record (a truncated download), and an
//! image with no data at all. Start address records (03, 05) carry no data and are
//! accepted and ignored: the ATmega2560 always starts at its reset vector.

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

use ihex::Record;

use crate::protocol::bootloader::{FLASH_SIZE, PAGE_COUNT, PAGE_SIZE, byte_address};

/// A firmware image: the flash pages it writes, each a full 256 bytes with the bytes
/// the file does not give left at 0xFF (erased flash, so programming them changes
/// nothing).
#[derive(Clone, PartialEq, Eq)]
pub struct Image {
    pages: BTreeMap<u16, Box<[u8; PAGE_SIZE]>>,
    data_bytes: usize,
    lowest: u32,
    highest: u32,
}

impl fmt::Debug for Image {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Image({})", self.summary())
    }
}

impl Image {
    /// Page numbers (the bootloader's address unit) and their contents, lowest first.
    pub fn pages(&self) -> impl Iterator<Item = (u16, &[u8; PAGE_SIZE])> {
        self.pages.iter().map(|(&n, p)| (n, &**p))
    }

    pub fn page(&self, page: u16) -> Option<&[u8; PAGE_SIZE]> {
        self.pages.get(&page).map(|p| &**p)
    }

    pub fn page_count(&self) -> usize {
        self.pages.len()
    }

    /// Bytes the file's data records give.
    pub fn data_bytes(&self) -> usize {
        self.data_bytes
    }

    /// Lowest and highest byte address the file writes.
    pub fn span(&self) -> (u32, u32) {
        (self.lowest, self.highest)
    }

    /// The whole flash as it should read after erase and programming.
    pub fn to_flash(&self) -> Vec<u8> {
        let mut flash = vec![0xFF; FLASH_SIZE];
        for (n, p) in self.pages() {
            let at = byte_address(n) as usize;
            flash[at..at + PAGE_SIZE].copy_from_slice(p);
        }
        flash
    }

    /// One line for people: size, span and pages.
    pub fn summary(&self) -> String {
        let (lo, hi) = self.span();
        format!(
            "{} bytes of data at {lo:#07x}–{hi:#07x}, {} page{} of {PAGE_SIZE} bytes ({:.1} KiB to write)",
            self.data_bytes,
            self.page_count(),
            if self.page_count() == 1 { "" } else { "s" },
            (self.page_count() * PAGE_SIZE) as f64 / 1024.0
        )
    }
}

/// Why a file is not a usable image. `line` is 1-based.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum HexError {
    #[error("cannot read {path}: {reason}")]
    Io { path: String, reason: String },
    #[error("line {line}: not a valid Intel HEX record: {reason}")]
    BadRecord { line: usize, reason: String },
    #[error(
        "line {line}: data at byte address {address:#07x} is outside the {} KiB flash (0x00000–{:#07x}); is this file for a VP-X?",
        FLASH_SIZE / 1024,
        FLASH_SIZE - 1
    )]
    OutsideFlash { line: usize, address: u64 },
    #[error(
        "line {line}: a {len}-byte data record at offset {offset:#06x} wraps past the end of its 64 KiB segment; the file is damaged"
    )]
    SegmentWrap {
        line: usize,
        offset: u16,
        len: usize,
    },
    #[error(
        "line {line}: byte address {address:#07x} was already given by line {first_line}: overlapping records"
    )]
    Overlap {
        line: usize,
        first_line: usize,
        address: u32,
    },
    #[error("line {line}: a record after the end-of-file record (line {eof_line})")]
    AfterEof { line: usize, eof_line: usize },
    #[error(
        "no end-of-file record (:00000001FF) after line {last_line}: the file is truncated, download it again"
    )]
    MissingEof { last_line: usize },
    #[error("the file holds no data to program (line {last_line} is its last)")]
    Empty { last_line: usize },
}

/// Reads and checks a whole file.
pub fn load_hex(path: &Path) -> Result<Image, HexError> {
    let text = std::fs::read_to_string(path).map_err(|e| HexError::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    parse_hex(&text)
}

/// Where data records' offsets are relative to.
#[derive(Clone, Copy)]
enum Base {
    /// Type 02: wraps inside the segment.
    Segment(u32),
    /// Type 04 (and the initial state, base 0).
    Linear(u32),
}

/// Parses and checks the text of a whole file.
pub fn parse_hex(text: &str) -> Result<Image, HexError> {
    // Which line gave each byte (0 = none yet): names both lines of an overlap.
    let mut given_by: Vec<u32> = vec![0; FLASH_SIZE];
    let mut pages: BTreeMap<u16, Box<[u8; PAGE_SIZE]>> = BTreeMap::new();
    let mut base = Base::Linear(0);
    let mut eof_line: Option<usize> = None;
    let mut data_bytes = 0usize;
    let mut lowest = u32::MAX;
    let mut highest = 0u32;
    let mut last_line = 0usize;

    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let rec = raw.trim();
        if rec.is_empty() {
            continue;
        }
        last_line = line;
        if let Some(eof_line) = eof_line {
            return Err(HexError::AfterEof { line, eof_line });
        }
        let record = Record::from_record_string(rec).map_err(|e| HexError::BadRecord {
            line,
            reason: e.to_string(),
        })?;
        match record {
            Record::Data { offset, value } => {
                if let Base::Segment(_) = base
                    && offset as usize + value.len() > 0x1_0000
                {
                    return Err(HexError::SegmentWrap {
                        line,
                        offset,
                        len: value.len(),
                    });
                }
                for (k, &b) in value.iter().enumerate() {
                    let address: u64 = match base {
                        Base::Segment(s) => s as u64 + ((offset as u64 + k as u64) & 0xFFFF),
                        Base::Linear(l) => l as u64 + offset as u64 + k as u64,
                    };
                    if address >= FLASH_SIZE as u64 {
                        return Err(HexError::OutsideFlash { line, address });
                    }
                    let address = address as u32;
                    let slot = &mut given_by[address as usize];
                    if *slot != 0 {
                        return Err(HexError::Overlap {
                            line,
                            first_line: *slot as usize,
                            address,
                        });
                    }
                    *slot = line as u32;
                    let page = (address as usize / PAGE_SIZE) as u16;
                    pages
                        .entry(page)
                        .or_insert_with(|| Box::new([0xFF; PAGE_SIZE]))
                        [address as usize % PAGE_SIZE] = b;
                    data_bytes += 1;
                    lowest = lowest.min(address);
                    highest = highest.max(address);
                }
            }
            Record::EndOfFile => eof_line = Some(line),
            Record::ExtendedSegmentAddress(s) => base = Base::Segment((s as u32) << 4),
            Record::ExtendedLinearAddress(u) => base = Base::Linear((u as u32) << 16),
            Record::StartSegmentAddress { .. } | Record::StartLinearAddress(_) => {}
        }
    }
    if eof_line.is_none() {
        return Err(HexError::MissingEof { last_line });
    }
    if data_bytes == 0 {
        return Err(HexError::Empty { last_line });
    }
    debug_assert!(pages.keys().all(|&p| (p as usize) < PAGE_COUNT));
    Ok(Image {
        pages,
        data_bytes,
        lowest,
        highest,
    })
}

/// Writes `bytes` at byte address `at` as Intel HEX text (16-byte data records, an
/// Extended Linear Address record wherever the upper 16 bits change, and the EOF
/// record), for tests and for making demonstration images.
pub fn to_hex_text(at: u32, bytes: &[u8]) -> String {
    let mut records = Vec::new();
    let mut upper: Option<u16> = None;
    let mut address = at;
    for chunk in bytes.chunks(16) {
        // A record must not cross a 64 KiB boundary: split there.
        let room = 0x1_0000 - (address & 0xFFFF) as usize;
        let parts: Vec<&[u8]> = if chunk.len() > room {
            vec![&chunk[..room], &chunk[room..]]
        } else {
            vec![chunk]
        };
        for part in parts {
            let hi = (address >> 16) as u16;
            if upper != Some(hi) {
                records.push(Record::ExtendedLinearAddress(hi));
                upper = Some(hi);
            }
            records.push(Record::Data {
                offset: address as u16,
                value: part.to_vec(),
            });
            address += part.len() as u32;
        }
    }
    records.push(Record::EndOfFile);
    // Records of at most 16 bytes and one EOF always write.
    ihex::create_object_file_representation(&records).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    // Records written out by hand (checksum: two's complement of the byte sum), not
    // produced by the writer under test:
    //   :0400000001020304F2   four bytes at 0x0000
    //   :020000040001F9       linear base 0x10000
    //   :020000021000EC       segment base 0x10000
    const EOF: &str = ":00000001FF";

    fn text(lines: &[&str]) -> String {
        lines.join("\n")
    }

    #[test]
    fn four_bytes_make_one_page_padded_with_ff() {
        let img = parse_hex(&text(&[":0400000001020304F2", EOF])).unwrap();
        assert_eq!(img.page_count(), 1);
        assert_eq!(img.data_bytes(), 4);
        let p = img.page(0).unwrap();
        assert_eq!(&p[..5], &[1, 2, 3, 4, 0xFF]);
        assert!(p[4..].iter().all(|&b| b == 0xFF));
        assert_eq!(img.span(), (0, 3));
    }

    #[test]
    fn extended_linear_address_moves_data_to_page_256() {
        // 0x10000 + 0x0010 = byte 0x10010: page 256, offset 16.
        let img = parse_hex(&text(&[":020000040001F9", ":02001000AABB89", EOF])).unwrap();
        assert_eq!(img.pages().map(|(n, _)| n).collect::<Vec<_>>(), vec![256]);
        assert_eq!(img.page(256).unwrap()[16..18], [0xAA, 0xBB]);
        assert_eq!(img.span(), (0x10010, 0x10011));
    }

    #[test]
    fn extended_segment_address_is_times_sixteen() {
        // Segment 0x1000 → base 0x10000, the same byte as above.
        let img = parse_hex(&text(&[":020000021000EC", ":02001000AABB89", EOF])).unwrap();
        assert_eq!(img.span(), (0x10010, 0x10011));
    }

    /// A damaged record is refused by its line, in the error and in its words.
    #[test]
    fn a_damaged_record_is_refused_by_its_line() {
        type Expected = fn(&HexError) -> bool;
        let cases: [(&str, &[&str], Expected); 3] = [
            (
                "a bad checksum",
                &[":0400000001020304F2", ":0400040001020304F3", EOF],
                |e| {
                    matches!(e, HexError::BadRecord { line: 2, .. })
                        && e.to_string().contains("checksum")
                },
            ),
            (
                "a line that is no record",
                &[":0400000001020304F2", "hello", EOF],
                |e| matches!(e, HexError::BadRecord { line: 2, .. }),
            ),
            (
                "a segment record that wraps",
                &[":020000021000EC", ":02FFFF00556645", EOF],
                |e| matches!(e, HexError::SegmentWrap { line: 2, .. }),
            ),
        ];
        for (what, lines, expected) in cases {
            let e = parse_hex(&text(lines)).expect_err(what);
            assert!(expected(&e), "{what}: {e:?}");
            assert!(e.to_string().starts_with("line 2:"), "{what}: {e}");
        }
    }

    #[test]
    fn a_missing_eof_is_a_truncated_file() {
        let e = parse_hex(&text(&[":0400000001020304F2", ""])).unwrap_err();
        assert_eq!(e, HexError::MissingEof { last_line: 1 });
        assert!(e.to_string().contains("truncated"), "{e}");
    }

    #[test]
    fn records_after_eof_are_refused() {
        let e = parse_hex(&text(&[EOF, ":0400000001020304F2"])).unwrap_err();
        assert_eq!(
            e,
            HexError::AfterEof {
                line: 2,
                eof_line: 1
            }
        );
    }

    #[test]
    fn data_past_256_kib_is_refused() {
        // Linear base 0x40000 is the first byte past the flash.
        let e = parse_hex(&text(&[":020000040004F6", ":0100000055AA", EOF])).unwrap_err();
        assert_eq!(
            e,
            HexError::OutsideFlash {
                line: 2,
                address: 0x40000
            }
        );
        // The last byte of the flash is fine: base 0x30000, offset 0xFFFF.
        let img = parse_hex(&text(&[":020000040003F7", ":01FFFF0055AC", EOF])).unwrap();
        assert_eq!(img.pages().map(|(n, _)| n).collect::<Vec<_>>(), vec![1023]);
    }

    #[test]
    fn a_record_straddling_the_end_of_flash_is_refused_at_the_first_byte_outside() {
        // Base 0x30000, offset 0xFFFF, two bytes: the second is 0x40000. Linear records
        // run on past 64 KiB (no wrap), so this is outside, not a wrap.
        let e = parse_hex(&text(&[":020000040003F7", ":02FFFF00556645", EOF])).unwrap_err();
        assert_eq!(
            e,
            HexError::OutsideFlash {
                line: 2,
                address: 0x40000
            }
        );
    }

    #[test]
    fn overlapping_records_name_both_lines() {
        // Line 1 writes 0x0000–0x0003, line 2 writes 0x0002–0x0003.
        let e = parse_hex(&text(&[":0400000001020304F2", ":020002000506F1", EOF])).unwrap_err();
        assert_eq!(
            e,
            HexError::Overlap {
                line: 2,
                first_line: 1,
                address: 2
            }
        );
    }

    #[test]
    fn the_same_byte_through_two_address_forms_overlaps() {
        // 0x10010 via a linear base, then via a segment base.
        let e = parse_hex(&text(&[
            ":020000040001F9",
            ":02001000AABB89",
            ":020000021000EC",
            ":01001100CC22",
            EOF,
        ]))
        .unwrap_err();
        assert!(
            matches!(
                e,
                HexError::Overlap {
                    line: 4,
                    first_line: 2,
                    address: 0x10011
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn an_image_without_data_is_refused() {
        let e = parse_hex(&text(&[":020000040001F9", EOF])).unwrap_err();
        assert_eq!(e, HexError::Empty { last_line: 2 });
        assert!(parse_hex("").is_err());
    }

    #[test]
    fn crlf_blank_lines_and_start_records_are_fine() {
        let img =
            parse_hex(":0400000001020304F2\r\n\r\n:0400000300000000F9\r\n:00000001FF\r\n").unwrap();
        assert_eq!(img.data_bytes(), 4);
    }

    #[test]
    fn generated_text_reads_back_to_the_same_flash() {
        let bytes: Vec<u8> = (0..3000u32).map(|i| (i * 7 + 3) as u8).collect();
        // Start just below a 64 KiB boundary so the writer must split and re-base.
        let at = 0x1_0000 - 100;
        let img = parse_hex(&to_hex_text(at, &bytes)).unwrap();
        let flash = img.to_flash();
        assert_eq!(&flash[at as usize..at as usize + bytes.len()], &bytes[..]);
        assert_eq!(flash[at as usize - 1], 0xFF);
        assert_eq!(img.data_bytes(), bytes.len());
        // 0xFF9C..0x10B54 spans pages 255..=267.
        assert_eq!(img.page_count(), 13);
    }
}

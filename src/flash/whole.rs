//! Whether an image can be a whole program, judged before anything reaches the unit:
//! the update erases the whole application flash first (FLASH_ERASE, ICD §7.5.2), so an
//! image that is only part of a program leaves a unit that does not start, which only
//! Vertical Power can recover (§7.3).
//!
//! The figures, from the hardware (the ICD names the processor only by its signature,
//! icd-reading R17: an ATmega2560, 256 KiB of flash in 256-byte pages):
//!
//! * **Program range**: the flash below the bootloader section. The ICD does not give
//!   the bootloader's size; the ATmega2560's boot section is 512 to 4096 words at the
//!   top of flash, set by its BOOTSZ fuses (datasheet, "Boot Size Configuration"), and
//!   4096 words (8 KiB, from byte 0x3E000) is the chip's factory setting. We take that,
//!   the largest: 0x00000–0x3DFFF, 992 pages. Data at 0x3E000 or above would go to the
//!   bootloader's own section, which no application image writes.
//! * **Reset/vector page**: the ATmega2560 starts at byte 0 (its reset vector, then 56
//!   interrupt vectors, 4 bytes each: datasheet "Reset and Interrupt Vectors"). An image
//!   that leaves the reset vector erased (not given, or 0xFF) never starts.
//! * **Least size**: [`MIN_DATA`]. The VP-X software drives 28 circuits, 3 motors, the
//!   EEPROM settings and two serial protocols; the C runtime and the vector table
//!   alone are a few hundred bytes. Decision: an image with less than 8 KiB of data
//!   (3 % of the program range) is far smaller than any build of it could be: a test
//!   record, a truncated download that kept its end-of-file record, the wrong file.
//!
//! `--force-image` takes the risk (`cmd::flash`).

use std::fmt;

use super::hex::Image;
use crate::protocol::bootloader::{FLASH_SIZE, PAGE_SIZE};

/// The first byte of the bootloader section: 4096 words (8 KiB) below the top of the
/// ATmega2560's 256 KiB flash (see the module doc).
pub const PROGRAM_END: u32 = (FLASH_SIZE - 8 * 1024) as u32;
/// Pages in the program range.
pub const PROGRAM_PAGES: usize = PROGRAM_END as usize / PAGE_SIZE;
/// The least data an image may hold to be taken as a whole program (see the module
/// doc).
pub const MIN_DATA: usize = 8 * 1024;
/// The reset vector: a JMP, 4 bytes at byte address 0.
const RESET_VECTOR: usize = 4;

/// What an image covers of the program range, for people.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Coverage {
    pub data_bytes: usize,
    /// Pages of the program range the image writes.
    pub program_pages: usize,
    /// Pages it writes at or above [`PROGRAM_END`].
    pub outside_pages: usize,
    /// The highest byte address it writes.
    pub highest: u32,
    /// Whether the reset vector (bytes 0–3) is given and not erased.
    pub reset_vector: bool,
}

impl Coverage {
    pub fn of(image: &Image) -> Coverage {
        let outside_pages = image
            .pages()
            .filter(|(n, _)| usize::from(*n) >= PROGRAM_PAGES)
            .count();
        Coverage {
            data_bytes: image.data_bytes(),
            program_pages: image.page_count() - outside_pages,
            outside_pages,
            highest: image.span().1,
            reset_vector: image
                .page(0)
                .is_some_and(|p| p[..RESET_VECTOR].iter().any(|&b| b != 0xFF)),
        }
    }

    /// Why the image cannot be a whole program, each with its numbers; empty when it
    /// can be.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.data_bytes < MIN_DATA {
            out.push(format!(
                "it holds {} bytes of data: far smaller than a whole program (at least {} bytes; \
                 the unit's program memory is {} bytes, 0x00000–{:#07x})",
                self.data_bytes,
                MIN_DATA,
                PROGRAM_END,
                PROGRAM_END - 1
            ));
        }
        if !self.reset_vector {
            out.push(format!(
                "its reset/vector page (page 0, 0x00000–{:#07x}) leaves the reset vector empty: \
                 the unit would not start",
                PAGE_SIZE - 1
            ));
        }
        if self.outside_pages > 0 {
            out.push(format!(
                "it has data outside the program range (0x00000–{:#07x}): {} page{} up to \
                 {:#07x}, in the bootloader's section",
                PROGRAM_END - 1,
                self.outside_pages,
                if self.outside_pages == 1 { "" } else { "s" },
                self.highest
            ));
        }
        out
    }
}

impl fmt::Display for Coverage {
    /// "8448 bytes of data, 33 of 992 program pages (3.3 %), reset vector given".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} bytes of data, {} of {PROGRAM_PAGES} program pages ({:.1} %), reset vector {}",
            self.data_bytes,
            self.program_pages,
            self.program_pages as f64 * 100.0 / PROGRAM_PAGES as f64,
            if self.reset_vector {
                "given"
            } else {
                "MISSING"
            }
        )?;
        if self.outside_pages > 0 {
            write!(
                f,
                ", {} page(s) OUTSIDE the program range",
                self.outside_pages
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flash::parse_hex;

    #[test]
    fn the_figures_are_the_atmega2560s_with_its_largest_boot_section() {
        assert_eq!(PROGRAM_END, 0x3E000);
        assert_eq!(PROGRAM_PAGES, 992);
    }

    /// Records written by hand: one 4-byte data record at 0, and the end of file.
    #[test]
    fn four_bytes_are_far_too_small_though_they_give_the_reset_vector() {
        let img = parse_hex(":040000000C947200EA\n:00000001FF\n").unwrap();
        let c = Coverage::of(&img);
        assert!(c.reset_vector);
        let p = c.problems();
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(p[0].starts_with("it holds 4 bytes of data"), "{p:?}");
        assert!(p[0].contains("253952 bytes, 0x00000–0x3dfff"), "{p:?}");
        assert_eq!(
            c.to_string(),
            "4 bytes of data, 1 of 992 program pages (0.1 %), reset vector given"
        );
    }
}

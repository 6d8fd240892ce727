//! The bootloader of ICD §7, entered by SOFTWARE_UPDATE (§6.1.3).
//!
//! Frames are `0x69 0x96 <cmd> <num> <jump=0> <num 16-bit words of data>` (Table 35).
//! The flash is modelled as 256 KiB in 256-byte pages (icd-reading R17: the SIGNATURE
//! reply is the ATmega2560's), erased to 0xFF; programming ANDs the new bytes into the
//! page as real flash does, so a flasher that forgets FLASH_ERASE reads back garbage.
//!
//! Decisions where the ICD is silent or loose (icd-reading R24):
//!
//! * **Address unit.** FLASH_PROG's and FLASH_READ's 16-bit little-endian address is a
//!   **page number** (byte address / 256): 16 bits of bytes or words cannot reach all of
//!   256 KiB, pages can. FLASH_READ's size is in bytes.
//! * **SERIAL_CONF gate.** FLASH_ERASE, FLASH_PROG and FLASH_READ are ignored until a
//!   SERIAL_CONF with ports 3/0 and the security bytes 75 DB 9C 97 (Table 37) has been
//!   answered "!!!"; a wrong code gets no answer. QUERY_PORT, SIGNATURE, VERSION and EXIT
//!   are answered at any time, so a flasher can always find out where it is.
//! * **Malformed frames** (a command character with the wrong word count, a non-zero jump
//!   byte, an address past the end of flash) are ignored and counted, never answered.
//! * **Bootloader version** is 1.0 (bytes `0x01 0x00`).

use crate::protocol::bootloader::{
    BootCommand, BootCommandDecoder, BootResponse, FLASH_SIZE, PAGE_SIZE, PRIMARY_PORT,
    SECONDARY_PORT, SECURITY,
};

/// Bootloader version the sim reports (§7.5.7), high byte first: 1.0.
pub const BOOT_VERSION: u16 = 0x0100;

/// The program flash.
#[derive(Clone)]
pub struct Flash {
    pub bytes: Vec<u8>,
}

impl Default for Flash {
    fn default() -> Self {
        Flash {
            bytes: vec![0xFF; FLASH_SIZE],
        }
    }
}

impl std::fmt::Debug for Flash {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let used = self.bytes.iter().filter(|&&b| b != 0xFF).count();
        write!(f, "Flash({used} bytes programmed)")
    }
}

/// What the bootloader did with its input.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BootStats {
    pub commands: u64,
    /// Commands refused: locked, bad security code, page outside the flash.
    pub refused: u64,
    /// Frames with a command character that is not one of Table 36's.
    pub ignored_frames: u64,
    /// Bytes dropped while looking for a frame.
    pub skipped_bytes: u64,
    pub pages_programmed: u64,
    pub erases: u64,
}

/// The bootloader's state while the unit is in it.
#[derive(Debug, Default)]
pub struct Bootloader {
    decoder: BootCommandDecoder,
    configured: bool,
    refused: u64,
    /// The next FLASH_PROG has one byte flipped on its way into flash (test injection).
    pub corrupt_next_prog: bool,
    pages_programmed: u64,
    erases: u64,
}

impl Bootloader {
    pub fn stats(&self) -> BootStats {
        let d = self.decoder.stats();
        BootStats {
            commands: d.commands,
            refused: self.refused,
            ignored_frames: d.ignored_frames,
            skipped_bytes: d.skipped_bytes,
            pages_programmed: self.pages_programmed,
            erases: self.erases,
        }
    }

    /// Takes bytes from the wire; appends replies to `out`. Returns `true` on EXIT; the
    /// bytes after EXIT are dropped, as the unit is rebooting.
    pub fn feed(&mut self, bytes: &[u8], flash: &mut Flash, out: &mut Vec<u8>) -> bool {
        for &b in bytes {
            if let Some(cmd) = self.decoder.push(b) {
                match self.command(cmd, flash) {
                    Some(BootResponse::Exit) => {
                        out.extend(BootResponse::Exit.emit());
                        return true;
                    }
                    Some(r) => out.extend(r.emit()),
                    None => self.refused += 1,
                }
            }
        }
        false
    }

    fn command(&mut self, cmd: BootCommand, flash: &mut Flash) -> Option<BootResponse> {
        Some(match cmd {
            BootCommand::SerialConf {
                primary_port,
                secondary_port,
                security,
            } => {
                if (primary_port, secondary_port, security)
                    != (PRIMARY_PORT, SECONDARY_PORT, SECURITY)
                {
                    return None;
                }
                self.configured = true;
                BootResponse::SerialConf
            }
            BootCommand::QueryPort => BootResponse::Port,
            BootCommand::Signature => {
                BootResponse::Signature(crate::protocol::bootloader::SIGNATURE)
            }
            BootCommand::Version => BootResponse::Version(BOOT_VERSION),
            BootCommand::Exit => BootResponse::Exit,
            _ if !self.configured => return None,
            BootCommand::FlashErase => {
                flash.bytes.fill(0xFF);
                self.erases += 1;
                BootResponse::Erased
            }
            BootCommand::FlashProg { address, mut data } => {
                let at = address as usize * PAGE_SIZE;
                if data.len() != PAGE_SIZE || at + PAGE_SIZE > FLASH_SIZE {
                    return None;
                }
                if std::mem::take(&mut self.corrupt_next_prog) {
                    data[PAGE_SIZE / 2] ^= 0x5A;
                }
                for (f, b) in flash.bytes[at..at + PAGE_SIZE].iter_mut().zip(data) {
                    *f &= b;
                }
                self.pages_programmed += 1;
                BootResponse::Programmed
            }
            BootCommand::FlashRead { address, size } => {
                let at = address as usize * PAGE_SIZE;
                if at + size as usize > FLASH_SIZE {
                    return None;
                }
                BootResponse::Flash(flash.bytes[at..at + size as usize].to_vec())
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::protocol::bootloader::SIGNATURE;

    fn conf() -> Vec<u8> {
        BootCommand::serial_conf().emit()
    }

    fn prog(page: u16, fill: u8) -> Vec<u8> {
        BootCommand::flash_prog(page, &[fill; PAGE_SIZE])
            .unwrap()
            .emit()
    }

    fn frame(cmd: BootCommand) -> Vec<u8> {
        cmd.emit()
    }

    #[test]
    fn erase_program_read_exit() {
        let mut b = Bootloader::default();
        let mut flash = Flash::default();
        let mut out = Vec::new();
        let mut input = vec![0x00, 0x69]; // noise, and a lone header byte
        input.extend(conf());
        input.extend(frame(BootCommand::QueryPort));
        input.extend(frame(BootCommand::Signature));
        input.extend(frame(BootCommand::FlashErase));
        input.extend(prog(3, 0xA5));
        input.extend(frame(BootCommand::flash_read_page(3)));
        // Split anywhere: one byte at a time.
        for byte in &input {
            assert!(!b.feed(&[*byte], &mut flash, &mut out));
        }
        let mut want = b"!!!VP_AVRBOOT".to_vec();
        want.extend(SIGNATURE);
        want.extend(b"eP");
        want.extend([0xA5; PAGE_SIZE]);
        assert_eq!(out, want);
        assert!(b.feed(&frame(BootCommand::Exit), &mut flash, &mut out));
        assert_eq!(out.last(), Some(&b'x'));
    }

    #[test]
    fn a_wrong_security_code_locks_erase_and_program() {
        let mut b = Bootloader::default();
        let mut flash = Flash::default();
        let mut out = Vec::new();
        b.feed(
            &frame(BootCommand::SerialConf {
                primary_port: 3,
                secondary_port: 0,
                security: [0x75, 0xDB, 0x9C, 0x98],
            }),
            &mut flash,
            &mut out,
        );
        b.feed(&frame(BootCommand::FlashErase), &mut flash, &mut out);
        b.feed(&prog(0, 0), &mut flash, &mut out);
        assert!(out.is_empty());
        assert!(flash.bytes.iter().all(|&x| x == 0xFF));
        assert_eq!(b.stats().refused, 3);
    }

    #[test]
    fn an_injected_corruption_changes_exactly_one_programmed_byte() {
        let mut b = Bootloader::default();
        let mut flash = Flash::default();
        let mut out = Vec::new();
        b.feed(&conf(), &mut flash, &mut out);
        b.corrupt_next_prog = true;
        b.feed(&prog(0, 0x11), &mut flash, &mut out);
        b.feed(&prog(1, 0x11), &mut flash, &mut out);
        let bad = flash.bytes[..2 * PAGE_SIZE]
            .iter()
            .filter(|&&x| x != 0x11)
            .count();
        assert_eq!(bad, 1);
    }
}

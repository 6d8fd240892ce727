//! System messages, ICD §6.1 (major 0x10).

use super::types::HardwareVersion;
use super::{IGNORED_PAYLOAD_MAX, Payload, Reader, Writer, exact, flag};
use crate::error::{Error, LenRule, Result};
use crate::frame::MessageId;

/// PING — ICD Table 10. The EFIS sends `ack = false`; the VP-X answers `ack = true`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ping {
    /// Table 10 byte 1: 0 on a request, 1 on the VP-X's response.
    pub ack: bool,
}

impl Payload for Ping {
    const ID: MessageId = MessageId::new(0x10, 0x00);
    const NAME: &'static str = "PING";
    const LEN: LenRule = LenRule::Exact(1);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 1>(p)?;
        Ok(Ping {
            ack: flag(Self::NAME, "ACK flag", p[0])?,
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.ack as u8);
    }
}

/// VERSION — ICD Table 11. The request's payload is ignored by the unit (§6.1.2:
/// "Payload data sent by the external system is ignored by the VP-X"); we send three
/// zeros, the table's size.
///
/// Decision (icd-reading R29), for what we receive: a payload of any length up to
/// [`IGNORED_PAYLOAD_MAX`] passes the frame check (so a request of another length
/// reaches the virtual VP-X, which answers it); the three fields of Table 11 decode
/// from a payload of at least 3 bytes, bytes after them are ignored, and a shorter
/// one is a [`Error::BadLength`] (no version is made up).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Version {
    /// Table 11 byte 1: hardware version (note 1).
    pub hardware_version: HardwareVersion,
    /// Table 11 byte 2: software major version.
    pub software_major: u8,
    /// Table 11 byte 3: software minor version.
    pub software_minor: u8,
}

impl Version {
    /// The request the EFIS sends: three zero bytes, which the VP-X ignores (§6.1.2).
    pub const REQUEST: Version = Version {
        hardware_version: HardwareVersion::Unknown(0),
        software_major: 0,
        software_minor: 0,
    };
}

impl Payload for Version {
    const ID: MessageId = MessageId::new(0x10, 0x01);
    const NAME: &'static str = "VERSION";
    /// Any length: see the type's documentation.
    const LEN: LenRule = LenRule::Between(0, IGNORED_PAYLOAD_MAX);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        if p.len() < 3 {
            return Err(Error::BadLength {
                message: Self::NAME,
                expected: LenRule::Between(3, IGNORED_PAYLOAD_MAX),
                got: p.len(),
            });
        }
        let mut r = Reader::new(p);
        Ok(Version {
            hardware_version: HardwareVersion::from_byte(r.u8()),
            software_major: r.u8(),
            software_minor: r.u8(),
        })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.hardware_version.to_byte());
        w.u8(self.software_major);
        w.u8(self.software_minor);
    }
}

/// SOFTWARE_UPDATE — ICD §6.1.3: no payload; the unit enters its bootloader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SoftwareUpdate;

impl Payload for SoftwareUpdate {
    const ID: MessageId = MessageId::new(0x10, 0x02);
    const NAME: &'static str = "SOFTWARE_UPDATE";
    const LEN: LenRule = LenRule::Exact(0);
    fn parse_payload(_: &[u8]) -> Result<Self> {
        Ok(SoftwareUpdate)
    }
    fn emit_payload(&self, _: &mut Writer) {}
}

/// EEPROM_ERASE — ICD Table 12. Response code 0 means success.
///
/// The request carries no meaning in its byte (§6.1.4 gives the table for the
/// response), and an EFIS may send it with no payload at all. Decision (icd-reading
/// R30): the frame check takes 0 or 1 bytes; the typed message needs its response
/// code, so an empty payload is a [`Error::BadLength`] here (an empty *reply* never
/// reads as success) and the virtual VP-X answers an empty *request* all the same. We
/// send 1 byte.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EepromErase {
    /// Table 12 byte 1: 0 success, anything else failure.
    pub response_code: u8,
}

impl Payload for EepromErase {
    const ID: MessageId = MessageId::new(0x10, 0x03);
    const NAME: &'static str = "EEPROM_ERASE";
    const LEN: LenRule = LenRule::Between(0, 1);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let Some(&response_code) = p.first() else {
            return Err(Error::BadLength {
                message: Self::NAME,
                expected: LenRule::Exact(1),
                got: 0,
            });
        };
        Ok(EepromErase { response_code })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.response_code);
    }
}

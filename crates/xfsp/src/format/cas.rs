//! CASMSG (§3.3.5, format 5): a crew alerting message or checklist item. Carried by
//! CASMSG (0x05) and CHKLIST (0xb6).
//!
//! level u8, rsvd u8, flags u16, label: the draft's "length(data) + 4" fixes `flags`
//! at 16 bits.

use crate::cursor::Reader;
use crate::dict::{CasFlags, CasLevel};
use crate::format::latin1_bytes;

pub(crate) const FIXED_LEN: usize = 4;

/// A CASMSG value (§3.3.5, Table 14).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CasMsg {
    /// Table 14 `level`: the CAS level or checklist item kind (Table 15).
    pub level: CasLevel,
    /// "Reserved, set to 0"; kept so that a nonzero value survives relaying.
    pub rsvd: u8,
    /// Table 14 `flags`: CAS related flags (Table 16), 16 bits.
    pub flags: CasFlags,
    /// ISO-8859-1 text as sent.
    pub label: Vec<u8>,
}

impl CasMsg {
    /// A message at `level` with `text` (non-Latin-1 characters become `?`).
    pub fn new(level: CasLevel, text: &str) -> CasMsg {
        CasMsg {
            level,
            rsvd: 0,
            flags: CasFlags::default(),
            label: latin1_bytes(text),
        }
    }

    pub(crate) fn read(r: &mut Reader<'_>) -> Option<CasMsg> {
        Some(CasMsg {
            level: r.u8()?.into(),
            rsvd: r.u8()?,
            flags: CasFlags(r.u16()?),
            label: r.rest().to_vec(),
        })
    }

    pub(crate) fn write(&self, out: &mut Vec<u8>) {
        out.push(self.level.into());
        out.push(self.rsvd);
        out.extend_from_slice(&self.flags.0.to_be_bytes());
        out.extend_from_slice(&self.label);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{FormatId, Value};

    #[test]
    fn caution_message_by_hand() {
        // CAUTION 6, rsvd 0, flags AUTO 0x0001, "LOW VOLTS".
        let bytes = b"\x06\x00\x00\x01LOW VOLTS";
        let mut m = CasMsg::new(CasLevel::Caution, "LOW VOLTS");
        m.flags = CasFlags(CasFlags::AUTO);
        assert_eq!(Value::CasMsg(m.clone()).to_bytes(), bytes);
        assert_eq!(Value::parse(FormatId::CasMsg, bytes), Ok(Value::CasMsg(m)));
    }
}

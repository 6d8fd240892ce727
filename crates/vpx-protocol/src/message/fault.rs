//! Fault messages, ICD §6.5 (major 0x14).

use super::{Payload, Writer, exact};
use crate::error::{LenRule, Result};
use crate::frame::MessageId;

/// DEVICE_CLEAR — ICD Table 33. Device 255 clears the system fault.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceClear {
    /// Table 33 byte 1: the faulted device, 0–30, or 255 for the system fault.
    pub device_id: u8,
}

impl Payload for DeviceClear {
    const ID: MessageId = MessageId::new(0x14, 0x00);
    const NAME: &'static str = "DEVICE_CLEAR";
    const LEN: LenRule = LenRule::Exact(1);
    fn parse_payload(p: &[u8]) -> Result<Self> {
        let p = exact::<Self, 1>(p)?;
        Ok(DeviceClear { device_id: p[0] })
    }
    fn emit_payload(&self, w: &mut Writer) {
        w.u8(self.device_id);
    }
}

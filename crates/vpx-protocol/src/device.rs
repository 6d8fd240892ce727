//! The system device table, ICD Appendix B (Table 40).

/// Which switch a device can follow (the "Switch" column of Table 40).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SwitchRule {
    /// Flaps: driven by the flap switches, not assignable.
    Flaps,
    /// Starter: "always on" as far as the EFIS is concerned, not assignable.
    StarterAlwaysOn,
    /// Any of off, 1–10 and always on.
    Any,
    /// Trim_R: driven by the roll trim switches, not assignable.
    RollTrim,
    /// Trim_P: driven by the pitch trim switches, not assignable.
    PitchTrim,
}

/// One row of ICD Table 40.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeviceInfo {
    /// Table 40 "Device ID", 0x00–0x1E.
    pub id: u8,
    /// Table 40 "System Name", e.g. `5A-2` or `Trim_P`.
    pub system_name: &'static str,
    /// Table 40 "Amps": lowest breaker setting, whole amps.
    pub amps_min: u8,
    /// Table 40 "Amps": highest breaker setting, whole amps.
    pub amps_max: u8,
    /// Table 40's default breaker. For the EFIS this says 2 A while Appendix F says 5 A
    /// (icd-reading R21); see `defaults` for the value the virtual unit resets to.
    pub default_breaker: u8,
    /// Table 40 "Current Fault Support": whether DEVICE_SPEC's current fault flag applies.
    pub current_fault_support: bool,
    /// Table 40 "Switch": which switch the device follows.
    pub switch: SwitchRule,
}

impl DeviceInfo {
    /// Whether DEVICE_SPEC may set the device's switch (Table 40 "Switch" = Any).
    pub fn switch_assignable(&self) -> bool {
        self.switch == SwitchRule::Any
    }

    /// Trim_R and Trim_P: "circuit breaker value not changeable".
    pub fn breaker_changeable(&self) -> bool {
        self.amps_min != self.amps_max
    }
}

/// Device 0x00, Flaps (ICD Table 40).
pub const FLAPS: u8 = 0x00;
/// Device 0x01, Starter (ICD Table 40): cannot be switched from the EFIS, only reset
/// (icd-reading R18).
pub const STARTER: u8 = 0x01;
/// Device 0x02, EFIS (ICD Table 40): its switch must not be 0 (Table 13 note 4).
pub const EFIS: u8 = 0x02;
/// Device 0x03, Field_Pri, the primary alternator field (ICD Table 40).
pub const FIELD_PRI: u8 = 0x03;
/// Device 0x1D, Trim_R, the roll trim motor (ICD Table 40).
pub const TRIM_R: u8 = 0x1D;
/// Device 0x1E, Trim_P, the pitch trim motor (ICD Table 40).
pub const TRIM_P: u8 = 0x1E;
/// Number of device ids, 0 through 30 (ICD Table 40).
pub const DEVICE_COUNT: usize = 31;
/// DEVICE_SPEC_QUERY / SPEC_ACK id for the system spec (ICD Tables 18, 19).
pub const SYSTEM_SPEC_ID: u8 = 253;
/// DEVICE_SPEC_QUERY / SPEC_ACK id for the wig-wag spec (ICD Tables 18, 19).
pub const WIG_WAG_SPEC_ID: u8 = 254;
/// DEVICE_CLEAR id that clears the system fault (ICD Table 33 note 1).
pub const SYSTEM_FAULT_ID: u8 = 255;

const fn d(
    id: u8,
    system_name: &'static str,
    amps_min: u8,
    amps_max: u8,
    default_breaker: u8,
    current_fault_support: bool,
    switch: SwitchRule,
) -> DeviceInfo {
    DeviceInfo {
        id,
        system_name,
        amps_min,
        amps_max,
        default_breaker,
        current_fault_support,
        switch,
    }
}

use SwitchRule::*;

/// ICD Table 40, indexed by device id.
pub const DEVICES: [DeviceInfo; DEVICE_COUNT] = [
    d(0x00, "Flaps", 1, 10, 7, false, Flaps),
    d(0x01, "Starter", 1, 10, 5, false, StarterAlwaysOn),
    d(0x02, "EFIS", 1, 5, 2, true, Any),
    d(0x03, "Field_Pri", 1, 5, 5, false, Any),
    d(0x04, "5A-1", 1, 5, 2, true, Any),
    d(0x05, "5A-2", 1, 5, 2, true, Any),
    d(0x06, "5A-3", 1, 5, 2, true, Any),
    d(0x07, "5A-4", 1, 5, 2, true, Any),
    d(0x08, "5A-5", 1, 5, 2, true, Any),
    d(0x09, "5A-6", 1, 5, 2, true, Any),
    d(0x0A, "5A-7", 1, 5, 2, true, Any),
    d(0x0B, "5A-8", 1, 5, 2, true, Any),
    d(0x0C, "5A-9", 1, 5, 2, true, Any),
    d(0x0D, "5A-10", 1, 5, 2, true, Any),
    d(0x0E, "5A-11", 1, 5, 2, true, Any),
    d(0x0F, "5A-12", 1, 5, 2, true, Any),
    d(0x10, "5A-13", 1, 5, 2, true, Any),
    d(0x11, "10A-1", 1, 10, 2, true, Any),
    d(0x12, "10A-2", 1, 10, 2, true, Any),
    d(0x13, "10A-3", 1, 10, 2, true, Any),
    d(0x14, "10A-4", 1, 10, 2, true, Any),
    d(0x15, "10A-5", 1, 10, 2, true, Any),
    d(0x16, "10A-6", 1, 10, 2, true, Any),
    d(0x17, "15A-1", 5, 15, 2, true, Any),
    d(0x18, "15A-2", 5, 15, 2, true, Any),
    d(0x19, "15A-3", 5, 15, 2, true, Any),
    d(0x1A, "3A-1", 1, 3, 2, true, Any),
    d(0x1B, "2A-1", 1, 2, 2, true, Any),
    d(0x1C, "2A-2", 1, 2, 2, true, Any),
    d(0x1D, "Trim_R", 2, 2, 2, false, RollTrim),
    d(0x1E, "Trim_P", 2, 2, 2, false, PitchTrim),
];

/// The Table 40 row of a device id, if it is one.
pub fn device(id: u8) -> Option<&'static DeviceInfo> {
    DEVICES.get(id as usize)
}

/// Pins that may be the secondary alternator (ICD Table 14: 4–25, 27–28).
pub fn secondary_alternator_allowed(id: u8) -> bool {
    matches!(id, 4..=25 | 27..=28)
}

/// Pins that may be wig-wag devices (ICD Table 17: 4–28).
pub fn wig_wag_allowed(id: u8) -> bool {
    matches!(id, 4..=28)
}

/// Pins whose display the EFIS may enable or disable (ICD Table 23: 4–28).
pub fn enable_flag_allowed(id: u8) -> bool {
    matches!(id, 4..=28)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_40_is_indexed_by_id() {
        for (i, d) in DEVICES.iter().enumerate() {
            assert_eq!(d.id as usize, i, "{}", d.system_name);
        }
    }

    #[test]
    fn table_40_spot_checks() {
        assert_eq!(
            device(0x17).map(|d| (d.system_name, d.amps_min, d.amps_max)),
            Some(("15A-1", 5, 15))
        );
        assert_eq!(device(0x1A).map(|d| (d.amps_min, d.amps_max)), Some((1, 3)));
        assert!(!device(TRIM_P).unwrap().breaker_changeable());
        assert!(!device(STARTER).unwrap().switch_assignable());
        assert!(device(EFIS).unwrap().current_fault_support);
        assert!(!device(FIELD_PRI).unwrap().current_fault_support);
        assert!(device(31).is_none());
    }
}

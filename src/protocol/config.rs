//! The unit's whole configuration: what the §6.2 rules judge a new spec against, what
//! the virtual VP-X keeps in its EEPROM, and what a backup holds.

use super::defaults;
use super::device::{DEVICE_COUNT, enable_flag_allowed};
use super::message::{DeviceSpec, FlapSpec, SystemSpec, TrimSpec, TrimType, WigWagSpec};

#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct UnitConfig {
    /// DEVICE_SPEC per device id. Ids 0 (flaps), 29 and 30 (trims) are configured by
    /// FLAP_SPEC and TRIM_SPEC; their entries here only hold their fixed breaker.
    pub devices: [DeviceSpec; DEVICE_COUNT],
    pub system: SystemSpec,
    pub flap: FlapSpec,
    pub pitch_trim: TrimSpec,
    pub roll_trim: TrimSpec,
    pub wig_wag: WigWagSpec,
    /// DEVICE_NAME per device id, raw 16 bytes (all zero when never named).
    pub names: [[u8; 16]; DEVICE_COUNT],
    /// DEVICE_ENABLE per device id. The ICD gives no default (Appendix F is silent);
    /// we take "enabled" so that a fresh unit hides nothing from the person wiring it.
    /// Ids outside 4–28 are always shown and their flag here is ignored.
    pub enabled: [bool; DEVICE_COUNT],
}

impl Default for UnitConfig {
    /// ICD Appendix F: what EEPROM_ERASE restores.
    fn default() -> Self {
        UnitConfig {
            devices: defaults::device_specs(),
            system: defaults::system_spec(),
            flap: defaults::flap_spec(),
            pitch_trim: defaults::trim_spec(TrimType::Pitch),
            roll_trim: defaults::trim_spec(TrimType::Roll),
            wig_wag: defaults::wig_wag_spec(),
            names: [[0; 16]; DEVICE_COUNT],
            enabled: std::array::from_fn(|i| enable_flag_allowed(i as u8)),
        }
    }
}

impl UnitConfig {
    pub fn trim(&self, t: TrimType) -> &TrimSpec {
        match t {
            TrimType::Roll => &self.roll_trim,
            _ => &self.pitch_trim,
        }
    }

    /// Whether `id` is currently one of the two wig-wag devices.
    pub fn is_wig_wag_device(&self, id: u8) -> bool {
        self.wig_wag.device_one == Some(id) || self.wig_wag.device_two == Some(id)
    }

    /// Whether `id` is currently the secondary alternator.
    pub fn is_secondary_alternator(&self, id: u8) -> bool {
        self.system.secondary_alternator == Some(id)
    }
}

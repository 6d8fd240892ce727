//! The unit's whole configuration: what the §6.2 rules judge a new spec against, what
//! the virtual VP-X keeps in its EEPROM, and what a backup holds.

use super::defaults;
use super::device::{DEVICE_COUNT, FLAPS, enable_flag_allowed};
use super::message::{
    DeviceEnable, DeviceName, DeviceSpec, EnableFlag, FlapSpec, SystemSpec, TrimSpec, TrimType,
    WigWagSpec,
};

/// Everything the §6.2 configuration messages set on one unit (ICD Tables 13–17, 21, 23).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct UnitConfig {
    /// DEVICE_SPEC per device id. Ids 0 (flaps), 29 and 30 (trims) are configured by
    /// FLAP_SPEC and TRIM_SPEC; their entries here only hold their fixed breaker.
    pub devices: [DeviceSpec; DEVICE_COUNT],
    /// SYSTEM_SPEC (ICD Table 14).
    pub system: SystemSpec,
    /// FLAP_SPEC (ICD Table 16), the settings of device 0.
    pub flap: FlapSpec,
    /// TRIM_SPEC for pitch (ICD Table 15, trim type 0), the settings of device 30.
    pub pitch_trim: TrimSpec,
    /// TRIM_SPEC for roll (ICD Table 15, trim type 1), the settings of device 29.
    pub roll_trim: TrimSpec,
    /// WIG_WAG_SPEC (ICD Table 17).
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
            enabled: core::array::from_fn(|i| enable_flag_allowed(i as u8)),
        }
    }
}

impl UnitConfig {
    /// The TRIM_SPEC of trim type `t` (ICD Table 15); an unknown type reads as pitch.
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

    /// Stores an accepted DEVICE_SPEC (ICD Table 13).
    ///
    /// The `apply_*` methods do not judge: the unit only stores what
    /// `validate` accepted, so call the matching `validate::*` function first (or
    /// `validate::accept`, which does both). An id with no slot is dropped rather than
    /// panicking, because these also run on whatever a backup file contains.
    pub fn apply_device_spec(&mut self, spec: &DeviceSpec) {
        if let Some(slot) = self.devices.get_mut(spec.device_id as usize) {
            *slot = *spec;
        }
    }

    /// Stores an accepted SYSTEM_SPEC (ICD Table 14).
    pub fn apply_system_spec(&mut self, spec: &SystemSpec) {
        self.system = *spec;
    }

    /// Stores an accepted TRIM_SPEC (ICD Table 15) in the axis its type flag names.
    /// A type the wire cannot carry (`Unknown`) has no axis and is dropped.
    pub fn apply_trim_spec(&mut self, spec: &TrimSpec) {
        match spec.trim_type {
            TrimType::Pitch => self.pitch_trim = *spec,
            TrimType::Roll => self.roll_trim = *spec,
            TrimType::Unknown(_) => {}
        }
    }

    /// Stores an accepted FLAP_SPEC (ICD Table 16). The flap breaker is also copied
    /// into `devices[0]` so that the two places that hold it never disagree.
    pub fn apply_flap_spec(&mut self, spec: &FlapSpec) {
        self.flap = *spec;
        if let Some(flaps) = self.devices.get_mut(FLAPS as usize) {
            flaps.circuit_breaker = spec.circuit_breaker;
        }
    }

    /// Stores an accepted WIG_WAG_SPEC (ICD Table 17).
    pub fn apply_wig_wag_spec(&mut self, spec: &WigWagSpec) {
        self.wig_wag = *spec;
    }

    /// Stores a DEVICE_NAME (ICD Table 21).
    pub fn apply_device_name(&mut self, name: &DeviceName) {
        if let Some(slot) = self.names.get_mut(name.device_id as usize) {
            *slot = name.name;
        }
    }

    /// Stores a DEVICE_ENABLE set request (ICD Table 23). Queries (flag 2), unknown
    /// flags and ids outside 4–28 change nothing: Table 23 note 1 says those devices
    /// are always shown.
    pub fn apply_device_enable(&mut self, e: &DeviceEnable) {
        if !enable_flag_allowed(e.device_id) {
            return;
        }
        let on = match e.flag {
            EnableFlag::Enabled => true,
            EnableFlag::Disabled => false,
            _ => return,
        };
        if let Some(slot) = self.enabled.get_mut(e.device_id as usize) {
            *slot = on;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::message::{FlapMode, Polarity, Tenths};

    #[test]
    fn apply_stores_where_queries_read() {
        let mut c = UnitConfig::default();
        let spec = DeviceSpec {
            device_id: 9,
            circuit_breaker: 4,
            switch_id: crate::message::SwitchId::Input(3),
            current_fault: true,
            switch_raw: None,
        };
        c.apply_device_spec(&spec);
        assert_eq!(c.devices[9], spec);

        let roll = TrimSpec {
            trim_type: TrimType::Roll,
            enabled: true,
            polarity: Polarity::Inverted,
            up: 10,
            down: 200,
            neutral: 100,
            power: 100,
            speed: 0,
        };
        c.apply_trim_spec(&roll);
        assert_eq!(c.trim(TrimType::Roll), &roll);
        assert_ne!(c.trim(TrimType::Pitch), &roll);

        c.apply_flap_spec(&FlapSpec {
            mode: FlapMode::PositionBased,
            enabled: true,
            polarity: Polarity::Standard,
            up: 10,
            down: 200,
            midpoint_1: 50,
            midpoint_2: 100,
            circuit_breaker: 9,
            overspeed_position: 20,
            max_speed: 100,
            endpoint_duration: Tenths(5),
        });
        assert_eq!(
            c.devices[0].circuit_breaker, 9,
            "flap breaker kept in one value"
        );

        c.apply_device_name(&DeviceName::new(5, "Strobe Lt").unwrap());
        assert_eq!(&c.names[5][..9], b"Strobe Lt");
    }

    #[test]
    fn apply_never_panics_on_ids_without_a_slot() {
        let mut c = UnitConfig::default();
        let before = c.clone();
        c.apply_device_spec(&DeviceSpec {
            device_id: 200,
            ..c.devices[4]
        });
        c.apply_device_name(&DeviceName {
            device_id: 31,
            name: [b'x'; 16],
        });
        c.apply_trim_spec(&TrimSpec {
            trim_type: TrimType::Unknown(7),
            ..c.pitch_trim
        });
        assert_eq!(c, before);
    }

    #[test]
    fn enable_flags_only_for_pins_4_to_28() {
        let mut c = UnitConfig::default();
        c.apply_device_enable(&DeviceEnable {
            device_id: 4,
            flag: EnableFlag::Disabled,
        });
        assert!(!c.enabled[4]);
        c.apply_device_enable(&DeviceEnable {
            device_id: 4,
            flag: EnableFlag::Query,
        });
        assert!(!c.enabled[4], "a query changes nothing");
        c.apply_device_enable(&DeviceEnable {
            device_id: 2,
            flag: EnableFlag::Disabled,
        });
        assert_eq!(c.enabled[2], UnitConfig::default().enabled[2]);
    }
}

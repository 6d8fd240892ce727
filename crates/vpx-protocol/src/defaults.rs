//! Factory defaults, ICD Appendix F (Table 44): what a unit holds after EEPROM_ERASE or
//! a failed integrity check.
//!
//! icd-reading R21: the EFIS breaker is 2 A in Table 40 but 5 A in Table 44. The
//! defaults appendix is the table that describes a reset unit, so 5 A is used here.

use super::device::{self, DEVICE_COUNT, EFIS, FIELD_PRI, STARTER};
use super::message::{
    DeviceSpec, FlapMode, FlapSpec, OvervoltageLimit, Polarity, SwitchId, SystemSpec, Tenths,
    TrimSpec, TrimType, WigWagSpec,
};

/// Flap "Max Run Time": 30 s (Table 44). Not settable through FLAP_SPEC.
pub const FLAP_MAX_RUN_TIME_S: u32 = 30;

/// Table 44 breaker, switch and current-fault for a pin configured by DEVICE_SPEC.
pub fn device_spec(device_id: u8) -> DeviceSpec {
    let (circuit_breaker, switch_id) = match device_id {
        STARTER => (5, SwitchId::AlwaysOn),
        EFIS => (5, SwitchId::AlwaysOn),
        FIELD_PRI => (5, SwitchId::Off),
        id => (
            device::device(id).map_or(2, |d| d.default_breaker),
            SwitchId::Off,
        ),
    };
    DeviceSpec {
        device_id,
        circuit_breaker,
        switch_id,
        current_fault: false,
        switch_raw: None,
    }
}

/// Table 44 defaults for every device id, indexed by id.
pub fn device_specs() -> [DeviceSpec; DEVICE_COUNT] {
    core::array::from_fn(|i| device_spec(i as u8))
}

/// SYSTEM_SPEC after EEPROM_ERASE (ICD Table 44): 16 V overvoltage limit, no secondary
/// alternator.
pub fn system_spec() -> SystemSpec {
    SystemSpec {
        overvoltage_limit: OvervoltageLimit::V16,
        secondary_alternator: None,
    }
}

/// FLAP_SPEC after EEPROM_ERASE (ICD Table 44): disabled, momentary, standard polarity, 7 A
/// breaker (Table 40), every position 0.
pub fn flap_spec() -> FlapSpec {
    FlapSpec {
        mode: FlapMode::Momentary,
        enabled: false,
        polarity: Polarity::Standard,
        up: 0,
        down: 0,
        midpoint_1: 0,
        midpoint_2: 0,
        circuit_breaker: 7,
        overspeed_position: 0,
        max_speed: 0,
        endpoint_duration: Tenths(0),
    }
}

/// Pitch and roll share their defaults; power is 100 % (icd-reading R16).
pub fn trim_spec(trim_type: TrimType) -> TrimSpec {
    TrimSpec {
        trim_type,
        enabled: false,
        polarity: Polarity::Standard,
        up: 0,
        down: 0,
        neutral: 0,
        power: 100,
        speed: 0,
    }
}

/// WIG_WAG_SPEC after EEPROM_ERASE (ICD Table 44).
pub fn wig_wag_spec() -> WigWagSpec {
    WigWagSpec {
        device_one: None,
        device_two: None,
        warm_up_period: 5,
        speed: 70,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_44_values() {
        assert_eq!(
            device_spec(EFIS).circuit_breaker,
            5,
            "icd-reading R21: Appendix F's 5 A"
        );
        assert_eq!(device_spec(EFIS).switch_id, SwitchId::AlwaysOn);
        assert_eq!(
            device_spec(FIELD_PRI),
            DeviceSpec {
                device_id: 3,
                circuit_breaker: 5,
                switch_id: SwitchId::Off,
                current_fault: false,
                switch_raw: None,
            }
        );
        assert_eq!(device_spec(0x17).circuit_breaker, 2);
        assert_eq!(flap_spec().circuit_breaker, 7);
        assert_eq!(trim_spec(TrimType::Pitch).power, 100);
        assert_eq!(
            wig_wag_spec(),
            WigWagSpec {
                device_one: None,
                device_two: None,
                warm_up_period: 5,
                speed: 70
            }
        );
        assert_eq!(system_spec().secondary_alternator, None);
    }
}

//! The §6.2 configuration rules as pure functions: what a VP-X answers with a non-zero
//! SPEC_ACK (ICD Tables 19, 20), judged against the unit's current [`UnitConfig`].
//!
//! Three users: the virtual unit answers SPEC_ACK with them, the setup screens refuse a
//! value before sending it and say why ([`explain`], [`Invalid`]), and restore checks a
//! backup as a whole before writing anything ([`whole_config`]).
//!
//! Each function runs its checks in the order its doc lists and reports the first that
//! fails, as a unit that refuses the whole message can only carry one code.
//!
//! Decisions where the ICD is silent or contradicts itself (each pinned by a test):
//!
//! * **Factory-default breaker** (icd-reading R25). The 15 A pins take 5–15 A (Table 40) yet default to
//!   2 A (Tables 40 and 44). As icd-reading R16 does for trim power, the pin's own
//!   factory default is accepted although outside its range: a restore of a backup
//!   taken from a fresh unit must not be refused, and the unit itself reports it.
//!   The same holds for pitch trim power 100 % against Table 15's 40–90 (icd-reading
//!   R16). A strict reading would answer these with 0x03 / 0x01; we take the
//!   unit's own values over the table's range.
//! * **DEVICE_SPEC for 0, 29 and 30** (icd-reading R26). Table 13's id range is 0–30, but the flaps and
//!   trims are configured by FLAP_SPEC and TRIM_SPEC (their DEVICE_SPEC_QUERY answers
//!   with those, icd-reading R13), and a breaker or switch for them would be stored
//!   where nothing reads it back: refused `InvalidDevice` (0x02).
//! * **"Same switch" for the alternators** (Table 13 note 6, Table 14 note 5;
//!   icd-reading R27) means the
//!   same switch 1–10 or both always on (11). Both always off (0) is not a shared
//!   switch: it is the factory state of the primary alternator and of every pin, and
//!   two alternators that never run cannot run together.
//! * **Current fault on a pin without support** (Table 40 "Current Fault Support" No:
//!   starter, Field_Pri) → `OutOfRange`, the field's range for that pin being 0 only.
//! * **Error codes the notes leave unnamed:** the starter's switch (Table 40 "not
//!   assignable") and the EFIS switched off (Table 13 note 4) → `InvalidSwitch`; a
//!   wig-wag or secondary-alternator id outside its table range → `InvalidDevice`.
//! * **Roll trim power and speed** are "ignored if roll trim is selected" (Table 15
//!   notes 5, 6), so they are not judged for roll.
//! * **Flap midpoints:** only the case Table 16 note 4 names is checked (both
//!   non-zero); one midpoint alone, or the trim endpoints, are not ordered by the ICD.
//! * **Wig-wag device one and two the same pin** → `BadConfig`: the function alternates
//!   two lights, and a pin cannot alternate with itself.
//! * **DEVICE_NAME** bytes are "0–255" (Table 21), so any byte is accepted; only the
//!   device id (0–30) is judged.

use alloc::{format, string::String, vec::Vec};

use core::fmt;

use super::config::UnitConfig;
use super::device::{
    self, EFIS, FIELD_PRI, FLAPS, STARTER, TRIM_P, TRIM_R, enable_flag_allowed,
    secondary_alternator_allowed, wig_wag_allowed,
};
use super::message::*;

/// Why a spec is refused: the SPEC_ACK code the unit sends (ICD Table 20), the payload
/// field at fault
/// (as named in our message types), and a sentence for a person.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Invalid {
    /// The SPEC_ACK code the unit sends (ICD Table 20).
    pub error: SpecAckError,
    /// The payload field at fault, as named in our message types.
    pub field: &'static str,
    /// Why, in a sentence for a person.
    pub reason: String,
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.reason)
    }
}

fn refuse(error: SpecAckError, field: &'static str, reason: String) -> Invalid {
    Invalid {
        error,
        field,
        reason,
    }
}

/// One problem found by [`whole_config`]. `field` is a path into [`UnitConfig`]
/// (`devices[23].circuit_breaker`); `message` says why without repeating the path;
/// `Display` gives `"<field>: <message>"`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigProblem {
    /// Path of the field into [`UnitConfig`], e.g. `devices[23].circuit_breaker`.
    pub field: String,
    /// The SPEC_ACK code a unit would send for it (ICD Table 20).
    pub error: SpecAckError,
    /// Why, without repeating the path.
    pub message: String,
}

impl fmt::Display for ConfigProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

fn pin_name(id: u8) -> String {
    match device::device(id) {
        Some(d) => format!("{} (device {id})", d.system_name),
        None => format!("device {id}"),
    }
}

/// "Same switch" for the two alternators; see the module doc for why 0 is excluded.
fn shares_switch(a: SwitchId, b: SwitchId) -> bool {
    a == b && a != SwitchId::Off
}

fn switch_of(cfg: &UnitConfig, id: u8) -> Option<SwitchId> {
    cfg.devices.get(id as usize).map(|d| d.switch_id)
}

/// Whether DEVICE_SPEC's checks against other parts of the config (wig-wag and
/// alternator notes) run. `whole_config` reports those once, from SYSTEM_SPEC's and
/// WIG_WAG_SPEC's side, instead of once per end of each conflict.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Cross {
    Check,
    Skip,
}

// ---------------------------------------------------------------- DEVICE_SPEC

/// DEVICE_SPEC, ICD Table 13 and Appendix B (Table 40). In order:
///
/// 1. Device id 1–28. Flaps (0) and the trims (29, 30) are configured by FLAP_SPEC and
///    TRIM_SPEC, and there is no device above 30 → `InvalidDevice`.
/// 2. Breaker within the pin's Table 40 amps, or the pin's own factory default (module
///    doc) → `InvalidBreaker`.
/// 3. Switch 0–11 (`InvalidSwitch`); the starter stays always on (Table 40: not
///    assignable) and the EFIS is never always off (note 4) → `InvalidSwitch`.
/// 4. A wig-wag device may not become always off or always on (note 5) → `WigWagConfig`.
/// 5. The secondary alternator may not take the primary's switch, nor the primary the
///    secondary's (note 6) → `SecAltConfig`.
/// 6. Current fault only where Table 40 supports it → `OutOfRange`.
pub fn check_device_spec(cfg: &UnitConfig, spec: &DeviceSpec) -> Result<(), Invalid> {
    device_spec_inner(cfg, spec, Cross::Check)
}

fn device_spec_inner(cfg: &UnitConfig, spec: &DeviceSpec, cross: Cross) -> Result<(), Invalid> {
    use SpecAckError::*;
    let id = spec.device_id;
    let info = match id {
        FLAPS => {
            return Err(refuse(
                InvalidDevice,
                "device_id",
                "the flaps (device 0) are configured with FLAP_SPEC, not DEVICE_SPEC \
                 (ICD Table 16)"
                    .into(),
            ));
        }
        TRIM_R | TRIM_P => {
            return Err(refuse(
                InvalidDevice,
                "device_id",
                format!(
                    "{} is configured with TRIM_SPEC, not DEVICE_SPEC (ICD Table 15)",
                    pin_name(id)
                ),
            ));
        }
        _ => match device::device(id) {
            Some(info) => info,
            None => {
                return Err(refuse(
                    InvalidDevice,
                    "device_id",
                    format!("there is no device {id}; device ids run 0–30 (ICD Table 40)"),
                ));
            }
        },
    };

    let cb = spec.circuit_breaker;
    if !(info.amps_min..=info.amps_max).contains(&cb) && cb != factory_breaker(id) {
        return Err(refuse(
            InvalidBreaker,
            "circuit_breaker",
            format!(
                "{cb} A is outside {}–{} A for {} (ICD Table 40)",
                info.amps_min, info.amps_max, info.system_name
            ),
        ));
    }

    match spec.switch_id {
        SwitchId::Unknown(n) => {
            return Err(refuse(
                InvalidSwitch,
                "switch_id",
                format!(
                    "switch {n} does not exist: 0 is always off, 1–10 the switch inputs, \
                     11 always on (ICD Table 13 note 3)"
                ),
            ));
        }
        s if id == STARTER && s != SwitchId::AlwaysOn => {
            return Err(refuse(
                InvalidSwitch,
                "switch_id",
                "the starter's switch is not assignable: it stays always on and the unit \
                 turns it off above 500 RPM (ICD Table 40)"
                    .into(),
            ));
        }
        SwitchId::Off if id == EFIS => {
            return Err(refuse(
                InvalidSwitch,
                "switch_id",
                "the EFIS can never be switched always off (ICD Table 13 note 4)".into(),
            ));
        }
        _ => {}
    }

    if cross == Cross::Check {
        if cfg.is_wig_wag_device(id) && matches!(spec.switch_id, SwitchId::Off | SwitchId::AlwaysOn)
        {
            return Err(refuse(
                WigWagConfig,
                "switch_id",
                format!(
                    "{} is a wig-wag device and must stay on a switch 1–10; remove it from \
                     the wig-wag first (ICD Table 13 note 5)",
                    pin_name(id)
                ),
            ));
        }
        if id != FIELD_PRI
            && cfg.is_secondary_alternator(id)
            && switch_of(cfg, FIELD_PRI).is_some_and(|p| shares_switch(spec.switch_id, p))
        {
            return Err(refuse(
                SecAltConfig,
                "switch_id",
                format!(
                    "{} is the secondary alternator and may not share the primary \
                     alternator's switch ({}) (ICD Table 13 note 6)",
                    pin_name(id),
                    spec.switch_id.label()
                ),
            ));
        }
        if id == FIELD_PRI
            && let Some(sec) = cfg.system.secondary_alternator
            && sec != FIELD_PRI
            && switch_of(cfg, sec).is_some_and(|s| shares_switch(spec.switch_id, s))
        {
            return Err(refuse(
                SecAltConfig,
                "switch_id",
                format!(
                    "the primary alternator may not share the switch ({}) of the secondary \
                     alternator, {} (ICD Table 13 note 6)",
                    spec.switch_id.label(),
                    pin_name(sec)
                ),
            ));
        }
    }

    if spec.current_fault && !info.current_fault_support {
        return Err(refuse(
            OutOfRange,
            "current_fault",
            format!(
                "{} has no current fault checking (ICD Table 40)",
                info.system_name
            ),
        ));
    }
    Ok(())
}

/// The breaker a pin holds after EEPROM_ERASE (ICD Table 44 via `defaults`). For the
/// EFIS this is 5 A and Table 40's 2 A is inside its 1–5 A range anyway (note 21).
fn factory_breaker(id: u8) -> u8 {
    super::defaults::device_spec(id).circuit_breaker
}

// ---------------------------------------------------------------- SYSTEM_SPEC

/// SYSTEM_SPEC, ICD Table 14. In order:
///
/// 1. Overvoltage limit 0 or 1 → `OutOfRange`.
/// 2. Secondary alternator on pins 4–25, 27–28 or disabled (note 3) → `InvalidDevice`.
/// 3. Not a current wig-wag device (note 4) → `WigWagConfig`.
/// 4. Not on the primary alternator's switch (note 5) → `SecAltConfig`.
pub fn check_system_spec(cfg: &UnitConfig, spec: &SystemSpec) -> Result<(), Invalid> {
    use SpecAckError::*;
    if let OvervoltageLimit::Unknown(n) = spec.overvoltage_limit {
        return Err(refuse(
            OutOfRange,
            "overvoltage_limit",
            format!("overvoltage limit {n} is neither 0 (16 V) nor 1 (32 V) (ICD Table 14)"),
        ));
    }
    let Some(sec) = spec.secondary_alternator else {
        return Ok(());
    };
    if !secondary_alternator_allowed(sec) {
        return Err(refuse(
            InvalidDevice,
            "secondary_alternator",
            format!(
                "{} cannot be the secondary alternator; only pins 4–25 and 27–28 can \
                 (ICD Table 14 note 3)",
                pin_name(sec)
            ),
        ));
    }
    if cfg.is_wig_wag_device(sec) {
        return Err(refuse(
            WigWagConfig,
            "secondary_alternator",
            format!(
                "{} is a wig-wag device; remove it from the wig-wag before making it the \
                 secondary alternator (ICD Table 14 note 4)",
                pin_name(sec)
            ),
        ));
    }
    if let (Some(s), Some(p)) = (switch_of(cfg, sec), switch_of(cfg, FIELD_PRI))
        && shares_switch(s, p)
    {
        return Err(refuse(
            SecAltConfig,
            "secondary_alternator",
            format!(
                "{} is on the primary alternator's switch ({}); the two alternators need \
                 different switches (ICD Table 14 note 5)",
                pin_name(sec),
                s.label()
            ),
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------- TRIM_SPEC

/// Trim power is 40–90 % (ICD Table 15); 100 is the factory value (Table 44, icd-reading
/// R16) and accepted too.
pub const TRIM_POWER_RANGE: core::ops::RangeInclusive<u8> = 40..=90;
/// What a unit fresh from EEPROM_ERASE reports for trim power (ICD Table 44, icd-reading
/// R16).
pub const TRIM_POWER_FACTORY: u8 = 100;
/// Highest TRIM_SPEC speed (ICD Table 15, bytes 6–7: 0–300).
pub const TRIM_SPEED_MAX: u16 = 300;

/// TRIM_SPEC, ICD Table 15. In order:
///
/// 1. Trim type pitch or roll → `OutOfRange`.
/// 2. Pitch only (notes 5, 6 say roll ignores them): power 40–90 or the factory 100,
///    then speed 0–300 → `OutOfRange`.
///
/// Endpoints and neutral take any byte (note 4: the sensor's own 0–255).
pub fn check_trim_spec(_cfg: &UnitConfig, spec: &TrimSpec) -> Result<(), Invalid> {
    use SpecAckError::*;
    match spec.trim_type {
        TrimType::Unknown(n) => Err(refuse(
            OutOfRange,
            "trim_type",
            format!("trim type {n} is neither pitch (0) nor roll (1) (ICD Table 15)"),
        )),
        TrimType::Roll => Ok(()),
        TrimType::Pitch => {
            if !TRIM_POWER_RANGE.contains(&spec.power) && spec.power != TRIM_POWER_FACTORY {
                return Err(refuse(
                    OutOfRange,
                    "power",
                    format!(
                        "trim power {} % is outside 40–90 % (ICD Table 15; 100 % is the \
                         factory value and also accepted)",
                        spec.power
                    ),
                ));
            }
            if spec.speed > TRIM_SPEED_MAX {
                return Err(refuse(
                    OutOfRange,
                    "speed",
                    format!("trim speed {} is above 300 (ICD Table 15)", spec.speed),
                ));
            }
            Ok(())
        }
    }
}

// ---------------------------------------------------------------- FLAP_SPEC

/// FLAP_SPEC circuit breaker range, whole amps (ICD Table 16, byte 6).
pub const FLAP_BREAKER_RANGE: core::ops::RangeInclusive<u8> = 1..=10;
/// Highest FLAP_SPEC max speed (ICD Table 16, bytes 8–9: 0–500).
pub const FLAP_MAX_SPEED_MAX: u16 = 500;
/// Tenths of a second (icd-reading R23).
pub const FLAP_ENDPOINT_DURATION_MAX: u16 = 300;

/// FLAP_SPEC, ICD Table 16. In order:
///
/// 1. With both midpoints non-zero, up → midpoint 1 → midpoint 2 → down strictly in
///    one direction, rising or falling (note 4) → `BadOrder`.
/// 2. Breaker 1–10 A → `InvalidBreaker`.
/// 3. Max speed 0–500, then endpoint duration 0–300 tenths → `OutOfRange`.
pub fn check_flap_spec(_cfg: &UnitConfig, spec: &FlapSpec) -> Result<(), Invalid> {
    use SpecAckError::*;
    if spec.midpoint_1 != 0 && spec.midpoint_2 != 0 {
        let p = [spec.up, spec.midpoint_1, spec.midpoint_2, spec.down];
        let rising = p.windows(2).all(|w| matches!(w, [a, b] if a < b));
        let falling = p.windows(2).all(|w| matches!(w, [a, b] if a > b));
        if !rising && !falling {
            return Err(refuse(
                BadOrder,
                "midpoint_1",
                format!(
                    "up {}, midpoint 1 {}, midpoint 2 {}, down {} are not in order: with both \
                     midpoints set they must run from up to down in one direction \
                     (ICD Table 16 note 4)",
                    spec.up, spec.midpoint_1, spec.midpoint_2, spec.down
                ),
            ));
        }
    }
    if !FLAP_BREAKER_RANGE.contains(&spec.circuit_breaker) {
        return Err(refuse(
            InvalidBreaker,
            "circuit_breaker",
            format!(
                "{} A is outside 1–10 A for the flaps (ICD Table 16)",
                spec.circuit_breaker
            ),
        ));
    }
    if spec.max_speed > FLAP_MAX_SPEED_MAX {
        return Err(refuse(
            OutOfRange,
            "max_speed",
            format!(
                "flap max speed {} is above 500 (ICD Table 16)",
                spec.max_speed
            ),
        ));
    }
    if spec.endpoint_duration.0 > FLAP_ENDPOINT_DURATION_MAX {
        return Err(refuse(
            OutOfRange,
            "endpoint_duration",
            format!(
                "endpoint duration {:.1} s is above 30.0 s (ICD Table 16, in tenths)",
                spec.endpoint_duration.value()
            ),
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------- WIG_WAG_SPEC

/// WIG_WAG_SPEC warm-up period, seconds (ICD Table 17, byte 3).
pub const WIG_WAG_WARM_UP_RANGE: core::ops::RangeInclusive<u8> = 5..=60;
/// Highest WIG_WAG_SPEC speed (ICD Table 17, byte 4: 0–200).
pub const WIG_WAG_SPEED_MAX: u8 = 200;

/// WIG_WAG_SPEC, ICD Table 17. In order:
///
/// 1. Each device 4–28 or disabled; this also keeps out the starter, primary
///    alternator, EFIS, flaps and trims (note 2) → `InvalidDevice`.
/// 2. Device two only with device one (note 3), and not the same pin as device one
///    (module doc) → `BadConfig`.
/// 3. Neither is the secondary alternator (note 2) → `SecAltConfig`.
/// 4. Each is on a switch 1–10 (note 1) → `BadConfig`.
/// 5. Warm-up 5–60 s, then speed 0–200 → `OutOfRange`.
pub fn check_wig_wag_spec(cfg: &UnitConfig, spec: &WigWagSpec) -> Result<(), Invalid> {
    wig_wag_inner(cfg, spec, Cross::Check)
}

fn wig_wag_inner(cfg: &UnitConfig, spec: &WigWagSpec, sec_alt: Cross) -> Result<(), Invalid> {
    use SpecAckError::*;
    let devices = [
        ("device_one", spec.device_one),
        ("device_two", spec.device_two),
    ];
    for (field, d) in devices {
        if let Some(id) = d
            && !wig_wag_allowed(id)
        {
            return Err(refuse(
                InvalidDevice,
                field,
                format!(
                    "{} cannot be a wig-wag device; only pins 4–28 can (ICD Table 17 note 2)",
                    pin_name(id)
                ),
            ));
        }
    }
    if spec.device_one.is_none() && spec.device_two.is_some() {
        return Err(refuse(
            BadConfig,
            "device_two",
            "wig-wag device two needs device one set first (ICD Table 17 note 3)".into(),
        ));
    }
    if spec.device_one.is_some() && spec.device_one == spec.device_two {
        return Err(refuse(
            BadConfig,
            "device_two",
            "wig-wag devices one and two are the same pin; it cannot alternate with itself".into(),
        ));
    }
    for (field, d) in devices {
        let Some(id) = d else { continue };
        if sec_alt == Cross::Check && cfg.is_secondary_alternator(id) {
            return Err(refuse(
                SecAltConfig,
                field,
                format!(
                    "{} is the secondary alternator and cannot be a wig-wag device \
                     (ICD Table 17 note 2)",
                    pin_name(id)
                ),
            ));
        }
    }
    for (field, d) in devices {
        let Some(id) = d else { continue };
        let sw = switch_of(cfg, id);
        if !matches!(sw, Some(SwitchId::Input(_))) {
            return Err(refuse(
                BadConfig,
                field,
                format!(
                    "{} is {}; a wig-wag device must be on a switch 1–10 (ICD Table 17 note 1)",
                    pin_name(id),
                    sw.map_or("not configured".into(), |s| s.label())
                ),
            ));
        }
    }
    if !WIG_WAG_WARM_UP_RANGE.contains(&spec.warm_up_period) {
        return Err(refuse(
            OutOfRange,
            "warm_up_period",
            format!(
                "warm-up {} s is outside 5–60 s (ICD Table 17)",
                spec.warm_up_period
            ),
        ));
    }
    if spec.speed > WIG_WAG_SPEED_MAX {
        return Err(refuse(
            OutOfRange,
            "speed",
            format!("wig-wag speed {} is above 200 (ICD Table 17)", spec.speed),
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------- DEVICE_NAME

/// DEVICE_NAME, ICD Table 21: device id 0–30 → `InvalidDevice`. The 16 name bytes are
/// "0–255", so none is refused.
pub fn check_device_name(_cfg: &UnitConfig, name: &DeviceName) -> Result<(), Invalid> {
    if device::device(name.device_id).is_none() {
        return Err(refuse(
            SpecAckError::InvalidDevice,
            "device_id",
            format!(
                "there is no device {}; names are stored for ids 0–30 (ICD Table 21)",
                name.device_id
            ),
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------- DEVICE_ENABLE

/// DEVICE_ENABLE, ICD Table 23: id 4–28 (`InvalidDevice`; note 1: the others are always
/// shown) and flag 0–2 (`OutOfRange`). The unit answers DEVICE_ENABLE, not SPEC_ACK;
/// the codes here only say which rule failed.
pub fn device_enable(_cfg: &UnitConfig, e: &DeviceEnable) -> Result<(), SpecAckError> {
    if !enable_flag_allowed(e.device_id) {
        return Err(SpecAckError::InvalidDevice);
    }
    if let EnableFlag::Unknown(_) = e.flag {
        return Err(SpecAckError::OutOfRange);
    }
    Ok(())
}

// ---------------------------------------------------------------- any message

/// Judges any message the unit answers with SPEC_ACK (DEVICE_SPEC, SYSTEM_SPEC,
/// TRIM_SPEC, FLAP_SPEC, WIG_WAG_SPEC, DEVICE_NAME). `None` for every other message.
pub fn check(cfg: &UnitConfig, message: &Message) -> Option<Result<(), Invalid>> {
    Some(match message {
        Message::DeviceSpec(m) => check_device_spec(cfg, m),
        Message::SystemSpec(m) => check_system_spec(cfg, m),
        Message::TrimSpec(m) => check_trim_spec(cfg, m),
        Message::FlapSpec(m) => check_flap_spec(cfg, m),
        Message::WigWagSpec(m) => check_wig_wag_spec(cfg, m),
        Message::DeviceName(m) => check_device_name(cfg, m),
        _ => return None,
    })
}

/// What the unit does with a spec message: judge it and, when accepted, store it.
/// The error is what its SPEC_ACK carries. `None` for messages SPEC_ACK does not answer.
pub fn accept(cfg: &mut UnitConfig, message: &Message) -> Option<Result<(), SpecAckError>> {
    let verdict = check(cfg, message)?.map_err(|r| r.error);
    if verdict.is_ok() {
        match message {
            Message::DeviceSpec(m) => cfg.apply_device_spec(m),
            Message::SystemSpec(m) => cfg.apply_system_spec(m),
            Message::TrimSpec(m) => cfg.apply_trim_spec(m),
            Message::FlapSpec(m) => cfg.apply_flap_spec(m),
            Message::WigWagSpec(m) => cfg.apply_wig_wag_spec(m),
            Message::DeviceName(m) => cfg.apply_device_name(m),
            _ => {}
        }
    }
    Some(verdict)
}

/// Words for a SPEC_ACK error the unit sent in answer to `sent`, for the setup screens.
///
/// The caller gives Table 20's words for the code ([`SpecAckError::description`]);
/// this gives the reason after them, never those words again. When our own rules
/// refuse `sent` with the same code, their reason is given. When they do not (the
/// unit checks something the ICD does not tell us, or its state differs from `cfg`), a
/// sentence about *this* message is given (the range of this pin, or of the flap
/// motor) and says so.
pub fn explain(err: SpecAckError, cfg: &UnitConfig, sent: &Message) -> String {
    if let Some(Err(r)) = check(cfg, sent)
        && r.error == err
    {
        return r.reason;
    }
    let hint = match err {
        SpecAckError::OutOfRange => "a value is outside the range its ICD table gives",
        SpecAckError::InvalidDevice => {
            "this message cannot configure that device id (ICD Tables 13, 14, 17)"
        }
        SpecAckError::InvalidBreaker => {
            return format!("{}; this program's checks accepted it", breaker_range(sent));
        }
        SpecAckError::InvalidSwitch => {
            "switch ids are 0–11; the starter's is fixed and the EFIS is never off \
             (ICD Table 13 notes 3, 4)"
        }
        SpecAckError::BadConfig => {
            "wig-wag devices must be on a switch 1–10, device two only with device one \
             (ICD Table 17 notes 1, 3)"
        }
        SpecAckError::EepromWrite => {
            "the unit could not store the setting; try again, and if it repeats its \
             EEPROM may be failing"
        }
        SpecAckError::BadOrder => {
            "with both flap midpoints set, up, midpoint 1, midpoint 2 and down must run in \
             one direction (ICD Table 16 note 4)"
        }
        SpecAckError::WigWagConfig => {
            "a wig-wag device cannot be switched always off or always on, nor become the \
             secondary alternator; remove it from the wig-wag first (ICD Table 13 note 5, \
             Table 14 note 4)"
        }
        SpecAckError::SecAltConfig => {
            "the secondary alternator cannot share the primary alternator's switch nor be \
             a wig-wag device (ICD Table 13 note 6, Table 14 note 5, Table 17 note 2)"
        }
        SpecAckError::Unknown(_) => "the ICD does not define this code",
    };
    format!("{hint} (the unit refused what this program's checks would accept)")
}

/// The breaker that was sent and the range that applies to it: the pin's amps in
/// Appendix B, or the flap motor's in Table 16.
fn breaker_range(sent: &Message) -> String {
    match sent {
        Message::DeviceSpec(s) => match device::device(s.device_id) {
            Some(d) => format!(
                "{} A was sent; ICD Appendix B gives {}–{} A for {}",
                s.circuit_breaker, d.amps_min, d.amps_max, d.system_name
            ),
            None => format!(
                "{} A was sent for device {}",
                s.circuit_breaker, s.device_id
            ),
        },
        Message::FlapSpec(f) => format!(
            "{} A was sent; the flap motor takes {}–{} A (ICD Table 16)",
            f.circuit_breaker,
            FLAP_BREAKER_RANGE.start(),
            FLAP_BREAKER_RANGE.end()
        ),
        _ => "the breaker is outside the amps ICD Appendix B gives this device".into(),
    }
}

// ---------------------------------------------------------------- whole config

/// Every problem in a whole configuration, e.g. a backup before it is restored, each
/// with a field path (`devices[23].circuit_breaker`).
///
/// Checks every DEVICE_SPEC entry 1–28 and the system, flap, trim and wig-wag specs with
/// the rules above, each against the rest of `cfg`. A conflict between two parts (wig-wag
/// device on switch 0, secondary alternator on the primary's switch) is reported once,
/// from the SYSTEM_SPEC or WIG_WAG_SPEC side, not once per end. Entries 0, 29 and 30 of
/// `devices` are not sent by anything, so only their `device_id` is checked; names and
/// enable flags hold nothing that can be wrong.
pub fn whole_config(cfg: &UnitConfig) -> Vec<ConfigProblem> {
    let mut out = Vec::new();
    let mut push = |prefix: String, r: Invalid| {
        out.push(ConfigProblem {
            field: format!("{prefix}.{}", r.field),
            error: r.error,
            message: r.reason,
        })
    };

    for (i, d) in cfg.devices.iter().enumerate() {
        let prefix = format!("devices[{i}]");
        if d.device_id as usize != i {
            push(
                prefix,
                refuse(
                    SpecAckError::InvalidDevice,
                    "device_id",
                    format!("entry {i} holds device id {}", d.device_id),
                ),
            );
            continue;
        }
        if matches!(d.device_id, FLAPS | TRIM_R | TRIM_P) {
            continue;
        }
        if let Err(r) = device_spec_inner(cfg, d, Cross::Skip) {
            push(prefix, r);
        }
    }
    if let Err(r) = check_system_spec(cfg, &cfg.system) {
        push("system".into(), r);
    }
    if let Err(r) = check_flap_spec(cfg, &cfg.flap) {
        push("flap".into(), r);
    }
    for (name, want, t) in [
        ("pitch_trim", TrimType::Pitch, &cfg.pitch_trim),
        ("roll_trim", TrimType::Roll, &cfg.roll_trim),
    ] {
        if t.trim_type != want {
            push(
                name.into(),
                refuse(
                    SpecAckError::BadConfig,
                    "trim_type",
                    format!("the {name} entry holds a {:?} trim spec", t.trim_type),
                ),
            );
        } else if let Err(r) = check_trim_spec(cfg, t) {
            push(name.into(), r);
        }
    }
    // SYSTEM_SPEC already reported a secondary alternator that is a wig-wag device.
    if let Err(r) = wig_wag_inner(cfg, &cfg.wig_wag, Cross::Skip) {
        push("wig_wag".into(), r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use SpecAckError::*;

    fn cfg() -> UnitConfig {
        UnitConfig::default()
    }

    /// The SPEC_ACK code alone, what the unit sends.
    fn code(verdict: Result<(), Invalid>) -> Result<(), SpecAckError> {
        verdict.map_err(|r| r.error)
    }

    /// Judges each spec on `c` with `check`: the SPEC_ACK code it must get. A failure
    /// names the spec.
    #[track_caller]
    fn judge<M: fmt::Debug>(
        check: fn(&UnitConfig, &M) -> Result<(), Invalid>,
        c: &UnitConfig,
        cases: &[(M, Result<(), SpecAckError>)],
    ) {
        for (spec, want) in cases {
            assert_eq!(code(check(c, spec)), *want, "{spec:?}");
        }
    }

    fn dev(id: u8, cb: u8, sw: SwitchId, cf: bool) -> DeviceSpec {
        DeviceSpec {
            device_id: id,
            circuit_breaker: cb,
            switch_id: sw,
            current_fault: cf,
            switch_raw: None,
        }
    }

    fn on(n: u8) -> SwitchId {
        SwitchId::Input(n)
    }

    /// A config with pin `id` on switch `n`.
    fn with_switch(mut c: UnitConfig, id: u8, sw: SwitchId) -> UnitConfig {
        c.devices[id as usize].switch_id = sw;
        c
    }

    fn pitch(power: u8, speed: u16) -> TrimSpec {
        TrimSpec {
            trim_type: TrimType::Pitch,
            enabled: true,
            polarity: Polarity::Standard,
            up: 200,
            down: 20,
            neutral: 110,
            power,
            speed,
        }
    }

    fn flap(up: u8, m1: u8, m2: u8, down: u8) -> FlapSpec {
        FlapSpec {
            mode: FlapMode::PositionBased,
            enabled: true,
            polarity: Polarity::Standard,
            up,
            down,
            midpoint_1: m1,
            midpoint_2: m2,
            circuit_breaker: 7,
            overspeed_position: 50,
            max_speed: 100,
            endpoint_duration: Tenths(5),
        }
    }

    fn ww(d1: Option<u8>, d2: Option<u8>) -> WigWagSpec {
        WigWagSpec {
            device_one: d1,
            device_two: d2,
            warm_up_period: 5,
            speed: 70,
        }
    }

    // ---- DEVICE_SPEC

    #[test]
    fn device_id_must_be_1_to_28() {
        let c = cfg();
        for id in [0, 29, 30, 31, 200, 255] {
            assert_eq!(
                code(check_device_spec(&c, &dev(id, 2, SwitchId::Off, false))),
                Err(InvalidDevice),
                "id {id}"
            );
        }
        for id in 1..=28u8 {
            let spec = c.devices[id as usize];
            assert_eq!(
                code(check_device_spec(&c, &spec)),
                Ok(()),
                "factory spec of {id}"
            );
        }
    }

    #[test]
    fn breaker_within_appendix_b_amps() {
        judge(
            check_device_spec,
            &cfg(),
            &[
                (dev(4, 5, on(1), false), Ok(())),
                (dev(4, 6, on(1), false), Err(InvalidBreaker)),
                (dev(4, 0, on(1), false), Err(InvalidBreaker)),
                (dev(0x11, 10, on(1), false), Ok(())),
                (dev(0x11, 11, on(1), false), Err(InvalidBreaker)),
                (dev(0x17, 15, on(1), false), Ok(())),
                (dev(0x17, 16, on(1), false), Err(InvalidBreaker)),
                (dev(0x1A, 4, on(1), false), Err(InvalidBreaker)),
                (dev(0x1B, 3, on(1), false), Err(InvalidBreaker)),
                (dev(EFIS, 6, on(1), true), Err(InvalidBreaker)),
                (dev(STARTER, 10, SwitchId::AlwaysOn, false), Ok(())),
                (
                    dev(STARTER, 11, SwitchId::AlwaysOn, false),
                    Err(InvalidBreaker),
                ),
            ],
        );
    }

    /// ICD contradiction: 15 A pins take 5–15 A but default to 2 A (Tables 40, 44). The
    /// factory 2 A is accepted; other values below 5 are not.
    #[test]
    fn fifteen_amp_pins_accept_their_factory_two_amps_only() {
        let c = cfg();
        for id in [0x17, 0x18, 0x19] {
            assert_eq!(
                code(check_device_spec(&c, &dev(id, 2, on(1), false))),
                Ok(()),
                "{id}"
            );
            for cb in [0, 1, 3, 4] {
                assert_eq!(
                    code(check_device_spec(&c, &dev(id, cb, on(1), false))),
                    Err(InvalidBreaker),
                    "{id} {cb} A"
                );
            }
        }
        let r = check_device_spec(&c, &dev(0x17, 1, on(1), false)).unwrap_err();
        assert_eq!(r.reason, "1 A is outside 5–15 A for 15A-1 (ICD Table 40)");
    }

    #[test]
    fn unknown_switch_is_invalid() {
        judge(
            check_device_spec,
            &cfg(),
            &[
                (dev(4, 2, SwitchId::Unknown(12), false), Err(InvalidSwitch)),
                (
                    dev(4, 2, SwitchId::from_byte(254), false),
                    Err(InvalidSwitch),
                ),
                (dev(4, 2, SwitchId::Off, false), Ok(())),
                (dev(4, 2, on(1), false), Ok(())),
                (dev(4, 2, on(10), false), Ok(())),
                (dev(4, 2, SwitchId::AlwaysOn, false), Ok(())),
                (dev(4, 2, SwitchId::from_byte(255), false), Ok(())),
            ],
        );
    }

    #[test]
    fn starter_switch_is_not_assignable() {
        judge(
            check_device_spec,
            &cfg(),
            &[
                (dev(STARTER, 5, SwitchId::Off, false), Err(InvalidSwitch)),
                (dev(STARTER, 5, on(3), false), Err(InvalidSwitch)),
                (dev(STARTER, 5, SwitchId::AlwaysOn, false), Ok(())),
            ],
        );
    }

    #[test]
    fn efis_is_never_off() {
        let c = cfg();
        let r = check_device_spec(&c, &dev(EFIS, 5, SwitchId::Off, false)).unwrap_err();
        assert_eq!(r.error, InvalidSwitch);
        assert!(r.reason.contains("Table 13 note 4"), "{}", r.reason);
        judge(
            check_device_spec,
            &c,
            &[
                (dev(EFIS, 5, on(2), false), Ok(())),
                (dev(EFIS, 2, SwitchId::AlwaysOn, true), Ok(())),
            ],
        );
    }

    #[test]
    fn wig_wag_device_keeps_a_switch() {
        let mut c = with_switch(cfg(), 8, on(4));
        c.wig_wag = ww(Some(8), None);
        judge(
            check_device_spec,
            &c,
            &[
                (dev(8, 2, SwitchId::Off, false), Err(WigWagConfig)),
                (dev(8, 2, SwitchId::AlwaysOn, false), Err(WigWagConfig)),
                (dev(8, 2, on(5), false), Ok(())),
                // Not a wig-wag device: the same change is fine.
                (dev(9, 2, SwitchId::Off, false), Ok(())),
            ],
        );
    }

    #[test]
    fn secondary_alternator_cannot_take_primary_switch() {
        let mut c = with_switch(cfg(), FIELD_PRI, on(2));
        c = with_switch(c, 12, on(3));
        c.system.secondary_alternator = Some(12);
        judge(
            check_device_spec,
            &c,
            &[
                (dev(12, 2, on(2), false), Err(SecAltConfig)),
                (dev(12, 2, on(4), false), Ok(())),
                // A pin that is not the secondary alternator may share the primary's
                // switch.
                (dev(13, 2, on(2), false), Ok(())),
            ],
        );
    }

    #[test]
    fn primary_alternator_cannot_take_secondary_switch() {
        let mut c = with_switch(cfg(), 12, on(3));
        c.system.secondary_alternator = Some(12);
        judge(
            check_device_spec,
            &c,
            &[
                (dev(FIELD_PRI, 5, on(3), false), Err(SecAltConfig)),
                (dev(FIELD_PRI, 5, on(1), false), Ok(())),
            ],
        );
        // Both always on means both run at once.
        let c = with_switch(c, 12, SwitchId::AlwaysOn);
        judge(
            check_device_spec,
            &c,
            &[(
                dev(FIELD_PRI, 5, SwitchId::AlwaysOn, false),
                Err(SecAltConfig),
            )],
        );
    }

    /// Decision: both alternators always off (0) do not share a switch.
    #[test]
    fn both_alternators_off_is_not_a_shared_switch() {
        let mut c = cfg();
        c.system.secondary_alternator = Some(12);
        assert_eq!(c.devices[FIELD_PRI as usize].switch_id, SwitchId::Off);
        judge(
            check_device_spec,
            &c,
            &[
                (dev(12, 2, SwitchId::Off, false), Ok(())),
                (dev(FIELD_PRI, 5, SwitchId::Off, false), Ok(())),
            ],
        );
        assert_eq!(code(check_system_spec(&cfg(), &c.system)), Ok(()));
    }

    /// Decision: current fault where Table 40 has no support → OutOfRange.
    #[test]
    fn current_fault_only_where_supported() {
        judge(
            check_device_spec,
            &cfg(),
            &[
                (dev(FIELD_PRI, 5, SwitchId::Off, true), Err(OutOfRange)),
                (dev(STARTER, 5, SwitchId::AlwaysOn, true), Err(OutOfRange)),
                (dev(4, 2, on(1), true), Ok(())),
                (dev(FIELD_PRI, 5, SwitchId::Off, false), Ok(())),
            ],
        );
    }

    // ---- SYSTEM_SPEC

    fn sys(ov: OvervoltageLimit, sec: Option<u8>) -> SystemSpec {
        SystemSpec {
            overvoltage_limit: ov,
            secondary_alternator: sec,
        }
    }

    #[test]
    fn overvoltage_limit_is_0_or_1() {
        judge(
            check_system_spec,
            &cfg(),
            &[
                (sys(OvervoltageLimit::Unknown(2), None), Err(OutOfRange)),
                (sys(OvervoltageLimit::V32, None), Ok(())),
                (sys(OvervoltageLimit::V16, None), Ok(())),
            ],
        );
    }

    #[test]
    fn secondary_alternator_pins() {
        let c = with_switch(cfg(), FIELD_PRI, on(1));
        for id in [0, 1, 2, 3, 26, 29, 30, 31, 254] {
            assert_eq!(
                code(check_system_spec(&c, &sys(OvervoltageLimit::V16, Some(id)))),
                Err(InvalidDevice),
                "{id}"
            );
        }
        for id in (4..=25).chain(27..=28) {
            assert_eq!(
                code(check_system_spec(&c, &sys(OvervoltageLimit::V16, Some(id)))),
                Ok(()),
                "{id}"
            );
        }
    }

    #[test]
    fn wig_wag_device_cannot_be_secondary_alternator() {
        let mut c = with_switch(cfg(), 8, on(4));
        c.wig_wag = ww(Some(7), Some(8));
        judge(
            check_system_spec,
            &c,
            &[
                (sys(OvervoltageLimit::V16, Some(8)), Err(WigWagConfig)),
                (sys(OvervoltageLimit::V16, Some(9)), Ok(())),
            ],
        );
    }

    #[test]
    fn secondary_alternator_not_on_primary_switch() {
        let c = with_switch(with_switch(cfg(), FIELD_PRI, on(2)), 12, on(2));
        let spec = sys(OvervoltageLimit::V16, Some(12));
        assert_eq!(code(check_system_spec(&c, &spec)), Err(SecAltConfig));
        let c = with_switch(c, 12, on(3));
        assert_eq!(code(check_system_spec(&c, &spec)), Ok(()));
    }

    // ---- TRIM_SPEC

    #[test]
    fn trim_power_40_to_90_or_factory_100() {
        let c = cfg();
        for p in [40, 65, 90, 100] {
            assert_eq!(code(check_trim_spec(&c, &pitch(p, 100))), Ok(()), "{p}");
        }
        for p in [0, 39, 91, 99, 101, 255] {
            assert_eq!(
                code(check_trim_spec(&c, &pitch(p, 100))),
                Err(OutOfRange),
                "{p}"
            );
        }
    }

    #[test]
    fn trim_speed_0_to_300() {
        judge(
            check_trim_spec,
            &cfg(),
            &[
                (pitch(60, 300), Ok(())),
                (pitch(60, 0), Ok(())),
                (pitch(60, 301), Err(OutOfRange)),
            ],
        );
    }

    /// Decision: roll trim ignores power and speed (Table 15 notes 5, 6), so they are
    /// not judged.
    #[test]
    fn roll_trim_power_and_speed_are_ignored() {
        let c = cfg();
        let roll = TrimSpec {
            trim_type: TrimType::Roll,
            ..pitch(0, 1000)
        };
        assert_eq!(code(check_trim_spec(&c, &roll)), Ok(()));
    }

    #[test]
    fn trim_type_must_be_pitch_or_roll() {
        let t = TrimSpec {
            trim_type: TrimType::Unknown(2),
            ..pitch(60, 100)
        };
        assert_eq!(code(check_trim_spec(&cfg(), &t)), Err(OutOfRange));
    }

    // ---- FLAP_SPEC

    #[test]
    fn flap_breaker_1_to_10() {
        let c = cfg();
        for cb in [0, 11, 15] {
            let f = FlapSpec {
                circuit_breaker: cb,
                ..flap(10, 0, 0, 200)
            };
            assert_eq!(code(check_flap_spec(&c, &f)), Err(InvalidBreaker), "{cb}");
        }
        for cb in [1, 10] {
            let f = FlapSpec {
                circuit_breaker: cb,
                ..flap(10, 0, 0, 200)
            };
            assert_eq!(code(check_flap_spec(&c, &f)), Ok(()), "{cb}");
        }
    }

    #[test]
    fn flap_max_speed_and_endpoint_duration() {
        let ok = flap(10, 0, 0, 200);
        let speed = |max_speed| FlapSpec { max_speed, ..ok };
        let duration = |tenths| FlapSpec {
            endpoint_duration: Tenths(tenths),
            ..ok
        };
        judge(
            check_flap_spec,
            &cfg(),
            &[
                (speed(500), Ok(())),
                (speed(501), Err(OutOfRange)),
                (duration(300), Ok(())),
                (duration(301), Err(OutOfRange)),
            ],
        );
    }

    #[test]
    fn flap_midpoints_in_order_either_direction() {
        let c = cfg();
        assert_eq!(code(check_flap_spec(&c, &flap(10, 50, 100, 200))), Ok(()));
        assert_eq!(code(check_flap_spec(&c, &flap(200, 100, 50, 10))), Ok(()));
        for (u, m1, m2, d) in [
            (10, 100, 50, 200), // midpoints swapped
            (200, 50, 100, 10), // swapped, falling
            (10, 5, 100, 200),  // midpoint 1 beyond up
            (10, 50, 250, 200), // midpoint 2 beyond down
            (10, 50, 50, 200),  // equal midpoints: not strictly ordered
            (10, 10, 100, 200), // midpoint on an endpoint
            (100, 50, 60, 100), // up == down
        ] {
            assert_eq!(
                code(check_flap_spec(&c, &flap(u, m1, m2, d))),
                Err(BadOrder),
                "{u} {m1} {m2} {d}"
            );
        }
    }

    /// Decision: only "both midpoints non-zero" is ordered (Table 16 note 4).
    #[test]
    fn flap_single_midpoint_is_not_ordered() {
        let c = cfg();
        assert_eq!(code(check_flap_spec(&c, &flap(10, 250, 0, 200))), Ok(()));
        assert_eq!(code(check_flap_spec(&c, &flap(10, 0, 5, 200))), Ok(()));
        assert_eq!(code(check_flap_spec(&c, &defaults_flap())), Ok(()));
    }

    fn defaults_flap() -> FlapSpec {
        super::super::defaults::flap_spec()
    }

    // ---- WIG_WAG_SPEC

    /// Pins 5 and 6 on switches, the rest factory.
    fn ww_cfg() -> UnitConfig {
        with_switch(with_switch(cfg(), 5, on(1)), 6, on(1))
    }

    #[test]
    fn wig_wag_devices_4_to_28_or_none() {
        let c = ww_cfg();
        for id in [0, 1, 2, 3, 29, 30, 31, 100] {
            assert_eq!(
                code(check_wig_wag_spec(&c, &ww(Some(id), None))),
                Err(InvalidDevice),
                "{id}"
            );
            assert_eq!(
                code(check_wig_wag_spec(&c, &ww(Some(5), Some(id)))),
                Err(InvalidDevice),
                "two = {id}"
            );
        }
        assert_eq!(code(check_wig_wag_spec(&c, &ww(None, None))), Ok(()));
        assert_eq!(code(check_wig_wag_spec(&c, &ww(Some(5), None))), Ok(()));
        assert_eq!(code(check_wig_wag_spec(&c, &ww(Some(5), Some(6)))), Ok(()));
        let c = with_switch(with_switch(c, 4, on(9)), 28, on(10));
        assert_eq!(code(check_wig_wag_spec(&c, &ww(Some(4), Some(28)))), Ok(()));
    }

    #[test]
    fn wig_wag_device_two_needs_device_one() {
        assert_eq!(
            code(check_wig_wag_spec(&ww_cfg(), &ww(None, Some(6)))),
            Err(BadConfig)
        );
    }

    /// Decision: one pin cannot be both wig-wag devices.
    #[test]
    fn wig_wag_devices_differ() {
        assert_eq!(
            code(check_wig_wag_spec(&ww_cfg(), &ww(Some(5), Some(5)))),
            Err(BadConfig)
        );
    }

    #[test]
    fn wig_wag_devices_need_switch_1_to_10() {
        let c = ww_cfg();
        assert_eq!(
            code(check_wig_wag_spec(&c, &ww(Some(7), None))),
            Err(BadConfig),
            "switch 0"
        );
        assert_eq!(
            code(check_wig_wag_spec(&c, &ww(Some(5), Some(7)))),
            Err(BadConfig)
        );
        let c = with_switch(c, 7, SwitchId::AlwaysOn);
        assert_eq!(
            code(check_wig_wag_spec(&c, &ww(Some(7), None))),
            Err(BadConfig),
            "switch 11"
        );
        let c = with_switch(c, 7, on(10));
        assert_eq!(code(check_wig_wag_spec(&c, &ww(Some(7), None))), Ok(()));
    }

    #[test]
    fn wig_wag_device_not_secondary_alternator() {
        let mut c = ww_cfg();
        c.system.secondary_alternator = Some(6);
        assert_eq!(
            code(check_wig_wag_spec(&c, &ww(Some(5), Some(6)))),
            Err(SecAltConfig)
        );
        assert_eq!(
            code(check_wig_wag_spec(&c, &ww(Some(6), None))),
            Err(SecAltConfig)
        );
        assert_eq!(code(check_wig_wag_spec(&c, &ww(Some(5), None))), Ok(()));
    }

    #[test]
    fn wig_wag_warm_up_and_speed() {
        let c = ww_cfg();
        for (w, s, want) in [
            (5, 0, Ok(())),
            (60, 200, Ok(())),
            (4, 70, Err(OutOfRange)),
            (61, 70, Err(OutOfRange)),
            (5, 201, Err(OutOfRange)),
        ] {
            let spec = WigWagSpec {
                warm_up_period: w,
                speed: s,
                ..ww(Some(5), None)
            };
            assert_eq!(code(check_wig_wag_spec(&c, &spec)), want, "{w} {s}");
        }
        // Disabled wig-wag still carries a warm-up and speed the unit judges.
        let spec = WigWagSpec {
            warm_up_period: 0,
            ..ww(None, None)
        };
        assert_eq!(code(check_wig_wag_spec(&c, &spec)), Err(OutOfRange));
    }

    // ---- DEVICE_NAME / DEVICE_ENABLE

    #[test]
    fn device_name_ids_0_to_30_any_bytes() {
        let c = cfg();
        for id in [0, 2, 30] {
            let n = DeviceName {
                device_id: id,
                name: [0xFF; 16],
            };
            assert_eq!(code(check_device_name(&c, &n)), Ok(()), "{id}");
        }
        let n = DeviceName {
            device_id: 31,
            name: [0; 16],
        };
        assert_eq!(code(check_device_name(&c, &n)), Err(InvalidDevice));
    }

    #[test]
    fn device_enable_pins_4_to_28() {
        let c = cfg();
        let e = |device_id, flag| DeviceEnable { device_id, flag };
        assert_eq!(device_enable(&c, &e(4, EnableFlag::Disabled)), Ok(()));
        assert_eq!(device_enable(&c, &e(28, EnableFlag::Query)), Ok(()));
        assert_eq!(
            device_enable(&c, &e(3, EnableFlag::Disabled)),
            Err(InvalidDevice)
        );
        assert_eq!(
            device_enable(&c, &e(29, EnableFlag::Enabled)),
            Err(InvalidDevice)
        );
        assert_eq!(
            device_enable(&c, &e(4, EnableFlag::Unknown(3))),
            Err(OutOfRange)
        );
    }

    // ---- accept / explain / whole_config

    #[test]
    fn accept_stores_only_what_passes() {
        let mut c = cfg();
        let good = Message::DeviceSpec(dev(9, 3, on(2), true));
        assert_eq!(accept(&mut c, &good), Some(Ok(())));
        assert_eq!(c.devices[9], dev(9, 3, on(2), true));
        let bad = Message::DeviceSpec(dev(9, 9, on(2), true));
        assert_eq!(accept(&mut c, &bad), Some(Err(InvalidBreaker)));
        assert_eq!(c.devices[9].circuit_breaker, 3, "a refused spec is ignored");
        assert_eq!(accept(&mut c, &Message::Ping(Ping { ack: false })), None);
    }

    #[test]
    fn explain_gives_our_reason_or_a_general_one() {
        let c = cfg();
        let sent = Message::DeviceSpec(dev(EFIS, 5, SwitchId::Off, false));
        assert_eq!(
            explain(InvalidSwitch, &c, &sent),
            "the EFIS can never be switched always off (ICD Table 13 note 4)"
        );
        let fine = Message::DeviceSpec(dev(4, 2, on(1), false));
        let s = explain(EepromWrite, &c, &fine);
        assert!(s.starts_with("the unit could not store the setting"), "{s}");
        assert!(s.contains("refused what this program"), "{s}");
        // Table 20's words are the caller's, so they are never here twice.
        assert!(!s.contains("EEPROM write failure"), "{s}");
        // A unit refusing 5 A on a 1–5 A pin: this pin's range, not the flaps'.
        let five = Message::DeviceSpec(dev(9, 5, on(1), false));
        assert_eq!(
            explain(InvalidBreaker, &c, &five),
            "5 A was sent; ICD Appendix B gives 1–5 A for 5A-6; this program's checks accepted it"
        );
        let flap = Message::FlapSpec(FlapSpec {
            circuit_breaker: 7,
            ..crate::defaults::flap_spec()
        });
        assert_eq!(
            explain(InvalidBreaker, &c, &flap),
            "7 A was sent; the flap motor takes 1–10 A (ICD Table 16); this program's checks accepted it"
        );
    }

    #[test]
    fn factory_config_is_whole() {
        assert_eq!(whole_config(&cfg()), vec![]);
    }

    #[test]
    fn whole_config_lists_every_problem_with_its_path() {
        let mut c = cfg();
        c.devices[0x17].circuit_breaker = 1;
        c.devices[EFIS as usize].switch_id = SwitchId::Off;
        c.devices[10].device_id = 11;
        c.flap = flap(10, 100, 50, 200);
        c.pitch_trim.power = 20;
        c.roll_trim.trim_type = TrimType::Pitch;
        c.system.overvoltage_limit = OvervoltageLimit::Unknown(9);
        c.wig_wag = ww(None, Some(5));
        let got: Vec<(String, SpecAckError)> = whole_config(&c)
            .into_iter()
            .map(|p| (p.field, p.error))
            .collect();
        let want: Vec<(String, SpecAckError)> = [
            ("devices[2].switch_id", InvalidSwitch),
            ("devices[10].device_id", InvalidDevice),
            ("devices[23].circuit_breaker", InvalidBreaker),
            ("system.overvoltage_limit", OutOfRange),
            ("flap.midpoint_1", BadOrder),
            ("pitch_trim.power", OutOfRange),
            ("roll_trim.trim_type", BadConfig),
            ("wig_wag.device_two", BadConfig),
        ]
        .into_iter()
        .map(|(f, e)| (f.to_string(), e))
        .collect();
        assert_eq!(got, want);
        let p = &whole_config(&c)[2];
        assert_eq!(
            p.to_string(),
            "devices[23].circuit_breaker: 1 A is outside 5–15 A for 15A-1 (ICD Table 40)"
        );
    }

    #[test]
    fn whole_config_reports_each_conflict_once() {
        // Secondary alternator on the primary's switch.
        let mut c = with_switch(with_switch(cfg(), FIELD_PRI, on(2)), 12, on(2));
        c.system.secondary_alternator = Some(12);
        let p = whole_config(&c);
        assert_eq!(p.len(), 1, "{p:?}");
        assert_eq!(
            (p[0].field.as_str(), p[0].error),
            ("system.secondary_alternator", SecAltConfig)
        );

        // Wig-wag device on switch 0.
        let mut c = cfg();
        c.wig_wag = ww(Some(5), None);
        let p = whole_config(&c);
        assert_eq!(p.len(), 1, "{p:?}");
        assert_eq!(
            (p[0].field.as_str(), p[0].error),
            ("wig_wag.device_one", BadConfig)
        );

        // Secondary alternator that is also a wig-wag device.
        let mut c = with_switch(cfg(), 5, on(3));
        c.wig_wag = ww(Some(5), None);
        c.system.secondary_alternator = Some(5);
        let p = whole_config(&c);
        assert_eq!(p.len(), 1, "{p:?}");
        assert_eq!(
            (p[0].field.as_str(), p[0].error),
            ("system.secondary_alternator", WigWagConfig)
        );
    }

    #[test]
    fn whole_config_never_panics_on_nonsense() {
        let mut c = cfg();
        c.system.secondary_alternator = Some(250);
        c.wig_wag = ww(Some(250), Some(251));
        for d in c.devices.iter_mut() {
            d.switch_id = SwitchId::Unknown(99);
            d.circuit_breaker = 255;
            d.current_fault = true;
        }
        let p = whole_config(&c);
        assert!(p.len() >= 28, "{}", p.len());
    }

    #[test]
    fn device_spec_for_the_flaps_and_trims_is_an_invalid_device() {
        let c = UnitConfig::default();
        for id in [FLAPS, TRIM_R, TRIM_P] {
            let spec = DeviceSpec {
                device_id: id,
                ..super::super::defaults::device_spec(5)
            };
            assert_eq!(
                code(check_device_spec(&c, &spec)),
                Err(SpecAckError::InvalidDevice),
                "device {id}"
            );
        }
    }
}

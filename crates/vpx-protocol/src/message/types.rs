//! Enumerations shared by several messages. Each keeps a value it does not know in
//! `Unknown(u8)`, so nothing a unit sends is lost or misread.

use alloc::{format, string::String};

macro_rules! byte_enum {
    ($(#[$m:meta])* $name:ident { $($(#[$vm:meta])* $v:ident = $n:expr),+ $(,)? }) => {
        $(#[$m])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
        pub enum $name {
            $($(#[$vm])* $v,)+
            /// A byte the ICD table does not list, kept as it was.
            Unknown(u8),
        }
        impl $name {
            /// The value of a byte; unlisted bytes are kept in `Unknown`.
            pub fn from_byte(b: u8) -> Self {
                match b {
                    $($n => $name::$v,)+
                    n => $name::Unknown(n),
                }
            }
            /// The byte on the wire.
            pub fn to_byte(self) -> u8 {
                match self {
                    $($name::$v => $n,)+
                    $name::Unknown(n) => n,
                }
            }
        }
    };
}

byte_enum! {
    /// VERSION hardware version (ICD Table 11 note 1).
    HardwareVersion {
        /// 1: VP-X (Gen 1).
        VpxGen1 = 1,
        /// 2: VP-X Pro.
        VpxPro = 2,
        /// 3: VP-X Sport.
        VpxSport = 3,
    }
}

impl HardwareVersion {
    /// The product name of ICD Table 11 note 1, e.g. `VP-X Pro`.
    pub fn name(self) -> String {
        match self {
            HardwareVersion::VpxGen1 => "VP-X (Gen 1)".into(),
            HardwareVersion::VpxPro => "VP-X Pro".into(),
            HardwareVersion::VpxSport => "VP-X Sport".into(),
            HardwareVersion::Unknown(n) => format!("unknown hardware {n}"),
        }
    }
}

byte_enum! {
    /// SYSTEM_SPEC overvoltage limit (ICD Table 14).
    OvervoltageLimit {
        /// 0: 16 volts.
        V16 = 0,
        /// 1: 32 volts.
        V32 = 1,
    }
}

byte_enum! {
    /// Trim type: TRIM_SPEC flag bit and TRIM_MOVE byte (ICD Tables 15, 30).
    TrimType {
        /// 0: pitch.
        Pitch = 0,
        /// 1: roll.
        Roll = 1,
    }
}

byte_enum! {
    /// TRIM_MOVE direction (ICD Table 30 note 2): pitch down/up, roll right/left.
    TrimDirection {
        /// 0: pitch down or roll right.
        DownOrRight = 0,
        /// 1: pitch up or roll left.
        UpOrLeft = 1,
    }
}

byte_enum! {
    /// FLAP_MOVE direction (ICD Table 31).
    FlapDirection {
        /// 0: up.
        Up = 0,
        /// 1: down.
        Down = 1,
    }
}

byte_enum! {
    /// Wig-wag mode: WIG_WAG_MODE byte and SYSTEM_STATUS misc bit (ICD Tables 24, 32).
    WigWagModeSetting {
        /// 0: auto, the wig-wag engages as WIG_WAG_SPEC configures it (§6.4.4).
        Auto = 0,
        /// 1: steady, the lights stay on.
        Steady = 1,
    }
}

byte_enum! {
    /// DEVICE_ENABLE flag (ICD Table 23).
    EnableFlag {
        /// 0: disabled.
        Disabled = 0,
        /// 1: enabled.
        Enabled = 1,
        /// 2: asks the unit for the current state.
        Query = 2,
    }
}

byte_enum! {
    /// SPEC_ACK error codes (ICD Table 20; icd-reading R11: 0x01–0x09).
    SpecAckError {
        /// 0x01: parameter value out of range.
        OutOfRange = 0x01,
        /// 0x02: invalid device identifier.
        InvalidDevice = 0x02,
        /// 0x03: invalid circuit breaker value.
        InvalidBreaker = 0x03,
        /// 0x04: invalid switch ID.
        InvalidSwitch = 0x04,
        /// 0x05: invalid configuration (SPEC_ACK_BAD_CONFIG).
        BadConfig = 0x05,
        /// 0x06: EEPROM write failure.
        EepromWrite = 0x06,
        /// 0x07: parameters out of order (SPEC_ACK_BAD_ORDER).
        BadOrder = 0x07,
        /// 0x08: wig-wag configuration error (SPEC_ACK_WIG_WAG_CONFIG).
        WigWagConfig = 0x08,
        /// 0x09: secondary alternator configuration error (SPEC_ACK_SEC_ALT_CONFIG).
        SecAltConfig = 0x09,
    }
}

impl SpecAckError {
    /// The words of ICD Table 20.
    pub fn description(self) -> String {
        match self {
            SpecAckError::OutOfRange => "Parameter value out of range".into(),
            SpecAckError::InvalidDevice => "Invalid device identifier".into(),
            SpecAckError::InvalidBreaker => "Invalid circuit breaker value".into(),
            SpecAckError::InvalidSwitch => "Invalid switch ID".into(),
            SpecAckError::BadConfig => "Invalid configuration".into(),
            SpecAckError::EepromWrite => "EEPROM write failure".into(),
            SpecAckError::BadOrder => "Parameters out of order".into(),
            SpecAckError::WigWagConfig => "Wig-Wag configuration error".into(),
            SpecAckError::SecAltConfig => "Secondary alternator configuration error".into(),
            SpecAckError::Unknown(n) => format!("Unknown error code {n:#04x}"),
        }
    }
}

byte_enum! {
    /// SYSTEM_STATUS data integrity error codes (ICD Table 25).
    DataIntegrityCode {
        /// 0x01: general EEPROM error.
        GeneralEeprom = 0x01,
        /// 0x02: system configuration error.
        SystemConfig = 0x02,
        /// 0x03: device configuration error.
        DeviceConfig = 0x03,
        /// 0x04: flap configuration error.
        FlapConfig = 0x04,
        /// 0x05: trim configuration error.
        TrimConfig = 0x05,
        /// 0x06: wig-wag configuration error.
        WigWagConfig = 0x06,
    }
}

impl DataIntegrityCode {
    /// The words of ICD Table 25.
    pub fn description(self) -> String {
        match self {
            DataIntegrityCode::GeneralEeprom => "General EEPROM error".into(),
            DataIntegrityCode::SystemConfig => "System configuration error".into(),
            DataIntegrityCode::DeviceConfig => "Device configuration error".into(),
            DataIntegrityCode::FlapConfig => "Flap configuration error".into(),
            DataIntegrityCode::TrimConfig => "Trim configuration error".into(),
            DataIntegrityCode::WigWagConfig => "Wig-wag configuration error".into(),
            DataIntegrityCode::Unknown(n) => format!("Unknown data integrity code {n:#04x}"),
        }
    }
}

/// The external switch a device follows (ICD Table 13 notes 3–6).
///
/// icd-reading R10: 11 means "always on" in most places of the ICD, 255 in one. We
/// decode both as [`SwitchId::AlwaysOn`] and always send 11.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum SwitchId {
    /// 0: the device is always off.
    Off,
    /// 1–10: the device follows that external switch input.
    Input(u8),
    /// 11 (or 255 when decoding): the device is always on.
    AlwaysOn,
    /// Any other byte, kept as it was.
    Unknown(u8),
}

impl SwitchId {
    /// The byte sent for always on (icd-reading R10: 11, not 255).
    pub const ALWAYS_ON_BYTE: u8 = 11;

    /// The switch of a DEVICE_SPEC byte 3 (ICD Table 13).
    pub fn from_byte(b: u8) -> Self {
        match b {
            0 => SwitchId::Off,
            1..=10 => SwitchId::Input(b),
            11 | 255 => SwitchId::AlwaysOn,
            n => SwitchId::Unknown(n),
        }
    }

    /// The DEVICE_SPEC byte 3 (ICD Table 13); always on is sent as 11.
    pub fn to_byte(self) -> u8 {
        match self {
            SwitchId::Off => 0,
            SwitchId::Input(n) => n,
            SwitchId::AlwaysOn => Self::ALWAYS_ON_BYTE,
            SwitchId::Unknown(n) => n,
        }
    }

    /// A short label for people: `off`, `sw 3`, `always on`.
    pub fn label(self) -> String {
        match self {
            SwitchId::Off => "off".into(),
            SwitchId::Input(n) => format!("sw {n}"),
            SwitchId::AlwaysOn => "always on".into(),
            SwitchId::Unknown(n) => format!("? {n}"),
        }
    }
}

/// A quantity the ICD sends in tenths (amps, volts, seconds), unsigned: e.g. ICD Table 24
/// bytes 1–2, Table 26 currents, Table 16 endpoint duration.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Hash,
    Default,
    serde::Serialize,
    serde::Deserialize,
)]
pub struct Tenths(pub u16);

impl Tenths {
    /// The quantity in whole units (amps, volts or seconds).
    pub fn value(self) -> f32 {
        self.0 as f32 / 10.0
    }
}

/// A quantity the ICD sends in tenths, signed (main bus volts, ICD Table 24 bytes 3–4).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Hash,
    Default,
    serde::Serialize,
    serde::Deserialize,
)]
pub struct SignedTenths(pub i16);

impl SignedTenths {
    /// The quantity in whole units (volts).
    pub fn value(self) -> f32 {
        self.0 as f32 / 10.0
    }
}

/// Motor polarity bit of TRIM_SPEC and FLAP_SPEC (ICD Tables 15, 16).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Polarity {
    /// 0: standard.
    Standard,
    /// 1: inverted, the motor runs the other way.
    Inverted,
}

/// Flap mode bit of FLAP_SPEC (ICD Table 16 note 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum FlapMode {
    /// 0: momentary, the flaps run while the switch is held.
    Momentary,
    /// 1: position-based, the flaps run to the next position.
    PositionBased,
}

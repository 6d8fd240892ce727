//! Enumerations shared by several messages. Each keeps a value it does not know in
//! `Unknown(u8)`, so nothing a unit sends is lost or misread.

macro_rules! byte_enum {
    ($(#[$m:meta])* $name:ident { $($(#[$vm:meta])* $v:ident = $n:expr),+ $(,)? }) => {
        $(#[$m])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
        pub enum $name {
            $($(#[$vm])* $v,)+
            Unknown(u8),
        }
        impl $name {
            pub fn from_byte(b: u8) -> Self {
                match b {
                    $($n => $name::$v,)+
                    n => $name::Unknown(n),
                }
            }
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
    HardwareVersion { VpxGen1 = 1, VpxPro = 2, VpxSport = 3 }
}

impl HardwareVersion {
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
    OvervoltageLimit { V16 = 0, V32 = 1 }
}

byte_enum! {
    /// Trim type: TRIM_SPEC flag bit and TRIM_MOVE byte (ICD Tables 15, 30).
    TrimType { Pitch = 0, Roll = 1 }
}

byte_enum! {
    /// TRIM_MOVE direction (ICD Table 30 note 2): pitch down/up, roll right/left.
    TrimDirection { DownOrRight = 0, UpOrLeft = 1 }
}

byte_enum! {
    /// FLAP_MOVE direction (ICD Table 31).
    FlapDirection { Up = 0, Down = 1 }
}

byte_enum! {
    /// Wig-wag mode: WIG_WAG_MODE byte and SYSTEM_STATUS misc bit (ICD Tables 24, 32).
    WigWagModeSetting { Auto = 0, Steady = 1 }
}

byte_enum! {
    /// DEVICE_ENABLE flag (ICD Table 23).
    EnableFlag { Disabled = 0, Enabled = 1, Query = 2 }
}

byte_enum! {
    /// SPEC_ACK error codes (ICD Table 20; reading note 11: 0x01–0x09).
    SpecAckError {
        OutOfRange = 0x01,
        InvalidDevice = 0x02,
        InvalidBreaker = 0x03,
        InvalidSwitch = 0x04,
        BadConfig = 0x05,
        EepromWrite = 0x06,
        BadOrder = 0x07,
        WigWagConfig = 0x08,
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
        GeneralEeprom = 0x01,
        SystemConfig = 0x02,
        DeviceConfig = 0x03,
        FlapConfig = 0x04,
        TrimConfig = 0x05,
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
/// Reading note 10: 11 means "always on" in most places of the ICD, 255 in one. We
/// decode both as [`SwitchId::AlwaysOn`] and always send 11.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum SwitchId {
    /// 0: the device is always off.
    Off,
    /// 1–10: the device follows that external switch input.
    Input(u8),
    /// 11 (or 255 when decoding): the device is always on.
    AlwaysOn,
    Unknown(u8),
}

impl SwitchId {
    pub const ALWAYS_ON_BYTE: u8 = 11;

    pub fn from_byte(b: u8) -> Self {
        match b {
            0 => SwitchId::Off,
            1..=10 => SwitchId::Input(b),
            11 | 255 => SwitchId::AlwaysOn,
            n => SwitchId::Unknown(n),
        }
    }

    pub fn to_byte(self) -> u8 {
        match self {
            SwitchId::Off => 0,
            SwitchId::Input(n) => n,
            SwitchId::AlwaysOn => Self::ALWAYS_ON_BYTE,
            SwitchId::Unknown(n) => n,
        }
    }

    pub fn label(self) -> String {
        match self {
            SwitchId::Off => "off".into(),
            SwitchId::Input(n) => format!("sw {n}"),
            SwitchId::AlwaysOn => "always on".into(),
            SwitchId::Unknown(n) => format!("? {n}"),
        }
    }
}

/// A quantity the ICD sends in tenths (amps, volts, seconds), unsigned.
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
    pub fn value(self) -> f32 {
        self.0 as f32 / 10.0
    }
}

/// A quantity the ICD sends in tenths, signed (main bus volts).
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
    pub fn value(self) -> f32 {
        self.0 as f32 / 10.0
    }
}

/// Motor polarity bit of TRIM_SPEC and FLAP_SPEC (ICD Tables 15, 16).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Polarity {
    Standard,
    Inverted,
}

/// Flap mode bit of FLAP_SPEC (ICD Table 16 note 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum FlapMode {
    Momentary,
    PositionBased,
}

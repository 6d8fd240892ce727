//! Enumerations shared by several messages. Each keeps a value it does not know in
//! `Unknown(u8)`, so nothing a unit sends is lost or misread.

use alloc::{format, string::String};

/// An enum over one byte of an ICD table: each row's name, byte and words, and an
/// `Unknown(u8)` that keeps any byte the table does not list.
macro_rules! byte_enum {
    ($(#[$m:meta])* $name:ident { $($v:ident = $n:literal => $words:literal),+ $(,)? }) => {
        $(#[$m])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
        pub enum $name {
            $(#[doc = concat!(stringify!($n), ": ", $words, ".")] $v,)+
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
            /// The words of the value's row; `None` for a byte the table does not list.
            pub fn words(self) -> Option<&'static str> {
                match self {
                    $($name::$v => Some($words),)+
                    $name::Unknown(_) => None,
                }
            }
        }
    };
}

byte_enum! {
    /// VERSION hardware version (ICD Table 11 note 1).
    HardwareVersion {
        VpxGen1 = 1 => "VP-X (Gen 1)",
        VpxPro = 2 => "VP-X Pro",
        VpxSport = 3 => "VP-X Sport",
    }
}

impl HardwareVersion {
    /// The product name of ICD Table 11 note 1, e.g. `VP-X Pro`.
    pub fn name(self) -> String {
        self.words().map_or_else(
            || format!("unknown hardware {}", self.to_byte()),
            String::from,
        )
    }
}

byte_enum! {
    /// SYSTEM_SPEC overvoltage limit (ICD Table 14).
    OvervoltageLimit {
        V16 = 0 => "16 V",
        V32 = 1 => "32 V",
    }
}

byte_enum! {
    /// Trim type: TRIM_SPEC flag bit and TRIM_MOVE byte (ICD Tables 15, 30).
    TrimType {
        Pitch = 0 => "pitch",
        Roll = 1 => "roll",
    }
}

byte_enum! {
    /// TRIM_MOVE direction (ICD Table 30 note 2): pitch down/up, roll right/left.
    TrimDirection {
        DownOrRight = 0 => "pitch down or roll right",
        UpOrLeft = 1 => "pitch up or roll left",
    }
}

byte_enum! {
    /// FLAP_MOVE direction (ICD Table 31).
    FlapDirection {
        Up = 0 => "up",
        Down = 1 => "down",
    }
}

byte_enum! {
    /// Wig-wag mode: WIG_WAG_MODE byte and SYSTEM_STATUS misc bit (ICD Tables 24, 32).
    /// Auto engages the wig-wag as WIG_WAG_SPEC configures it (§6.4.4); steady keeps
    /// the lights on.
    WigWagModeSetting {
        Auto = 0 => "auto",
        Steady = 1 => "steady",
    }
}

byte_enum! {
    /// DEVICE_ENABLE flag (ICD Table 23); 2 asks the unit for the current state.
    EnableFlag {
        Disabled = 0 => "disabled",
        Enabled = 1 => "enabled",
        Query = 2 => "query",
    }
}

byte_enum! {
    /// SPEC_ACK error codes, in the words of ICD Table 20 (icd-reading R11: 0x01–0x09).
    /// 0x05, 0x07, 0x08 and 0x09 are the ICD's SPEC_ACK_BAD_CONFIG, SPEC_ACK_BAD_ORDER,
    /// SPEC_ACK_WIG_WAG_CONFIG and SPEC_ACK_SEC_ALT_CONFIG.
    SpecAckError {
        OutOfRange = 0x01 => "Parameter value out of range",
        InvalidDevice = 0x02 => "Invalid device identifier",
        InvalidBreaker = 0x03 => "Invalid circuit breaker value",
        InvalidSwitch = 0x04 => "Invalid switch ID",
        BadConfig = 0x05 => "Invalid configuration",
        EepromWrite = 0x06 => "EEPROM write failure",
        BadOrder = 0x07 => "Parameters out of order",
        WigWagConfig = 0x08 => "Wig-Wag configuration error",
        SecAltConfig = 0x09 => "Secondary alternator configuration error",
    }
}

impl SpecAckError {
    /// The words of ICD Table 20.
    pub fn description(self) -> String {
        self.words().map_or_else(
            || format!("Unknown error code {:#04x}", self.to_byte()),
            String::from,
        )
    }
}

byte_enum! {
    /// SYSTEM_STATUS data integrity error codes, in the words of ICD Table 25.
    DataIntegrityCode {
        GeneralEeprom = 0x01 => "General EEPROM error",
        SystemConfig = 0x02 => "System configuration error",
        DeviceConfig = 0x03 => "Device configuration error",
        FlapConfig = 0x04 => "Flap configuration error",
        TrimConfig = 0x05 => "Trim configuration error",
        WigWagConfig = 0x06 => "Wig-wag configuration error",
    }
}

impl DataIntegrityCode {
    /// The words of ICD Table 25.
    pub fn description(self) -> String {
        self.words().map_or_else(
            || format!("Unknown data integrity code {:#04x}", self.to_byte()),
            String::from,
        )
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

//! Writing the backup file: the file's sections as `serde` structs, each value in the
//! file's words and units (the keys and their order are [`schema`](super::schema)'s,
//! held by its test), and the header that says what the file is.

use serde::Serialize;
use serde::ser::SerializeMap;

use super::provenance::Provenance;
use super::{Backup, FORMAT};
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{self, FLAPS, TRIM_P, TRIM_R, enable_flag_allowed};
use crate::protocol::message::{FlapMode, OvervoltageLimit, Polarity, SwitchId, TrimSpec};

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BackupFile {
    pub format: u32,
    /// When, from what and by what the backup was made; optional (see [`super::provenance`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub made: Option<Provenance>,
    pub unit: UnitSection,
    pub system: SystemSection,
    pub flaps: FlapSection,
    pub pitch_trim: TrimSection,
    pub roll_trim: TrimSection,
    pub wig_wag: WigWagSection,
    pub devices: Devices,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UnitSection {
    pub hardware_version: u8,
    pub hardware: String,
    pub software: String,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SystemSection {
    pub overvoltage_limit_volts: u8,
    pub secondary_alternator: String,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlapSection {
    pub name: String,
    pub enabled: bool,
    pub mode: String,
    pub polarity: String,
    pub up: u8,
    pub midpoint_1: u8,
    pub midpoint_2: u8,
    pub down: u8,
    pub breaker_amps: u8,
    pub overspeed_position: u8,
    pub max_speed_kt: u16,
    pub endpoint_duration_s: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrimSection {
    pub name: String,
    pub enabled: bool,
    pub polarity: String,
    pub up: u8,
    pub down: u8,
    pub neutral: u8,
    pub reduced_power_percent: u8,
    pub reduce_above_kt: u16,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WigWagSection {
    pub device_one: String,
    pub device_two: String,
    pub warm_up_s: u8,
    pub speed_kt: u8,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviceSection {
    pub name: String,
    /// Absent for the starter, EFIS and primary field, which are always shown.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub show_on_page: Option<bool>,
    pub breaker_amps: u8,
    pub switch: Switch,
    pub current_fault: bool,
}

/// `"off"`, `1`–`10` or `"always-on"`. `Input` also carries a number outside 1–10
/// that a unit reported, so that it is written as it is (and refused on loading).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Switch {
    Off,
    Input(u8),
    AlwaysOn,
}

impl Serialize for Switch {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Switch::Off => s.serialize_str("off"),
            Switch::Input(n) => s.serialize_u8(*n),
            Switch::AlwaysOn => s.serialize_str("always-on"),
        }
    }
}

/// Pins 1–28 by Table 40 name, written in device-id order so the file reads like the
/// table (a map would sort `10A-1` before `2A-1`).
#[derive(Debug, Clone, PartialEq)]
pub struct Devices(pub Vec<(String, DeviceSection)>);

impl Serialize for Devices {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}

// ------------------------------------------------------------------ words ↔ values

/// What the file says for no pin.
pub(super) const NONE: &str = "none";

/// A pin by its ICD Table 40 name, as the file names it.
pub(super) fn pin_name(id: u8) -> String {
    device::device(id).map_or_else(|| id.to_string(), |d| d.system_name.to_string())
}

fn opt_pin(id: Option<u8>) -> String {
    id.map_or_else(|| NONE.to_string(), pin_name)
}

fn polarity_word(p: Polarity) -> &'static str {
    match p {
        Polarity::Standard => "standard",
        Polarity::Inverted => "inverted",
    }
}

fn mode_word(m: FlapMode) -> &'static str {
    match m {
        FlapMode::Momentary => "momentary",
        FlapMode::PositionBased => "position-based",
    }
}

/// The 16 name bytes up to the first NUL, one char per byte (Latin-1).
pub fn name_text(bytes: &[u8; 16]) -> String {
    bytes
        .iter()
        .take_while(|&&b| b != 0)
        .map(|&b| b as char)
        .collect()
}

/// What a name means: its bytes up to the first NUL, the rest zero (ICD Table 21).
/// Bytes after a NUL are never shown by anyone, so they are not part of a backup.
pub fn normalize_name(bytes: &[u8; 16]) -> [u8; 16] {
    let mut out = [0u8; 16];
    for (o, &b) in out.iter_mut().zip(bytes.iter().take_while(|&&b| b != 0)) {
        *o = b;
    }
    out
}

/// `cfg` with every name normalized, for comparing what a unit holds with a file.
pub fn normalized(cfg: &UnitConfig) -> UnitConfig {
    let mut c = cfg.clone();
    for n in c.names.iter_mut() {
        *n = normalize_name(n);
    }
    c
}

fn switch_of(s: SwitchId) -> Switch {
    match s {
        SwitchId::Off => Switch::Off,
        SwitchId::Input(n) | SwitchId::Unknown(n) => Switch::Input(n),
        SwitchId::AlwaysOn => Switch::AlwaysOn,
    }
}

impl BackupFile {
    /// The file form of a backup. A value the unit reports outside the ICD's encodings
    /// (a switch id 12, an overvoltage code 7) is written as its raw number, so nothing
    /// the unit holds is lost; [`from_toml`](super::from_toml) then refuses it by its path.
    pub fn from_backup(b: &Backup) -> BackupFile {
        let cfg = &b.config;
        let overvoltage_limit_volts = match cfg.system.overvoltage_limit {
            OvervoltageLimit::V16 => 16,
            OvervoltageLimit::V32 => 32,
            OvervoltageLimit::Unknown(n) => n,
        };
        let trim = |t: &TrimSpec, name_id: u8| TrimSection {
            name: name_text(&cfg.names[name_id as usize]),
            enabled: t.enabled,
            polarity: polarity_word(t.polarity).into(),
            up: t.up,
            down: t.down,
            neutral: t.neutral,
            reduced_power_percent: t.power,
            reduce_above_kt: t.speed,
        };
        let devices = (1..TRIM_R)
            .map(|id| {
                let d = &cfg.devices[id as usize];
                let section = DeviceSection {
                    name: name_text(&cfg.names[id as usize]),
                    show_on_page: enable_flag_allowed(id).then_some(cfg.enabled[id as usize]),
                    breaker_amps: d.circuit_breaker,
                    switch: switch_of(d.switch_id),
                    current_fault: d.current_fault,
                };
                (pin_name(id), section)
            })
            .collect();
        BackupFile {
            format: FORMAT,
            made: None,
            unit: UnitSection {
                hardware_version: b.version.hardware_version.to_byte(),
                hardware: b.version.hardware_version.name(),
                software: format!("{}.{}", b.version.software_major, b.version.software_minor),
            },
            system: SystemSection {
                overvoltage_limit_volts,
                secondary_alternator: opt_pin(cfg.system.secondary_alternator),
            },
            flaps: FlapSection {
                name: name_text(&cfg.names[FLAPS as usize]),
                enabled: cfg.flap.enabled,
                mode: mode_word(cfg.flap.mode).into(),
                polarity: polarity_word(cfg.flap.polarity).into(),
                up: cfg.flap.up,
                midpoint_1: cfg.flap.midpoint_1,
                midpoint_2: cfg.flap.midpoint_2,
                down: cfg.flap.down,
                breaker_amps: cfg.flap.circuit_breaker,
                overspeed_position: cfg.flap.overspeed_position,
                max_speed_kt: cfg.flap.max_speed,
                endpoint_duration_s: cfg.flap.endpoint_duration.0 as f64 / 10.0,
            },
            pitch_trim: trim(&cfg.pitch_trim, TRIM_P),
            roll_trim: trim(&cfg.roll_trim, TRIM_R),
            wig_wag: WigWagSection {
                device_one: opt_pin(cfg.wig_wag.device_one),
                device_two: opt_pin(cfg.wig_wag.device_two),
                warm_up_s: cfg.wig_wag.warm_up_period,
                speed_kt: cfg.wig_wag.speed,
            },
            devices: Devices(devices),
        }
    }

    /// The TOML text, with a header that says what the file is and how to use it.
    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).unwrap_or_else(|e| {
            // Only plain strings, integers, floats and tables are serialized, all of
            // which TOML can express; a failure here is a bug, said in the file itself.
            format!("# could not write this backup: {e}\n")
        });
        format!("{HEADER}\n{body}")
    }
}

const HEADER: &str = "\
# VP-X configuration backup written by vpx-efis.
# Restore it with `vpx-efis restore --port PATH FILE`; the file is checked as a whole
# and every problem is listed before anything is sent to the unit.
# Units: breaker_amps in amps, *_s in seconds (to 0.1 s), *_kt in knots (the airspeed
# unit this EFIS sends the VP-X), *_percent in percent. Pins are named as in ICD
# Table 40. switch is \"off\", 1-10 or \"always-on\". Names are up to 16 characters.
";

/// The TOML text of a backup.
pub fn to_toml(b: &Backup) -> String {
    BackupFile::from_backup(b).to_toml()
}

/// The TOML text of a backup with its `[made]` section.
pub fn to_toml_made(b: &Backup, made: &Provenance) -> String {
    let mut f = BackupFile::from_backup(b);
    f.made = Some(made.clone());
    f.to_toml()
}

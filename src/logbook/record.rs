//! What is recorded: plain data, built by whoever did the thing (the check flow's
//! results, the setup screens, backup, restore, flash, the stop gate) and written by
//! the [`super::writer`] thread. Nothing here reads the unit or a file.

use std::time::SystemTime;

use crate::audit;

/// "command line": a subcommand (`backup`, `restore`, `flash`, the headless check)
/// run by a person at a prompt. The other origins are [`audit::Origin::word`]'s.
pub const COMMAND_LINE: &str = "command line";

/// One record: when, who, a line in words, and what.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    pub at: SystemTime,
    /// Who did it: [`audit::Origin::word`] or [`COMMAND_LINE`].
    pub origin: &'static str,
    /// One line in words, as `vpx-efis log` lists it.
    pub summary: String,
    pub what: What,
}

/// What the entry holds beyond its line (see [`super::schema`] for the tables).
#[derive(Debug, Clone, PartialEq)]
pub enum What {
    Check(Box<Check>),
    Backup {
        path: Option<String>,
        text: String,
    },
    /// A restore, with each setting it changed.
    Restore {
        changes: Vec<SettingChange>,
    },
    /// One setup write.
    Setting(SettingChange),
    Firmware(Firmware),
    /// A line of the audit log (a command sent, a reset, a motor run's start or stop).
    Command(audit::Line),
    Fault {
        device: u8,
        name: String,
        fault: String,
    },
}

impl What {
    /// `entries.kind`.
    pub fn kind(&self) -> &'static str {
        use super::schema::kind;
        match self {
            What::Check(_) => kind::CHECK,
            What::Backup { .. } => kind::BACKUP,
            What::Restore { .. } => kind::RESTORE,
            What::Setting(_) => kind::SETTING,
            What::Firmware(_) => kind::FIRMWARE,
            What::Command(l) if l.run.is_some() => kind::RUN,
            What::Command(l) if l.command.starts_with("DEVICE_CLEAR") => kind::RESET,
            What::Command(_) => kind::COMMAND,
            What::Fault { .. } => kind::FAULT,
        }
    }
}

/// A check, as its report has it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Check {
    pub port: String,
    /// This program's version.
    pub program: String,
    /// "1 failed, 14 passed".
    pub tally: String,
    /// Why it stopped early; `None`: it finished.
    pub interrupted: Option<String>,
    pub report: Option<String>,
    pub load_path: Option<String>,
    /// The load file's text as it was at the check.
    pub load_file: Option<String>,
    pub alternator_amps: Option<f64>,
    pub battery_amp_hours: Option<f64>,
    pub battery_usable: Option<f64>,
    pub circuits: Vec<CheckCircuit>,
    pub switches: Vec<CheckItem>,
    pub motors: Vec<CheckMotor>,
    pub loads: Vec<CheckLoad>,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct CheckCircuit {
    pub device: u8,
    pub name: String,
    pub pin: String,
    pub breaker: Option<u8>,
    pub switch: Option<String>,
    /// Measured; `None`: none.
    pub amps: Option<f64>,
    /// `PASS`, `WARN`, `FAIL`, `SKIPPED`, `NOT RUN`, as the report prints them.
    pub verdict: String,
    pub finding: String,
}

/// A switch input's line.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CheckItem {
    /// "switch 3".
    pub input: String,
    /// Its circuits, in words.
    pub circuits: String,
    pub verdict: String,
    pub finding: String,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct CheckMotor {
    /// "pitch trim".
    pub motor: String,
    /// "20 200 20".
    pub positions: String,
    pub verdict: String,
    pub finding: String,
}

/// One phase of the load analysis.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CheckLoad {
    pub phase: String,
    pub amps: f64,
    pub margin_percent: Option<f64>,
    pub endurance_minutes: Option<f64>,
    /// `ok`, `warning`, `failed`.
    pub level: String,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct SettingChange {
    /// "Landing Lt breaker".
    pub setting: String,
    pub old: Option<String>,
    pub new: String,
    /// The unit's read-back matched.
    pub confirmed: bool,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Firmware {
    /// Hex, lower case.
    pub image_sha256: String,
    pub image_path: String,
    pub version_before: Option<String>,
    pub version_after: Option<String>,
    /// "updated", "failed: …".
    pub outcome: String,
}

/// The unit as it tells who it is: VERSION (ICD Table 11) and the names its
/// circuits hold, in device-id order.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Unit {
    /// "VP-X Pro".
    pub hardware: String,
    /// "1.4".
    pub software: String,
    pub names: Vec<String>,
}

impl Unit {
    /// The unit from its VERSION and its names, by device id.
    pub fn of(v: &crate::protocol::message::Version, names: Vec<String>) -> Unit {
        Unit {
            hardware: v.hardware_version.name().to_string(),
            software: format!("{}.{}", v.software_major, v.software_minor),
            names,
        }
    }

    /// The unit as a backup holds it: VERSION and the raw names.
    pub fn of_config(
        v: &crate::protocol::message::Version,
        config: &crate::protocol::config::UnitConfig,
    ) -> Unit {
        let names = config
            .names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                crate::protocol::message::DeviceName {
                    device_id: i as u8,
                    name: *n,
                }
                .text()
            })
            .collect();
        Unit::of(v, names)
    }

    /// `units.identity`: the three as one text, one per line.
    pub fn identity(&self) -> String {
        format!(
            "{}\n{}\n{}",
            self.hardware,
            self.software,
            self.names.join("\n")
        )
    }
}

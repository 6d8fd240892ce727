//! Backups of a VP-X's whole configuration: the TOML file format (below), what a
//! restore would change ([`diff`]), the order a restore writes in ([`plan`]), and
//! reading and writing the file (here). No I/O with the unit: the `backup` and
//! `restore` commands and the setup screens bring a [`UnitClient`](crate::link::UnitClient).
//!
//! The backup file is a VP-X's whole configuration as TOML a person can read and edit.
//!
//! ```toml
//! format = 1
//!
//! [unit]                            # the unit the backup was taken from (ICD Table 11)
//! hardware_version = 2              # 1 VP-X (Gen 1), 2 VP-X Pro, 3 VP-X Sport
//! hardware = "VP-X Pro"             # for people; ignored when loading
//! software = "3.7"                  # major.minor
//!
//! [system]                          # SYSTEM_SPEC, ICD Table 14
//! overvoltage_limit_volts = 16      # 16 or 32
//! secondary_alternator = "none"     # "none" or a pin as named in Table 40, e.g. "10A-2"
//!
//! [flaps]                           # FLAP_SPEC, Table 16; name is DEVICE_NAME 0
//! name = "Flaps"
//! enabled = true                    # false when the aircraft has no VP-X flaps
//! mode = "position-based"           # or "momentary"
//! polarity = "standard"             # or "inverted"
//! up = 10                           # position sensor readings, 0–255
//! midpoint_1 = 60
//! midpoint_2 = 120
//! down = 200
//! breaker_amps = 7
//! overspeed_position = 20
//! max_speed_kt = 100
//! endpoint_duration_s = 0.5         # in tenths of a second on the wire (icd-reading R23)
//!
//! [pitch_trim]                      # TRIM_SPEC, Table 15; name is DEVICE_NAME 30
//! name = ""
//! enabled = true
//! polarity = "standard"
//! up = 200
//! down = 20
//! neutral = 110
//! reduced_power_percent = 60        # motor power above reduce_above_kt (40–90; 100 = factory)
//! reduce_above_kt = 120
//!
//! [roll_trim]                       # the same fields; name is DEVICE_NAME 29
//! # ...
//!
//! [wig_wag]                         # WIG_WAG_SPEC, Table 17
//! device_one = "5A-7"               # "none" or a pin name
//! device_two = "5A-8"
//! warm_up_s = 5
//! speed_kt = 70
//!
//! [devices.5A-3]                    # one table per pin 1–28, named as in Table 40
//! name = "Strobe Lt"                # DEVICE_NAME: up to 16 bytes; "" = never named
//! show_on_page = true               # DEVICE_ENABLE (pins 4–28 only)
//! breaker_amps = 5                  # DEVICE_SPEC: within the pin's Appendix B range
//! switch = 3                        # "off", 1–10 or "always-on"
//! current_fault = true
//! ```
//!
//! Speeds are in knots: the unit compares them with the airspeed this EFIS sends it in
//! EXTERNAL_DATA, and this EFIS sends knots (icd-reading R20). Names are single bytes:
//! each character U+0000–U+00FF is one byte (Latin-1), so a name the unit holds comes
//! back byte for byte, while anything above U+00FF is refused.
//!
//! Each setting is written once, in [`schema`]: the [`writer`], the [`reader`], the
//! [`path`] map from the §6.2 rules' names to the file's, and the [`diff`](mod@diff)
//! read it.

pub mod diff;
pub mod path;
pub mod plan;
pub mod provenance;
pub mod reader;
pub mod schema;
pub mod writer;

use std::path::Path;

pub use diff::{Change, diff};
pub use plan::{RestoreWrite, plan};
pub use provenance::Provenance;
pub use reader::{from_toml, from_toml_made};
pub use writer::{normalized, to_toml, to_toml_made};

use crate::protocol::config::UnitConfig;
use crate::protocol::message::Version;
use crate::toml_lines::FileError;

/// The `format` number this program writes and reads.
pub const FORMAT: u32 = 1;

/// A unit's configuration together with the version of the unit it came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Backup {
    pub version: Version,
    pub config: UnitConfig,
}

/// What a backup file is called in what is said of it.
const KIND: &str = "backup file";

/// Reads and checks a backup file as a whole (see [`from_toml_made`]), and where the
/// backup came from if the file says.
pub fn load_made(path: &Path) -> Result<(Backup, Option<Provenance>), FileError> {
    read_made(path, std::fs::read_to_string(path))
}

/// [`load_made`] of a file someone else read: its text, or why it could not be read.
pub fn read(path: &Path, text: std::io::Result<String>) -> Result<Backup, FileError> {
    read_made(path, text).map(|(b, _)| b)
}

/// [`load_made`] of a file someone else read.
pub fn read_made(
    path: &Path,
    text: std::io::Result<String>,
) -> Result<(Backup, Option<Provenance>), FileError> {
    let text = text.map_err(|e| FileError::unreadable(KIND, path.to_path_buf(), &e))?;
    from_toml_made(&text).map_err(|problems| FileError {
        kind: KIND,
        path: path.to_path_buf(),
        problems,
    })
}

/// Refuses a backup taken from other hardware: pins, ranges and defaults differ between
/// the VP-X models (ICD Table 11 note 1), so one model's settings are not another's.
pub fn check_hardware(backup: &Version, unit: &Version) -> Result<(), String> {
    if backup.hardware_version == unit.hardware_version {
        return Ok(());
    }
    Err(format!(
        "this backup is from a {} (hardware version {}) but the unit is a {} (hardware \
         version {}); a configuration is only restored onto the hardware it was taken \
         from. Nothing was sent to the unit.",
        backup.hardware_version.name(),
        backup.hardware_version.to_byte(),
        unit.hardware_version.name(),
        unit.hardware_version.to_byte(),
    ))
}

/// A software version difference is allowed but worth saying.
pub fn software_note(backup: &Version, unit: &Version) -> Option<String> {
    let (b, u) = (
        (backup.software_major, backup.software_minor),
        (unit.software_major, unit.software_minor),
    );
    (b != u).then(|| {
        format!(
            "note: the backup was taken from software {}.{}; the unit runs {}.{}",
            b.0, b.1, u.0, u.1
        )
    })
}

/// Writes a backup with its `[made]` section (when, from what, by which program) so
/// that an interrupted write leaves either the old file or the new one, never half of
/// one ([`crate::files::write_atomically`]).
pub fn save_made(path: &Path, backup: &Backup, made: &Provenance) -> std::io::Result<()> {
    crate::files::write_atomically(path, to_toml_made(backup, made).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::config::UnitConfig;
    use crate::protocol::message::HardwareVersion;

    fn v(hw: HardwareVersion, major: u8, minor: u8) -> Version {
        Version {
            hardware_version: hw,
            software_major: major,
            software_minor: minor,
        }
    }

    #[test]
    fn a_backup_from_other_hardware_is_refused_in_words() {
        let err = check_hardware(
            &v(HardwareVersion::VpxPro, 1, 0),
            &v(HardwareVersion::VpxSport, 1, 0),
        )
        .unwrap_err();
        assert!(
            err.starts_with(
                "this backup is from a VP-X Pro (hardware version 2) but the unit is a \
                 VP-X Sport (hardware version 3)"
            ),
            "{err}"
        );
        assert!(
            check_hardware(
                &v(HardwareVersion::VpxPro, 1, 0),
                &v(HardwareVersion::VpxPro, 2, 0)
            )
            .is_ok()
        );
        assert_eq!(
            software_note(
                &v(HardwareVersion::VpxPro, 1, 0),
                &v(HardwareVersion::VpxPro, 2, 1)
            )
            .as_deref(),
            Some("note: the backup was taken from software 1.0; the unit runs 2.1")
        );
    }

    #[test]
    fn a_load_error_names_path_line_and_field_of_every_problem() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.toml");
        let good = to_toml(&Backup {
            version: v(HardwareVersion::VpxPro, 1, 2),
            config: UnitConfig::default(),
        });
        let bad = good
            .replace("format = 1", "format = 2")
            .replace("warm_up_s = 5", "warm_up_s = \"five\"")
            .replace("[devices.5A-3]\n", "[devices.5A-3]\ncolour = 1\n");
        std::fs::write(&path, &bad).unwrap();
        // Lines found in the text, not by the reader.
        let line = |start: &str| 1 + bad.lines().position(|l| l.starts_with(start)).unwrap();
        let err = load_made(&path).unwrap_err().to_string();
        let at = format!("backup file {}, ", path.display());
        let want = [
            format!(
                "{at}line {}: format: 2 is not a format this program reads",
                line("format")
            ),
            format!(
                "{at}line {}: devices.5A-3.colour: unknown setting",
                line("colour")
            ),
            format!(
                "{at}line {}: wig_wag.warm_up_s: must be a whole number",
                line("warm_up_s")
            ),
        ];
        let lines: Vec<&str> = err.lines().collect();
        assert_eq!(lines.len(), want.len(), "{err}");
        for w in want {
            assert!(lines.iter().any(|l| l.starts_with(&w)), "{w}\nin\n{err}");
        }
    }
}

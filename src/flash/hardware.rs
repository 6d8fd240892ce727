//! The hardware check of ICD §7.2: the `.hex` file names the hardware it is built for
//! with a suffix before the extension (`cu_2.hex` for hardware 2, `cu_3.hex` for 3),
//! and loading the wrong one "may render the system inoperable".
//!
//! Decisions:
//!
//! * The suffix is `_<digits>` at the end of the file stem (`cu_2.hex`, `CU_3.HEX`,
//!   `vpx-cu_2.hex`). Anything else (`cu.hex`, `cu_2 (1).hex` from a browser's second
//!   download, `cu_2b.hex`) has no suffix.
//! * A name with no suffix is refused: §7.2 says files carry one from hardware 2 on, so
//!   a Gen 1 file (hardware 1) has none, and so does a renamed file of any version; we
//!   cannot tell which. `--force-hardware N` states what the file is for.
//! * `--force-hardware N` replaces the file name's word, never the unit's: the unit must
//!   still report hardware N. Nothing lets a file for one hardware go to another.

use std::path::Path;

/// The hardware version a file name states, if it has the §7.2 suffix.
pub fn hardware_from_file_name(path: &Path) -> Option<u8> {
    let stem = path.file_stem()?.to_str()?;
    let (_, digits) = stem.rsplit_once('_')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// Why the file may not go to this unit.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum HardwareError {
    #[error(
        "{file}: the name has no hardware suffix (like cu_2.hex for hardware 2, ICD §7.2), so it cannot be checked against the unit. \
         Files for hardware 1 (VP-X Gen 1) have none. If you are sure this file is for hardware N, pass --force-hardware N"
    )]
    NoSuffix { file: String },
    #[error(
        "{file} is for hardware {file_hw} ({}), but the unit is hardware {unit_hw} ({}). \
         Loading the wrong file may leave the unit inoperable (ICD §7.2); get the file named _{unit_hw}.hex from Vertical Power",
        hw_name(*file_hw),
        hw_name(*unit_hw)
    )]
    Mismatch {
        file: String,
        file_hw: u8,
        unit_hw: u8,
    },
}

/// The name ICD Table 11 note 1 gives a hardware version.
pub fn hw_name(hw: u8) -> String {
    crate::protocol::message::types::HardwareVersion::from_byte(hw).name()
}

/// What the file is for: `--force-hardware` if given, else the file name's suffix.
pub fn file_hardware(path: &Path, force: Option<u8>) -> Result<u8, HardwareError> {
    force
        .or_else(|| hardware_from_file_name(path))
        .ok_or_else(|| HardwareError::NoSuffix {
            file: display_name(path),
        })
}

/// Checks the file against the hardware version the unit reported.
pub fn check_hardware(path: &Path, force: Option<u8>, unit_hw: u8) -> Result<u8, HardwareError> {
    let file_hw = file_hardware(path, force)?;
    if file_hw != unit_hw {
        return Err(HardwareError::Mismatch {
            file: display_name(path),
            file_hw,
            unit_hw,
        });
    }
    Ok(file_hw)
}

fn display_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hw(name: &str) -> Option<u8> {
        hardware_from_file_name(Path::new(name))
    }

    #[test]
    fn suffixes_from_section_7_2() {
        assert_eq!(hw("cu_2.hex"), Some(2));
        assert_eq!(hw("cu_3.hex"), Some(3));
        assert_eq!(hw("/tmp/fw/CU_3.HEX"), Some(3));
        assert_eq!(hw("vpx-cu_2.hex"), Some(2));
    }

    #[test]
    fn names_without_a_clean_suffix_have_none() {
        for name in [
            "cu.hex",
            "cu_.hex",
            "cu_2 (1).hex",
            "cu_2b.hex",
            "cu_999.hex",
            "_",
        ] {
            assert_eq!(hw(name), None, "{name}");
        }
    }

    #[test]
    fn a_mismatch_is_refused_and_says_both() {
        let e = check_hardware(Path::new("cu_3.hex"), None, 2).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("hardware 3") && text.contains("hardware 2"),
            "{text}"
        );
        assert!(text.contains("VP-X Pro"), "{text}");
        assert_eq!(check_hardware(Path::new("cu_2.hex"), None, 2), Ok(2));
    }

    #[test]
    fn no_suffix_needs_force_and_force_must_match_the_unit() {
        assert!(matches!(
            check_hardware(Path::new("cu.hex"), None, 1),
            Err(HardwareError::NoSuffix { .. })
        ));
        assert_eq!(check_hardware(Path::new("cu.hex"), Some(1), 1), Ok(1));
        // Forcing a file for 3 onto a unit that says 2 is still a mismatch.
        assert!(matches!(
            check_hardware(Path::new("cu.hex"), Some(3), 2),
            Err(HardwareError::Mismatch { .. })
        ));
        // Force overrides the name: a file named _3 declared to be for 2 goes to a 2.
        assert_eq!(check_hardware(Path::new("cu_3.hex"), Some(2), 2), Ok(2));
    }
}

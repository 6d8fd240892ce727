//! Where a backup came from: when it was made, from what (a port, a bridge, or the
//! virtual VP-X), and by which vpx-efis. The unit's own version is in `[unit]`.
//!
//! ```toml
//! [made]
//! at = "2026-12-01T15:37:16Z"       # UTC
//! from = "/dev/ttyUSB0"             # or "tcp://192.168.4.1:8880", or the simulator
//! simulated = false                 # true: the built-in virtual VP-X, not an aircraft
//! by = "vpx-efis 0.1.0 (abc1234)"
//! ```
//!
//! The section is optional when reading: files written before it existed load as they
//! did, and `restore` says it cannot tell where they came from.

use std::time::SystemTime;

use crate::protocol::message::Version;
use crate::toml_lines::Problem;

/// The file's `[made]` section: when, from what and by which vpx-efis it was made.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Provenance {
    pub at: String,
    pub from: String,
    pub simulated: bool,
    pub by: String,
}

impl Provenance {
    /// Made at `wall` (the caller's clock), by this program, from `from`.
    pub fn at(from: &str, simulated: bool, wall: SystemTime) -> Provenance {
        Provenance {
            at: crate::utc::utc_text(wall),
            from: from.to_string(),
            simulated,
            by: format!("vpx-efis {}", crate::program::VERSION),
        }
    }
}

/// Reads `[made]` if the file has one; any key missing or of the wrong kind is a problem
/// by its path, like every other field.
pub fn read(t: &toml::Table, problems: &mut Vec<Problem>) -> Option<Provenance> {
    let section = match t.get("made")? {
        toml::Value::Table(s) => s,
        _ => {
            problems.push(Problem {
                line: None,
                field: "made".into(),
                message: "not a section ([made])".into(),
            });
            return None;
        }
    };
    let mut text = |key: &str| match section.get(key) {
        Some(toml::Value::String(s)) => s.clone(),
        Some(_) => {
            problems.push(Problem {
                line: None,
                field: format!("made.{key}"),
                message: "not text".into(),
            });
            String::new()
        }
        None => String::new(),
    };
    let (at, from, by) = (text("at"), text("from"), text("by"));
    let simulated = match section.get("simulated") {
        Some(toml::Value::Boolean(b)) => *b,
        Some(_) => {
            problems.push(Problem {
                line: None,
                field: "made.simulated".into(),
                message: "not true or false".into(),
            });
            false
        }
        None => false,
    };
    Some(Provenance {
        at,
        from,
        simulated,
        by,
    })
}

/// What `restore` shows before it asks: when, from what, which unit, which program.
pub fn describe(made: Option<&Provenance>, version: &Version) -> String {
    let unit = format!(
        "{} software {}.{}",
        version.hardware_version.name(),
        version.software_major,
        version.software_minor
    );
    let or_unknown = |s: &str| {
        if s.is_empty() {
            "?".to_string()
        } else {
            s.to_string()
        }
    };
    match made {
        None => format!(
            "The backup is of a {unit}. It does not say when or from what it was made \
             (written before vpx-efis recorded that)."
        ),
        Some(m) => format!(
            "The backup was made {} from {}{}, a {unit}, by {}.",
            or_unknown(&m.at),
            or_unknown(&m.from),
            if m.simulated {
                " (THE VIRTUAL VP-X, not an aircraft)"
            } else {
                ""
            },
            or_unknown(&m.by),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backup::{Backup, from_toml, from_toml_made, to_toml, to_toml_made};
    use crate::protocol::config::UnitConfig;
    use crate::protocol::message::HardwareVersion;

    fn backup() -> Backup {
        Backup {
            version: Version {
                hardware_version: HardwareVersion::from_byte(2),
                software_major: 2,
                software_minor: 1,
            },
            config: UnitConfig::default(),
        }
    }

    fn made() -> Provenance {
        Provenance {
            at: "2026-12-01T15:37:16.000Z".into(),
            from: "tcp://192.168.4.1:8880".into(),
            simulated: false,
            by: "vpx-efis 0.1.0 (abc1234)".into(),
        }
    }

    #[test]
    fn the_section_is_written_after_format_and_read_back() {
        let text = to_toml_made(&backup(), &made());
        assert!(
            text.contains(
                "format = 1\n\n[made]\nat = \"2026-12-01T15:37:16.000Z\"\n\
                 from = \"tcp://192.168.4.1:8880\"\nsimulated = false\n\
                 by = \"vpx-efis 0.1.0 (abc1234)\"\n"
            ),
            "{text}"
        );
        assert_eq!(from_toml_made(&text), Ok((backup(), Some(made()))));
    }

    #[test]
    fn a_file_from_before_the_section_still_loads_and_says_so() {
        let old = to_toml(&backup());
        assert!(!old.contains("[made]"));
        assert_eq!(from_toml_made(&old), Ok((backup(), None)));
        let said = describe(None, &backup().version);
        assert!(said.contains("VP-X Pro software 2.1"), "{said}");
        assert!(said.contains("does not say when or from what"), "{said}");
    }

    #[test]
    fn a_simulated_source_is_said_loudly_and_wrong_kinds_are_problems() {
        let mut m = made();
        m.simulated = true;
        m.from = "the built-in virtual VP-X (scenario demo)".into();
        let said = describe(Some(&m), &backup().version);
        assert!(said.contains("THE VIRTUAL VP-X"), "{said}");
        assert!(said.contains("2026-12-01T15:37:16.000Z"), "{said}");

        let text = to_toml_made(&backup(), &made()).replace("simulated = false", "simulated = 3");
        let problems = from_toml(&text).unwrap_err();
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert_eq!(problems[0].field, "made.simulated");
    }
}

//! The unit's EEPROM: where its configuration survives a power cycle (ICD §6.1.4,
//! Table 24 note 5, Appendix F).
//!
//! In memory by default, or a file (`--eeprom FILE`). The file is JSON of the whole
//! [`UnitConfig`] with a checksum, written to a temporary file in the same directory
//! and renamed over the old one, so a process killed mid-write leaves the old contents
//! or the new ones, never half of each.
//!
//! A file that cannot be read back (not JSON, wrong checksum, or a configuration the
//! §6.2 rules refuse) is what a failed integrity check is on the real unit: the unit
//! starts from the Appendix F defaults with DATA_INTEGRITY set and a Table 25 code. The
//! bad file is kept beside it as `FILE.corrupt` for a person to look at, never lost.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::protocol::config::UnitConfig;
use crate::protocol::message::DataIntegrityCode;
use crate::protocol::validate;

/// Where the configuration lives.
#[derive(Debug)]
pub struct Eeprom {
    file: Option<PathBuf>,
    /// What a power cycle reads back.
    stored: UnitConfig,
    pub writes: u64,
}

/// What reading the EEPROM at power-on found.
#[derive(Debug, Clone)]
pub struct LoadOutcome {
    pub config: UnitConfig,
    /// `Some` when the integrity check failed and the defaults were taken.
    pub integrity: Option<DataIntegrityCode>,
    /// Sentences for the log.
    pub log: Vec<String>,
}

#[derive(Serialize, Deserialize)]
struct FileImage {
    format: u32,
    /// FNV-1a of `config` serialised as compact JSON.
    checksum: u64,
    config: UnitConfig,
}

const FORMAT: u32 = 1;

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01B3)
    })
}

fn checksum(config: &UnitConfig) -> u64 {
    fnv1a(&serde_json::to_vec(config).unwrap_or_default())
}

/// The Table 25 code for a problem the §6.2 rules found in one part of the config.
fn code_for_field(field: &str) -> DataIntegrityCode {
    if field.starts_with("devices") {
        DataIntegrityCode::DeviceConfig
    } else if field.starts_with("system") {
        DataIntegrityCode::SystemConfig
    } else if field.starts_with("flap") {
        DataIntegrityCode::FlapConfig
    } else if field.contains("trim") {
        DataIntegrityCode::TrimConfig
    } else if field.starts_with("wig_wag") {
        DataIntegrityCode::WigWagConfig
    } else {
        DataIntegrityCode::GeneralEeprom
    }
}

impl Eeprom {
    /// An EEPROM that lives only as long as the process.
    pub fn in_memory(initial: UnitConfig) -> Self {
        Eeprom {
            file: None,
            stored: initial,
            writes: 0,
        }
    }

    /// An EEPROM in `path`. A missing file is a fresh unit holding `initial` (the
    /// scenario's configuration), written out at once.
    pub fn open(path: &Path, initial: UnitConfig) -> (Self, LoadOutcome) {
        let mut e = Eeprom {
            file: Some(path.to_path_buf()),
            stored: initial.clone(),
            writes: 0,
        };
        let mut log = Vec::new();
        let (config, integrity) = match std::fs::read(path) {
            Err(err) if err.kind() == std::io::ErrorKind::NotFound => {
                log.push(format!(
                    "EEPROM file {} does not exist: starting from the scenario's configuration",
                    path.display()
                ));
                (initial, None)
            }
            Err(err) => {
                log.push(format!(
                    "EEPROM file {} cannot be read ({err}): data integrity failure, \
                     starting from the ICD Appendix F defaults",
                    path.display()
                ));
                (
                    UnitConfig::default(),
                    Some(DataIntegrityCode::GeneralEeprom),
                )
            }
            Ok(bytes) => match Self::decode(&bytes) {
                Ok(cfg) => {
                    log.push(format!("EEPROM read from {}", path.display()));
                    (cfg, None)
                }
                Err((code, why)) => {
                    let keep = path.with_extension("corrupt");
                    let kept = std::fs::copy(path, &keep).is_ok();
                    log.push(format!(
                        "EEPROM file {} is corrupt ({why}): data integrity failure (code {:#04x}, {}), \
                         starting from the ICD Appendix F defaults{}",
                        path.display(),
                        code.to_byte(),
                        code.description(),
                        if kept {
                            format!("; the bad file is kept as {}", keep.display())
                        } else {
                            String::new()
                        }
                    ));
                    (UnitConfig::default(), Some(code))
                }
            },
        };
        e.stored = config.clone();
        if let Err(err) = e.write_file(&config) {
            log.push(format!(
                "EEPROM file {} cannot be written: {err}",
                path.display()
            ));
        }
        (
            e,
            LoadOutcome {
                config,
                integrity,
                log,
            },
        )
    }

    fn decode(bytes: &[u8]) -> Result<UnitConfig, (DataIntegrityCode, String)> {
        let image: FileImage = serde_json::from_slice(bytes).map_err(|e| {
            (
                DataIntegrityCode::GeneralEeprom,
                format!("not readable: {e}"),
            )
        })?;
        if image.format != FORMAT {
            return Err((
                DataIntegrityCode::GeneralEeprom,
                format!("format {} is not {FORMAT}", image.format),
            ));
        }
        if checksum(&image.config) != image.checksum {
            return Err((
                DataIntegrityCode::GeneralEeprom,
                "checksum does not match".into(),
            ));
        }
        if let Some(p) = validate::whole_config(&image.config).into_iter().next() {
            return Err((code_for_field(&p.field), p.to_string()));
        }
        Ok(image.config)
    }

    /// Stores `config`: what the next power cycle reads back.
    pub fn store(&mut self, config: &UnitConfig) -> std::io::Result<()> {
        self.write_file(config)?;
        self.stored = config.clone();
        self.writes += 1;
        Ok(())
    }

    /// What a power cycle reads back.
    pub fn stored(&self) -> &UnitConfig {
        &self.stored
    }

    fn write_file(&self, config: &UnitConfig) -> std::io::Result<()> {
        let Some(path) = &self.file else {
            return Ok(());
        };
        let image = FileImage {
            format: FORMAT,
            checksum: checksum(config),
            config: config.clone(),
        };
        let text = serde_json::to_vec_pretty(&image).map_err(std::io::Error::other)?;
        crate::files::write_atomically(path, &text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::SwitchId;

    #[test]
    fn a_store_survives_reopening_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("unit.eeprom");
        let (mut e, first) = Eeprom::open(&path, UnitConfig::default());
        assert!(first.integrity.is_none());
        let mut cfg = first.config;
        cfg.devices[9].switch_id = SwitchId::Input(4);
        e.store(&cfg).unwrap();
        let (_, again) = Eeprom::open(&path, UnitConfig::default());
        assert_eq!(again.config, cfg);
        assert!(again.integrity.is_none());
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names, vec!["unit.eeprom".to_string()]);
    }

    #[test]
    fn a_flipped_byte_is_caught_by_the_checksum() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("unit.eeprom");
        let (mut e, first) = Eeprom::open(&path, UnitConfig::default());
        let mut cfg = first.config;
        cfg.devices[9].circuit_breaker = 4;
        e.store(&cfg).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        // Still valid JSON and still a valid config, but not what was written.
        let tampered = text.replacen("\"circuit_breaker\": 4", "\"circuit_breaker\": 3", 1);
        assert_ne!(text, tampered);
        std::fs::write(&path, tampered).unwrap();
        let (_, again) = Eeprom::open(&path, UnitConfig::default());
        assert_eq!(again.integrity, Some(DataIntegrityCode::GeneralEeprom));
        assert_eq!(again.config, UnitConfig::default());
        assert!(path.with_extension("corrupt").exists());
    }
}

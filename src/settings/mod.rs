//! The person's settings: flags, then `VPX_EFIS_*` environment variables, then the
//! config file, then the defaults. A mechanic types the port once (in the file, or in
//! the environment) and every command finds it; `vpx-efis config` shows each value
//! with where it came from.
//!
//! The first two are clap's (`env`); this module reads the file, finds where it lives
//! (the OS's configuration folder, or `VPX_EFIS_CONFIG`), and names each origin.

mod file;
pub mod values;

use std::fmt;
use std::path::{Path, PathBuf};

pub use file::{FileProblem, KEYS, Setting, SettingsFile, parse};

pub use crate::places::{CONFIG_ENV, config_path};
pub const PORT_ENV: &str = "VPX_EFIS_PORT";
pub const BAUD_ENV: &str = "VPX_EFIS_BAUD";
pub const XFSP_CONTROL_ENV: &str = "VPX_EFIS_XFSP_CONTROL";
pub const XFSP_CONTROL_FROM_ENV: &str = "VPX_EFIS_XFSP_CONTROL_FROM";
pub const LOGBOOK_ENV: &str = "VPX_EFIS_LOGBOOK";
pub const AIRCRAFT_ENV: &str = "VPX_EFIS_AIRCRAFT";

/// Where an effective value came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    Flag,
    Env(&'static str),
    File { line: usize },
    Default,
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::Flag => write!(f, "flag"),
            Origin::Env(name) => write!(f, "environment ({name})"),
            Origin::File { line } => write!(f, "config file, line {line}"),
            Origin::Default => write!(f, "default"),
        }
    }
}

/// The config file as found: its path (if the OS has a configuration folder at all),
/// whether it exists, and what it sets.
#[derive(Debug, Clone, Default)]
pub struct Loaded {
    pub path: Option<PathBuf>,
    pub exists: bool,
    pub file: SettingsFile,
}

/// A config file that cannot be used, named with its path and line: the first
/// problem, and every other one after it (`more`), one a line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigError {
    pub path: String,
    pub line: Option<usize>,
    pub message: String,
    pub more: Vec<FileProblem>,
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let one = |f: &mut fmt::Formatter<'_>, line: Option<usize>, message: &str| {
            let at = line.map(|l| format!(", line {l}")).unwrap_or_default();
            write!(f, "config file {}{at}: {message}", self.path)
        };
        one(f, self.line, &self.message)?;
        for p in &self.more {
            writeln!(f)?;
            one(f, p.line, &p.message)?;
        }
        Ok(())
    }
}

impl std::error::Error for ConfigError {}

/// Reads the config file; a missing one sets nothing and is no error.
pub fn load() -> Result<Loaded, ConfigError> {
    match config_path() {
        None => Ok(Loaded::default()),
        Some(path) => load_from(&path),
    }
}

pub fn load_from(path: &Path) -> Result<Loaded, ConfigError> {
    let shown = path.display().to_string();
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Ok(Loaded {
                path: Some(path.to_path_buf()),
                exists: false,
                file: SettingsFile::default(),
            });
        }
        Err(e) => {
            return Err(ConfigError {
                path: shown,
                line: None,
                message: format!("cannot read it: {e}"),
                more: Vec::new(),
            });
        }
    };
    let file = parse(&text).map_err(|mut p| {
        let first = p.remove(0);
        ConfigError {
            path: shown,
            line: first.line,
            message: first.message,
            more: p,
        }
    })?;
    Ok(Loaded {
        path: Some(path.to_path_buf()),
        exists: true,
        file,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_file_sets_nothing_and_a_bad_one_names_path_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let missing = load_from(&dir.path().join("none.toml")).unwrap();
        assert!(!missing.exists);
        assert_eq!(missing.file, SettingsFile::default());

        let bad = dir.path().join("config.toml");
        std::fs::write(&bad, "port = \"/dev/ttyUSB0\"\nbaud = 12345\n").unwrap();
        let err = load_from(&bad).unwrap_err();
        assert_eq!(err.line, Some(2));
        let text = err.to_string();
        assert!(
            text.starts_with(&format!("config file {}, line 2: baud:", bad.display())),
            "{text}"
        );
    }
}

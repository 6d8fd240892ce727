//! Where the program keeps its own files: the config file, and beside it the load
//! file, the check's reports and the logbook. Every such location is decided here,
//! once; the rest of the program asks. A leaf, so that every layer can ask without
//! reaching up to `settings`, which reads the file.
//!
//! `VPX_EFIS_CONFIG` moves the config file and, with it, everything beside it: one
//! variable gives a test, or a second set-up on one machine, a folder of its own.

use std::path::PathBuf;

/// Overrides the config file's path (tests; several set-ups on one machine).
pub const CONFIG_ENV: &str = "VPX_EFIS_CONFIG";

/// Where the file lives: `$VPX_EFIS_CONFIG`, else `config.toml` in the OS's
/// configuration folder (`~/.config/vpx-efis` on Linux, `~/Library/Application
/// Support/vpx-efis` on macOS, `%APPDATA%\vpx-efis\config` on Windows).
pub fn config_path() -> Option<PathBuf> {
    match std::env::var_os(CONFIG_ENV) {
        Some(p) if !p.is_empty() => Some(PathBuf::from(p)),
        _ => directories::ProjectDirs::from("", "", "vpx-efis")
            .map(|d| d.config_dir().join("config.toml")),
    }
}

/// The load file, unless the person names one (`--loads`): `loads.toml` beside the
/// config file.
pub fn loads_path() -> Option<PathBuf> {
    beside_config("loads.toml")
}

/// The check's reports, unless the person names a folder (`--report`): `reports`
/// beside the config file.
pub fn reports_dir() -> Option<PathBuf> {
    beside_config("reports")
}

/// `logbook.sqlite` beside the config file: the aircraft's logbook
/// ([`crate::logbook`]), unless `--logbook`, `VPX_EFIS_LOGBOOK` or the config key
/// `logbook` moves it.
pub fn logbook_path() -> Option<PathBuf> {
    beside_config("logbook.sqlite")
}

/// `name` in the config file's folder, wherever `VPX_EFIS_CONFIG` puts it.
fn beside_config(name: &str) -> Option<PathBuf> {
    config_path().and_then(|c| c.parent().map(|d| d.join(name)))
}

//! Where the program keeps its own files: the config file, and beside it the load
//! file, the check's reports and the audit log. A leaf, so that every layer can ask
//! without reaching up to `settings`, which reads the file.

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

/// `logbook.sqlite` beside the config file: the aircraft's logbook
/// ([`crate::logbook`]), unless `--logbook`, `VPX_EFIS_LOGBOOK` or the config key
/// `logbook` moves it.
pub fn logbook_path() -> Option<PathBuf> {
    config_path().and_then(|c| c.parent().map(|d| d.join("logbook.sqlite")))
}

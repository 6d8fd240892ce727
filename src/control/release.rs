//! How the page learns that a motor key was let go: the one place that decides it
//! from the platform and the terminal.

use crate::ui::state::ReleaseMode;

/// Key-release mode where key releases are reported, auto-repeat mode elsewhere.
///
/// - A terminal that accepted the kitty keyboard protocol's event types
///   (`keyboard_enhancement`) reports every release.
/// - The Windows console reports key-up natively: crossterm delivers Release events
///   there although `supports_keyboard_enhancement()` says false.
/// - Anywhere else only repeated presses arrive, and a run is kept alive by them.
pub fn release_mode(windows: bool, keyboard_enhancement: bool) -> ReleaseMode {
    if windows || keyboard_enhancement {
        ReleaseMode::KeyRelease
    } else {
        ReleaseMode::AutoRepeat
    }
}

/// [`release_mode`] for the platform this was built for.
pub fn release_mode_here(keyboard_enhancement: bool) -> ReleaseMode {
    release_mode(cfg!(windows), keyboard_enhancement)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_reports_release_with_or_without_keyboard_enhancement() {
        assert_eq!(release_mode(true, false), ReleaseMode::KeyRelease);
        assert_eq!(release_mode(true, true), ReleaseMode::KeyRelease);
    }

    #[test]
    fn elsewhere_only_keyboard_enhancement_reports_release() {
        assert_eq!(release_mode(false, true), ReleaseMode::KeyRelease);
        assert_eq!(release_mode(false, false), ReleaseMode::AutoRepeat);
    }

    #[test]
    fn this_platform_decides_by_its_own_os() {
        let expected = if cfg!(windows) {
            ReleaseMode::KeyRelease
        } else {
            ReleaseMode::AutoRepeat
        };
        assert_eq!(release_mode_here(false), expected);
    }
}

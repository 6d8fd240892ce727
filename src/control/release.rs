//! How the page learns that a motor key was let go: the one place that decides it
//! from the operating system and the terminal.

use super::run_state::ReleaseMode;
use crate::platform::Os;

/// Key-release mode where key releases are reported, auto-repeat mode elsewhere.
///
/// - A terminal that accepted the kitty keyboard protocol's event types
///   (`keyboard_enhancement`) reports every release.
/// - The Windows console reports key-up natively: crossterm delivers Release events
///   there although `supports_keyboard_enhancement()` says false.
/// - Anywhere else only repeated presses arrive, and a run is kept alive by them.
pub fn release_mode(os: Os, keyboard_enhancement: bool) -> ReleaseMode {
    if os == Os::Windows || keyboard_enhancement {
        ReleaseMode::KeyRelease
    } else {
        ReleaseMode::AutoRepeat
    }
}

/// [`release_mode`] for the operating system this was built for.
pub fn release_mode_here(keyboard_enhancement: bool) -> ReleaseMode {
    release_mode(Os::current(), keyboard_enhancement)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_reports_release_with_or_without_keyboard_enhancement() {
        assert_eq!(release_mode(Os::Windows, false), ReleaseMode::KeyRelease);
        assert_eq!(release_mode(Os::Windows, true), ReleaseMode::KeyRelease);
    }

    #[test]
    fn elsewhere_only_keyboard_enhancement_reports_release() {
        for os in [Os::Linux, Os::MacOs, Os::OtherUnix] {
            assert_eq!(release_mode(os, true), ReleaseMode::KeyRelease, "{os:?}");
            assert_eq!(release_mode(os, false), ReleaseMode::AutoRepeat, "{os:?}");
        }
    }
}

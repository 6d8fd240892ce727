//! Which operating system this build is for, decided in one place.
//!
//! Code that behaves differently per OS does not test `cfg` itself: it is a pure
//! function taking an [`Os`], called with [`Os::current`]. So every branch (the
//! Windows bind address, the macOS port advice, …) is unit-tested on Linux, and the
//! rest of the program is the same everywhere. Only the code that must call an OS's
//! own API (signals, pseudo-terminals) sits behind `#[cfg]`.

/// The operating systems the program is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Os {
    Linux,
    MacOs,
    Windows,
    /// Another Unix (a BSD): POSIX behaviour, Linux's words where they fit.
    OtherUnix,
}

impl Os {
    /// The OS this binary was built for.
    pub const fn current() -> Os {
        if cfg!(target_os = "linux") {
            Os::Linux
        } else if cfg!(target_os = "macos") {
            Os::MacOs
        } else if cfg!(windows) {
            Os::Windows
        } else {
            Os::OtherUnix
        }
    }

    pub const ALL: [Os; 4] = [Os::Linux, Os::MacOs, Os::Windows, Os::OtherUnix];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn this_build_knows_its_os() {
        // The tests run on Linux here; the assertion documents that and would catch a
        // cfg! typo that made every build "other".
        if cfg!(target_os = "linux") {
            assert_eq!(Os::current(), Os::Linux);
        }
        assert!(Os::ALL.contains(&Os::current()));
    }
}

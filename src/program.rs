//! What the program says about itself, for every layer to use without reaching up to
//! the command line: its version, the error that means "the command line or the config
//! file was refused", and its exit codes (also in the README).

/// `--version`: ours, and the git commit when built from a checkout (see build.rs).
pub const VERSION: &str = env!("VPX_EFIS_VERSION");

/// The command line or the config file was refused, in words; the process exits with
/// [`exit::USAGE`] and nothing was opened.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// Exit codes (also in the README).
pub mod exit {
    /// Done.
    pub const OK: u8 = 0;
    /// It went wrong at run time: the port, the unit, a file, the network.
    pub const FAILURE: u8 = 1;
    /// The command line or the config file was refused; nothing was opened (clap also
    /// exits 2 for a usage error).
    pub const USAGE: u8 = 2;
}

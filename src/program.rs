//! What the program says about itself, for every layer to use without reaching up to
//! the command line: its version, the error that means "the command line or the config
//! file was refused", and its exit codes (listed in the guide's reference, generated from [`exit::MEANINGS`]).

/// `--version`: ours, and the git commit when built from a checkout (see build.rs).
pub const VERSION: &str = env!("VPX_EFIS_VERSION");

/// The command line or the config file was refused, in words; the process exits with
/// [`exit::USAGE`] and nothing was opened.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// Exit codes.
pub mod exit {
    /// Done.
    pub const OK: u8 = 0;
    /// It went wrong at run time: the port, the unit, a file, the network.
    pub const FAILURE: u8 = 1;
    /// The command line or the config file was refused; nothing was opened (clap also
    /// exits 2 for a usage error).
    pub const USAGE: u8 = 2;

    /// Every exit status in words, for the guide's exit codes page (generated from
    /// this table by `cargo run -- reference`).
    pub const MEANINGS: &[(&str, &str)] = &[
        (
            "0",
            "done; for `check`, everything passed (a warning is not a failure)",
        ),
        (
            "1",
            "it went wrong while running: the port, the unit, a file, the network (the \
             message says what); for `check`, something failed",
        ),
        (
            "2",
            "the command line or the config file was refused, and nothing was opened or \
             sent; for `check`, also: it was interrupted (it puts back first)",
        ),
        (
            "128 + n",
            "the page, `gateway` or `flash` was stopped by signal n and stopped cleanly \
             first (motor stop on the wire, terminal restored; `flash` at a safe point, the \
             unit left to resume): 130 SIGINT, 143 SIGTERM, 129 SIGHUP; on Windows 130 \
             Ctrl-C, 149 Ctrl-Break, 129 console closed. Before `flash` has asked to go \
             ahead nothing needs stopping and the signal ends it at once; a signal that \
             comes once the last page is verified lets the update finish, and `flash` \
             exits 0",
        ),
    ];
}

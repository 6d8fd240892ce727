//! vpx-efis: a terminal EFIS electrical page for the Vertical Power VP-X.
//!
// ANCHOR: layers
//! The data flows one way through the modules, lowest layer first; a module imports
//! its own layer and those below, never one above (`tests/layers.rs` holds this):
//!
//! 1. The codecs, crates of their own: [`protocol`] (`crates/vpx-protocol`, the VP-X
//!    ICD) and the XFSp wire format (`crates/xfsp`, re-exported in [`xfsp`]); beside
//!    them the small helpers [`program`] (version, usage error, exit codes),
//!    [`places`] (where the config file and the files beside it live),
//!    [`utc`], [`files`] (every file the program writes), [`toml_lines`],
//!    [`platform`], [`transient`] (which I/O errors a reader retries) and
//!    [`staleness`] (how long each broadcast stays current).
//! 2. Bytes in and out: [`link`] (serial, TCP, pseudo-terminal, capture files),
//!    [`traffic`] (every frame, for the traffic view), [`audit`] (every command
//!    sent to the unit, with its origin) and [`logbook`] (the aircraft's record in
//!    SQLite: checks, changes, updates and the audit log, for the aircraft's life).
//! 3. What we know: [`model`] (every fact with its time, and the traffic log;
//!    staleness decided here), and [`sim`], the virtual VP-X (sans-IO: bytes in,
//!    bytes out, the caller's clock).
//! 4. Intent into commands: [`control`] (keys and runs under the safety rules, the
//!    motor streamer) and [`exchange`] (request, answer, retry on the caller's clock).
//! 5. Flows and maintenance: [`check`] (the installation check), [`setup`] (the setup
//!    screens' writes), [`loads`] (the load analysis, and each breaker held against
//!    its wire by AC 43.13-1B's tables), [`backup`], [`flash`],
//!    [`xfsp`] (the gateway onto the XFSp network) and [`settings`] (flags, environment
//!    and config file).
//! 6. [`remote`]: the walk-around remote, an HTTP server for a paired phone; what
//!    it is asked goes to the page as requests, and through [`control`] from there.
//! 7. [`ui`]: drawing, a pure function of the model, the controller and the flows.
//! 8. [`app`]: wires the page together; [`cmd`]: one file per subcommand, each owning
//!    its clap arguments; [`cli`]: the command line, on top, composing them, filling
//!    them from the config file and dispatching.
// ANCHOR_END: layers

pub mod app;
pub mod audit;
pub mod backup;
pub mod check;
pub mod cli;
pub mod cmd;
pub mod control;
pub mod exchange;
pub mod files;
pub mod flash;
pub mod link;
pub mod loads;
pub mod logbook;
pub mod model;
pub mod places;
pub mod platform;
pub mod program;
pub mod remote;
pub mod settings;
pub mod setup;
pub mod sim;
pub mod staleness;
pub mod toml_lines;
pub mod traffic;
pub mod transient;
pub mod ui;
pub mod utc;
pub mod xfsp;

/// The VP-X wire format: the `vpx-protocol` crate (`crates/vpx-protocol`), named
/// `protocol` here as the rest of the program has always called it.
pub use vpx_protocol as protocol;

//! vpx-efis: a terminal EFIS electrical page for the Vertical Power VP-X.
//!
//! The data flows one way through the modules:
//! `protocol` (wire format, pure) → `link` (bytes in and out) → `model` (what we know,
//! with timestamps) → `ui` (pure rendering), `control` (keys become commands), and the flows beside
//! it: `setup` (the setup screens' writes and re-reads) on `exchange` (request,
//! answer, retry and re-read on the caller's clock).
//! `sim` is a second, independent implementation of the device side; `xfsp` bridges
//! the model onto the XFSp avionics network; `app` wires everything together.

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
pub mod model;
pub mod platform;
pub mod protocol;
pub mod settings;
pub mod setup;
pub mod sim;
pub mod toml_lines;
pub mod traffic;
pub mod ui;
pub mod utc;
pub mod xfsp;

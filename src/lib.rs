//! vpx-efis: a terminal EFIS electrical page for the Vertical Power VP-X.
//!
//! The data flows one way through the modules:
//! `protocol` (wire format, pure) → `link` (bytes in and out) → `model` (what we know,
//! with timestamps) → `ui` (pure rendering) and `control` (keys become commands).
//! `sim` is a second, independent implementation of the device side; `xfsp` bridges
//! the model onto the XFSp avionics network; `app` wires everything together.

pub mod app;
pub mod backup;
pub mod cli;
pub mod cmd;
pub mod control;
pub mod flash;
pub mod link;
pub mod model;
pub mod protocol;
pub mod sim;
pub mod traffic;
pub mod ui;
pub mod xfsp;

//! One file per subcommand. Each owns its clap arguments (`cli` composes them), takes
//! them parsed and does the work; [`common`] holds the options several share.

pub mod backup;
pub mod check;
pub mod common;
pub mod completions;
pub mod config;
pub mod decode;
pub mod flash;
pub mod gateway;
pub mod log;
pub mod page;
pub mod ports;
pub mod restore;
pub mod sim;
pub mod wires;
pub mod xfsp_dump;

//! One file per subcommand. Each takes its parsed arguments and does the work.

pub mod backup;
pub mod check;
pub mod completions;
pub mod config;
pub mod decode;
pub mod flash;
pub mod gateway;
pub mod ports;
pub mod restore;
pub mod sim;
pub mod xfsp_dump;

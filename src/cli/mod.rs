//! The command line, on top of everything: [`args`] composes each subcommand's clap
//! arguments (owned by its `cmd/` file), [`resolve`] fills them from the config file,
//! and [`dispatch`] runs the one asked for.

pub mod args;
pub mod dispatch;
pub mod resolve;

pub use args::{Cli, Command};
pub use dispatch::main;

//! The command line, on top of everything: [`args`] composes each subcommand's clap
//! arguments (owned by its `cmd/` file), [`resolve`] fills them from the config file,
//! [`dispatch`] runs the one asked for, and [`reference`] writes the guide's
//! reference pages from all of it.

pub mod args;
pub mod dispatch;
pub mod reference;
pub mod resolve;

pub use args::{Cli, Command};
pub use dispatch::main;

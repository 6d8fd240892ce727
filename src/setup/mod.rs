//! The setup screens' flow: what a key does to the forms, which messages a page
//! sends, when a write is resent, when a setting is left unknown and re-read, and
//! what each write line says. Pure and driven on the caller's clock like `control`:
//! it reads the model, changes the setup view's state ([`view`]) and returns the
//! effects (messages to send, a backup file to write or read) that `app` carries out.
//!
//! The request/answer/retry/re-read machinery underneath is [`crate::exchange`],
//! which other flows share.

pub mod diagnostics;
pub mod flow;
pub mod form;
pub mod view;
pub mod write;

#[cfg(test)]
mod tests;

pub use write::WriteQueue;

//! The setup screens' flow: what a key does to the forms, which messages a page
//! sends, when a write is resent, when a setting is left unknown and re-read, and
//! what each write line says. Pure and driven on the caller's clock like `control`:
//! it reads the model, changes the setup view's state and returns the messages to
//! send; `app` only carries keys in and messages out.
//!
//! The request/answer/retry/re-read machinery underneath is [`crate::exchange`],
//! which other flows share.

pub mod flow;
pub mod form;
pub mod probe;
pub mod view;
pub mod write;

pub use write::{ANSWER_TIMEOUT, TRIES, WriteQueue, unit_config};

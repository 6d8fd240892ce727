//! The installation check: every switch input, circuit and motor tested in turn, an
//! electrical load analysis, and a report for the builder's log. A flow like `setup`:
//! the person's commands and ticks in, the view ([`state::CheckView`]) changed and
//! what the app must send out. Pure and driven on the caller's clock; the app only
//! wires it to the link, the page's controller (so every motor rule and stop cause
//! applies) and the terminal.
//!
//! The arrows inside run one way: `flow` drives the steps (`switches`, `circuits`,
//! `motors`) through the one interface in `step`, which is all a step knows of the
//! flow; `state` and `words` are the data and the words everyone reads.

pub mod advice;
mod calls;
mod circuits;
pub mod flow;
pub mod lights;
mod motors;
pub mod plan;
pub mod record;
pub mod report;
pub mod state;
mod step;
mod switches;
mod timing;
pub mod trend;
pub mod words;

pub use calls::{CheckEffects, Command};
pub use flow::{Cause, CheckFlow, Options};
pub use motors::judge as judge_motor;
pub use plan::Choices;
pub use timing::Timing;

#[cfg(test)]
mod tests;

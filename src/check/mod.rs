//! The installation check: every switch input, circuit and motor tested in turn, an
//! electrical load analysis, and a report for the builder's log. A flow like `setup`:
//! keys and ticks in, the view ([`state::CheckView`]) changed and what the app
//! must send out. Pure and driven on the caller's clock; the app only wires it to the
//! link, the page's controller (so every motor rule and stop cause applies) and the
//! terminal.

mod circuits;
pub mod flow;
mod motors;
pub mod plan;
pub mod report;
pub mod state;
mod switches;
pub mod words;

pub use circuits::judge as judge_current;
pub use flow::{Cause, CheckFlow, Command, Options, Out, Timing};
pub use motors::{expected_sign, judge as judge_motor};
pub use plan::{Choices, SUGGEST_EXCLUDING};

#[cfg(test)]
mod tests;

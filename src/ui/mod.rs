//! ratatui widgets that render the model and nothing else: no I/O, no clocks.

pub mod state;

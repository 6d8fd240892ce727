//! The wiring: link, model, UI, control and the built-in virtual VP-X.
//!
//! Threads, after gitui and bottom:
//! - the link's reader thread decodes bytes, applies them to the shared model, and
//!   wakes the main loop over a crossbeam channel;
//! - an input thread turns terminal events into messages on another channel;
//! - the main loop selects over input, link wake-ups and a deadline: the earliest
//!   thing that must happen next (a query batch, a redraw). It redraws only when the
//!   model or the view changed, or once a second for ages;
//! - a motor-stream thread re-sends a held motor's move message on its own clock
//!   (see `motor_stream`), so no redraw, terminal write or model lock delays it.
//!
//! The files, one job each: `page` holds the page's state and answers keys, link
//! wake-ups and ticks; `serve` is the loop every process runs (the page, the
//! headless check, the gateway), each with its own front; `stop_gate` is the one way
//! to the wire and the panic's stop; `link_sink` applies what the link reports to the model;
//! `options` is what the page is asked to do and its checks; `runner` runs the page
//! as the process (`vpx-efis` with no subcommand). The flows the page hosts
//! (`check`, `setup`, `traffic`, `gateway`, `replay`) add their own `impl App` blocks.

mod background;
mod check;
mod gateway;
mod last_check;
mod link_sink;
pub mod log_views;
mod logbook;
mod motor_stream;
pub use motor_stream::LOOP_STALL;
mod options;
mod page;
pub mod queries;
mod record;
mod remote;
mod replay;
mod runner;
mod serve;
mod setup;
mod signals;
mod stop_gate;
mod terminal;
mod traffic;
mod wires;

use std::sync::{Mutex, MutexGuard};

use crate::model::Model;
use link_sink::SharedSink;
use page::{IDLE_REDRAW, MIN_FRAME_GAP, input_closed};
use runner::spawn_input_thread;

pub use background::choose_theme;
pub use check::{
    CheckEnd, HeadlessCheck, prepare_report_dir, run_headless, run_headless_with, write_report,
};
pub use gateway::xfsp_setup;
pub use options::{PageOptions, XfspOptions};
pub use page::{App, AppOptions, Flow, Wake};
pub use queries::QueryPacer;
pub use record::Recorder;
pub use replay::Capture;
pub use runner::{builtin_sim, run};
pub use signals::{StopFlag, Terminated, Termination, stop_flag};
pub use stop_gate::StopGate;
pub use terminal::{
    TerminalGuard, clear_emergency_stop, install_panic_hook, panicked, set_emergency_stop,
};

fn lock(m: &Mutex<Model>) -> MutexGuard<'_, Model> {
    // A panic elsewhere while holding the lock must not also take the page down.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

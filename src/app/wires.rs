//! The load file's wires for the page: read when the page starts and each time the
//! setup screens open (the builder may have edited it meanwhile), for the device
//! list's and the detail pane's wire verdicts and for setup's question before a
//! breaker goes over its wire.

use std::time::Instant;

use super::{App, lock};
use crate::loads::disk;
use crate::model::LogLevel;

impl App {
    /// Reads the wires of the load file beside the config file (as the check does).
    /// No file means no wires; a bad one is said in the event log, and the wires
    /// read before are kept rather than forgotten.
    pub fn reload_wires(&mut self) {
        let Some(path) = crate::places::loads_path().filter(|p| p.exists()) else {
            return self.set_wires(Vec::new());
        };
        match disk::read_circuits(&path) {
            Ok(circuits) => self.set_wires(circuits),
            Err(e) => {
                let text = format!("wires not read: {e}");
                let mut model = lock(&self.model);
                let already = model.events.back().is_some_and(|l| l.text == text);
                if !already {
                    model.log(Instant::now(), LogLevel::Warning, text);
                }
            }
        }
    }

    /// The load file's circuits (their wires), for the page and for setup.
    pub fn set_wires(&mut self, circuits: Vec<crate::loads::LoadCircuit>) {
        if self.view.wires != circuits {
            self.dirty = true;
        }
        self.setup.set_wires(circuits.clone());
        self.view.wires = circuits;
    }
}

//! The aircraft's last check, read from the logbook for the trend: the check's screen
//! and report show each current beside it, the page's detail pane the selected
//! circuit's. The flow reads no file; the app reads it here and hands it in.

use std::time::Instant;

use super::{App, lock};
use crate::check::trend::LastCheck;
use crate::logbook::{self, Logbook, Mode, query};
use crate::model::LogLevel;

/// The last check of the aircraft the command line names (`--aircraft`; without it,
/// the records under no registration), or why it could not be read. No logbook yet
/// is no error: there is no last check.
pub fn read() -> Result<Option<LastCheck>, String> {
    let Some(target) = logbook::target() else {
        return Ok(None);
    };
    let book = match Logbook::open(&target.path, Mode::ReadOnly) {
        Ok(b) => b,
        Err(logbook::Error::Missing { .. }) => return Ok(None),
        Err(e) => return Err(e.to_string()),
    };
    query::last_check(&book, target.aircraft.as_deref())
        .map(|l| l.map(LastCheck::from))
        .map_err(|e| e.to_string())
}

impl App {
    /// Reads the last check into the page (the detail pane) and gives it, for a
    /// check about to start. A logbook that cannot be read is said in the event log
    /// once, and the page goes on without the trend.
    pub fn reload_last_check(&mut self) -> Option<LastCheck> {
        let last = match read() {
            Ok(l) => l,
            Err(e) => {
                let text = format!("logbook: the last check not read, no trend shown ({e})");
                let mut model = lock(&self.model);
                if model.events.back().is_none_or(|l| l.text != text) {
                    model.log(Instant::now(), LogLevel::Warning, text);
                }
                None
            }
        };
        if self.view.last_check != last {
            self.view.last_check = last.clone();
            self.dirty = true;
        }
        last
    }
}

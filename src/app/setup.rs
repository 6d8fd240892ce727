//! Keys and timers of the setup screens (`c` from the device list).

use std::time::Instant;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind};

use super::{App, Flow};
use crate::control::StopReason;
use crate::ui::state::Screen;

impl App {
    pub(super) fn setup_key(&mut self, key: KeyEvent, now: Instant) -> Flow {
        let stop = self.controller.stop(now, StopReason::OtherKey);
        self.send(stop);
        if key.kind == KeyEventKind::Release {
            return Flow::Continue;
        }
        match key.code {
            KeyCode::Char('q') => return Flow::Quit,
            KeyCode::Esc | KeyCode::Char('c') => self.view.screen = Screen::Devices,
            _ => {}
        }
        Flow::Continue
    }

    /// Spec writes waiting for their SPEC_ACK time out and retry here.
    pub(super) fn setup_tick(&mut self, _now: Instant) {}
}

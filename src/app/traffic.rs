//! Keys of the traffic view (`t` from the device list).

use std::time::Instant;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind};

use super::{App, Flow};
use crate::control::StopReason;
use crate::ui::state::Screen;

impl App {
    pub(super) fn traffic_key(&mut self, key: KeyEvent, now: Instant) -> Flow {
        // Any key stops a running motor before it does anything else here.
        let stop = self.controller.stop(now, StopReason::OtherKey);
        self.send(stop);
        if key.kind == KeyEventKind::Release {
            return Flow::Continue;
        }
        match key.code {
            KeyCode::Char('q') => return Flow::Quit,
            KeyCode::Esc | KeyCode::Char('t') => self.view.screen = Screen::Devices,
            _ => {}
        }
        Flow::Continue
    }
}

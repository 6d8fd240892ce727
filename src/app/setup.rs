//! The setup screens (`c` from the device list) wired to their flow in
//! [`crate::setup::flow`]: motor keys go to the controller as on the device list,
//! every other key and every tick to the flow, and what the flow asks for goes out
//! on the link. Nothing here waits: the flow's timeouts are deadlines of the page's
//! loop.

use std::time::{Instant, SystemTime};

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::{App, Flow, lock};
use crate::control::{Action, KeyContext, Selected, StopReason, keymap};
use crate::model::{CircuitKind, CircuitState, Model, Motor};
use crate::protocol::message::{Message, Packet};
use crate::setup::flow::{SetupEffects, SetupKey};
use crate::setup::view::{Dialog, Tone};
use crate::ui::state::Screen;

/// The key context that makes the controller run `motor`, as if its row were selected
/// on the device list: the same keys, checks and 4 Hz stream; but past the configured
/// endpoints, which is how new ones are found here (`control::endpoints`).
fn motor_ctx(motor: Motor, model: &Model, now: Instant) -> KeyContext {
    let id = motor.device_id();
    let state = model
        .circuits(now)
        .into_iter()
        .find(|c| c.id == id)
        .map_or(CircuitState::Unknown, |c| c.state);
    let kind = match motor {
        Motor::Flaps => CircuitKind::Flaps,
        Motor::Trim(k) => CircuitKind::Trim(k),
    };
    KeyContext {
        selected: Some(Selected { id, kind, state }),
        overlay_open: false,
        past_endpoints: true,
    }
}

/// The terminal's key as the setup flow reads it; `None` for one it has no use for.
fn setup_key_of(key: &KeyEvent) -> Option<SetupKey> {
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    Some(match key.code {
        KeyCode::Tab => SetupKey::Tab,
        KeyCode::BackTab => SetupKey::BackTab,
        KeyCode::Esc => SetupKey::Esc,
        KeyCode::Up => SetupKey::Up,
        KeyCode::Down => SetupKey::Down,
        KeyCode::Left if shift => SetupKey::ShiftLeft,
        KeyCode::Right if shift => SetupKey::ShiftRight,
        KeyCode::Left => SetupKey::Left,
        KeyCode::Right => SetupKey::Right,
        KeyCode::Enter => SetupKey::Enter,
        KeyCode::Backspace => SetupKey::Backspace,
        KeyCode::Char(c) => SetupKey::Char(c),
        _ => return None,
    })
}

impl App {
    pub(super) fn setup_key(&mut self, key: KeyEvent, now: Instant) -> Flow {
        if key.modifiers.contains(KeyModifiers::CONTROL) && key.code == KeyCode::Char('c') {
            self.controller.stop(now, StopReason::Quit);
            return Flow::Quit;
        }
        let sv = &self.view.setup;
        let field = sv.field();
        if let Some(motor) = sv.page.motor()
            && sv.dialog == Dialog::None
            && !(field.takes_digits() && key.code == KeyCode::Char('.'))
        {
            let shared = self.model.clone();
            let model = lock(&shared);
            let ctx = motor_ctx(motor, &model, now);
            match keymap::map(&key, &ctx) {
                Some(Action::Motor { .. }) | Some(Action::KeyReleased) => {
                    let out = self.controller.handle_key(key, &ctx, &model, now);
                    drop(model);
                    self.set_notice(now, out.notice);
                    return Flow::Continue;
                }
                Some(Action::Unavailable(why)) => {
                    drop(model);
                    self.controller.stop(now, StopReason::OtherKey);
                    self.view.setup.message = Some((Tone::Bad, why.to_string()));
                    return Flow::Continue;
                }
                _ => {}
            }
        }
        if key.kind == KeyEventKind::Release {
            return Flow::Continue;
        }
        // Any other key stops a running motor before it does anything else.
        self.controller.stop(now, StopReason::OtherKey);
        let n = self.controller.take_notice();
        self.set_notice(now, n);

        let shared = self.model.clone();
        let out = match setup_key_of(&key) {
            Some(key) => {
                let mut model = lock(&shared);
                let wall = SystemTime::now();
                self.setup
                    .key(key, &mut self.view.setup, &mut model, now, wall)
            }
            None => SetupEffects::default(),
        };
        self.apply_setup(out, now)
    }

    /// Does what the setup flow asked for, and hands back what came of the files.
    fn apply_setup(&mut self, out: SetupEffects, now: Instant) -> Flow {
        if let Some(file) = &out.write_backup {
            let result = crate::files::write_atomically(&file.path, file.content.as_bytes());
            let shared = self.model.clone();
            self.setup
                .backup_written(result, &mut self.view.setup, &lock(&shared));
        }
        if let Some(path) = &out.read_backup {
            let text = std::fs::read_to_string(path);
            let shared = self.model.clone();
            self.setup
                .backup_read(text, &mut self.view.setup, &lock(&shared), now);
        }
        for m in out.send {
            {
                let shared = self.model.clone();
                self.note_setup_sent(&lock(&shared), &m);
            }
            lock(&self.model).log(
                now,
                crate::model::LogLevel::Info,
                format!(
                    "setup: {} sent ({})",
                    m.name(),
                    crate::protocol::describe::describe(&m)
                ),
            );
            let cnt = self.controller.next_cnt();
            self.send(crate::audit::Origin::Setup, vec![Packet::request(cnt, m)]);
        }
        if out.reread_all {
            self.pacer.start(now);
        }
        self.note_setup_settled();
        if out.leave {
            self.view.screen = Screen::Devices;
        }
        self.dirty = true;
        if out.quit { Flow::Quit } else { Flow::Continue }
    }

    /// Sends `messages` through the write queue without this program's own §6.2 check,
    /// so a test can show what the screen does with the unit's own refusal.
    #[doc(hidden)]
    pub fn setup_send_unchecked(&mut self, messages: Vec<Message>, now: Instant) {
        let shared = self.model.clone();
        let out = {
            let mut model = lock(&shared);
            self.setup
                .send_unchecked(messages, &mut self.view.setup, &mut model, now)
        };
        self.apply_setup(out, now);
    }

    /// The flow's timeouts, retries and re-reads, and the forms following the unit.
    pub(super) fn setup_tick(&mut self, now: Instant) {
        let before = self.view.setup.clone();
        let on_screen = self.view.screen == Screen::Setup;
        let shared = self.model.clone();
        let out = {
            let mut model = lock(&shared);
            self.setup.tick(
                &mut self.view.setup,
                on_screen,
                self.view.selected,
                &mut model,
                now,
            )
        };
        let dirty = self.dirty;
        self.apply_setup(out, now);
        self.dirty = dirty || self.view.setup != before;
    }
}

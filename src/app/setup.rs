//! Keys and timers of the setup screens (`c` from the device list), wired to the
//! pure flow in [`crate::setup`].
//!
//! Everything that waits here (a SPEC_ACK, a re-read, a PING) is a deadline checked in
//! [`App::setup_tick`], never a blocking call: the motors, the queries and the screen
//! keep going while the unit thinks. The forms, the write queue and the timed
//! requests are pure (`setup::form`, `setup::write`, `setup::probe`); this file only
//! wires them to keys, the link and the view.

use std::path::Path;
use std::time::Instant;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::{App, Flow, lock};
use crate::backup::{self, Backup};
use crate::control::{Action, KeyContext, Selected, StopReason, keymap};
use crate::model::{CircuitKind, CircuitState, Model, Motor};
use crate::protocol::device::{STARTER, TRIM_R};
use crate::protocol::message::{Message, Packet, Version};
use crate::setup::probe::{EraseEnd, Probes};
use crate::setup::{form, write};
use crate::ui::setup::state::{Dialog, Field, Page, Tone};
use crate::ui::state::Screen;

/// The setup screens' own state that the view does not need: the write queue, the
/// timed requests, and a checked backup waiting for its confirmation.
#[derive(Debug, Default)]
pub(super) struct SetupCtl {
    queue: write::WriteQueue,
    /// The page a batch came from; `None` for a backup being applied.
    batch_page: Option<Option<Page>>,
    probes: Probes,
    pending_load: Vec<Message>,
    on_screen: bool,
}

impl SetupCtl {
    /// When the page loop must tick for a setup timeout.
    pub(super) fn next_deadline(&self) -> Option<Instant> {
        [self.queue.next_deadline(), self.probes.next_deadline()]
            .into_iter()
            .flatten()
            .min()
    }
}

/// The key context that makes the controller run `motor`, as if its row were selected
/// on the device list: the same keys, checks and 4 Hz stream.
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
    }
}

impl App {
    pub(super) fn setup_key(&mut self, key: KeyEvent, now: Instant) -> Flow {
        if key.modifiers.contains(KeyModifiers::CONTROL) && key.code == KeyCode::Char('c') {
            let stop = self.controller.stop(now, StopReason::Quit);
            self.send(stop);
            return Flow::Quit;
        }
        let sv = &self.view.setup;
        let field = sv.field();
        if let Some(motor) = sv.page.motor()
            && sv.dialog == Dialog::None
            && !(form::takes_digits(field) && key.code == KeyCode::Char('.'))
        {
            let shared = self.model.clone();
            let model = lock(&shared);
            let ctx = motor_ctx(motor, &model, now);
            match keymap::map(&key, &ctx) {
                Some(Action::Motor { .. }) | Some(Action::KeyReleased) => {
                    let out = self.controller.handle_key(key, &ctx, &model, now);
                    drop(model);
                    self.send(out.packets);
                    self.set_notice(now, out.notice);
                    self.view.motor_run = self.controller.running();
                    return Flow::Continue;
                }
                Some(Action::Unavailable(why)) => {
                    drop(model);
                    let stop = self.controller.stop(now, StopReason::OtherKey);
                    self.send(stop);
                    self.say(Tone::Bad, why);
                    return Flow::Continue;
                }
                _ => {}
            }
        }
        if key.kind == KeyEventKind::Release {
            return Flow::Continue;
        }
        // Any other key stops a running motor before it does anything else.
        let stop = self.controller.stop(now, StopReason::OtherKey);
        self.send(stop);
        let n = self.controller.take_notice();
        self.set_notice(now, n);
        self.view.motor_run = self.controller.running();

        if self.view.setup.dialog != Dialog::None {
            self.dialog_key(key, now);
            return Flow::Continue;
        }
        let page = self.view.setup.page;
        match key.code {
            KeyCode::Tab => self.goto_page(page.next()),
            KeyCode::BackTab => self.goto_page(page.prev()),
            KeyCode::Esc => {
                let sv = &mut self.view.setup;
                if sv.typing.take().is_some() {
                } else if page.is_form() && sv.is_edited(page) {
                    sv.edited[page.index()] = false;
                    self.reload_forms();
                    self.say(Tone::Info, "edits discarded: the page shows the unit again");
                } else {
                    self.view.screen = Screen::Devices;
                }
            }
            KeyCode::Up | KeyCode::Down => {
                let sv = &mut self.view.setup;
                let n = sv.page.fields().len();
                sv.field = if key.code == KeyCode::Up {
                    sv.field.saturating_sub(1)
                } else {
                    (sv.field + 1).min(n - 1)
                };
                sv.typing = None;
            }
            KeyCode::Left | KeyCode::Right => {
                let step = if key.code == KeyCode::Left { -1 } else { 1 };
                let step = if key.modifiers.contains(KeyModifiers::SHIFT) {
                    step * 10
                } else {
                    step
                };
                self.adjust(step);
            }
            KeyCode::Char('-') if !field.is_text() => self.adjust(-1),
            KeyCode::Char('+') if !field.is_text() => self.adjust(1),
            KeyCode::Enter => {
                if field.is_action() {
                    self.action(field, now);
                } else if page.is_form() {
                    self.send_page(now);
                }
            }
            KeyCode::Backspace => self.backspace(),
            KeyCode::Char(c) if field.is_text() => self.type_text(c),
            KeyCode::Char(c) if c.is_ascii_digit() || c == '.' => self.type_digit(c),
            KeyCode::Char('p') => {
                let shared = self.model.clone();
                let model = lock(&shared);
                let sv = &mut self.view.setup;
                let r = form::capture(&mut sv.forms, sv.page, field, &model, now);
                drop(model);
                match r {
                    Ok(words) => {
                        self.view.setup.edited[page.index()] = true;
                        self.say(Tone::Good, words);
                    }
                    Err(why) => self.say(Tone::Bad, why),
                }
            }
            KeyCode::Char('q') => return Flow::Quit,
            _ => {}
        }
        Flow::Continue
    }

    fn say(&mut self, tone: Tone, text: impl Into<String>) {
        self.view.setup.message = Some((tone, text.into()));
        self.dirty = true;
    }

    fn goto_page(&mut self, page: Page) {
        let sv = &mut self.view.setup;
        sv.page = page;
        sv.field = 0;
        sv.typing = None;
        sv.message = None;
    }

    fn adjust(&mut self, step: i32) {
        let shared = self.model.clone();
        let model = lock(&shared);
        let sv = &mut self.view.setup;
        sv.typing = None;
        let (page, field) = (sv.page, sv.field());
        if field.is_text() && field != Field::Name {
            return;
        }
        let r = form::adjust(&mut sv.forms, page, field, step, &model);
        drop(model);
        match r {
            Ok(true) => {
                let sv = &mut self.view.setup;
                let discarded = sv.edited[page.index()];
                sv.edited[page.index()] = false;
                if discarded {
                    self.say(
                        Tone::Info,
                        "unsent edits of the previous pin were discarded",
                    );
                }
            }
            Ok(false) => self.view.setup.edited[page.index()] = true,
            Err(why) => self.say(Tone::Bad, why),
        }
    }

    fn type_digit(&mut self, c: char) {
        let sv = &mut self.view.setup;
        let field = sv.field();
        if !form::takes_digits(field) || (c == '.' && field != Field::FlapEndpointDuration) {
            return;
        }
        let t = sv.typing.get_or_insert_with(String::new);
        if t.len() < 6 {
            t.push(c);
        }
        let text = t.clone();
        form::set_typed(&mut sv.forms, sv.page, field, &text);
        sv.edited[sv.page.index()] = true;
    }

    fn type_text(&mut self, c: char) {
        let sv = &mut self.view.setup;
        match sv.field() {
            Field::Name => {
                if !c.is_ascii() || c.is_ascii_control() {
                    return self.say(Tone::Bad, "names are ASCII only (ICD Table 21)");
                }
                if sv.forms.name.len() >= 16 {
                    return self.say(Tone::Bad, "names are at most 16 characters (ICD Table 21)");
                }
                sv.forms.name.push(c);
                sv.edited[Page::Device.index()] = true;
            }
            Field::File => sv.file.push(c),
            _ => {}
        }
    }

    fn backspace(&mut self) {
        let sv = &mut self.view.setup;
        let (page, field) = (sv.page, sv.field());
        match field {
            Field::Name => {
                sv.forms.name.pop();
                sv.edited[page.index()] = true;
            }
            Field::File => {
                sv.file.pop();
            }
            _ => {
                if let Some(t) = &mut sv.typing {
                    t.pop();
                    let text = t.clone();
                    form::set_typed(&mut sv.forms, page, field, &text);
                }
            }
        }
    }

    /// Enter on a form page: check what changed against the §6.2 rules, then queue it.
    fn send_page(&mut self, now: Instant) {
        if self.setup.queue.busy() {
            return self.say(
                Tone::Bad,
                "wait: the last write is still waiting for the unit",
            );
        }
        let shared = self.model.clone();
        let model = lock(&shared);
        let sv = &mut self.view.setup;
        sv.typing = None;
        let page = sv.page;
        let messages = match form::messages(&sv.forms, page, &model) {
            Ok(m) => m,
            Err(why) => {
                drop(model);
                return self.say(Tone::Bad, why);
            }
        };
        if messages.is_empty() {
            drop(model);
            return self.say(
                Tone::Info,
                "nothing to send: the unit already holds these values",
            );
        }
        let (cfg, _) = write::unit_config(&model);
        drop(model);
        match form::check(&cfg, &messages) {
            Err((i, why)) => {
                self.setup.queue.refused_here(&messages, i, why);
                self.say(Tone::Bad, "refused before sending: nothing was sent");
            }
            Ok(()) => {
                self.setup.queue.start(messages);
                self.setup.batch_page = Some(Some(page));
                self.view.setup.message = None;
            }
        }
        self.setup_tick(now);
    }

    /// Sends `messages` through the write queue without this program's own §6.2 check,
    /// so a test can show what the screen does with the unit's own refusal.
    #[doc(hidden)]
    pub fn setup_send_unchecked(&mut self, messages: Vec<Message>, now: Instant) {
        self.setup.queue.start(messages);
        self.setup.batch_page = Some(None);
        self.setup_tick(now);
    }

    fn send_now(&mut self, message: Message) {
        let cnt = self.controller.next_cnt();
        self.send(vec![Packet::request(cnt, message)]);
    }

    fn action(&mut self, field: Field, now: Instant) {
        match field {
            Field::Ping => {
                let m = self.setup.probes.ping(&mut self.view.setup, now);
                self.send_now(m);
            }
            Field::Version => {
                let m = self.setup.probes.version(&mut self.view.setup, now);
                self.send_now(m);
            }
            Field::SaveBackup => {
                let file = self.view.setup.file.clone();
                match self.save_backup(&file) {
                    Ok(words) => self.say(Tone::Good, words),
                    Err(why) => self.say(Tone::Bad, why),
                }
            }
            Field::LoadBackup => self.load_backup(),
            Field::Reread => self.reread(now),
            Field::Erase => {
                let missing = self.missing_for_backup();
                self.view.setup.dialog = Dialog::Erase {
                    missing,
                    backed_up: None,
                };
            }
            _ => {}
        }
    }

    fn reread(&mut self, now: Instant) {
        self.pacer.start(now);
        self.say(
            Tone::Info,
            "asking the unit for every spec, name and enable flag again (about a second)",
        );
    }

    fn missing_for_backup(&self) -> Vec<String> {
        self.known_for_backup().1
    }

    /// The configuration the model knows, what it lacks for a whole backup (VERSION
    /// first), and the version: read under one lock so they agree.
    fn known_for_backup(
        &self,
    ) -> (
        crate::protocol::config::UnitConfig,
        Vec<String>,
        Option<Version>,
    ) {
        let model = lock(&self.model);
        let (config, mut missing) = write::unit_config(&model);
        if model.version.is_none() {
            missing.insert(0, "VERSION".into());
        }
        (config, missing, model.version.map(|v| v.value))
    }

    /// Writes what the model knows of the unit to `file`; refuses when it does not know
    /// everything, since a partial backup would restore defaults over real settings.
    fn save_backup(&mut self, file: &str) -> Result<String, String> {
        if file.trim().is_empty() {
            return Err("type a file name in the Backup file field first".into());
        }
        let (config, missing, version) = self.known_for_backup();
        let Some(version) = version.filter(|_| missing.is_empty()) else {
            return Err(format!(
                "not saved: the page has not heard {} yet; choose \"Re-read the unit\" and \
                 save again",
                crate::ui::setup::dialog::missing_summary(&missing)
            ));
        };
        backup::save(Path::new(file.trim()), &Backup { version, config })
            .map_err(|e| format!("could not write {}: {e}", file.trim()))?;
        Ok(format!("backup written to {}", file.trim()))
    }

    fn load_backup(&mut self) {
        if self.setup.queue.busy() {
            return self.say(
                Tone::Bad,
                "wait: the last write is still waiting for the unit",
            );
        }
        let file = self.view.setup.file.trim().to_string();
        if file.is_empty() {
            return self.say(Tone::Bad, "type a file name in the Backup file field first");
        }
        let b = match backup::load(Path::new(&file)) {
            Ok(b) => b,
            Err(e) => {
                let n = e.problems.len();
                let first: Vec<String> = e.problems.iter().take(2).map(|p| p.to_string()).collect();
                return self.say(
                    Tone::Bad,
                    format!(
                        "{file}: {n} problem{}, nothing sent: {}",
                        if n == 1 { "" } else { "s" },
                        first.join("; ")
                    ),
                );
            }
        };
        let missing = self.missing_for_backup();
        if !missing.is_empty() {
            return self.say(
                Tone::Bad,
                format!(
                    "the page has not heard {} of the unit's settings yet (e.g. {}): choose \
                     \"Re-read the unit\" first, so only real differences are written",
                    missing.len(),
                    missing[0]
                ),
            );
        }
        let (current, unit_version) = {
            let model = lock(&self.model);
            (write::unit_config(&model).0, model.version.map(|v| v.value))
        };
        let Some(unit_version) = unit_version else {
            return;
        };
        if let Err(why) = backup::check_hardware(&b.version, &unit_version) {
            return self.say(Tone::Bad, why);
        }
        let steps = match backup::plan(&current, &b.config) {
            Ok(s) => s,
            Err(e) => return self.say(Tone::Bad, e.to_string()),
        };
        if steps.is_empty() {
            return self.say(
                Tone::Good,
                format!("the unit already holds everything in {file}"),
            );
        }
        let changes = backup::diff(&current, &b.config)
            .iter()
            .map(|c| c.to_string())
            .collect();
        let notes = backup::software_note(&b.version, &unit_version)
            .into_iter()
            .collect();
        self.setup.pending_load = steps.iter().map(|s| s.message()).collect();
        self.view.setup.dialog = Dialog::Load {
            file,
            changes,
            notes,
            writes: steps.len(),
        };
    }

    fn dialog_key(&mut self, key: KeyEvent, now: Instant) {
        let dialog = self.view.setup.dialog.clone();
        let close = |app: &mut App| app.view.setup.dialog = Dialog::None;
        match (dialog, key.code) {
            (_, KeyCode::Esc | KeyCode::Char('n')) => {
                close(self);
                self.setup.pending_load.clear();
                self.say(Tone::Info, "cancelled: nothing was sent");
            }
            (Dialog::Erase { .. }, KeyCode::Char('b')) => {
                let file = self.view.setup.file.clone();
                let r = self.save_backup(&file);
                let missing = self.missing_for_backup();
                match r {
                    Ok(words) => {
                        self.view.setup.dialog = Dialog::Erase {
                            missing,
                            backed_up: Some(words),
                        }
                    }
                    Err(why) => self.say(Tone::Bad, why),
                }
            }
            (Dialog::Erase { backed_up, .. }, KeyCode::Char('r')) => {
                self.reread(now);
                let missing = self.missing_for_backup();
                self.view.setup.dialog = Dialog::Erase { missing, backed_up };
            }
            (Dialog::Erase { .. }, KeyCode::Char('y')) => {
                close(self);
                let m = self.setup.probes.erase(&mut self.view.setup, now);
                self.send_now(m);
                self.say(Tone::Info, "EEPROM_ERASE sent");
            }
            (Dialog::Load { .. }, KeyCode::Char('y') | KeyCode::Enter) => {
                close(self);
                let msgs = std::mem::take(&mut self.setup.pending_load);
                self.setup.queue.start(msgs);
                self.setup.batch_page = Some(None);
                self.say(
                    Tone::Info,
                    "applying the backup, one acknowledged write at a time",
                );
                self.setup_tick(now);
            }
            _ => {}
        }
    }

    /// Every form page without unsent edits follows what the unit holds.
    fn reload_forms(&mut self) {
        let model = lock(&self.model);
        let sv = &mut self.view.setup;
        for page in Page::ALL {
            if page.is_form() && !sv.is_edited(page) {
                form::load(&mut sv.forms, page, &model);
            }
        }
    }

    /// Spec writes waiting for their SPEC_ACK time out and retry here, timed requests
    /// get their answers, and the forms follow the unit.
    pub(super) fn setup_tick(&mut self, now: Instant) {
        let before = self.view.setup.clone();
        let on_screen = self.view.screen == Screen::Setup;
        if on_screen && !self.setup.on_screen {
            // Arriving from the device list: configure the pin that was selected there.
            let model = lock(&self.model);
            let id = self
                .view
                .selected
                .filter(|id| (STARTER..TRIM_R).contains(id))
                .unwrap_or(self.view.setup.forms.device.device_id);
            if !self.view.setup.is_edited(Page::Device) {
                form::select_device(&mut self.view.setup.forms, id, &model);
            }
        }
        self.setup.on_screen = on_screen;

        let messages = {
            let mut model = lock(&self.model);
            self.setup.queue.tick(&mut model, now)
        };
        for m in messages {
            self.send_now(m);
        }
        if self.setup.queue.settled()
            && let Some(page) = self.setup.batch_page.take()
            && self.setup.queue.all_saved()
        {
            // Saved: the form follows the unit again, showing what it really holds.
            match page {
                Some(p) => self.view.setup.edited[p.index()] = false,
                None => self.view.setup.edited = [false; 8],
            }
        }
        self.view.setup.writes = self.setup.queue.lines();
        self.probe_tick(now);
        if on_screen {
            self.reload_forms();
        }
        if self.view.setup != before {
            self.dirty = true;
        }
    }

    fn probe_tick(&mut self, now: Instant) {
        let (again, erase_end) = {
            let model = lock(&self.model);
            self.setup.probes.tick(&model, &mut self.view.setup, now)
        };
        for m in again {
            self.send_now(m);
        }
        match erase_end {
            Some(EraseEnd::Answered(code)) if code != 0 => {
                // Table 12: a non-zero code means the erase did not complete, so
                // nothing may be shown as reset; re-read to show what it holds.
                self.reread(now);
                self.say(
                    Tone::Bad,
                    format!(
                        "the unit reports EEPROM_ERASE failed (response code {code}); \
                         its settings were re-read, check them before going on"
                    ),
                );
            }
            Some(EraseEnd::Answered(_)) => {
                // Every setting is now Appendix F's: forget edits and ask again.
                self.view.setup.edited = [false; 8];
                self.reread(now);
                self.say(
                    Tone::Info,
                    "the unit answered EEPROM_ERASE: it holds the factory settings and \
                     reports a data integrity error until its next power cycle (ICD §6.1.4)",
                );
            }
            Some(EraseEnd::NoAnswer) => self.say(
                Tone::Bad,
                "no answer to EEPROM_ERASE: the unit may or may not have erased; \
                 re-read it to see",
            ),
            None => {}
        }
    }
}

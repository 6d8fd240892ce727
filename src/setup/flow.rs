//! The setup screens' flow: a key or a tick in, the view's state changed and what the
//! app must do out (requests to send, a whole re-read, a backup file to write or read,
//! leave, quit). It holds the write queue, the timed requests and a checked backup
//! waiting for its confirmation.
//!
//! No I/O: the app maps the terminal's keys to [`SetupKey`], hands in the model it
//! has locked, `now`, and the wall-clock time a backup is stamped with; it carries out
//! the [`SetupEffects`] and hands back what came of them ([`SetupFlow::backup_written`],
//! [`SetupFlow::backup_read`]). Motor keys go to its controller before anything
//! comes here.

use std::io;
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

use super::diagnostics::{Diagnostics, EraseEnd};
use super::view::{Dialog, Field, Page, SetupView, Tone, missing_summary};
use super::{form, write};
use crate::backup::{self, Backup, Provenance};
use crate::loads::LoadCircuit;
use crate::model::{Model, Source};
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{STARTER, TRIM_R};
use crate::protocol::message::{Message, Version};
use crate::protocol::names::PIN_NAMES;

/// A key on the setup screens, as the flow reads it; the app maps the terminal's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetupKey {
    Tab,
    BackTab,
    Esc,
    Up,
    Down,
    Left,
    Right,
    /// Shift+←/→: ten steps at once.
    ShiftLeft,
    ShiftRight,
    Enter,
    Backspace,
    Char(char),
}

/// What the app must do after the flow moved; the flow does none of it itself.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct SetupEffects {
    /// Requests to put on the wire, in this order, each with its own command number.
    pub send: Vec<Message>,
    /// Ask the unit for every spec, name and enable flag again (the connect queries).
    pub reread_all: bool,
    /// Back to the device list.
    pub leave: bool,
    pub quit: bool,
    /// Write this backup file, then hand the result to [`SetupFlow::backup_written`].
    pub write_backup: Option<BackupFile>,
    /// Read this backup file, then hand its text to [`SetupFlow::backup_read`].
    pub read_backup: Option<PathBuf>,
}

/// A backup file to write: where, and its whole text (stamped with the caller's time).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BackupFile {
    pub path: PathBuf,
    pub content: String,
}

/// The setup screens' state that the view does not need.
#[derive(Debug, Default)]
pub struct SetupFlow {
    queue: write::WriteQueue,
    /// The page a batch came from; `None` for a backup being applied.
    batch_page: Option<Option<Page>>,
    diagnostics: Diagnostics,
    /// The backup file the app is writing, or reading, for this flow.
    writing: Option<String>,
    reading: Option<String>,
    /// Checked writes waiting for their dialog's `y`: a backup's, or a page's that
    /// disarm a protection.
    pending: Vec<Message>,
    on_screen: bool,
    /// The load file's circuits, for their wires: a breaker above what its wire
    /// allows is asked with `y` like a setting that disarms a protection.
    wires: Vec<LoadCircuit>,
}

fn say(sv: &mut SetupView, tone: Tone, text: impl Into<String>) {
    sv.message = Some((tone, text.into()));
}

const BUSY: &str = "wait: the last write is still waiting for the unit";
const NO_FILE: &str = "type a file name in the Backup file field first";

impl SetupFlow {
    /// The load file's circuits (their wires), read by the app.
    pub fn set_wires(&mut self, wires: Vec<LoadCircuit>) {
        self.wires = wires;
    }

    /// What `messages` would disarm, a breaker over its wire included, in words.
    fn consequences(&self, messages: &[Message], model: &Model, now: Instant) -> Vec<String> {
        let mut out = form::disarms(messages, model, now);
        out.extend(form::over_wires(messages, model, &self.wires));
        out
    }

    /// When the app must tick for a setup timeout.
    pub fn next_deadline(&self) -> Option<Instant> {
        [self.queue.next_deadline(), self.diagnostics.next_deadline()]
            .into_iter()
            .flatten()
            .min()
    }

    /// A key pressed on the setup screens that is not a motor key.
    pub fn key(
        &mut self,
        key: SetupKey,
        sv: &mut SetupView,
        model: &mut Model,
        now: Instant,
        wall: SystemTime,
    ) -> SetupEffects {
        let mut out = SetupEffects::default();
        if sv.dialog != Dialog::None {
            self.dialog_key(key, sv, model, now, wall, &mut out);
            return out;
        }
        let page = sv.page;
        let field = sv.field();
        match key {
            SetupKey::Tab => goto_page(sv, page.next()),
            SetupKey::BackTab => goto_page(sv, page.prev()),
            SetupKey::Esc => {
                if sv.typing.take().is_some() {
                } else if page.is_form() && sv.is_edited(page) {
                    sv.edited[page.index()] = false;
                    reload_forms(sv, model);
                    say(
                        sv,
                        Tone::Info,
                        "edits discarded: the page shows the unit again",
                    );
                } else {
                    out.leave = true;
                }
            }
            SetupKey::Up | SetupKey::Down => {
                let n = sv.page.fields().len();
                sv.field = if key == SetupKey::Up {
                    sv.field.saturating_sub(1)
                } else {
                    (sv.field + 1).min(n - 1)
                };
                sv.typing = None;
            }
            SetupKey::Left => adjust(sv, model, -1),
            SetupKey::Right => adjust(sv, model, 1),
            SetupKey::ShiftLeft => adjust(sv, model, -10),
            SetupKey::ShiftRight => adjust(sv, model, 10),
            SetupKey::Char('-') if !field.is_text() => adjust(sv, model, -1),
            SetupKey::Char('+') if !field.is_text() => adjust(sv, model, 1),
            SetupKey::Enter => {
                if field.is_action() {
                    self.action(field, sv, model, now, wall, &mut out);
                } else if page.is_form() {
                    self.send_page(sv, model, now, &mut out);
                }
            }
            SetupKey::Backspace => backspace(sv),
            SetupKey::Char(c) if field.is_text() => type_text(sv, c),
            SetupKey::Char(c) if c.is_ascii_digit() || c == '.' => type_digit(sv, c),
            SetupKey::Char('p') => match form::capture(&mut sv.forms, page, field, model, now) {
                Ok(words) => {
                    sv.edited[page.index()] = true;
                    say(sv, Tone::Good, words);
                }
                Err(why) => say(sv, Tone::Bad, why),
            },
            SetupKey::Char('q') => out.quit = true,
            _ => {}
        }
        out
    }

    /// Enter on a form page: check what changed against the §6.2 rules, then queue it.
    fn send_page(
        &mut self,
        sv: &mut SetupView,
        model: &mut Model,
        now: Instant,
        out: &mut SetupEffects,
    ) {
        if self.queue.busy() {
            return say(sv, Tone::Bad, BUSY);
        }
        sv.typing = None;
        let page = sv.page;
        let messages = match form::messages(&sv.forms, page, model) {
            Ok(m) => m,
            Err(why) => return say(sv, Tone::Bad, why),
        };
        if messages.is_empty() {
            return say(
                sv,
                Tone::Info,
                "nothing to send: the unit already holds these values",
            );
        }
        let (cfg, _) = write::unit_config(model);
        match form::check(&cfg, &messages) {
            Err((i, why)) => {
                self.queue.refused_here(&messages, i, why);
                say(sv, Tone::Bad, "refused before sending: nothing was sent");
            }
            Ok(()) => {
                let consequences = self.consequences(&messages, model, now);
                if !consequences.is_empty() {
                    // Nothing goes out until the person has read what it turns off.
                    self.pending = messages;
                    sv.dialog = Dialog::Disarm { consequences };
                    return;
                }
                self.queue.start(messages);
                self.batch_page = Some(Some(page));
                sv.message = None;
            }
        }
        self.tick_into(sv, model, now, out);
    }

    /// Sends `messages` through the write queue without this program's own §6.2 check,
    /// so a test can show what the screen does with the unit's own refusal.
    pub fn send_unchecked(
        &mut self,
        messages: Vec<Message>,
        sv: &mut SetupView,
        model: &mut Model,
        now: Instant,
    ) -> SetupEffects {
        self.queue.start(messages);
        self.batch_page = Some(None);
        let mut out = SetupEffects::default();
        self.tick_into(sv, model, now, &mut out);
        out
    }

    fn action(
        &mut self,
        field: Field,
        sv: &mut SetupView,
        model: &Model,
        now: Instant,
        wall: SystemTime,
        out: &mut SetupEffects,
    ) {
        match field {
            Field::Ping => out.send.push(self.diagnostics.ping(sv, now)),
            Field::Version => out.send.push(self.diagnostics.version(sv, now)),
            Field::SaveBackup => self.save_backup(sv, model, wall, out),
            Field::LoadBackup => self.load_backup(sv, out),
            Field::Reread => reread(sv, out),
            Field::Erase => {
                sv.dialog = Dialog::Erase {
                    missing: known_for_backup(model).1,
                    backed_up: None,
                };
            }
            _ => {}
        }
    }

    /// Asks the app for the backup file's text; [`Self::backup_read`] checks it.
    fn load_backup(&mut self, sv: &mut SetupView, out: &mut SetupEffects) {
        if self.queue.busy() {
            return say(sv, Tone::Bad, BUSY);
        }
        let file = sv.file.trim().to_string();
        if file.is_empty() {
            return say(sv, Tone::Bad, NO_FILE);
        }
        out.read_backup = Some(PathBuf::from(&file));
        self.reading = Some(file);
    }

    /// The text of the backup file [`SetupEffects::read_backup`] asked for, or why it could
    /// not be read: checked against the unit, and what applying it changes put in a
    /// dialog for the person to confirm.
    pub fn backup_read(
        &mut self,
        text: io::Result<String>,
        sv: &mut SetupView,
        model: &Model,
        now: Instant,
    ) {
        let Some(file) = self.reading.take() else {
            return;
        };
        let b = match backup::read(Path::new(&file), text) {
            Ok(b) => b,
            Err(e) => {
                let n = e.problems.len();
                let first: Vec<String> = e.problems.iter().take(2).map(|p| p.to_string()).collect();
                return say(
                    sv,
                    Tone::Bad,
                    format!(
                        "{file}: {n} problem{}, nothing sent: {}",
                        if n == 1 { "" } else { "s" },
                        first.join("; ")
                    ),
                );
            }
        };
        let (current, missing, unit_version) = known_for_backup(model);
        if !missing.is_empty() {
            return say(
                sv,
                Tone::Bad,
                format!(
                    "the page has not heard {} of the unit's settings yet (e.g. {}): choose \
                     \"Re-read the unit\" first, so only real differences are written",
                    missing.len(),
                    missing[0]
                ),
            );
        }
        let Some(unit_version) = unit_version else {
            return;
        };
        if let Err(why) = backup::check_hardware(&b.version, &unit_version) {
            return say(sv, Tone::Bad, why);
        }
        let steps = match backup::plan(&current, &b.config) {
            Ok(s) => s,
            Err(e) => return say(sv, Tone::Bad, e.to_string()),
        };
        if steps.is_empty() {
            return say(
                sv,
                Tone::Good,
                format!("the unit already holds everything in {file}"),
            );
        }
        let changes = backup::diff(&current, &b.config)
            .iter()
            .map(|c| c.to_string())
            .collect();
        self.pending = steps.iter().map(|s| s.message()).collect();
        // A backup that turns a protection off names it, as a page's write does, and
        // only `y` applies it then.
        let notes = backup::software_note(&b.version, &unit_version)
            .into_iter()
            .chain(
                self.consequences(&self.pending, model, now)
                    .into_iter()
                    .map(|c| format!("turns a protection off: {c}")),
            )
            .collect();
        sv.dialog = Dialog::Load {
            file,
            changes,
            notes,
            writes: steps.len(),
        };
    }

    /// Asks the app to write what the model knows of the unit to the backup file, on
    /// the Backup page or from the erase dialog; [`Self::backup_written`] says how it went.
    fn save_backup(
        &mut self,
        sv: &mut SetupView,
        model: &Model,
        wall: SystemTime,
        out: &mut SetupEffects,
    ) {
        match backup_file(&sv.file, model, wall) {
            Ok(file) => {
                self.writing = Some(file.path.display().to_string());
                out.write_backup = Some(file);
            }
            Err(why) => say(sv, Tone::Bad, why),
        }
    }

    /// How writing the file of [`SetupEffects::write_backup`] went.
    pub fn backup_written(&mut self, result: io::Result<()>, sv: &mut SetupView, model: &Model) {
        let Some(file) = self.writing.take() else {
            return;
        };
        match result {
            Err(e) => say(sv, Tone::Bad, format!("could not write {file}: {e}")),
            Ok(()) => {
                let words = format!("backup written to {file}");
                if let Dialog::Erase { .. } = sv.dialog {
                    sv.dialog = Dialog::Erase {
                        missing: known_for_backup(model).1,
                        backed_up: Some(words),
                    };
                } else {
                    say(sv, Tone::Good, words);
                }
            }
        }
    }

    fn dialog_key(
        &mut self,
        key: SetupKey,
        sv: &mut SetupView,
        model: &mut Model,
        now: Instant,
        wall: SystemTime,
        out: &mut SetupEffects,
    ) {
        match (sv.dialog.clone(), key) {
            (_, SetupKey::Esc | SetupKey::Char('n')) => {
                sv.dialog = Dialog::None;
                self.pending.clear();
                say(sv, Tone::Info, "cancelled: nothing was sent");
            }
            (Dialog::Erase { .. }, SetupKey::Char('b')) => self.save_backup(sv, model, wall, out),
            (Dialog::Erase { backed_up, .. }, SetupKey::Char('r')) => {
                reread(sv, out);
                sv.dialog = Dialog::Erase {
                    missing: known_for_backup(model).1,
                    backed_up,
                };
            }
            (Dialog::Erase { .. }, SetupKey::Char('y')) => {
                sv.dialog = Dialog::None;
                out.send.push(self.diagnostics.erase(sv, now));
                say(sv, Tone::Info, "EEPROM_ERASE sent");
            }
            (Dialog::Disarm { .. }, SetupKey::Char('y')) => {
                sv.dialog = Dialog::None;
                let msgs = std::mem::take(&mut self.pending);
                self.queue.start(msgs);
                self.batch_page = Some(Some(sv.page));
                sv.message = None;
                self.tick_into(sv, model, now, out);
            }
            (Dialog::Load { .. }, SetupKey::Enter)
                if !self.consequences(&self.pending, model, now).is_empty() =>
            {
                say(
                    sv,
                    Tone::Bad,
                    "this backup turns a protection off: y applies it, Esc cancels",
                );
            }
            (Dialog::Load { .. }, SetupKey::Char('y') | SetupKey::Enter) => {
                sv.dialog = Dialog::None;
                let msgs = std::mem::take(&mut self.pending);
                self.queue.start(msgs);
                self.batch_page = Some(None);
                say(
                    sv,
                    Tone::Info,
                    "applying the backup, one acknowledged write at a time",
                );
                self.tick_into(sv, model, now, out);
            }
            _ => {}
        }
    }

    /// Writes waiting for their SPEC_ACK time out and retry here, timed requests get
    /// their answers, and the forms follow the unit. `on_screen` says whether the
    /// setup screens are shown; `selected` is the device list's selected pin.
    pub fn tick(
        &mut self,
        sv: &mut SetupView,
        on_screen: bool,
        selected: Option<u8>,
        model: &mut Model,
        now: Instant,
    ) -> SetupEffects {
        if on_screen && !self.on_screen {
            // Arriving from the device list: always the Device page, never where the
            // screens were left, so keys typed from memory land where they are meant.
            goto_page(sv, Page::Device);
            // And it configures the pin that was selected there.
            let id = selected
                .filter(|id| (STARTER..TRIM_R).contains(id))
                .unwrap_or(sv.forms.device.device_id);
            if !sv.is_edited(Page::Device) {
                form::select_device(&mut sv.forms, id, model);
            }
        }
        self.on_screen = on_screen;
        let mut out = SetupEffects::default();
        self.tick_into(sv, model, now, &mut out);
        self.diagnostics_tick(sv, model, now, &mut out);
        if on_screen {
            reload_forms(sv, model);
        }
        out
    }

    fn tick_into(
        &mut self,
        sv: &mut SetupView,
        model: &mut Model,
        now: Instant,
        out: &mut SetupEffects,
    ) {
        out.send.extend(self.queue.tick(model, now));
        if self.queue.settled()
            && let Some(page) = self.batch_page.take()
            && self.queue.all_saved()
        {
            // Saved: the form follows the unit again, showing what it really holds.
            match page {
                Some(p) => sv.edited[p.index()] = false,
                None => sv.edited = [false; 8],
            }
        }
        sv.writes = self.queue.lines();
    }

    fn diagnostics_tick(
        &mut self,
        sv: &mut SetupView,
        model: &Model,
        now: Instant,
        out: &mut SetupEffects,
    ) {
        let (again, erase_end) = self.diagnostics.tick(model, sv, now);
        out.send.extend(again);
        match erase_end {
            Some(EraseEnd::Answered(code)) if code != 0 => {
                // Table 12: a non-zero code means the erase did not complete, so
                // nothing may be shown as reset; re-read to show what it holds.
                reread(sv, out);
                say(
                    sv,
                    Tone::Bad,
                    format!(
                        "the unit reports EEPROM_ERASE failed (response code {code}); \
                         its settings were re-read, check them before going on"
                    ),
                );
            }
            Some(EraseEnd::Answered(_)) => {
                // Every setting is now Appendix F's: forget edits and ask again.
                sv.edited = [false; 8];
                reread(sv, out);
                say(
                    sv,
                    Tone::Info,
                    "the unit answered EEPROM_ERASE: it holds the factory settings and \
                     reports a data integrity error until its next power cycle (ICD §6.1.4)",
                );
            }
            Some(EraseEnd::NoAnswer) => say(
                sv,
                Tone::Bad,
                "no answer to EEPROM_ERASE: the unit may or may not have erased; \
                 re-read it to see",
            ),
            None => {}
        }
    }
}

fn goto_page(sv: &mut SetupView, page: Page) {
    sv.page = page;
    sv.field = 0;
    sv.typing = None;
    sv.message = None;
}

fn reread(sv: &mut SetupView, out: &mut SetupEffects) {
    out.reread_all = true;
    say(
        sv,
        Tone::Info,
        "asking the unit for every spec, name and enable flag again (about a second)",
    );
}

fn adjust(sv: &mut SetupView, model: &Model, step: i32) {
    sv.typing = None;
    let (page, field) = (sv.page, sv.field());
    if field.is_text() && field != Field::Name {
        return;
    }
    if refuse_unread(sv) {
        return;
    }
    let name_before = sv.forms.name.clone();
    match form::adjust(&mut sv.forms, page, field, step, model) {
        Ok(false) if field == Field::Name => {
            sv.edited[page.index()] = true;
            // Decision: ←/→ replaces a name not from Appendix C, and says so.
            if !name_before.is_empty() && !PIN_NAMES.contains(&name_before.as_str()) {
                let now = sv.forms.name.clone();
                say(
                    sv,
                    Tone::Info,
                    format!(
                        "←/→ picks from ICD Appendix C: \"{name_before}\" replaced by \
                         \"{now}\" (Esc discards the edit)"
                    ),
                );
            }
        }
        Ok(true) => {
            let discarded = sv.edited[page.index()];
            sv.edited[page.index()] = false;
            if discarded {
                say(
                    sv,
                    Tone::Info,
                    "unsent edits of the previous pin were discarded",
                );
            }
        }
        Ok(false) => sv.edited[page.index()] = true,
        Err(why) => say(sv, Tone::Bad, why),
    }
}

fn type_digit(sv: &mut SetupView, c: char) {
    let field = sv.field();
    if field.is_action() {
        return say(sv, Tone::Bad, "digits do nothing here: Enter does this one");
    }
    if !field.takes_digits() {
        // Decision: a field of choices is not typed into; the digit is refused in
        // words rather than dropped.
        return say(
            sv,
            Tone::Bad,
            format!(
                "{} is not typed: ←/→ chooses it (the line above says from what)",
                field.label().to_lowercase()
            ),
        );
    }
    if c == '.' && field != Field::FlapEndpointDuration {
        return say(sv, Tone::Bad, "whole numbers only here: '.' not taken");
    }
    if refuse_unread(sv) {
        return;
    }
    let t = sv.typing.get_or_insert_with(String::new);
    if t.len() >= 6 {
        return say(sv, Tone::Bad, "at most 6 digits: the digit was not taken");
    }
    t.push(c);
    let text = t.clone();
    form::set_typed(&mut sv.forms, sv.page, field, &text);
    sv.edited[sv.page.index()] = true;
}

fn type_text(sv: &mut SetupView, c: char) {
    match sv.field() {
        Field::Name => {
            if refuse_unread(sv) {
                return;
            }
            if !c.is_ascii() || c.is_ascii_control() {
                return say(
                    sv,
                    Tone::Bad,
                    format!("'{c}' not taken: names are ASCII only (ICD Table 21)"),
                );
            }
            if sv.forms.name.len() >= 16 {
                return say(
                    sv,
                    Tone::Bad,
                    format!("'{c}' not taken: names are at most 16 characters (ICD Table 21)"),
                );
            }
            sv.forms.name.push(c);
            sv.edited[Page::Device.index()] = true;
        }
        Field::File => sv.file.push(c),
        _ => {}
    }
}

fn backspace(sv: &mut SetupView) {
    let (page, field) = (sv.page, sv.field());
    match field {
        Field::Name => {
            if refuse_unread(sv) {
                return;
            }
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

/// Every form page without unsent edits follows what the unit holds, and on every
/// page a part the unit had not reported fills in when it does.
fn reload_forms(sv: &mut SetupView, model: &Model) {
    for page in Page::ALL {
        if page.is_form() {
            let edited = sv.is_edited(page);
            form::load(&mut sv.forms, page, model, edited);
        }
    }
}

/// Refuses an edit of a field whose part the unit has not reported: there is no value
/// of the unit's to change, only a stand-in. True when refused.
fn refuse_unread(sv: &mut SetupView) -> bool {
    match form::not_read(&sv.forms, sv.page, sv.field()) {
        Some(why) => {
            sv.typing = None;
            say(sv, Tone::Bad, why);
            true
        }
        None => false,
    }
}

/// The configuration the model knows, what it lacks for a whole backup (VERSION
/// first), and the version.
fn known_for_backup(model: &Model) -> (UnitConfig, Vec<String>, Option<Version>) {
    let (config, mut missing) = write::unit_config(model);
    if model.version.is_none() {
        missing.insert(0, "VERSION".into());
    }
    (config, missing, model.version.map(|v| v.value))
}

/// What the model knows of the unit as a backup file's text for `file`, stamped with
/// `wall`; refused when it does not know everything, since a partial backup would
/// restore defaults over real settings.
fn backup_file(file: &str, model: &Model, wall: SystemTime) -> Result<BackupFile, String> {
    if file.trim().is_empty() {
        return Err(NO_FILE.into());
    }
    let (config, missing, version) = known_for_backup(model);
    let Some(version) = version.filter(|_| missing.is_empty()) else {
        return Err(format!(
            "not saved: the page has not heard {} yet; choose \"Re-read the unit\" and \
             save again",
            missing_summary(&missing)
        ));
    };
    // The file says where it came from, as `vpx-efis backup` writes it.
    let made = match &model.source {
        Source::Serial { path } => Provenance::at(path, false, wall),
        Source::Simulated { scenario } => Provenance::at(
            &format!("the built-in virtual VP-X (scenario {scenario})"),
            true,
            wall,
        ),
        Source::Replay { file } => Provenance::at(&format!("a replay of {file}"), false, wall),
    };
    Ok(BackupFile {
        path: PathBuf::from(file.trim()),
        content: backup::to_toml_made(&Backup { version, config }, &made),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::tests::{hear, hear_named, model, ms};

    use crate::model::Rereader;
    use crate::model::Setting;
    use crate::protocol::message::{
        DeviceName, DeviceSpec, DeviceSpecQuery, OvervoltageLimit, SpecAck, SwitchId,
    };
    use crate::setup::view::WriteStatus;

    /// The wall-clock time backups are stamped with in these tests.
    const WALL: SystemTime = SystemTime::UNIX_EPOCH;

    fn held(cb: u8) -> DeviceSpec {
        DeviceSpec {
            device_id: 9,
            circuit_breaker: cb,
            switch_id: SwitchId::Input(2),
            current_fault: false,
            switch_raw: None,
        }
    }

    /// Connected while the unit was silent: nothing of pin 9 is heard. The page shows
    /// no value as the unit's, refuses edits and Enter in words and sends nothing; the
    /// re-reads go out after the connect grace, and once the unit answers the form
    /// shows its values and the write goes out built on them.
    #[test]
    fn a_spec_never_heard_is_not_written_until_the_unit_reports_it() {
        let t0 = Instant::now();
        let mut m = model();
        let mut sv = SetupView::default();
        let mut flow = SetupFlow::default();
        let mut rereader = Rereader::default();
        rereader.connected(t0);
        flow.tick(&mut sv, true, Some(9), &mut m, ms(t0, 500));
        assert_eq!(sv.forms.device.device_id, 9);
        assert!(
            !sv.forms.from_unit.device,
            "Appendix F's spec is not the unit's"
        );
        let mut sent = Vec::new();
        sent.extend(
            flow.key(SetupKey::Down, &mut sv, &mut m, ms(t0, 600), WALL)
                .send,
        );
        sent.extend(
            flow.key(SetupKey::Char('3'), &mut sv, &mut m, ms(t0, 600), WALL)
                .send,
        );
        assert!(
            !sv.is_edited(Page::Device),
            "the breaker could not be typed"
        );
        let refusal = sv.message.clone().unwrap();
        assert_eq!(refusal.0, Tone::Bad);
        assert!(
            refusal
                .1
                .contains("not yet read from the unit — re-reading; try again when it answers"),
            "{refusal:?}"
        );
        sent.extend(
            flow.key(SetupKey::Enter, &mut sv, &mut m, ms(t0, 700), WALL)
                .send,
        );
        assert!(sv.message.as_ref().unwrap().1.starts_with("nothing sent: "));
        for t in (800..=2900).step_by(100) {
            sent.extend(flow.tick(&mut sv, true, Some(9), &mut m, ms(t0, t)).send);
            assert!(
                rereader.due(&m, ms(t0, t)).is_empty(),
                "the connect queries' turn"
            );
        }
        assert!(sent.is_empty(), "nothing written: {sent:?}");
        // The unit is still silent; from the grace on, pin 9's settings are re-read.
        let mut queries = Vec::new();
        for t in (3000..=3400).step_by(20) {
            queries.extend(rereader.due(&m, ms(t0, t)));
        }
        assert!(queries.contains(&DeviceSpecQuery { device_id: 9 }.into()));
        // It answers.
        let unit = DeviceSpec {
            device_id: 9,
            circuit_breaker: 4,
            switch_id: SwitchId::Input(6),
            current_fault: true,
            switch_raw: None,
        };
        hear(&mut m, ms(t0, 3500), unit);
        hear_named(&mut m, ms(t0, 3500), 9, "Strobe");
        flow.tick(&mut sv, true, Some(9), &mut m, ms(t0, 3600));
        assert_eq!(sv.forms.device, unit, "the form shows what the unit holds");
        assert_eq!(sv.forms.name, "Strobe");
        flow.key(SetupKey::Char('3'), &mut sv, &mut m, ms(t0, 3700), WALL);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, ms(t0, 3700), WALL);
        assert_eq!(
            out.send,
            vec![Message::DeviceSpec(DeviceSpec {
                circuit_breaker: 3,
                ..unit
            })],
            "only the breaker changed; the unit's switch 6 and current fault kept"
        );
    }

    /// The whole flow on a fake clock, keys to what the page shows, with the unit's
    /// side played by hand: its SPEC_ACKs are lost, it stores the spec, and it answers
    /// the second re-read.
    #[test]
    fn a_typed_breaker_whose_acks_are_lost_ends_showing_what_the_unit_holds() {
        let t0 = Instant::now();
        let mut m = model();
        hear(&mut m, t0, held(4));
        hear_named(&mut m, t0, 9, "Landing Lt");
        let mut sv = SetupView::default();
        let mut flow = SetupFlow::default();
        let mut rereader = Rereader::default();
        flow.tick(&mut sv, true, Some(9), &mut m, t0);
        assert_eq!(
            sv.forms.device,
            held(4),
            "the form shows what the unit holds"
        );
        flow.key(SetupKey::Down, &mut sv, &mut m, t0, WALL);
        flow.key(SetupKey::Char('3'), &mut sv, &mut m, t0, WALL);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert_eq!(out.send, vec![Message::DeviceSpec(held(3))]);
        let mut sent = 1;
        let mut queries = 0;
        for t in (100..=6000).step_by(100) {
            let now = ms(t0, t);
            let mut out = flow.tick(&mut sv, true, Some(9), &mut m, now).send;
            out.extend(rereader.due(&m, now));
            for msg in out {
                match msg {
                    Message::DeviceSpec(_) => sent += 1,
                    Message::DeviceSpecQuery(DeviceSpecQuery { device_id: 9 }) => {
                        queries += 1;
                        // The first re-read is lost on the line; the second answered.
                        if queries == 2 {
                            hear(&mut m, now, held(3));
                        }
                    }
                    other => panic!("unexpected {other:?}"),
                }
            }
            if t == 3000 {
                assert_eq!(sv.writes[0].status, WriteStatus::NoAnswer);
                assert!(m.is_unknown(Setting::DeviceSpec(9)));
                assert_eq!(m.device_specs[9], None, "4 A is not shown as held");
            }
        }
        assert_eq!(sent, 3);
        assert_eq!(queries, 2, "asked at 3 s, again at 4 s, then answered");
        assert!(matches!(
            sv.writes[0].status,
            WriteStatus::ReadBack {
                matches: true,
                acked: false,
                ..
            }
        ));
        assert_eq!(m.device_specs[9].unwrap().value, held(3));
        assert!(
            !sv.is_edited(Page::Device),
            "the form follows the unit again"
        );
        // A SPEC_ACK arriving late, for nothing in flight, changes nothing.
        hear(
            &mut m,
            ms(t0, 6100),
            SpecAck {
                device_id: 9,
                error: None,
            },
        );
        assert!(
            flow.tick(&mut sv, true, Some(9), &mut m, ms(t0, 6200))
                .send
                .is_empty()
        );
    }

    /// A unit that reported every setting: overvoltage `limit`, flaps and both trims
    /// fitted, 5A-1 with current-fault checking on; and a live bus at `bus` volts.
    fn armed_unit(t0: Instant, limit: OvervoltageLimit, bus: Option<f32>) -> Model {
        use crate::protocol::Payload;
        use crate::protocol::defaults;
        use crate::protocol::message::{SignedTenths, SystemSpec, SystemStatus, TrimType};
        let mut m = model();
        for id in 1..=28u8 {
            let mut spec = defaults::device_spec(id);
            if id == 4 {
                spec.current_fault = true;
            }
            hear(&mut m, t0, spec);
            hear_named(&mut m, t0, id, "");
        }
        for id in [0, 29, 30] {
            hear(&mut m, t0, DeviceName::new(id, "").unwrap());
        }
        hear(&mut m, t0, defaults::wig_wag_spec());
        let system = SystemSpec {
            overvoltage_limit: limit,
            secondary_alternator: None,
        };
        hear(&mut m, t0, system);
        let mut flap = defaults::flap_spec();
        flap.enabled = true;
        hear(&mut m, t0, flap);
        for t in [TrimType::Pitch, TrimType::Roll] {
            let mut trim = defaults::trim_spec(t);
            trim.enabled = true;
            trim.power = 60;
            hear(&mut m, t0, trim);
        }
        if let Some(v) = bus {
            let mut st = SystemStatus::parse(&[0u8; 12]).unwrap();
            st.main_bus_volts = SignedTenths((v * 10.0).round() as i16);
            hear(&mut m, t0, st);
        }
        m
    }

    /// The setup screens opened on pin `pin` of [`armed_unit`] (16 V on a 14.2 V bus).
    fn opened_on(pin: u8) -> (Instant, Model, SetupView, SetupFlow) {
        let t0 = Instant::now();
        let mut m = armed_unit(t0, OvervoltageLimit::V16, Some(14.2));
        let mut sv = SetupView::default();
        let mut flow = SetupFlow::default();
        flow.tick(&mut sv, true, Some(pin), &mut m, t0);
        (t0, m, sv, flow)
    }

    /// On `page`, `field` changed by → and Enter pressed: what went out, and the flow
    /// and view to go on with.
    fn change_and_send(
        m: &mut Model,
        t0: Instant,
        page: Page,
        field: Field,
        pin: u8,
    ) -> (SetupFlow, SetupView, Vec<Message>) {
        let mut sv = SetupView::default();
        let mut flow = SetupFlow::default();
        flow.tick(&mut sv, true, Some(pin), m, t0);
        sv.page = page;
        sv.field = page.fields().iter().position(|&f| f == field).unwrap();
        let mut sent = flow.key(SetupKey::Right, &mut sv, m, t0, WALL).send;
        assert!(sv.is_edited(page), "{field:?} changed");
        sent.extend(flow.key(SetupKey::Enter, &mut sv, m, t0, WALL).send);
        (flow, sv, sent)
    }

    /// Every setting that disarms a protection: Enter sends nothing and asks, naming
    /// the consequence; Esc sends nothing and keeps the edit; Enter again asks again
    /// and a second Enter does not confirm; only `y` sends it.
    #[test]
    fn a_setting_that_disarms_a_protection_is_sent_only_once_confirmed() {
        use OvervoltageLimit::{V16, V32};
        type Case = (
            &'static str,
            OvervoltageLimit,
            Option<f32>,
            Page,
            Field,
            &'static str,
        );
        let cases: [Case; 7] = [
            (
                "32 V on a 14 V bus",
                V16,
                Some(14.2),
                Page::System,
                Field::Overvoltage,
                "overvoltage 32 V while the bus reads 14.2 V: 32 V is for a 28 V system; on this 14 V system the overvoltage protection would never trip",
            ),
            (
                "16 V on a 28 V bus",
                V32,
                Some(27.9),
                Page::System,
                Field::Overvoltage,
                "overvoltage 16 V while the bus reads 27.9 V: 16 V is for a 14 V system; on this 28 V system the unit would flag overvoltage at once",
            ),
            (
                "32 V with no live bus",
                V16,
                None,
                Page::System,
                Field::Overvoltage,
                "overvoltage 32 V with no live bus voltage to check it against",
            ),
            (
                "flaps disabled",
                V16,
                Some(14.2),
                Page::Flaps,
                Field::FlapEnabled,
                "flaps disabled: the unit holds them as fitted",
            ),
            (
                "pitch trim disabled",
                V16,
                Some(14.2),
                Page::PitchTrim,
                Field::TrimEnabled,
                "pitch trim disabled: the unit holds it as fitted; disabled, it takes it as not installed and the pitch trim switches no longer run it",
            ),
            (
                "roll trim disabled",
                V16,
                Some(14.2),
                Page::RollTrim,
                Field::TrimEnabled,
                "roll trim disabled",
            ),
            (
                "current fault off",
                V16,
                Some(14.2),
                Page::Device,
                Field::CurrentFault,
                "current fault check off on 5A-1 (device 4): it will no longer be switched off when it draws more than its 2 A breaker",
            ),
        ];
        for (name, limit, bus, page, field, words) in cases {
            let t0 = Instant::now();
            let mut m = armed_unit(t0, limit, bus);
            let (mut flow, mut sv, sent) = change_and_send(&mut m, t0, page, field, 4);
            assert!(
                sent.is_empty(),
                "{name}: nothing sent before confirming: {sent:?}"
            );
            let Dialog::Disarm { consequences } = sv.dialog.clone() else {
                panic!("{name}: no confirmation: {:?}", sv.message);
            };
            assert_eq!(consequences.len(), 1, "{name}: {consequences:?}");
            assert!(
                consequences[0].starts_with(words),
                "{name}: {consequences:?}"
            );
            for t in [100, 2000] {
                let out = flow.tick(&mut sv, true, Some(4), &mut m, ms(t0, t));
                assert!(out.send.is_empty(), "{name}: a tick sends nothing");
            }
            let out = flow.key(SetupKey::Esc, &mut sv, &mut m, t0, WALL);
            assert!(out.send.is_empty(), "{name}: cancelled");
            assert_eq!(sv.dialog, Dialog::None);
            assert!(sv.is_edited(page), "{name}: the edit stays after Esc");
            let mut sent = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL).send;
            sent.extend(flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL).send);
            assert!(sent.is_empty(), "{name}: Enter never confirms: {sent:?}");
            assert!(matches!(sv.dialog, Dialog::Disarm { .. }), "{name}");
            let out = flow.key(SetupKey::Char('y'), &mut sv, &mut m, t0, WALL);
            assert_eq!(sv.dialog, Dialog::None);
            let expected: Message = match page {
                Page::System => sv.forms.system.into(),
                Page::Flaps => sv.forms.flap.into(),
                Page::PitchTrim => sv.forms.pitch.into(),
                Page::RollTrim => sv.forms.roll.into(),
                _ => sv.forms.device.into(),
            };
            assert_eq!(out.send, vec![expected], "{name}: sent once confirmed");
        }
    }

    /// The limit that suits the bus, and enabling what was disabled, go out at once.
    #[test]
    fn a_setting_that_arms_a_protection_is_sent_without_asking() {
        let t0 = Instant::now();
        let mut m = armed_unit(t0, OvervoltageLimit::V32, Some(14.2));
        let (_, sv, sent) = change_and_send(&mut m, t0, Page::System, Field::Overvoltage, 4);
        assert_eq!(sv.dialog, Dialog::None);
        assert_eq!(sent.len(), 1, "16 V on a 14.2 V bus: {sent:?}");
        let mut m = armed_unit(t0, OvervoltageLimit::V16, Some(28.4));
        let (_, sv, sent) = change_and_send(&mut m, t0, Page::System, Field::Overvoltage, 4);
        assert_eq!(sv.dialog, Dialog::None);
        assert_eq!(sent.len(), 1, "32 V on a 28.4 V bus: {sent:?}");
        // 5A-1's check off → on is arming it.
        let mut m = armed_unit(t0, OvervoltageLimit::V16, Some(14.2));
        let (_, sv, sent) = change_and_send(&mut m, t0, Page::Device, Field::CurrentFault, 5);
        assert_eq!(sv.dialog, Dialog::None);
        assert_eq!(sent.len(), 1, "5A-2's check switched on: {sent:?}");
    }

    /// A breaker above what the circuit's wire allows (AC 43.13-1B Table 11-3: 5 A for
    /// 22 AWG) is a protection disarmed: Enter sends nothing and asks, naming the wire
    /// and the limit; only `y` sends it. At the chart's 5 A it goes out at once.
    #[test]
    fn a_breaker_over_its_wire_is_asked_naming_the_wire_and_the_limit() {
        use crate::loads::wiring::WireRun;
        let strobe = 0x11; // 10A-1: up to 10 A on the pin, 5 A on its 22 AWG wire
        let wires = vec![LoadCircuit {
            id: strobe,
            name: "Strobe".into(),
            amps: None,
            duty: [0.0; 7],
            wire: WireRun {
                wire: Some(crate::loads::wire::Wire::parse("22 AWG").unwrap()),
                feed_feet: Some(12.0),
                return_feet: None,
            },
        }];
        let t0 = Instant::now();
        let mut m = armed_unit(t0, OvervoltageLimit::V16, Some(14.2));
        hear(&mut m, t0, DeviceName::new(strobe, "Strobe Lt").unwrap());
        let (mut sv, mut flow) = (SetupView::default(), SetupFlow::default());
        flow.tick(&mut sv, true, Some(strobe), &mut m, t0);
        flow.set_wires(wires.clone());
        sv.field = 1;
        assert_eq!(sv.field(), Field::Breaker);
        flow.key(SetupKey::Char('6'), &mut sv, &mut m, t0, WALL);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert!(out.send.is_empty(), "nothing sent before y: {:?}", out.send);
        let Dialog::Disarm { consequences } = sv.dialog.clone() else {
            panic!("no confirmation: {:?}", sv.message);
        };
        assert_eq!(
            consequences,
            [
                "Strobe Lt's wire is 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 6 A \
              breaker would not protect it"
            ]
        );
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert!(out.send.is_empty(), "Enter never confirms");
        let out = flow.key(SetupKey::Char('y'), &mut sv, &mut m, t0, WALL);
        assert_eq!(out.send, vec![Message::from(sv.forms.device)]);
        assert_eq!(sv.forms.device.circuit_breaker, 6);

        // 5 A, what the chart allows, is not asked.
        let (t0, mut m, mut sv, mut flow) = opened_on(strobe);
        flow.set_wires(wires);
        sv.field = 1;
        flow.key(SetupKey::Char('5'), &mut sv, &mut m, t0, WALL);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert_eq!(sv.dialog, Dialog::None);
        assert_eq!(out.send.len(), 1, "5 A on 22 AWG goes out at once");
    }

    /// A breaker above the pin's rating never reaches a confirmation: Appendix B's
    /// range ends at the rating, so it is refused before anything is sent.
    #[test]
    fn a_breaker_above_the_pins_rating_is_refused_not_confirmed() {
        let (t0, mut m, mut sv, mut flow) = opened_on(4);
        sv.field = 1;
        assert_eq!(sv.field(), Field::Breaker);
        flow.key(SetupKey::Char('6'), &mut sv, &mut m, t0, WALL);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert!(out.send.is_empty());
        assert_eq!(sv.dialog, Dialog::None);
        assert_eq!(
            sv.writes[0].status,
            WriteStatus::Refused {
                why: "Invalid circuit breaker value: 6 A is outside 1–5 A for 5A-1 (ICD Table 40)"
                    .into(),
                by_unit: false,
            }
        );
    }

    /// Left on the System page, the setup screens open again on the Device page.
    #[test]
    fn the_setup_screens_open_on_the_device_page_every_time() {
        let (t0, mut m, mut sv, mut flow) = opened_on(4);
        flow.key(SetupKey::Tab, &mut sv, &mut m, t0, WALL);
        flow.key(SetupKey::Down, &mut sv, &mut m, t0, WALL);
        assert_eq!(
            (sv.page, sv.field()),
            (Page::System, Field::SecondaryAlternator)
        );
        assert!(flow.key(SetupKey::Esc, &mut sv, &mut m, t0, WALL).leave);
        flow.tick(&mut sv, false, Some(4), &mut m, ms(t0, 100));
        flow.tick(&mut sv, true, Some(7), &mut m, ms(t0, 200));
        assert_eq!((sv.page, sv.field()), (Page::Device, Field::DeviceId));
        assert_eq!(sv.forms.device.device_id, 7);
    }

    fn typed(flow: &mut SetupFlow, sv: &mut SetupView, m: &mut Model, t: Instant, text: &str) {
        for c in text.chars() {
            flow.key(SetupKey::Char(c), sv, m, t, WALL);
        }
    }

    fn said(sv: &SetupView) -> (Tone, String) {
        sv.message.clone().expect("a word on screen")
    }

    /// Typing never fails in silence: a digit on a field of choices, a character
    /// that is not ASCII, a 17th character, ←/→ over a typed name, an empty name:
    /// each is refused or done in words, and the footer offers typing only where
    /// digits are taken.
    #[test]
    fn typing_in_setup_is_refused_or_done_in_words() {
        let (t0, mut m, mut sv, mut flow) = opened_on(4);
        hear(&mut m, t0, DeviceName::new(4, "Nav Lt").unwrap());
        flow.tick(&mut sv, true, Some(4), &mut m, t0);
        for (page, field) in [
            (Page::Device, Field::Switch),
            (Page::System, Field::Overvoltage),
            (Page::System, Field::SecondaryAlternator),
        ] {
            sv.page = page;
            sv.field = page.fields().iter().position(|&f| f == field).unwrap();
            let before = sv.forms.clone();
            sv.message = None;
            flow.key(SetupKey::Char('3'), &mut sv, &mut m, t0, WALL);
            assert_eq!(sv.forms, before, "{field:?}: nothing typed");
            let (tone, words) = said(&sv);
            assert_eq!(tone, Tone::Bad);
            assert!(
                words.starts_with(&format!(
                    "{} is not typed: ←/→ chooses it",
                    field.label().to_lowercase()
                )),
                "{words}"
            );
            let keys = crate::setup::view::keys(&sv);
            assert!(
                !keys.iter().any(|(k, _)| *k == "0-9"),
                "{field:?}: {keys:?}"
            );
        }
        sv.page = Page::Device;
        sv.field = 1;
        assert!(
            crate::setup::view::keys(&sv).contains(&("0-9", "type")),
            "the breaker"
        );
        // The name: é, then 19 characters.
        sv.field = Page::Device
            .fields()
            .iter()
            .position(|&f| f == Field::Name)
            .unwrap();
        for (erased, text, name, refused) in [
            (
                0,
                "é",
                "Nav Lt",
                "'é' not taken: names are ASCII only (ICD Table 21)",
            ),
            (
                6,
                "Landing Light Left",
                "Landing Light Le",
                "'t' not taken: names are at most 16 characters (ICD Table 21)",
            ),
        ] {
            for _ in 0..erased {
                flow.key(SetupKey::Backspace, &mut sv, &mut m, t0, WALL);
            }
            typed(&mut flow, &mut sv, &mut m, t0, text);
            assert_eq!(sv.forms.name, name, "typed {text:?}");
            assert_eq!(said(&sv), (Tone::Bad, refused.into()), "typed {text:?}");
        }
        // ←/→ over a typed name replaces it, and says so.
        flow.key(SetupKey::Right, &mut sv, &mut m, t0, WALL);
        let (tone, words) = said(&sv);
        assert_eq!(tone, Tone::Info);
        assert_eq!(
            words,
            format!(
                "←/→ picks from ICD Appendix C: \"Landing Light Le\" replaced by \"{}\" \
                 (Esc discards the edit)",
                sv.forms.name
            )
        );
        // An empty name is refused, nothing sent.
        for _ in 0..16 {
            flow.key(SetupKey::Backspace, &mut sv, &mut m, t0, WALL);
        }
        assert_eq!(sv.forms.name, "");
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert!(out.send.is_empty(), "{:?}", out.send);
        assert_eq!(
            said(&sv),
            (
                Tone::Bad,
                "nothing sent: an empty name is refused (the unit keeps \"Nav Lt\"); type a \
                 name, or pick one with ←/→"
                    .into()
            )
        );
    }

    /// Pin 4 opened, the unit's VERSION heard (so a backup can be whole), and the
    /// Backup page showing with `unit.toml` in its file field.
    fn on_backup_page() -> (Instant, Model, SetupView, SetupFlow) {
        use crate::protocol::message::{HardwareVersion, Version};
        let (t0, mut m, mut sv, flow) = opened_on(4);
        let version = Version {
            hardware_version: HardwareVersion::VpxPro,
            software_major: 2,
            software_minor: 1,
        };
        hear(&mut m, t0, version);
        sv.file = "unit.toml".into();
        sv.page = Page::Backup;
        (t0, m, sv, flow)
    }

    /// A backup that sets 32 V on a 14.2 V bus names that in its confirmation, and
    /// Enter does not apply it; `y` does.
    #[test]
    fn a_backup_that_disarms_a_protection_says_so_and_needs_y() {
        let (t0, mut m, mut sv, mut flow) = on_backup_page();
        // The flow writes and reads no file: it asks, and is told what came of it.
        sv.field = Page::Backup
            .fields()
            .iter()
            .position(|&f| f == Field::SaveBackup)
            .unwrap();
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        let written = out.write_backup.expect("a backup to write");
        assert_eq!(written.path, PathBuf::from("unit.toml"));
        assert!(
            written
                .content
                .contains("at = \"1970-01-01T00:00:00.000Z\""),
            "stamped with the caller's time: {}",
            written.content
        );
        assert_eq!(sv.message, None, "not said written before it is");
        flow.backup_written(Ok(()), &mut sv, &m);
        assert_eq!(said_tone(&sv), Tone::Good, "{:?}", sv.message);
        let text = written.content.replace(
            "overvoltage_limit_volts = 16",
            "overvoltage_limit_volts = 32",
        );
        sv.field = Page::Backup
            .fields()
            .iter()
            .position(|&f| f == Field::LoadBackup)
            .unwrap();
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert_eq!(out.read_backup, Some(PathBuf::from("unit.toml")));
        flow.backup_read(Ok(text), &mut sv, &m, t0);
        let Dialog::Load { notes, .. } = sv.dialog.clone() else {
            panic!("{:?}", sv.message);
        };
        assert!(
            notes.iter().any(|n| n.starts_with(
                "turns a protection off: overvoltage 32 V while the bus reads 14.2 V"
            )),
            "{notes:?}"
        );
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert!(
            out.send.is_empty(),
            "Enter does not apply it: {:?}",
            out.send
        );
        assert!(matches!(sv.dialog, Dialog::Load { .. }));
        let out = flow.key(SetupKey::Char('y'), &mut sv, &mut m, t0, WALL);
        assert!(
            matches!(out.send.as_slice(), [Message::SystemSpec(s)] if s.overvoltage_limit == OvervoltageLimit::V32),
            "{:?}",
            out.send
        );
    }

    /// What the app hands back decides what the page says: a write that failed is
    /// never shown as a backup taken, in the erase dialog or on the page, and a file
    /// that could not be read says why and applies nothing.
    #[test]
    fn a_backup_is_said_written_or_read_only_as_the_app_reports() {
        let (t0, mut m, mut sv, mut flow) = on_backup_page();
        let at = |f| Page::Backup.fields().iter().position(|&x| x == f).unwrap();
        sv.field = at(Field::SaveBackup);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert!(out.write_backup.is_some());
        let denied = io::Error::new(io::ErrorKind::PermissionDenied, "denied");
        flow.backup_written(Err(denied), &mut sv, &m);
        assert_eq!(
            sv.message,
            Some((Tone::Bad, "could not write unit.toml: denied".into()))
        );

        sv.field = at(Field::Erase);
        flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        let out = flow.key(SetupKey::Char('b'), &mut sv, &mut m, t0, WALL);
        assert!(out.write_backup.is_some());
        assert!(
            matches!(
                &sv.dialog,
                Dialog::Erase {
                    backed_up: None,
                    ..
                }
            ),
            "{:?}",
            sv.dialog
        );
        flow.backup_written(Ok(()), &mut sv, &m);
        assert!(
            matches!(&sv.dialog, Dialog::Erase { backed_up: Some(w), .. } if w == "backup written to unit.toml"),
            "{:?}",
            sv.dialog
        );
        flow.key(SetupKey::Esc, &mut sv, &mut m, t0, WALL);

        sv.field = at(Field::LoadBackup);
        let out = flow.key(SetupKey::Enter, &mut sv, &mut m, t0, WALL);
        assert_eq!(out.read_backup, Some(PathBuf::from("unit.toml")));
        let gone = io::Error::new(io::ErrorKind::NotFound, "no such file");
        flow.backup_read(Err(gone), &mut sv, &m, t0);
        assert_eq!(sv.dialog, Dialog::None);
        assert_eq!(
            sv.message,
            Some((
                Tone::Bad,
                "unit.toml: 1 problem, nothing sent: cannot read it: no such file".into()
            ))
        );
        // An answer nobody asked for changes nothing.
        flow.backup_written(Ok(()), &mut sv, &m);
        assert_eq!(said_tone(&sv), Tone::Bad);
    }

    fn said_tone(sv: &SetupView) -> Tone {
        sv.message.as_ref().map_or(Tone::Info, |m| m.0)
    }
}

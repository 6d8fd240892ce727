//! What the page tells the logbook on its own: the unit connected (VERSION and its
//! circuits' names, so records go under it), and each fault the unit shows. The
//! commands are the stop gate's ([`super::StopGate`]), a check's record the check's
//! (`super::check`).

use std::time::SystemTime;

use super::page::App;
use crate::logbook::record::Unit;
use crate::logbook::{Entry, What};
use crate::model::Model;
use crate::protocol::device::DEVICE_COUNT;

/// The unit as it has told who it is, once it has told all of it: VERSION and every
/// circuit's name.
pub fn unit_of(model: &Model) -> Option<Unit> {
    let v = model.version.as_ref()?.value;
    let mut names = Vec::with_capacity(DEVICE_COUNT);
    for n in &model.names {
        names.push(n.as_ref()?.value.text());
    }
    Some(Unit::of(&v, names))
}

/// What the logbook was last told, so it is told only of a change.
#[derive(Debug, Default)]
pub(super) struct Told {
    revision: u64,
    unit: Option<Unit>,
    /// Setup writes sent, waiting to settle.
    setup: Vec<SetupWrite>,
}

impl App {
    /// After the model changed: a new unit (or one renamed) and new faults go to the
    /// logbook. Costs nothing while the model is unchanged.
    pub(super) fn tell_logbook(&mut self, model: &mut Model) {
        let faults = std::mem::take(&mut model.faults_seen);
        let Some(book) = &self.logbook else {
            return;
        };
        let at = SystemTime::now();
        for (device, name, fault) in faults {
            book.record(Entry {
                at,
                origin: "unit",
                summary: format!("fault: {name}: {fault}"),
                what: What::Fault {
                    device,
                    name,
                    fault,
                },
            });
        }
        // The writer finds the unit's earlier aircraft when it first writes under
        // this one: the title and the event log say so once.
        if let Some(was) = book.was_in()
            && let Some(a) = model.aircraft.as_mut()
            && a.was_in.as_ref() != Some(&was)
        {
            a.was_in = Some(was.clone());
            model.log(
                std::time::Instant::now(),
                crate::model::LogLevel::Warning,
                format!(
                    "logbook: this unit was in {} until {}; it is now recorded in {}",
                    was.0,
                    was.1,
                    book.aircraft().unwrap_or("this aircraft")
                ),
            );
        }
        if model.revision() == self.told.revision {
            return;
        }
        self.told.revision = model.revision();
        if let Some(unit) = unit_of(model)
            && self.told.unit.as_ref() != Some(&unit)
        {
            book.unit(unit.clone());
            self.told.unit = Some(unit);
        }
    }
}

/// A setup write sent and not yet settled: its line's words, and the values.
#[derive(Debug, Clone)]
pub(super) struct SetupWrite {
    what: String,
    old: Option<String>,
    new: String,
}

impl App {
    /// A setup write going out: what the unit held before, for its record.
    pub(super) fn note_setup_sent(&mut self, model: &Model, m: &crate::protocol::message::Message) {
        if self.logbook.is_none() {
            return;
        }
        let what = crate::link::request::setting_name(m);
        // A resend of the same write keeps the first "before".
        if self.told.setup.iter().any(|w| w.what == what) {
            return;
        }
        self.told.setup.push(SetupWrite {
            what,
            old: crate::setup::write::held_now(model, m),
            new: crate::setup::write::describe(m),
        });
    }

    /// Each setup write whose line has settled (saved, read back, refused) into the
    /// logbook, with whether the unit confirmed it.
    pub(super) fn note_setup_settled(&mut self) {
        use crate::setup::view::WriteStatus;
        if self.told.setup.is_empty() {
            return;
        }
        let Some(book) = &self.logbook else {
            return;
        };
        for line in &self.view.setup.writes {
            let confirmed = match &line.status {
                WriteStatus::Saved { matches, .. } | WriteStatus::ReadBack { matches, .. } => {
                    *matches
                }
                WriteStatus::Refused { .. } => false,
                _ => continue,
            };
            let Some(i) = self.told.setup.iter().position(|w| w.what == line.what) else {
                continue;
            };
            let w = self.told.setup.remove(i);
            let how = match &line.status {
                WriteStatus::Refused { why, .. } => format!("refused: {why}"),
                WriteStatus::Saved { holds, .. } | WriteStatus::ReadBack { holds, .. }
                    if !confirmed =>
                {
                    format!("not confirmed: the unit holds {holds}")
                }
                _ => "confirmed by the unit".into(),
            };
            book.record(Entry {
                at: SystemTime::now(),
                origin: crate::audit::Origin::Setup.word(),
                summary: format!(
                    "setting {}: {} → {} ({how})",
                    w.what,
                    w.old.as_deref().unwrap_or("not known"),
                    w.new
                ),
                what: What::Setting(crate::logbook::record::SettingChange {
                    setting: w.what,
                    old: w.old,
                    new: w.new,
                    confirmed,
                }),
            });
        }
    }
}

//! What a call into the flow takes from the person, and what it gives back for the
//! app to carry out.

use crate::protocol::message::Packet;

/// What the person does. The app maps keys to these, `vpx-efis check` typed answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// Confirm (before power), or go on after a timed-out item.
    Enter,
    Up,
    Down,
    /// Before power: exclude the selected circuit, or take back a suggested exclusion.
    Toggle,
    /// Skip the item under test.
    SkipItem,
    /// Skip the rest of the step.
    SkipStep,
    /// Try a timed-out or stopped item again.
    Retry,
    /// Stop the check: put back what it changed, and say what is left.
    Stop,
    /// The answer to "Is it lit?" for the light under test: what the person saw.
    Lit(bool),
    /// Nobody can answer any more (a headless check's standard input ended): no
    /// light is held on for an answer that cannot come.
    NobodyToAnswer,
}

/// What the caller must do after the flow moved.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct CheckEffects {
    /// To queue on the link, in this order, before letting go of the controller.
    pub packets: Vec<Packet>,
    /// Each result as it came, in words, for a headless run to print.
    pub progress: Vec<String>,
    /// The check ended in this call, finished or interrupted, at whatever stage: the
    /// app writes its report now (marked INCOMPLETE when interrupted). Set once per
    /// check, by `CheckFlow::finish`, the one way every end goes.
    pub ended: bool,
    /// The check reached its load analysis: the app opens the load file (reads it, or
    /// writes its template when there is none) and hands the result back with
    /// `CheckFlow::loads_opened`, in the same turn; the flow touches no file.
    pub open_loads: Option<LoadsToOpen>,
}

impl CheckEffects {
    /// Adds what a later call in the same turn gave back, after this call's own.
    pub fn absorb(&mut self, later: CheckEffects) {
        self.packets.extend(later.packets);
        self.progress.extend(later.progress);
        self.ended |= later.ended;
        if later.open_loads.is_some() {
            self.open_loads = later.open_loads;
        }
    }
}

/// The load file the load analysis needs, and the circuits its template lists.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadsToOpen {
    pub path: std::path::PathBuf,
    pub circuits: Vec<crate::model::Circuit>,
}

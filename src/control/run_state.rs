//! The controller's state as the rest of the program reads it: the motor run on the
//! wire, how a release is known, the repeat timing in force. These are control's own
//! types; the screen draws them, and nothing keeps a copy of them.

use std::time::Duration;

use crate::model::Motor;

/// How the page knows a motor key was let go (shown on screen).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReleaseMode {
    /// The terminal reports key release (keyboard enhancement).
    KeyRelease,
    /// The terminal only repeats presses; a run ends when repeats stop.
    #[default]
    AutoRepeat,
}

/// How the page judges a held motor key in auto-repeat mode, for the screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RepeatTiming {
    /// How long after a fresh press the first repeat may take (a tap runs this long
    /// at most).
    pub first_window: Duration,
    /// Measured from this terminal's own repeats, once a hold has shown them.
    pub delay: Option<Duration>,
    pub interval: Option<Duration>,
    /// How long after the last repeat a run ends.
    pub end_gap: Duration,
    /// `first_window` was set by hand (`--repeat-delay`).
    pub set_by_hand: bool,
}

/// What the screens draw of the controller, read from it for each frame: the run on
/// the wire, how a release is known, and the repeat timing in force (`None` where no
/// streamer feeds the page, as in a replay).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ControlState {
    pub run: Option<MotorRun>,
    pub release_mode: ReleaseMode,
    pub repeat: Option<RepeatTiming>,
}

/// The motor stream the page is sending right now, for display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MotorRun {
    pub motor: Motor,
    /// "up", "down", "left", "right".
    pub direction: &'static str,
}

//! What the person is looking at: selection, sort order, overlays. Owned by the app,
//! changed by the app in answer to control's actions, read by the widgets.

use crate::control::KeyContext;
use crate::model::Circuit;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SortOrder {
    /// By pin (device id), flaps and trims grouped apart.
    #[default]
    Pin,
    /// By displayed name, flaps and trims grouped apart.
    Alphabetical,
}

/// Which screen of the page is showing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Screen {
    /// The Appendix A device list, system panel and motors.
    #[default]
    Devices,
    /// Frames in both directions with their bytes (`t`).
    Traffic,
    /// Configuration of the unit (`c`).
    Setup,
    /// The installation check (`i`), drawn by `ui::check` from the app's `CheckView`.
    Check,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Overlay {
    #[default]
    None,
    Help,
    /// The walk-around remote: its QR code, its URL and the words to type.
    Remote,
}

/// The walk-around remote while it is on, for the overlay and the title.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RemoteView {
    /// `http://ADDR:PORT/#k=KEY`: the QR code's URL, the key in its fragment.
    pub url: String,
    /// `http://ADDR:PORT/`: what a phone without a camera opens.
    pub address: String,
    /// The words it types then.
    pub words: String,
    /// Phones paired now.
    pub paired: usize,
    /// Of them, paired by typed words (weaker than the QR code's key).
    pub typed: usize,
    /// No LAN address was found: only this laptop can reach it.
    pub loopback_only: bool,
    /// The URL's QR code in half blocks, with a quiet zone of 4 modules and of 2
    /// (for a short terminal): made once per code, not at every frame
    /// (`ui::remote::qr_rows`).
    pub qr: [Vec<String>; 2],
}

/// The controller's own types (they live in `control::run_state`): the screens draw
/// a [`ControlState`] read from the controller for each frame; the view copies none.
pub use crate::control::run_state::{ControlState, MotorRun, ReleaseMode, RepeatTiming};

#[derive(Debug, Clone, PartialEq, Default)]
pub struct ViewState {
    pub screen: Screen,
    /// Device id of the selected row, so the selection survives re-sorting.
    pub selected: Option<u8>,
    pub sort: SortOrder,
    pub overlay: Overlay,
    /// A short message for the person (a refused key, a sent command).
    pub notice: Option<String>,
    /// The setup screens (`c`): page, field, forms and where each write stands.
    pub setup: crate::setup::view::SetupView,
    /// The palette the page paints in, and why (the help overlay says it).
    pub theme: super::palette::ThemeChoice,
    /// The walk-around remote, while it is on.
    pub remote: Option<RemoteView>,
    /// The load file's circuits, for their wires: the device list marks a breaker
    /// over its wire, the detail pane gives the wire's verdict.
    pub wires: Vec<crate::loads::LoadCircuit>,
    /// The aircraft's last check, from the logbook: the detail pane gives the
    /// selected circuit's current then.
    pub last_check: Option<crate::check::trend::LastCheck>,
}

impl ViewState {
    /// What the keymap needs of this view: the selected row among `circuits` (the
    /// rows on screen) and whether an overlay covers them.
    pub fn key_context(&self, circuits: &[Circuit]) -> KeyContext {
        KeyContext::for_selection(self.selected, self.overlay != Overlay::None, circuits)
    }
}

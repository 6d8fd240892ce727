//! The key context the page gives the controller with one circuit selected, for the
//! tests that drive `Controller::handle_key` without a page. Included by `#[path]`.

use vpx_efis::control::{KeyContext, Selected};
use vpx_efis::model::{CircuitKind, CircuitState};

/// Circuit `id`, of `kind` and in `state`, selected on the device list, no overlay
/// open and no setup past the endpoints.
pub fn selected(id: u8, kind: CircuitKind, state: CircuitState) -> KeyContext {
    KeyContext {
        selected: Some(Selected { id, kind, state }),
        overlay_open: false,
        past_endpoints: false,
    }
}

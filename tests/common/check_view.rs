//! Parts of the installation check's view that the screen and report tests build by
//! hand.

use vpx_efis::check::state::{Excluded, MotorFinding, MotorResult, Outcome};
use vpx_efis::model::Motor;
use vpx_efis::protocol::message::SwitchId;

/// A circuit as the check lists it: id, name, pin, breaker in amps, switch.
pub type Circuit = (u8, &'static str, &'static str, u8, SwitchId);

/// `c` left alone by the check for `why`; the person may take it back into the check
/// only if `may_include` (a suggestion, not a rule).
pub fn left_alone(c: Circuit, why: &str, may_include: bool) -> Excluded {
    let (id, name, pin, breaker, switch) = c;
    Excluded {
        id,
        name: name.into(),
        pin,
        breaker: Some(breaker),
        switch: Some(switch),
        why: why.into(),
        may_include,
    }
}

/// What the check found of `motor`, run through `positions` (counts).
pub fn motor_result(motor: Motor, positions: &[u8], outcome: Outcome<MotorFinding>) -> MotorResult {
    MotorResult {
        motor,
        positions: positions.to_vec(),
        outcome,
    }
}

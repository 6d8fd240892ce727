//! Parts of the installation check's view that the screen and report tests build by
//! hand.

use vpx_efis::check::state::{Excluded, MotorFinding, MotorResult, Outcome};
use vpx_efis::model::Motor;
use vpx_efis::protocol::message::SwitchId;

/// A circuit as the check lists it: id, name, pin, breaker in amps, switch.
pub type Circuit = (u8, &'static str, &'static str, u8, SwitchId);

/// The starter, pin `id`, on a 5 A breaker and always on: left alone by every check.
pub fn the_starter(id: u8) -> Excluded {
    never_touched(
        (id, "Starter", "Starter", 5, SwitchId::AlwaysOn),
        "the starter",
    )
}

/// `c` left alone by the check's rule, being `what`.
pub fn never_touched(c: Circuit, what: &str) -> Excluded {
    left_alone(c, format!("never touched: {what}"), false)
}

/// `c` left out on the check's suggestion, for `why`: the person may take it back.
pub fn suggested(c: Circuit, why: &str) -> Excluded {
    left_alone(c, format!("suggested: {why}"), true)
}

fn left_alone(c: Circuit, why: String, may_include: bool) -> Excluded {
    let (id, name, pin, breaker, switch) = c;
    Excluded {
        id,
        name: name.into(),
        pin,
        breaker: Some(breaker),
        switch: Some(switch),
        why,
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

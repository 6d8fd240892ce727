//! A peer's ECBSTAT request as the draft's BUS value carries it, for the tests that
//! ask the gateway to switch a circuit. Included by `#[path]`.

use vpx_efis::xfsp::{Bus, Confidence, EcbState, Parameter, Value, idents};

/// ECBSTAT for circuit `unit` in `state`, at `conf` (USERSEL or SYSSEL make it a
/// request; any other confidence is a report).
pub fn ecb_request(unit: u16, state: EcbState, conf: Confidence) -> Parameter {
    Parameter::new(
        idents::ECBSTAT,
        Value::Bus(Bus {
            state,
            ..Bus::default()
        }),
    )
    .unit(unit)
    .confidence(conf)
}

//! What a person should do about each fault code of ICD Appendix E (Table 43). The ICD
//! says what the unit does and how the fault clears ([`crate::protocol::fault`]); these
//! are our words for the mechanic, following the practice of FAA AC 43.13-1B for a
//! tripped breaker: reset once, then find the cause. The guide's fault code page is
//! generated from them (`cargo run -- reference`).

use crate::protocol::fault::FaultCode;

/// What to do about a fault, in words; `None` for 0x00 NO FAULT.
pub fn what_to_do(code: FaultCode) -> Option<&'static str> {
    Some(match code {
        FaultCode::NoFault => return None,
        FaultCode::OverVoltage => {
            "The bus voltage went above the unit's overvoltage limit. Check the voltage \
             regulator and the alternator, and that the system voltage (System setup page: \
             16 V or 32 V) fits the aircraft. Reset (r) once, with the engine stopped, only \
             after the cause is found."
        }
        FaultCode::ShortCircuit => {
            "A short to ground on this circuit. Do not reset it to see: find the short \
             first. Look for a chafed wire against structure, a pinched or wet connector, a \
             failed load; disconnect the load and measure its wire to ground. Then reset \
             (r) once."
        }
        FaultCode::OverCurrent => {
            "The circuit drew more than its breaker setting. Compare the load's rated \
             current with the breaker in the CB column (Device setup page), then look for a \
             failing load: a motor that binds, a lamp or a heater drawing too much. Reset \
             (r) once; if it trips again, find the cause before another reset."
        }
        FaultCode::CurrentFault => {
            "The unit's current check on this circuit failed. Check the wiring and the \
             load as for an over-current. Current-fault checking can be switched off for \
             one circuit on the Device setup page (the page asks before it turns a \
             protection off): do it only for a load known to need it."
        }
        FaultCode::FlapRunaway => {
            "The flaps ran without a command. Check the flap switch for a contact stuck \
             closed, its wires to the unit, and the flap position sensor. Reset (r) on the \
             flaps row only once the cause is found, watching the flaps."
        }
        FaultCode::FlapActive => {
            "A flap switch was held while the fault was being reset. Put the flap switch \
             in its centre (off) position, then reset (r) again."
        }
        FaultCode::FlapDisabled => {
            "Both flap switch inputs were on when the unit started: a switch wired wrong, \
             shorted, or its two wires crossed. Fix the switch, then switch the unit off and \
             on again; a reset does not clear this one."
        }
        FaultCode::TrimRunaway => {
            "A trim ran without a command. Check the trim switch for a contact stuck \
             closed, its wires to the unit, and the trim's position sensor. Reset (r) on the \
             trim's row only once the cause is found, watching the trim tab."
        }
        FaultCode::TrimDisabled => {
            "Both switch inputs of a trim were on when the unit started: a switch wired \
             wrong, shorted, or its two wires crossed. Fix the switch, then switch the unit \
             off and on again; a reset does not clear this one."
        }
        FaultCode::TrimActive => {
            "A trim switch was held while the fault was being reset. Let go of the trim \
             switch, then reset (r) again."
        }
        FaultCode::Unknown(_) => {
            "A code the ICD does not list (or lists as RESERVED): note the code, the \
             circuit and what it feeds, and ask Vertical Power. Treat it as a breaker that \
             tripped: find the cause before resetting it."
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::fault::FAULT_TABLE;

    #[test]
    fn every_fault_of_table_43_has_words_and_no_fault_has_none() {
        for row in FAULT_TABLE {
            let code = FaultCode::from_byte(row.code);
            match what_to_do(code) {
                None => assert_eq!(row.code, 0x00, "{} has no advice", row.name),
                Some(words) => {
                    assert_ne!(row.code, 0x00);
                    assert!(words.len() > 40, "{}: {words}", row.name);
                }
            }
        }
        // Resets that cannot clear a fault say so, rather than suggesting `r`.
        for code in [FaultCode::FlapDisabled, FaultCode::TrimDisabled] {
            assert!(what_to_do(code).unwrap().contains("a reset does not clear"));
        }
    }
}

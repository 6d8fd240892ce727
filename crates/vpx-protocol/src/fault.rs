//! System fault codes, ICD Appendix E (Table 43).

use alloc::{
    format,
    string::{String, ToString},
};

/// A device or motor fault code (ICD Table 43). Reserved and unlisted codes are kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum FaultCode {
    /// 0x00 NO FAULT (ICD Table 43).
    NoFault,
    /// 0x06 OVER_VOLTAGE: device over voltage (ICD Table 43).
    OverVoltage,
    /// 0x07 SHORT_CIRCUIT: device short circuit (ICD Table 43).
    ShortCircuit,
    /// 0x08 OVER_CURRENT: device over-current (ICD Table 43).
    OverCurrent,
    /// 0x09 CURRENT_FAULT: device current fault (ICD Table 43).
    CurrentFault,
    /// 0x0A FLAP_RUNAWAY: runaway condition on the flaps (ICD Table 43).
    FlapRunaway,
    /// 0x0B FLAP_ACTIVE: the fault could not be cleared because a flap switch is active
    /// (ICD Table 43).
    FlapActive,
    /// 0x0C FLAP_DISABLED: both flap switches active at system start (ICD Table 43).
    FlapDisabled,
    /// 0x0E TRIM_RUNAWAY: runaway condition on the pitch or roll trim (ICD Table 43).
    TrimRunaway,
    /// 0x0F TRIM_DISABLED: both switches of a trim active at system start (ICD Table 43).
    TrimDisabled,
    /// 0x10 TRIM_ACTIVE: the fault could not be cleared because a trim switch is active
    /// (ICD Table 43).
    TrimActive,
    /// 0x01–0x05 and 0x0D are RESERVED in Table 43; anything else is not listed at all.
    Unknown(u8),
}

/// One row of ICD Table 43.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FaultInfo {
    /// Table 43 "Fault Code".
    pub code: u8,
    /// Table 43 "Name", e.g. `SHORT_CIRCUIT`.
    pub name: &'static str,
    /// Table 43 "Description".
    pub description: &'static str,
    /// Table 43 "Action": what the VP-X does.
    pub action: &'static str,
    /// Table 43 "Clears": how the fault ends.
    pub clears: &'static str,
}

const PIN_ACTION: &str = "Device faulted and disabled, FAULT_STATUS message broadcast.";
const PIN_CLEARS: &str = "The faulted pin remains off until cleared by the external system.";

/// ICD Table 43, in order. Reserved rows are included so a code's row is never missing.
pub const FAULT_TABLE: [FaultInfo; 17] = [
    FaultInfo {
        code: 0x00,
        name: "NO FAULT",
        description: "No device fault.",
        action: "N/A",
        clears: "N/A",
    },
    FaultInfo {
        code: 0x01,
        name: "RESERVED",
        description: "",
        action: "",
        clears: "",
    },
    FaultInfo {
        code: 0x02,
        name: "RESERVED",
        description: "",
        action: "",
        clears: "",
    },
    FaultInfo {
        code: 0x03,
        name: "RESERVED",
        description: "",
        action: "",
        clears: "",
    },
    FaultInfo {
        code: 0x04,
        name: "RESERVED",
        description: "",
        action: "",
        clears: "",
    },
    FaultInfo {
        code: 0x05,
        name: "RESERVED",
        description: "",
        action: "",
        clears: "",
    },
    FaultInfo {
        code: 0x06,
        name: "OVER_VOLTAGE",
        description: "Device over voltage.",
        action: PIN_ACTION,
        clears: PIN_CLEARS,
    },
    FaultInfo {
        code: 0x07,
        name: "SHORT_CIRCUIT",
        description: "Device short circuit.",
        action: PIN_ACTION,
        clears: PIN_CLEARS,
    },
    FaultInfo {
        code: 0x08,
        name: "OVER_CURRENT",
        description: "Device over-current.",
        action: PIN_ACTION,
        clears: PIN_CLEARS,
    },
    FaultInfo {
        code: 0x09,
        name: "CURRENT_FAULT",
        description: "Device current fault.",
        action: PIN_ACTION,
        clears: PIN_CLEARS,
    },
    FaultInfo {
        code: 0x0A,
        name: "FLAP_RUNAWAY",
        description: "Runaway condition on the flaps.",
        action: "Flaps faulted and disabled, FAULT_STATUS message broadcast.",
        clears: "The flaps remain off until cleared by the external system.",
    },
    FaultInfo {
        code: 0x0B,
        name: "FLAP_ACTIVE",
        description: "Flaps active when clearing fault. Indicates fault could not be cleared because flap switch is active.",
        action: "Flaps faulted and disabled, FAULT_STATUS message broadcast.",
        clears: "The flaps remain off until cleared by the external system.",
    },
    FaultInfo {
        code: 0x0C,
        name: "FLAP_DISABLED",
        description: "Flaps disabled. Occurs when both flap switches simultaneously active on system start.",
        action: "Flap input switches are disabled.",
        clears: "When system is power cycled and condition no longer exists.",
    },
    FaultInfo {
        code: 0x0D,
        name: "RESERVED",
        description: "",
        action: "",
        clears: "",
    },
    FaultInfo {
        code: 0x0E,
        name: "TRIM_RUNAWAY",
        description: "Runaway condition on the pitch or roll trim circuit.",
        action: "Pitch or roll trim faulted and disabled, FAULT_STATUS message broadcast.",
        clears: "The faulted trim remains off until cleared by the external system.",
    },
    FaultInfo {
        code: 0x0F,
        name: "TRIM_DISABLED",
        description: "Trim disabled. Occurs when both pitch trim switches or both roll trim switches are simultaneous active on system start.",
        action: "Trim input switches are disabled.",
        clears: "When system is power cycled and condition no longer exists.",
    },
    FaultInfo {
        code: 0x10,
        name: "TRIM_ACTIVE",
        description: "Trim active when clearing fault. Indicates fault could not be cleared because trim switch(es) is active.",
        action: "Trim faulted and disabled, FAULT_STATUS message broadcast.",
        clears: "The trim remain off until cleared by the external system.",
    },
];

impl FaultCode {
    /// The code of a Table 43 byte; unlisted bytes are kept in [`FaultCode::Unknown`].
    pub fn from_byte(b: u8) -> Self {
        match b {
            0x00 => FaultCode::NoFault,
            0x06 => FaultCode::OverVoltage,
            0x07 => FaultCode::ShortCircuit,
            0x08 => FaultCode::OverCurrent,
            0x09 => FaultCode::CurrentFault,
            0x0A => FaultCode::FlapRunaway,
            0x0B => FaultCode::FlapActive,
            0x0C => FaultCode::FlapDisabled,
            0x0E => FaultCode::TrimRunaway,
            0x0F => FaultCode::TrimDisabled,
            0x10 => FaultCode::TrimActive,
            n => FaultCode::Unknown(n),
        }
    }

    /// The Table 43 byte.
    pub fn to_byte(self) -> u8 {
        match self {
            FaultCode::NoFault => 0x00,
            FaultCode::OverVoltage => 0x06,
            FaultCode::ShortCircuit => 0x07,
            FaultCode::OverCurrent => 0x08,
            FaultCode::CurrentFault => 0x09,
            FaultCode::FlapRunaway => 0x0A,
            FaultCode::FlapActive => 0x0B,
            FaultCode::FlapDisabled => 0x0C,
            FaultCode::TrimRunaway => 0x0E,
            FaultCode::TrimDisabled => 0x0F,
            FaultCode::TrimActive => 0x10,
            FaultCode::Unknown(n) => n,
        }
    }

    /// Whether this is a fault, i.e. not 0x00 NO FAULT (ICD Table 43).
    pub fn is_fault(self) -> bool {
        self != FaultCode::NoFault
    }

    /// The Table 43 row, or `None` for a code the ICD does not list.
    pub fn info(self) -> Option<&'static FaultInfo> {
        FAULT_TABLE.get(self.to_byte() as usize)
    }

    /// The Table 43 name (e.g. `SHORT_CIRCUIT`), or a name that shows the raw code.
    pub fn name(self) -> String {
        match self.info() {
            Some(i) => i.name.to_string(),
            None => format!("FAULT {:#04x}", self.to_byte()),
        }
    }
}

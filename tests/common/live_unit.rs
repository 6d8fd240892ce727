//! The unit's side for the tests that run motors on a fake clock: the broadcasts that
//! keep the model live (nothing on, nothing faulted, 13.8 V), and the flaps and both
//! trims standing mid-travel.

use std::time::Instant;

use vpx_efis::model::Model;
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::protocol::message::{
    DeviceStatus, FlapFlags, FlapTrimStatus, Packet, SignedTenths, SystemStatus, Tenths, TrimFlags,
};

pub fn system_status() -> Packet {
    Packet::from_vpx(
        0,
        SystemStatus {
            system_current: Tenths(100),
            main_bus_volts: SignedTenths(138),
            internal_temp: 30,
            ..Default::default()
        },
    )
}

pub fn device_status() -> Packet {
    Packet::from_vpx(0, DeviceStatus::default())
}

/// Flaps and both trims fitted, travelling 0 to 100, the flaps and roll trim at 50
/// and the pitch trim at `pitch_position`, `pitch_fault` its fault code: mid-travel,
/// so no endpoint is in play (a run near the endpoint behind it starts as probes,
/// `control::endpoints::probe`, which a position that never moves cannot end).
pub fn mid_travel(pitch_fault: FaultCode, pitch_position: u8) -> FlapTrimStatus {
    let trim = TrimFlags {
        enabled: true,
        motor_running: false,
        fault: pitch_fault.is_fault(),
    };
    FlapTrimStatus {
        flap: FlapFlags {
            enabled: true,
            ..Default::default()
        },
        pitch_trim: trim,
        roll_trim: TrimFlags {
            fault: false,
            ..trim
        },
        flap_position: 50,
        pitch_trim_position: pitch_position,
        roll_trim_position: 50,
        pitch_trim_fault: pitch_fault,
        flap_down: 100,
        flap_midpoint_1: 30,
        flap_midpoint_2: 60,
        pitch_trim_down: 100,
        pitch_trim_neutral: 50,
        roll_trim_down: 100,
        roll_trim_neutral: 50,
        ..Default::default()
    }
}

/// The flaps alone fitted (no trim), still at `position`, their up endpoint 40 and
/// down 200.
pub fn flaps_at(position: u8) -> FlapTrimStatus {
    FlapTrimStatus {
        flap: FlapFlags {
            enabled: true,
            ..Default::default()
        },
        flap_position: position,
        flap_up: 40,
        flap_down: 200,
        ..Default::default()
    }
}

/// What the virtual unit is doing, so a loop can feed the model as the link's reader
/// does.
#[derive(Clone, Copy, PartialEq)]
pub enum Unit {
    Healthy,
    /// SYSTEM_STATUS and DEVICE_STATUS stop (COMMUNICATION LOST after 2.5 s);
    /// FLAP_TRIM_STATUS keeps coming.
    StatusSilent,
    /// The pitch trim reports TRIM_RUNAWAY.
    PitchFault,
}

/// One round of `unit`'s broadcasts at `now`, the pitch trim at `pitch_position`.
pub fn feed(model: &mut Model, unit: Unit, pitch_position: u8, now: Instant) {
    if unit != Unit::StatusSilent {
        model.apply_packet(now, &system_status());
        model.apply_packet(now, &device_status());
    }
    let fault = match unit {
        Unit::PitchFault => FaultCode::TrimRunaway,
        _ => FaultCode::NoFault,
    };
    model.apply_packet(now, &Packet::from_vpx(0, mid_travel(fault, pitch_position)));
}

//! The configured unit the screen snapshots start from: a VP-X Pro that answered every
//! connect-time question at `t0` (version, system spec, every pin's enable flag, the
//! wired pins' names and specs, the flaps' and both trims' specs), fed to a `Model`
//! as the link's reader feeds it.

use std::time::{Duration, Instant};

use vpx_efis::model::{Model, Source};
use vpx_efis::protocol::message::{
    DeviceEnable, DeviceName, DeviceSpec, EnableFlag, FaultStatus, FlapFlags, FlapMode, FlapSpec,
    FlapTrimStatus, HardwareVersion, Message, Polarity, SwitchId, SystemSpec, Tenths, TrimFlags,
    TrimSpec, TrimType, Version,
};
use vpx_efis::protocol::{FaultCode, Packet, defaults};

/// A wired pin: id, name ("" for none), breaker in amps, switch.
pub type Wired = (u8, &'static str, u8, SwitchId);

/// VERSION: a VP-X Pro running 1.4.
pub fn version() -> Version {
    Version {
        hardware_version: HardwareVersion::VpxPro,
        software_major: 1,
        software_minor: 4,
    }
}

/// SYSTEM_SPEC as the factory left it: overvoltage at 16 V, no secondary alternator.
pub fn system_spec() -> SystemSpec {
    defaults::system_spec()
}

/// FLAP_SPEC: position-based flaps from 20 (up) to 220 (down), midpoints 90 and 160,
/// standard polarity on a 7 A breaker.
pub fn flap_spec() -> FlapSpec {
    FlapSpec {
        mode: FlapMode::PositionBased,
        enabled: true,
        up: 20,
        down: 220,
        midpoint_1: 90,
        midpoint_2: 160,
        overspeed_position: 90,
        max_speed: 100,
        endpoint_duration: Tenths(5),
        ..defaults::flap_spec()
    }
}

/// Both TRIM_SPECs: pitch 30 up, 230 down, neutral 128; roll 40, 200, 120.
pub fn trim_specs() -> [TrimSpec; 2] {
    [
        (TrimType::Pitch, 30, 230, 128),
        (TrimType::Roll, 40, 200, 120),
    ]
    .map(|(trim_type, up, down, neutral)| TrimSpec {
        trim_type,
        enabled: true,
        polarity: Polarity::Standard,
        up,
        down,
        neutral,
        power: 60,
        speed: 120,
    })
}

/// FLAP_TRIM_STATUS of that unit: the flaps and both trims enabled and still, their
/// endpoints as [`flap_spec`] and [`trim_specs`] give them, at `positions` (flaps,
/// pitch, roll).
pub fn flap_trim(positions: (u8, u8, u8)) -> FlapTrimStatus {
    let on = TrimFlags {
        enabled: true,
        ..Default::default()
    };
    FlapTrimStatus {
        flap: FlapFlags {
            enabled: true,
            ..Default::default()
        },
        pitch_trim: on,
        roll_trim: on,
        flap_position: positions.0,
        pitch_trim_position: positions.1,
        roll_trim_position: positions.2,
        flap_up: 20,
        flap_down: 220,
        flap_midpoint_1: 90,
        flap_midpoint_2: 160,
        pitch_trim_up: 30,
        pitch_trim_down: 230,
        pitch_trim_neutral: 128,
        roll_trim_up: 40,
        roll_trim_down: 200,
        roll_trim_neutral: 120,
        ..Default::default()
    }
}

/// FAULT_STATUS with `devices` faulted, each with its code, and the system fault flag
/// `system`.
pub fn faults(devices: &[(u8, FaultCode)], system: bool) -> FaultStatus {
    FaultStatus {
        system_fault: system,
        ..FaultStatus::with_faults(devices)
    }
}

/// Every connect-time answer of a unit wired as `wired`, in the order they are fed:
/// pins 4–28 enabled only where wired, names only where given.
pub fn answers(wired: &[Wired]) -> Vec<Message> {
    let mut out: Vec<Message> = vec![version().into(), system_spec().into()];
    for id in 4..=28u8 {
        let flag = if wired.iter().any(|w| w.0 == id) {
            EnableFlag::Enabled
        } else {
            EnableFlag::Disabled
        };
        out.push(
            DeviceEnable {
                device_id: id,
                flag,
            }
            .into(),
        );
    }
    for &(id, name, breaker, switch_id) in wired {
        if !name.is_empty() {
            out.push(DeviceName::new(id, name).unwrap().into());
        }
        out.push(
            DeviceSpec {
                device_id: id,
                circuit_breaker: breaker,
                switch_id,
                current_fault: true,
                switch_raw: None,
            }
            .into(),
        );
    }
    out.push(flap_spec().into());
    out.extend(trim_specs().map(Message::from));
    out
}

/// A model fed as the link's reader feeds it, on a clock that starts at `t0`.
pub struct Unit {
    pub model: Model,
    pub t0: Instant,
    cnt: u8,
}

impl Unit {
    /// The unit on `source`, wired as `wired`, that answered every connect-time
    /// question at `t0`.
    pub fn answered(source: Source, wired: &[Wired]) -> Unit {
        let t0 = Instant::now();
        let mut u = Unit {
            model: Model::new(source),
            t0,
            cnt: 0,
        };
        u.model.note_connected(t0, "/dev/ttyUSB0".into());
        for m in answers(wired) {
            u.apply(0, m);
        }
        u
    }

    /// `ms` milliseconds after `t0`.
    pub fn at(&self, ms: u64) -> Instant {
        self.t0 + Duration::from_millis(ms)
    }

    /// `message` from the unit, heard `ms` milliseconds after `t0`.
    pub fn apply(&mut self, ms: u64, message: impl Into<Message>) {
        self.cnt = self.cnt.wrapping_add(1);
        let at = self.at(ms);
        self.model
            .apply_packet(at, &Packet::from_vpx(self.cnt, message));
    }
}

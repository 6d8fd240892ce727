//! Every message in words and as JSON, for `vpx-efis decode` and the traffic view.
//!
//! Field names follow the ICD tables (lower-cased); values carry their real units
//! ("main bus 13.8 V"), devices are shown by id and Table 40 name. Pure: no I/O.
//! Speeds are knots: the ICD leaves their unit to the EFIS (icd-reading R20), and
//! this one's is knots, as its setup screens and backups say.
//!
//! JSON numbers in real units are computed from the integer on the wire as `f64`
//! (`138 / 10.0`), never through `f32`, so `13.8` prints as `13.8`.

use alloc::{
    format,
    string::{String, ToString},
    vec::Vec,
};

use serde_json::{Value, json};

use super::device::{SYSTEM_FAULT_ID, SYSTEM_SPEC_ID, WIG_WAG_SPEC_ID, device};
use super::frame::Node;
use super::message::*;

/// A device id with its Table 40 name, e.g. `9 5A-6`; ids outside the table as `id 200`.
pub fn device_label(id: u8) -> String {
    match device(id) {
        Some(d) => format!("{id} {}", d.system_name),
        None => format!("id {id}"),
    }
}

/// A node address in words; unlisted addresses as hex.
pub fn node_label(n: Node) -> String {
    match n {
        Node::Other(b) => format!("{b:#04x}"),
        n => n.name().to_string(),
    }
}

fn tenths(v: u16) -> f64 {
    v as f64 / 10.0
}

fn on_off(b: bool) -> &'static str {
    if b { "on" } else { "off" }
}

fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// Names of the set flags, or `none`.
fn flags(set: &[(&'static str, bool)]) -> String {
    let on: Vec<&str> = set.iter().filter(|(_, b)| *b).map(|(n, _)| *n).collect();
    if on.is_empty() {
        "none".into()
    } else {
        on.join(", ")
    }
}

fn opt_device(id: Option<u8>) -> String {
    id.map_or_else(|| "disabled (255)".into(), device_label)
}

fn opt_device_json(id: Option<u8>) -> Value {
    id.map_or(Value::Null, device_json)
}

fn device_json(id: u8) -> Value {
    json!({ "id": id, "name": device(id).map(|d| d.system_name) })
}

/// DEVICE_SPEC_QUERY and SPEC_ACK use ids past the table for the other specs (Tables 18, 19).
fn spec_target(id: u8) -> String {
    match id {
        SYSTEM_SPEC_ID => format!("{id} (system spec)"),
        WIG_WAG_SPEC_ID => format!("{id} (wig-wag spec)"),
        _ => device_label(id),
    }
}

fn polarity(p: Polarity) -> &'static str {
    match p {
        Polarity::Standard => "standard",
        Polarity::Inverted => "inverted",
    }
}

fn trim_type(t: TrimType) -> String {
    match t {
        TrimType::Pitch => "pitch".into(),
        TrimType::Roll => "roll".into(),
        TrimType::Unknown(n) => format!("unknown ({n})"),
    }
}

fn wig_wag_mode(m: WigWagModeSetting) -> String {
    match m {
        WigWagModeSetting::Auto => "auto".into(),
        WigWagModeSetting::Steady => "steady".into(),
        WigWagModeSetting::Unknown(n) => format!("unknown ({n})"),
    }
}

fn overvoltage(o: OvervoltageLimit) -> String {
    match o {
        OvervoltageLimit::V16 => "16 V".into(),
        OvervoltageLimit::V32 => "32 V".into(),
        OvervoltageLimit::Unknown(n) => format!("unknown ({n})"),
    }
}

fn enable_flag(f: EnableFlag) -> String {
    match f {
        EnableFlag::Disabled => "0 (disabled)".into(),
        EnableFlag::Enabled => "1 (enabled)".into(),
        EnableFlag::Query => "2 (query)".into(),
        EnableFlag::Unknown(n) => format!("{n} (unknown)"),
    }
}

fn trim_direction(t: TrimType, d: TrimDirection) -> String {
    match (t, d) {
        (TrimType::Roll, TrimDirection::DownOrRight) => "right".into(),
        (TrimType::Roll, TrimDirection::UpOrLeft) => "left".into(),
        (_, TrimDirection::DownOrRight) => "down".into(),
        (_, TrimDirection::UpOrLeft) => "up".into(),
        (_, TrimDirection::Unknown(n)) => format!("unknown ({n})"),
    }
}

fn flap_direction(d: FlapDirection) -> String {
    match d {
        FlapDirection::Up => "up".into(),
        FlapDirection::Down => "down".into(),
        FlapDirection::Unknown(n) => format!("unknown ({n})"),
    }
}

fn fault_name(c: super::fault::FaultCode) -> String {
    format!("{:#04x} {}", c.to_byte(), c.name())
}

fn switches_on(s: &SwitchInputs) -> String {
    let mut on: Vec<String> = s
        .switch
        .iter()
        .enumerate()
        .filter(|(_, b)| **b)
        .map(|(i, _)| format!("switch {}", i + 1))
        .collect();
    for (name, b) in [
        ("roll trim down", s.roll_trim_down),
        ("roll trim up", s.roll_trim_up),
        ("pitch trim down", s.pitch_trim_down),
        ("pitch trim up", s.pitch_trim_up),
        ("flap down", s.flap_down),
        ("flap up", s.flap_up),
    ] {
        if b {
            on.push(name.into());
        }
    }
    if on.is_empty() {
        "none".into()
    } else {
        on.join(", ")
    }
}

/// The switch of a DEVICE_SPEC for JSON's `switch`, with the byte that was on the wire
/// where icd-reading R10 reads two bytes alike: "always on (255)" for 255, which the
/// page takes as 11. A mechanic can then see which of the two a real unit uses.
fn switch_label(m: &DeviceSpec) -> String {
    match m.switch_raw {
        Some(raw) if raw != m.switch_id.to_byte() => format!("{} ({raw})", m.switch_id.label()),
        _ => m.switch_id.label(),
    }
}

/// The switch of a DEVICE_SPEC said once, by the byte that was sent, then what it
/// means: "switch 3 (input 3)", "switch 11 (always on)". Where icd-reading R10 reads a
/// byte as another (255 is always on, as 11), the reading says so: "switch 255 (always
/// on; read as 11)".
fn switch_text(m: &DeviceSpec) -> String {
    let read = m.switch_id.to_byte();
    let sent = m.switch_raw.unwrap_or(read);
    let meaning = match m.switch_id {
        SwitchId::Off => "always off".to_string(),
        SwitchId::Input(n) => format!("input {n}"),
        SwitchId::AlwaysOn => "always on".to_string(),
        SwitchId::Unknown(_) => "not a switch id: 0-11".to_string(),
    };
    if sent == read {
        format!("switch {sent} ({meaning})")
    } else {
        format!("switch {sent} ({meaning}; read as {read})")
    }
}

/// One message in words: its fields with ICD names and real units.
pub fn describe(msg: &Message) -> String {
    match msg {
        Message::Ping(m) => format!(
            "ack flag {} ({})",
            m.ack as u8,
            if m.ack { "response" } else { "request" }
        ),
        Message::Version(m) => format!(
            "hardware version {} ({}), software {}.{}",
            m.hardware_version.to_byte(),
            m.hardware_version.name(),
            m.software_major,
            m.software_minor
        ),
        Message::SoftwareUpdate(_) | Message::DeviceStatusQuery(_) => "no payload".into(),
        Message::EepromErase(m) => format!(
            "response code {} ({})",
            m.response_code,
            if m.response_code == 0 {
                "success"
            } else {
                "failure"
            }
        ),
        Message::DeviceSpec(m) => format!(
            "device {}, circuit breaker {} A, {}, current fault {}",
            device_label(m.device_id),
            m.circuit_breaker,
            switch_text(m),
            if m.current_fault {
                "enabled"
            } else {
                "disabled"
            }
        ),
        Message::SystemSpec(m) => format!(
            "overvoltage limit {}, secondary alternator {}",
            overvoltage(m.overvoltage_limit),
            opt_device(m.secondary_alternator)
        ),
        Message::TrimSpec(m) => format!(
            "trim type {}, {}, polarity {}, up {}, down {}, neutral {}, power {} %, speed {} kt",
            trim_type(m.trim_type),
            if m.enabled { "enabled" } else { "disabled" },
            polarity(m.polarity),
            m.up,
            m.down,
            m.neutral,
            m.power,
            m.speed
        ),
        Message::FlapSpec(m) => format!(
            "mode {}, {}, polarity {}, up {}, down {}, midpoint 1 {}, midpoint 2 {}, \
             circuit breaker {} A, overspeed position {}, max speed {} kt, endpoint duration {:.1} s",
            match m.mode {
                FlapMode::Momentary => "momentary",
                FlapMode::PositionBased => "position-based",
            },
            if m.enabled { "enabled" } else { "disabled" },
            polarity(m.polarity),
            m.up,
            m.down,
            m.midpoint_1,
            m.midpoint_2,
            m.circuit_breaker,
            m.overspeed_position,
            m.max_speed,
            tenths(m.endpoint_duration.0)
        ),
        Message::WigWagSpec(m) => format!(
            "device one {}, device two {}, warm up period {} s, speed {} kt",
            opt_device(m.device_one),
            opt_device(m.device_two),
            m.warm_up_period,
            m.speed
        ),
        Message::DeviceSpecQuery(m) => format!("device {}", spec_target(m.device_id)),
        Message::SpecAck(m) => format!(
            "device {}, error code {}",
            spec_target(m.device_id),
            match m.error {
                None => "0 (none)".into(),
                Some(e) => format!("{:#04x} ({})", e.to_byte(), e.description()),
            }
        ),
        Message::DeviceName(m) => format!(
            "device {}, device name {:?}",
            device_label(m.device_id),
            m.text()
        ),
        Message::DeviceNameQuery(m) => format!("device {}", device_label(m.device_id)),
        Message::DeviceEnable(m) => format!(
            "device {}, enable flag {}",
            device_label(m.device_id),
            enable_flag(m.flag)
        ),
        Message::SystemStatus(m) => format!(
            "system current {:.1} A, main bus {:.1} V, aux battery {:.1} V, internal temp {} °C, \
             switches on: {}; misc: starter annunciator {}, wig-wag mode {}, software update {}, \
             wig-wag active {}; system faults: {}; data integrity code {}",
            tenths(m.system_current.0),
            m.main_bus_volts.0 as f64 / 10.0,
            tenths(m.aux_battery_volts.0),
            m.internal_temp,
            switches_on(&m.switches),
            yes_no(m.misc.starter_annunciator),
            wig_wag_mode(m.misc.wig_wag_mode),
            yes_no(m.misc.software_update),
            yes_no(m.misc.wig_wag_active),
            flags(&[
                ("current > 48 A", m.faults.current_over_48a),
                ("current > 60 A", m.faults.current_over_60a),
                ("CU warm reset", m.faults.warm_reset),
                ("data integrity failure", m.faults.data_integrity_failure),
                ("external data missing", m.faults.external_data_missing),
            ]),
            match m.data_integrity_code {
                None => "0 (none)".into(),
                Some(c) => format!("{:#04x} ({})", c.to_byte(), c.description()),
            }
        ),
        Message::DeviceStatus(m) => {
            let devices = || m.on.iter().zip(&m.current).enumerate();
            let on: Vec<String> = devices()
                .filter(|&(_, (&on, _))| on)
                .map(|(i, (_, c))| format!("{} {:.1} A", device_label(i as u8), tenths(c.0)))
                .collect();
            // An off device drawing current is worth seeing; off devices at zero are not.
            let off: Vec<String> = devices()
                .filter(|&(_, (&on, c))| !on && c.0 != 0)
                .map(|(i, (_, c))| format!("{} {:.1} A", device_label(i as u8), tenths(c.0)))
                .collect();
            let mut s = format!(
                "on: {}",
                if on.is_empty() {
                    "none".into()
                } else {
                    on.join(", ")
                }
            );
            if !off.is_empty() {
                s.push_str(&format!("; off but drawing: {}", off.join(", ")));
            }
            s
        }
        Message::FlapTrimStatus(m) => format!(
            "flap: position {} [{}], fault code {}, up {}, down {}, midpoint 1 {}, midpoint 2 {}; \
             pitch trim: position {} [{}], fault code {}, up {}, down {}, neutral {}; \
             roll trim: position {} [{}], fault code {}, up {}, down {}, neutral {}",
            m.flap_position,
            flags(&[
                ("enabled", m.flap.enabled),
                ("motor running", m.flap.motor_running),
                ("fault", m.flap.fault),
                ("overspeed alarm", m.flap.overspeed_alarm),
                ("down switch inhibited", m.flap.down_switch_inhibited),
            ]),
            fault_name(m.flap_fault),
            m.flap_up,
            m.flap_down,
            m.flap_midpoint_1,
            m.flap_midpoint_2,
            m.pitch_trim_position,
            trim_flags(&m.pitch_trim),
            fault_name(m.pitch_trim_fault),
            m.pitch_trim_up,
            m.pitch_trim_down,
            m.pitch_trim_neutral,
            m.roll_trim_position,
            trim_flags(&m.roll_trim),
            fault_name(m.roll_trim_fault),
            m.roll_trim_up,
            m.roll_trim_down,
            m.roll_trim_neutral,
        ),
        Message::FaultStatus(m) => {
            let devices = || m.faulted.iter().zip(&m.codes).enumerate();
            let faulted: Vec<String> = devices()
                .filter(|&(_, (&faulted, _))| faulted)
                .map(|(i, (_, code))| match code {
                    Some(c) => format!("{} {}", device_label(i as u8), fault_name(*c)),
                    None => format!("{} (no code sent)", device_label(i as u8)),
                })
                .collect();
            // A code without its fault bit is unusual enough to show.
            let stray: Vec<String> = devices()
                .filter_map(|(i, (&faulted, code))| match code {
                    Some(c) if !faulted && c.is_fault() => {
                        Some(format!("{} {}", device_label(i as u8), fault_name(*c)))
                    }
                    _ => None,
                })
                .collect();
            let carried = m.codes.iter().filter(|c| c.is_some()).count();
            let mut s = format!(
                "faulted: {}; system fault {}; {} codes carried",
                if faulted.is_empty() {
                    "none".into()
                } else {
                    faulted.join(", ")
                },
                yes_no(m.system_fault),
                carried
            );
            if !stray.is_empty() {
                s.push_str(&format!("; codes without fault bit: {}", stray.join(", ")));
            }
            s
        }
        Message::DevicePower(m) => format!(
            "device {}, power state {}",
            device_label(m.device_id),
            on_off(m.on)
        ),
        Message::TrimMove(m) => format!(
            "trim type {}, power state {}, direction {}",
            trim_type(m.trim_type),
            on_off(m.on),
            trim_direction(m.trim_type, m.direction)
        ),
        Message::FlapMove(m) => format!(
            "power state {}, direction {}",
            on_off(m.on),
            flap_direction(m.direction)
        ),
        Message::WigWagMode(m) => format!("wig-wag mode {}", wig_wag_mode(m.mode)),
        Message::DeviceClear(m) => {
            if m.device_id == SYSTEM_FAULT_ID {
                format!("device {} (system fault)", m.device_id)
            } else {
                format!("device {}", device_label(m.device_id))
            }
        }
        Message::ExternalData(m) => {
            let v = |b: bool| if b { "" } else { " (invalid)" };
            format!(
                "indicated airspeed {} kt{}, ground speed {} kt{}, baro altitude {} ft{}, \
                 fuel pressure {} psi{}, rpm {}{}",
                m.indicated_airspeed,
                v(m.valid.indicated_airspeed),
                m.ground_speed,
                v(m.valid.ground_speed),
                m.baro_altitude,
                v(m.valid.baro_altitude),
                m.fuel_pressure,
                v(m.valid.fuel_pressure),
                m.rpm,
                v(m.valid.rpm)
            )
        }
    }
}

fn trim_flags(t: &TrimFlags) -> String {
    flags(&[
        ("enabled", t.enabled),
        ("motor running", t.motor_running),
        ("fault", t.fault),
    ])
}

fn trim_flags_json(t: &TrimFlags) -> Value {
    json!({ "enabled": t.enabled, "motor_running": t.motor_running, "fault": t.fault })
}

fn fault_json(c: super::fault::FaultCode) -> Value {
    json!({ "code": c.to_byte(), "name": c.name() })
}

/// One message's fields as a JSON object: ICD field names in snake case, real units
/// named in the key (`_a`, `_v`, `_s`). The caller adds the message name and header.
pub fn to_json(msg: &Message) -> Value {
    match msg {
        Message::Ping(m) => json!({ "ack": m.ack }),
        Message::Version(m) => json!({
            "hardware_version": m.hardware_version.to_byte(),
            "hardware_name": m.hardware_version.name(),
            "software_major": m.software_major,
            "software_minor": m.software_minor,
        }),
        Message::SoftwareUpdate(_) | Message::DeviceStatusQuery(_) => json!({}),
        Message::EepromErase(m) => json!({ "response_code": m.response_code }),
        Message::DeviceSpec(m) => json!({
            "device": device_json(m.device_id),
            "circuit_breaker_a": m.circuit_breaker,
            "switch_id": m.switch_id.to_byte(),
            "switch_raw": m.switch_raw.unwrap_or(m.switch_id.to_byte()),
            "switch": switch_label(m),
            "current_fault": m.current_fault,
        }),
        Message::SystemSpec(m) => json!({
            "overvoltage_limit": m.overvoltage_limit.to_byte(),
            "overvoltage_limit_v": match m.overvoltage_limit {
                OvervoltageLimit::V16 => json!(16),
                OvervoltageLimit::V32 => json!(32),
                OvervoltageLimit::Unknown(_) => Value::Null,
            },
            "secondary_alternator": opt_device_json(m.secondary_alternator),
        }),
        Message::TrimSpec(m) => json!({
            "trim_type": trim_type(m.trim_type),
            "enabled": m.enabled,
            "polarity": polarity(m.polarity),
            "up": m.up,
            "down": m.down,
            "neutral": m.neutral,
            "power_percent": m.power,
            "speed": m.speed,
        }),
        Message::FlapSpec(m) => json!({
            "mode": match m.mode {
                FlapMode::Momentary => "momentary",
                FlapMode::PositionBased => "position-based",
            },
            "enabled": m.enabled,
            "polarity": polarity(m.polarity),
            "up": m.up,
            "down": m.down,
            "midpoint_1": m.midpoint_1,
            "midpoint_2": m.midpoint_2,
            "circuit_breaker_a": m.circuit_breaker,
            "overspeed_position": m.overspeed_position,
            "max_speed": m.max_speed,
            "endpoint_duration_s": tenths(m.endpoint_duration.0),
        }),
        Message::WigWagSpec(m) => json!({
            "device_one": opt_device_json(m.device_one),
            "device_two": opt_device_json(m.device_two),
            "warm_up_period_s": m.warm_up_period,
            "speed": m.speed,
        }),
        Message::DeviceSpecQuery(m) => json!({ "device_id": m.device_id }),
        Message::SpecAck(m) => json!({
            "device_id": m.device_id,
            "error_code": m.error.map_or(0, SpecAckError::to_byte),
            "error": m.error.map(SpecAckError::description),
        }),
        Message::DeviceName(m) => json!({
            "device": device_json(m.device_id),
            "device_name": m.text(),
        }),
        Message::DeviceNameQuery(m) => json!({ "device": device_json(m.device_id) }),
        Message::DeviceEnable(m) => json!({
            "device": device_json(m.device_id),
            "enable_flag": m.flag.to_byte(),
        }),
        Message::SystemStatus(m) => {
            let s = &m.switches;
            let switches: Vec<u8> = (1..=10u8)
                .zip(s.switch)
                .filter_map(|(n, on)| on.then_some(n))
                .collect();
            json!({
                "system_current_a": tenths(m.system_current.0),
                "main_bus_v": m.main_bus_volts.0 as f64 / 10.0,
                "aux_battery_v": tenths(m.aux_battery_volts.0),
                "internal_temp_c": m.internal_temp,
                "switches_on": switches,
                "roll_trim_down": s.roll_trim_down,
                "roll_trim_up": s.roll_trim_up,
                "pitch_trim_down": s.pitch_trim_down,
                "pitch_trim_up": s.pitch_trim_up,
                "flap_down": s.flap_down,
                "flap_up": s.flap_up,
                "starter_annunciator": m.misc.starter_annunciator,
                "wig_wag_mode": wig_wag_mode(m.misc.wig_wag_mode),
                "software_update": m.misc.software_update,
                "wig_wag_active": m.misc.wig_wag_active,
                "current_over_48a": m.faults.current_over_48a,
                "current_over_60a": m.faults.current_over_60a,
                "warm_reset": m.faults.warm_reset,
                "data_integrity_failure": m.faults.data_integrity_failure,
                "external_data_missing": m.faults.external_data_missing,
                "data_integrity_code": m.data_integrity_code.map_or(0, |c| c.to_byte()),
            })
        }
        Message::DeviceStatus(m) => {
            let devices: Vec<Value> = (m.on.iter().zip(&m.current).enumerate())
                .map(|(i, (on, current))| {
                    json!({
                        "id": i,
                        "name": device(i as u8).map(|d| d.system_name),
                        "on": on,
                        "current_a": tenths(current.0),
                    })
                })
                .collect();
            json!({ "devices": devices })
        }
        Message::FlapTrimStatus(m) => json!({
            "flap": {
                "enabled": m.flap.enabled,
                "motor_running": m.flap.motor_running,
                "fault": m.flap.fault,
                "overspeed_alarm": m.flap.overspeed_alarm,
                "down_switch_inhibited": m.flap.down_switch_inhibited,
                "position": m.flap_position,
                "fault_code": fault_json(m.flap_fault),
                "up": m.flap_up,
                "down": m.flap_down,
                "midpoint_1": m.flap_midpoint_1,
                "midpoint_2": m.flap_midpoint_2,
            },
            "pitch_trim": merge(trim_flags_json(&m.pitch_trim), json!({
                "position": m.pitch_trim_position,
                "fault_code": fault_json(m.pitch_trim_fault),
                "up": m.pitch_trim_up,
                "down": m.pitch_trim_down,
                "neutral": m.pitch_trim_neutral,
            })),
            "roll_trim": merge(trim_flags_json(&m.roll_trim), json!({
                "position": m.roll_trim_position,
                "fault_code": fault_json(m.roll_trim_fault),
                "up": m.roll_trim_up,
                "down": m.roll_trim_down,
                "neutral": m.roll_trim_neutral,
            })),
        }),
        Message::FaultStatus(m) => {
            let devices: Vec<Value> = (m.faulted.iter().zip(&m.codes).enumerate())
                .filter(|&(_, (&faulted, code))| faulted || code.is_some_and(|c| c.is_fault()))
                .map(|(i, (faulted, code))| {
                    json!({
                        "id": i,
                        "name": device(i as u8).map(|d| d.system_name),
                        "faulted": faulted,
                        "fault_code": code.map(fault_json),
                    })
                })
                .collect();
            json!({
                "faulted": devices,
                "system_fault": m.system_fault,
                "codes_carried": m.codes.iter().filter(|c| c.is_some()).count(),
            })
        }
        Message::DevicePower(m) => {
            json!({ "device": device_json(m.device_id), "power_state": m.on })
        }
        Message::TrimMove(m) => json!({
            "trim_type": trim_type(m.trim_type),
            "power_state": m.on,
            "direction": trim_direction(m.trim_type, m.direction),
        }),
        Message::FlapMove(m) => json!({
            "power_state": m.on,
            "direction": flap_direction(m.direction),
        }),
        Message::WigWagMode(m) => json!({ "wig_wag_mode": wig_wag_mode(m.mode) }),
        Message::DeviceClear(m) => json!({ "device_id": m.device_id }),
        Message::ExternalData(m) => json!({
            "indicated_airspeed": m.indicated_airspeed,
            "indicated_airspeed_valid": m.valid.indicated_airspeed,
            "ground_speed": m.ground_speed,
            "ground_speed_valid": m.valid.ground_speed,
            "baro_altitude_ft": m.baro_altitude,
            "baro_altitude_valid": m.valid.baro_altitude,
            "fuel_pressure_psi": m.fuel_pressure,
            "fuel_pressure_valid": m.valid.fuel_pressure,
            "rpm": m.rpm,
            "rpm_valid": m.valid.rpm,
        }),
    }
}

fn merge(mut a: Value, b: Value) -> Value {
    if let (Some(a), Value::Object(b)) = (a.as_object_mut(), b) {
        a.extend(b);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Packet;
    use crate::device::DEVICE_COUNT;

    /// DEVICE_SPEC, cnt 1, VP-X → EFIS: device 4, breaker 5 A, switch `sw`, current
    /// fault off (ICD Table 13). Checksums by hand: E7^7E^11^00^01^00^01^04^04^05^00 =
    /// 0x8D before the switch byte; ^FF = 0x72, inverted 0x8D; ^0B = 0x86, inverted 0x79.
    const SPEC_SW_255: [u8; 13] = [
        0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0xFF, 0x00, 0x8D,
    ];
    const SPEC_SW_11: [u8; 13] = [
        0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0x0B, 0x00, 0x79,
    ];

    #[test]
    fn device_spec_shows_the_switch_byte_that_was_sent() {
        // icd-reading R10: 255 and 11 both mean always on; the page takes 11, and the
        // typed message keeps the 255 that was on the wire so decode can show it.
        let p = Packet::parse_bytes(&SPEC_SW_255).unwrap();
        let Message::DeviceSpec(spec) = p.message else {
            panic!("{p:?}")
        };
        assert_eq!(spec.switch_id, SwitchId::AlwaysOn);
        assert_eq!(spec.switch_raw, Some(255));
        let text = describe(&p.message);
        assert!(
            text.contains(", switch 255 (always on; read as 11),"),
            "{text}"
        );
        let j = to_json(&p.message);
        assert_eq!(
            (&j["switch_id"], &j["switch_raw"], &j["switch"]),
            (&json!(11), &json!(255), &json!("always on (255)"))
        );
        // What the page sends for always on is 11, whatever it read (icd-reading R10).
        assert_eq!(p.message.emit().as_slice(), [0x04, 0x05, 0x0B, 0x00]);

        // Sent as 11: nothing to add.
        let p = Packet::parse_bytes(&SPEC_SW_11).unwrap();
        let text = describe(&p.message);
        assert!(text.contains(", switch 11 (always on),"), "{text}");
        let j = to_json(&p.message);
        assert_eq!(
            (&j["switch_id"], &j["switch_raw"], &j["switch"]),
            (&json!(11), &json!(11), &json!("always on"))
        );
        // Both mean the same setting.
        assert_eq!(
            Packet::parse_bytes(&SPEC_SW_255),
            Packet::parse_bytes(&SPEC_SW_11)
        );
    }

    #[test]
    fn system_status_shows_real_units_and_named_switches() {
        let mut switch = [false; 10];
        switch[0] = true;
        let m = Message::SystemStatus(SystemStatus {
            system_current: Tenths(123),
            main_bus_volts: SignedTenths(138),
            aux_battery_volts: Tenths(125),
            internal_temp: 31,
            switches: SwitchInputs {
                roll_trim_down: true,
                switch,
                ..Default::default()
            },
            misc: MiscFlags {
                starter_annunciator: false,
                wig_wag_mode: WigWagModeSetting::Auto,
                software_update: false,
                wig_wag_active: false,
            },
            faults: SystemFaultFlags::default(),
            data_integrity_code: None,
        });
        let s = describe(&m);
        assert!(s.contains("main bus 13.8 V"), "{s}");
        assert!(s.contains("system current 12.3 A"), "{s}");
        assert!(s.contains("switches on: switch 1, roll trim down"), "{s}");
        let j = to_json(&m);
        assert_eq!(j["main_bus_v"], json!(13.8));
        assert_eq!(j["switches_on"], json!([1]));
    }

    #[test]
    fn device_status_lists_on_devices_by_id_and_name() {
        let mut on = [false; DEVICE_COUNT];
        let mut current = [Tenths(0); DEVICE_COUNT];
        on[2] = true;
        current[2] = Tenths(23);
        current[5] = Tenths(4);
        let s = describe(&Message::DeviceStatus(DeviceStatus { on, current }));
        assert_eq!(s, "on: 2 EFIS 2.3 A; off but drawing: 5 5A-2 0.4 A");
    }

    #[test]
    fn no_field_shadows_the_header_keys() {
        // decode --json merges these objects with name/cnt/src/dst.
        let msgs = [
            Message::DeviceName(DeviceName::new(9, "Landing Lt").unwrap()),
            Message::Version(Version::REQUEST),
        ];
        for m in msgs {
            let j = to_json(&m);
            for k in ["name", "cnt", "src", "dst"] {
                assert!(j.get(k).is_none(), "{} has {k}", m.name());
            }
        }
    }
}

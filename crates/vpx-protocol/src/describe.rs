//! Every message in words and as JSON, for `vpx-efis decode` and the traffic view.
//!
//! One table gives both: [`fields`] lists each message's fields, named as in its ICD
//! table (lower-cased), with their values. [`describe`] joins them into words, each
//! value in its real unit ("main bus 13.8 V"); [`to_json`] makes them an object, each
//! key the field's name in snake case ending in its unit (`"main_bus_v": 13.8`).
//! Devices are shown by id and Table 40 name. Pure: no I/O.
//!
//! Speeds are knots: the ICD leaves their unit to the EFIS (icd-reading R20), and
//! this one's is knots, as its setup screens and backups say; so knots are said in
//! the words but not written into a key.
//!
//! JSON numbers in real units are computed from the integer on the wire as `f64`
//! (`138 / 10.0`), never through `f32`, so `13.8` prints as `13.8`.

use alloc::{
    format,
    string::{String, ToString},
    vec,
    vec::Vec,
};

use serde_json::{Map, Value, json};

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

/// One message in words: its fields with ICD names and real units.
pub fn describe(msg: &Message) -> String {
    let fields = fields(msg);
    if fields.is_empty() {
        return "no payload".into();
    }
    words(&fields)
}

/// One message's fields as a JSON object: ICD field names in snake case, real units
/// named in the key (`_a`, `_v`, `_s`). The caller adds the message name and header.
pub fn to_json(msg: &Message) -> Value {
    Value::Object(members(fields(msg)))
}

/// A unit: as said after a value, and as the end of the value's JSON key.
type Unit = (&'static str, &'static str);
const NO_UNIT: Unit = ("", "");
const AMPS: Unit = (" A", "_a");
const VOLTS: Unit = (" V", "_v");
const SECONDS: Unit = (" s", "_s");
const CELSIUS: Unit = (" °C", "_c");
const FEET: Unit = (" ft", "_ft");
const PSI: Unit = (" psi", "_psi");
const PERCENT: Unit = (" %", "_percent");
const KNOTS: Unit = (" kt", "");

/// One field of a message: its words ("circuit breaker 5 A") and its JSON members
/// (`"circuit_breaker_a": 5`).
struct Field {
    words: String,
    json: Vec<(String, Value)>,
    /// Words that list several things ("switches on: switch 1, flap up"): the next
    /// field is set off by a semicolon rather than a comma.
    list: bool,
}

/// A field name as a JSON key: `wig-wag mode` as `wig_wag_mode`.
fn snake(name: &str) -> String {
    name.replace([' ', '-'], "_")
}

/// The field `name`, said as `name words`, in JSON `name: json`.
fn field(name: &str, words: impl core::fmt::Display, json: impl Into<Value>) -> Field {
    Field {
        words: format!("{name} {words}"),
        json: vec![(snake(name), json.into())],
        list: false,
    }
}

impl Field {
    /// The JSON key differs from the name (the first member's key).
    fn key(mut self, key: &str) -> Field {
        if let Some(first) = self.json.first_mut() {
            first.0 = key.into();
        }
        self
    }

    /// A JSON member the words say within the field's value.
    fn also(mut self, key: &str, value: impl Into<Value>) -> Field {
        self.json.push((key.into(), value.into()));
        self
    }
}

/// A number in `unit`: `speed 40 kt`, `"speed": 40`.
fn num<T: core::fmt::Display + Into<Value> + Copy>(name: &str, v: T, unit: Unit) -> Field {
    field(name, format!("{v}{}", unit.0), v).key(&(snake(name) + unit.1))
}

/// A number sent in tenths of `unit`: `main bus 13.8 V`, `"main_bus_v": 13.8`.
fn tenths(name: &str, tenths: impl Into<f64>, unit: Unit) -> Field {
    let v = tenths.into() / 10.0;
    field(name, format!("{v:.1}{}", unit.0), v).key(&(snake(name) + unit.1))
}

/// A yes/no field, its two states in words: `power state on`, `"power_state": true`.
fn flag(name: &str, b: bool, [yes, no]: [&str; 2]) -> Field {
    field(name, if b { yes } else { no }, b)
}

/// A yes/no field said by its state alone: `enabled`, `"enabled": true`.
fn state(name: &str, b: bool, [yes, no]: [&str; 2]) -> Field {
    Field {
        words: (if b { yes } else { no }).into(),
        ..flag(name, b, [yes, no])
    }
}

/// A device by id and name: `device 9 5A-6`, `"device": {"id": 9, "name": "5A-6"}`.
fn device_field(name: &str, id: u8) -> Field {
    field(name, device_label(id), device_json(id))
}

/// A device or none (255): `disabled (255)`, JSON `null`.
fn opt_device(name: &str, id: Option<u8>) -> Field {
    match id {
        Some(id) => device_field(name, id),
        None => field(name, "disabled (255)", Value::Null),
    }
}

/// A group of fields under a name: `flap: position 40, up 20`; in JSON an object of
/// its own (`nested`) or its members beside the others.
fn group(name: &str, fields: Vec<Field>, nested: bool) -> Field {
    let words = format!("{name}: {}", words(&fields));
    let json = if nested {
        vec![(snake(name), Value::Object(members(fields)))]
    } else {
        fields.into_iter().flat_map(|f| f.json).collect()
    };
    Field {
        words,
        json,
        list: true,
    }
}

/// Flags by their ICD names: in words the set ones (or `none`), in JSON each one.
type Flags<'a> = [(&'a str, &'a str, bool)];

fn set_flags(set: &Flags) -> String {
    let on: Vec<&str> = set.iter().filter(|f| f.2).map(|f| f.0).collect();
    if on.is_empty() {
        "none".into()
    } else {
        on.join(", ")
    }
}

fn flag_members(set: &Flags) -> Vec<(String, Value)> {
    set.iter()
        .map(|&(_, key, b)| (key.into(), b.into()))
        .collect()
}

/// A list of the flags that are set: `system faults: none`.
fn flag_list(name: &str, set: &Flags) -> Field {
    Field {
        words: format!("{name}: {}", set_flags(set)),
        json: flag_members(set),
        list: true,
    }
}

/// A position with its motor's flags: `position 40 [enabled, motor running]`.
fn position(position: u8, set: &Flags) -> Field {
    let mut f = field(
        "position",
        format!("{position} [{}]", set_flags(set)),
        position,
    );
    f.json.extend(flag_members(set));
    f
}

/// A value the unit may mark invalid: `ground speed 0 kt (invalid)`, with
/// `"ground_speed_valid": false` beside it.
fn reading<T: core::fmt::Display + Into<Value> + Copy>(
    name: &str,
    v: T,
    unit: Unit,
    valid: bool,
) -> Field {
    let mut f = num(name, v, unit).also(&(snake(name) + "_valid"), valid);
    if !valid {
        f.words.push_str(" (invalid)");
    }
    f
}

fn words(fields: &[Field]) -> String {
    let mut s = String::new();
    let mut after_list = None;
    for f in fields {
        match after_list {
            Some(true) => s.push_str("; "),
            Some(false) => s.push_str(", "),
            None => {}
        }
        s.push_str(&f.words);
        after_list = Some(f.list);
    }
    s
}

fn members(fields: Vec<Field>) -> Map<String, Value> {
    fields.into_iter().flat_map(|f| f.json).collect()
}

fn device_json(id: u8) -> Value {
    json!({ "id": id, "name": device(id).map(|d| d.system_name) })
}

const ENABLED: [&str; 2] = ["enabled", "disabled"];
const ON: [&str; 2] = ["on", "off"];
const YES: [&str; 2] = ["yes", "no"];

/// Every message's fields, in the order of its ICD table.
fn fields(msg: &Message) -> Vec<Field> {
    match msg {
        Message::Ping(m) => vec![
            field(
                "ack flag",
                format!(
                    "{} ({})",
                    u8::from(m.ack),
                    if m.ack { "response" } else { "request" }
                ),
                m.ack,
            )
            .key("ack"),
        ],
        Message::Version(m) => vec![
            field(
                "hardware version",
                format!(
                    "{} ({})",
                    m.hardware_version.to_byte(),
                    m.hardware_version.name()
                ),
                m.hardware_version.to_byte(),
            )
            .also("hardware_name", m.hardware_version.name()),
            field(
                "software",
                format!("{}.{}", m.software_major, m.software_minor),
                m.software_major,
            )
            .key("software_major")
            .also("software_minor", m.software_minor),
        ],
        Message::SoftwareUpdate(_) | Message::DeviceStatusQuery(_) => vec![],
        Message::EepromErase(m) => vec![field(
            "response code",
            format!(
                "{} ({})",
                m.response_code,
                if m.response_code == 0 {
                    "success"
                } else {
                    "failure"
                }
            ),
            m.response_code,
        )],
        Message::DeviceSpec(m) => vec![
            device_field("device", m.device_id),
            num("circuit breaker", m.circuit_breaker, AMPS),
            field("switch", switch_text(m), switch_label(m))
                .also("switch_id", m.switch_id.to_byte())
                .also("switch_raw", m.switch_raw.unwrap_or(m.switch_id.to_byte())),
            flag("current fault", m.current_fault, ENABLED),
        ],
        Message::SystemSpec(m) => vec![
            field(
                "overvoltage limit",
                overvoltage(m.overvoltage_limit),
                m.overvoltage_limit.to_byte(),
            )
            .also(
                "overvoltage_limit_v",
                match m.overvoltage_limit {
                    OvervoltageLimit::V16 => json!(16),
                    OvervoltageLimit::V32 => json!(32),
                    OvervoltageLimit::Unknown(_) => Value::Null,
                },
            ),
            opt_device("secondary alternator", m.secondary_alternator),
        ],
        Message::TrimSpec(m) => vec![
            field("trim type", trim_type(m.trim_type), trim_type(m.trim_type)),
            state("enabled", m.enabled, ENABLED),
            field("polarity", polarity(m.polarity), polarity(m.polarity)),
            num("up", m.up, NO_UNIT),
            num("down", m.down, NO_UNIT),
            num("neutral", m.neutral, NO_UNIT),
            num("power", m.power, PERCENT),
            num("speed", m.speed, KNOTS),
        ],
        Message::FlapSpec(m) => {
            let mode = match m.mode {
                FlapMode::Momentary => "momentary",
                FlapMode::PositionBased => "position-based",
            };
            vec![
                field("mode", mode, mode),
                state("enabled", m.enabled, ENABLED),
                field("polarity", polarity(m.polarity), polarity(m.polarity)),
                num("up", m.up, NO_UNIT),
                num("down", m.down, NO_UNIT),
                num("midpoint 1", m.midpoint_1, NO_UNIT),
                num("midpoint 2", m.midpoint_2, NO_UNIT),
                num("circuit breaker", m.circuit_breaker, AMPS),
                num("overspeed position", m.overspeed_position, NO_UNIT),
                num("max speed", m.max_speed, KNOTS),
                tenths("endpoint duration", m.endpoint_duration.0, SECONDS),
            ]
        }
        Message::WigWagSpec(m) => vec![
            opt_device("device one", m.device_one),
            opt_device("device two", m.device_two),
            num("warm up period", m.warm_up_period, SECONDS),
            num("speed", m.speed, KNOTS),
        ],
        Message::DeviceSpecQuery(m) => {
            vec![field("device", spec_target(m.device_id), m.device_id).key("device_id")]
        }
        Message::SpecAck(m) => vec![
            field("device", spec_target(m.device_id), m.device_id).key("device_id"),
            field(
                "error code",
                match m.error {
                    None => "0 (none)".into(),
                    Some(e) => format!("{:#04x} ({})", e.to_byte(), e.description()),
                },
                m.error.map_or(0, SpecAckError::to_byte),
            )
            .also("error", m.error.map(SpecAckError::description)),
        ],
        Message::DeviceName(m) => vec![
            device_field("device", m.device_id),
            field("device name", format!("{:?}", m.text()), m.text()),
        ],
        Message::DeviceNameQuery(m) => vec![device_field("device", m.device_id)],
        Message::DeviceEnable(m) => vec![
            device_field("device", m.device_id),
            field("enable flag", enable_flag(m.flag), m.flag.to_byte()),
        ],
        Message::SystemStatus(m) => vec![
            tenths("system current", m.system_current.0, AMPS),
            tenths("main bus", m.main_bus_volts.0, VOLTS),
            tenths("aux battery", m.aux_battery_volts.0, VOLTS),
            num("internal temp", m.internal_temp, CELSIUS),
            switches_on(&m.switches),
            group(
                "misc",
                vec![
                    flag("starter annunciator", m.misc.starter_annunciator, YES),
                    field(
                        "wig-wag mode",
                        wig_wag_mode(m.misc.wig_wag_mode),
                        wig_wag_mode(m.misc.wig_wag_mode),
                    ),
                    flag("software update", m.misc.software_update, YES),
                    flag("wig-wag active", m.misc.wig_wag_active, YES),
                ],
                false,
            ),
            flag_list(
                "system faults",
                &[
                    (
                        "current > 48 A",
                        "current_over_48a",
                        m.faults.current_over_48a,
                    ),
                    (
                        "current > 60 A",
                        "current_over_60a",
                        m.faults.current_over_60a,
                    ),
                    ("CU warm reset", "warm_reset", m.faults.warm_reset),
                    (
                        "data integrity failure",
                        "data_integrity_failure",
                        m.faults.data_integrity_failure,
                    ),
                    (
                        "external data missing",
                        "external_data_missing",
                        m.faults.external_data_missing,
                    ),
                ],
            ),
            field(
                "data integrity code",
                match m.data_integrity_code {
                    None => "0 (none)".into(),
                    Some(c) => format!("{:#04x} ({})", c.to_byte(), c.description()),
                },
                m.data_integrity_code.map_or(0, |c| c.to_byte()),
            ),
        ],
        Message::DeviceStatus(m) => vec![device_status(m)],
        Message::FlapTrimStatus(m) => vec![
            group(
                "flap",
                vec![
                    position(
                        m.flap_position,
                        &[
                            ("enabled", "enabled", m.flap.enabled),
                            ("motor running", "motor_running", m.flap.motor_running),
                            ("fault", "fault", m.flap.fault),
                            ("overspeed alarm", "overspeed_alarm", m.flap.overspeed_alarm),
                            (
                                "down switch inhibited",
                                "down_switch_inhibited",
                                m.flap.down_switch_inhibited,
                            ),
                        ],
                    ),
                    fault_code(m.flap_fault),
                    num("up", m.flap_up, NO_UNIT),
                    num("down", m.flap_down, NO_UNIT),
                    num("midpoint 1", m.flap_midpoint_1, NO_UNIT),
                    num("midpoint 2", m.flap_midpoint_2, NO_UNIT),
                ],
                true,
            ),
            trim_status(
                "pitch trim",
                &m.pitch_trim,
                m.pitch_trim_position,
                m.pitch_trim_fault,
                [m.pitch_trim_up, m.pitch_trim_down, m.pitch_trim_neutral],
            ),
            trim_status(
                "roll trim",
                &m.roll_trim,
                m.roll_trim_position,
                m.roll_trim_fault,
                [m.roll_trim_up, m.roll_trim_down, m.roll_trim_neutral],
            ),
        ],
        Message::FaultStatus(m) => vec![fault_status(m)],
        Message::DevicePower(m) => vec![
            device_field("device", m.device_id),
            flag("power state", m.on, ON),
        ],
        Message::TrimMove(m) => {
            let direction = trim_direction(m.trim_type, m.direction);
            vec![
                field("trim type", trim_type(m.trim_type), trim_type(m.trim_type)),
                flag("power state", m.on, ON),
                field("direction", &direction, direction.as_str()),
            ]
        }
        Message::FlapMove(m) => {
            let direction = flap_direction(m.direction);
            vec![
                flag("power state", m.on, ON),
                field("direction", &direction, direction.as_str()),
            ]
        }
        Message::WigWagMode(m) => {
            let mode = wig_wag_mode(m.mode);
            vec![field("wig-wag mode", &mode, mode.as_str())]
        }
        Message::DeviceClear(m) => {
            let words = if m.device_id == SYSTEM_FAULT_ID {
                format!("{} (system fault)", m.device_id)
            } else {
                device_label(m.device_id)
            };
            vec![field("device", words, m.device_id).key("device_id")]
        }
        Message::ExternalData(m) => vec![
            reading(
                "indicated airspeed",
                m.indicated_airspeed,
                KNOTS,
                m.valid.indicated_airspeed,
            ),
            reading("ground speed", m.ground_speed, KNOTS, m.valid.ground_speed),
            reading(
                "baro altitude",
                m.baro_altitude,
                FEET,
                m.valid.baro_altitude,
            ),
            reading("fuel pressure", m.fuel_pressure, PSI, m.valid.fuel_pressure),
            reading("rpm", m.rpm, NO_UNIT, m.valid.rpm),
        ],
    }
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

/// A table value in its words, or its byte where the table does not list it.
fn named(words: Option<&str>, byte: u8) -> String {
    words.map_or_else(|| format!("unknown ({byte})"), String::from)
}

fn trim_type(t: TrimType) -> String {
    named(t.words(), t.to_byte())
}

fn wig_wag_mode(m: WigWagModeSetting) -> String {
    named(m.words(), m.to_byte())
}

fn overvoltage(o: OvervoltageLimit) -> String {
    named(o.words(), o.to_byte())
}

fn enable_flag(f: EnableFlag) -> String {
    format!("{} ({})", f.to_byte(), f.words().unwrap_or("unknown"))
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
    named(d.words(), d.to_byte())
}

fn fault_name(c: super::fault::FaultCode) -> String {
    format!("{:#04x} {}", c.to_byte(), c.name())
}

fn fault_json(c: super::fault::FaultCode) -> Value {
    json!({ "code": c.to_byte(), "name": c.name() })
}

fn fault_code(c: super::fault::FaultCode) -> Field {
    field("fault code", fault_name(c), fault_json(c))
}

/// One trim's part of FLAP_TRIM_STATUS: `pitch trim: position 128 [enabled], …`.
fn trim_status(
    name: &str,
    flags: &TrimFlags,
    at: u8,
    fault: super::fault::FaultCode,
    [up, down, neutral]: [u8; 3],
) -> Field {
    let set = [
        ("enabled", "enabled", flags.enabled),
        ("motor running", "motor_running", flags.motor_running),
        ("fault", "fault", flags.fault),
    ];
    group(
        name,
        vec![
            position(at, &set),
            fault_code(fault),
            num("up", up, NO_UNIT),
            num("down", down, NO_UNIT),
            num("neutral", neutral, NO_UNIT),
        ],
        true,
    )
}

/// SYSTEM_STATUS's switch inputs: in words the ones closed (`switch 1, flap up`), in
/// JSON the numbered switches closed and each named one.
fn switches_on(s: &SwitchInputs) -> Field {
    let named = [
        ("roll trim down", "roll_trim_down", s.roll_trim_down),
        ("roll trim up", "roll_trim_up", s.roll_trim_up),
        ("pitch trim down", "pitch_trim_down", s.pitch_trim_down),
        ("pitch trim up", "pitch_trim_up", s.pitch_trim_up),
        ("flap down", "flap_down", s.flap_down),
        ("flap up", "flap_up", s.flap_up),
    ];
    let numbered: Vec<u8> = (1..=10u8)
        .zip(s.switch)
        .filter_map(|(n, on)| on.then_some(n))
        .collect();
    let mut on: Vec<String> = numbered.iter().map(|n| format!("switch {n}")).collect();
    on.extend(named.iter().filter(|f| f.2).map(|f| f.0.to_string()));
    let words = if on.is_empty() {
        "none".into()
    } else {
        on.join(", ")
    };
    let mut json = vec![("switches_on".into(), numbered.into())];
    json.extend(flag_members(&named));
    Field {
        words: format!("switches on: {words}"),
        json,
        list: true,
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
/// means: "3 (input 3)", "11 (always on)". Where icd-reading R10 reads a byte as
/// another (255 is always on, as 11), the reading says so: "255 (always on; read as
/// 11)".
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
        format!("{sent} ({meaning})")
    } else {
        format!("{sent} ({meaning}; read as {read})")
    }
}

/// DEVICE_STATUS: in words the devices on with their currents, and the off ones
/// drawing current (worth seeing; off devices at zero are not); in JSON every device.
fn device_status(m: &DeviceStatus) -> Field {
    let devices = || m.on.iter().zip(&m.current).enumerate();
    let drawing = |(i, (_, c)): (usize, (&bool, &Tenths))| {
        format!("{} {:.1} A", device_label(i as u8), f64::from(c.0) / 10.0)
    };
    let on: Vec<String> = devices().filter(|&(_, (&on, _))| on).map(drawing).collect();
    let off: Vec<String> = devices()
        .filter(|&(_, (&on, c))| !on && c.0 != 0)
        .map(drawing)
        .collect();
    let mut words = format!(
        "on: {}",
        if on.is_empty() {
            "none".into()
        } else {
            on.join(", ")
        }
    );
    if !off.is_empty() {
        words.push_str(&format!("; off but drawing: {}", off.join(", ")));
    }
    let all: Vec<Value> = devices()
        .map(|(i, (on, current))| {
            json!({
                "id": i,
                "name": device(i as u8).map(|d| d.system_name),
                "on": on,
                "current_a": f64::from(current.0) / 10.0,
            })
        })
        .collect();
    Field {
        words,
        json: vec![("devices".into(), all.into())],
        list: false,
    }
}

/// FAULT_STATUS: the faulted devices with their codes, the system fault, how many
/// codes the message carried, and any code sent without its fault bit (unusual enough
/// to show).
fn fault_status(m: &FaultStatus) -> Field {
    let devices = || m.faulted.iter().zip(&m.codes).enumerate();
    let faulted: Vec<String> = devices()
        .filter(|&(_, (&faulted, _))| faulted)
        .map(|(i, (_, code))| match code {
            Some(c) => format!("{} {}", device_label(i as u8), fault_name(*c)),
            None => format!("{} (no code sent)", device_label(i as u8)),
        })
        .collect();
    let stray: Vec<String> = devices()
        .filter_map(|(i, (&faulted, code))| match code {
            Some(c) if !faulted && c.is_fault() => {
                Some(format!("{} {}", device_label(i as u8), fault_name(*c)))
            }
            _ => None,
        })
        .collect();
    let carried = m.codes.iter().filter(|c| c.is_some()).count();
    let mut words = format!(
        "faulted: {}; system fault {}; {} codes carried",
        if faulted.is_empty() {
            "none".into()
        } else {
            faulted.join(", ")
        },
        if m.system_fault { "yes" } else { "no" },
        carried
    );
    if !stray.is_empty() {
        words.push_str(&format!("; codes without fault bit: {}", stray.join(", ")));
    }
    let listed: Vec<Value> = devices()
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
    Field {
        words,
        json: vec![
            ("faulted".into(), listed.into()),
            ("system_fault".into(), m.system_fault.into()),
            ("codes_carried".into(), carried.into()),
        ],
        list: false,
    }
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

//! The configuration's settings, each written once: its key in the backup file, the
//! field of the ICD spec that holds it (as `validate::whole_config` names it in a path),
//! the message that carries it, its words and its unit. The backup file's writer,
//! reader and path map, the diff and the setup screens all read this table.
//!
//! The rows of a section are in the order the file writes them.

/// The message that carries a setting to the unit (and whose answer reports it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// SYSTEM_SPEC, ICD Table 14.
    System,
    /// FLAP_SPEC, Table 16.
    Flap,
    /// TRIM_SPEC, Table 15 (pitch and roll alike).
    Trim,
    /// WIG_WAG_SPEC, Table 17.
    WigWag,
    /// DEVICE_SPEC, Table 13.
    Device,
    /// DEVICE_NAME, Table 21 (a pin's, or the flaps' and trims' own).
    Name,
    /// DEVICE_ENABLE, Table 23.
    Enable,
}

/// How a value of the file reads in words ("5 A", "yes", "always on").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Words {
    /// The value as the file writes it, then the unit if there is one.
    Plain,
    /// A name in quotes, or "(no name)".
    Quoted,
    YesNo,
    OnOff,
    /// "always off", "switch 3", "always on".
    Switch,
    /// Seconds to a tenth.
    Tenths,
}

/// One setting of the configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Item {
    /// Its key in its section of the backup file.
    pub key: &'static str,
    /// The field of the spec that holds it, as in a `validate::whole_config` path; ""
    /// for a name or an enable flag, which are not spec fields.
    pub spec: &'static str,
    pub part: Part,
    /// In words: whole for `[system]`, `[flaps]` and `[wig_wag]`; after the trim's or the
    /// pin's name for the others ("breaker" → "5A-3 (Strobe Lt) breaker").
    pub words: &'static str,
    /// "A", "kt", "s", "%", "V", or "".
    pub unit: &'static str,
    pub shown: Words,
    /// What a number is, for a problem with its range ("a breaker").
    pub what: &'static str,
}

const fn item(key: &'static str, spec: &'static str, part: Part, words: &'static str) -> Item {
    Item {
        key,
        spec,
        part,
        words,
        unit: "",
        shown: Words::Plain,
        what: "",
    }
}

impl Item {
    const fn unit(self, unit: &'static str) -> Item {
        Item { unit, ..self }
    }
    const fn shown(self, shown: Words) -> Item {
        Item { shown, ..self }
    }
    const fn what(self, what: &'static str) -> Item {
        Item { what, ..self }
    }
}

// [system]: SYSTEM_SPEC.
pub const OVERVOLTAGE: Item = item(
    "overvoltage_limit_volts",
    "overvoltage_limit",
    Part::System,
    "overvoltage limit",
)
.unit("V");
pub const SECONDARY_ALTERNATOR: Item = item(
    "secondary_alternator",
    "secondary_alternator",
    Part::System,
    "secondary alternator",
);
pub const SYSTEM: &[Item; 2] = &[OVERVOLTAGE, SECONDARY_ALTERNATOR];

// [flaps]: FLAP_SPEC, and DEVICE_NAME 0.
const FLAP_POSITION: &str = "a flap position sensor reading";
pub const FLAP_NAME: Item = item("name", "", Part::Name, "flaps name").shown(Words::Quoted);
pub const FLAP_ENABLED: Item =
    item("enabled", "enabled", Part::Flap, "flaps fitted").shown(Words::YesNo);
pub const FLAP_MODE: Item = item("mode", "mode", Part::Flap, "flap mode");
pub const FLAP_POLARITY: Item = item("polarity", "polarity", Part::Flap, "flap motor polarity");
pub const FLAP_UP: Item = item("up", "up", Part::Flap, "flap up position").what(FLAP_POSITION);
pub const FLAP_MIDPOINT_1: Item =
    item("midpoint_1", "midpoint_1", Part::Flap, "flap midpoint 1").what(FLAP_POSITION);
pub const FLAP_MIDPOINT_2: Item =
    item("midpoint_2", "midpoint_2", Part::Flap, "flap midpoint 2").what(FLAP_POSITION);
pub const FLAP_DOWN: Item =
    item("down", "down", Part::Flap, "flap down position").what(FLAP_POSITION);
pub const FLAP_BREAKER: Item = item(
    "breaker_amps",
    "circuit_breaker",
    Part::Flap,
    "flap breaker",
)
.unit("A")
.what("a breaker");
pub const FLAP_OVERSPEED_POSITION: Item = item(
    "overspeed_position",
    "overspeed_position",
    Part::Flap,
    "flap overspeed position",
)
.what(FLAP_POSITION);
pub const FLAP_MAX_SPEED: Item = item("max_speed_kt", "max_speed", Part::Flap, "flap max speed")
    .unit("kt")
    .what("a speed");
pub const FLAP_ENDPOINT_DURATION: Item = item(
    "endpoint_duration_s",
    "endpoint_duration",
    Part::Flap,
    "flap endpoint duration",
)
.unit("s")
.shown(Words::Tenths);
pub const FLAPS: &[Item; 12] = &[
    FLAP_NAME,
    FLAP_ENABLED,
    FLAP_MODE,
    FLAP_POLARITY,
    FLAP_UP,
    FLAP_MIDPOINT_1,
    FLAP_MIDPOINT_2,
    FLAP_DOWN,
    FLAP_BREAKER,
    FLAP_OVERSPEED_POSITION,
    FLAP_MAX_SPEED,
    FLAP_ENDPOINT_DURATION,
];

// [pitch_trim] and [roll_trim]: TRIM_SPEC, and DEVICE_NAME 30 and 29.
const TRIM_POSITION: &str = "a trim position sensor reading";
pub const TRIM_NAME: Item = item("name", "", Part::Name, "name").shown(Words::Quoted);
pub const TRIM_ENABLED: Item = item("enabled", "enabled", Part::Trim, "fitted").shown(Words::YesNo);
pub const TRIM_POLARITY: Item = item("polarity", "polarity", Part::Trim, "motor polarity");
pub const TRIM_UP: Item = item("up", "up", Part::Trim, "up position").what(TRIM_POSITION);
pub const TRIM_DOWN: Item = item("down", "down", Part::Trim, "down position").what(TRIM_POSITION);
pub const TRIM_NEUTRAL: Item =
    item("neutral", "neutral", Part::Trim, "neutral position").what(TRIM_POSITION);
pub const TRIM_POWER: Item = item(
    "reduced_power_percent",
    "power",
    Part::Trim,
    "reduced power",
)
.unit("%")
.what("a percentage");
pub const TRIM_SPEED: Item = item("reduce_above_kt", "speed", Part::Trim, "reduce power above")
    .unit("kt")
    .what("a speed");
pub const TRIM: &[Item; 8] = &[
    TRIM_NAME,
    TRIM_ENABLED,
    TRIM_POLARITY,
    TRIM_UP,
    TRIM_DOWN,
    TRIM_NEUTRAL,
    TRIM_POWER,
    TRIM_SPEED,
];

// [wig_wag]: WIG_WAG_SPEC.
pub const WIG_WAG_ONE: Item = item(
    "device_one",
    "device_one",
    Part::WigWag,
    "wig-wag device one",
);
pub const WIG_WAG_TWO: Item = item(
    "device_two",
    "device_two",
    Part::WigWag,
    "wig-wag device two",
);
pub const WIG_WAG_WARM_UP: Item = item(
    "warm_up_s",
    "warm_up_period",
    Part::WigWag,
    "wig-wag warm-up",
)
.unit("s")
.what("a warm-up time");
pub const WIG_WAG_SPEED: Item = item("speed_kt", "speed", Part::WigWag, "wig-wag speed")
    .unit("kt")
    .what("a speed");
pub const WIG_WAG: &[Item; 4] = &[WIG_WAG_ONE, WIG_WAG_TWO, WIG_WAG_WARM_UP, WIG_WAG_SPEED];

// [devices.PIN]: DEVICE_SPEC, DEVICE_NAME and DEVICE_ENABLE of pins 1–28.
pub const DEVICE_NAME: Item = item("name", "", Part::Name, "name").shown(Words::Quoted);
pub const DEVICE_SHOWN: Item =
    item("show_on_page", "", Part::Enable, "shown on the page").shown(Words::YesNo);
pub const DEVICE_BREAKER: Item = item("breaker_amps", "circuit_breaker", Part::Device, "breaker")
    .unit("A")
    .what("a breaker");
pub const DEVICE_SWITCH: Item =
    item("switch", "switch_id", Part::Device, "switch").shown(Words::Switch);
pub const DEVICE_CURRENT_FAULT: Item = item(
    "current_fault",
    "current_fault",
    Part::Device,
    "current fault checking",
)
.shown(Words::OnOff);
pub const DEVICE: &[Item; 5] = &[
    DEVICE_NAME,
    DEVICE_SHOWN,
    DEVICE_BREAKER,
    DEVICE_SWITCH,
    DEVICE_CURRENT_FAULT,
];

/// Spec fields with no key of their own in the file: a problem with one is the
/// section's (the entry's device id, the trim type).
pub const NOT_IN_FILE: &[&str] = &["device_id", "trim_type"];

/// A value read from the file in words, as the diff shows it.
pub fn words(item: &Item, v: &toml::Value) -> String {
    use toml::Value as V;
    let plain = |s: String| {
        if item.unit.is_empty() {
            s
        } else {
            format!("{s} {}", item.unit)
        }
    };
    match (item.shown, v) {
        (Words::Quoted, V::String(s)) if s.is_empty() => "(no name)".into(),
        (Words::Quoted, V::String(s)) => format!("\"{}\"", s.escape_default()),
        (Words::YesNo, V::Boolean(b)) => if *b { "yes" } else { "no" }.into(),
        (Words::OnOff, V::Boolean(b)) => if *b { "on" } else { "off" }.into(),
        (Words::Switch, V::String(s)) if s == "off" => "always off".into(),
        (Words::Switch, V::String(s)) if s == "always-on" => "always on".into(),
        (Words::Switch, V::Integer(n)) => format!("switch {n}"),
        (Words::Tenths, V::Float(f)) => plain(format!("{f:.1}")),
        (_, V::String(s)) => plain(s.clone()),
        (_, v) => plain(v.to_string()),
    }
}

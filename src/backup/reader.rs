//! Reading the backup file. Deliberately not one `serde` pass: that stops at the first
//! problem, while a person fixing a file wants all of them at once, each by its line
//! and its path in the file (`devices.5A-3.breaker_amps`, [`toml_lines`]). The file is
//! parsed as TOML, each value is read on its own by its [`schema`](super::schema) key,
//! and the result is judged by the same §6.2 rules the unit applies
//! ([`validate::whole_config`]).

use std::collections::{BTreeMap, BTreeSet};

use super::path::file_path;
use super::provenance::{self, Provenance};
use super::schema::{
    DEVICE_BREAKER, DEVICE_CURRENT_FAULT, DEVICE_NAME, DEVICE_SHOWN, DEVICE_SWITCH, FLAP_BREAKER,
    FLAP_DOWN, FLAP_ENABLED, FLAP_ENDPOINT_DURATION, FLAP_MAX_SPEED, FLAP_MIDPOINT_1,
    FLAP_MIDPOINT_2, FLAP_MODE, FLAP_NAME, FLAP_OVERSPEED_POSITION, FLAP_POLARITY, FLAP_UP,
    OVERVOLTAGE, SECONDARY_ALTERNATOR, TRIM_DOWN, TRIM_ENABLED, TRIM_NAME, TRIM_NEUTRAL,
    TRIM_POLARITY, TRIM_POWER, TRIM_SPEED, TRIM_UP, WIG_WAG_ONE, WIG_WAG_SPEED, WIG_WAG_TWO,
    WIG_WAG_WARM_UP,
};
use super::writer::NONE;
use super::{Backup, FORMAT};
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{DEVICES, FLAPS, TRIM_P, TRIM_R, enable_flag_allowed};
use crate::protocol::message::{
    DeviceSpec, FlapMode, HardwareVersion, OvervoltageLimit, Polarity, SwitchId, Tenths, TrimType,
    Version,
};
use crate::protocol::validate;
use crate::toml_lines::{self, Keys, Problem};

/// Reads a backup from TOML text: every problem, from TOML syntax to a breaker outside
/// its pin's range or a wig-wag device on no switch, is listed by its path in the file.
pub fn from_toml(text: &str) -> Result<Backup, Vec<Problem>> {
    from_toml_made(text).map(|(b, _)| b)
}

/// [`from_toml`], and the `[made]` section if the file has one.
pub fn from_toml_made(text: &str) -> Result<(Backup, Option<Provenance>), Vec<Problem>> {
    let table = toml_lines::table(text).map_err(|p| vec![p])?;
    let mut problems = Vec::new();
    let made = provenance::read(&table, &mut problems);
    let backup = read_file(&table, &mut problems);
    // A field that could not be read holds the factory value instead; judging the rest
    // by the §6.2 rules still finds every other problem, and nothing is reported twice.
    let reported: BTreeSet<String> = problems.iter().map(|p| p.field.clone()).collect();
    for p in validate::whole_config(&backup.config) {
        let field = file_path(&p.field);
        if !reported.iter().any(|r| field.starts_with(r.as_str())) {
            problems.push(Problem {
                line: None,
                field,
                message: p.message,
            });
        }
    }
    if problems.is_empty() {
        return Ok((backup, made));
    }
    let keys = Keys::of(text);
    for p in &mut problems {
        p.line = keys.line(&p.field);
    }
    // Those of the file as a whole (a section it lacks) first, then in its order.
    problems.sort_by_key(|p| p.line);
    Err(problems)
}

/// One TOML table being read: typed getters that record a problem (with the full path)
/// instead of failing, and a check for keys nobody asked for (typos).
struct Section<'a, 'p> {
    table: Option<&'a toml::Table>,
    path: String,
    asked: Vec<&'static str>,
    problems: &'p mut Vec<Problem>,
}

impl<'a, 'p> Section<'a, 'p> {
    fn new(
        parent: &'a toml::Table,
        key: &str,
        path: String,
        problems: &'p mut Vec<Problem>,
    ) -> Self {
        let table = match parent.get(key) {
            Some(toml::Value::Table(t)) => Some(t),
            Some(v) => {
                problems.push(Problem {
                    line: None,
                    field: path.clone(),
                    message: format!("must be a table ([{path}]), not {}", kind(v)),
                });
                None
            }
            None => {
                problems.push(Problem {
                    line: None,
                    field: path.clone(),
                    message: format!("missing: the file has no [{path}] table"),
                });
                None
            }
        };
        Section {
            table,
            path,
            asked: Vec::new(),
            problems,
        }
    }

    fn problem(&mut self, key: &str, message: String) {
        self.problems.push(Problem {
            line: None,
            field: format!("{}.{key}", self.path),
            message,
        });
    }

    /// The raw value, or a "missing" problem. `None` too when the table itself was bad
    /// (already reported once for the table).
    fn value(&mut self, key: &'static str) -> Option<&'a toml::Value> {
        self.asked.push(key);
        let table = self.table?;
        let v = table.get(key);
        if v.is_none() {
            self.problem(key, "missing".into());
        }
        v
    }

    fn int(&mut self, key: &'static str, max: i64, what: &str) -> Option<i64> {
        match self.value(key)? {
            toml::Value::Integer(n) if (0..=max).contains(n) => Some(*n),
            toml::Value::Integer(n) => {
                self.problem(
                    key,
                    format!("{n} does not fit: {what} is a whole number 0–{max}"),
                );
                None
            }
            v => {
                self.problem(
                    key,
                    format!("must be a whole number 0–{max}, not {}", kind(v)),
                );
                None
            }
        }
    }

    fn u8(&mut self, key: &'static str, what: &str) -> Option<u8> {
        self.int(key, u8::MAX as i64, what).map(|n| n as u8)
    }

    fn u16(&mut self, key: &'static str, what: &str) -> Option<u16> {
        self.int(key, u16::MAX as i64, what).map(|n| n as u16)
    }

    fn bool(&mut self, key: &'static str) -> Option<bool> {
        match self.value(key)? {
            toml::Value::Boolean(b) => Some(*b),
            v => {
                self.problem(key, format!("must be true or false, not {}", kind(v)));
                None
            }
        }
    }

    fn string(&mut self, key: &'static str) -> Option<&'a str> {
        match self.value(key)? {
            toml::Value::String(s) => Some(s),
            v => {
                self.problem(key, format!("must be a quoted string, not {}", kind(v)));
                None
            }
        }
    }

    fn choice<T: Copy>(&mut self, key: &'static str, choices: &[(&str, T)]) -> Option<T> {
        let s = self.string(key)?;
        if let Some((_, v)) = choices.iter().find(|(w, _)| *w == s) {
            return Some(*v);
        }
        let words: Vec<String> = choices.iter().map(|(w, _)| format!("\"{w}\"")).collect();
        self.problem(key, format!("\"{s}\" is not one of {}", words.join(", ")));
        None
    }

    /// A device name: up to 16 single-byte characters (module doc).
    fn name(&mut self, key: &'static str) -> Option<[u8; 16]> {
        let s = self.string(key)?;
        let mut out = [0u8; 16];
        for (n, c) in s.chars().enumerate() {
            let Ok(b) = u8::try_from(c as u32) else {
                self.problem(
                    key,
                    format!("\"{s}\" has '{c}', which is not a single byte; names are ASCII (ICD Table 21)"),
                );
                return None;
            };
            if b == 0 {
                // A NUL ends the name on the unit; anything after it would be lost.
                break;
            }
            if n == 16 {
                self.problem(
                    key,
                    format!(
                        "\"{s}\" is {} characters; the unit stores at most 16 (ICD Table 21)",
                        s.chars().count()
                    ),
                );
                return None;
            }
            out[n] = b;
        }
        Some(out)
    }

    /// `"none"`, a Table 40 pin name, or a device id.
    fn pin(&mut self, key: &'static str) -> Option<Option<u8>> {
        let v = self.value(key)?;
        match v {
            toml::Value::String(s) if s == NONE => Some(None),
            toml::Value::String(s) => match DEVICES.iter().find(|d| d.system_name == s) {
                Some(d) => Some(Some(d.id)),
                None => {
                    self.problem(
                        key,
                        format!("\"{s}\" is neither \"none\" nor a pin of ICD Table 40 (e.g. \"5A-1\", \"10A-2\")"),
                    );
                    None
                }
            },
            toml::Value::Integer(n) if (0..=254).contains(n) => Some(Some(*n as u8)),
            v => {
                self.problem(
                    key,
                    format!(
                        "must be \"none\" or a pin name such as \"5A-1\", not {}",
                        kind(v)
                    ),
                );
                None
            }
        }
    }

    fn switch(&mut self, key: &'static str) -> Option<SwitchId> {
        let v = self.value(key)?;
        match v {
            toml::Value::String(s) if s == "off" => Some(SwitchId::Off),
            toml::Value::String(s) if s == "always-on" => Some(SwitchId::AlwaysOn),
            toml::Value::Integer(n) if (1..=10).contains(n) => Some(SwitchId::Input(*n as u8)),
            v => {
                let shown = match v {
                    toml::Value::String(s) => format!("\"{s}\""),
                    toml::Value::Integer(n) => n.to_string(),
                    v => kind(v).to_string(),
                };
                self.problem(
                    key,
                    format!("{shown} is not a switch: use \"off\", 1–10 or \"always-on\" (ICD Table 13 note 3)"),
                );
                None
            }
        }
    }

    /// Seconds to a tenth, as the wire's tenths.
    fn tenths(&mut self, key: &'static str) -> Option<Tenths> {
        let v = self.value(key)?;
        let secs = match v {
            toml::Value::Float(f) => *f,
            toml::Value::Integer(n) => *n as f64,
            v => {
                self.problem(key, format!("must be a number of seconds, not {}", kind(v)));
                return None;
            }
        };
        let t = (secs * 10.0).round();
        if !(0.0..=u16::MAX as f64).contains(&t) {
            self.problem(
                key,
                format!("{secs} s does not fit: it must be 0 s or more, in tenths"),
            );
            return None;
        }
        if (secs * 10.0 - t).abs() > 1e-6 {
            self.problem(
                key,
                format!("{secs} s is not a whole number of tenths of a second (ICD Table 16)"),
            );
            return None;
        }
        Some(Tenths(t as u16))
    }

    fn finish(self) {
        let Some(table) = self.table else { return };
        for key in table.keys() {
            if !self.asked.contains(&key.as_str()) {
                self.problems.push(Problem {
                    line: None,
                    field: format!("{}.{key}", self.path),
                    message: format!(
                        "unknown setting; [{}] has {}",
                        self.path,
                        self.asked.join(", ")
                    ),
                });
            }
        }
    }
}

fn kind(v: &toml::Value) -> &'static str {
    match v {
        toml::Value::String(_) => "a string",
        toml::Value::Integer(_) => "a whole number",
        toml::Value::Float(_) => "a decimal number",
        toml::Value::Boolean(_) => "true/false",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "a list",
        toml::Value::Table(_) => "a table",
    }
}

/// Puts a setting the file gave in its place; one it lacks (or got wrong, then a
/// problem) leaves the place as it was.
fn set<T>(slot: &mut T, read: Option<T>) {
    if let Some(v) = read {
        *slot = v;
    }
}

const POLARITIES: &[(&str, Polarity)] = &[
    ("standard", Polarity::Standard),
    ("inverted", Polarity::Inverted),
];

fn read_file(t: &toml::Table, problems: &mut Vec<Problem>) -> Backup {
    let mut cfg = UnitConfig::default();
    let mut version = Version {
        hardware_version: HardwareVersion::Unknown(0),
        software_major: 0,
        software_minor: 0,
    };

    match t.get("format") {
        Some(toml::Value::Integer(n)) if *n == FORMAT as i64 => {}
        Some(v) => problems.push(Problem {
            line: None,
            field: "format".into(),
            message: format!(
                "{} is not a format this program reads (it reads format = {FORMAT})",
                match v {
                    toml::Value::Integer(n) => n.to_string(),
                    v => kind(v).to_string(),
                }
            ),
        }),
        None => problems.push(Problem {
            line: None,
            field: "format".into(),
            message: format!("missing (format = {FORMAT}); is this a vpx-efis backup?"),
        }),
    }
    const TOP: &[&str] = &[
        "format",
        "made",
        "unit",
        "system",
        "flaps",
        "pitch_trim",
        "roll_trim",
        "wig_wag",
        "devices",
    ];
    for key in t.keys() {
        if !TOP.contains(&key.as_str()) {
            problems.push(Problem {
                line: None,
                field: key.clone(),
                message: format!("unknown section; a backup has {}", TOP.join(", ")),
            });
        }
    }

    {
        let mut s = Section::new(t, "unit", "unit".into(), problems);
        if let Some(hw) = s.u8("hardware_version", "a hardware version") {
            version.hardware_version = HardwareVersion::from_byte(hw);
        }
        // For people only; the number above is what counts.
        let _ = s.string("hardware");
        if let Some(sw) = s.string("software") {
            match sw
                .split_once('.')
                .and_then(|(a, b)| Some((a.parse::<u8>().ok()?, b.parse::<u8>().ok()?)))
            {
                Some((major, minor)) => {
                    version.software_major = major;
                    version.software_minor = minor;
                }
                None => s.problem(
                    "software",
                    format!("\"{sw}\" is not MAJOR.MINOR with each 0–255, e.g. \"3.7\""),
                ),
            }
        }
        s.finish();
    }

    {
        let mut s = Section::new(t, "system", "system".into(), problems);
        if let Some(v) = s.value(OVERVOLTAGE.key) {
            match v {
                toml::Value::Integer(16) => cfg.system.overvoltage_limit = OvervoltageLimit::V16,
                toml::Value::Integer(32) => cfg.system.overvoltage_limit = OvervoltageLimit::V32,
                _ => s.problem(OVERVOLTAGE.key, "must be 16 or 32 (ICD Table 14)".into()),
            }
        }
        set(
            &mut cfg.system.secondary_alternator,
            s.pin(SECONDARY_ALTERNATOR.key),
        );
        s.finish();
    }

    {
        let mut s = Section::new(t, "flaps", "flaps".into(), problems);
        let f = &mut cfg.flap;
        set(&mut cfg.names[FLAPS as usize], s.name(FLAP_NAME.key));
        set(&mut f.enabled, s.bool(FLAP_ENABLED.key));
        set(
            &mut f.mode,
            s.choice(
                FLAP_MODE.key,
                &[
                    ("momentary", FlapMode::Momentary),
                    ("position-based", FlapMode::PositionBased),
                ],
            ),
        );
        set(&mut f.polarity, s.choice(FLAP_POLARITY.key, POLARITIES));
        for (item, slot) in [
            (FLAP_UP, &mut f.up),
            (FLAP_MIDPOINT_1, &mut f.midpoint_1),
            (FLAP_MIDPOINT_2, &mut f.midpoint_2),
            (FLAP_DOWN, &mut f.down),
            (FLAP_OVERSPEED_POSITION, &mut f.overspeed_position),
            (FLAP_BREAKER, &mut f.circuit_breaker),
        ] {
            set(slot, s.u8(item.key, item.what));
        }
        set(
            &mut f.max_speed,
            s.u16(FLAP_MAX_SPEED.key, FLAP_MAX_SPEED.what),
        );
        set(
            &mut f.endpoint_duration,
            s.tenths(FLAP_ENDPOINT_DURATION.key),
        );
        s.finish();
        // The flap breaker is kept in one value (UnitConfig::apply_flap_spec).
        let flap = cfg.flap;
        cfg.apply_flap_spec(&flap);
    }

    for (key, id, trim_type) in [
        ("pitch_trim", TRIM_P, TrimType::Pitch),
        ("roll_trim", TRIM_R, TrimType::Roll),
    ] {
        let mut s = Section::new(t, key, key.into(), problems);
        let mut spec = *cfg.trim(trim_type);
        set(&mut cfg.names[id as usize], s.name(TRIM_NAME.key));
        set(&mut spec.enabled, s.bool(TRIM_ENABLED.key));
        set(&mut spec.polarity, s.choice(TRIM_POLARITY.key, POLARITIES));
        for (item, slot) in [
            (TRIM_UP, &mut spec.up),
            (TRIM_DOWN, &mut spec.down),
            (TRIM_NEUTRAL, &mut spec.neutral),
            (TRIM_POWER, &mut spec.power),
        ] {
            set(slot, s.u8(item.key, item.what));
        }
        set(&mut spec.speed, s.u16(TRIM_SPEED.key, TRIM_SPEED.what));
        s.finish();
        cfg.apply_trim_spec(&spec);
    }

    {
        let mut s = Section::new(t, "wig_wag", "wig_wag".into(), problems);
        let w = &mut cfg.wig_wag;
        set(&mut w.device_one, s.pin(WIG_WAG_ONE.key));
        set(&mut w.device_two, s.pin(WIG_WAG_TWO.key));
        set(
            &mut w.warm_up_period,
            s.u8(WIG_WAG_WARM_UP.key, WIG_WAG_WARM_UP.what),
        );
        set(&mut w.speed, s.u8(WIG_WAG_SPEED.key, WIG_WAG_SPEED.what));
        s.finish();
    }

    read_devices(t, &mut cfg, problems);
    Backup {
        version,
        config: cfg,
    }
}

fn read_devices(t: &toml::Table, cfg: &mut UnitConfig, problems: &mut Vec<Problem>) {
    let Some(devices) = (match t.get("devices") {
        Some(toml::Value::Table(d)) => Some(d),
        Some(v) => {
            problems.push(Problem {
                line: None,
                field: "devices".into(),
                message: format!("must be tables like [devices.5A-1], not {}", kind(v)),
            });
            None
        }
        None => {
            problems.push(Problem {
                line: None,
                field: "devices".into(),
                message: "missing: the file has no [devices.…] tables".into(),
            });
            None
        }
    }) else {
        return;
    };
    let known: BTreeMap<&str, u8> = (1..TRIM_R)
        .map(|id| (DEVICES[id as usize].system_name, id))
        .collect();
    for key in devices.keys() {
        if !known.contains_key(key.as_str()) {
            let hint = match key.as_str() {
                "Flaps" => "the flaps are in [flaps]".to_string(),
                "Trim_R" | "Trim_P" => "the trims are in [roll_trim] and [pitch_trim]".into(),
                _ => "pins are named as in ICD Table 40: Starter, EFIS, Field_Pri, 5A-1 … 5A-13, \
                      10A-1 … 10A-6, 15A-1 … 15A-3, 3A-1, 2A-1, 2A-2"
                    .into(),
            };
            problems.push(Problem {
                line: None,
                field: format!("devices.{key}"),
                message: format!("no such pin; {hint}"),
            });
        }
    }
    for id in 1..TRIM_R {
        let name = DEVICES[id as usize].system_name;
        let path = format!("devices.{name}");
        let mut s = Section::new(devices, name, path, problems);
        let mut spec: DeviceSpec = cfg.devices[id as usize];
        set(&mut cfg.names[id as usize], s.name(DEVICE_NAME.key));
        if enable_flag_allowed(id) {
            set(&mut cfg.enabled[id as usize], s.bool(DEVICE_SHOWN.key));
        } else if s.table.is_some_and(|t| t.contains_key(DEVICE_SHOWN.key)) {
            // Accepted only as the truth, so a hand-written `true` does no harm.
            if s.bool(DEVICE_SHOWN.key) == Some(false) {
                s.problem(
                    DEVICE_SHOWN.key,
                    format!("{name} is always shown and cannot be hidden (ICD Table 23 note 1)"),
                );
            }
        }
        set(
            &mut spec.circuit_breaker,
            s.u8(DEVICE_BREAKER.key, DEVICE_BREAKER.what),
        );
        set(&mut spec.switch_id, s.switch(DEVICE_SWITCH.key));
        set(&mut spec.current_fault, s.bool(DEVICE_CURRENT_FAULT.key));
        s.finish();
        cfg.apply_device_spec(&spec);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backup::to_toml;
    use crate::protocol::message::{DeviceName, SwitchId};

    fn version() -> Version {
        Version {
            hardware_version: HardwareVersion::VpxPro,
            software_major: 3,
            software_minor: 7,
        }
    }

    /// A configured aircraft: every kind of value away from its factory setting.
    pub(crate) fn configured() -> UnitConfig {
        let mut c = UnitConfig::default();
        c.devices[6].circuit_breaker = 5;
        c.devices[6].switch_id = SwitchId::Input(3);
        c.devices[6].current_fault = true;
        c.devices[10].switch_id = SwitchId::Input(4);
        c.devices[11].switch_id = SwitchId::Input(4);
        c.devices[3].switch_id = SwitchId::Input(1);
        c.devices[17].switch_id = SwitchId::Input(2);
        c.devices[0x17].circuit_breaker = 15;
        c.devices[0x17].switch_id = SwitchId::AlwaysOn;
        c.system.overvoltage_limit = OvervoltageLimit::V32;
        c.system.secondary_alternator = Some(17);
        c.wig_wag.device_one = Some(10);
        c.wig_wag.device_two = Some(11);
        c.wig_wag.warm_up_period = 12;
        c.wig_wag.speed = 80;
        c.flap.enabled = true;
        c.flap.mode = FlapMode::PositionBased;
        c.flap.polarity = Polarity::Inverted;
        c.flap.up = 10;
        c.flap.midpoint_1 = 60;
        c.flap.midpoint_2 = 120;
        c.flap.down = 200;
        c.flap.overspeed_position = 20;
        c.flap.max_speed = 100;
        c.flap.endpoint_duration = Tenths(5);
        let flap = c.flap;
        c.apply_flap_spec(&FlapSpec {
            circuit_breaker: 9,
            ..flap
        });
        c.pitch_trim.enabled = true;
        c.pitch_trim.up = 200;
        c.pitch_trim.down = 20;
        c.pitch_trim.neutral = 110;
        c.pitch_trim.power = 60;
        c.pitch_trim.speed = 120;
        c.roll_trim.enabled = true;
        c.roll_trim.polarity = Polarity::Inverted;
        for (id, n) in [
            (0, "Flaps"),
            (6, "Strobe Lt"),
            (10, "Wig"),
            (17, "Standby Alt"),
        ] {
            c.apply_device_name(&DeviceName::new(id, n).unwrap());
        }
        // Every byte a unit may hold in a name comes back (ICD Table 21: 0–255).
        c.names[12] = *b"Caf\xe9 \x01\x7f\xffsixteen!";
        c.enabled[20] = false;
        c
    }

    use crate::protocol::message::FlapSpec;

    #[test]
    fn a_configured_unit_round_trips_through_the_file() {
        assert!(validate::whole_config(&configured()).is_empty());
        let b = Backup {
            version: version(),
            config: configured(),
        };
        let text = to_toml(&b);
        assert_eq!(from_toml(&text), Ok(b.clone()));
        // And the text is stable: a second trip writes the same bytes.
        assert_eq!(to_toml(&from_toml(&text).unwrap()), text);
    }

    #[test]
    fn a_factory_unit_round_trips_too() {
        // Factory values outside the ICD's ranges (15 A pins at 2 A, trim power 100 %)
        // are what a fresh unit reports and must come back (icd-reading R16).
        let b = Backup {
            version: version(),
            config: UnitConfig::default(),
        };
        assert_eq!(from_toml(&to_toml(&b)), Ok(b));
    }

    #[test]
    fn the_file_reads_in_real_units_and_words() {
        let text = to_toml(&Backup {
            version: version(),
            config: configured(),
        });
        for line in [
            "hardware_version = 2",
            "hardware = \"VP-X Pro\"",
            "software = \"3.7\"",
            "overvoltage_limit_volts = 32",
            "secondary_alternator = \"10A-1\"",
            "mode = \"position-based\"",
            "endpoint_duration_s = 0.5",
            "max_speed_kt = 100",
            "reduced_power_percent = 60",
            "device_one = \"5A-7\"",
            "[devices.5A-3]\nname = \"Strobe Lt\"\nshow_on_page = true\nbreaker_amps = 5\nswitch = 3\ncurrent_fault = true\n",
            "[devices.15A-1]\nname = \"\"\nshow_on_page = true\nbreaker_amps = 15\nswitch = \"always-on\"",
            "[devices.Starter]\nname = \"\"\nbreaker_amps = 5\nswitch = \"always-on\"",
            "[devices.Field_Pri]\nname = \"\"\nbreaker_amps = 5\nswitch = 1\n",
            "[devices.5A-4]\nname = \"\"\nshow_on_page = true\nbreaker_amps = 2\nswitch = \"off\"",
        ] {
            assert!(text.contains(line), "missing {line:?} in\n{text}");
        }
        // Pins are in Table 40 order, not sorted as text.
        let at = |s: &str| text.find(s).unwrap();
        assert!(at("[devices.5A-13]") < at("[devices.10A-1]"));
        assert!(at("[devices.15A-3]") < at("[devices.3A-1]"));
    }

    /// Each problem's field and words (its line is held in tests of its own).
    fn problems(text: &str) -> Vec<String> {
        from_toml(text)
            .unwrap_err()
            .into_iter()
            .map(|p| format!("{}: {}", p.field, p.message))
            .collect()
    }

    fn good_text() -> String {
        to_toml(&Backup {
            version: version(),
            config: configured(),
        })
    }

    #[test]
    fn a_toml_syntax_error_says_where() {
        let p = from_toml("format = 1\n[devices.5A-1\nname = \"x\"\n").unwrap_err();
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].line, Some(2), "{p:?}");
        assert!(
            p[0].to_string().starts_with("line 2: not valid TOML"),
            "{p:?}"
        );
    }

    #[test]
    fn every_malformed_value_is_listed_by_its_path() {
        let text = good_text()
            .replace(
                "breaker_amps = 5\nswitch = 3",
                "breaker_amps = \"five\"\nswitch = 12",
            )
            .replace("endpoint_duration_s = 0.5", "endpoint_duration_s = 0.55")
            .replace(
                "secondary_alternator = \"10A-1\"",
                "secondary_alternator = \"10A-9\"",
            )
            .replace("mode = \"position-based\"", "mode = \"positional\"")
            .replace("name = \"Strobe Lt\"", "name = \"Strobe light left wing\"")
            .replace("neutral = 110", "neutral = 110\nneutrall = 3")
            .replace("warm_up_s = 12\n", "");
        let p = problems(&text);
        let fields: Vec<&str> = p.iter().map(|s| s.split(": ").next().unwrap()).collect();
        assert_eq!(
            fields,
            [
                "system.secondary_alternator",
                "flaps.mode",
                "flaps.endpoint_duration_s",
                "pitch_trim.neutrall",
                "wig_wag.warm_up_s",
                "devices.5A-3.name",
                "devices.5A-3.breaker_amps",
                "devices.5A-3.switch",
            ],
            "{p:#?}"
        );
        assert!(
            p[0].contains("\"10A-9\" is neither \"none\" nor a pin"),
            "{}",
            p[0]
        );
        assert!(p[2].contains("not a whole number of tenths"), "{}", p[2]);
        assert!(p[5].contains("at most 16"), "{}", p[5]);
        assert!(
            p[6].contains("must be a whole number 0–255, not a string"),
            "{}",
            p[6]
        );
        assert!(p[7].contains("12 is not a switch"), "{}", p[7]);
    }

    #[test]
    fn out_of_range_values_are_judged_by_the_unit_rules_and_named_in_file_terms() {
        let text = good_text()
            .replace(
                "[devices.5A-3]\nname = \"Strobe Lt\"\nshow_on_page = true\nbreaker_amps = 5",
                "[devices.5A-3]\nname = \"Strobe Lt\"\nshow_on_page = true\nbreaker_amps = 7",
            )
            .replace("reduced_power_percent = 60", "reduced_power_percent = 95")
            .replace("endpoint_duration_s = 0.5", "endpoint_duration_s = 31.5")
            .replace("speed_kt = 80", "speed_kt = 250");
        // In the file's order: the devices come last in it.
        let p = problems(&text);
        assert_eq!(
            p,
            [
                "flaps.endpoint_duration_s: endpoint duration 31.5 s is above 30.0 s (ICD Table 16, in tenths)",
                "pitch_trim.reduced_power_percent: trim power 95 % is outside 40–90 % (ICD Table 15; 100 % is the factory value and also accepted)",
                "wig_wag.speed_kt: wig-wag speed 250 is above 200 (ICD Table 17)",
                "devices.5A-3.breaker_amps: 7 A is outside 1–5 A for 5A-3 (ICD Table 40)",
            ]
        );
    }

    #[test]
    fn cross_rules_are_checked_on_the_whole_file() {
        // The wig-wag device switched always off: the unit would refuse the WIG_WAG_SPEC.
        let text = good_text().replace(
            "[devices.5A-7]\nname = \"Wig\"\nshow_on_page = true\nbreaker_amps = 2\nswitch = 4",
            "[devices.5A-7]\nname = \"Wig\"\nshow_on_page = true\nbreaker_amps = 2\nswitch = \"off\"",
        );
        let p = problems(&text);
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(
            p[0].starts_with("wig_wag.device_one: 5A-7 (device 10) is off"),
            "{p:?}"
        );
    }

    #[test]
    fn missing_and_unknown_sections_and_pins_are_named() {
        let text = good_text()
            .replace("[devices.2A-2]", "[devices.2A-3]")
            .replace("[roll_trim]", "[roll_trimm]");
        let p = problems(&text);
        assert!(
            p.contains(&"roll_trim: missing: the file has no [roll_trim] table".to_string()),
            "{p:#?}"
        );
        assert!(
            p.iter()
                .any(|s| s.starts_with("roll_trimm: unknown section")),
            "{p:#?}"
        );
        assert!(
            p.iter().any(|s| s.starts_with("devices.2A-3: no such pin")),
            "{p:#?}"
        );
        assert!(
            p.contains(&"devices.2A-2: missing: the file has no [devices.2A-2] table".to_string()),
            "{p:#?}"
        );
        assert!(
            problems("")
                .contains(&"format: missing (format = 1); is this a vpx-efis backup?".to_string())
        );
    }

    #[test]
    fn the_always_shown_pins_cannot_be_hidden() {
        let text = good_text().replace(
            "[devices.EFIS]\nname = \"\"\n",
            "[devices.EFIS]\nname = \"\"\nshow_on_page = false\n",
        );
        assert_eq!(
            problems(&text),
            [
                "devices.EFIS.show_on_page: EFIS is always shown and cannot be hidden (ICD Table 23 note 1)"
            ]
        );
        let text = good_text().replace(
            "[devices.EFIS]\nname = \"\"\n",
            "[devices.EFIS]\nname = \"\"\nshow_on_page = true\n",
        );
        assert!(from_toml(&text).is_ok());
    }

    #[test]
    fn names_are_bytes_up_to_sixteen() {
        let text = good_text().replace("name = \"Strobe Lt\"", "name = \"Strobe → Lt\"");
        let p = problems(&text);
        assert_eq!(p.len(), 1);
        assert!(
            p[0].starts_with("devices.5A-3.name: \"Strobe → Lt\" has '→'"),
            "{p:?}"
        );
        let text = good_text().replace("name = \"Strobe Lt\"", "name = \"Sixteen chars ok\"");
        let b = from_toml(&text).unwrap();
        assert_eq!(&b.config.names[6], b"Sixteen chars ok");
    }
}

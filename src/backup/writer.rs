//! Writing the backup file: each section's settings as the [`schema`] lists them,
//! each value in the file's words and units, after a header that says what the file
//! is. The file is written by hand rather than by `serde`, so that its sections and
//! keys keep the table's order (a map would sort `10A-1` before `2A-1`).

use toml::Value;

use super::provenance::Provenance;
use super::schema::{self, Item, Part};
use super::{Backup, FORMAT};
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{self, FLAPS, TRIM_P, TRIM_R, enable_flag_allowed};
use crate::protocol::message::{FlapMode, OvervoltageLimit, Polarity, SwitchId, TrimSpec};

/// One section's settings, each schema row with its value.
pub type Rows = Vec<(&'static Item, Value)>;

/// The rows of `items`, given their values in the same order (the array lengths must
/// agree, so a setting cannot be left out or given another's value by position).
fn rows<const N: usize>(items: &'static [Item; N], values: [Value; N]) -> Rows {
    items.iter().zip(values).collect()
}

fn int(n: impl Into<i64>) -> Value {
    Value::Integer(n.into())
}

fn text(s: impl Into<String>) -> Value {
    Value::String(s.into())
}

/// The settings' sections of a configuration in the file's order, each by its path
/// (`flaps`, `devices.5A-3`). A value the unit reports outside the ICD's encodings (a
/// switch id 12, an overvoltage code 7) is written as its raw number, so nothing the
/// unit holds is lost; [`from_toml`](super::from_toml) then refuses it by its path.
pub fn sections(cfg: &UnitConfig) -> Vec<(String, Rows)> {
    let name = |id: u8| text(name_text(&cfg.names[id as usize]));
    let volts = match cfg.system.overvoltage_limit {
        OvervoltageLimit::V16 => 16,
        OvervoltageLimit::V32 => 32,
        OvervoltageLimit::Unknown(n) => n,
    };
    let f = &cfg.flap;
    let trim = |t: &TrimSpec, name_id: u8| {
        rows(
            schema::TRIM,
            [
                name(name_id),
                Value::Boolean(t.enabled),
                text(polarity_word(t.polarity)),
                int(t.up),
                int(t.down),
                int(t.neutral),
                int(t.power),
                int(t.speed),
            ],
        )
    };
    let w = &cfg.wig_wag;
    let mut out = vec![
        (
            "system".to_string(),
            rows(
                schema::SYSTEM,
                [int(volts), text(opt_pin(cfg.system.secondary_alternator))],
            ),
        ),
        (
            "flaps".into(),
            rows(
                schema::FLAPS,
                [
                    name(FLAPS),
                    Value::Boolean(f.enabled),
                    text(mode_word(f.mode)),
                    text(polarity_word(f.polarity)),
                    int(f.up),
                    int(f.midpoint_1),
                    int(f.midpoint_2),
                    int(f.down),
                    int(f.circuit_breaker),
                    int(f.overspeed_position),
                    int(f.max_speed),
                    Value::Float(f.endpoint_duration.0 as f64 / 10.0),
                ],
            ),
        ),
        ("pitch_trim".into(), trim(&cfg.pitch_trim, TRIM_P)),
        ("roll_trim".into(), trim(&cfg.roll_trim, TRIM_R)),
        (
            "wig_wag".into(),
            rows(
                schema::WIG_WAG,
                [
                    text(opt_pin(w.device_one)),
                    text(opt_pin(w.device_two)),
                    int(w.warm_up_period),
                    int(w.speed),
                ],
            ),
        ),
    ];
    for id in 1..TRIM_R {
        let d = &cfg.devices[id as usize];
        let mut r = rows(
            schema::DEVICE,
            [
                name(id),
                Value::Boolean(cfg.enabled[id as usize]),
                int(d.circuit_breaker),
                switch_value(d.switch_id),
                Value::Boolean(d.current_fault),
            ],
        );
        // The starter, EFIS and primary field are always shown: no flag to write.
        if !enable_flag_allowed(id) {
            r.retain(|(i, _)| i.part != Part::Enable);
        }
        out.push((format!("devices.{}", pin_name(id)), r));
    }
    out
}

/// `"off"`, `1`–`10` or `"always-on"`; a number outside 1–10 that a unit reported is
/// written as it is (and refused on loading).
fn switch_value(s: SwitchId) -> Value {
    match s {
        SwitchId::Off => text("off"),
        SwitchId::Input(n) | SwitchId::Unknown(n) => int(n),
        SwitchId::AlwaysOn => text("always-on"),
    }
}

/// `[path]` and its `key = value` lines.
fn section<'a>(out: &mut String, path: &str, rows: impl IntoIterator<Item = (&'a str, Value)>) {
    out.push_str(&format!("\n[{path}]\n"));
    for (key, value) in rows {
        out.push_str(&format!("{key} = {value}\n"));
    }
}

/// The file's text: header, format, `[made]` if given, `[unit]`, then the settings.
fn file_text(b: &Backup, made: Option<&Provenance>) -> String {
    let mut out = format!("{HEADER}\nformat = {FORMAT}\n");
    if let Some(m) = made {
        section(
            &mut out,
            "made",
            [
                ("at", text(m.at.as_str())),
                ("from", text(m.from.as_str())),
                ("simulated", Value::Boolean(m.simulated)),
                ("by", text(m.by.as_str())),
            ],
        );
    }
    let v = &b.version;
    section(
        &mut out,
        "unit",
        [
            ("hardware_version", int(v.hardware_version.to_byte())),
            ("hardware", text(v.hardware_version.name())),
            (
                "software",
                text(format!("{}.{}", v.software_major, v.software_minor)),
            ),
        ],
    );
    for (path, rows) in sections(&b.config) {
        section(&mut out, &path, rows.into_iter().map(|(i, v)| (i.key, v)));
    }
    out
}

const HEADER: &str = "\
# VP-X configuration backup written by vpx-efis.
# Restore it with `vpx-efis restore --port PATH FILE`; the file is checked as a whole
# and every problem is listed before anything is sent to the unit.
# Units: breaker_amps in amps, *_s in seconds (to 0.1 s), *_kt in knots (the airspeed
# unit this EFIS sends the VP-X), *_percent in percent. Pins are named as in ICD
# Table 40. switch is \"off\", 1-10 or \"always-on\". Names are up to 16 characters.
";

/// The TOML text of a backup.
pub fn to_toml(b: &Backup) -> String {
    file_text(b, None)
}

/// The TOML text of a backup with its `[made]` section.
pub fn to_toml_made(b: &Backup, made: &Provenance) -> String {
    file_text(b, Some(made))
}

// ------------------------------------------------------------------ words ↔ values

/// What the file says for no pin.
pub(super) const NONE: &str = "none";

/// A pin by its ICD Table 40 name, as the file names it.
pub(super) fn pin_name(id: u8) -> String {
    device::device(id).map_or_else(|| id.to_string(), |d| d.system_name.to_string())
}

fn opt_pin(id: Option<u8>) -> String {
    id.map_or_else(|| NONE.to_string(), pin_name)
}

fn polarity_word(p: Polarity) -> &'static str {
    match p {
        Polarity::Standard => "standard",
        Polarity::Inverted => "inverted",
    }
}

fn mode_word(m: FlapMode) -> &'static str {
    match m {
        FlapMode::Momentary => "momentary",
        FlapMode::PositionBased => "position-based",
    }
}

/// The 16 name bytes up to the first NUL, one char per byte (Latin-1).
pub fn name_text(bytes: &[u8; 16]) -> String {
    bytes
        .iter()
        .take_while(|&&b| b != 0)
        .map(|&b| b as char)
        .collect()
}

/// What a name means: its bytes up to the first NUL, the rest zero (ICD Table 21).
/// Bytes after a NUL are never shown by anyone, so they are not part of a backup.
pub fn normalize_name(bytes: &[u8; 16]) -> [u8; 16] {
    let mut out = [0u8; 16];
    for (o, &b) in out.iter_mut().zip(bytes.iter().take_while(|&&b| b != 0)) {
        *o = b;
    }
    out
}

/// `cfg` with every name normalized, for comparing what a unit holds with a file.
pub fn normalized(cfg: &UnitConfig) -> UnitConfig {
    let mut c = cfg.clone();
    for n in c.names.iter_mut() {
        *n = normalize_name(n);
    }
    c
}

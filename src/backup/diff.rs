//! What a restore would change, in words: "5A-3 (Strobe Lt) breaker: 2 A → 5 A".
//!
//! Compared in the file's own terms (see [`writer`](super::writer)), so a change reads
//! the way the person would write it in the backup file and names the same path.

use std::fmt;

use super::Backup;
use super::schema::{self, Item, Part};
use super::writer::BackupFile;
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{DEVICES, TRIM_R};
use crate::protocol::message::{HardwareVersion, Version};

/// One setting that differs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Change {
    /// The value's path in a backup file, e.g. `devices.5A-3.breaker_amps`.
    pub path: String,
    /// Which setting, in words, e.g. `5A-3 (Strobe Lt) breaker`.
    pub setting: String,
    pub from: String,
    pub to: String,
}

impl fmt::Display for Change {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {} → {}", self.setting, self.from, self.to)
    }
}

/// The changes found so far.
struct Changes(Vec<Change>);

impl Changes {
    /// Each setting of `items` in the two sections that differs, its words given by
    /// `label` from the item's.
    fn section(
        &mut self,
        path: &str,
        items: &[Item],
        a: Option<&toml::Value>,
        b: Option<&toml::Value>,
        label: impl Fn(&Item) -> String,
    ) {
        for item in items {
            let (Some(x), Some(y)) = (
                a.and_then(|a| a.get(item.key)),
                b.and_then(|b| b.get(item.key)),
            ) else {
                // Not in the file for this pin (show_on_page of pins 1–3).
                continue;
            };
            let (from, to) = (schema::words(item, x), schema::words(item, y));
            if from != to {
                self.0.push(Change {
                    path: format!("{path}.{}", item.key),
                    setting: label(item),
                    from,
                    to,
                });
            }
        }
    }
}

/// A configuration in the file's own terms, as TOML values.
fn file_values(config: &UnitConfig) -> toml::Value {
    let version = Version {
        hardware_version: HardwareVersion::Unknown(0),
        software_major: 0,
        software_minor: 0,
    };
    let file = BackupFile::from_backup(&Backup {
        version,
        config: config.clone(),
    });
    // Plain strings, integers, floats and tables only: always a TOML value.
    toml::Value::try_from(&file).unwrap_or(toml::Value::Table(Default::default()))
}

/// Every setting that differs between `current` (what the unit holds) and `target`
/// (what a restore would write), in the order of the backup file. Names are compared by
/// what they show (up to the first NUL).
pub fn diff(current: &UnitConfig, target: &UnitConfig) -> Vec<Change> {
    let (a, b) = (file_values(current), file_values(target));
    let mut out = Changes(Vec::new());
    let whole = |i: &Item| i.words.to_string();
    for (section, items) in [("system", schema::SYSTEM), ("flaps", schema::FLAPS)] {
        out.section(section, items, a.get(section), b.get(section), whole);
    }
    for (section, words) in [("pitch_trim", "pitch trim"), ("roll_trim", "roll trim")] {
        out.section(
            section,
            schema::TRIM,
            a.get(section),
            b.get(section),
            |i: &Item| format!("{words} {}", i.words),
        );
    }
    out.section(
        "wig_wag",
        schema::WIG_WAG,
        a.get("wig_wag"),
        b.get("wig_wag"),
        whole,
    );
    for id in 1..TRIM_R {
        let pin = DEVICES[id as usize].system_name;
        let (d, e) = (
            a.get("devices").and_then(|d| d.get(pin)),
            b.get("devices").and_then(|d| d.get(pin)),
        );
        // The pin is named as the person will know it after the restore.
        let name = |v: Option<&toml::Value>| {
            v.and_then(|v| v.get(schema::DEVICE_NAME.key))
                .and_then(|n| n.as_str())
                .unwrap_or("")
                .to_string()
        };
        let shown = Some(name(e))
            .filter(|n| !n.is_empty())
            .unwrap_or_else(|| name(d));
        let label = if shown.is_empty() {
            pin.to_string()
        } else {
            format!("{pin} ({shown})")
        };
        out.section(
            &format!("devices.{pin}"),
            schema::DEVICE,
            d,
            e,
            |i: &Item| {
                if i.part == Part::Name {
                    format!("{pin} {}", i.words)
                } else {
                    format!("{label} {}", i.words)
                }
            },
        );
    }
    out.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::{DeviceName, SwitchId, Tenths};

    #[test]
    fn identical_configs_have_no_changes() {
        let c = UnitConfig::default();
        assert!(diff(&c, &c).is_empty());
    }

    #[test]
    fn each_change_is_said_in_words_with_units_and_its_file_path() {
        let a = UnitConfig::default();
        let mut b = a.clone();
        b.devices[6].circuit_breaker = 5;
        b.devices[6].switch_id = SwitchId::Input(3);
        b.apply_device_name(&DeviceName::new(6, "Strobe Lt").unwrap());
        b.enabled[6] = false;
        b.flap.endpoint_duration = Tenths(5);
        b.wig_wag.device_one = Some(10);
        let changes: Vec<String> = diff(&a, &b).iter().map(|c| c.to_string()).collect();
        assert_eq!(
            changes,
            [
                "flap endpoint duration: 0.0 s → 0.5 s",
                "wig-wag device one: none → 5A-7",
                "5A-3 name: (no name) → \"Strobe Lt\"",
                "5A-3 (Strobe Lt) shown on the page: yes → no",
                "5A-3 (Strobe Lt) breaker: 2 A → 5 A",
                "5A-3 (Strobe Lt) switch: always off → switch 3",
            ]
        );
        let paths: Vec<String> = diff(&a, &b).into_iter().map(|c| c.path).collect();
        assert!(paths.contains(&"devices.5A-3.breaker_amps".to_string()));
        assert!(paths.contains(&"flaps.endpoint_duration_s".to_string()));
    }

    /// Every setting of every section changed at once: each is found, in the file's
    /// order, with its path, words and units.
    #[test]
    fn every_setting_of_every_section_is_compared() {
        use crate::protocol::message::{FlapMode, OvervoltageLimit, Polarity};
        let a = UnitConfig::default();
        let mut b = a.clone();
        b.system.overvoltage_limit = OvervoltageLimit::V32;
        b.system.secondary_alternator = Some(10);
        b.names[0] = *b"Flaps\0\0\0\0\0\0\0\0\0\0\0";
        let f = &mut b.flap;
        f.enabled = !f.enabled;
        f.mode = match f.mode {
            FlapMode::Momentary => FlapMode::PositionBased,
            FlapMode::PositionBased => FlapMode::Momentary,
        };
        f.polarity = Polarity::Inverted;
        f.up += 1;
        f.midpoint_1 += 1;
        f.midpoint_2 += 1;
        f.down += 1;
        f.circuit_breaker += 1;
        f.overspeed_position += 1;
        f.max_speed += 1;
        f.endpoint_duration = Tenths(f.endpoint_duration.0 + 1);
        b.names[30] = *b"Pitch\0\0\0\0\0\0\0\0\0\0\0";
        let t = &mut b.pitch_trim;
        t.enabled = !t.enabled;
        t.polarity = Polarity::Inverted;
        t.up += 1;
        t.down += 1;
        t.neutral += 1;
        t.power -= 1;
        t.speed += 1;
        b.roll_trim.speed += 1;
        let w = &mut b.wig_wag;
        w.device_one = Some(10);
        w.device_two = Some(11);
        w.warm_up_period += 1;
        w.speed += 1;
        b.devices[1].current_fault = !b.devices[1].current_fault;
        b.enabled[6] = false;
        let changes: Vec<String> = diff(&a, &b)
            .iter()
            .map(|c| format!("{} = {c}", c.path))
            .collect();
        assert_eq!(changes, EVERY);
    }

    const EVERY: &[&str] = &[
        "system.overvoltage_limit_volts = overvoltage limit: 16 V → 32 V",
        "system.secondary_alternator = secondary alternator: none → 5A-7",
        "flaps.name = flaps name: (no name) → \"Flaps\"",
        "flaps.enabled = flaps fitted: no → yes",
        "flaps.mode = flap mode: momentary → position-based",
        "flaps.polarity = flap motor polarity: standard → inverted",
        "flaps.up = flap up position: 0 → 1",
        "flaps.midpoint_1 = flap midpoint 1: 0 → 1",
        "flaps.midpoint_2 = flap midpoint 2: 0 → 1",
        "flaps.down = flap down position: 0 → 1",
        "flaps.breaker_amps = flap breaker: 7 A → 8 A",
        "flaps.overspeed_position = flap overspeed position: 0 → 1",
        "flaps.max_speed_kt = flap max speed: 0 kt → 1 kt",
        "flaps.endpoint_duration_s = flap endpoint duration: 0.0 s → 0.1 s",
        "pitch_trim.name = pitch trim name: (no name) → \"Pitch\"",
        "pitch_trim.enabled = pitch trim fitted: no → yes",
        "pitch_trim.polarity = pitch trim motor polarity: standard → inverted",
        "pitch_trim.up = pitch trim up position: 0 → 1",
        "pitch_trim.down = pitch trim down position: 0 → 1",
        "pitch_trim.neutral = pitch trim neutral position: 0 → 1",
        "pitch_trim.reduced_power_percent = pitch trim reduced power: 100 % → 99 %",
        "pitch_trim.reduce_above_kt = pitch trim reduce power above: 0 kt → 1 kt",
        "roll_trim.reduce_above_kt = roll trim reduce power above: 0 kt → 1 kt",
        "wig_wag.device_one = wig-wag device one: none → 5A-7",
        "wig_wag.device_two = wig-wag device two: none → 5A-8",
        "wig_wag.warm_up_s = wig-wag warm-up: 5 s → 6 s",
        "wig_wag.speed_kt = wig-wag speed: 70 kt → 71 kt",
        "devices.Starter.current_fault = Starter current fault checking: off → on",
        "devices.5A-3.show_on_page = 5A-3 shown on the page: yes → no",
    ];

    #[test]
    fn bytes_after_a_names_nul_are_not_a_difference() {
        let a = UnitConfig::default();
        let mut b = a.clone();
        b.names[4] = *b"\0garbage........";
        assert!(diff(&a, &b).is_empty());
    }
}

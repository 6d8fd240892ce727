//! What a restore would change, in words: "5A-3 (Strobe Lt) breaker: 2 A → 5 A".
//!
//! Compared in the file's own terms (see [`writer`](super::writer)), so a change reads
//! the way the person would write it in the backup file and names the same path.

use std::fmt;

use super::schema::{self, Item, Part};
use super::writer::{Rows, sections};
use crate::protocol::config::UnitConfig;

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

/// Every setting that differs between `current` (what the unit holds) and `target`
/// (what a restore would write), in the order of the backup file. Names are compared by
/// what they show (up to the first NUL).
pub fn diff(current: &UnitConfig, target: &UnitConfig) -> Vec<Change> {
    let mut out = Vec::new();
    for ((path, a), (_, b)) in sections(current).iter().zip(&sections(target)) {
        let label = |item: &Item| match path.strip_prefix("devices.") {
            // The pin is named as the person will know it after the restore.
            Some(pin) if item.part != Part::Name => match Some(name_of(b))
                .filter(|n| !n.is_empty())
                .unwrap_or_else(|| name_of(a))
            {
                n if n.is_empty() => format!("{pin} {}", item.words),
                n => format!("{pin} ({n}) {}", item.words),
            },
            Some(pin) => format!("{pin} {}", item.words),
            None if path == "pitch_trim" => format!("pitch trim {}", item.words),
            None if path == "roll_trim" => format!("roll trim {}", item.words),
            None => item.words.to_string(),
        };
        for ((item, x), (_, y)) in a.iter().zip(b) {
            let (from, to) = (schema::words(item, x), schema::words(item, y));
            if from != to {
                out.push(Change {
                    path: format!("{path}.{}", item.key),
                    setting: label(item),
                    from,
                    to,
                });
            }
        }
    }
    out
}

/// The name a section's rows hold, or "".
fn name_of(rows: &Rows) -> String {
    rows.iter()
        .find(|(i, _)| i.part == Part::Name)
        .and_then(|(_, v)| v.as_str())
        .unwrap_or("")
        .to_string()
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

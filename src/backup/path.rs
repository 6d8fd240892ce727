//! Where a value the §6.2 rules name (`devices[23].circuit_breaker`) is in the backup
//! file (`devices.15A-1.breaker_amps`), so a problem is said in the file's terms.

use super::schema::{self, Item};
use super::writer::pin_name;
use crate::protocol::device::{FLAPS, TRIM_P, TRIM_R};

/// A `validate::whole_config` path (`devices[23].circuit_breaker`) as the path of the
/// same value in the file (`devices.15A-1.breaker_amps`), by the [`schema`] table.
pub fn file_path(config_path: &str) -> String {
    let (head, field) = config_path.split_once('.').unwrap_or((config_path, ""));
    let (section, items): (String, &[Item]) = if let Some(i) = head
        .strip_prefix("devices[")
        .and_then(|r| r.strip_suffix(']'))
        .and_then(|n| n.parse::<u8>().ok())
    {
        match i {
            FLAPS => ("flaps".into(), schema::FLAPS),
            TRIM_R => ("roll_trim".into(), schema::TRIM),
            TRIM_P => ("pitch_trim".into(), schema::TRIM),
            i => (format!("devices.{}", pin_name(i)), schema::DEVICE),
        }
    } else {
        match head {
            "system" => ("system".into(), schema::SYSTEM),
            "flap" => ("flaps".into(), schema::FLAPS),
            "pitch_trim" | "roll_trim" => (head.to_string(), schema::TRIM),
            "wig_wag" => ("wig_wag".into(), schema::WIG_WAG),
            other => (other.to_string(), &[]),
        }
    };
    let field = match items.iter().find(|i| !i.spec.is_empty() && i.spec == field) {
        Some(i) => i.key,
        None if schema::NOT_IN_FILE.contains(&field) => "",
        None => field,
    };
    if field.is_empty() {
        section
    } else {
        format!("{section}.{field}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_whole_config_path_has_a_place_in_the_file() {
        for (from, to) in [
            ("devices[6].circuit_breaker", "devices.5A-3.breaker_amps"),
            ("devices[2].switch_id", "devices.EFIS.switch"),
            (
                "devices[3].current_fault",
                "devices.Field_Pri.current_fault",
            ),
            ("devices[9].device_id", "devices.5A-6"),
            ("system.overvoltage_limit", "system.overvoltage_limit_volts"),
            ("system.secondary_alternator", "system.secondary_alternator"),
            ("flap.midpoint_1", "flaps.midpoint_1"),
            ("flap.circuit_breaker", "flaps.breaker_amps"),
            ("flap.max_speed", "flaps.max_speed_kt"),
            ("flap.endpoint_duration", "flaps.endpoint_duration_s"),
            ("pitch_trim.power", "pitch_trim.reduced_power_percent"),
            ("pitch_trim.speed", "pitch_trim.reduce_above_kt"),
            ("roll_trim.trim_type", "roll_trim"),
            ("wig_wag.device_two", "wig_wag.device_two"),
            ("wig_wag.warm_up_period", "wig_wag.warm_up_s"),
            ("wig_wag.speed", "wig_wag.speed_kt"),
        ] {
            assert_eq!(file_path(from), to, "{from}");
        }
    }
}

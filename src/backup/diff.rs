//! What a restore would change, in words: "5A-3 (Strobe Lt) breaker: 2 A → 5 A".
//!
//! Compared in the file's own terms (see [`format`](super::format)), so a change reads
//! the way the person would write it in the backup file and names the same path.

use std::fmt;

use super::format::{Backup, BackupFile, DeviceSection, Switch, TrimSection};
use crate::protocol::config::UnitConfig;
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

struct Out(Vec<Change>);

impl Out {
    fn ch(&mut self, path: String, setting: String, from: String, to: String) {
        if from != to {
            self.0.push(Change {
                path,
                setting,
                from,
                to,
            });
        }
    }
}

fn quoted(s: &str) -> String {
    if s.is_empty() {
        "(no name)".into()
    } else {
        format!("\"{}\"", s.escape_default())
    }
}

fn yes_no(b: bool) -> String {
    if b { "yes" } else { "no" }.into()
}

fn on_off(b: bool) -> String {
    if b { "on" } else { "off" }.into()
}

fn switch(s: Switch) -> String {
    match s {
        Switch::Off => "always off".into(),
        Switch::Input(n) => format!("switch {n}"),
        Switch::AlwaysOn => "always on".into(),
    }
}

/// Every setting that differs between `current` (what the unit holds) and `target`
/// (what a restore would write), in the order of the backup file. Names are compared by
/// what they show (up to the first NUL).
pub fn diff(current: &UnitConfig, target: &UnitConfig) -> Vec<Change> {
    let version = Version {
        hardware_version: HardwareVersion::Unknown(0),
        software_major: 0,
        software_minor: 0,
    };
    let a = BackupFile::from_backup(&Backup {
        version,
        config: current.clone(),
    });
    let b = BackupFile::from_backup(&Backup {
        version,
        config: target.clone(),
    });
    let mut out = Out(Vec::new());

    out.ch(
        "system.overvoltage_limit_volts".into(),
        "overvoltage limit".into(),
        format!("{} V", a.system.overvoltage_limit_volts),
        format!("{} V", b.system.overvoltage_limit_volts),
    );
    out.ch(
        "system.secondary_alternator".into(),
        "secondary alternator".into(),
        a.system.secondary_alternator.clone(),
        b.system.secondary_alternator.clone(),
    );

    let (f, g) = (&a.flaps, &b.flaps);
    let p = |k: &str| format!("flaps.{k}");
    out.ch(
        p("name"),
        "flaps name".into(),
        quoted(&f.name),
        quoted(&g.name),
    );
    out.ch(
        p("enabled"),
        "flaps fitted".into(),
        yes_no(f.enabled),
        yes_no(g.enabled),
    );
    out.ch(
        p("mode"),
        "flap mode".into(),
        f.mode.clone(),
        g.mode.clone(),
    );
    out.ch(
        p("polarity"),
        "flap motor polarity".into(),
        f.polarity.clone(),
        g.polarity.clone(),
    );
    for (k, words, x, y) in [
        ("up", "flap up position", f.up, g.up),
        ("midpoint_1", "flap midpoint 1", f.midpoint_1, g.midpoint_1),
        ("midpoint_2", "flap midpoint 2", f.midpoint_2, g.midpoint_2),
        ("down", "flap down position", f.down, g.down),
        (
            "overspeed_position",
            "flap overspeed position",
            f.overspeed_position,
            g.overspeed_position,
        ),
    ] {
        out.ch(p(k), words.into(), x.to_string(), y.to_string());
    }
    out.ch(
        p("breaker_amps"),
        "flap breaker".into(),
        format!("{} A", f.breaker_amps),
        format!("{} A", g.breaker_amps),
    );
    out.ch(
        p("max_speed_kt"),
        "flap max speed".into(),
        format!("{} kt", f.max_speed_kt),
        format!("{} kt", g.max_speed_kt),
    );
    out.ch(
        p("endpoint_duration_s"),
        "flap endpoint duration".into(),
        format!("{:.1} s", f.endpoint_duration_s),
        format!("{:.1} s", g.endpoint_duration_s),
    );

    trim(
        &mut out,
        "pitch_trim",
        "pitch trim",
        &a.pitch_trim,
        &b.pitch_trim,
    );
    trim(
        &mut out,
        "roll_trim",
        "roll trim",
        &a.roll_trim,
        &b.roll_trim,
    );

    let (w, x) = (&a.wig_wag, &b.wig_wag);
    out.ch(
        "wig_wag.device_one".into(),
        "wig-wag device one".into(),
        w.device_one.clone(),
        x.device_one.clone(),
    );
    out.ch(
        "wig_wag.device_two".into(),
        "wig-wag device two".into(),
        w.device_two.clone(),
        x.device_two.clone(),
    );
    out.ch(
        "wig_wag.warm_up_s".into(),
        "wig-wag warm-up".into(),
        format!("{} s", w.warm_up_s),
        format!("{} s", x.warm_up_s),
    );
    out.ch(
        "wig_wag.speed_kt".into(),
        "wig-wag speed".into(),
        format!("{} kt", w.speed_kt),
        format!("{} kt", x.speed_kt),
    );

    for ((pin, d), (_, e)) in a.devices.0.iter().zip(&b.devices.0) {
        device(&mut out, pin, d, e);
    }
    out.0
}

fn trim(out: &mut Out, key: &str, words: &str, t: &TrimSection, u: &TrimSection) {
    let p = |k: &str| format!("{key}.{k}");
    out.ch(
        p("name"),
        format!("{words} name"),
        quoted(&t.name),
        quoted(&u.name),
    );
    out.ch(
        p("enabled"),
        format!("{words} fitted"),
        yes_no(t.enabled),
        yes_no(u.enabled),
    );
    out.ch(
        p("polarity"),
        format!("{words} motor polarity"),
        t.polarity.clone(),
        u.polarity.clone(),
    );
    for (k, w, x, y) in [
        ("up", "up position", t.up, u.up),
        ("down", "down position", t.down, u.down),
        ("neutral", "neutral position", t.neutral, u.neutral),
    ] {
        out.ch(p(k), format!("{words} {w}"), x.to_string(), y.to_string());
    }
    out.ch(
        p("reduced_power_percent"),
        format!("{words} reduced power"),
        format!("{} %", t.reduced_power_percent),
        format!("{} %", u.reduced_power_percent),
    );
    out.ch(
        p("reduce_above_kt"),
        format!("{words} reduce power above"),
        format!("{} kt", t.reduce_above_kt),
        format!("{} kt", u.reduce_above_kt),
    );
}

fn device(out: &mut Out, pin: &str, d: &DeviceSection, e: &DeviceSection) {
    // The pin is named as the person will know it after the restore.
    let shown = if e.name.is_empty() { &d.name } else { &e.name };
    let label = if shown.is_empty() {
        pin.to_string()
    } else {
        format!("{pin} ({shown})")
    };
    let p = |k: &str| format!("devices.{pin}.{k}");
    out.ch(
        p("name"),
        format!("{pin} name"),
        quoted(&d.name),
        quoted(&e.name),
    );
    if let (Some(x), Some(y)) = (d.show_on_page, e.show_on_page) {
        out.ch(
            p("show_on_page"),
            format!("{label} shown on the page"),
            yes_no(x),
            yes_no(y),
        );
    }
    out.ch(
        p("breaker_amps"),
        format!("{label} breaker"),
        format!("{} A", d.breaker_amps),
        format!("{} A", e.breaker_amps),
    );
    out.ch(
        p("switch"),
        format!("{label} switch"),
        switch(d.switch),
        switch(e.switch),
    );
    out.ch(
        p("current_fault"),
        format!("{label} current fault checking"),
        on_off(d.current_fault),
        on_off(e.current_fault),
    );
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

    #[test]
    fn bytes_after_a_names_nul_are_not_a_difference() {
        let a = UnitConfig::default();
        let mut b = a.clone();
        b.names[4] = *b"\0garbage........";
        assert!(diff(&a, &b).is_empty());
    }
}

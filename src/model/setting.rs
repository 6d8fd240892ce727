//! One configuration setting of the unit, named so that it can be forgotten when a
//! write to it goes unanswered and asked for again until the unit says what it holds.

use super::TrimKind;
use crate::protocol::device::{self, FLAPS, SYSTEM_SPEC_ID, TRIM_P, TRIM_R, WIG_WAG_SPEC_ID};
use crate::protocol::message::{
    DeviceEnable, DeviceNameQuery, DeviceSpecQuery, EnableFlag, Message, TrimType,
};

/// A setting the unit holds, by the message that sets it and the query that reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Setting {
    /// DEVICE_SPEC of a pin 1–28 (ICD Table 13).
    DeviceSpec(u8),
    /// DEVICE_NAME (Table 21).
    Name(u8),
    /// DEVICE_ENABLE of a pin 4–28 (Table 23).
    Enable(u8),
    /// SYSTEM_SPEC (Table 14), read with DEVICE_SPEC_QUERY 253.
    System,
    /// FLAP_SPEC (Table 16), read with DEVICE_SPEC_QUERY 0.
    Flaps,
    /// TRIM_SPEC (Table 15), read with DEVICE_SPEC_QUERY 30 (pitch) or 29 (roll).
    Trim(TrimKind),
    /// WIG_WAG_SPEC (Table 17), read with DEVICE_SPEC_QUERY 254.
    WigWag,
}

impl Setting {
    /// Every setting the page reads at connect and a backup holds: DEVICE_SPEC of pins
    /// 1–28, FLAP_SPEC, both TRIM_SPECs, SYSTEM_SPEC, WIG_WAG_SPEC, the DEVICE_NAME of
    /// every device 0–30 and DEVICE_ENABLE of pins 4–28 (the same set as
    /// `app::queries` asks for at connect and `setup::write::unit_config` needs).
    pub fn all() -> impl Iterator<Item = Setting> {
        let specs = (1..TRIM_R).map(Setting::DeviceSpec);
        let motors = [
            Setting::Flaps,
            Setting::Trim(TrimKind::Pitch),
            Setting::Trim(TrimKind::Roll),
            Setting::System,
            Setting::WigWag,
        ];
        let names = (0..device::DEVICE_COUNT as u8).map(Setting::Name);
        let enables = (0..device::DEVICE_COUNT as u8)
            .filter(|&id| device::enable_flag_allowed(id))
            .map(Setting::Enable);
        specs.chain(motors).chain(names).chain(enables)
    }

    /// The setting a write message sets.
    pub fn written_by(m: &Message) -> Option<Setting> {
        Some(match m {
            Message::DeviceSpec(s) => Setting::DeviceSpec(s.device_id),
            Message::DeviceName(n) => Setting::Name(n.device_id),
            Message::DeviceEnable(e) if e.flag != EnableFlag::Query => Setting::Enable(e.device_id),
            Message::SystemSpec(_) => Setting::System,
            Message::FlapSpec(_) => Setting::Flaps,
            Message::TrimSpec(t) => Setting::Trim(trim_kind(t.trim_type)),
            Message::WigWagSpec(_) => Setting::WigWag,
            _ => return None,
        })
    }

    /// The setting an answer from the unit reports. The same messages as
    /// [`written_by`](Self::written_by): the unit answers a query with the set message.
    pub fn answered_by(m: &Message) -> Option<Setting> {
        Setting::written_by(m)
    }

    /// The query whose answer says what the unit holds (ICD Tables 18, 22, 23).
    pub fn query(self) -> Message {
        let spec = |device_id| DeviceSpecQuery { device_id }.into();
        match self {
            Setting::DeviceSpec(id) => spec(id),
            Setting::Name(id) => DeviceNameQuery { device_id: id }.into(),
            Setting::Enable(id) => DeviceEnable {
                device_id: id,
                flag: EnableFlag::Query,
            }
            .into(),
            Setting::System => spec(SYSTEM_SPEC_ID),
            Setting::Flaps => spec(FLAPS),
            Setting::Trim(TrimKind::Pitch) => spec(TRIM_P),
            Setting::Trim(TrimKind::Roll) => spec(TRIM_R),
            Setting::WigWag => spec(WIG_WAG_SPEC_ID),
        }
    }

    /// "DEVICE_SPEC for 5A-3", "TRIM_SPEC (roll)", in the words of the write lines.
    pub fn name(self) -> String {
        let pin = |id: u8| {
            device::device(id).map_or_else(|| format!("device {id}"), |d| d.system_name.into())
        };
        match self {
            Setting::DeviceSpec(id) => format!("DEVICE_SPEC for {}", pin(id)),
            Setting::Name(id) => format!("DEVICE_NAME for {}", pin(id)),
            Setting::Enable(id) => format!("DEVICE_ENABLE for {}", pin(id)),
            Setting::System => "SYSTEM_SPEC".into(),
            Setting::Flaps => "FLAP_SPEC".into(),
            Setting::Trim(TrimKind::Pitch) => "TRIM_SPEC (pitch)".into(),
            Setting::Trim(TrimKind::Roll) => "TRIM_SPEC (roll)".into(),
            Setting::WigWag => "WIG_WAG_SPEC".into(),
        }
    }
}

/// For tests: a factory-fresh unit's answer to `setting`'s query (ICD Appendix F's
/// defaults, every name blank, every pin enabled).
#[cfg(test)]
pub(crate) fn factory_answer(setting: Setting) -> Message {
    use crate::protocol::defaults;
    use crate::protocol::message::DeviceName;
    match setting {
        Setting::DeviceSpec(id) => defaults::device_spec(id).into(),
        Setting::Name(id) => DeviceName::new(id, "").unwrap().into(),
        Setting::Enable(id) => DeviceEnable {
            device_id: id,
            flag: EnableFlag::Enabled,
        }
        .into(),
        Setting::System => defaults::system_spec().into(),
        Setting::Flaps => defaults::flap_spec().into(),
        Setting::Trim(TrimKind::Pitch) => defaults::trim_spec(TrimType::Pitch).into(),
        Setting::Trim(TrimKind::Roll) => defaults::trim_spec(TrimType::Roll).into(),
        Setting::WigWag => defaults::wig_wag_spec().into(),
    }
}

/// TRIM_SPEC's type byte: anything but roll is taken as pitch, as the model stores it.
fn trim_kind(t: TrimType) -> TrimKind {
    match t {
        TrimType::Roll => TrimKind::Roll,
        _ => TrimKind::Pitch,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::DeviceName;

    #[test]
    fn each_write_is_read_back_with_its_own_query() {
        let spec = crate::protocol::config::UnitConfig::default().devices[9];
        let s = Setting::written_by(&spec.into()).unwrap();
        assert_eq!(s, Setting::DeviceSpec(9));
        // ICD Table 18: DEVICE_SPEC_QUERY carries the device id.
        assert_eq!(s.query(), DeviceSpecQuery { device_id: 9 }.into());
        let name = Setting::written_by(&DeviceName::new(9, "GPS").unwrap().into()).unwrap();
        assert_eq!(name.query(), DeviceNameQuery { device_id: 9 }.into());
        // Table 16 note: flaps are device 0; Table 15: roll trim 29, pitch 30; Table 18:
        // the system 253, the wig-wag 254.
        for (setting, device_id) in [
            (Setting::Flaps, 0),
            (Setting::Trim(TrimKind::Roll), 29),
            (Setting::Trim(TrimKind::Pitch), 30),
            (Setting::System, 253),
            (Setting::WigWag, 254),
        ] {
            let want: Message = DeviceSpecQuery { device_id }.into();
            assert_eq!(setting.query(), want, "{setting:?}");
        }
        // A DEVICE_ENABLE query sets nothing.
        let q = DeviceEnable {
            device_id: 9,
            flag: EnableFlag::Query,
        };
        assert_eq!(Setting::written_by(&q.into()), None);
    }

    #[test]
    fn all_is_every_spec_name_and_enable_flag_once() {
        let all: Vec<Setting> = Setting::all().collect();
        let set: std::collections::BTreeSet<Setting> = all.iter().copied().collect();
        assert_eq!(set.len(), all.len(), "no setting twice");
        // 28 device specs, 5 motor/system specs, 31 names, 25 enable flags (4–28).
        assert_eq!(all.len(), 28 + 5 + 31 + 25);
        assert!(set.contains(&Setting::DeviceSpec(1)) && set.contains(&Setting::DeviceSpec(28)));
        assert!(
            !set.contains(&Setting::DeviceSpec(0)),
            "device 0 is FLAP_SPEC"
        );
        assert!(
            !set.contains(&Setting::Enable(3)),
            "pins 1–3 are always shown"
        );
        assert!(set.contains(&Setting::Name(0)) && set.contains(&Setting::Name(30)));
    }
}

//! What the setup screens show: the page and field the person is on, the values being
//! edited, and where each write to the unit stands. Pure data plus the words for it;
//! the setup flow owns and changes it, the screens in `ui::setup` only read it.
//!
//! The forms hold the ICD's own spec structs, so what is edited is exactly what is
//! sent; the words here turn their raw numbers into real units (amps, seconds, knots,
//! percent) for display.

use std::time::Duration;

use crate::backup::schema::{self, Item, Part};
use crate::model::{Model, Setting, TrimKind};
use crate::protocol::defaults;
use crate::protocol::device::{self, EFIS, STARTER, enable_flag_allowed};
use crate::protocol::message::{
    DeviceSpec, FlapMode as Mode, FlapSpec, OvervoltageLimit, Polarity, SwitchId, SystemSpec,
    TrimSpec, TrimType, WigWagSpec,
};

/// One setup screen (Tab / Shift+Tab between them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Page {
    #[default]
    Device,
    System,
    Flaps,
    PitchTrim,
    RollTrim,
    WigWag,
    Diagnostics,
    Backup,
}

impl Page {
    pub const ALL: [Page; 8] = [
        Page::Device,
        Page::System,
        Page::Flaps,
        Page::PitchTrim,
        Page::RollTrim,
        Page::WigWag,
        Page::Diagnostics,
        Page::Backup,
    ];

    pub fn index(self) -> usize {
        Page::ALL.iter().position(|&p| p == self).unwrap_or(0)
    }

    pub fn next(self) -> Page {
        Page::ALL[(self.index() + 1) % Page::ALL.len()]
    }

    pub fn prev(self) -> Page {
        Page::ALL[(self.index() + Page::ALL.len() - 1) % Page::ALL.len()]
    }

    pub fn title(self) -> &'static str {
        match self {
            Page::Device => "Device",
            Page::System => "System",
            Page::Flaps => "Flaps",
            Page::PitchTrim => "Pitch",
            Page::RollTrim => "Roll",
            Page::WigWag => "Wig-wag",
            Page::Diagnostics => "Diagnostics",
            Page::Backup => "Backup",
        }
    }

    /// The message the page's Enter sends, for the heading.
    pub fn sends(self) -> &'static str {
        match self {
            Page::Device => "DEVICE_SPEC, DEVICE_NAME, DEVICE_ENABLE",
            Page::System => "SYSTEM_SPEC",
            Page::Flaps => "FLAP_SPEC",
            Page::PitchTrim | Page::RollTrim => "TRIM_SPEC",
            Page::WigWag => "WIG_WAG_SPEC",
            Page::Diagnostics => "PING, VERSION",
            Page::Backup => "backup file, EEPROM_ERASE",
        }
    }

    pub fn fields(self) -> &'static [Field] {
        use Field::*;
        match self {
            Page::Device => &[DeviceId, Breaker, Switch, CurrentFault, Name, Shown],
            Page::System => &[Overvoltage, SecondaryAlternator],
            Page::Flaps => &[
                FlapEnabled,
                FlapMode,
                FlapPolarity,
                FlapUp,
                FlapMid1,
                FlapMid2,
                FlapDown,
                FlapOverspeedPosition,
                FlapMaxSpeed,
                FlapBreaker,
                FlapEndpointDuration,
            ],
            Page::PitchTrim | Page::RollTrim => &[
                TrimEnabled,
                TrimPolarity,
                TrimUp,
                TrimNeutral,
                TrimDown,
                TrimPower,
                TrimSpeed,
            ],
            Page::WigWag => &[WigWagOne, WigWagTwo, WigWagWarmUp, WigWagSpeed],
            Page::Diagnostics => &[Ping, Version],
            Page::Backup => &[File, SaveBackup, LoadBackup, Reread, Erase],
        }
    }

    /// Pages whose fields are a spec sent with Enter.
    pub fn is_form(self) -> bool {
        !matches!(self, Page::Diagnostics | Page::Backup)
    }

    /// The motor this page runs and calibrates.
    pub fn motor(self) -> Option<crate::model::Motor> {
        use crate::model::{Motor, TrimKind};
        match self {
            Page::Flaps => Some(Motor::Flaps),
            Page::PitchTrim => Some(Motor::Trim(TrimKind::Pitch)),
            Page::RollTrim => Some(Motor::Trim(TrimKind::Roll)),
            _ => None,
        }
    }
}

/// One row of a setup page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    DeviceId,
    Breaker,
    Switch,
    CurrentFault,
    Name,
    Shown,
    Overvoltage,
    SecondaryAlternator,
    FlapEnabled,
    FlapMode,
    FlapPolarity,
    FlapUp,
    FlapDown,
    FlapMid1,
    FlapMid2,
    FlapBreaker,
    FlapOverspeedPosition,
    FlapMaxSpeed,
    FlapEndpointDuration,
    TrimEnabled,
    TrimPolarity,
    TrimUp,
    TrimDown,
    TrimNeutral,
    TrimPower,
    TrimSpeed,
    WigWagOne,
    WigWagTwo,
    WigWagWarmUp,
    WigWagSpeed,
    Ping,
    Version,
    File,
    SaveBackup,
    LoadBackup,
    Reread,
    Erase,
}

impl Field {
    pub fn label(self) -> &'static str {
        use Field::*;
        match self {
            DeviceId => "Pin",
            Breaker => "Circuit breaker",
            Switch => "Switch",
            CurrentFault => "Current fault check",
            Name => "Name",
            Shown => "Shown on the page",
            Overvoltage => "Overvoltage limit",
            SecondaryAlternator => "Secondary alternator",
            FlapEnabled | TrimEnabled => "Fitted (enabled)",
            FlapMode => "Mode",
            FlapPolarity | TrimPolarity => "Motor polarity",
            FlapUp | TrimUp => "Up position",
            FlapDown | TrimDown => "Down position",
            FlapMid1 => "Midpoint 1",
            FlapMid2 => "Midpoint 2",
            FlapBreaker => "Circuit breaker",
            FlapOverspeedPosition => "Overspeed position",
            FlapMaxSpeed => "Max speed",
            FlapEndpointDuration => "Endpoint run-on",
            TrimNeutral => "Neutral position",
            TrimPower => "Power above speed",
            TrimSpeed => "Reduce power above",
            WigWagOne => "Device one",
            WigWagTwo => "Device two",
            WigWagWarmUp => "Warm-up",
            WigWagSpeed => "Flash from",
            Ping => "PING round trip",
            Version => "VERSION",
            File => "Backup file",
            SaveBackup => "Save a backup",
            LoadBackup => "Load a backup",
            Reread => "Re-read the unit",
            Erase => "Erase the EEPROM",
        }
    }

    /// The configuration setting the field edits ([`schema`]), or `None` for the pin
    /// number and the actions.
    pub fn item(self) -> Option<&'static Item> {
        use Field::*;
        Some(match self {
            Breaker => &schema::DEVICE_BREAKER,
            Switch => &schema::DEVICE_SWITCH,
            CurrentFault => &schema::DEVICE_CURRENT_FAULT,
            Name => &schema::DEVICE_NAME,
            Shown => &schema::DEVICE_SHOWN,
            Overvoltage => &schema::OVERVOLTAGE,
            SecondaryAlternator => &schema::SECONDARY_ALTERNATOR,
            FlapEnabled => &schema::FLAP_ENABLED,
            FlapMode => &schema::FLAP_MODE,
            FlapPolarity => &schema::FLAP_POLARITY,
            FlapUp => &schema::FLAP_UP,
            FlapDown => &schema::FLAP_DOWN,
            FlapMid1 => &schema::FLAP_MIDPOINT_1,
            FlapMid2 => &schema::FLAP_MIDPOINT_2,
            FlapBreaker => &schema::FLAP_BREAKER,
            FlapOverspeedPosition => &schema::FLAP_OVERSPEED_POSITION,
            FlapMaxSpeed => &schema::FLAP_MAX_SPEED,
            FlapEndpointDuration => &schema::FLAP_ENDPOINT_DURATION,
            TrimEnabled => &schema::TRIM_ENABLED,
            TrimPolarity => &schema::TRIM_POLARITY,
            TrimUp => &schema::TRIM_UP,
            TrimDown => &schema::TRIM_DOWN,
            TrimNeutral => &schema::TRIM_NEUTRAL,
            TrimPower => &schema::TRIM_POWER,
            TrimSpeed => &schema::TRIM_SPEED,
            WigWagOne => &schema::WIG_WAG_ONE,
            WigWagTwo => &schema::WIG_WAG_TWO,
            WigWagWarmUp => &schema::WIG_WAG_WARM_UP,
            WigWagSpeed => &schema::WIG_WAG_SPEED,
            DeviceId | Ping | Version | File | SaveBackup | LoadBackup | Reread | Erase => {
                return None;
            }
        })
    }

    /// Typed text (not digits) goes into this field.
    pub fn is_text(self) -> bool {
        matches!(self, Field::Name | Field::File)
    }

    /// Whether digits can be typed into the field (and '.' for the run-on seconds).
    /// The others are chosen with ←/→, and a digit there is refused in words.
    pub fn takes_digits(self) -> bool {
        use Field::*;
        matches!(
            self,
            Breaker
                | FlapUp
                | FlapDown
                | FlapMid1
                | FlapMid2
                | FlapOverspeedPosition
                | FlapBreaker
                | FlapMaxSpeed
                | FlapEndpointDuration
                | TrimUp
                | TrimDown
                | TrimNeutral
                | TrimPower
                | TrimSpeed
                | WigWagWarmUp
                | WigWagSpeed
        )
    }

    /// Enter does something here instead of sending the page.
    pub fn is_action(self) -> bool {
        use Field::*;
        matches!(
            self,
            Ping | Version | SaveBackup | LoadBackup | Reread | Erase
        )
    }

    /// A motor position the live FLAP_TRIM_STATUS can be captured into.
    pub fn is_position(self) -> bool {
        use Field::*;
        matches!(
            self,
            FlapUp
                | FlapDown
                | FlapMid1
                | FlapMid2
                | FlapOverspeedPosition
                | TrimUp
                | TrimDown
                | TrimNeutral
        )
    }

    /// What the field means and its range, for the line under the table.
    pub fn help(self, device_id: u8, page: Page) -> String {
        use Field::*;
        let pin = device::device(device_id);
        match self {
            DeviceId => {
                "the pin to configure, 1–28 (flaps and trims have pages of their own)".into()
            }
            Breaker => match pin {
                Some(d) => format!(
                    "{}–{} A on {} (ICD Appendix B); {} A is its factory value",
                    d.amps_min,
                    d.amps_max,
                    d.system_name,
                    defaults::device_spec(device_id).circuit_breaker
                ),
                None => "whole amps".into(),
            },
            Switch => match device_id {
                STARTER => {
                    "the starter's switch is not assignable: always on (ICD Table 40)".into()
                }
                EFIS => "off is not allowed for the EFIS (ICD Table 13 note 4)".into(),
                _ => "always off, one of the switch inputs 1–10, or always on".into(),
            },
            CurrentFault => match pin {
                Some(d) if !d.current_fault_support => {
                    format!(
                        "{} has no current fault checking (ICD Table 40)",
                        d.system_name
                    )
                }
                _ => "fault when the current exceeds the breaker (ICD Table 13)".into(),
            },
            Name => "up to 16 ASCII characters: type, or ←/→ to pick from ICD Appendix C".into(),
            Shown => {
                if enable_flag_allowed(device_id) {
                    "whether the page lists this device (DEVICE_ENABLE, pins 4–28)".into()
                } else {
                    "pins 1–3 are always shown (ICD Table 23 note 1)".into()
                }
            }
            Overvoltage => "the bus voltage the unit treats as overvoltage (ICD Table 14)".into(),
            SecondaryAlternator => {
                "the pin driving a second alternator's field: 4–25, 27–28 or none".into()
            }
            FlapEnabled | TrimEnabled => "whether the motor is installed".into(),
            FlapMode => "momentary: runs while held; position: runs to the next stop".into(),
            FlapPolarity | TrimPolarity => "swap if the motor runs the wrong way".into(),
            FlapMid1 | FlapMid2 => {
                "0 = not used; with both set, up → 1 → 2 → down in one direction (Table 16 note 4)"
                    .into()
            }
            FlapOverspeedPosition => {
                "flaps beyond this sensor value count for the overspeed alarm".into()
            }
            FlapUp | FlapDown | TrimUp | TrimDown | TrimNeutral => {
                "sensor value 0–255: run the motor there (u/d or ,/.) and press p".into()
            }
            FlapBreaker => "1–10 A (ICD Table 16)".into(),
            FlapMaxSpeed => "0–500 kt: above it flap-down is inhibited and the alarm sounds".into(),
            FlapEndpointDuration => "0.0–30.0 s of extra run at the ends (tenths)".into(),
            TrimPower | TrimSpeed if page == Page::RollTrim => {
                "ignored for roll trim (ICD Table 15 notes 5, 6)".into()
            }
            TrimPower => "40–90 % power above the speed below (100 % is the factory value)".into(),
            TrimSpeed => "0–300 kt".into(),
            WigWagOne | WigWagTwo => "pins 4–28 on a switch 1–10, or none (ICD Table 17)".into(),
            WigWagWarmUp => "5–60 s before flashing starts".into(),
            WigWagSpeed => "0–200 kt: the lights flash at this speed and above".into(),
            Ping => "Enter: send PING and time the answer".into(),
            Version => "Enter: ask VERSION again".into(),
            File => "type a path; Backspace deletes".into(),
            SaveBackup => "Enter: write what the page knows of the unit to the file".into(),
            LoadBackup => "Enter: read the file, show what would change, then apply".into(),
            Reread => "Enter: ask the unit for every spec, name and enable flag again".into(),
            Erase => "Enter: EEPROM_ERASE, after a confirmation".into(),
        }
    }
}

/// The values being edited, one form per spec page.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Forms {
    pub device: DeviceSpec,
    pub name: String,
    pub shown: bool,
    pub system: SystemSpec,
    pub flap: FlapSpec,
    pub pitch: TrimSpec,
    pub roll: TrimSpec,
    pub wig_wag: WigWagSpec,
    /// Which parts hold what the unit reported, rather than Appendix F's values
    /// standing in until it does.
    pub from_unit: FromUnit,
}

/// Per part of the forms: whether its values came from the unit. A part that did not
/// is shown as "?", cannot be edited, and no write is built on it: a DEVICE_SPEC made
/// of defaults would overwrite the pin's switch when only its breaker was changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FromUnit {
    pub device: bool,
    pub name: bool,
    pub shown: bool,
    pub system: bool,
    pub flap: bool,
    pub pitch: bool,
    pub roll: bool,
    pub wig_wag: bool,
}

impl FromUnit {
    /// Every part as the unit reported it.
    pub const ALL: FromUnit = FromUnit {
        device: true,
        name: true,
        shown: true,
        system: true,
        flap: true,
        pitch: true,
        roll: true,
        wig_wag: true,
    };

    /// Whether `field` on `page` shows a value the unit reported (fields that are not
    /// a setting, the pin number and the actions, always do).
    pub fn has(&self, field: Field, page: Page) -> bool {
        match field_setting(field, page, 0) {
            Some(Setting::DeviceSpec(_)) => self.device,
            Some(Setting::Name(_)) => self.name,
            Some(Setting::Enable(_)) => self.shown,
            Some(Setting::System) => self.system,
            Some(Setting::Flaps) => self.flap,
            Some(Setting::Trim(TrimKind::Pitch)) => self.pitch,
            Some(Setting::Trim(TrimKind::Roll)) => self.roll,
            Some(Setting::WigWag) => self.wig_wag,
            None => true,
        }
    }
}

/// What a field whose part the unit has not reported shows as its value.
pub const NOT_READ: &str = "?";
/// … and in "the unit holds".
pub const NOT_READ_HOLDS: &str = "? not yet read from the unit";

impl Default for Forms {
    fn default() -> Self {
        Forms {
            device: defaults::device_spec(4),
            name: String::new(),
            shown: true,
            system: defaults::system_spec(),
            flap: defaults::flap_spec(),
            pitch: defaults::trim_spec(TrimType::Pitch),
            roll: defaults::trim_spec(TrimType::Roll),
            wig_wag: defaults::wig_wag_spec(),
            from_unit: FromUnit::default(),
        }
    }
}

/// What the model knows the unit holds, in form shape; `None` where it has not said.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Held {
    pub device: Option<DeviceSpec>,
    pub name: Option<String>,
    pub shown: Option<bool>,
    pub system: Option<SystemSpec>,
    pub flap: Option<FlapSpec>,
    pub pitch: Option<TrimSpec>,
    pub roll: Option<TrimSpec>,
    pub wig_wag: Option<WigWagSpec>,
}

impl Held {
    pub fn from_model(model: &Model, device_id: u8) -> Held {
        let i = device_id as usize;
        Held {
            device: model.device_specs.get(i).and_then(|s| s.map(|s| s.value)),
            name: model.names.get(i).and_then(|n| n.map(|n| n.value.text())),
            shown: if enable_flag_allowed(device_id) {
                model.enabled.get(i).and_then(|e| e.map(|e| e.value))
            } else {
                Some(true)
            },
            system: model.system_spec.map(|s| s.value),
            flap: model.flap_spec.map(|s| s.value),
            pitch: model.pitch_trim_spec.map(|s| s.value),
            roll: model.roll_trim_spec.map(|s| s.value),
            wig_wag: model.wig_wag_spec.map(|s| s.value),
        }
    }

    /// The unit's value of `field` in the same words as the form's, or `None`.
    pub fn text(&self, field: Field, page: Page) -> Option<String> {
        let mut f = Forms::default();
        let known = match field.item()?.part {
            Part::Device => self.device.map(|d| f.device = d).is_some(),
            Part::Name => self.name.clone().map(|n| f.name = n).is_some(),
            Part::Enable => self.shown.map(|s| f.shown = s).is_some(),
            Part::System => self.system.map(|s| f.system = s).is_some(),
            Part::Flap => self.flap.map(|s| f.flap = s).is_some(),
            Part::Trim => {
                let t = if page == Page::RollTrim {
                    self.roll
                } else {
                    self.pitch
                };
                t.map(|t| {
                    f.pitch = t;
                    f.roll = t;
                })
                .is_some()
            }
            Part::WigWag => self.wig_wag.map(|w| f.wig_wag = w).is_some(),
        };
        known.then(|| value_text(field, page, &f))
    }
}

/// The unit's setting a field shows, so a setting left unknown by an unanswered
/// write can be marked so on every field it covers.
pub fn field_setting(field: Field, page: Page, device_id: u8) -> Option<Setting> {
    Some(match field.item()?.part {
        Part::Device => Setting::DeviceSpec(device_id),
        Part::Name => Setting::Name(device_id),
        Part::Enable => Setting::Enable(device_id),
        Part::System => Setting::System,
        Part::Flap => Setting::Flaps,
        Part::Trim => Setting::Trim(if page == Page::RollTrim {
            TrimKind::Roll
        } else {
            TrimKind::Pitch
        }),
        Part::WigWag => Setting::WigWag,
    })
}

/// What an unknown value being re-read looks like: its unit with a question mark.
pub fn unknown_text(field: Field) -> String {
    match field.item().map_or("", |i| i.unit) {
        "" => "? re-reading…".into(),
        unit => format!("? {unit} re-reading…"),
    }
}

/// A pin in words: "5A-3 (device 6)".
pub fn pin_text(id: u8) -> String {
    match device::device(id) {
        Some(d) => format!("{} (device {id})", d.system_name),
        None => format!("device {id}"),
    }
}

fn opt_pin(id: Option<u8>) -> String {
    id.map_or("none".into(), pin_text)
}

fn yes_no(b: bool) -> String {
    if b { "yes" } else { "no" }.into()
}

fn position(p: u8) -> String {
    format!("{p}")
}

fn midpoint(p: u8) -> String {
    if p == 0 {
        "0 (not used)".into()
    } else {
        position(p)
    }
}

/// Switch words as the installer reads them.
pub fn switch_text(s: SwitchId) -> String {
    match s {
        SwitchId::Off => "always off".into(),
        SwitchId::Input(n) => format!("switch {n}"),
        SwitchId::AlwaysOn => "always on".into(),
        SwitchId::Unknown(n) => format!("unknown ({n})"),
    }
}

/// A number with its field's unit from the [`schema`]: "5 A", "0.5 s".
fn in_unit(field: Field, n: impl std::fmt::Display) -> String {
    match field.item().map_or("", |i| i.unit) {
        "" => n.to_string(),
        unit => format!("{n} {unit}"),
    }
}

/// The form's value of `field`, in real units.
pub fn value_text(field: Field, page: Page, f: &Forms) -> String {
    use Field::*;
    let trim = if page == Page::RollTrim {
        &f.roll
    } else {
        &f.pitch
    };
    match field {
        DeviceId => pin_text(f.device.device_id),
        Breaker => in_unit(field, f.device.circuit_breaker),
        Switch => switch_text(f.device.switch_id),
        CurrentFault => yes_no(f.device.current_fault),
        Name => {
            if f.name.is_empty() {
                "(no name)".into()
            } else {
                format!("\"{}\"", f.name)
            }
        }
        Shown => yes_no(f.shown),
        Overvoltage => match f.system.overvoltage_limit {
            OvervoltageLimit::V16 => "16 V".into(),
            OvervoltageLimit::V32 => "32 V".into(),
            OvervoltageLimit::Unknown(n) => format!("unknown ({n})"),
        },
        SecondaryAlternator => opt_pin(f.system.secondary_alternator),
        FlapEnabled => yes_no(f.flap.enabled),
        FlapMode => match f.flap.mode {
            Mode::Momentary => "momentary".into(),
            Mode::PositionBased => "position based".into(),
        },
        FlapPolarity => polarity(f.flap.polarity),
        FlapUp => position(f.flap.up),
        FlapDown => position(f.flap.down),
        FlapMid1 => midpoint(f.flap.midpoint_1),
        FlapMid2 => midpoint(f.flap.midpoint_2),
        FlapBreaker => in_unit(field, f.flap.circuit_breaker),
        FlapOverspeedPosition => position(f.flap.overspeed_position),
        FlapMaxSpeed => in_unit(field, f.flap.max_speed),
        FlapEndpointDuration => in_unit(field, format!("{:.1}", f.flap.endpoint_duration.value())),
        TrimEnabled => yes_no(trim.enabled),
        TrimPolarity => polarity(trim.polarity),
        TrimUp => position(trim.up),
        TrimDown => position(trim.down),
        TrimNeutral => position(trim.neutral),
        TrimPower => in_unit(field, trim.power),
        TrimSpeed => in_unit(field, trim.speed),
        WigWagOne => opt_pin(f.wig_wag.device_one),
        WigWagTwo => opt_pin(f.wig_wag.device_two),
        WigWagWarmUp => in_unit(field, f.wig_wag.warm_up_period),
        WigWagSpeed => in_unit(field, f.wig_wag.speed),
        Ping | Version | File | SaveBackup | LoadBackup | Reread | Erase => String::new(),
    }
}

fn polarity(p: Polarity) -> String {
    match p {
        Polarity::Standard => "standard".into(),
        Polarity::Inverted => "inverted".into(),
    }
}

/// Where one write to the unit stands. Only `Saved` means the unit acknowledged it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum WriteStatus {
    /// Waiting for the writes before it.
    Queued,
    /// Sent; waiting for the SPEC_ACK (`attempt` of `of`).
    Sending { attempt: u8, of: u8 },
    /// Acknowledged (or refused); asking the unit what it now holds.
    Rereading,
    /// Acknowledged. `holds` is what the re-read shows, `matches` whether it is what
    /// was sent.
    Saved { holds: String, matches: bool },
    /// The unit, or this program's §6.2 check before sending, refused it.
    Refused { why: String, by_unit: bool },
    /// No answer after every retry: the unit may or may not have stored it, so what
    /// it holds is unknown until the re-read (still going) is answered.
    NoAnswer,
    /// Acknowledged, but the re-read went unanswered: unknown, still re-reading.
    AckedUnread,
    /// Left unknown, then a re-read answered: what the unit holds, whether it is what
    /// was sent, and whether the write itself was acknowledged.
    ReadBack {
        holds: String,
        matches: bool,
        acked: bool,
    },
    /// Not sent because an earlier write failed.
    NotSent,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WriteLine {
    /// "DEVICE_SPEC for 5A-1", "FLAP_SPEC".
    pub what: String,
    pub status: WriteStatus,
}

/// The tone of a one-line message on the setup screens.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tone {
    Info,
    Good,
    Bad,
}

/// A question that takes the keys until answered.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum Dialog {
    #[default]
    None,
    /// EEPROM_ERASE: what is lost, whether a backup can be taken first.
    Erase {
        /// What the page does not know of the unit (so a backup would be incomplete).
        missing: Vec<String>,
        /// Set once a backup was written from this dialog.
        backed_up: Option<String>,
    },
    /// A page's writes that turn a protection off: each consequence in words. Only
    /// `y` sends them; Enter does not, so a habit of keys cannot.
    Disarm { consequences: Vec<String> },
    /// A backup file read and checked: what applying it changes.
    Load {
        file: String,
        changes: Vec<String>,
        notes: Vec<String>,
        writes: usize,
    },
}

/// A request whose answer is timed: PING, VERSION, EEPROM_ERASE.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum Diagnostic {
    #[default]
    Idle,
    Waiting {
        attempt: u8,
        of: u8,
    },
    Answered {
        after: Duration,
    },
    NoAnswer,
}

#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct SetupView {
    pub page: Page,
    /// Index into `page.fields()`.
    pub field: usize,
    pub forms: Forms,
    /// Pages with edits not yet sent (indexed by `Page::index`); the others follow
    /// the unit.
    pub edited: [bool; 8],
    /// Digits typed into the selected numeric field.
    pub typing: Option<String>,
    /// The last batch of writes, oldest first.
    pub writes: Vec<WriteLine>,
    pub message: Option<(Tone, String)>,
    pub dialog: Dialog,
    pub ping: Diagnostic,
    pub version: Diagnostic,
    pub erase: Diagnostic,
    /// The backup file path.
    pub file: String,
}

impl SetupView {
    pub fn field(&self) -> Field {
        let fields = self.page.fields();
        fields[self.field.min(fields.len() - 1)]
    }

    pub fn is_edited(&self, page: Page) -> bool {
        self.edited[page.index()]
    }
}

/// The switch ids the secondary alternator field cycles through, and similar lists.
pub fn secondary_alternator_choices() -> Vec<Option<u8>> {
    std::iter::once(None)
        .chain(
            (0..=30u8)
                .filter(|&i| device::secondary_alternator_allowed(i))
                .map(Some),
        )
        .collect()
}

pub fn wig_wag_choices() -> Vec<Option<u8>> {
    std::iter::once(None)
        .chain((0..=30u8).filter(|&i| device::wig_wag_allowed(i)).map(Some))
        .collect()
}

/// Pins the device page configures (DEVICE_SPEC takes 1–28).
pub fn device_choices() -> Vec<u8> {
    (STARTER..=28).collect()
}

/// The keys that work on this page now.
pub fn keys(sv: &SetupView) -> Vec<(&'static str, &'static str)> {
    if let Dialog::Load { .. } | Dialog::Erase { .. } | Dialog::Disarm { .. } = sv.dialog {
        return vec![("y", "confirm"), ("Esc", "cancel")];
    }
    let mut k = vec![("Tab", "page"), ("↑↓", "field")];
    match sv.page {
        Page::Diagnostics | Page::Backup => {
            k.push(("Enter", "do"));
            if sv.field().is_text() {
                k.push(("type", "file name"));
            }
        }
        page => {
            if sv.field().is_text() {
                k.push(("type", "name"));
                k.push(("←→", "Appendix C"));
            } else {
                k.push(("←→", "change"));
                if sv.field().takes_digits() {
                    k.push(("0-9", "type"));
                }
            }
            k.push(("Enter", "send"));
            match page {
                Page::Flaps | Page::PitchTrim => {
                    k.push(("u/d", "run"));
                    k.push(("p", "capture"));
                }
                Page::RollTrim => {
                    k.push((",/.", "run"));
                    k.push(("p", "capture"));
                }
                _ => {}
            }
        }
    }
    k.push((
        "Esc",
        if sv.is_edited(sv.page) {
            "discard"
        } else {
            "back"
        },
    ));
    k
}

/// "3 settings (DEVICE_SPEC 5A-3, …)": what the page has not heard, for the words
/// that refuse or warn about an incomplete backup.
pub fn missing_summary(missing: &[String]) -> String {
    format!(
        "{} setting{} ({}{})",
        missing.len(),
        if missing.len() == 1 { "" } else { "s" },
        missing
            .iter()
            .take(3)
            .cloned()
            .collect::<Vec<_>>()
            .join(", "),
        if missing.len() > 3 { ", …" } else { "" }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every field that edits a setting names its row of the schema, and the row's
    /// message is the setting the field is marked unknown by; the unit beside a "?"
    /// is the schema's (the overvoltage limit's "V" included).
    #[test]
    fn fields_read_their_setting_and_unit_from_the_schema() {
        for page in Page::ALL {
            for &f in page.fields() {
                let setting = field_setting(f, page, 6);
                assert_eq!(f.item().is_some(), setting.is_some(), "{f:?}");
            }
        }
        assert_eq!(
            field_setting(Field::TrimPower, Page::RollTrim, 6),
            Some(Setting::Trim(TrimKind::Roll))
        );
        assert_eq!(
            field_setting(Field::Shown, Page::Device, 6),
            Some(Setting::Enable(6))
        );
        assert_eq!(unknown_text(Field::Breaker), "? A re-reading…");
        assert_eq!(unknown_text(Field::FlapEndpointDuration), "? s re-reading…");
        assert_eq!(unknown_text(Field::Overvoltage), "? V re-reading…");
        assert_eq!(unknown_text(Field::Switch), "? re-reading…");
    }
}

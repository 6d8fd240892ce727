//! Editing the setup forms: stepping a value, typing one, picking a name, capturing a
//! motor position, and turning a page into the messages that set it. Pure functions of
//! the view's forms, the model and `now`, so each is tested without a terminal.

use std::time::Instant;

use super::view::{
    Field, Forms, Held, Page, device_choices, secondary_alternator_choices, wig_wag_choices,
};
use crate::loads::LoadCircuit;
use crate::loads::wiring::breaker_words;
use crate::model::Model;
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{self, enable_flag_allowed};
use crate::protocol::message::{
    DeviceEnable, DeviceName, EnableFlag, FlapMode as Mode, Message, OvervoltageLimit, Polarity,
    SwitchId, Tenths, TrimSpec, TrimType,
};
use crate::protocol::names::PIN_NAMES;
use crate::protocol::validate;

/// Copies what the unit holds into the page's form. On a page without edits every
/// part follows the unit, and a part it has not reported (or that a lost write left
/// unknown) is marked not from the unit. On an edited page only the parts not yet
/// from the unit fill in as the unit answers: they could not be edited meanwhile.
pub fn load(forms: &mut Forms, page: Page, model: &Model, edited: bool) {
    fn follow<T>(value: &mut T, from_unit: &mut bool, held: Option<T>, edited: bool) {
        if edited && *from_unit {
            return;
        }
        *from_unit = held.is_some();
        if let Some(h) = held {
            *value = h;
        }
    }
    let held = Held::from_model(model, forms.device.device_id);
    let f = &mut forms.from_unit;
    match page {
        Page::Device => {
            follow(&mut forms.device, &mut f.device, held.device, edited);
            follow(&mut forms.name, &mut f.name, held.name, edited);
            follow(&mut forms.shown, &mut f.shown, held.shown, edited);
        }
        Page::System => follow(&mut forms.system, &mut f.system, held.system, edited),
        Page::Flaps => follow(&mut forms.flap, &mut f.flap, held.flap, edited),
        Page::PitchTrim => follow(&mut forms.pitch, &mut f.pitch, held.pitch, edited),
        Page::RollTrim => follow(&mut forms.roll, &mut f.roll, held.roll, edited),
        Page::WigWag => follow(&mut forms.wig_wag, &mut f.wig_wag, held.wig_wag, edited),
        Page::Diagnostics | Page::Backup => {}
    }
}

/// Puts a device on the device page with the unit's values; a part the unit has not
/// reported keeps Appendix F's values underneath, shown as not read.
pub fn select_device(forms: &mut Forms, id: u8, model: &Model) {
    forms.device = crate::protocol::defaults::device_spec(id);
    forms.name = String::new();
    forms.shown = true;
    load(forms, Page::Device, model, false);
}

/// Why `field` cannot be edited or sent yet: the unit has not reported its part, so
/// the form holds no value of the unit's to start from. `None` when it can.
pub fn not_read(forms: &Forms, page: Page, field: Field) -> Option<String> {
    if forms.from_unit.has(field, page) {
        return None;
    }
    let setting = super::view::field_setting(field, page, forms.device.device_id)?;
    Some(format!(
        "{} not yet read from the unit — re-reading; try again when it answers",
        setting.name()
    ))
}

/// The first field of `page` whose part the unit has not reported, in words.
fn page_not_read(forms: &Forms, page: Page) -> Option<String> {
    page.fields().iter().find_map(|&f| not_read(forms, page, f))
}

fn cycle<T: PartialEq + Copy>(choices: &[T], current: T, step: i32) -> T {
    let n = choices.len() as i32;
    let i = choices.iter().position(|&c| c == current).unwrap_or(0) as i32;
    choices[((i + step).rem_euclid(n)) as usize]
}

fn step_u8(v: u8, step: i32, lo: u8, hi: u8) -> u8 {
    (v as i32 + step).clamp(lo as i32, hi as i32) as u8
}

fn step_u16(v: u16, step: i32, lo: u16, hi: u16) -> u16 {
    (v as i32 + step).clamp(lo as i32, hi as i32) as u16
}

fn trim_mut(forms: &mut Forms, page: Page) -> &mut TrimSpec {
    if page == Page::RollTrim {
        &mut forms.roll
    } else {
        &mut forms.pitch
    }
}

/// ←/→ on a field: the next or previous value within its range (choices wrap). Returns
/// a refusal in words for a field that cannot change, and `Ok(true)` when the device
/// page moved to another pin (its form was reloaded).
pub fn adjust(
    forms: &mut Forms,
    page: Page,
    field: Field,
    step: i32,
    model: &Model,
) -> Result<bool, String> {
    use Field::*;
    let id = forms.device.device_id;
    let pin = device::device(id);
    match field {
        DeviceId => {
            let next = cycle(&device_choices(), id, step.signum());
            select_device(forms, next, model);
            return Ok(true);
        }
        Breaker => {
            let d = pin.ok_or("no such pin")?;
            forms.device.circuit_breaker =
                step_u8(forms.device.circuit_breaker, step, d.amps_min, d.amps_max);
        }
        Switch => {
            if !pin.is_some_and(|d| d.switch_assignable()) {
                return Err(field.help(id, page));
            }
            let all: Vec<SwitchId> = (0..=11).map(SwitchId::from_byte).collect();
            forms.device.switch_id = cycle(&all, forms.device.switch_id, step.signum());
        }
        CurrentFault => {
            if !pin.is_some_and(|d| d.current_fault_support) {
                return Err(field.help(id, page));
            }
            forms.device.current_fault = !forms.device.current_fault;
        }
        Name => {
            let i = PIN_NAMES.iter().position(|&n| n == forms.name);
            let next = match i {
                Some(i) => (i as i32 + step.signum()).rem_euclid(PIN_NAMES.len() as i32) as usize,
                None if step > 0 => 0,
                None => PIN_NAMES.len() - 1,
            };
            forms.name = PIN_NAMES[next].to_string();
        }
        Shown => {
            if !enable_flag_allowed(id) {
                return Err(field.help(id, page));
            }
            forms.shown = !forms.shown;
        }
        Overvoltage => {
            forms.system.overvoltage_limit = match forms.system.overvoltage_limit {
                OvervoltageLimit::V16 => OvervoltageLimit::V32,
                _ => OvervoltageLimit::V16,
            }
        }
        SecondaryAlternator => {
            forms.system.secondary_alternator = cycle(
                &secondary_alternator_choices(),
                forms.system.secondary_alternator,
                step.signum(),
            )
        }
        FlapEnabled => forms.flap.enabled = !forms.flap.enabled,
        FlapMode => {
            forms.flap.mode = match forms.flap.mode {
                Mode::Momentary => Mode::PositionBased,
                _ => Mode::Momentary,
            }
        }
        FlapPolarity => forms.flap.polarity = flip(forms.flap.polarity),
        FlapUp => forms.flap.up = step_u8(forms.flap.up, step, 0, 255),
        FlapDown => forms.flap.down = step_u8(forms.flap.down, step, 0, 255),
        FlapMid1 => forms.flap.midpoint_1 = step_u8(forms.flap.midpoint_1, step, 0, 255),
        FlapMid2 => forms.flap.midpoint_2 = step_u8(forms.flap.midpoint_2, step, 0, 255),
        FlapOverspeedPosition => {
            forms.flap.overspeed_position = step_u8(forms.flap.overspeed_position, step, 0, 255)
        }
        FlapBreaker => {
            forms.flap.circuit_breaker = step_u8(
                forms.flap.circuit_breaker,
                step,
                *validate::FLAP_BREAKER_RANGE.start(),
                *validate::FLAP_BREAKER_RANGE.end(),
            )
        }
        FlapMaxSpeed => {
            forms.flap.max_speed =
                step_u16(forms.flap.max_speed, step, 0, validate::FLAP_MAX_SPEED_MAX)
        }
        FlapEndpointDuration => {
            forms.flap.endpoint_duration = Tenths(step_u16(
                forms.flap.endpoint_duration.0,
                step,
                0,
                validate::FLAP_ENDPOINT_DURATION_MAX,
            ))
        }
        TrimEnabled => {
            let t = trim_mut(forms, page);
            t.enabled = !t.enabled;
        }
        TrimPolarity => {
            let t = trim_mut(forms, page);
            t.polarity = flip(t.polarity);
        }
        TrimUp => {
            let t = trim_mut(forms, page);
            t.up = step_u8(t.up, step, 0, 255);
        }
        TrimDown => {
            let t = trim_mut(forms, page);
            t.down = step_u8(t.down, step, 0, 255);
        }
        TrimNeutral => {
            let t = trim_mut(forms, page);
            t.neutral = step_u8(t.neutral, step, 0, 255);
        }
        TrimPower | TrimSpeed if page == Page::RollTrim => return Err(field.help(id, page)),
        TrimPower => {
            let t = trim_mut(forms, page);
            // 100 is the factory value: stepping from it lands in the range.
            let lo = *validate::TRIM_POWER_RANGE.start();
            let hi = *validate::TRIM_POWER_RANGE.end();
            t.power = step_u8(t.power.min(hi + 1), step, lo, hi);
        }
        TrimSpeed => {
            let t = trim_mut(forms, page);
            t.speed = step_u16(t.speed, step, 0, validate::TRIM_SPEED_MAX);
        }
        WigWagOne => {
            forms.wig_wag.device_one =
                cycle(&wig_wag_choices(), forms.wig_wag.device_one, step.signum())
        }
        WigWagTwo => {
            forms.wig_wag.device_two =
                cycle(&wig_wag_choices(), forms.wig_wag.device_two, step.signum())
        }
        WigWagWarmUp => {
            forms.wig_wag.warm_up_period = step_u8(
                forms.wig_wag.warm_up_period,
                step,
                *validate::WIG_WAG_WARM_UP_RANGE.start(),
                *validate::WIG_WAG_WARM_UP_RANGE.end(),
            )
        }
        WigWagSpeed => {
            forms.wig_wag.speed = step_u8(forms.wig_wag.speed, step, 0, validate::WIG_WAG_SPEED_MAX)
        }
        _ => return Err("Enter does this one".into()),
    }
    Ok(false)
}

fn flip(p: Polarity) -> Polarity {
    match p {
        Polarity::Standard => Polarity::Inverted,
        Polarity::Inverted => Polarity::Standard,
    }
}

/// Sets `field` from typed text. Not clamped: a value outside the range is kept so
/// the §6.2 check can say why it is refused.
pub fn set_typed(forms: &mut Forms, page: Page, field: Field, text: &str) {
    use Field::*;
    let n: u32 = if field == FlapEndpointDuration {
        // Seconds with one decimal, stored in tenths.
        let secs: f64 = text.parse().unwrap_or(0.0);
        (secs * 10.0).round().clamp(0.0, u16::MAX as f64) as u32
    } else {
        text.parse::<u32>().unwrap_or(0)
    };
    let b = n.min(255) as u8;
    let w = n.min(u16::MAX as u32) as u16;
    match field {
        Breaker => forms.device.circuit_breaker = b,
        FlapUp => forms.flap.up = b,
        FlapDown => forms.flap.down = b,
        FlapMid1 => forms.flap.midpoint_1 = b,
        FlapMid2 => forms.flap.midpoint_2 = b,
        FlapOverspeedPosition => forms.flap.overspeed_position = b,
        FlapBreaker => forms.flap.circuit_breaker = b,
        FlapMaxSpeed => forms.flap.max_speed = w,
        FlapEndpointDuration => forms.flap.endpoint_duration = Tenths(w),
        TrimUp => trim_mut(forms, page).up = b,
        TrimDown => trim_mut(forms, page).down = b,
        TrimNeutral => trim_mut(forms, page).neutral = b,
        TrimPower => trim_mut(forms, page).power = b,
        TrimSpeed => trim_mut(forms, page).speed = w,
        WigWagWarmUp => forms.wig_wag.warm_up_period = b,
        WigWagSpeed => forms.wig_wag.speed = b,
        _ => {}
    }
}

/// Captures the live motor position into a position field. The words say what was
/// captured, or why nothing was.
pub fn capture(
    forms: &mut Forms,
    page: Page,
    field: Field,
    model: &Model,
    now: Instant,
) -> Result<String, String> {
    use crate::model::Motor;
    let Some(motor) = page.motor() else {
        return Err("p captures a motor position on the flaps and trim pages".into());
    };
    if !field.is_position() {
        return Err(format!(
            "select the up, down, {} field first (↑/↓), then press p",
            if motor == Motor::Flaps {
                "midpoint or overspeed"
            } else {
                "neutral"
            }
        ));
    }
    if let Some(why) = not_read(forms, page, field) {
        return Err(why);
    }
    let Some(ft) = model.live_flap_trim(now) else {
        return Err("no live FLAP_TRIM_STATUS: the position is not known".into());
    };
    let pos = ft.position(motor.axis());
    set_typed(forms, page, field, &pos.to_string());
    Ok(format!(
        "{} set to the {} position {pos}; Enter sends it",
        field.label().to_lowercase(),
        motor.name()
    ))
}

/// The messages that take the unit from what it holds to the page's form, in the
/// order they are sent. Refused in words when a part of the page never came from the
/// unit: whatever the form holds there is a stand-in, not a value to write. A part a
/// lost write left unknown is sent as edited: the edit was made on the unit's values.
pub fn messages(forms: &Forms, page: Page, model: &Model) -> Result<Vec<Message>, String> {
    if let Some(why) = page_not_read(forms, page) {
        return Err(format!("nothing sent: {why}"));
    }
    let held = Held::from_model(model, forms.device.device_id);
    let mut out: Vec<Message> = Vec::new();
    match page {
        Page::Device => {
            let id = forms.device.device_id;
            if held.device != Some(forms.device) {
                out.push(forms.device.into());
            }
            if held.name.as_deref() != Some(forms.name.as_str()) {
                // Decision: an empty name is refused, not sent; a name is cleared only
                // by EEPROM_ERASE (Appendix F), never by a field left empty.
                if forms.name.is_empty() {
                    return Err(format!(
                        "nothing sent: an empty name is refused (the unit keeps \"{}\"); \
                         type a name, or pick one with ←/→",
                        held.name.as_deref().unwrap_or_default()
                    ));
                }
                let name = DeviceName::new(id, &forms.name)
                    .ok_or("a name is at most 16 ASCII characters (ICD Table 21)")?;
                out.push(name.into());
            }
            if enable_flag_allowed(id) && held.shown != Some(forms.shown) {
                out.push(
                    DeviceEnable {
                        device_id: id,
                        flag: if forms.shown {
                            EnableFlag::Enabled
                        } else {
                            EnableFlag::Disabled
                        },
                    }
                    .into(),
                );
            }
        }
        Page::System if held.system != Some(forms.system) => out.push(forms.system.into()),
        Page::Flaps if held.flap != Some(forms.flap) => out.push(forms.flap.into()),
        Page::PitchTrim if held.pitch != Some(forms.pitch) => out.push(forms.pitch.into()),
        Page::RollTrim if held.roll != Some(forms.roll) => out.push(forms.roll.into()),
        Page::WigWag if held.wig_wag != Some(forms.wig_wag) => out.push(forms.wig_wag.into()),
        _ => {}
    }
    Ok(out)
}

/// The bus voltage from which a system counts as a 28 V one (ICD Table 14 notes 1
/// and 2), one figure with the wire rules' choice of system.
pub use crate::loads::wire::SYSTEM_28V_FROM;

/// Each breaker `messages` set above what its circuit's wire allows (AC 43.13-1B
/// ¶11-48, Table 11-3), in words naming the wire and the limit: "Strobe Lt's wire is
/// 22 AWG: AC 43.13-1B Table 11-3 allows 5 A; a 6 A breaker would not protect it".
/// `wires`: the load file's circuits. Only a breaker the write changes is asked
/// about (one the unit already holds was asked, or read, before).
pub fn over_wires(messages: &[Message], model: &Model, wires: &[LoadCircuit]) -> Vec<String> {
    let held = |id: u8| -> Option<u8> {
        if id == device::FLAPS {
            model.flap_spec.map(|s| s.value.circuit_breaker)
        } else {
            model
                .device_specs
                .get(id as usize)
                .copied()
                .flatten()
                .map(|s| s.value.circuit_breaker)
        }
    };
    messages
        .iter()
        .filter_map(|m| match m {
            Message::DeviceSpec(d) => Some((d.device_id, d.circuit_breaker)),
            Message::FlapSpec(f) => Some((device::FLAPS, f.circuit_breaker)),
            _ => None,
        })
        .filter(|&(id, breaker)| held(id) != Some(breaker))
        .filter_map(|(id, breaker)| {
            let w = wires.iter().find(|c| c.id == id)?.wire.wire?;
            (!w.protected_by(f64::from(breaker)))
                .then(|| breaker_words(&model.display_name(id), &w, breaker))
        })
        .collect()
}

/// What each of `messages` would disarm, in words naming the consequence, for a
/// confirmation before anything is sent. Empty when nothing is disarmed.
///
/// The rules, decided here:
/// - the overvoltage limit of the other system's voltage: 32 V while the live bus
///   reads below 20 V (a 14 V system: the protection would never trip), 16 V while it
///   reads 20 V or more (a 28 V system: it would trip at once and turn the alternator
///   off); with no live bus voltage any change of the limit is confirmed;
/// - flaps or a trim the unit holds enabled (fitted), disabled;
/// - current-fault checking switched off on a pin that has it: the breaker no longer
///   trips.
///
/// A breaker above the pin's rating is not here: Appendix B's range of every pin ends
/// at its rating (5A-1 at 5 A, 15A-1 at 15 A), so the §6.2 check refuses it before a
/// confirmation could be asked (`check`).
pub fn disarms(messages: &[Message], model: &Model, now: Instant) -> Vec<String> {
    let mut out = Vec::new();
    for m in messages {
        match m {
            Message::SystemSpec(s) => {
                let held = model.system_spec.map(|h| h.value.overvoltage_limit);
                if held == Some(s.overvoltage_limit) {
                    continue;
                }
                let bus = model.live_system(now).map(|st| st.main_bus_volts.value());
                if let Some(w) = overvoltage_words(s.overvoltage_limit, bus) {
                    out.push(w);
                }
            }
            Message::FlapSpec(f)
                if model.flap_spec.is_some_and(|h| h.value.enabled) && !f.enabled =>
            {
                out.push(
                    "flaps disabled: the unit holds them as fitted; disabled, it takes \
                     them as not installed and the flap switches no longer run them"
                        .into(),
                );
            }
            Message::TrimSpec(t) => {
                let (held, axis) = match t.trim_type {
                    TrimType::Roll => (model.roll_trim_spec, "roll"),
                    _ => (model.pitch_trim_spec, "pitch"),
                };
                if held.is_some_and(|h| h.value.enabled) && !t.enabled {
                    out.push(format!(
                        "{axis} trim disabled: the unit holds it as fitted; disabled, it takes \
                         it as not installed and the {axis} trim switches no longer run it"
                    ));
                }
            }
            Message::DeviceSpec(d) => {
                let held = model
                    .device_specs
                    .get(d.device_id as usize)
                    .copied()
                    .flatten();
                let supported =
                    device::device(d.device_id).is_some_and(|p| p.current_fault_support);
                if supported && held.is_some_and(|h| h.value.current_fault) && !d.current_fault {
                    out.push(format!(
                        "current fault check off on {}: it will no longer be switched off \
                         when it draws more than its {} A breaker (a short is not cut)",
                        super::view::pin_text(d.device_id),
                        d.circuit_breaker
                    ));
                }
            }
            _ => {}
        }
    }
    out
}

/// The consequence of overvoltage limit `limit` on a bus reading `bus` volts (`None`:
/// not live), or `None` when the limit suits the system.
fn overvoltage_words(limit: OvervoltageLimit, bus: Option<f32>) -> Option<String> {
    let system_28 = bus.map(|v| v >= SYSTEM_28V_FROM);
    match (limit, system_28, bus) {
        (OvervoltageLimit::V32, Some(false), Some(v)) => Some(format!(
            "overvoltage 32 V while the bus reads {v:.1} V: 32 V is for a 28 V system; on \
             this 14 V system the overvoltage protection would never trip, and a runaway \
             alternator would not be turned off"
        )),
        (OvervoltageLimit::V16, Some(true), Some(v)) => Some(format!(
            "overvoltage 16 V while the bus reads {v:.1} V: 16 V is for a 14 V system; on \
             this 28 V system the unit would flag overvoltage at once and turn the \
             alternator off"
        )),
        (OvervoltageLimit::V32, None, _) => Some(
            "overvoltage 32 V with no live bus voltage to check it against: 32 V is for a \
             28 V system; on a 14 V system the overvoltage protection would never trip"
                .into(),
        ),
        (OvervoltageLimit::V16, None, _) => Some(
            "overvoltage 16 V with no live bus voltage to check it against: 16 V is for a \
             14 V system; on a 28 V system the unit would flag overvoltage at once and \
             turn the alternator off"
                .into(),
        ),
        _ => None,
    }
}

/// The §6.2 check of each message against the unit's configuration with the ones
/// before it applied: the index of the first refused and why, in words.
pub fn check(cfg: &UnitConfig, messages: &[Message]) -> Result<(), (usize, String)> {
    let mut cfg = cfg.clone();
    for (i, m) in messages.iter().enumerate() {
        match m {
            Message::DeviceEnable(e) => {
                if validate::device_enable(&cfg, e).is_err() {
                    return Err((i, "pins 1–3 are always shown (ICD Table 23 note 1)".into()));
                }
                cfg.apply_device_enable(e);
            }
            m => {
                if let Some(Err(r)) = validate::check(&cfg, m) {
                    return Err((i, format!("{}: {}", r.error.description(), r.reason)));
                }
                validate::accept(&mut cfg, m);
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::defaults;
    use crate::protocol::message::{DeviceSpec, FlapTrimStatus, TrimType};
    use crate::setup::tests::{hear, hear_named, model};

    /// The unit reports pin `id` as it leaves the factory: Appendix F's spec, no
    /// name, shown.
    fn factory_pin(m: &mut Model, id: u8) {
        let t = Instant::now();
        hear(m, t, defaults::device_spec(id));
        hear_named(m, t, id, "");
    }

    /// Connected while the unit was silent: nothing of pin 9 heard. The form's
    /// Appendix F values are not the unit's: they are not editable and no write is
    /// built on them. As the unit answers, the parts fill in, an edited page's too.
    #[test]
    fn a_part_the_unit_never_reported_is_neither_edited_nor_written() {
        let t0 = Instant::now();
        let mut m = model();
        let mut f = Forms::default();
        select_device(&mut f, 9, &m);
        assert!(!f.from_unit.device && !f.from_unit.name && !f.from_unit.shown);
        let why = not_read(&f, Page::Device, Field::Breaker).unwrap();
        assert_eq!(
            why,
            "DEVICE_SPEC for 5A-6 not yet read from the unit — re-reading; try again when it answers"
        );
        assert_eq!(not_read(&f, Page::Device, Field::DeviceId), None);
        let refused = messages(&f, Page::Device, &m).unwrap_err();
        assert!(
            refused.starts_with("nothing sent: DEVICE_SPEC for 5A-6 not yet read"),
            "{refused}"
        );
        // The spec arrives, the name and enable flag not yet: the page may be edited
        // there, but Enter still sends nothing built on a name nobody read.
        let held = DeviceSpec {
            device_id: 9,
            circuit_breaker: 3,
            switch_id: SwitchId::Input(4),
            current_fault: true,
            switch_raw: None,
        };
        hear(&mut m, t0, held);
        load(&mut f, Page::Device, &m, false);
        assert_eq!(f.device, held, "the unit's switch, not Appendix F's off");
        assert!(f.from_unit.device && !f.from_unit.name);
        f.device.circuit_breaker = 4; // edited
        let refused = messages(&f, Page::Device, &m).unwrap_err();
        assert!(
            refused.contains(": DEVICE_NAME for 5A-6 not yet read"),
            "{refused}"
        );
        // The name and flag arrive while the page is edited: they fill in, the
        // edited breaker stays, and now only the spec goes out, with the unit's switch.
        hear_named(&mut m, t0, 9, "GPS 1");
        load(&mut f, Page::Device, &m, true);
        assert_eq!(f.name, "GPS 1");
        assert_eq!(f.device.circuit_breaker, 4, "the edit is kept");
        assert_eq!(
            messages(&f, Page::Device, &m).unwrap(),
            vec![Message::DeviceSpec(DeviceSpec {
                circuit_breaker: 4,
                ..held
            })]
        );
        // The motor pages likewise: no FLAP_SPEC from defaults, and no capture.
        assert!(
            messages(&f, Page::Flaps, &m)
                .unwrap_err()
                .contains("FLAP_SPEC not yet read")
        );
        assert!(
            capture(&mut f, Page::Flaps, Field::FlapUp, &m, t0)
                .unwrap_err()
                .starts_with("FLAP_SPEC not yet read")
        );
    }

    #[test]
    fn breaker_steps_stay_in_the_pins_range_but_typing_does_not() {
        let mut m = model();
        factory_pin(&mut m, 0x17);
        let mut f = Forms::default();
        select_device(&mut f, 0x17, &m);
        assert_eq!(f.device.circuit_breaker, 2, "Appendix F default");
        adjust(&mut f, Page::Device, Field::Breaker, 1, &m).unwrap();
        assert_eq!(f.device.circuit_breaker, 5, "into 5–15 A");
        for _ in 0..20 {
            adjust(&mut f, Page::Device, Field::Breaker, 1, &m).unwrap();
        }
        assert_eq!(f.device.circuit_breaker, 15);
        set_typed(&mut f, Page::Device, Field::Breaker, "20");
        assert_eq!(f.device.circuit_breaker, 20);
        let msgs = messages(&f, Page::Device, &m).unwrap();
        let (i, why) = check(&UnitConfig::default(), &msgs).unwrap_err();
        assert_eq!(i, 0);
        assert_eq!(
            why,
            "Invalid circuit breaker value: 20 A is outside 5–15 A for 15A-1 (ICD Table 40)"
        );
    }

    #[test]
    fn switch_cycles_off_1_to_10_always_on_and_the_starter_refuses() {
        let m = model();
        let mut f = Forms::default();
        select_device(&mut f, 5, &m);
        assert_eq!(f.device.switch_id, SwitchId::Off);
        adjust(&mut f, Page::Device, Field::Switch, -1, &m).unwrap();
        assert_eq!(f.device.switch_id, SwitchId::AlwaysOn);
        adjust(&mut f, Page::Device, Field::Switch, 1, &m).unwrap();
        adjust(&mut f, Page::Device, Field::Switch, 1, &m).unwrap();
        assert_eq!(f.device.switch_id, SwitchId::Input(1));
        select_device(&mut f, 1, &m);
        assert!(
            adjust(&mut f, Page::Device, Field::Switch, 1, &m)
                .unwrap_err()
                .contains("not assignable")
        );
        assert!(adjust(&mut f, Page::Device, Field::Shown, 1, &m).is_err());
        select_device(&mut f, 3, &m);
        assert!(
            adjust(&mut f, Page::Device, Field::CurrentFault, 1, &m)
                .unwrap_err()
                .contains("no current fault checking")
        );
    }

    #[test]
    fn names_are_picked_from_appendix_c_and_only_changes_are_sent() {
        let t0 = Instant::now();
        let mut m = model();
        let spec = DeviceSpec {
            device_id: 9,
            circuit_breaker: 2,
            switch_id: SwitchId::Input(2),
            current_fault: true,
            switch_raw: None,
        };
        hear(&mut m, t0, spec);
        hear_named(&mut m, t0, 9, "GPS 1");
        let mut f = Forms::default();
        select_device(&mut f, 9, &m);
        assert_eq!(f.name, "GPS 1");
        assert!(messages(&f, Page::Device, &m).unwrap().is_empty());
        adjust(&mut f, Page::Device, Field::Name, 1, &m).unwrap();
        assert_eq!(f.name, "GPS 2");
        f.shown = false;
        let msgs = messages(&f, Page::Device, &m).unwrap();
        assert_eq!(
            msgs,
            vec![
                DeviceName::new(9, "GPS 2").unwrap().into(),
                DeviceEnable {
                    device_id: 9,
                    flag: EnableFlag::Disabled
                }
                .into()
            ]
        );
        f.name = "a name far too long".into();
        assert!(messages(&f, Page::Device, &m).is_err());
    }

    #[test]
    fn capture_takes_the_live_position_into_the_selected_field() {
        let t0 = Instant::now();
        let mut m = model();
        hear(&mut m, t0, defaults::flap_spec());
        for t in [TrimType::Pitch, TrimType::Roll] {
            hear(&mut m, t0, defaults::trim_spec(t));
        }
        let mut f = Forms::default();
        for page in [Page::Flaps, Page::PitchTrim, Page::RollTrim] {
            load(&mut f, page, &m, false);
        }
        assert!(
            capture(&mut f, Page::Flaps, Field::FlapMid1, &m, t0)
                .unwrap_err()
                .contains("no live")
        );
        let ft = FlapTrimStatus {
            flap_position: 87,
            roll_trim_position: 140,
            ..<FlapTrimStatus as crate::protocol::Payload>::parse(&[0u8; 18]).unwrap()
        };
        hear(&mut m, t0, ft);
        assert!(
            capture(&mut f, Page::Flaps, Field::FlapMaxSpeed, &m, t0)
                .unwrap_err()
                .contains("select the up, down")
        );
        capture(&mut f, Page::Flaps, Field::FlapMid1, &m, t0).unwrap();
        assert_eq!(f.flap.midpoint_1, 87);
        capture(&mut f, Page::RollTrim, Field::TrimNeutral, &m, t0).unwrap();
        assert_eq!(f.roll.neutral, 140);
        assert_eq!(f.pitch.neutral, 0, "the roll page captures into roll");
        assert!(messages(&f, Page::Flaps, &m).unwrap()[0] == Message::FlapSpec(f.flap));
    }

    #[test]
    fn endpoint_run_on_is_typed_in_seconds() {
        let mut f = Forms::default();
        set_typed(&mut f, Page::Flaps, Field::FlapEndpointDuration, "1.5");
        assert_eq!(f.flap.endpoint_duration, Tenths(15));
        let m = model();
        adjust(&mut f, Page::Flaps, Field::FlapEndpointDuration, 1, &m).unwrap();
        assert_eq!(f.flap.endpoint_duration, Tenths(16));
    }

    #[test]
    fn a_wig_wag_conflict_is_refused_here_in_words() {
        let mut cfg = UnitConfig::default();
        cfg.devices[7].switch_id = SwitchId::Input(4);
        let mut f = Forms::default();
        f.wig_wag.device_one = Some(7);
        f.wig_wag.device_two = Some(8);
        let (i, why) = check(&cfg, &[f.wig_wag.into()]).unwrap_err();
        assert_eq!(i, 0);
        assert!(
            why.starts_with("Invalid configuration: 5A-5 (device 8) is off;"),
            "{why}"
        );
    }
}

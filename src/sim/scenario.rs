//! Scenarios: the aircraft the virtual VP-X is wired into, as a TOML file.
//!
//! A scenario says what the unit's EEPROM holds when it is fresh (device specs, names,
//! enables, flap/trim/wig-wag/system specs), what the aircraft around it does (loads,
//! shorts, switch positions, bus volts) and a timeline of things that happen to it.
//! Its keys are the fields of [`Scenario`] and its sections; `assets/scenarios/README.md`
//! describes each for people writing one. Unknown keys are errors, so a typo does not
//! silently give a different aircraft.

use std::borrow::Cow;
use std::path::PathBuf;

use anyhow::bail;
use serde::Deserialize;

use crate::protocol::config::UnitConfig;
use crate::protocol::device::{self, DEVICE_COUNT};
use crate::protocol::message::{
    DeviceEnable, DeviceName, EnableFlag, FlapMode, Message, OvervoltageLimit, SwitchId, Tenths,
    TrimType,
};
use crate::protocol::{FaultCode, validate};
use crate::toml_lines::{self, FileError, Problem};

/// The shipped scenarios, embedded so the binary works from any directory.
pub const BUILT_IN: &[(&str, &str)] = &[
    ("demo", include_str!("../../assets/scenarios/demo.toml")),
    ("hangar", include_str!("../../assets/scenarios/hangar.toml")),
    (
        "short-circuit",
        include_str!("../../assets/scenarios/short-circuit.toml"),
    ),
    (
        "comm-loss",
        include_str!("../../assets/scenarios/comm-loss.toml"),
    ),
    (
        "runaway",
        include_str!("../../assets/scenarios/runaway.toml"),
    ),
    (
        "disabled-pins",
        include_str!("../../assets/scenarios/disabled-pins.toml"),
    ),
    (
        "install",
        include_str!("../../assets/scenarios/install.toml"),
    ),
    (
        "reversed-flaps",
        include_str!("../../assets/scenarios/reversed-flaps.toml"),
    ),
    ("wires", include_str!("../../assets/scenarios/wires.toml")),
];

/// A whole scenario; see the module documentation for the file format.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scenario {
    pub description: String,
    /// The timeline restarts every this many seconds (the events fire again).
    pub loop_after: Option<f64>,
    pub electrical: Electrical,
    pub system: Option<SystemSection>,
    #[serde(rename = "device")]
    pub devices: Vec<DeviceSection>,
    pub flap: Option<FlapSection>,
    pub pitch_trim: Option<TrimSection>,
    pub roll_trim: Option<TrimSection>,
    pub wig_wag: Option<WigWagSection>,
    /// What the line does to the unit's answers.
    pub line: LineSection,
    #[serde(rename = "event")]
    pub events: Vec<Event>,
}

/// `[line]`: faults of the wire between the unit and the page.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LineSection {
    /// Every SPEC_ACK is lost on the way out; the unit still applies and stores each
    /// spec and keeps broadcasting (a write whose answer is lost).
    pub drop_spec_acks: bool,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Electrical {
    pub bus_volts: f32,
    pub battery_volts: f32,
    pub aux_battery_volts: f32,
    pub temperature_c: u8,
    pub switches: Vec<u8>,
    pub starter: bool,
    pub rpm: Option<u16>,
    /// Wiring fault: these inputs (1–10) never change, whatever their switches do (a
    /// broken wire, a bad switch, the wrong pin): they always read open.
    pub dead_switches: Vec<u8>,
    /// Wiring fault: each pair's switches are wired to each other's input.
    pub crossed_switches: Vec<[u8; 2]>,
}

impl Default for Electrical {
    fn default() -> Self {
        Electrical {
            bus_volts: 14.2,
            battery_volts: 12.5,
            aux_battery_volts: 12.7,
            temperature_c: 25,
            switches: Vec::new(),
            starter: false,
            rpm: None,
            dead_switches: Vec::new(),
            crossed_switches: Vec::new(),
        }
    }
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SystemSection {
    #[serde(default = "byte::<16>")]
    pub overvoltage_limit: u8,
    #[serde(default)]
    pub secondary_alternator: Option<u8>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DeviceSection {
    pub id: u8,
    #[serde(default)]
    pub name: Option<String>,
    #[serde(default)]
    pub breaker: Option<u8>,
    #[serde(default)]
    pub switch: Option<u8>,
    #[serde(default)]
    pub current_fault: Option<bool>,
    #[serde(default)]
    pub enabled: Option<bool>,
    /// Amps drawn while powered.
    #[serde(default)]
    pub load: f32,
    #[serde(default)]
    pub short: bool,
    /// Wiring fault: the load is not connected (a broken wire, a blown bulb): the pin
    /// draws 0 A while on, whatever `load` says.
    #[serde(default)]
    pub open_circuit: bool,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlapSection {
    #[serde(default = "yes")]
    pub enabled: bool,
    #[serde(default)]
    pub mode: FlapModeName,
    #[serde(default)]
    pub inverted: bool,
    pub up: u8,
    pub down: u8,
    #[serde(default)]
    pub midpoint_1: u8,
    #[serde(default)]
    pub midpoint_2: u8,
    #[serde(default = "byte::<7>")]
    pub breaker: u8,
    #[serde(default)]
    pub overspeed_position: u8,
    #[serde(default)]
    pub max_speed: u16,
    /// Seconds (sent in tenths, icd-reading R23).
    #[serde(default)]
    pub endpoint_duration: f32,
    #[serde(default)]
    pub position: Option<u8>,
    /// Wiring fault: see [`MotorWiring::reversed`].
    #[serde(default)]
    pub reversed: bool,
    /// Wiring fault: see [`MotorWiring::stuck`].
    #[serde(default)]
    pub stuck: bool,
}

fn yes() -> bool {
    true
}

/// A number's default, written where the field is.
fn byte<const N: u8>() -> u8 {
    N
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FlapModeName {
    #[default]
    Momentary,
    Position,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrimSection {
    #[serde(default = "yes")]
    pub enabled: bool,
    #[serde(default)]
    pub inverted: bool,
    pub up: u8,
    pub down: u8,
    pub neutral: u8,
    #[serde(default = "byte::<100>")]
    pub power: u8,
    #[serde(default)]
    pub speed: u16,
    #[serde(default)]
    pub position: Option<u8>,
    /// Wiring fault: see [`MotorWiring::reversed`].
    #[serde(default)]
    pub reversed: bool,
    /// Wiring fault: see [`MotorWiring::stuck`].
    #[serde(default)]
    pub stuck: bool,
}

/// Wiring faults of a flap or trim motor (keys `reversed` and `stuck` of `[flap]`,
/// `[pitch_trim]`, `[roll_trim]`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MotorWiring {
    /// The motor's leads are swapped: it runs the other way from the one the unit
    /// drives (by TRIM_MOVE/FLAP_MOVE and by its switches). The polarity setting
    /// (`inverted`, the Table 15/16 flag) undoes it, as it would on the aircraft.
    pub reversed: bool,
    /// The motor is driven (and reported running) but the position never changes: a
    /// jammed motor, a broken motor lead, or a disconnected position sensor.
    pub stuck: bool,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WigWagSection {
    pub device_one: Option<u8>,
    #[serde(default)]
    pub device_two: Option<u8>,
    #[serde(default = "byte::<5>")]
    pub warm_up: u8,
    #[serde(default = "byte::<70>")]
    pub speed: u8,
}

/// One timeline entry: at `at` seconds after power-on, do `action`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Event {
    pub at: f64,
    #[serde(flatten)]
    pub action: EventAction,
}

/// Which motor an event or injection means.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MotorId {
    Flap,
    Pitch,
    Roll,
}

/// A motor direction: toward the `up` endpoint (roll: left) or the `down` one (right).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MotorDirection {
    Up,
    Down,
}

/// What an event does. Written `do = "<name>"` with the fields below.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "do", rename_all = "snake_case", deny_unknown_fields)]
pub enum EventAction {
    /// External switch input 1–10 opens or closes.
    Switch { switch: u8, on: bool },
    /// The device faults now with `code` (Appendix E name in snake case, e.g.
    /// `over_current`, or a number).
    Fault { device: u8, code: FaultName },
    /// A short appears (or goes away) on a pin: SHORT_CIRCUIT whenever it is powered.
    Short { device: u8, on: bool },
    /// The pin's load changes.
    Load { device: u8, amps: f32 },
    /// No byte leaves the unit for `seconds` (requests are still taken in).
    Silent { seconds: f64 },
    /// SPEC_ACKs are lost from now on (`on = true`) or no longer (`on = false`).
    DropSpecAcks { on: bool },
    /// `bytes` bytes of noise go out on the wire.
    Garbage { bytes: usize },
    /// The running alternator's regulator now holds `volts` (over the limit: it trips).
    BusVolts { volts: f32 },
    /// Engine RPM as the unit sees it (valid); omit `rpm` to forget it.
    Rpm {
        #[serde(default)]
        rpm: Option<u16>,
    },
    /// The starter button is pressed (or released).
    Starter { on: bool },
    /// The motor runs by itself in `direction` until the unit trips a runaway fault.
    Runaway {
        motor: MotorId,
        direction: MotorDirection,
    },
    /// The flap or trim switch input is held in `direction`, or released (omitted).
    MotorSwitch {
        motor: MotorId,
        #[serde(default)]
        direction: Option<MotorDirection>,
    },
    /// The system fault bit of FAULT_STATUS is set (ICD Table 28 byte 4).
    SystemFault,
    /// The unit loses and regains power.
    PowerCycle,
    /// The processor resets without a power cycle (CU Warm Reset, Table 24 note 4).
    WarmReset,
}

/// A fault code in a scenario: an Appendix E name or the raw number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(untagged)]
pub enum FaultName {
    Code(u8),
    Name(FaultWord),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FaultWord {
    OverVoltage,
    ShortCircuit,
    OverCurrent,
    CurrentFault,
    FlapRunaway,
    TrimRunaway,
}

impl FaultName {
    pub fn code(self) -> FaultCode {
        match self {
            FaultName::Code(n) => FaultCode::from_byte(n),
            FaultName::Name(w) => match w {
                FaultWord::OverVoltage => FaultCode::OverVoltage,
                FaultWord::ShortCircuit => FaultCode::ShortCircuit,
                FaultWord::OverCurrent => FaultCode::OverCurrent,
                FaultWord::CurrentFault => FaultCode::CurrentFault,
                FaultWord::FlapRunaway => FaultCode::FlapRunaway,
                FaultWord::TrimRunaway => FaultCode::TrimRunaway,
            },
        }
    }
}

/// The longest time a scenario may name (`at`, `loop_after`, a silence): a week.
pub const MAX_SCENARIO_SECONDS: f64 = 7.0 * 24.0 * 3600.0;
/// The most line noise one `garbage` event may send.
pub const MAX_GARBAGE_BYTES: usize = 65_536;

impl Scenario {
    /// Reads a scenario from TOML text and checks it, listing every problem with its
    /// line and field ([`toml_lines`]). The unit's own rules, which judge one section
    /// against the others ([`Scenario::unit_config`]), are applied once every section
    /// reads and is in range.
    pub fn from_toml(text: &str) -> Result<Scenario, Vec<Problem>> {
        let (read, keys, mut problems) = toml_lines::read_all::<Scenario>(text);
        let Some(scenario) = read else {
            return Err(problems);
        };
        let mut wrong = scenario.out_of_range();
        if problems.is_empty() && wrong.is_empty() {
            wrong = scenario.configure().1;
        }
        problems.extend(wrong.into_iter().map(|(at, why)| keys.problem(&at, why)));
        if problems.is_empty() {
            Ok(scenario)
        } else {
            problems.sort_by_key(|p| p.line);
            Err(problems)
        }
    }

    /// What TOML types cannot say: ids in range, switches 1–10, times and sizes within
    /// reason. Each with the dotted path of its key (an entry of an array by its number).
    fn out_of_range(&self) -> Vec<(String, String)> {
        let mut wrong = Vec::new();
        let mut bad = |at: String, why: String| wrong.push((at, why));
        let e = &self.electrical;
        for (key, switches) in [
            ("switches", &e.switches),
            ("dead_switches", &e.dead_switches),
        ] {
            for s in switches.iter().filter(|s| !(1..=10).contains(*s)) {
                bad(
                    format!("electrical.{key}"),
                    format!("switch {s} is not 1–10"),
                );
            }
        }
        let crossed_at = || "electrical.crossed_switches".to_string();
        let mut crossed = Vec::new();
        for &[a, b] in &e.crossed_switches {
            if !(1..=10).contains(&a) || !(1..=10).contains(&b) || a == b {
                bad(
                    crossed_at(),
                    format!("[{a}, {b}] must be two different switches 1–10"),
                );
                continue;
            }
            for s in [a, b] {
                if crossed.contains(&s) || e.dead_switches.contains(&s) {
                    let why = format!(
                        "switch {s} is in more than one wiring fault; give each switch at most one"
                    );
                    bad(crossed_at(), why);
                }
                crossed.push(s);
            }
        }
        for (i, d) in self.devices.iter().enumerate() {
            if device::device(d.id).is_none() {
                bad(
                    format!("device.{i}.id"),
                    format!("there is no device {} (0–30)", d.id),
                );
            }
            if !(d.load.is_finite() && d.load >= 0.0) {
                let why = format!(
                    "device {}: {} A: must be a number of amps, 0 or more",
                    d.id, d.load
                );
                bad(format!("device.{i}.load"), why);
            }
        }
        // Times past this are surely a typo; they also keep every Instant sum in range.
        let max = MAX_SCENARIO_SECONDS;
        if let Some(l) = self.loop_after
            && !(l.is_finite() && l > 0.0 && l <= max)
        {
            let why = format!("{l}: must be more than 0 and at most {max} seconds");
            bad("loop_after".into(), why);
        }
        for (i, e) in self.events.iter().enumerate() {
            let (at, key) = (e.at, |k: &str| format!("event.{i}.{k}"));
            if !(at.is_finite() && at >= 0.0 && at <= max) {
                bad(key("at"), format!("{at}: must be seconds from 0 to {max}"));
            }
            let (k, why) = match e.action {
                EventAction::Silent { seconds }
                    if !(seconds.is_finite() && (0.0..=max).contains(&seconds)) =>
                {
                    (
                        "seconds",
                        format!("silent for {seconds} s: must be 0 to {max} seconds"),
                    )
                }
                EventAction::Garbage { bytes } if bytes > MAX_GARBAGE_BYTES => (
                    "bytes",
                    format!("garbage of {bytes} bytes: at most {MAX_GARBAGE_BYTES}"),
                ),
                EventAction::Switch { switch, .. } if !(1..=10).contains(&switch) => {
                    ("switch", format!("switch {switch} is not 1–10"))
                }
                EventAction::Fault { device: d, .. }
                | EventAction::Short { device: d, .. }
                | EventAction::Load { device: d, .. }
                    if device::device(d).is_none() =>
                {
                    ("device", format!("there is no device {d}"))
                }
                _ => continue,
            };
            bad(key(k), format!("event at {at}: {why}"));
        }
        wrong
    }

    /// The EEPROM contents this scenario describes: Appendix F defaults with every
    /// section applied, each judged by `protocol::validate` as the unit would judge it.
    /// A refusal says every rule broken.
    pub fn unit_config(&self) -> Result<UnitConfig, String> {
        let (cfg, wrong) = self.configure();
        if wrong.is_empty() {
            Ok(cfg)
        } else {
            let words: Vec<String> = wrong.into_iter().map(|(_, why)| why).collect();
            Err(words.join("; "))
        }
    }

    /// [`Scenario::unit_config`], with each refused section left as it was and named
    /// by the dotted path of its key.
    fn configure(&self) -> (UnitConfig, Vec<(String, String)>) {
        use crate::protocol::message::{FlapSpec, SystemSpec, TrimSpec, WigWagSpec};
        let mut cfg = UnitConfig::default();
        let mut wrong = Vec::new();
        let mut judge = |at: String, r: Result<(), String>| {
            if let Err(why) = r {
                wrong.push((at, why));
            }
        };
        // Device specs first: the system and wig-wag rules look at the pins' switches.
        for (i, d) in self.devices.iter().enumerate() {
            let who = |r: Result<(), String>| r.map_err(|why| format!("device {}: {why}", d.id));
            let Some(mut spec) = cfg.devices.get(d.id as usize).copied() else {
                judge(
                    format!("device.{i}.id"),
                    who(Err("there is no such device".into())),
                );
                continue;
            };
            spec.circuit_breaker = d.breaker.unwrap_or(spec.circuit_breaker);
            spec.switch_id = d.switch.map_or(spec.switch_id, SwitchId::from_byte);
            spec.current_fault = d.current_fault.unwrap_or(spec.current_fault);
            if d.breaker.is_some() || d.switch.is_some() || d.current_fault.is_some() {
                judge(format!("device.{i}"), who(take(&mut cfg, spec)));
            }
            if let Some(name) = &d.name {
                let n = DeviceName::new(d.id, name)
                    .ok_or_else(|| format!("name {name:?} is not ≤ 16 ASCII bytes"));
                judge(
                    format!("device.{i}.name"),
                    who(n.and_then(|n| take(&mut cfg, n))),
                );
            }
            if let Some(on) = d.enabled {
                let r = if device::enable_flag_allowed(d.id) {
                    let flag = if on {
                        EnableFlag::Enabled
                    } else {
                        EnableFlag::Disabled
                    };
                    cfg.apply_device_enable(&DeviceEnable {
                        device_id: d.id,
                        flag,
                    });
                    Ok(())
                } else {
                    Err("only devices 4–28 have an enable flag (ICD Table 23)".into())
                };
                judge(format!("device.{i}.enabled"), who(r));
            }
        }
        if let Some(s) = &self.system {
            match s.overvoltage_limit {
                16 | 32 => {
                    let spec = SystemSpec {
                        overvoltage_limit: if s.overvoltage_limit == 16 {
                            OvervoltageLimit::V16
                        } else {
                            OvervoltageLimit::V32
                        },
                        secondary_alternator: s.secondary_alternator,
                    };
                    judge("system".into(), take(&mut cfg, spec));
                }
                n => judge(
                    "system.overvoltage_limit".into(),
                    Err(format!("{n} is not 16 or 32")),
                ),
            }
        }
        if let Some(w) = &self.wig_wag {
            let spec = WigWagSpec {
                device_one: w.device_one,
                device_two: w.device_two,
                warm_up_period: w.warm_up,
                speed: w.speed,
            };
            judge("wig_wag".into(), take(&mut cfg, spec));
        }
        if let Some(f) = &self.flap {
            let spec = FlapSpec {
                mode: match f.mode {
                    FlapModeName::Momentary => FlapMode::Momentary,
                    FlapModeName::Position => FlapMode::PositionBased,
                },
                enabled: f.enabled,
                polarity: polarity(f.inverted),
                up: f.up,
                down: f.down,
                midpoint_1: f.midpoint_1,
                midpoint_2: f.midpoint_2,
                circuit_breaker: f.breaker,
                overspeed_position: f.overspeed_position,
                max_speed: f.max_speed,
                endpoint_duration: Tenths((f.endpoint_duration * 10.0).round().max(0.0) as u16),
            };
            judge("flap".into(), take(&mut cfg, spec));
        }
        for (section, trim_type, name) in [
            (&self.pitch_trim, TrimType::Pitch, "pitch_trim"),
            (&self.roll_trim, TrimType::Roll, "roll_trim"),
        ] {
            if let Some(s) = section {
                let spec = TrimSpec {
                    trim_type,
                    enabled: s.enabled,
                    polarity: polarity(s.inverted),
                    up: s.up,
                    down: s.down,
                    neutral: s.neutral,
                    power: s.power,
                    speed: s.speed,
                };
                judge(name.into(), take(&mut cfg, spec));
            }
        }
        (cfg, wrong)
    }

    /// Per-device load in amps (0 for pins the scenario does not mention).
    pub fn loads(&self) -> [f32; DEVICE_COUNT] {
        self.per_device(|d| d.load)
    }

    /// Pins whose load is not connected (`open_circuit`).
    pub fn open_circuits(&self) -> [bool; DEVICE_COUNT] {
        self.per_device(|d| d.open_circuit)
    }

    /// Pins with a short.
    pub fn shorts(&self) -> [bool; DEVICE_COUNT] {
        self.per_device(|d| d.short)
    }

    /// One value a pin, from its `[[device]]` (the default for pins it does not name).
    fn per_device<T: Copy + Default>(&self, f: impl Fn(&DeviceSection) -> T) -> [T; DEVICE_COUNT] {
        let mut out = [T::default(); DEVICE_COUNT];
        for d in &self.devices {
            if let Some(o) = out.get_mut(d.id as usize) {
                *o = f(d);
            }
        }
        out
    }

    /// The wiring faults of a motor (none when its section is absent).
    pub fn motor_wiring(&self, m: MotorId) -> MotorWiring {
        let (reversed, stuck) = match m {
            MotorId::Flap => self.flap.as_ref().map(|f| (f.reversed, f.stuck)),
            MotorId::Pitch => self.pitch_trim.as_ref().map(|t| (t.reversed, t.stuck)),
            MotorId::Roll => self.roll_trim.as_ref().map(|t| (t.reversed, t.stuck)),
        }
        .unwrap_or_default();
        MotorWiring { reversed, stuck }
    }

    /// Which input each cockpit switch 1–10 drives: index `n − 1` holds the 0-based
    /// input, or `None` for a dead one (`dead_switches`, `crossed_switches`).
    pub fn switch_wiring(&self) -> [Option<usize>; 10] {
        let mut map: [Option<usize>; 10] = std::array::from_fn(Some);
        for &[a, b] in &self.electrical.crossed_switches {
            let (a, b) = (a as usize - 1, b as usize - 1);
            map[a] = Some(b);
            map[b] = Some(a);
        }
        // A dead input reads open whichever switch is wired to it.
        for &d in &self.electrical.dead_switches {
            let dead = d as usize - 1;
            for m in &mut map {
                if *m == Some(dead) {
                    *m = None;
                }
            }
        }
        map
    }
}

fn polarity(inverted: bool) -> crate::protocol::message::Polarity {
    if inverted {
        crate::protocol::message::Polarity::Inverted
    } else {
        crate::protocol::message::Polarity::Standard
    }
}

/// Judges `spec` by the unit's own rules and, if they take it, stores it, as the
/// unit would; else says why.
fn take(cfg: &mut UnitConfig, spec: impl Into<Message>) -> Result<(), String> {
    let spec = spec.into();
    match validate::check(cfg, &spec) {
        Some(Err(r)) => Err(r.to_string()),
        _ => {
            let _ = validate::accept(cfg, &spec);
            Ok(())
        }
    }
}

/// Loads a scenario by name (`demo`, `hangar`, … from [`BUILT_IN`]) or by path to a
/// TOML file; a file that will not do is refused with every problem in it.
pub fn load_scenario(name_or_path: &str) -> anyhow::Result<Scenario> {
    let looks_like_path = name_or_path.ends_with(".toml") || name_or_path.contains('/');
    let (kind, path, text) = if looks_like_path {
        let path = PathBuf::from(name_or_path);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| FileError::unreadable("scenario file", path.clone(), &e))?;
        ("scenario file", path, Cow::Owned(text))
    } else {
        let Some((name, text)) = BUILT_IN.iter().find(|(n, _)| *n == name_or_path) else {
            let names: Vec<&str> = BUILT_IN.iter().map(|(n, _)| *n).collect();
            bail!(
                "no scenario named {name_or_path:?}; built in: {} (or give a path to a .toml file)",
                names.join(", ")
            )
        };
        (
            "built-in scenario",
            PathBuf::from(name),
            Cow::Borrowed(*text),
        )
    };
    Scenario::from_toml(&text).map_err(|problems| {
        anyhow::Error::new(FileError {
            kind,
            path,
            problems,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_built_in_scenario_loads_and_is_accepted_by_the_shared_rules() {
        for (name, _) in BUILT_IN {
            let s = load_scenario(name).unwrap_or_else(|e| panic!("{name}: {e:#}"));
            assert!(!s.description.is_empty(), "{name} says what it is");
        }
    }

    /// Each problem as the person reads it: its line, its field, its words.
    fn problems(toml: &str) -> Vec<(Option<usize>, String, String)> {
        let problems = Scenario::from_toml(toml).expect_err(toml);
        problems
            .into_iter()
            .map(|p| (p.line, p.field, p.message))
            .collect()
    }

    #[test]
    fn every_problem_is_listed_with_its_line_and_field() {
        let toml = "description = \"t\"\n\
                    [[device]]\nid = 9\nlaod = 1.0\n\
                    [[event]]\nat = 1\ndo = \"swich\"\n\
                    [[device]]\nid = 40\n\
                    [electrical]\nswitches = [1, 12]\n";
        let got = problems(toml);
        let lines: Vec<(Option<usize>, &str)> =
            got.iter().map(|(l, f, _)| (*l, f.as_str())).collect();
        assert_eq!(
            lines,
            [
                (Some(4), "device.laod"),
                (Some(5), "event"),
                (Some(9), "device.id"),
                (Some(11), "electrical.switches"),
            ],
            "{got:?}"
        );
        assert!(got[0].2.contains("unknown field `laod`"), "{got:?}");
        assert!(got[1].2.contains("unknown variant `swich`"), "{got:?}");
        assert_eq!(got[2].2, "there is no device 40 (0–30)");
        assert_eq!(got[3].2, "switch 12 is not 1–10");
    }

    /// Each mistake is refused in words at its key: ranges, wiring, times and sizes
    /// that would overflow an Instant, panic in Duration or ask for an absurd
    /// allocation, and what the unit itself would refuse.
    #[test]
    fn a_value_out_of_reason_is_refused_in_words_at_its_key() {
        let event = |fields: &str| format!("[[event]]\nat = 1\n{fields}");
        let crossed = "electrical.crossed_switches";
        for (toml, field, words) in [
            ("loop_after = inf".to_string(), "loop_after", "at most"),
            ("loop_after = 1.5e19".into(), "loop_after", "at most"),
            (
                event("do = \"silent\"\nseconds = inf"),
                "event.seconds",
                "silent",
            ),
            (
                event("do = \"silent\"\nseconds = 1.5e19"),
                "event.seconds",
                "silent",
            ),
            (
                event("do = \"garbage\"\nbytes = 99999999999"),
                "event.bytes",
                "garbage",
            ),
            (
                event("do = \"switch\"\nswitch = 0\non = true"),
                "event.switch",
                "1–10",
            ),
            (
                event("do = \"load\"\ndevice = 31\namps = 1.0"),
                "event.device",
                "no device",
            ),
            (
                "[[event]]\nat = 1e20\ndo = \"switch\"\nswitch = 1\non = true".into(),
                "event.at",
                "must be seconds",
            ),
            (
                "[electrical]\ndead_switches = [11]".into(),
                "electrical.dead_switches",
                "1–10",
            ),
            (
                "[electrical]\ncrossed_switches = [[3, 3]]".into(),
                crossed,
                "two different",
            ),
            (
                "[electrical]\ncrossed_switches = [[0, 3]]".into(),
                crossed,
                "1–10",
            ),
            (
                "[electrical]\ncrossed_switches = [[1, 2], [2, 3]]".into(),
                crossed,
                "more than one",
            ),
            (
                "[electrical]\ndead_switches = [2]\ncrossed_switches = [[1, 2]]".into(),
                crossed,
                "more than one",
            ),
            (
                "[pitch_trim]\nup = 1\ndown = 2\nneutral = 1\nreverse = true".into(),
                "pitch_trim.reverse",
                "unknown field",
            ),
            (
                "[[device]]\nid = 9\nload = -1.0".into(),
                "device.load",
                "device 9",
            ),
            (
                "[[device]]\nid = 9\nbreaker = 12".into(),
                "device",
                "device 9",
            ),
            (
                "[[device]]\nid = 2\nenabled = false".into(),
                "device.enabled",
                "4–28",
            ),
            (
                "[system]\novervoltage_limit = 20".into(),
                "system.overvoltage_limit",
                "16 or 32",
            ),
        ] {
            let got = problems(&format!("description = \"t\"\n{toml}"));
            let [(line, f, message)] = &got[..] else {
                panic!("{toml}: one problem, not {got:?}");
            };
            assert_eq!(f, field, "{toml}: {got:?}");
            assert!(line.is_some_and(|l| l > 1), "{toml}: its own line: {got:?}");
            assert!(message.contains(words), "{toml}: {message}");
        }
        assert!(Scenario::from_toml("description = \"t\"\nloop_after = 60.0").is_ok());
    }

    #[test]
    fn events_parse_with_their_fields() {
        let s = Scenario::from_toml(
            "[[event]]\nat = 2.5\ndo = \"fault\"\ndevice = 9\ncode = \"short_circuit\"\n\
             [[event]]\nat = 3\ndo = \"runaway\"\nmotor = \"pitch\"\ndirection = \"up\"\n",
        )
        .unwrap();
        assert_eq!(
            s.events[0].action,
            EventAction::Fault {
                device: 9,
                code: FaultName::Name(FaultWord::ShortCircuit)
            }
        );
        assert!(matches!(
            s.events[1].action,
            EventAction::Runaway {
                motor: MotorId::Pitch,
                direction: MotorDirection::Up
            }
        ));
    }

    #[test]
    fn wiring_faults_map_switches_to_inputs() {
        let s = Scenario::from_toml(
            "[electrical]\ndead_switches = [7]\ncrossed_switches = [[5, 6], [1, 10]]\n",
        )
        .unwrap();
        let map = s.switch_wiring();
        assert_eq!(map[4], Some(5), "switch 5 drives input 6");
        assert_eq!(map[5], Some(4), "switch 6 drives input 5");
        assert_eq!((map[0], map[9]), (Some(9), Some(0)));
        assert_eq!(map[6], None, "input 7 is dead");
        assert_eq!(map[2], Some(2), "the rest straight through");
    }

    /// The `install` scenario's faults are a contract with the installation check's
    /// end-to-end test and the README and the guide: exactly these, and nothing else.
    #[test]
    fn install_has_exactly_its_six_wiring_faults() {
        let s = load_scenario("install").unwrap();
        let open: Vec<usize> = (0..DEVICE_COUNT)
            .filter(|&i| s.open_circuits()[i])
            .collect();
        assert_eq!(open, [6], "Beacon");
        let cfg = s.unit_config().unwrap();
        let near: Vec<u8> = s
            .devices
            .iter()
            .filter(|d| d.load >= 0.8 * cfg.devices[d.id as usize].circuit_breaker as f32)
            .map(|d| d.id)
            .collect();
        assert_eq!(near, [17], "Landing Lt, 7.2 A of 8 A");
        assert_eq!(s.electrical.dead_switches, [7]);
        assert_eq!(s.electrical.crossed_switches, [[5, 6]]);
        assert!(s.devices.iter().all(|d| !d.short));
        assert!(s.electrical.switches.is_empty(), "every switch off");
        assert_eq!(
            [MotorId::Flap, MotorId::Pitch, MotorId::Roll].map(|m| s.motor_wiring(m)),
            [
                MotorWiring::default(),
                MotorWiring {
                    reversed: true,
                    stuck: false
                },
                MotorWiring {
                    reversed: false,
                    stuck: true
                },
            ]
        );
        assert!(s.events.is_empty(), "nothing happens by itself");
        let names: Vec<(u8, String)> = [6u8, 17, 18, 19, 20]
            .iter()
            .map(|&i| {
                let name = DeviceName {
                    device_id: i,
                    name: cfg.names[i as usize],
                };
                (i, name.text())
            })
            .collect();
        assert_eq!(
            names,
            [
                (6, "Beacon".to_string()),
                (17, "Landing Lt".into()),
                (18, "Taxi Lt".into()),
                (19, "Boost Pump".into()),
                (20, "Pitot Heat".into())
            ]
        );
    }
}

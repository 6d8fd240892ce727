//! Scenarios: the aircraft the virtual VP-X is wired into, as a TOML file.
//!
//! A scenario says what the unit's EEPROM holds when it is fresh (device specs, names,
//! enables, flap/trim/wig-wag/system specs), what the aircraft around it does (loads,
//! shorts, switch positions, bus volts) and a timeline of things that happen to it.
//! `assets/scenarios/README.md` is the same description for people writing one.
//!
//! ```toml
//! description = "one line shown in logs"
//! loop_after = 60.0            # optional: the timeline starts again every 60 s
//!
//! [electrical]                 # all optional
//! bus_volts = 14.2             # regulated bus volts while an alternator runs
//! battery_volts = 12.5         # bus volts with no alternator running
//! aux_battery_volts = 12.7
//! temperature_c = 31
//! switches = [1, 3]            # external switch inputs closed at start (1–10)
//! starter = false              # starter engaged (cranking) at start
//! rpm = 2400                   # engine RPM the unit sees even without EXTERNAL_DATA
//! dead_switches = [7]          # wiring fault: input 7 never changes, whatever its switch does
//! crossed_switches = [[5, 6]]  # wiring fault: switch 5 drives input 6 and 6 drives 5
//!
//! [system]                     # SYSTEM_SPEC, ICD Table 14
//! overvoltage_limit = 16       # 16 or 32
//! secondary_alternator = 17    # device id, omit for none
//!
//! [[device]]                   # DEVICE_SPEC (Table 13) plus the wiring behind the pin
//! id = 4
//! name = "Nav Lt"              # DEVICE_NAME, ≤ 16 ASCII bytes
//! breaker = 3                  # amps; default: Appendix F
//! switch = 1                   # 0 off, 1–10, 11 always on; default: Appendix F
//! current_fault = false
//! enabled = true               # DEVICE_ENABLE (4–28 only)
//! load = 1.4                   # amps drawn when powered
//! short = false                # a short: SHORT_CIRCUIT as soon as it is powered
//! open_circuit = false         # wiring fault: the load is not connected, 0 A while on
//!
//! [flap]                       # FLAP_SPEC, Table 16; endpoint_duration in seconds
//! enabled = true
//! mode = "momentary"           # or "position"
//! up = 20
//! down = 220
//! midpoint_1 = 90
//! midpoint_2 = 160
//! breaker = 7
//! overspeed_position = 60
//! max_speed = 100
//! endpoint_duration = 0.5
//! position = 20                # where the flaps are at start
//! reversed = false             # wiring fault: the motor runs the other way
//! stuck = false                # wiring fault: the motor runs but the position never moves
//!
//! [pitch_trim]                 # TRIM_SPEC, Table 15 (also [roll_trim])
//! enabled = true
//! up = 30
//! down = 220
//! neutral = 125
//! power = 60
//! speed = 120
//! position = 125
//!
//! [wig_wag]                    # WIG_WAG_SPEC, Table 17
//! device_one = 7
//! device_two = 8
//! warm_up = 5
//! speed = 70
//!
//! [line]                       # what the wire does to the unit's answers
//! drop_spec_acks = false       # true: SPEC_ACKs are lost, specs still applied
//!
//! [[event]]                    # the timeline; `at` is seconds after power-on
//! at = 5.0
//! do = "switch"                # see `EventAction` for every action and its fields
//! switch = 2
//! on = true
//! ```
//!
//! Unknown keys are errors, so a typo does not silently give a different aircraft.

use std::path::Path;

use anyhow::{Context, bail};
use serde::Deserialize;

use crate::protocol::config::UnitConfig;
use crate::protocol::device::{self, DEVICE_COUNT};
use crate::protocol::message::{
    DeviceEnable, DeviceName, EnableFlag, FlapMode, OvervoltageLimit, SwitchId, Tenths, TrimType,
};
use crate::protocol::{FaultCode, validate};

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
#[serde(deny_unknown_fields)]
pub struct Scenario {
    #[serde(default)]
    pub description: String,
    /// The timeline restarts every this many seconds (the events fire again).
    #[serde(default)]
    pub loop_after: Option<f64>,
    #[serde(default)]
    pub electrical: Electrical,
    #[serde(default)]
    pub system: Option<SystemSection>,
    #[serde(default, rename = "device")]
    pub devices: Vec<DeviceSection>,
    #[serde(default)]
    pub flap: Option<FlapSection>,
    #[serde(default)]
    pub pitch_trim: Option<TrimSection>,
    #[serde(default)]
    pub roll_trim: Option<TrimSection>,
    #[serde(default)]
    pub wig_wag: Option<WigWagSection>,
    /// What the line does to the unit's answers.
    #[serde(default)]
    pub line: LineSection,
    #[serde(default, rename = "event")]
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
    #[serde(default = "sixteen")]
    pub overvoltage_limit: u8,
    #[serde(default)]
    pub secondary_alternator: Option<u8>,
}

fn sixteen() -> u8 {
    16
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
    #[serde(default = "seven")]
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
fn seven() -> u8 {
    7
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
    #[serde(default = "hundred")]
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

fn hundred() -> u8 {
    100
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WigWagSection {
    pub device_one: Option<u8>,
    #[serde(default)]
    pub device_two: Option<u8>,
    #[serde(default = "five")]
    pub warm_up: u8,
    #[serde(default = "seventy")]
    pub speed: u8,
}

fn five() -> u8 {
    5
}
fn seventy() -> u8 {
    70
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
    /// Parses a scenario from TOML text and checks it (see [`Scenario::check`]).
    pub fn from_toml(text: &str) -> anyhow::Result<Scenario> {
        let s: Scenario = toml::from_str(text)?;
        s.check()?;
        Ok(s)
    }

    /// Checks what TOML types cannot: ids in range, switches 1–10, and a configuration
    /// the unit itself would accept (the shared §6.2 rules).
    pub fn check(&self) -> anyhow::Result<()> {
        for &s in &self.electrical.switches {
            if !(1..=10).contains(&s) {
                bail!("electrical.switches: switch {s} is not 1–10");
            }
        }
        let e = &self.electrical;
        for &s in &e.dead_switches {
            if !(1..=10).contains(&s) {
                bail!("electrical.dead_switches: switch {s} is not 1–10");
            }
        }
        let mut crossed = Vec::new();
        for &[a, b] in &e.crossed_switches {
            if !(1..=10).contains(&a) || !(1..=10).contains(&b) || a == b {
                bail!(
                    "electrical.crossed_switches: [{a}, {b}] must be two different switches 1–10"
                );
            }
            for s in [a, b] {
                if crossed.contains(&s) || e.dead_switches.contains(&s) {
                    bail!(
                        "electrical.crossed_switches: switch {s} is in more than one \
                         wiring fault; give each switch at most one"
                    );
                }
                crossed.push(s);
            }
        }
        for d in &self.devices {
            if device::device(d.id).is_none() {
                bail!("device {}: there is no such device (0–30)", d.id);
            }
            if !(d.load.is_finite() && d.load >= 0.0) {
                bail!(
                    "device {}: load must be a non-negative number of amps",
                    d.id
                );
            }
        }
        // Times past this are surely a typo; they also keep every Instant sum in range.
        let max = MAX_SCENARIO_SECONDS;
        if let Some(l) = self.loop_after
            && !(l.is_finite() && l > 0.0 && l <= max)
        {
            bail!("loop_after {l}: must be more than 0 and at most {max} seconds");
        }
        for e in &self.events {
            if !(e.at.is_finite() && e.at >= 0.0 && e.at <= max) {
                bail!("event at {}: `at` must be seconds from 0 to {max}", e.at);
            }
            match e.action {
                EventAction::Silent { seconds }
                    if !(seconds.is_finite() && (0.0..=max).contains(&seconds)) =>
                {
                    bail!(
                        "event at {}: silent for {seconds} s: must be 0 to {max} seconds",
                        e.at
                    )
                }
                EventAction::Garbage { bytes } if bytes > MAX_GARBAGE_BYTES => {
                    bail!(
                        "event at {}: garbage of {bytes} bytes: at most {MAX_GARBAGE_BYTES}",
                        e.at
                    )
                }
                EventAction::Switch { switch, .. } if !(1..=10).contains(&switch) => {
                    bail!("event at {}: switch {switch} is not 1–10", e.at)
                }
                EventAction::Fault { device: d, .. }
                | EventAction::Short { device: d, .. }
                | EventAction::Load { device: d, .. }
                    if device::device(d).is_none() =>
                {
                    bail!("event at {}: there is no device {d}", e.at)
                }
                _ => {}
            }
        }
        self.unit_config()?;
        Ok(())
    }

    /// The EEPROM contents this scenario describes: Appendix F defaults with every
    /// section applied, each judged by `protocol::validate` as the unit would judge it.
    pub fn unit_config(&self) -> anyhow::Result<UnitConfig> {
        let mut cfg = UnitConfig::default();
        // Device specs first: the system and wig-wag rules look at the pins' switches.
        for d in &self.devices {
            let mut spec = cfg.devices[d.id as usize];
            if let Some(b) = d.breaker {
                spec.circuit_breaker = b;
            }
            if let Some(s) = d.switch {
                spec.switch_id = SwitchId::from_byte(s);
            }
            if let Some(c) = d.current_fault {
                spec.current_fault = c;
            }
            if d.breaker.is_some() || d.switch.is_some() || d.current_fault.is_some() {
                validate::check_device_spec(&cfg, &spec)
                    .map_err(|r| anyhow::anyhow!("device {}: {r}", d.id))?;
                cfg.apply_device_spec(&spec);
            }
            if let Some(name) = &d.name {
                let n = DeviceName::new(d.id, name).with_context(|| {
                    format!("device {}: name {name:?} is not ≤ 16 ASCII bytes", d.id)
                })?;
                validate::check_device_name(&cfg, &n)
                    .map_err(|r| anyhow::anyhow!("device {}: {r}", d.id))?;
                cfg.apply_device_name(&n);
            }
            if let Some(en) = d.enabled {
                if !device::enable_flag_allowed(d.id) {
                    bail!(
                        "device {}: only devices 4–28 have an enable flag (ICD Table 23)",
                        d.id
                    );
                }
                cfg.apply_device_enable(&DeviceEnable {
                    device_id: d.id,
                    flag: if en {
                        EnableFlag::Enabled
                    } else {
                        EnableFlag::Disabled
                    },
                });
            }
        }
        if let Some(s) = &self.system {
            let spec = crate::protocol::message::SystemSpec {
                overvoltage_limit: match s.overvoltage_limit {
                    16 => OvervoltageLimit::V16,
                    32 => OvervoltageLimit::V32,
                    n => bail!("system.overvoltage_limit: {n} is not 16 or 32"),
                },
                secondary_alternator: s.secondary_alternator,
            };
            validate::check_system_spec(&cfg, &spec).map_err(|r| anyhow::anyhow!("system: {r}"))?;
            cfg.apply_system_spec(&spec);
        }
        if let Some(w) = &self.wig_wag {
            let spec = crate::protocol::message::WigWagSpec {
                device_one: w.device_one,
                device_two: w.device_two,
                warm_up_period: w.warm_up,
                speed: w.speed,
            };
            validate::check_wig_wag_spec(&cfg, &spec)
                .map_err(|r| anyhow::anyhow!("wig_wag: {r}"))?;
            cfg.apply_wig_wag_spec(&spec);
        }
        if let Some(f) = &self.flap {
            let spec = crate::protocol::message::FlapSpec {
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
            validate::check_flap_spec(&cfg, &spec).map_err(|r| anyhow::anyhow!("flap: {r}"))?;
            cfg.apply_flap_spec(&spec);
        }
        for (section, t, name) in [
            (&self.pitch_trim, TrimType::Pitch, "pitch_trim"),
            (&self.roll_trim, TrimType::Roll, "roll_trim"),
        ] {
            if let Some(s) = section {
                let spec = crate::protocol::message::TrimSpec {
                    trim_type: t,
                    enabled: s.enabled,
                    polarity: polarity(s.inverted),
                    up: s.up,
                    down: s.down,
                    neutral: s.neutral,
                    power: s.power,
                    speed: s.speed,
                };
                validate::check_trim_spec(&cfg, &spec)
                    .map_err(|r| anyhow::anyhow!("{name}: {r}"))?;
                cfg.apply_trim_spec(&spec);
            }
        }
        Ok(cfg)
    }

    /// Per-device load in amps (0 for pins the scenario does not mention).
    pub fn loads(&self) -> [f32; DEVICE_COUNT] {
        let mut out = [0.0; DEVICE_COUNT];
        for d in &self.devices {
            out[d.id as usize] = d.load;
        }
        out
    }

    /// Pins whose load is not connected (`open_circuit`).
    pub fn open_circuits(&self) -> [bool; DEVICE_COUNT] {
        let mut out = [false; DEVICE_COUNT];
        for d in &self.devices {
            out[d.id as usize] = d.open_circuit;
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

    pub fn shorts(&self) -> [bool; DEVICE_COUNT] {
        let mut out = [false; DEVICE_COUNT];
        for d in &self.devices {
            out[d.id as usize] = d.short;
        }
        out
    }
}

fn polarity(inverted: bool) -> crate::protocol::message::Polarity {
    if inverted {
        crate::protocol::message::Polarity::Inverted
    } else {
        crate::protocol::message::Polarity::Standard
    }
}

/// Loads a scenario by name (`demo`, `hangar`, … from [`BUILT_IN`]; a file of that name
/// under `assets/scenarios/` next to the working directory wins, so one can be edited
/// without rebuilding) or by path to a TOML file.
pub fn load_scenario(name_or_path: &str) -> anyhow::Result<Scenario> {
    let path = Path::new(name_or_path);
    let looks_like_path = name_or_path.ends_with(".toml") || name_or_path.contains('/');
    if looks_like_path {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read scenario file {}", path.display()))?;
        return Scenario::from_toml(&text)
            .with_context(|| format!("scenario file {}", path.display()));
    }
    match BUILT_IN.iter().find(|(n, _)| *n == name_or_path) {
        Some((name, text)) => {
            Scenario::from_toml(text).with_context(|| format!("built-in scenario {name}"))
        }
        None => {
            let names: Vec<&str> = BUILT_IN.iter().map(|(n, _)| *n).collect();
            bail!(
                "no scenario named {name_or_path:?}; built in: {} (or give a path to a .toml file)",
                names.join(", ")
            )
        }
    }
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

    #[test]
    fn a_config_the_unit_would_refuse_is_an_error_that_names_the_device() {
        let err = Scenario::from_toml("[[device]]\nid = 9\nbreaker = 12\n").unwrap_err();
        assert!(format!("{err:#}").contains("device 9"), "{err:#}");
    }

    #[test]
    fn typos_are_errors_not_silently_ignored() {
        assert!(Scenario::from_toml("[[device]]\nid = 9\nlaod = 1.0\n").is_err());
        assert!(Scenario::from_toml("[[event]]\nat = 1\ndo = \"swich\"\n").is_err());
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

    /// Times and sizes that would overflow an Instant, panic in Duration, or ask for
    /// an absurd allocation are refused in words when the file is read.
    #[test]
    fn absurd_times_and_sizes_are_refused_not_crashed_on() {
        for (toml, words) in [
            ("loop_after = inf", "loop_after"),
            ("loop_after = 1.5e19", "loop_after"),
            (
                "[[event]]\nat = 1e20\ndo = \"switch\"\nswitch = 1\non = true",
                "`at`",
            ),
            (
                "[[event]]\nat = 1\ndo = \"silent\"\nseconds = inf",
                "silent",
            ),
            (
                "[[event]]\nat = 1\ndo = \"silent\"\nseconds = 1.5e19",
                "silent",
            ),
            (
                "[[event]]\nat = 1\ndo = \"garbage\"\nbytes = 9223372036854775807",
                "garbage",
            ),
        ] {
            let err = Scenario::from_toml(&format!("description = \"t\"\n{toml}"))
                .expect_err(toml)
                .to_string();
            assert!(err.contains(words), "{toml}: {err}");
            assert!(
                err.contains("at most") || err.contains("must be"),
                "refused by our check, not the parser: {err}"
            );
        }
        assert!(Scenario::from_toml("description = \"t\"\nloop_after = 60.0").is_ok());
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

    #[test]
    fn impossible_wiring_is_refused_in_words() {
        for (toml, words) in [
            ("[electrical]\ndead_switches = [11]", "dead_switches"),
            ("[electrical]\ncrossed_switches = [[3, 3]]", "two different"),
            ("[electrical]\ncrossed_switches = [[0, 3]]", "1–10"),
            (
                "[electrical]\ncrossed_switches = [[1, 2], [2, 3]]",
                "more than one",
            ),
            (
                "[electrical]\ndead_switches = [2]\ncrossed_switches = [[1, 2]]",
                "more than one",
            ),
            (
                "[pitch_trim]\nup = 1\ndown = 2\nneutral = 1\nreverse = true",
                "reverse",
            ),
        ] {
            let err = format!("{:#}", Scenario::from_toml(toml).expect_err(toml));
            assert!(err.contains(words), "{toml}: {err}");
        }
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

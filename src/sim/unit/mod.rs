//! The virtual VP-X itself: a pure state machine, bytes in and bytes out, driven by the
//! caller's clock so tests can run it without sleeping.
//!
//! [`Unit::feed`] takes received bytes, [`Unit::tick`] lets time pass (broadcasts,
//! motors, timeline), [`Unit::take_output`] hands over the bytes to send. Nothing here
//! reads a clock or touches a port.
//!
//! Behaviour follows ICD §6 and §8; where the ICD is silent the decision is written at
//! the place it is made, and summarised in the `sim` module documentation.
//!
//! One file per job: this one holds the unit's state, its start and its clock
//! ([`Unit::tick`]); `wire` decodes requests and answers them, `commands` takes
//! what is done from outside the wire, `power` decides which pins are on and what
//! they draw, `aircraft` reads the speeds and motor geometry, `broadcasts` builds
//! the §6.3 messages, and `stats` counts.

mod aircraft;
mod broadcasts;
mod commands;
mod power;
mod stats;
mod wire;

pub use broadcasts::is_broadcast;
pub use commands::SimCommand;
pub use stats::{SimStats, WireStats};

use std::time::{Duration, Instant};

use commands::inputs;

use super::bootloader::{BootStats, Bootloader, Flash};
use super::eeprom::{Eeprom, LoadOutcome};
use super::motors::Motor;
use super::scenario::{MotorId, MotorWiring, Scenario};
use crate::protocol::FaultCode;
use crate::protocol::config::UnitConfig;
use crate::protocol::decoder::Decoder;
use crate::protocol::device::{DEVICE_COUNT, FLAPS, TRIM_P, TRIM_R};
use crate::protocol::message::{DataIntegrityCode, ExternalData, WigWagModeSetting};

/// Period of the 1 Hz broadcasts (ICD §6.3.1, §6.3.2, §6.3.4).
pub const SLOW_PERIOD: Duration = Duration::from_secs(1);
/// Period of FLAP_TRIM_STATUS (ICD §6.3.3, 10 Hz).
pub const FAST_PERIOD: Duration = Duration::from_millis(100);
/// EXTERNAL_DATA older than this sets "External Data Missing" (Table 24 note 6).
pub const EXTERNAL_DATA_TIMEOUT: Duration = Duration::from_secs(2);
/// Each wig-wag light is on for this long, then the other (the ICD gives no rate).
pub const WIG_WAG_HALF_PERIOD: Duration = Duration::from_millis(500);
/// The starter is cut above this valid RPM (Appendix B note 1, icd-reading R18).
pub const STARTER_CUTOUT_RPM: u16 = 500;

/// Fixed facts about the unit, chosen when it is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnitOptions {
    /// VERSION hardware version (Table 11 note 1: 1 Gen 1, 2 Pro, 3 Sport).
    pub hardware_version: u8,
    pub software_version: (u8, u8),
    /// Seed of the load noise and garbage bytes, so a run can be repeated.
    pub seed: u64,
}

impl Default for UnitOptions {
    fn default() -> Self {
        UnitOptions {
            hardware_version: 2,
            software_version: (2, 1),
            seed: 0x5650_5820,
        }
    }
}

/// splitmix64: small, seedable, and good enough for load noise.
#[derive(Debug, Clone)]
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in −1..1.
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    }
}

#[derive(Debug)]
enum Mode {
    Normal,
    Boot(Bootloader),
}

/// How the unit comes up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Start {
    Cold,
    Warm,
    /// The bootloader's EXIT; `programmed` when a page of flash was written.
    BootloaderExit {
        programmed: bool,
    },
}

/// The virtual VP-X; see the module documentation.
pub struct Unit {
    opts: UnitOptions,
    eeprom: Eeprom,
    pub config: UnitConfig,
    decoder: Decoder,
    mode: Mode,
    pub flash: Flash,
    boot_stats: BootStats,
    out: Vec<u8>,
    log: Vec<String>,
    rng: Rng,
    wire: WireStats,

    // The aircraft around the unit: survives a power cycle.
    /// The cockpit switches 1–10 (index n − 1), where a person left them.
    cockpit: [bool; 10],
    /// Which input each cockpit switch drives (`None`: its input is dead).
    switch_wiring: [Option<usize>; 10],
    /// The unit's external switch inputs 1–10, as the wiring delivers the switches.
    switches: [bool; 10],
    /// Pins whose load is not connected (0 A while on).
    open_circuits: [bool; DEVICE_COUNT],
    /// Per motor (flap, pitch, roll): reversed leads, a jammed motor or sensor.
    motor_wiring: [MotorWiring; 3],
    /// Things a person does later (the second half of a flip), on the unit's clock.
    pending: Vec<(Instant, SimCommand)>,
    loads: [f32; DEVICE_COUNT],
    shorts: [bool; DEVICE_COUNT],
    nominal_volts: f32,
    regulator_volts: Option<f32>,
    battery_volts: f32,
    aux_battery_volts: f32,
    temperature_c: u8,
    starter_pressed: bool,
    engine_rpm: Option<u16>,
    motors: [Motor; 3],

    // The unit's RAM: lost on a power cycle.
    overrides: [Option<bool>; DEVICE_COUNT],
    faults: [FaultCode; DEVICE_COUNT],
    powered: [bool; DEVICE_COUNT],
    system_fault: bool,
    over_48: bool,
    over_60: bool,
    wig_wag_mode: WigWagModeSetting,
    wig_wag_since: Option<Instant>,
    wig_wag_active: bool,
    external: Option<(Instant, ExternalData)>,
    booted_at: Instant,
    software_update: bool,
    warm_reset: bool,
    integrity: Option<DataIntegrityCode>,
    cnt: u8,
    next_slow: Instant,
    next_fast: Instant,
    silent_until: Option<Instant>,
    /// SPEC_ACKs are lost on the way out (the scenario's `[line]`, or a command).
    drop_spec_acks: bool,

    // The scenario's timeline.
    events: Vec<(Duration, SimCommand)>,
    loop_after: Option<Duration>,
    timeline_start: Instant,
    next_event: usize,
}

fn motor_index(m: MotorId) -> usize {
    match m {
        MotorId::Flap => 0,
        MotorId::Pitch => 1,
        MotorId::Roll => 2,
    }
}

fn motor_device(m: MotorId) -> u8 {
    match m {
        MotorId::Flap => FLAPS,
        MotorId::Pitch => TRIM_P,
        MotorId::Roll => TRIM_R,
    }
}

fn motor_of_device(id: u8) -> Option<MotorId> {
    match id {
        FLAPS => Some(MotorId::Flap),
        TRIM_P => Some(MotorId::Pitch),
        TRIM_R => Some(MotorId::Roll),
        _ => None,
    }
}

impl Unit {
    /// A unit wired into `scenario`, powered on at `now`. `eeprom` is what its EEPROM
    /// held at power-on (see [`Eeprom`]); use [`Unit::with_memory_eeprom`] for none.
    pub fn new(
        scenario: &Scenario,
        eeprom: (Eeprom, LoadOutcome),
        opts: UnitOptions,
        now: Instant,
    ) -> Self {
        let (eeprom, outcome) = eeprom;
        let e = &scenario.electrical;
        let mut cockpit = [false; 10];
        for &s in &e.switches {
            if let Some(sw) = cockpit.get_mut(s as usize - 1) {
                *sw = true;
            }
        }
        let switch_wiring = scenario.switch_wiring();
        let position = |p: Option<u8>, fallback: u8| p.unwrap_or(fallback) as f32;
        let cfg = &outcome.config;
        let motors = [
            Motor::new(
                MotorId::Flap,
                position(scenario.flap.as_ref().and_then(|f| f.position), cfg.flap.up),
                now,
            ),
            Motor::new(
                MotorId::Pitch,
                position(
                    scenario.pitch_trim.as_ref().and_then(|t| t.position),
                    cfg.pitch_trim.neutral,
                ),
                now,
            ),
            Motor::new(
                MotorId::Roll,
                position(
                    scenario.roll_trim.as_ref().and_then(|t| t.position),
                    cfg.roll_trim.neutral,
                ),
                now,
            ),
        ];
        let mut events: Vec<(Duration, SimCommand)> = scenario
            .events
            .iter()
            .map(|ev| {
                (
                    Duration::from_secs_f64(ev.at),
                    SimCommand::from_event(&ev.action),
                )
            })
            .collect();
        events.sort_by_key(|(at, _)| *at);
        let mut u = Unit {
            opts,
            eeprom,
            config: outcome.config.clone(),
            decoder: Decoder::new(),
            mode: Mode::Normal,
            flash: Flash::default(),
            boot_stats: BootStats::default(),
            out: Vec::new(),
            log: outcome.log,
            rng: Rng(opts.seed),
            wire: WireStats::default(),
            cockpit,
            switch_wiring,
            switches: inputs(&cockpit, &switch_wiring),
            open_circuits: scenario.open_circuits(),
            motor_wiring: [MotorId::Flap, MotorId::Pitch, MotorId::Roll]
                .map(|m| scenario.motor_wiring(m)),
            pending: Vec::new(),
            loads: scenario.loads(),
            shorts: scenario.shorts(),
            nominal_volts: e.bus_volts,
            regulator_volts: None,
            battery_volts: e.battery_volts,
            aux_battery_volts: e.aux_battery_volts,
            temperature_c: e.temperature_c,
            starter_pressed: e.starter,
            engine_rpm: e.rpm,
            motors,
            overrides: [None; DEVICE_COUNT],
            faults: [FaultCode::NoFault; DEVICE_COUNT],
            powered: [false; DEVICE_COUNT],
            system_fault: false,
            over_48: false,
            over_60: false,
            wig_wag_mode: WigWagModeSetting::Auto,
            wig_wag_since: None,
            wig_wag_active: false,
            external: None,
            booted_at: now,
            software_update: false,
            warm_reset: false,
            integrity: outcome.integrity,
            cnt: 0,
            next_slow: now,
            next_fast: now,
            silent_until: None,
            drop_spec_acks: scenario.line.drop_spec_acks,
            events,
            loop_after: scenario
                .loop_after
                .filter(|s| *s > 0.0)
                .map(Duration::from_secs_f64),
            timeline_start: now,
            next_event: 0,
        };
        if !scenario.description.is_empty() {
            u.log(format!("scenario: {}", scenario.description));
        }
        u.boot(now, Start::Cold);
        u.integrity = outcome.integrity;
        u
    }

    /// A unit whose EEPROM lives in memory, starting from the scenario's configuration.
    pub fn with_memory_eeprom(scenario: &Scenario, opts: UnitOptions, now: Instant) -> Self {
        let cfg = scenario.unit_config().unwrap_or_default();
        let outcome = LoadOutcome {
            config: cfg.clone(),
            integrity: None,
            log: Vec::new(),
        };
        Unit::new(scenario, (Eeprom::in_memory(cfg), outcome), opts, now)
    }

    fn log(&mut self, line: String) {
        self.log.push(line);
    }

    /// Log lines written since the last call.
    pub fn take_log(&mut self) -> Vec<String> {
        std::mem::take(&mut self.log)
    }

    /// Bytes to send since the last call.
    pub fn take_output(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.out)
    }

    pub fn in_bootloader(&self) -> bool {
        matches!(self.mode, Mode::Boot(_))
    }

    /// (Re)starts the firmware: everything in RAM is lost, the EEPROM is read again.
    fn boot(&mut self, now: Instant, how: Start) {
        self.config = self.eeprom.stored().clone();
        self.mode = Mode::Normal;
        self.decoder.reset();
        self.overrides = [None; DEVICE_COUNT];
        self.faults = [FaultCode::NoFault; DEVICE_COUNT];
        self.powered = [false; DEVICE_COUNT];
        self.system_fault = false;
        self.over_48 = false;
        self.over_60 = false;
        self.wig_wag_mode = WigWagModeSetting::Auto;
        self.wig_wag_since = None;
        self.wig_wag_active = false;
        self.external = None;
        self.booted_at = now;
        self.regulator_volts = None;
        for m in &mut self.motors {
            m.halt(now);
            m.fault = FaultCode::NoFault;
        }
        // Table 24 notes 1, 4, 5: what each kind of start does to the flags.
        match how {
            Start::Cold => {
                self.warm_reset = false;
                self.software_update = false;
                self.integrity = None;
            }
            // §6.1.4: the DATA_INTEGRITY an EEPROM_ERASE raised "should clear
            // automatically after resetting or cycling power", so every kind of start
            // clears it (a bootloader EXIT restarts the processor too). A corrupt EEPROM
            // found at power-on is raised again by the caller after `boot`.
            Start::Warm => {
                self.warm_reset = true;
                self.integrity = None;
            }
            // Table 24 note 1: the flag says the software "was updated during the last
            // power cycle". Decision: an EXIT after no FLASH_PROG (a flasher that only
            // looked, or gave up before writing) updated nothing, so it leaves the flag
            // as it was; it clears only on a power cycle.
            Start::BootloaderExit { programmed } => {
                self.software_update |= programmed;
                self.integrity = None;
            }
        }
        // The first broadcasts come shortly after start, the fast ones offset from
        // the slow ones so that they do not all leave in one burst.
        self.next_slow = now + Duration::from_millis(200);
        self.next_fast = now + Duration::from_millis(50);
        self.update_power(now);
    }

    /// Lets time pass up to `now`: the timeline, motors, power, broadcasts.
    pub fn tick(&mut self, now: Instant) {
        self.run_timeline(now);
        self.run_pending(now);
        if self.in_bootloader() {
            return;
        }
        for m in [MotorId::Flap, MotorId::Pitch, MotorId::Roll] {
            let g = self.geometry(m, now);
            let motor = &mut self.motors[motor_index(m)];
            let was = motor.fault;
            motor.advance(&g, now);
            if !g.enabled && motor.running(now) {
                motor.halt(now);
            }
            if motor.fault != was {
                let name = motor.fault.name();
                self.log(format!("{m:?} motor: {name}"));
            }
        }
        self.update_power(now);
        if now >= self.next_slow {
            self.broadcast_slow(now);
            // Absolute schedule, so the long-run rate is exact; after a stall (a
            // suspended process) the schedule restarts rather than bursting.
            self.next_slow += SLOW_PERIOD;
            if self.next_slow <= now {
                self.next_slow = now + SLOW_PERIOD;
            }
        }
        if now >= self.next_fast {
            let s = self.flap_trim_status(now);
            self.broadcast(s, now);
            self.wire.flap_trim_status += 1;
            self.next_fast += FAST_PERIOD;
            if self.next_fast <= now {
                self.next_fast = now + FAST_PERIOD;
            }
        }
    }

    /// When the next thing is due: the caller may sleep until then (or until input).
    pub fn next_deadline(&self) -> Instant {
        let mut t = self.next_slow.min(self.next_fast);
        if let Some((at, _)) = self.events.get(self.next_event) {
            t = t.min(self.timeline_start + *at);
        }
        if let Some(at) = self.pending.iter().map(|(at, _)| *at).min() {
            t = t.min(at);
        }
        t
    }

    /// What a person set out to do later and whose time has come, in order.
    fn run_pending(&mut self, now: Instant) {
        self.pending.sort_by_key(|(at, _)| *at);
        let due = self.pending.partition_point(|(at, _)| *at <= now);
        let due: Vec<_> = self.pending.drain(..due).collect();
        for (_, cmd) in due {
            self.apply(cmd, now);
        }
    }

    fn run_timeline(&mut self, now: Instant) {
        loop {
            if let Some((at, cmd)) = self.events.get(self.next_event)
                && self.timeline_start + *at <= now
            {
                let cmd = cmd.clone();
                self.next_event += 1;
                self.apply(cmd, now);
                continue;
            }
            match self.loop_after {
                Some(period)
                    if self.next_event >= self.events.len()
                        && self.timeline_start + period <= now =>
                {
                    self.timeline_start += period;
                    self.next_event = 0;
                }
                _ => return,
            }
        }
    }
}

#[cfg(test)]
mod tests;

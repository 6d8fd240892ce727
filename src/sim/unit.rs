//! The virtual VP-X itself: a pure state machine, bytes in and bytes out, driven by the
//! caller's clock so tests can run it without sleeping.
//!
//! [`Unit::feed`] takes received bytes, [`Unit::tick`] lets time pass (broadcasts,
//! motors, timeline), [`Unit::take_output`] hands over the bytes to send. Nothing here
//! reads a clock or touches a port.
//!
//! Behaviour follows ICD §6 and §8; where the ICD is silent the decision is written at
//! the place it is made, and summarised in the `sim` module documentation.

use std::time::{Duration, Instant};

use super::bootloader::{BootStats, Bootloader, Flash};
use super::eeprom::{Eeprom, LoadOutcome};
use super::motors::{FLAP_RATE, Geometry, Motor, TRIM_RATE};
use super::scenario::{EventAction, MotorDirection, MotorId, MotorWiring, Scenario};
use crate::protocol::config::UnitConfig;
use crate::protocol::decoder::{Decoder, Event};
use crate::protocol::device::{
    self, DEVICE_COUNT, EFIS, FIELD_PRI, FLAPS, STARTER, SYSTEM_FAULT_ID, SYSTEM_SPEC_ID, TRIM_P,
    TRIM_R, WIG_WAG_SPEC_ID,
};
use crate::protocol::message::*;
use crate::protocol::{FaultCode, Message, MessageId, Node, Packet, validate};

/// Period of the 1 Hz broadcasts (ICD §6.3.1, §6.3.2, §6.3.4).
pub const SLOW_PERIOD: Duration = Duration::from_secs(1);
/// Period of FLAP_TRIM_STATUS (ICD §6.3.3, 10 Hz).
pub const FAST_PERIOD: Duration = Duration::from_millis(100);
/// EXTERNAL_DATA older than this sets "External Data Missing" (Table 24 note 6).
pub const EXTERNAL_DATA_TIMEOUT: Duration = Duration::from_secs(2);
/// Each wig-wag light is on for this long, then the other (the ICD gives no rate).
pub const WIG_WAG_HALF_PERIOD: Duration = Duration::from_millis(500);
/// The starter is cut above this valid RPM (Appendix B note 1, reading note 18).
pub const STARTER_CUTOUT_RPM: u16 = 500;
/// Motor currents while running, amps (the ICD gives none).
const FLAP_MOTOR_AMPS: f32 = 3.5;
const TRIM_MOTOR_AMPS: f32 = 0.8;

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

/// Something done to the unit from outside the wire: by a test, the page's demo, or a
/// scenario's timeline.
#[derive(Debug, Clone, PartialEq)]
pub enum SimCommand {
    /// Another display on the unit's serial bus sends DEVICE_POWER: the unit holds
    /// the device so until its switch changes, and the page never hears of it.
    OtherDisplayPower { device: u8, on: bool },
    /// Cockpit switch 1–10 is set on (closed) or off, as a person would. It drives
    /// the unit's input of the same number, unless the scenario's wiring says
    /// otherwise (`dead_switches`, `crossed_switches`).
    Switch { switch: u8, on: bool },
    /// A person flips cockpit switch 1–10 to its other position, and back after
    /// `hold`. Decision: the unit broadcasts its inputs at 1 Hz (SYSTEM_STATUS), so a
    /// hold under about a second may never be seen by a page, as on a real unit.
    FlipSwitch { switch: u8, hold: Duration },
    /// The device faults now with `code` (for 0, 29, 30: the motor's fault).
    Fault { device: u8, code: FaultCode },
    /// A short appears on (or leaves) a pin: SHORT_CIRCUIT whenever it is powered.
    Short { device: u8, on: bool },
    /// The pin's load changes, amps.
    Load { device: u8, amps: f32 },
    /// Nothing leaves the unit for this long; requests are still taken in.
    Silent(Duration),
    /// The unit's name for a device changes, as if set from another display (stored
    /// in its EEPROM, and nothing on the wire says so).
    Rename(DeviceName),
    /// These bytes go out on the wire as they are.
    Garbage(Vec<u8>),
    /// This many pseudo-random bytes go out on the wire.
    GarbageRandom(usize),
    /// The running alternator's regulator now holds this many volts.
    BusVolts(f32),
    /// Engine RPM the unit sees (as if valid in EXTERNAL_DATA); `None` forgets it.
    Rpm(Option<u16>),
    /// The starter button is pressed or released.
    Starter(bool),
    /// The motor runs by itself until the unit trips a runaway fault.
    Runaway {
        motor: MotorId,
        direction: MotorDirection,
    },
    /// The flap or trim switch input is held in a direction, or released.
    MotorSwitch {
        motor: MotorId,
        direction: Option<MotorDirection>,
    },
    /// A person holds the flap or trim switch in `direction` and lets go after
    /// `hold` (the motor runs as the switch drives it, meanwhile).
    PressMotorSwitch {
        motor: MotorId,
        direction: MotorDirection,
        hold: Duration,
    },
    /// Sets the system fault bit of FAULT_STATUS.
    SystemFault,
    /// Power off and on: RAM state is lost, the EEPROM is read again.
    PowerCycle,
    /// A processor reset without a power cycle (CU Warm Reset, Table 24 note 4).
    WarmReset,
    /// The next FLASH_PROG in the bootloader writes one byte wrong.
    CorruptNextFlashProg,
    /// SPEC_ACKs are lost (or no longer lost) on the way out, as on a noisy line: the
    /// unit still applies and stores each spec and keeps broadcasting.
    DropSpecAcks(bool),
}

impl SimCommand {
    /// The command a scenario event stands for.
    pub fn from_event(a: &EventAction) -> SimCommand {
        match *a {
            EventAction::Switch { switch, on } => SimCommand::Switch { switch, on },
            EventAction::Fault { device, code } => SimCommand::Fault {
                device,
                code: code.code(),
            },
            EventAction::Short { device, on } => SimCommand::Short { device, on },
            EventAction::Load { device, amps } => SimCommand::Load { device, amps },
            EventAction::Silent { seconds } => {
                SimCommand::Silent(Duration::from_secs_f64(seconds.max(0.0)))
            }
            EventAction::Garbage { bytes } => SimCommand::GarbageRandom(bytes),
            EventAction::BusVolts { volts } => SimCommand::BusVolts(volts),
            EventAction::Rpm { rpm } => SimCommand::Rpm(rpm),
            EventAction::Starter { on } => SimCommand::Starter(on),
            EventAction::Runaway { motor, direction } => SimCommand::Runaway { motor, direction },
            EventAction::MotorSwitch { motor, direction } => {
                SimCommand::MotorSwitch { motor, direction }
            }
            EventAction::SystemFault => SimCommand::SystemFault,
            EventAction::PowerCycle => SimCommand::PowerCycle,
            EventAction::WarmReset => SimCommand::WarmReset,
            EventAction::DropSpecAcks { on } => SimCommand::DropSpecAcks(on),
        }
    }
}

/// Counters of what crossed the wire.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WireStats {
    pub rx_bytes: u64,
    /// Intact frames of known messages.
    pub rx_frames: u64,
    /// Bytes outside any frame (noise, and the first byte of each bad candidate).
    pub garbage_bytes: u64,
    /// Candidates with a bad checksum or impossible length, and unknown messages.
    pub bad_frames: u64,
    /// Intact frames whose payload does not decode (a field out of range).
    pub malformed: u64,
    /// Well-formed frames the unit does nothing with: messages only a VP-X sends,
    /// requests for devices that do not exist, DEVICE_POWER to the starter or motors.
    pub ignored: u64,
    /// Replies sent (each echoes its request's command number).
    pub replies: u64,
    pub system_status: u64,
    pub device_status: u64,
    pub flap_trim_status: u64,
    pub fault_status: u64,
    pub tx_bytes: u64,
    /// Bytes dropped because the unit was silent.
    pub silenced_bytes: u64,
    /// SPEC_ACKs not sent because they are being dropped (the spec was applied).
    pub spec_acks_dropped: u64,
}

/// A snapshot of the unit for tests and tools.
#[derive(Debug, Clone, PartialEq)]
pub struct SimStats {
    pub wire: WireStats,
    pub boot: BootStats,
    pub in_bootloader: bool,
    /// Motor positions 0–255.
    pub flap_position: u8,
    pub pitch_trim_position: u8,
    pub roll_trim_position: u8,
    pub flap_running: bool,
    pub pitch_trim_running: bool,
    pub roll_trim_running: bool,
    /// Streams that ended because no TRIM_MOVE/FLAP_MOVE came for 300 ms (the 250 ms
    /// of reading note 19 plus the unit's margin, see `sim::motors`).
    pub flap_starvations: u64,
    pub pitch_trim_starvations: u64,
    pub roll_trim_starvations: u64,
    /// TRIM_MOVE/FLAP_MOVE messages that came more than 250 ms after the one before
    /// while the run went on: forgiven by the unit, a gap the EFIS should not leave.
    pub flap_late: u64,
    pub pitch_trim_late: u64,
    pub roll_trim_late: u64,
    /// Power state per device id, as DEVICE_STATUS reports it.
    pub powered: [bool; DEVICE_COUNT],
    /// Fault per device id, as FAULT_STATUS reports it.
    pub faults: [FaultCode; DEVICE_COUNT],
    pub system_fault: bool,
    pub config: UnitConfig,
    pub data_integrity: Option<DataIntegrityCode>,
    pub external_data_missing: bool,
    pub software_update_flag: bool,
    pub eeprom_writes: u64,
    /// Broadcast command count (the unit's own, reading note 14).
    pub broadcast_cnt: u8,
    /// The last log lines, oldest first.
    pub log: Vec<String>,
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

    // ------------------------------------------------------------------ input

    /// Bytes received at `now`.
    pub fn feed(&mut self, bytes: &[u8], now: Instant) {
        self.wire.rx_bytes += bytes.len() as u64;
        if self.in_bootloader() {
            self.feed_bootloader(bytes, now);
            return;
        }
        // One byte at a time (5760 bytes/s at most): a SOFTWARE_UPDATE hands every
        // byte after its last one to the bootloader, even those in the same read.
        for (i, b) in bytes.iter().enumerate() {
            let mut frames: Vec<Vec<u8>> = Vec::new();
            let wire = &mut self.wire;
            self.decoder.push(std::slice::from_ref(b), |e| match e {
                Event::Frame(f) => frames.push(f.as_bytes().to_vec()),
                Event::Skipped(b) | Event::Truncated(b) => wire.garbage_bytes += b.len() as u64,
                Event::BadChecksum(_) | Event::BadLength(_) => {
                    wire.garbage_bytes += 1;
                    wire.bad_frames += 1;
                }
                Event::UnknownMessage(_) => wire.bad_frames += 1,
            });
            for f in &frames {
                self.wire.rx_frames += 1;
                let frame = crate::protocol::FrameRef::parse(f).expect("the decoder checked it");
                let h = frame.header();
                match Packet::parse(&frame) {
                    Ok(p) => self.handle(p, now),
                    // §6.1.2: the VP-X ignores a VERSION request's payload, so one of
                    // any length (too short to decode as Table 11) is still answered;
                    // so is an EEPROM_ERASE request without its byte (§6.1.4).
                    Err(_) if h.id == Version::ID && self.for_us(h.src, h.dst) => {
                        self.version(h.cnt, now)
                    }
                    Err(_) if h.id == EepromErase::ID && self.for_us(h.src, h.dst) => {
                        self.eeprom_erase(h.cnt, now);
                        self.update_power(now);
                    }
                    Err(_) => self.malformed(h, frame.payload(), now),
                }
            }
            if self.in_bootloader() {
                self.feed_bootloader(&bytes[i + 1..], now);
                return;
            }
        }
    }

    fn feed_bootloader(&mut self, bytes: &[u8], now: Instant) {
        let Mode::Boot(b) = &mut self.mode else {
            return;
        };
        let mut out = Vec::new();
        let exit = b.feed(bytes, &mut self.flash, &mut out);
        self.boot_stats = b.stats();
        self.emit_raw(&out, now);
        if exit {
            let programmed = self.boot_stats.pages_programmed > 0;
            self.log(if programmed {
                "bootloader EXIT: rebooting with the Software Update flag set".into()
            } else {
                "bootloader EXIT: nothing was programmed, rebooting".into()
            });
            self.boot(now, Start::BootloaderExit { programmed });
        }
    }

    /// An intact frame whose payload did not decode. A spec still gets its SPEC_ACK
    /// (OutOfRange), so the EFIS learns the unit refused it rather than waiting.
    fn malformed(&mut self, h: crate::protocol::FrameHeader, payload: &[u8], now: Instant) {
        self.wire.malformed += 1;
        let first = payload.first().copied().unwrap_or(0);
        let id = match h.id {
            DeviceSpec::ID | DeviceName::ID => Some(first),
            SystemSpec::ID => Some(SYSTEM_SPEC_ID),
            WigWagSpec::ID => Some(WIG_WAG_SPEC_ID),
            FlapSpec::ID => Some(FLAPS),
            TrimSpec::ID => Some(if first & 0x80 != 0 { TRIM_R } else { TRIM_P }),
            _ => None,
        };
        if let Some(device_id) = id {
            self.reply(
                h.cnt,
                SpecAck {
                    device_id,
                    error: Some(SpecAckError::OutOfRange),
                },
                now,
            );
        }
    }

    /// Whether a frame from `src` to `dst` is a request for this unit.
    fn for_us(&self, src: Node, dst: Node) -> bool {
        matches!(dst, Node::Vpx | Node::Broadcast) && src != Node::Vpx
    }

    /// The VERSION reply (ICD Table 11).
    fn version(&mut self, cnt: u8, now: Instant) {
        let v = Version {
            hardware_version: HardwareVersion::from_byte(self.opts.hardware_version),
            software_major: self.opts.software_version.0,
            software_minor: self.opts.software_version.1,
        };
        self.reply(cnt, v, now)
    }

    /// EEPROM_ERASE, ICD §6.1.4: defaults back, DATA_INTEGRITY until the next reset or
    /// power cycle.
    fn eeprom_erase(&mut self, cnt: u8, now: Instant) {
        let defaults = UnitConfig::default();
        let code = match self.eeprom.store(&defaults) {
            Ok(()) => 0,
            Err(e) => {
                self.log(format!("EEPROM_ERASE: cannot write the EEPROM: {e}"));
                1
            }
        };
        self.config = defaults;
        self.integrity = Some(DataIntegrityCode::GeneralEeprom);
        self.log("EEPROM_ERASE: configuration back to the ICD Appendix F defaults".into());
        self.reply(
            cnt,
            EepromErase {
                response_code: code,
            },
            now,
        );
    }

    fn handle(&mut self, p: Packet, now: Instant) {
        if !self.for_us(p.src, p.dst) {
            self.wire.ignored += 1;
            return;
        }
        let cnt = p.cnt;
        match p.message {
            Message::Ping(Ping { ack: false }) => self.reply(cnt, Ping { ack: true }, now),
            Message::Version(_) => self.version(cnt, now),
            Message::SoftwareUpdate(_) => {
                // §6.1.3: no reply; the unit goes quiet and listens for §7 frames.
                self.log("SOFTWARE_UPDATE: entering the bootloader".into());
                for m in &mut self.motors {
                    m.halt(now);
                }
                self.mode = Mode::Boot(Bootloader::default());
            }
            Message::EepromErase(_) => self.eeprom_erase(cnt, now),
            Message::DeviceSpecQuery(q) => self.spec_query(cnt, q.device_id, now),
            m @ (Message::DeviceSpec(_)
            | Message::SystemSpec(_)
            | Message::TrimSpec(_)
            | Message::FlapSpec(_)
            | Message::WigWagSpec(_)
            | Message::DeviceName(_)) => self.spec(cnt, &m, now),
            Message::DeviceNameQuery(q) => match self.config.names.get(q.device_id as usize) {
                Some(&name) => self.reply(
                    cnt,
                    DeviceName {
                        device_id: q.device_id,
                        name,
                    },
                    now,
                ),
                // Table 22: ids 0–30 only.
                None => self.wire.ignored += 1,
            },
            // Decision (Table 23 notes 1 and 2): a query for a device whose display
            // cannot be set is still answered with what holds: Starter, EFIS and
            // Field_Pri (1–3) are always enabled; the flaps (0) and trims (29, 30)
            // are as their FLAP_SPEC / TRIM_SPEC enable flag says. Setting them is
            // ignored, as the table's range 4–28 says.
            Message::DeviceEnable(DeviceEnable {
                device_id: id @ (0..=3 | TRIM_R | TRIM_P),
                flag: EnableFlag::Query,
            }) => {
                let on = match id {
                    FLAPS => self.config.flap.enabled,
                    TRIM_R => self.config.roll_trim.enabled,
                    TRIM_P => self.config.pitch_trim.enabled,
                    _ => true,
                };
                self.reply_enable(cnt, id, on, now);
            }
            Message::DeviceEnable(e) => {
                if validate::device_enable(&self.config, &e).is_err() {
                    self.wire.ignored += 1;
                } else if e.flag == EnableFlag::Query {
                    let on = self.config.enabled[e.device_id as usize];
                    self.reply_enable(cnt, e.device_id, on, now);
                } else {
                    // Table 23: a set has no answer.
                    let mut cfg = self.config.clone();
                    cfg.apply_device_enable(&e);
                    self.commit(cfg);
                }
            }
            Message::DeviceStatusQuery(_) => {
                let s = self.device_status();
                self.reply(cnt, s, now);
            }
            Message::DevicePower(d) => self.device_power(d, now),
            // Decision: a stop (power 0) is honoured whatever its other bytes hold, so
            // a motor never runs on to the stream timeout because the stop message
            // carried a direction (or, for TRIM_MOVE, a trim type) outside Tables 30
            // and 31. A stop of an unknown trim type stops both trims. A run ("on")
            // with such a byte is refused: the unit cannot know which way to go.
            Message::TrimMove(t) => {
                let motors: &[MotorId] = match t.trim_type {
                    TrimType::Pitch => &[MotorId::Pitch],
                    TrimType::Roll => &[MotorId::Roll],
                    TrimType::Unknown(_) if !t.on => &[MotorId::Pitch, MotorId::Roll],
                    TrimType::Unknown(_) => {
                        self.wire.malformed += 1;
                        return;
                    }
                };
                let dir = match t.direction {
                    TrimDirection::DownOrRight => MotorDirection::Down,
                    TrimDirection::UpOrLeft => MotorDirection::Up,
                    // Not looked at by a stop.
                    TrimDirection::Unknown(_) if !t.on => MotorDirection::Up,
                    TrimDirection::Unknown(_) => {
                        self.wire.malformed += 1;
                        return;
                    }
                };
                if matches!(t.trim_type, TrimType::Unknown(_))
                    || matches!(t.direction, TrimDirection::Unknown(_))
                {
                    self.wire.malformed += 1;
                }
                for &motor in motors {
                    self.stream(motor, t.on, dir, now);
                }
            }
            Message::FlapMove(f) => {
                let dir = match f.direction {
                    FlapDirection::Up => MotorDirection::Up,
                    FlapDirection::Down => MotorDirection::Down,
                    FlapDirection::Unknown(_) if !f.on => {
                        // A stop all the same (see TRIM_MOVE above), counted as odd.
                        self.wire.malformed += 1;
                        MotorDirection::Up
                    }
                    FlapDirection::Unknown(_) => {
                        self.wire.malformed += 1;
                        return;
                    }
                };
                // Decision: the overspeed inhibit (Table 16 "Max Speed") also refuses
                // FLAP_MOVE down, so the page's "inhibited" is never contradicted.
                if f.on && dir == MotorDirection::Down && self.flap_down_inhibited(now) {
                    self.wire.ignored += 1;
                    return;
                }
                self.stream(MotorId::Flap, f.on, dir, now);
            }
            Message::WigWagMode(w) => match w.mode {
                WigWagModeSetting::Unknown(_) => self.wire.malformed += 1,
                m => self.wig_wag_mode = m,
            },
            Message::DeviceClear(c) => self.clear(c.device_id, now),
            Message::ExternalData(d) => self.external = Some((now, d)),
            // Messages only a VP-X sends.
            _ => self.wire.ignored += 1,
        }
        self.update_power(now);
    }

    fn stream(&mut self, motor: MotorId, on: bool, dir: MotorDirection, now: Instant) {
        let g = self.geometry(motor, now);
        if !self.motors[motor_index(motor)].stream(on, dir, &g, now) {
            self.wire.ignored += 1;
        }
    }

    fn spec_query(&mut self, cnt: u8, id: u8, now: Instant) {
        let c = &self.config;
        // Reading note 13.
        let m: Message = match id {
            FLAPS => c.flap.into(),
            TRIM_R => c.roll_trim.into(),
            TRIM_P => c.pitch_trim.into(),
            1..=28 => c.devices[id as usize].into(),
            SYSTEM_SPEC_ID => c.system.into(),
            WIG_WAG_SPEC_ID => c.wig_wag.into(),
            // Table 18 note 1: invalid ids are ignored.
            _ => {
                self.wire.ignored += 1;
                return;
            }
        };
        self.reply(cnt, m, now);
    }

    /// A *_SPEC or DEVICE_NAME: judged by the shared §6.2 rules, stored if accepted.
    fn spec(&mut self, cnt: u8, m: &Message, now: Instant) {
        let device_id = match m {
            Message::DeviceSpec(s) => s.device_id,
            Message::DeviceName(n) => n.device_id,
            Message::SystemSpec(_) => SYSTEM_SPEC_ID,
            Message::WigWagSpec(_) => WIG_WAG_SPEC_ID,
            Message::FlapSpec(_) => FLAPS,
            // Table 19 gives no id for TRIM_SPEC; the axis's own device id is used.
            Message::TrimSpec(t) if t.trim_type == TrimType::Roll => TRIM_R,
            _ => TRIM_P,
        };
        let mut cfg = self.config.clone();
        let verdict = validate::accept(&mut cfg, m).unwrap_or(Err(SpecAckError::BadConfig));
        let error = match verdict {
            Ok(()) => {
                if self.commit(cfg) {
                    None
                } else {
                    Some(SpecAckError::EepromWrite)
                }
            }
            Err(e) => Some(e),
        };
        if self.drop_spec_acks {
            // The spec above is applied and stored; only its answer is lost.
            self.wire.spec_acks_dropped += 1;
            return;
        }
        self.reply(cnt, SpecAck { device_id, error }, now);
    }

    /// Stores a changed configuration; `false` (and nothing changed) if the EEPROM
    /// could not be written.
    fn commit(&mut self, cfg: UnitConfig) -> bool {
        match self.eeprom.store(&cfg) {
            Ok(()) => {
                self.config = cfg;
                true
            }
            Err(e) => {
                self.log(format!("EEPROM write failed: {e}"));
                false
            }
        }
    }

    fn device_power(&mut self, d: DevicePower, now: Instant) {
        match d.device_id {
            // Appendix B note 1: the starter cannot be switched from outside; the
            // motors run only by TRIM_MOVE / FLAP_MOVE.
            STARTER | FLAPS | TRIM_R | TRIM_P => self.wire.ignored += 1,
            id @ 2..=28 => {
                if self.faults[id as usize].is_fault() {
                    // Appendix E: a faulted pin stays off until DEVICE_CLEAR.
                    self.wire.ignored += 1;
                } else {
                    self.overrides[id as usize] = Some(d.on);
                }
            }
            _ => self.wire.ignored += 1,
        }
        self.update_power(now);
    }

    /// DEVICE_CLEAR, ICD §6.5.1.
    fn clear(&mut self, id: u8, now: Instant) {
        if id == SYSTEM_FAULT_ID {
            self.system_fault = false;
            return;
        }
        if let Some(m) = motor_of_device(id) {
            let g = self.geometry(m, now);
            let motor = &mut self.motors[motor_index(m)];
            motor.advance(&g, now);
            motor.clear();
            return;
        }
        let Some(slot) = self.faults.get_mut(id as usize) else {
            self.wire.ignored += 1;
            return;
        };
        if !slot.is_fault() {
            return;
        }
        *slot = FaultCode::NoFault;
        // Note 2: the device returns to its switch's state, and every switch-11 device
        // comes back on. Decision: that means their DEVICE_POWER overrides are dropped.
        self.overrides[id as usize] = None;
        for (i, d) in self.config.devices.iter().enumerate() {
            if d.switch_id == SwitchId::AlwaysOn {
                self.overrides[i] = None;
            }
        }
        self.log(format!("device {id} fault cleared by DEVICE_CLEAR"));
        self.update_power(now);
    }

    // ------------------------------------------------------------ commands

    /// Something done from outside the wire.
    pub fn apply(&mut self, c: SimCommand, now: Instant) {
        match c {
            SimCommand::Switch { switch, on } => self.set_cockpit_switch(switch, on),
            SimCommand::FlipSwitch { switch, hold } => {
                if let Some(&was) = self.cockpit.get((switch as usize).wrapping_sub(1)) {
                    self.set_cockpit_switch(switch, !was);
                    self.pending
                        .push((now + hold, SimCommand::Switch { switch, on: was }));
                }
            }
            SimCommand::Fault { device, code } => {
                if let Some(m) = motor_of_device(device) {
                    self.motors[motor_index(m)].set_fault(code, now);
                } else if let Some(f) = self.faults.get_mut(device as usize) {
                    *f = code;
                }
                self.log(format!("device {device}: {} injected", code.name()));
            }
            SimCommand::OtherDisplayPower { device, on } => {
                self.log(format!("another display: DEVICE_POWER {device} {on}"));
                self.device_power(
                    DevicePower {
                        device_id: device,
                        on,
                    },
                    now,
                );
            }
            SimCommand::Short { device, on } => {
                if let Some(s) = self.shorts.get_mut(device as usize) {
                    *s = on;
                }
            }
            SimCommand::Load { device, amps } => {
                if let Some(l) = self.loads.get_mut(device as usize) {
                    *l = amps.max(0.0);
                }
            }
            SimCommand::Silent(d) => {
                self.log(format!("going silent for {:.1} s", d.as_secs_f64()));
                self.silent_until = Some(now + d);
            }
            SimCommand::Rename(name) => {
                let mut cfg = self.config.clone();
                cfg.apply_device_name(&name);
                if self.commit(cfg) {
                    self.log(format!(
                        "device {} renamed {:?}",
                        name.device_id,
                        name.text()
                    ));
                }
            }
            SimCommand::DropSpecAcks(on) => {
                self.log(format!(
                    "{} SPEC_ACKs",
                    if on { "dropping" } else { "sending" }
                ));
                self.drop_spec_acks = on;
            }
            SimCommand::Garbage(bytes) => self.emit_raw(&bytes, now),
            SimCommand::GarbageRandom(n) => {
                let bytes: Vec<u8> = (0..n).map(|_| self.rng.next() as u8).collect();
                self.emit_raw(&bytes, now);
            }
            SimCommand::BusVolts(v) => self.regulator_volts = Some(v),
            SimCommand::Rpm(r) => self.engine_rpm = r,
            SimCommand::Starter(on) => self.starter_pressed = on,
            SimCommand::Runaway { motor, direction } => {
                let g = self.geometry(motor, now);
                self.motors[motor_index(motor)].runaway(direction, &g, now);
                self.log(format!("{motor:?} motor runaway injected"));
            }
            SimCommand::MotorSwitch { motor, direction } => {
                let g = self.geometry(motor, now);
                let inhibited = motor == MotorId::Flap
                    && direction == Some(MotorDirection::Down)
                    && self.flap_down_inhibited(now);
                let held = if inhibited { None } else { direction };
                self.motors[motor_index(motor)].switch(held, &g, now);
            }
            SimCommand::PressMotorSwitch {
                motor,
                direction,
                hold,
            } => {
                self.apply(
                    SimCommand::MotorSwitch {
                        motor,
                        direction: Some(direction),
                    },
                    now,
                );
                let release = SimCommand::MotorSwitch {
                    motor,
                    direction: None,
                };
                self.pending.push((now + hold, release));
            }
            SimCommand::SystemFault => self.system_fault = true,
            SimCommand::PowerCycle => {
                self.log("power cycle".into());
                self.boot(now, Start::Cold);
            }
            SimCommand::WarmReset => {
                self.log("warm reset".into());
                self.boot(now, Start::Warm);
            }
            SimCommand::CorruptNextFlashProg => {
                if let Mode::Boot(b) = &mut self.mode {
                    b.corrupt_next_prog = true;
                } else {
                    self.log("CorruptNextFlashProg ignored: not in the bootloader".into());
                }
            }
        }
        self.update_power(now);
    }

    /// A cockpit switch moves; the inputs it reaches through the wiring follow.
    fn set_cockpit_switch(&mut self, switch: u8, on: bool) {
        let Some(s) = self.cockpit.get_mut((switch as usize).wrapping_sub(1)) else {
            return;
        };
        *s = on;
        let now_in = inputs(&self.cockpit, &self.switch_wiring);
        for (i, (&was, &is)) in self.switches.iter().zip(&now_in).enumerate() {
            if was != is {
                // ICD Appendix A: DEVICE_POWER overrides last "until the switch is
                // cycled". Our reading, the page's too (`model::hold`): ANY change of
                // the input ends the override, a single change, not a round trip.
                let input = SwitchId::Input(i as u8 + 1);
                for (d, spec) in self.config.devices.iter().enumerate() {
                    if spec.switch_id == input {
                        self.overrides[d] = None;
                    }
                }
            }
        }
        self.switches = now_in;
    }

    // ------------------------------------------------------------ time

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

    fn broadcast_slow(&mut self, now: Instant) {
        let s = self.system_status(now);
        self.broadcast(s, now);
        self.wire.system_status += 1;
        let d = self.device_status();
        self.broadcast(d, now);
        self.wire.device_status += 1;
        // §6.3.4: only while a fault exists (reading note 9).
        if let Some(f) = self.fault_status() {
            self.broadcast(f, now);
            self.wire.fault_status += 1;
        }
    }

    // ------------------------------------------------------------ output

    fn silent(&mut self, now: Instant) -> bool {
        match self.silent_until {
            Some(t) if now < t => true,
            Some(_) => {
                self.silent_until = None;
                self.log("talking again".into());
                false
            }
            None => false,
        }
    }

    fn emit_raw(&mut self, bytes: &[u8], now: Instant) {
        if self.silent(now) {
            self.wire.silenced_bytes += bytes.len() as u64;
        } else {
            self.wire.tx_bytes += bytes.len() as u64;
            self.out.extend_from_slice(bytes);
        }
    }

    fn reply(&mut self, cnt: u8, m: impl Into<Message>, now: Instant) {
        self.wire.replies += 1;
        let bytes = Packet::from_vpx(cnt, m).to_bytes();
        self.emit_raw(&bytes, now);
    }

    /// DEVICE_ENABLE's answer to a query (Table 23, flag 2 asked, 0 or 1 told).
    fn reply_enable(&mut self, cnt: u8, device_id: u8, on: bool, now: Instant) {
        let flag = if on {
            EnableFlag::Enabled
        } else {
            EnableFlag::Disabled
        };
        self.reply(cnt, DeviceEnable { device_id, flag }, now);
    }

    fn broadcast(&mut self, m: impl Into<Message>, now: Instant) {
        let cnt = self.cnt;
        self.cnt = self.cnt.wrapping_add(1);
        let bytes = Packet::from_vpx(cnt, m).to_bytes();
        self.emit_raw(&bytes, now);
    }

    // ------------------------------------------------------------ the model

    fn fresh_external(&self, now: Instant) -> Option<&ExternalData> {
        self.external
            .as_ref()
            .filter(|(at, _)| now.saturating_duration_since(*at) <= EXTERNAL_DATA_TIMEOUT)
            .map(|(_, d)| d)
    }

    fn external_missing(&self, now: Instant) -> bool {
        let since = self.external.map_or(self.booted_at, |(at, _)| at);
        now.saturating_duration_since(since) > EXTERNAL_DATA_TIMEOUT
    }

    fn ias(&self, now: Instant) -> Option<u16> {
        self.fresh_external(now)
            .filter(|d| d.valid.indicated_airspeed)
            .map(|d| d.indicated_airspeed)
    }

    /// IAS, else ground speed (Table 15 note 5, Table 17 note 4).
    fn speed(&self, now: Instant) -> Option<u16> {
        self.ias(now).or_else(|| {
            self.fresh_external(now)
                .filter(|d| d.valid.ground_speed)
                .map(|d| d.ground_speed)
        })
    }

    fn rpm(&self, now: Instant) -> Option<u16> {
        let ext = self
            .fresh_external(now)
            .filter(|d| d.valid.rpm)
            .map(|d| d.rpm);
        ext.or(self.engine_rpm)
    }

    fn flap_down_inhibited(&self, now: Instant) -> bool {
        let max = self.config.flap.max_speed;
        max > 0 && self.ias(now).is_some_and(|ias| ias > max)
    }

    fn geometry(&self, m: MotorId, now: Instant) -> Geometry {
        let c = &self.config;
        match m {
            MotorId::Flap => Geometry {
                enabled: c.flap.enabled,
                up: c.flap.up,
                down: c.flap.down,
                stops: [c.flap.midpoint_1, c.flap.midpoint_2],
                position_mode: c.flap.mode == FlapMode::PositionBased,
                endpoint_run: Duration::from_millis(c.flap.endpoint_duration.0 as u64 * 100),
                rate: FLAP_RATE,
                reversed: self.runs_reversed(m, c.flap.polarity),
                stuck: self.motor_wiring[motor_index(m)].stuck,
            },
            MotorId::Pitch | MotorId::Roll => {
                let t = if m == MotorId::Pitch {
                    &c.pitch_trim
                } else {
                    &c.roll_trim
                };
                // Table 15 notes 5, 6: reduced power above the speed, pitch only.
                let reduced = m == MotorId::Pitch
                    && self.speed(now).is_some_and(|s| s > t.speed)
                    && t.power < 100;
                let rate = if reduced {
                    TRIM_RATE * t.power as f32 / 100.0
                } else {
                    TRIM_RATE
                };
                Geometry {
                    enabled: t.enabled,
                    up: t.up,
                    down: t.down,
                    stops: [0, 0],
                    position_mode: false,
                    endpoint_run: Duration::ZERO,
                    rate,
                    reversed: self.runs_reversed(m, t.polarity),
                    stuck: self.motor_wiring[motor_index(m)].stuck,
                }
            }
        }
    }

    /// Table 15/16 note 3: the polarity flag sets the direction the motor runs, so
    /// an inverted setting undoes leads that are swapped (and swaps good ones).
    fn runs_reversed(&self, m: MotorId, polarity: Polarity) -> bool {
        self.motor_wiring[motor_index(m)].reversed ^ (polarity == Polarity::Inverted)
    }

    fn switch_on(&self, s: SwitchId) -> bool {
        match s {
            SwitchId::Off => false,
            SwitchId::Input(n) => self.switches.get(n as usize - 1).copied().unwrap_or(false),
            SwitchId::AlwaysOn => true,
            SwitchId::Unknown(_) => false,
        }
    }

    /// What the pin would be without faults: its switch, or a DEVICE_POWER override.
    fn commanded(&self, id: usize) -> bool {
        self.overrides[id].unwrap_or_else(|| self.switch_on(self.config.devices[id].switch_id))
    }

    /// Recomputes every pin: switches, overrides, alternators, wig-wag, starter, and
    /// the faults that powering a pin can trip. A tripped alternator is replaced by
    /// the other one in the same instant.
    fn update_power(&mut self, now: Instant) {
        for _ in 0..3 {
            if !self.compute_power(now) {
                break;
            }
        }
    }

    /// One pass of [`Unit::update_power`]; `true` when an alternator tripped.
    fn compute_power(&mut self, now: Instant) -> bool {
        if self.in_bootloader() {
            self.powered = [false; DEVICE_COUNT];
            return false;
        }
        // Starter: Appendix B note 1.
        if self.starter_pressed && self.rpm(now).is_some_and(|r| r > STARTER_CUTOUT_RPM) {
            self.starter_pressed = false;
            self.log("starter cut out: engine RPM above 500".into());
        }
        let mut want = [false; DEVICE_COUNT];
        for (id, w) in want.iter_mut().enumerate().skip(EFIS as usize) {
            if id <= 28 {
                *w = self.commanded(id);
            }
        }
        want[STARTER as usize] = self.starter_pressed;
        // "Only one alternator runs at a time." Decision: the primary wins; the
        // secondary runs only while the primary is off or faulted.
        let primary_on = want[FIELD_PRI as usize] && !self.faults[FIELD_PRI as usize].is_fault();
        if let Some(sec) = self.config.system.secondary_alternator
            && primary_on
            && let Some(w) = want.get_mut(sec as usize)
        {
            *w = false;
        }
        self.apply_wig_wag(&mut want, now);

        #[allow(clippy::needless_range_loop)] // `id` indexes five arrays and names the pin
        for id in 1..=28usize {
            if !want[id] || self.faults[id].is_fault() {
                continue;
            }
            let spec = self.config.devices[id];
            let load = self.load(id);
            let code = if self.shorts[id] {
                FaultCode::ShortCircuit
            } else if load > spec.circuit_breaker as f32 {
                FaultCode::OverCurrent
            } else if spec.current_fault
                && device::device(id as u8).is_some_and(|d| d.current_fault_support)
                && load <= 0.0
            {
                FaultCode::CurrentFault
            } else {
                continue;
            };
            self.faults[id] = code;
            self.log(format!(
                "device {id} ({}): {}",
                device::device(id as u8).map_or("?", |d| d.system_name),
                code.name()
            ));
        }
        for (id, p) in self.powered.iter_mut().enumerate() {
            *p = match motor_of_device(id as u8) {
                Some(m) => self.motors[motor_index(m)].running(now),
                None => want[id] && !self.faults[id].is_fault(),
            };
        }

        // Table 14 note 1: above the limit the active alternator is turned off.
        let limit = match self.config.system.overvoltage_limit {
            OvervoltageLimit::V32 => 32.0,
            _ => 16.0,
        };
        let mut tripped = false;
        if let Some(alt) = self.active_alternator()
            && self.bus_volts(0.0) > limit
        {
            self.faults[alt] = FaultCode::OverVoltage;
            self.powered[alt] = false;
            self.regulator_volts = None;
            tripped = true;
            self.log(format!("device {alt}: OVER_VOLTAGE, alternator off"));
        }

        // Table 24 notes 2, 3: 48 A follows the current; 60 A clears below 48 A.
        let total = self.total_amps();
        self.over_48 = total > 48.0;
        if total > 60.0 {
            self.over_60 = true;
        } else if total < 48.0 {
            self.over_60 = false;
        }
        tripped
    }

    fn apply_wig_wag(&mut self, want: &mut [bool; DEVICE_COUNT], now: Instant) {
        let ww = self.config.wig_wag;
        let devices: Vec<usize> = [ww.device_one, ww.device_two]
            .into_iter()
            .flatten()
            .map(|d| d as usize)
            .filter(|&d| d < DEVICE_COUNT)
            .collect();
        let lit = !devices.is_empty() && devices.iter().all(|&d| want[d]);
        if !lit {
            self.wig_wag_since = None;
            self.wig_wag_active = false;
            return;
        }
        let since = *self.wig_wag_since.get_or_insert(now);
        let warm =
            now.saturating_duration_since(since) >= Duration::from_secs(ww.warm_up_period as u64);
        // Table 17: "the speed at which the wig-wag function is engaged"; Table 44:
        // "speed to start wig-wag" (70). Decision: the lights flash at that speed and
        // above (in flight, where they make the aircraft seen) and burn steady below it
        // (taxiing, where they light the way). Note 4: no valid speed, no wig-wag.
        let fast_enough = self.speed(now).is_some_and(|s| s >= ww.speed as u16);
        self.wig_wag_active = self.wig_wag_mode == WigWagModeSetting::Auto && warm && fast_enough;
        if self.wig_wag_active {
            let phase = (now.saturating_duration_since(since).as_millis()
                / WIG_WAG_HALF_PERIOD.as_millis())
                % 2;
            for (i, &d) in devices.iter().enumerate() {
                want[d] = (i as u128 % 2) == phase;
            }
        }
    }

    fn active_alternator(&self) -> Option<usize> {
        if self.powered[FIELD_PRI as usize] {
            return Some(FIELD_PRI as usize);
        }
        self.config
            .system
            .secondary_alternator
            .map(|s| s as usize)
            .filter(|&s| self.powered.get(s).copied().unwrap_or(false))
    }

    fn bus_volts(&self, noise: f32) -> f32 {
        match self.active_alternator() {
            Some(_) => self.regulator_volts.unwrap_or(self.nominal_volts) + noise,
            // On the battery alone the bus sags with the load.
            None => self.battery_volts - 0.02 * self.total_amps() + noise,
        }
    }

    fn amps(&self, id: usize) -> f32 {
        if !self.powered[id] {
            return 0.0;
        }
        match motor_of_device(id as u8) {
            Some(MotorId::Flap) => FLAP_MOTOR_AMPS,
            Some(_) => TRIM_MOTOR_AMPS,
            None => self.load(id),
        }
    }

    /// What the pin's wiring draws while powered: nothing if the load is not connected.
    fn load(&self, id: usize) -> f32 {
        if self.open_circuits[id] {
            0.0
        } else {
            self.loads[id]
        }
    }

    fn total_amps(&self) -> f32 {
        (0..DEVICE_COUNT).map(|i| self.amps(i)).sum()
    }

    fn tenths(v: f32) -> u16 {
        (v * 10.0).round().clamp(0.0, u16::MAX as f32) as u16
    }

    // ------------------------------------------------------------ messages

    fn device_status(&mut self) -> DeviceStatus {
        let mut current = [Tenths(0); DEVICE_COUNT];
        for (id, c) in current.iter_mut().enumerate() {
            let a = self.amps(id);
            if a > 0.0 {
                // ±3 % noise so the page has something alive to show.
                let n = 1.0 + 0.03 * self.rng.unit();
                *c = Tenths(Self::tenths(a * n).max(1));
            }
        }
        DeviceStatus {
            on: self.powered,
            current,
        }
    }

    fn system_status(&mut self, now: Instant) -> SystemStatus {
        let noise = 0.05 * self.rng.unit();
        let volts = self.bus_volts(noise);
        let mut switches = SwitchInputs {
            switch: self.switches,
            ..SwitchInputs::default()
        };
        for (m, held) in self.motors.iter().map(|m| (m.id, m.switch_held())) {
            let (up, down) = match m {
                MotorId::Flap => (&mut switches.flap_up, &mut switches.flap_down),
                MotorId::Pitch => (&mut switches.pitch_trim_up, &mut switches.pitch_trim_down),
                MotorId::Roll => (&mut switches.roll_trim_up, &mut switches.roll_trim_down),
            };
            *up = held == Some(MotorDirection::Up);
            *down = held == Some(MotorDirection::Down);
        }
        let total = self.total_amps() * (1.0 + 0.01 * self.rng.unit());
        SystemStatus {
            system_current: Tenths(Self::tenths(total)),
            main_bus_volts: SignedTenths((volts * 10.0).round() as i16),
            aux_battery_volts: Tenths(Self::tenths(self.aux_battery_volts)),
            internal_temp: self.temperature_c,
            switches,
            misc: MiscFlags {
                starter_annunciator: self.powered[STARTER as usize],
                wig_wag_mode: self.wig_wag_mode,
                software_update: self.software_update,
                wig_wag_active: self.wig_wag_active,
            },
            faults: SystemFaultFlags {
                current_over_48a: self.over_48,
                current_over_60a: self.over_60,
                warm_reset: self.warm_reset,
                data_integrity_failure: self.integrity.is_some(),
                external_data_missing: self.external_missing(now),
            },
            data_integrity_code: self.integrity,
        }
    }

    fn fault_codes(&self) -> [FaultCode; DEVICE_COUNT] {
        let mut codes = self.faults;
        for m in &self.motors {
            codes[motor_device(m.id) as usize] = m.fault;
        }
        codes
    }

    fn fault_status(&self) -> Option<FaultStatus> {
        let codes = self.fault_codes();
        let faulted: [bool; DEVICE_COUNT] = std::array::from_fn(|i| codes[i].is_fault());
        if !self.system_fault && !faulted.iter().any(|&f| f) {
            return None;
        }
        Some(FaultStatus {
            faulted,
            system_fault: self.system_fault,
            // Table 28: the full 35 bytes, a code for every device.
            codes: std::array::from_fn(|i| Some(codes[i])),
        })
    }

    fn flap_trim_status(&self, now: Instant) -> FlapTrimStatus {
        let c = &self.config;
        let [flap, pitch, roll] = &self.motors;
        let fg = self.geometry(MotorId::Flap, now);
        // Table 16 note 5: flaps further down than the overspeed position with the
        // IAS above the max flap speed.
        let overspeed = c.flap.enabled
            && self.flap_down_inhibited(now)
            && fg.extension(flap.position) > fg.extension(c.flap.overspeed_position as f32);
        let trim = |t: &TrimSpec, m: &Motor| TrimFlags {
            enabled: t.enabled,
            motor_running: m.running(now),
            fault: m.faulted(),
        };
        // Table 27 bytes 13–18: zero when that trim is not enabled.
        let points = |t: &TrimSpec| {
            if t.enabled {
                (t.up, t.down, t.neutral)
            } else {
                (0, 0, 0)
            }
        };
        let (pu, pd, pn) = points(&c.pitch_trim);
        let (ru, rd, rn) = points(&c.roll_trim);
        FlapTrimStatus {
            flap: FlapFlags {
                enabled: c.flap.enabled,
                motor_running: flap.running(now),
                fault: flap.faulted(),
                overspeed_alarm: overspeed,
                down_switch_inhibited: c.flap.enabled && self.flap_down_inhibited(now),
            },
            pitch_trim: trim(&c.pitch_trim, pitch),
            roll_trim: trim(&c.roll_trim, roll),
            flap_position: flap.position_byte(),
            pitch_trim_position: pitch.position_byte(),
            roll_trim_position: roll.position_byte(),
            flap_fault: flap.fault,
            pitch_trim_fault: pitch.fault,
            roll_trim_fault: roll.fault,
            flap_up: c.flap.up,
            flap_down: c.flap.down,
            flap_midpoint_1: c.flap.midpoint_1,
            flap_midpoint_2: c.flap.midpoint_2,
            pitch_trim_up: pu,
            pitch_trim_down: pd,
            pitch_trim_neutral: pn,
            roll_trim_up: ru,
            roll_trim_down: rd,
            roll_trim_neutral: rn,
        }
    }

    /// A snapshot for tests and tools (`log` is filled in by the runner).
    pub fn snapshot(&self, now: Instant) -> SimStats {
        let [f, p, r] = &self.motors;
        let boot = match &self.mode {
            Mode::Boot(b) => b.stats(),
            Mode::Normal => self.boot_stats,
        };
        SimStats {
            wire: self.wire,
            boot,
            in_bootloader: self.in_bootloader(),
            flap_position: f.position_byte(),
            pitch_trim_position: p.position_byte(),
            roll_trim_position: r.position_byte(),
            flap_running: f.running(now),
            pitch_trim_running: p.running(now),
            roll_trim_running: r.running(now),
            flap_starvations: f.starvations,
            pitch_trim_starvations: p.starvations,
            roll_trim_starvations: r.starvations,
            flap_late: f.late,
            pitch_trim_late: p.late,
            roll_trim_late: r.late,
            powered: self.powered,
            faults: self.fault_codes(),
            system_fault: self.system_fault,
            config: self.config.clone(),
            data_integrity: self.integrity,
            external_data_missing: self.external_missing(now),
            software_update_flag: self.software_update,
            eeprom_writes: self.eeprom.writes,
            broadcast_cnt: self.cnt,
            log: Vec::new(),
        }
    }
}

/// The unit's inputs 1–10 as the wiring delivers the cockpit switches: an input is
/// closed when any switch wired to it is.
fn inputs(cockpit: &[bool; 10], wiring: &[Option<usize>; 10]) -> [bool; 10] {
    let mut out = [false; 10];
    for (&on, to) in cockpit.iter().zip(wiring) {
        if let Some(i) = *to {
            out[i] |= on;
        }
    }
    out
}

/// Messages the unit sends, by id, for callers that sort its output.
pub fn is_broadcast(id: MessageId) -> bool {
    matches!(
        id,
        SystemStatus::ID | DeviceStatus::ID | FlapTrimStatus::ID | FaultStatus::ID
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::Decoder;

    /// A unit on a fake clock, and everything it has sent, decoded.
    struct Bench {
        unit: Unit,
        t0: Instant,
        now: Instant,
        rx: Decoder,
        seen: Vec<(Duration, Packet)>,
        /// Every byte the unit sent, as it left.
        raw: Vec<u8>,
        cnt: u8,
    }

    impl Bench {
        fn new(toml: &str) -> Self {
            let t0 = Instant::now();
            let s = Scenario::from_toml(toml).unwrap();
            let unit = Unit::with_memory_eeprom(&s, UnitOptions::default(), t0);
            Bench {
                unit,
                t0,
                now: t0,
                rx: Decoder::new(),
                seen: Vec::new(),
                raw: Vec::new(),
                cnt: 0,
            }
        }

        fn collect(&mut self) {
            let out = self.unit.take_output();
            self.raw.extend_from_slice(&out);
            let mut frames = Vec::new();
            self.rx.push(&out, |e| {
                if let Event::Frame(f) = e {
                    frames.push(Packet::parse(&f).unwrap());
                }
            });
            let at = self.now - self.t0;
            self.seen.extend(frames.into_iter().map(|p| (at, p)));
        }

        /// Lets `ms` milliseconds pass in 10 ms ticks.
        fn run(&mut self, ms: u64) {
            for _ in 0..ms / 10 {
                self.now += Duration::from_millis(10);
                self.unit.tick(self.now);
                self.collect();
            }
        }

        fn send(&mut self, m: impl Into<Message>) -> u8 {
            self.cnt = self.cnt.wrapping_add(1);
            let bytes = Packet::request(self.cnt, m).to_bytes();
            self.unit.feed(&bytes, self.now);
            self.collect();
            self.cnt
        }

        fn apply(&mut self, c: SimCommand) {
            self.unit.apply(c, self.now);
            self.collect();
        }

        fn count(&self, id: MessageId) -> usize {
            self.seen
                .iter()
                .filter(|(_, p)| p.message.id() == id)
                .count()
        }

        fn last<T>(&self, f: impl Fn(&Message) -> Option<T>) -> Option<T> {
            self.seen.iter().rev().find_map(|(_, p)| f(&p.message))
        }

        fn reply_to(&self, cnt: u8) -> Option<Message> {
            self.seen
                .iter()
                .find(|(_, p)| p.cnt == cnt && !is_broadcast(p.message.id()))
                .map(|(_, p)| p.message)
        }

        fn stats(&self) -> SimStats {
            self.unit.snapshot(self.now)
        }

        fn external(&mut self, ias: Option<u16>, rpm: Option<u16>) {
            self.send(ExternalData {
                indicated_airspeed: ias.unwrap_or(0),
                rpm: rpm.unwrap_or(0),
                valid: ExternalValidity {
                    indicated_airspeed: ias.is_some(),
                    rpm: rpm.is_some(),
                    ..Default::default()
                },
                ..Default::default()
            });
        }
    }

    const PINS: &str = "
        [system]
        secondary_alternator = 23
        [[device]]
        id = 3
        switch = 1
        load = 2.0
        [[device]]
        id = 9
        breaker = 3
        switch = 2
        load = 1.0
        [[device]]
        id = 10
        breaker = 3
        switch = 11
        load = 1.0
        [[device]]
        id = 23
        breaker = 5
        switch = 4
        load = 2.0
    ";

    #[test]
    fn broadcasts_keep_their_rates_and_their_own_count() {
        let mut b = Bench::new("");
        b.run(10_000);
        assert_eq!(b.count(SystemStatus::ID), 10);
        assert_eq!(b.count(DeviceStatus::ID), 10);
        assert_eq!(b.count(FlapTrimStatus::ID), 100);
        assert_eq!(b.count(FaultStatus::ID), 0, "no fault, no FAULT_STATUS");
        let cnts: Vec<u8> = b.seen.iter().map(|(_, p)| p.cnt).collect();
        assert!(cnts.windows(2).all(|w| w[1] == w[0].wrapping_add(1)));
    }

    #[test]
    fn requests_are_answered_with_their_command_number() {
        let mut b = Bench::new("");
        b.cnt = 41;
        let c = b.send(Ping { ack: false });
        assert_eq!(b.reply_to(c), Some(Message::Ping(Ping { ack: true })));
        let c = b.send(DeviceSpecQuery { device_id: 253 });
        assert!(matches!(b.reply_to(c), Some(Message::SystemSpec(_))));
        let c = b.send(DeviceSpecQuery { device_id: 29 });
        assert!(matches!(
            b.reply_to(c),
            Some(Message::TrimSpec(TrimSpec {
                trim_type: TrimType::Roll,
                ..
            }))
        ));
        let c = b.send(DeviceSpecQuery { device_id: 99 });
        assert_eq!(b.reply_to(c), None, "Table 18 note 1: ignored");
    }

    #[test]
    fn dropped_spec_acks_still_apply_the_spec_and_broadcasts_go_on() {
        let mut b = Bench::new("[line]\ndrop_spec_acks = true\n");
        let spec = DeviceSpec {
            device_id: 9,
            circuit_breaker: 3,
            switch_id: SwitchId::Input(2),
            current_fault: false,
            switch_raw: None,
        };
        let cnt = b.send(spec);
        b.run(1100);
        assert_eq!(b.reply_to(cnt), None, "no SPEC_ACK on the wire");
        assert_eq!(b.stats().config.devices[9], spec, "but the spec is stored");
        assert_eq!(b.stats().wire.spec_acks_dropped, 1);
        assert!(b.count(SystemStatus::ID) >= 1, "broadcasts carry on");
        // A query is still answered with what it holds.
        let q = b.send(DeviceSpecQuery { device_id: 9 });
        assert_eq!(b.reply_to(q), Some(Message::DeviceSpec(spec)));
        // Told to stop dropping, it answers again.
        b.apply(SimCommand::DropSpecAcks(false));
        let again = b.send(DeviceSpec {
            circuit_breaker: 4,
            ..spec
        });
        assert_eq!(
            b.reply_to(again),
            Some(Message::SpecAck(SpecAck {
                device_id: 9,
                error: None
            }))
        );
    }

    #[test]
    fn a_spec_that_does_not_decode_gets_out_of_range_for_its_device() {
        let mut b = Bench::new("");
        // DEVICE_SPEC for device 9 with a current-fault flag of 2.
        let mut bytes = Packet::request(
            7,
            DeviceSpec {
                device_id: 9,
                circuit_breaker: 3,
                switch_id: SwitchId::Input(2),
                current_fault: false,
                switch_raw: None,
            },
        )
        .to_bytes();
        bytes[8 + 3] = 2;
        let n = bytes.len();
        bytes[n - 1] = crate::protocol::checksum(&bytes[..n - 1]);
        b.unit.feed(&bytes, b.now);
        b.collect();
        assert_eq!(
            b.reply_to(7),
            Some(Message::SpecAck(SpecAck {
                device_id: 9,
                error: Some(SpecAckError::OutOfRange)
            }))
        );
        assert_eq!(b.stats().wire.malformed, 1);
        assert_eq!(b.stats().config, UnitConfig::default(), "nothing stored");
    }

    #[test]
    fn device_power_overrides_until_the_switch_is_cycled() {
        let mut b = Bench::new(PINS);
        b.send(DevicePower {
            device_id: 9,
            on: true,
        });
        assert!(b.stats().powered[9], "on although switch 2 is open");
        b.apply(SimCommand::Switch {
            switch: 2,
            on: true,
        });
        b.apply(SimCommand::Switch {
            switch: 2,
            on: false,
        });
        assert!(!b.stats().powered[9], "the switch has the last word again");
        b.send(DevicePower {
            device_id: 1,
            on: true,
        });
        assert!(
            !b.stats().powered[1],
            "the starter cannot be switched from outside"
        );
    }

    /// The reading of "cycled" (ICD Appendix A) the page's model shares: one change
    /// of the input ends the hold; the switch then has the word both ways.
    #[test]
    fn a_single_change_of_the_input_ends_a_device_power_hold() {
        let mut b = Bench::new(PINS);
        b.apply(SimCommand::Switch {
            switch: 2,
            on: true,
        });
        // Held ON while switch 2 is on: only the end of the hold can turn it off.
        b.send(DevicePower {
            device_id: 9,
            on: true,
        });
        assert!(b.stats().powered[9]);
        b.apply(SimCommand::Switch {
            switch: 2,
            on: false,
        });
        assert!(
            !b.stats().powered[9],
            "one change (on to off) ended the hold: the switch has the word"
        );
    }

    #[test]
    fn a_short_faults_the_pin_when_powered_and_clear_brings_back_the_switch_state() {
        let mut b = Bench::new(PINS);
        b.apply(SimCommand::Short {
            device: 9,
            on: true,
        });
        b.apply(SimCommand::Switch {
            switch: 2,
            on: true,
        });
        let s = b.stats();
        assert!(!s.powered[9]);
        assert_eq!(s.faults[9], FaultCode::ShortCircuit);
        b.run(1_500);
        let f = b.last(|m| match m {
            Message::FaultStatus(f) => Some(*f),
            _ => None,
        });
        let f = f.expect("FAULT_STATUS while a fault exists");
        assert!(f.faulted[9]);
        assert_eq!(f.codes[9], Some(FaultCode::ShortCircuit));
        // Clearing while still shorted: faulted again at once (§6.5.1).
        b.send(DeviceClear { device_id: 9 });
        assert_eq!(b.stats().faults[9], FaultCode::ShortCircuit);
        b.apply(SimCommand::Short {
            device: 9,
            on: false,
        });
        // An always-on pin the EFIS switched off comes back on with the clear (note 2).
        b.send(DevicePower {
            device_id: 10,
            on: false,
        });
        b.send(DeviceClear { device_id: 9 });
        let s = b.stats();
        assert!(s.powered[9], "back to switch 2, which is on");
        assert!(s.powered[10], "switch-11 pin powered again");
        let before = b.count(FaultStatus::ID);
        b.run(2_000);
        assert_eq!(
            b.count(FaultStatus::ID),
            before,
            "no fault, no FAULT_STATUS"
        );
    }

    #[test]
    fn over_current_and_current_fault() {
        let mut b = Bench::new(PINS);
        b.apply(SimCommand::Load {
            device: 10,
            amps: 3.5,
        });
        assert_eq!(b.stats().faults[10], FaultCode::OverCurrent);
        let mut s = b.unit.config.devices[9];
        s.current_fault = true;
        b.send(s);
        b.apply(SimCommand::Load {
            device: 9,
            amps: 0.0,
        });
        b.apply(SimCommand::Switch {
            switch: 2,
            on: true,
        });
        assert_eq!(b.stats().faults[9], FaultCode::CurrentFault);
    }

    #[test]
    fn one_alternator_at_a_time_and_over_voltage_trips_the_running_one() {
        let mut b = Bench::new(PINS);
        b.apply(SimCommand::Switch {
            switch: 1,
            on: true,
        });
        b.apply(SimCommand::Switch {
            switch: 4,
            on: true,
        });
        let s = b.stats();
        assert!(
            s.powered[3] && !s.powered[23],
            "primary runs, secondary waits"
        );
        b.apply(SimCommand::BusVolts(16.4));
        let s = b.stats();
        assert_eq!(s.faults[3], FaultCode::OverVoltage);
        assert!(!s.powered[3] && s.powered[23], "the secondary takes over");
        assert_eq!(s.faults[23], FaultCode::NoFault, "at normal volts");
    }

    #[test]
    fn the_60_a_flag_clears_only_below_48_a() {
        // Nine big pins, always on, whose loads add up to the total under test.
        let pins: Vec<u8> = (17..=25).collect();
        let toml: String = pins
            .iter()
            .map(|id| format!("[[device]]\nid = {id}\nswitch = 11\nbreaker = 10\n"))
            .collect();
        let mut b = Bench::new(&toml);
        let flags = |b: &mut Bench| {
            b.run(1_000);
            b.last(|m| match m {
                Message::SystemStatus(s) => {
                    Some((s.faults.current_over_48a, s.faults.current_over_60a))
                }
                _ => None,
            })
            .unwrap()
        };
        for (total, want) in [
            (50.0, (true, false)),
            (61.0, (true, true)),
            (49.0, (true, true)),
            (47.0, (false, false)),
            (49.0, (true, false)),
        ] {
            for &device in &pins {
                b.apply(SimCommand::Load {
                    device,
                    amps: total / pins.len() as f32,
                });
            }
            assert_eq!(flags(&mut b), want, "{total} A");
        }
        assert!(b.stats().faults.iter().all(|f| !f.is_fault()));
    }

    #[test]
    fn the_starter_cuts_out_above_500_rpm() {
        let mut b = Bench::new("[electrical]\nstarter = true\n");
        assert!(b.stats().powered[1]);
        b.external(None, Some(400));
        assert!(b.stats().powered[1]);
        b.external(None, Some(900));
        assert!(!b.stats().powered[1]);
    }

    #[test]
    fn external_data_missing_after_two_seconds() {
        let mut b = Bench::new("");
        b.run(1_900);
        assert!(!b.stats().external_data_missing);
        b.run(200);
        assert!(b.stats().external_data_missing);
        b.external(Some(90), None);
        assert!(!b.stats().external_data_missing);
        b.run(2_100);
        assert!(b.stats().external_data_missing);
    }

    #[test]
    fn wig_wag_flashes_at_and_above_its_speed_after_warm_up_and_steady_stops_it() {
        let mut b = Bench::new(
            "[[device]]\nid = 17\nswitch = 5\nbreaker = 8\nload = 6\n\
             [[device]]\nid = 18\nswitch = 5\nbreaker = 8\nload = 5\n\
             [wig_wag]\ndevice_one = 17\ndevice_two = 18\nwarm_up = 5\nspeed = 70\n",
        );
        b.apply(SimCommand::Switch {
            switch: 5,
            on: true,
        });
        let both = |b: &Bench| (b.stats().powered[17], b.stats().powered[18]);
        let patterns = |b: &mut Bench, ias: u16| {
            let mut seen = std::collections::HashSet::new();
            for _ in 0..4 {
                b.external(Some(ias), None);
                b.run(250);
                seen.insert(both(b));
            }
            seen
        };
        // Taxiing at 40 kt, through the warm-up and after it: steady.
        for _ in 0..6 {
            b.external(Some(40), None);
            b.run(1_000);
        }
        assert_eq!(
            patterns(&mut b, 40),
            std::collections::HashSet::from([(true, true)]),
            "below the speed: steady"
        );
        // At 70 kt exactly (Table 17's "speed at which the wig-wag is engaged") and
        // above: one lamp at a time.
        for ias in [70, 120] {
            let p = patterns(&mut b, ias);
            assert!(
                p.contains(&(true, false)) && p.contains(&(false, true)),
                "{ias} kt: {p:?}"
            );
            assert!(!p.contains(&(true, true)), "{ias} kt: {p:?}");
            let active = b.last(|m| match m {
                Message::SystemStatus(s) => Some(s.misc.wig_wag_active),
                _ => None,
            });
            assert_eq!(active, Some(true), "Table 24's Wig-Wag Active at {ias} kt");
        }
        b.send(WigWagMode {
            mode: WigWagModeSetting::Steady,
        });
        assert_eq!(both(&b), (true, true));
        b.send(WigWagMode {
            mode: WigWagModeSetting::Auto,
        });
        b.external(Some(69), None);
        b.run(100);
        assert_eq!(both(&b), (true, true), "below the speed again: steady");
    }

    #[test]
    fn eeprom_erase_restores_defaults_and_flags_integrity_until_power_cycle() {
        let mut b = Bench::new(PINS);
        let c = b.send(EepromErase { response_code: 0 });
        assert_eq!(
            b.reply_to(c),
            Some(Message::EepromErase(EepromErase { response_code: 0 }))
        );
        assert_eq!(b.stats().config, UnitConfig::default());
        b.run(1_000);
        let flag = |b: &Bench| {
            b.last(|m| match m {
                Message::SystemStatus(s) => Some(s.faults.data_integrity_failure),
                _ => None,
            })
        };
        assert_eq!(flag(&b), Some(true));
        b.apply(SimCommand::PowerCycle);
        b.run(1_000);
        assert_eq!(flag(&b), Some(false));
        assert_eq!(b.stats().config, UnitConfig::default(), "still erased");
    }

    #[test]
    fn bootloader_frames_in_the_same_read_as_software_update_are_not_lost() {
        let mut b = Bench::new("");
        let mut bytes = Packet::request(1, SoftwareUpdate).to_bytes();
        bytes.extend(crate::protocol::bootloader::BootCommand::QueryPort.emit());
        b.unit.feed(&bytes, b.now);
        assert_eq!(b.unit.take_output(), b"VP_AVRBOOT");
    }

    #[test]
    fn software_update_enters_the_bootloader_and_exit_sets_the_flag() {
        use crate::protocol::bootloader::{BootCommand, PAGE_SIZE};
        let mut b = Bench::new("");
        b.send(SoftwareUpdate);
        let before = b.seen.len();
        b.run(1_000);
        assert_eq!(b.seen.len(), before, "no broadcasts in the bootloader");
        let mut bytes = BootCommand::serial_conf().emit();
        bytes.extend(BootCommand::FlashErase.emit());
        bytes.extend(
            BootCommand::flash_prog(0, &[0x0C; PAGE_SIZE])
                .unwrap()
                .emit(),
        );
        bytes.extend(BootCommand::Exit.emit());
        b.unit.feed(&bytes, b.now);
        assert_eq!(b.unit.take_output(), b"!!!ePx");
        b.run(1_000);
        let flag = b.last(|m| match m {
            Message::SystemStatus(s) => Some(s.misc.software_update),
            _ => None,
        });
        assert_eq!(flag, Some(true));
        b.apply(SimCommand::PowerCycle);
        assert!(!b.stats().software_update_flag);
    }

    #[test]
    fn a_silent_unit_sends_nothing_then_resumes() {
        let mut b = Bench::new("[[event]]\nat = 1.0\ndo = \"silent\"\nseconds = 3.0\n");
        b.run(1_000);
        let n = b.seen.len();
        b.run(2_900);
        assert_eq!(b.seen.len(), n);
        b.run(1_100);
        assert!(b.seen.len() > n);
        assert!(b.stats().wire.silenced_bytes > 0);
    }

    /// The payloads of every frame with this major/minor id the unit sent since raw
    /// byte `from`, cut out by hand from ICD Table 1 (E7 7E, major, minor, cnt, src,
    /// dst, len, data, checksum): independent of our decoder.
    fn payloads(b: &Bench, from: usize, major: u8, minor: u8) -> Vec<Vec<u8>> {
        let raw = &b.raw[from..];
        let mut out = Vec::new();
        let mut i = 0;
        while i + 8 <= raw.len() {
            if raw[i] == 0xE7 && raw[i + 1] == 0x7E {
                let len = raw[i + 7] as usize;
                let end = i + 8 + len + 1;
                assert!(end <= raw.len(), "a frame cut short");
                // Source 0x00 (VP-X), destination 0x01 (external system).
                assert_eq!((raw[i + 5], raw[i + 6]), (0x00, 0x01));
                if raw[i + 2] == major && raw[i + 3] == minor {
                    out.push(raw[i + 8..i + 8 + len].to_vec());
                }
                i = end;
            } else {
                i += 1;
            }
        }
        out
    }

    /// The last SYSTEM_STATUS (0x12/0x00) payload after a second more.
    fn system_status_bytes(b: &mut Bench) -> Vec<u8> {
        let from = b.raw.len();
        b.run(1_000);
        let p = payloads(b, from, 0x12, 0x00);
        let last = p.last().expect("SYSTEM_STATUS every second").clone();
        assert_eq!(last.len(), 12, "Table 24: 12 bytes");
        last
    }

    /// The last DEVICE_STATUS (0x12/0x01) payload after a second more.
    fn device_status_bytes(b: &mut Bench) -> Vec<u8> {
        let from = b.raw.len();
        b.run(1_000);
        let p = payloads(b, from, 0x12, 0x01);
        let last = p.last().expect("DEVICE_STATUS every second").clone();
        assert_eq!(last.len(), 66, "Table 26: 66 bytes");
        last
    }

    /// Table 26: device `id`'s current, tenths of amps, big-endian at bytes 5 + 2·id.
    fn current_tenths(payload: &[u8], id: usize) -> u16 {
        u16::from_be_bytes([payload[4 + 2 * id], payload[5 + 2 * id]])
    }

    /// FLAP_TRIM_STATUS (0x12/0x02) payloads after `ms` more milliseconds.
    fn flap_trim_bytes(b: &mut Bench, ms: u64) -> Vec<Vec<u8>> {
        let from = b.raw.len();
        b.run(ms);
        payloads(b, from, 0x12, 0x02)
    }

    const WIRING: &str = "
        [electrical]
        dead_switches = [7]
        crossed_switches = [[5, 6]]
        [[device]]
        id = 4
        breaker = 3
        switch = 3
        load = 1.5
        [[device]]
        id = 6
        breaker = 2
        switch = 3
        load = 1.1
        open_circuit = true
        [[device]]
        id = 17
        breaker = 8
        switch = 5
        load = 7.2
        [[device]]
        id = 18
        breaker = 7
        switch = 6
        load = 4.0
        [[device]]
        id = 19
        breaker = 6
        switch = 7
        load = 3.5
    ";

    fn person_sets(b: &mut Bench, switch: u8, on: bool) {
        b.apply(SimCommand::Switch { switch, on });
    }

    #[test]
    fn an_open_circuit_is_on_and_draws_nothing() {
        let mut b = Bench::new(WIRING);
        person_sets(&mut b, 3, true);
        let d = device_status_bytes(&mut b);
        // Table 26 byte 1: device 7 is the MSB, device 0 the LSB; 4 and 6 are on.
        // The EFIS (2) is on too: always on by default (Appendix F).
        assert_eq!(d[0], 0b0101_0100);
        assert_eq!(
            current_tenths(&d, 6),
            0,
            "the beacon's load is not connected"
        );
        let nav = current_tenths(&d, 4);
        assert!(
            (14..=16).contains(&nav),
            "the good circuit draws 1.5 A: {nav}"
        );
        // Switched on by DEVICE_POWER instead, the same: on, and 0 A.
        person_sets(&mut b, 3, false);
        b.send(DevicePower {
            device_id: 6,
            on: true,
        });
        let d = device_status_bytes(&mut b);
        assert_eq!(d[0], 0b0100_0100);
        assert_eq!(current_tenths(&d, 6), 0);
    }

    #[test]
    fn an_open_circuit_with_current_fault_detection_faults() {
        // The unit's own check (Table 13 note): a pin that should draw and does not.
        let mut b = Bench::new(
            "[[device]]\nid = 6\nswitch = 3\nload = 1.1\nopen_circuit = true\n\
             current_fault = true\n",
        );
        person_sets(&mut b, 3, true);
        assert_eq!(b.stats().faults[6], FaultCode::CurrentFault);
    }

    #[test]
    fn a_load_near_its_breaker_draws_close_to_it_without_tripping() {
        let mut b = Bench::new(WIRING);
        let from = b.raw.len();
        person_sets(&mut b, 5, true);
        person_sets(&mut b, 6, true);
        let d = device_status_bytes(&mut b);
        // Byte 3 holds devices 16–23: 17 is bit 1, 18 bit 2.
        assert_eq!(d[2], 0b0000_0110);
        let amps = current_tenths(&d, 17);
        // 7.2 A ± 3 % noise, of an 8 A breaker: 87–93 %.
        assert!((70..=74).contains(&amps), "{amps} tenths");
        b.run(2_000);
        assert!(
            payloads(&b, from, 0x12, 0x03).is_empty(),
            "no FAULT_STATUS: the breaker holds"
        );
    }

    #[test]
    fn a_dead_switch_input_never_changes() {
        let mut b = Bench::new(WIRING);
        person_sets(&mut b, 7, true);
        let s = system_status_bytes(&mut b);
        // Table 24 byte 9: switch 8 is the MSB … switch 1 the LSB. Nothing closed.
        assert_eq!((s[7], s[8]), (0x00, 0x00));
        assert!(!b.stats().powered[19], "the boost pump stays off");
        // The switch next to it works, and the person's switch 7 is still on.
        person_sets(&mut b, 4, true);
        let s = system_status_bytes(&mut b);
        assert_eq!((s[7], s[8]), (0x00, 0b0000_1000));
        person_sets(&mut b, 7, false);
        let s = system_status_bytes(&mut b);
        assert_eq!((s[7], s[8]), (0x00, 0b0000_1000));
    }

    #[test]
    fn crossed_switches_close_each_others_input_and_power_each_others_circuits() {
        let mut b = Bench::new(WIRING);
        person_sets(&mut b, 5, true);
        let s = system_status_bytes(&mut b);
        // Switch 5 is bit 4 (0x10), switch 6 bit 5 (0x20): input 6 closed.
        assert_eq!(s[8], 0b0010_0000);
        let d = device_status_bytes(&mut b);
        assert_eq!(
            d[2], 0b0000_0100,
            "the taxi light (18) on, not the landing light"
        );
        person_sets(&mut b, 5, false);
        person_sets(&mut b, 6, true);
        let s = system_status_bytes(&mut b);
        assert_eq!(s[8], 0b0001_0000, "switch 6 closes input 5");
        let d = device_status_bytes(&mut b);
        assert_eq!(d[2], 0b0000_0010, "the landing light (17) on");
    }

    #[test]
    fn a_switch_change_through_the_wiring_still_ends_a_device_power_hold() {
        let mut b = Bench::new(WIRING);
        // The page switched the taxi light off; cycling its input ends the hold.
        b.send(DevicePower {
            device_id: 18,
            on: false,
        });
        person_sets(&mut b, 5, true);
        assert!(
            b.stats().powered[18],
            "input 6 changed, so the hold is gone"
        );
    }

    const MOTORS: &str = "
        [flap]
        up = 20
        down = 220
        position = 100
        [pitch_trim]
        up = 30
        down = 220
        neutral = 125
        position = 125
        reversed = true
        [roll_trim]
        up = 40
        down = 210
        neutral = 125
        position = 125
        stuck = true
    ";

    /// Streams TRIM_MOVE every 100 ms for `ms` (a page's safe stream), then stops.
    fn trim_run(b: &mut Bench, axis: TrimType, dir: TrimDirection, ms: u64) -> Vec<Vec<u8>> {
        let mut status = Vec::new();
        for _ in 0..ms / 100 {
            b.send(TrimMove {
                trim_type: axis,
                on: true,
                direction: dir,
            });
            status.extend(flap_trim_bytes(b, 100));
        }
        b.send(TrimMove {
            trim_type: axis,
            on: false,
            direction: dir,
        });
        status
    }

    #[test]
    fn a_reversed_trim_runs_the_other_way_and_its_polarity_setting_undoes_it() {
        let mut b = Bench::new(MOTORS);
        let before = flap_trim_bytes(&mut b, 100).last().unwrap().clone();
        // Table 27 byte 4: pitch position. Down is toward 220, the larger number.
        assert_eq!(before[3], 125);
        let during = trim_run(&mut b, TrimType::Pitch, TrimDirection::DownOrRight, 1_000);
        // Byte 2 MSB first: pitch enabled 0x80, running 0x40; roll enabled 0x10.
        assert!(during.iter().any(|p| p[1] == 0b1101_0000), "running");
        let after = flap_trim_bytes(&mut b, 300).last().unwrap().clone();
        assert_eq!(after[1], 0b1001_0000, "stopped");
        assert!(
            (98..=102).contains(&after[3]),
            "commanded down, went up: {}",
            after[3]
        );
        // The installer sets the polarity to inverted (Table 15 note 3): fixed.
        let spec = TrimSpec {
            polarity: Polarity::Inverted,
            power: 60,
            ..b.unit.config.pitch_trim
        };
        b.send(spec);
        trim_run(&mut b, TrimType::Pitch, TrimDirection::DownOrRight, 1_000);
        let fixed = flap_trim_bytes(&mut b, 300).last().unwrap().clone();
        assert!(
            fixed[3] > after[3] + 20,
            "now down: {} → {}",
            after[3],
            fixed[3]
        );
    }

    #[test]
    fn a_stuck_trim_runs_and_never_moves() {
        let mut b = Bench::new(MOTORS);
        let during = trim_run(&mut b, TrimType::Roll, TrimDirection::UpOrLeft, 1_000);
        // Byte 2: roll enabled 0x10, roll running 0x08 (pitch enabled 0x80).
        assert!(during.iter().any(|p| p[1] == 0b1001_1000), "roll running");
        // Byte 5: roll position, byte 8: roll fault code (none).
        assert!(during.iter().all(|p| p[4] == 125 && p[7] == 0));
        // Flaps, wired right, move as commanded (byte 3; down is the larger number).
        for _ in 0..10 {
            b.send(FlapMove {
                on: true,
                direction: FlapDirection::Down,
            });
            b.run(100);
        }
        b.send(FlapMove {
            on: false,
            direction: FlapDirection::Down,
        });
        let s = flap_trim_bytes(&mut b, 300).last().unwrap().clone();
        assert!((118..=122).contains(&s[2]), "flaps went down: {}", s[2]);
    }

    #[test]
    fn a_flipped_switch_comes_back_after_its_hold() {
        let mut b = Bench::new(WIRING);
        b.apply(SimCommand::FlipSwitch {
            switch: 3,
            hold: Duration::from_millis(2_500),
        });
        // SYSTEM_STATUS leaves at 0.2 s, 1.2 s, 2.2 s, 3.2 s … after power-on.
        for (window, want) in [(1, 0b0000_0100), (2, 0b0000_0100), (3, 0b0000_0100), (4, 0)] {
            let s = system_status_bytes(&mut b);
            assert_eq!(s[8], want, "switch 3 in the broadcast before {window} s");
        }
        // A switch that was on flips off, then on again (at 4 s, back at 5.5 s).
        person_sets(&mut b, 4, true);
        b.apply(SimCommand::FlipSwitch {
            switch: 4,
            hold: Duration::from_millis(1_500),
        });
        for want in [0, 0, 0b0000_1000] {
            let s = system_status_bytes(&mut b);
            assert_eq!(s[8], want);
        }
    }

    #[test]
    fn held_flap_and_trim_switches_show_in_system_status_byte_8() {
        let mut b = Bench::new(MOTORS);
        b.apply(SimCommand::MotorSwitch {
            motor: MotorId::Flap,
            direction: Some(MotorDirection::Down),
        });
        b.apply(SimCommand::MotorSwitch {
            motor: MotorId::Pitch,
            direction: Some(MotorDirection::Up),
        });
        let s = system_status_bytes(&mut b);
        // Table 24 byte 8, MSB first: roll down, roll up, pitch down, pitch up (0x10),
        // flap down (0x08), flap up, switch 10, switch 9.
        assert_eq!(s[7], 0b0001_1000);
        b.apply(SimCommand::MotorSwitch {
            motor: MotorId::Flap,
            direction: None,
        });
        b.apply(SimCommand::MotorSwitch {
            motor: MotorId::Pitch,
            direction: None,
        });
        // Pressed for 1.5 s: roll trim up (0x40) in the next broadcast, gone after.
        b.apply(SimCommand::PressMotorSwitch {
            motor: MotorId::Roll,
            direction: MotorDirection::Up,
            hold: Duration::from_millis(1_500),
        });
        for want in [0b0100_0000, 0b0100_0000, 0] {
            let s = system_status_bytes(&mut b);
            assert_eq!(s[7], want);
        }
    }
}

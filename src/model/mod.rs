//! What we know about the unit, each fact with the time we learned it.
//!
//! Staleness is part of the model, not the view: the `live_*` accessors and
//! [`Model::circuits`] take the current time and return nothing for a fact that is too
//! old, so no screen and no network publisher can show old data as current
//! (ICD Appendix A: "not display old and possibly inaccurate data").
//!
//! The model is fed by plain method calls (`apply_packet`, `note_*`) and knows nothing
//! of ports or threads.

use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

use crate::protocol::decoder::DecoderStats;
use crate::protocol::device::{
    self, DEVICE_COUNT, EFIS, FIELD_PRI, FLAPS, STARTER, TRIM_P, TRIM_R,
};
use crate::protocol::fault::FaultCode;
use crate::protocol::message::{
    Axis, DeviceEnable, DeviceName, DeviceSpec, DeviceStatus, EepromErase, EnableFlag,
    ExternalData, FaultStatus, FlapSpec, FlapTrimStatus, Message, Packet, SpecAck, SwitchId,
    SystemSpec, SystemStatus, TrimSpec, TrimType, Version, WigWagSpec,
};

mod hold;
mod reread;
mod rereader;
mod resets;
mod setting;
pub use hold::{Hold, Holds};
pub use reread::Reread;
pub use rereader::{REREAD_BATCH, REREAD_BATCH_GAP, Rereader};
pub use resets::{AfterReset, ResetsSent, reset_sent_words};
pub use setting::Setting;
#[cfg(test)]
pub(crate) use setting::factory_answer;

/// How long each broadcast stays current (a leaf, shared with the traffic log).
pub use crate::staleness::{
    COMM_LOST_AFTER, FAULT_STATUS_MARGIN, FAULT_STATUS_PERIOD, FAULT_STATUS_QUIET_AFTER,
    FLAP_TRIM_STALE_AFTER, STATUS_STALE_AFTER,
};
/// The page asks for every spec, name and enable flag again every minute
/// (`app::queries::REFRESH_EVERY`); a setting last heard longer ago than this missed
/// a refresh, so screens show its age beside it.
pub const SETTING_OLD_AFTER: Duration = Duration::from_secs(90);
/// How much bus history the plot keeps (one sample per SYSTEM_STATUS).
pub const HISTORY_LEN: usize = 600;
/// How many lines the event log keeps.
pub const EVENT_LOG_LEN: usize = 200;

/// A fact and when we learned it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stamped<T> {
    pub value: T,
    pub at: Instant,
}

impl<T> Stamped<T> {
    pub fn new(value: T, at: Instant) -> Self {
        Stamped { value, at }
    }

    pub fn age(&self, now: Instant) -> Duration {
        now.saturating_duration_since(self.at)
    }

    /// The value if it is no older than `max_age`.
    pub fn fresh(&self, now: Instant, max_age: Duration) -> Option<&T> {
        (self.age(now) <= max_age).then_some(&self.value)
    }
}

/// Where the page's data comes from: shown on screen so nobody mistakes the virtual
/// unit or a replay for an aircraft.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Source {
    Simulated { scenario: String },
    Serial { path: String },
    Replay { file: String },
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Connection {
    Connecting,
    Connected {
        port: String,
        since: Instant,
    },
    /// The port failed; the link is reopening it.
    Lost {
        reason: String,
        since: Instant,
    },
}

/// Per-message-type counters for the link health and traffic views.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MessageStat {
    pub count: u64,
    pub first: Instant,
    pub last: Instant,
}

#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LinkHealth {
    pub decoder: DecoderStats,
    /// Intact frames of known messages whose payload did not decode.
    pub malformed: u64,
    pub tx_frames: u64,
    pub write_errors: u64,
    pub last_write_error: Option<String>,
    pub rx: BTreeMap<&'static str, MessageStat>,
    pub tx: BTreeMap<&'static str, MessageStat>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LogLevel {
    Info,
    Warning,
    Alert,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogEntry {
    pub at: Instant,
    pub level: LogLevel,
    pub text: String,
}

/// One bus sample for the plot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BusSample {
    pub at: Instant,
    pub main_bus_volts: f32,
    pub system_amps: f32,
}

/// What a circuit is, for grouping and for the keys that apply to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CircuitKind {
    Starter,
    Device,
    /// Primary (Field_Pri) or the configured secondary alternator.
    Alternator {
        primary: bool,
    },
    Flaps,
    Trim(TrimKind),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TrimKind {
    Pitch,
    Roll,
}

impl TrimKind {
    pub fn trim_type(self) -> TrimType {
        match self {
            TrimKind::Pitch => TrimType::Pitch,
            TrimKind::Roll => TrimType::Roll,
        }
    }
}

/// A motor the page can run with TRIM_MOVE/FLAP_MOVE.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motor {
    Flaps,
    Trim(TrimKind),
}

impl Motor {
    /// Every motor, in FLAP_TRIM_STATUS's order (ICD Table 27): flaps, pitch trim,
    /// roll trim.
    pub const ALL: [Motor; 3] = [
        Motor::Flaps,
        Motor::Trim(TrimKind::Pitch),
        Motor::Trim(TrimKind::Roll),
    ];

    /// Its place in [`Motor::ALL`], for anything kept per motor.
    pub fn index(self) -> usize {
        match self {
            Motor::Flaps => 0,
            Motor::Trim(TrimKind::Pitch) => 1,
            Motor::Trim(TrimKind::Roll) => 2,
        }
    }

    /// The motor whose row has device id `id` (Appendix B), if it is one.
    pub fn of_device(id: u8) -> Option<Motor> {
        match id {
            FLAPS => Some(Motor::Flaps),
            TRIM_P => Some(Motor::Trim(TrimKind::Pitch)),
            TRIM_R => Some(Motor::Trim(TrimKind::Roll)),
            _ => None,
        }
    }

    /// The device id the motor's row has (Appendix B).
    pub fn device_id(self) -> u8 {
        match self {
            Motor::Flaps => FLAPS,
            Motor::Trim(TrimKind::Pitch) => TRIM_P,
            Motor::Trim(TrimKind::Roll) => TRIM_R,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Motor::Flaps => "flaps",
            Motor::Trim(TrimKind::Pitch) => "pitch trim",
            Motor::Trim(TrimKind::Roll) => "roll trim",
        }
    }

    /// Its axis of FLAP_TRIM_STATUS (ICD Table 27): which of that message's fields are
    /// this motor's.
    pub fn axis(self) -> Axis {
        match self {
            Motor::Flaps => Axis::Flap,
            Motor::Trim(TrimKind::Pitch) => Axis::PitchTrim,
            Motor::Trim(TrimKind::Roll) => Axis::RollTrim,
        }
    }

    /// The live fault code of this motor from FLAP_TRIM_STATUS, if any.
    pub fn fault(self, ft: &FlapTrimStatus) -> FaultCode {
        ft.axis(self.axis()).fault_code
    }
}

/// A circuit's state as the page and the network may show it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CircuitState {
    On,
    Off,
    Fault(FaultCode),
    /// The unit reported this fault and the page has sent a reset for it since, which
    /// the unit has not yet answered ([`AfterReset::Waiting`]): it may be gone, so it
    /// is never shown as a current fault.
    ResetSent(FaultCode),
    /// No live data: communication lost or not yet received.
    Unknown,
}

/// One row of the device list, derived from the model at a given time.
#[derive(Debug, Clone, PartialEq)]
pub struct Circuit {
    pub id: u8,
    /// DEVICE_NAME if the unit has one, else the Appendix B system name.
    pub name: String,
    /// The Appendix B system name, which is the pin's label on the unit.
    pub pin: &'static str,
    pub kind: CircuitKind,
    pub state: CircuitState,
    /// Live current; `None` when not live.
    pub amps: Option<f32>,
    pub breaker: Option<u8>,
    pub switch: Option<SwitchId>,
    /// The spec behind `breaker` and `switch` is unknown since a write to it went
    /// unanswered; it is being asked again.
    pub spec_unknown: bool,
    /// Faulted again after a reset the page sent this session (`resets`): the reset
    /// key refuses it unless confirmed.
    pub faulted_again: bool,
}

/// Everything we know about the unit.
#[derive(Debug, Clone)]
pub struct Model {
    pub source: Source,
    pub connection: Connection,
    pub version: Option<Stamped<Version>>,
    pub system_status: Option<Stamped<SystemStatus>>,
    pub device_status: Option<Stamped<DeviceStatus>>,
    pub flap_trim: Option<Stamped<FlapTrimStatus>>,
    pub fault_status: Option<Stamped<FaultStatus>>,
    pub device_specs: [Option<Stamped<DeviceSpec>>; DEVICE_COUNT],
    pub names: [Option<Stamped<DeviceName>>; DEVICE_COUNT],
    pub enabled: [Option<Stamped<bool>>; DEVICE_COUNT],
    pub system_spec: Option<Stamped<SystemSpec>>,
    pub flap_spec: Option<Stamped<FlapSpec>>,
    pub pitch_trim_spec: Option<Stamped<TrimSpec>>,
    pub roll_trim_spec: Option<Stamped<TrimSpec>>,
    pub wig_wag_spec: Option<Stamped<WigWagSpec>>,
    /// Settings nobody knows the unit's value of (a write to them went unanswered),
    /// and since when. Their slots above are empty until the unit answers a re-read.
    pub unknown: BTreeMap<Setting, Instant>,
    /// The settings being read again since the data came back after a loss
    /// (`reread`): until then none is held.
    pub reread: Option<Reread>,
    /// The fault resets sent this session, per device (`resets`).
    resets: [Option<ResetsSent>; DEVICE_COUNT],
    pub last_spec_ack: Option<Stamped<SpecAck>>,
    pub last_ping_reply: Option<Instant>,
    /// The unit's answer to EEPROM_ERASE: a response code other than zero means the
    /// erase did not complete (ICD Table 12).
    pub eeprom_erase: Option<Stamped<EepromErase>>,
    /// What the page (or the XFSp gateway) last sent as EXTERNAL_DATA.
    pub external_data_sent: Option<Stamped<ExternalData>>,
    /// The DEVICE_POWER holds the page sent that the unit still holds, as far as the
    /// page can tell (`hold`: when one ends).
    pub holds: Holds,
    pub link: LinkHealth,
    pub history: VecDeque<BusSample>,
    pub events: VecDeque<LogEntry>,
    /// Every frame and decoder drop in both directions, for the traffic view.
    pub traffic: crate::traffic::TrafficLog,
    /// Bumped whenever something a screen could show changes, so the page redraws
    /// only then (and once a second for ages).
    revision: u64,
    /// Faults seen since the app last took them, for the logbook: device id (255:
    /// the system fault flag), its name, the fault in words.
    pub faults_seen: Vec<(u8, String, String)>,
    /// The aircraft the page records under, for its title; `None` with no logbook.
    pub aircraft: Option<Aircraft>,
}

/// The aircraft as the logbook knows it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Aircraft {
    /// Its registration (`--aircraft`); `None`: records go under the unit.
    pub registration: Option<String>,
    /// The unit was seen in another aircraft before: that one, and the day it was
    /// last seen there.
    pub was_in: Option<(String, String)>,
}

impl Aircraft {
    /// The title's words: "N123AB", "aircraft not named (--aircraft)", then "this
    /// unit was in N123AB until 2026-11-03" when it was.
    pub fn words(&self) -> (String, Option<String>) {
        let name = self
            .registration
            .clone()
            .unwrap_or_else(|| "aircraft not named (--aircraft)".into());
        let was = self
            .was_in
            .as_ref()
            .map(|(reg, day)| format!("this unit was in {reg} until {day}"));
        (name, was)
    }
}

impl Model {
    pub fn new(source: Source) -> Self {
        Model {
            source,
            connection: Connection::Connecting,
            version: None,
            system_status: None,
            device_status: None,
            flap_trim: None,
            fault_status: None,
            device_specs: [None; DEVICE_COUNT],
            names: [None; DEVICE_COUNT],
            enabled: [None; DEVICE_COUNT],
            system_spec: None,
            flap_spec: None,
            pitch_trim_spec: None,
            roll_trim_spec: None,
            wig_wag_spec: None,
            unknown: BTreeMap::new(),
            reread: None,
            resets: [None; DEVICE_COUNT],
            last_spec_ack: None,
            last_ping_reply: None,
            eeprom_erase: None,
            external_data_sent: None,
            holds: Holds::default(),
            link: LinkHealth::default(),
            history: VecDeque::with_capacity(HISTORY_LEN),
            events: VecDeque::with_capacity(EVENT_LOG_LEN),
            traffic: crate::traffic::TrafficLog::new(),
            revision: 0,
            faults_seen: Vec::new(),
            aircraft: None,
        }
    }

    // ----- feeding the model -----

    /// Changes whenever something shown may have changed.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Records a packet received from the unit.
    pub fn apply_packet(&mut self, at: Instant, packet: &Packet) {
        bump(&mut self.link.rx, packet.message.name(), at);
        // The 10 Hz FLAP_TRIM_STATUS mostly repeats itself; only a change is news.
        let unchanged = matches!(
            (&packet.message, &self.flap_trim),
            (Message::FlapTrimStatus(new), Some(old)) if *new == old.value
        );
        if !unchanged {
            self.revision += 1;
        }
        if let Some(setting) = Setting::answered_by(&packet.message) {
            // The unit said what it holds: the setting is known again.
            if self.unknown.remove(&setting).is_some() {
                self.log(
                    at,
                    LogLevel::Info,
                    format!("{}: the unit answered the re-read", setting.name()),
                );
            }
        }
        // The first status after a loss: the unit may have changed meanwhile.
        if matches!(
            packet.message,
            Message::SystemStatus(_) | Message::DeviceStatus(_)
        ) && self.ever_heard()
            && self.comm_lost(at)
        {
            self.begin_reread(at);
        }
        match packet.message {
            Message::SystemStatus(s) => {
                let before = self
                    .system_status
                    .as_ref()
                    .map(|b| (&b.value, b.at, b.age(at) > COMM_LOST_AFTER));
                self.holds.status(before, &s, &self.specs());
                if self.history.len() == HISTORY_LEN {
                    self.history.pop_front();
                }
                self.history.push_back(BusSample {
                    at,
                    main_bus_volts: s.main_bus_volts.value(),
                    system_amps: s.system_current.value(),
                });
                self.system_status = Some(Stamped::new(s, at));
            }
            Message::DeviceStatus(s) => self.device_status = Some(Stamped::new(s, at)),
            Message::FlapTrimStatus(s) => self.flap_trim = Some(Stamped::new(s, at)),
            Message::FaultStatus(s) => {
                let before = self.faults_at(at);
                self.fault_status = Some(Stamped::new(s, at));
                self.log_new_faults(at, before);
            }
            Message::Version(v) => {
                self.reread_version(at, &v);
                self.version = Some(Stamped::new(v, at));
            }
            Message::DeviceSpec(s) => {
                if let Some(slot) = self.device_specs.get_mut(s.device_id as usize) {
                    *slot = Some(Stamped::new(s, at));
                }
            }
            Message::SystemSpec(s) => self.system_spec = Some(Stamped::new(s, at)),
            Message::FlapSpec(s) => self.flap_spec = Some(Stamped::new(s, at)),
            Message::TrimSpec(s) => match s.trim_type {
                TrimType::Roll => self.roll_trim_spec = Some(Stamped::new(s, at)),
                _ => self.pitch_trim_spec = Some(Stamped::new(s, at)),
            },
            Message::WigWagSpec(s) => self.wig_wag_spec = Some(Stamped::new(s, at)),
            Message::DeviceName(n) => {
                self.reread_name(at, &n);
                if let Some(slot) = self.names.get_mut(n.device_id as usize) {
                    *slot = Some(Stamped::new(n, at));
                }
            }
            Message::DeviceEnable(DeviceEnable { device_id, flag }) => {
                let on = match flag {
                    EnableFlag::Enabled => Some(true),
                    EnableFlag::Disabled => Some(false),
                    _ => None,
                };
                if let (Some(on), Some(slot)) = (on, self.enabled.get_mut(device_id as usize)) {
                    *slot = Some(Stamped::new(on, at));
                }
            }
            Message::SpecAck(a) => {
                if let Some(e) = a.error {
                    self.log(
                        at,
                        LogLevel::Warning,
                        format!(
                            "unit refused spec for {}: {}",
                            spec_target(a.device_id),
                            e.description()
                        ),
                    );
                }
                self.last_spec_ack = Some(Stamped::new(a, at));
            }
            Message::Ping(p) if p.ack => self.last_ping_reply = Some(at),
            Message::EepromErase(e) => self.eeprom_erase = Some(Stamped::new(e, at)),
            _ => {}
        }
        self.settle_reread(at);
    }

    /// Records a packet we sent.
    pub fn note_sent(&mut self, at: Instant, packet: &Packet) {
        self.link.tx_frames += 1;
        bump(&mut self.link.tx, packet.message.name(), at);
        match packet.message {
            Message::ExternalData(d) => self.external_data_sent = Some(Stamped::new(d, at)),
            Message::DeviceClear(c) => self.note_reset_sent(at, c.device_id),
            _ => {}
        }
        let specs = self.specs();
        self.holds.sent(at, &packet.message, &specs);
    }

    /// Each device's DEVICE_SPEC as the model holds it now.
    fn specs(&self) -> [Option<DeviceSpec>; DEVICE_COUNT] {
        self.device_specs.map(|s| s.map(|s| s.value))
    }

    /// The DEVICE_POWER hold the page sent on `id` that the unit still holds, as far
    /// as the page can tell.
    pub fn hold(&self, id: u8) -> Option<Hold> {
        self.holds.get(id)
    }

    /// A write to `setting` went unanswered: the unit may hold the old value or the
    /// new one, so the model forgets what it had and holds nothing for it until the
    /// unit answers a re-read. Nothing can then show the old value as the unit's.
    pub fn mark_unknown(&mut self, setting: Setting, at: Instant) {
        match setting {
            Setting::DeviceSpec(id) => clear(&mut self.device_specs, id),
            Setting::Name(id) => clear(&mut self.names, id),
            Setting::Enable(id) => clear(&mut self.enabled, id),
            Setting::System => self.system_spec = None,
            Setting::Flaps => self.flap_spec = None,
            Setting::Trim(TrimKind::Pitch) => self.pitch_trim_spec = None,
            Setting::Trim(TrimKind::Roll) => self.roll_trim_spec = None,
            Setting::WigWag => self.wig_wag_spec = None,
        }
        if self.unknown.insert(setting, at).is_none() {
            self.log(
                at,
                LogLevel::Warning,
                format!(
                    "{}: the write went unanswered, so what the unit holds is unknown; re-reading",
                    setting.name()
                ),
            );
        }
        self.revision += 1;
    }

    /// When the unit last reported `setting`, if the model holds it.
    pub fn setting_heard(&self, setting: Setting) -> Option<Instant> {
        match setting {
            Setting::DeviceSpec(id) => self
                .device_specs
                .get(id as usize)
                .and_then(|s| s.map(|s| s.at)),
            Setting::Name(id) => self.names.get(id as usize).and_then(|s| s.map(|s| s.at)),
            Setting::Enable(id) => self.enabled.get(id as usize).and_then(|s| s.map(|s| s.at)),
            Setting::System => self.system_spec.map(|s| s.at),
            Setting::Flaps => self.flap_spec.map(|s| s.at),
            Setting::Trim(TrimKind::Pitch) => self.pitch_trim_spec.map(|s| s.at),
            Setting::Trim(TrimKind::Roll) => self.roll_trim_spec.map(|s| s.at),
            Setting::WigWag => self.wig_wag_spec.map(|s| s.at),
        }
    }

    /// The age of what the model holds for `setting` when it is old enough to say so
    /// ([`SETTING_OLD_AFTER`]); `None` when fresh or not held.
    pub fn setting_old(&self, setting: Setting, now: Instant) -> Option<Duration> {
        let age = now.saturating_duration_since(self.setting_heard(setting)?);
        (age > SETTING_OLD_AFTER).then_some(age)
    }

    /// Whether `setting` is unknown and being re-read.
    pub fn is_unknown(&self, setting: Setting) -> bool {
        self.unknown.contains_key(&setting)
    }

    pub fn note_connected(&mut self, at: Instant, port: String) {
        self.log(at, LogLevel::Info, format!("connected to {port}"));
        // While the link was down the unit may have restarted or its switches moved.
        self.holds.forget();
        self.connection = Connection::Connected { port, since: at };
        self.revision += 1;
    }

    pub fn note_link_lost(&mut self, at: Instant, reason: String) {
        if !matches!(&self.connection, Connection::Lost { reason: r, .. } if *r == reason) {
            self.log(at, LogLevel::Alert, format!("link lost: {reason}"));
        }
        self.connection = Connection::Lost { reason, since: at };
        self.revision += 1;
    }

    pub fn note_write_error(&mut self, at: Instant, reason: String) {
        self.link.write_errors += 1;
        self.log(at, LogLevel::Warning, format!("could not send: {reason}"));
        self.link.last_write_error = Some(reason);
    }

    pub fn note_decoder(&mut self, stats: DecoderStats) {
        self.link.decoder = stats;
    }

    pub fn note_malformed(&mut self) {
        self.link.malformed += 1;
    }

    pub fn log(&mut self, at: Instant, level: LogLevel, text: String) {
        self.revision += 1;
        if self.events.len() == EVENT_LOG_LEN {
            self.events.pop_front();
        }
        self.events.push_back(LogEntry { at, level, text });
    }

    // ----- reading the model -----

    /// Neither SYSTEM_STATUS nor DEVICE_STATUS for more than 2.5 s (Appendix A).
    pub fn comm_lost(&self, now: Instant) -> bool {
        let live = |s: Option<Instant>| {
            s.is_some_and(|at| now.saturating_duration_since(at) <= COMM_LOST_AFTER)
        };
        !(live(self.system_status.map(|s| s.at)) || live(self.device_status.map(|s| s.at)))
    }

    /// Whether we have ever heard the unit on this connection's data.
    pub fn ever_heard(&self) -> bool {
        self.system_status.is_some() || self.device_status.is_some()
    }

    pub fn live_system(&self, now: Instant) -> Option<&SystemStatus> {
        self.system_status.as_ref()?.fresh(now, STATUS_STALE_AFTER)
    }

    pub fn live_devices(&self, now: Instant) -> Option<&DeviceStatus> {
        self.device_status.as_ref()?.fresh(now, STATUS_STALE_AFTER)
    }

    pub fn live_flap_trim(&self, now: Instant) -> Option<&FlapTrimStatus> {
        self.flap_trim.as_ref()?.fresh(now, FLAP_TRIM_STALE_AFTER)
    }

    /// Live fault codes per device and the system fault flag, or `None` when there is
    /// no live status to judge by. A quiet FAULT_STATUS while the other broadcasts
    /// flow means no faults (icd-reading R9).
    pub fn live_faults(&self, now: Instant) -> Option<([FaultCode; DEVICE_COUNT], bool)> {
        if self.comm_lost(now) {
            return None;
        }
        Some(self.faults_at(now))
    }

    fn faults_at(&self, now: Instant) -> ([FaultCode; DEVICE_COUNT], bool) {
        let mut codes = [FaultCode::NoFault; DEVICE_COUNT];
        let mut system = false;
        if let Some(f) = self
            .fault_status
            .as_ref()
            .and_then(|f| f.fresh(now, FAULT_STATUS_QUIET_AFTER))
        {
            for (i, c) in codes.iter_mut().enumerate() {
                // A fault the unit cleared on a reset, though its last FAULT_STATUS,
                // made before the reset, still lists it.
                let cleared = matches!(self.after_reset(i as u8, now), Some(AfterReset::Cleared));
                if f.faulted[i] && !cleared {
                    // A fault bit without its code (short payload) is still a fault.
                    *c = match f.codes[i] {
                        Some(FaultCode::NoFault) | None => FaultCode::Unknown(0xFF),
                        Some(code) => code,
                    };
                }
            }
            system = f.system_fault;
        }
        (codes, system)
    }

    fn log_new_faults(&mut self, at: Instant, before: ([FaultCode; DEVICE_COUNT], bool)) {
        let (now_codes, now_sys) = self.faults_at(at);
        for (id, (now_code, was)) in now_codes.iter().zip(before.0).enumerate() {
            if now_code.is_fault() && !was.is_fault() {
                let name = self.display_name(id as u8);
                self.log(at, LogLevel::Alert, format!("{name}: {}", now_code.name()));
                self.faults_seen.push((id as u8, name, now_code.name()));
            }
        }
        if now_sys && !before.1 {
            self.log(at, LogLevel::Alert, "system fault".into());
            self.faults_seen
                .push((255, "system".into(), "system fault".into()));
        }
    }

    /// DEVICE_NAME if set, else the Appendix B system name.
    pub fn display_name(&self, id: u8) -> String {
        let named = self
            .names
            .get(id as usize)
            .and_then(|n| n.as_ref())
            .map(|n| n.value.text());
        if self.is_unknown(Setting::Name(id)) || self.rereading_setting(Setting::Name(id)) {
            return "? (name re-reading…)".into();
        }
        match named {
            Some(n) if !n.trim().is_empty() => n,
            _ => device::device(id)
                .map_or_else(|| format!("device {id}"), |d| d.system_name.to_string()),
        }
    }

    /// The secondary alternator's device id, if the unit told us one is configured.
    pub fn secondary_alternator(&self) -> Option<u8> {
        self.system_spec
            .as_ref()
            .and_then(|s| s.value.secondary_alternator)
    }

    /// A motor's configuration as the unit last reported it (FLAP_SPEC or TRIM_SPEC,
    /// ICD Tables 15 and 16): whether it is enabled, and its (up, down) endpoints.
    /// Configuration, not a reading: it may be old.
    pub fn motor_spec(&self, motor: Motor) -> Option<(bool, (u8, u8))> {
        let trim = |t: &Option<Stamped<TrimSpec>>| {
            t.map(|s| (s.value.enabled, (s.value.up, s.value.down)))
        };
        match motor {
            Motor::Flaps => self
                .flap_spec
                .map(|s| (s.value.enabled, (s.value.up, s.value.down))),
            Motor::Trim(TrimKind::Pitch) => trim(&self.pitch_trim_spec),
            Motor::Trim(TrimKind::Roll) => trim(&self.roll_trim_spec),
        }
    }

    /// Whether a device belongs on the page: starter, EFIS and Field_Pri always; flaps
    /// and trims by their enable flags; 4–28 by DEVICE_ENABLE. A device whose flag we
    /// have not (yet) been told is shown: hiding a circuit from someone checking
    /// wiring is worse than showing one too many.
    pub fn is_shown(&self, id: u8, now: Instant) -> bool {
        let ft = self.live_flap_trim(now);
        match id {
            STARTER | EFIS | FIELD_PRI => true,
            id if let Some(m) = Motor::of_device(id) => ft
                .map(|f| f.axis(m.axis()).enabled)
                .or(self.motor_spec(m).map(|(enabled, _)| enabled))
                .unwrap_or(false),
            id => self
                .enabled
                .get(id as usize)
                .and_then(|e| e.map(|e| e.value))
                .unwrap_or(true),
        }
    }

    /// Every circuit the page shows, with live values or `Unknown`, in pin order.
    pub fn circuits(&self, now: Instant) -> Vec<Circuit> {
        let devices = self.live_devices(now);
        let faults = self.live_faults(now);
        let ft = self.live_flap_trim(now);
        let sec_alt = self.secondary_alternator();
        (0..DEVICE_COUNT as u8)
            .filter(|&id| self.is_shown(id, now))
            .map(|id| {
                let kind = match id {
                    STARTER => CircuitKind::Starter,
                    FIELD_PRI => CircuitKind::Alternator { primary: true },
                    FLAPS => CircuitKind::Flaps,
                    TRIM_P => CircuitKind::Trim(TrimKind::Pitch),
                    TRIM_R => CircuitKind::Trim(TrimKind::Roll),
                    id if Some(id) == sec_alt => CircuitKind::Alternator { primary: false },
                    _ => CircuitKind::Device,
                };
                let i = id as usize;
                let motor_fault =
                    ft.map(|f| Motor::of_device(id).map_or(FaultCode::NoFault, |m| m.fault(f)));
                let state = match (devices, faults) {
                    (Some(d), Some((codes, _))) => {
                        let code = if codes[i].is_fault() {
                            codes[i]
                        } else {
                            motor_fault.unwrap_or(FaultCode::NoFault)
                        };
                        let switched = if d.on[i] {
                            CircuitState::On
                        } else {
                            CircuitState::Off
                        };
                        match self.after_reset(id, now) {
                            _ if !code.is_fault() => switched,
                            Some(AfterReset::Waiting { .. }) => CircuitState::ResetSent(code),
                            Some(AfterReset::Cleared) => switched,
                            _ => CircuitState::Fault(code),
                        }
                    }
                    _ => CircuitState::Unknown,
                };
                let spec = self.device_specs[i].map(|s| s.value);
                let setting = match kind {
                    CircuitKind::Flaps => Some(Setting::Flaps),
                    CircuitKind::Trim(_) => None,
                    _ => Some(Setting::DeviceSpec(id)),
                };
                let spec_unknown =
                    setting.is_some_and(|s| self.is_unknown(s) || self.rereading_setting(s));

                let breaker = match kind {
                    CircuitKind::Flaps => self.flap_spec.map(|s| s.value.circuit_breaker),
                    CircuitKind::Trim(_) => device::device(id).map(|d| d.amps_max),
                    _ => spec.map(|s| s.circuit_breaker),
                };
                Circuit {
                    id,
                    name: self.display_name(id),
                    pin: device::device(id).map_or("?", |d| d.system_name),
                    kind,
                    state,
                    amps: devices.map(|d| d.current[i].value()),
                    breaker,
                    switch: match kind {
                        CircuitKind::Device | CircuitKind::Alternator { .. } => {
                            spec.map(|s| s.switch_id)
                        }
                        _ => None,
                    },
                    spec_unknown,
                    faulted_again: matches!(state, CircuitState::Fault(_))
                        && self.fault_heard_after_reset(id),
                }
            })
            .collect()
    }
}

fn clear<T>(slots: &mut [Option<Stamped<T>>], id: u8) {
    if let Some(slot) = slots.get_mut(id as usize) {
        *slot = None;
    }
}

fn bump(map: &mut BTreeMap<&'static str, MessageStat>, name: &'static str, at: Instant) {
    map.entry(name)
        .and_modify(|s| {
            s.count += 1;
            s.last = at;
        })
        .or_insert(MessageStat {
            count: 1,
            first: at,
            last: at,
        });
}

/// Words for a SPEC_ACK device id (ICD Table 19 note 1).
pub fn spec_target(id: u8) -> String {
    match id {
        device::SYSTEM_SPEC_ID => "system settings".into(),
        device::WIG_WAG_SPEC_ID => "wig-wag".into(),
        id => {
            device::device(id).map_or_else(|| format!("device {id}"), |d| d.system_name.to_string())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::{FaultStatus, SignedTenths, Tenths};

    fn status_packets(on: &[u8], amps: u16) -> (Packet, Packet) {
        let mut d = DeviceStatus::default();
        for &id in on {
            d.on[id as usize] = true;
            d.current[id as usize] = Tenths(amps);
        }
        let s = SystemStatus {
            system_current: Tenths(123),
            main_bus_volts: SignedTenths(138),
            internal_temp: 30,
            ..Default::default()
        };
        (Packet::from_vpx(0, s), Packet::from_vpx(1, d))
    }

    #[test]
    fn values_blank_and_comm_lost_after_two_and_a_half_seconds() {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        assert!(m.comm_lost(t0), "nothing heard yet is not live data");
        let (s, d) = status_packets(&[EFIS], 25);
        m.apply_packet(t0, &s);
        m.apply_packet(t0, &d);
        let efis = |m: &Model, t| m.circuits(t).into_iter().find(|c| c.id == EFIS).unwrap();
        assert_eq!(
            efis(&m, t0 + Duration::from_millis(2400)).state,
            CircuitState::On
        );
        assert_eq!(efis(&m, t0 + Duration::from_millis(2400)).amps, Some(2.5));
        let later = t0 + Duration::from_millis(2600);
        assert!(m.comm_lost(later));
        assert_eq!(efis(&m, later).state, CircuitState::Unknown);
        assert_eq!(efis(&m, later).amps, None);
        assert!(m.live_system(later).is_none());
    }

    #[test]
    fn a_quiet_fault_status_means_no_faults_while_status_flows() {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        let f = FaultStatus::with_faults(&[(5, FaultCode::ShortCircuit)]);
        let (s, d) = status_packets(&[], 0);
        m.apply_packet(t0, &s);
        m.apply_packet(t0, &d);
        m.apply_packet(t0, &Packet::from_vpx(2, f));
        let state5 = |m: &Model, t| m.circuits(t).into_iter().find(|c| c.id == 5).unwrap().state;
        assert_eq!(state5(&m, t0), CircuitState::Fault(FaultCode::ShortCircuit));
        assert!(m.events.iter().any(|e| e.text.contains("SHORT_CIRCUIT")));
        // Three seconds on, status still arriving but no FAULT_STATUS: the fault cleared.
        let t3 = t0 + Duration::from_secs(3);
        m.apply_packet(t3, &s);
        m.apply_packet(t3, &d);
        assert_eq!(state5(&m, t3), CircuitState::Off);
    }

    #[test]
    fn disabled_devices_are_hidden_and_unknown_ones_shown() {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        m.apply_packet(
            t0,
            &Packet::from_vpx(
                1,
                DeviceEnable {
                    device_id: 7,
                    flag: EnableFlag::Disabled,
                },
            ),
        );
        assert!(!m.is_shown(7, t0));
        assert!(m.is_shown(8, t0));
        assert!(m.is_shown(STARTER, t0));
        assert!(
            !m.is_shown(FLAPS, t0),
            "flaps follow their own enable flag, unknown means not fitted"
        );
    }
}

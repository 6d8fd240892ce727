//! The gateway: the VP-X on the XFSp network. A pure core driven by the caller's clock;
//! the sockets live in [`super::net`].
//!
//! # Wiring it into a main loop
//!
//! ```no_run
//! # use std::time::Instant;
//! # use vpx_efis::model::{Model, Source};
//! # use vpx_efis::xfsp::gateway::{Gateway, GatewayConfig};
//! # use vpx_efis::xfsp::net::{Target, XfspNet};
//! # fn send_to_unit(_: vpx_efis::protocol::message::Packet) {}
//! # let mut model = Model::new(Source::Simulated { scenario: "demo".into() });
//! # let mut ctl = vpx_efis::control::Controller::default();
//! # let link_events = crossbeam_channel::never::<()>();
//! let now = Instant::now();
//! let mut gw = Gateway::new(GatewayConfig::default(), now);
//! let net = XfspNet::open(&Target::parse("224.0.2.69:20234").unwrap(), "0.0.0.0".parse().unwrap()).unwrap();
//! loop {
//!     let wait = gw.next_deadline().saturating_duration_since(Instant::now());
//!     crossbeam_channel::select! {
//!         recv(link_events) -> _ev => {
//!             // model.apply_packet(..) / model.note_*(..) as usual; then fall through to
//!             // tick so a reached flap target or a new fault goes out at once.
//!         }
//!         recv(net.incoming()) -> d => {
//!             if let Ok(d) = d {
//!                 for p in gw.receive(&d.bytes, &mut model, &mut ctl, d.at) { send_to_unit(p) }
//!             }
//!         }
//!         default(wait) => {}
//!     }
//!     let step = gw.tick(&mut model, &mut ctl, Instant::now());
//!     for p in step.to_unit { send_to_unit(p) }
//!     let _ = net.send_all(&step.datagrams);
//! }
//! ```
//!
//! Motor requests run through the [`Controller`] the caller passes, the one every
//! motor run of the process goes through ([`super::drive`]). Duties of the caller,
//! each of which the motor stream's safety depends on (as for the controller): call
//! [`Gateway::tick`] at [`Gateway::next_deadline`] and after applying received
//! packets, tick the controller as for any run (a link error, quit and the rest end
//! the network's run as they end any), and call [`Gateway::shutdown`] before leaving,
//! sending what they return.
//!
//! Every command taken from the network, and every refusal, goes to the model's event
//! log (`model.log`), prefixed "XFSp" and the sender's source id, and is counted in
//! [`GatewayStats`]: nothing with SYSSEL/USERSEL confidence is dropped in silence.
//!
//! Commands are taken only when [`GatewayConfig::control`] allows their source
//! (`--xfsp-control`, `--xfsp-control-from`); by default every one is refused before
//! it is read further, counted in [`GatewayStats::commands_not_allowed`], and said in
//! the log once per source every [`NOT_ALLOWED_SAID_EVERY`]. Air data and publishing
//! do not depend on it.
//!
//! # How an ECBSTAT request names its circuit
//!
//! The draft gives ECBSTAT "Unit Usage: None" and a label, so the label alone must do;
//! we also publish each circuit with its VP-X device id as the unit, so a requester
//! that copies our unit number works too. The rule ([`match_circuit`]):
//! - a label and unit 0 (the draft's "None"): the circuit with that label;
//! - a label and a unit other than 0: both, and they must name the same circuit;
//! - no label: the circuit with that unit number (0 is then the flaps, device 0).
//!
//! A label is taken in the draft's "System/Item" form (Table 18), as we publish it
//! ("VP-X/LANDING LT"), or as the plain item ("LANDING LT"): the item is compared with
//! the circuits' names, trimmed and ignoring ASCII case. A label whose system part is
//! not ours ("ECU/FUEL PUMP") is for another system's breakers and is refused, never
//! matched by its item alone. (A name of ours that itself holds a '/' still matches
//! whole.) A label no circuit has, a label two circuits share, a unit no circuit has,
//! and a unit and label that disagree are refused, logged with the reason and counted.
//!
//! # Message classes and order
//!
//! We send OP/FLIGHTDATA (draft Table 2, value 2). The draft names DEVSTATUS (3,
//! "Device Status") but says nothing of what goes in it, and its one worked message
//! (§5.1) carries one device's state (a radio's frequency) as FLIGHTDATA; so does our
//! electrical state. On receipt every OP and MAINT message with parameters is read,
//! FLIGHTDATA, DEVSTATUS or any other operation.
//!
//! §4.4: a message numbered at or below the last one from its source is discarded
//! ([`super::receiver`], serial-number arithmetic). Decision: a source silent for
//! [`FORGET_SOURCE_AFTER`] (10 s) is forgotten, and its next message is taken whatever
//! its number. A node that restarts numbers "with an arbitrary initial value" (§4.1);
//! without this it would be ignored until its numbers passed the old ones (up to
//! 32767 messages). An old message replayed after 10 s of silence is taken once.
//! The receiver's table of sources is bounded by that silence, not by a count a busy
//! network passes (see [`super::receiver`] for the bound against forged ids).
//!
//! # Master Caution and Master Warning
//!
//! MSTRCAUTN or MSTRWARN with SYSSEL/USERSEL and FALSE resets that master (the draft's
//! words); see [`super::publish`] for when it rises again. TRUE is refused: the masters
//! are raised by the VP-X's faults, not by the network.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use crate::control::{Action, Controller, MotorStreamer, StopReason, command};
use crate::model::{LogLevel, Model, Motor, TrimKind};
use crate::protocol::device::DEVICE_COUNT;
use crate::protocol::message::{Message, Packet};

use super::consume::{AirData, Forwarded};
use super::dict::{CertLevel, Confidence, EcbState};
use super::drive::MotorDrive;
use super::format::{CasMsg, Value, latin1};
use super::header::Header;
use super::idents::{self, Ident};
use super::param::Parameter;
use super::publish::{Master, Publisher, SYSTEM_LABEL};
use super::receiver::{Received, Receiver, RxStats};
use super::sender::{MsgKind, Sender};

/// The gateway re-reads the model at least this often, so changes that come from the
/// clock alone (lost communication, a fault message aging out) go out promptly.
pub const POLL: Duration = Duration::from_millis(100);
/// The same circuit command from the network within this window is taken once: a
/// requester repeating itself against packet loss should not flood the unit or the log.
pub const COMMAND_REPEAT_WINDOW: Duration = Duration::from_secs(1);
/// At most this many requests are remembered for [`COMMAND_REPEAT_WINDOW`]. Their
/// keys hold labels from the network, so a flood of distinct ones within the window
/// must not grow the map without end; past this the oldest is forgotten (its repeat
/// is then taken, or refused, once more: harmless).
pub const RECENT_MAX: usize = 1024;
/// A source silent this long is forgotten, so a node that restarted (and numbers its
/// messages from scratch) is heard again at once instead of after 32767 messages.
/// A deliberate exception to the draft's §4.4 "MUST be discarded": see the module's
/// notes on order. The receiver keeps the rule ([`super::receiver::FORGET_AFTER`]),
/// and bounds its table by it, not by a count.
pub const FORGET_SOURCE_AFTER: Duration = super::receiver::FORGET_AFTER;
/// A source refused for want of `--xfsp-control` gets one line in the event log this
/// often (with the running count), not one per datagram: a display repeating its
/// request at 4 Hz must not bury the log.
pub const NOT_ALLOWED_SAID_EVERY: Duration = Duration::from_secs(10);

/// Who may command the unit over the network. XFSp -00 has no
/// authentication, so nobody may unless the person asked: `--xfsp-control` for any
/// source, `--xfsp-control-from` for listed ones. Publishing and taking air data do
/// not depend on it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub enum Control {
    /// Commands are refused (the default).
    #[default]
    Off,
    /// Commands from any source are taken (under control's rules).
    Any,
    /// Commands only from these source ids.
    From(Vec<u16>),
}

impl Control {
    /// `None` when `src` may command; otherwise why not, in words.
    pub fn refusal(&self, src: u16) -> Option<String> {
        match self {
            Control::Any => None,
            Control::From(ids) if ids.contains(&src) => None,
            Control::Off => Some(
                "commands from the network are off (start with --xfsp-control to take them)".into(),
            ),
            Control::From(ids) => Some(format!(
                "{src:#06x} is not in --xfsp-control-from ({})",
                source_list(ids)
            )),
        }
    }

    /// For the status line: "off", "from any source", "only from 0x1234, 0x5678".
    pub fn describe(&self) -> String {
        match self {
            Control::Off => "network commands off".into(),
            Control::Any => "network commands from any source".into(),
            Control::From(ids) => format!("network commands only from {}", source_list(ids)),
        }
    }
}

/// Source ids as hex, comma-separated.
pub fn source_list(ids: &[u16]) -> String {
    ids.iter()
        .map(|id| format!("{id:#06x}"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[derive(Debug, Clone)]
pub struct GatewayConfig {
    /// Our source id; messages carrying it are our own and are ignored.
    pub source_id: u16,
    pub cert: CertLevel,
    /// The first message number ("an arbitrary initial value", §4.1).
    pub first_msg_num: u16,
    /// Who may command the unit (off unless asked for).
    pub control: Control,
}

impl Default for GatewayConfig {
    /// Source id 0x5650 ("VP"), EXPERIMENTAL, like the command line's defaults.
    fn default() -> Self {
        GatewayConfig {
            source_id: 0x5650,
            cert: CertLevel::Experimental,
            first_msg_num: 0,
            control: Control::Off,
        }
    }
}

/// What one tick produced.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TickOutput {
    /// For the VP-X, in order.
    pub to_unit: Vec<Packet>,
    /// For the network, in order.
    pub datagrams: Vec<Vec<u8>>,
}

/// Counters for a status line.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct GatewayStats {
    /// Ordering and framing verdicts of everything not our own.
    pub rx: RxStats,
    /// Our own datagrams heard back (multicast loop).
    pub own: u64,
    /// Parameters in well-formed datagrams whose value did not decode.
    pub undecodable: u64,
    /// Requests acted on: circuit commands sent, motor runs started (or the motor
    /// already there), master resets.
    pub commands_taken: u64,
    /// Requests refused or expired unserved, each with a line in the event log.
    pub commands_refused: u64,
    /// Commands refused because this source may not command (see [`Control`]):
    /// counted apart from [`Self::commands_refused`], and said in the event log once
    /// per source every [`NOT_ALLOWED_SAID_EVERY`].
    pub commands_not_allowed: u64,
    pub datagrams_built: u64,
    pub build_errors: u64,
}

pub struct Gateway {
    cfg: GatewayConfig,
    sender: Sender,
    receiver: Receiver,
    publisher: Publisher,
    air: AirData,
    drive: MotorDrive,
    /// Requests taken (or refused for good: naming no circuit, or one never switched)
    /// lately, by (ident, unit or device id, state): a repeat within
    /// [`COMMAND_REPEAT_WINDOW`] is the same request.
    recent: HashMap<(Ident, u16, u8, Vec<u8>), Instant>,
    /// When each source last had a line for a command it may not give.
    not_allowed_said: HashMap<u16, Instant>,
    last_tick: Instant,
    stats: GatewayStats,
}

impl Gateway {
    pub fn new(cfg: GatewayConfig, now: Instant) -> Gateway {
        Gateway {
            sender: Sender::new(cfg.source_id, cfg.first_msg_num),
            receiver: Receiver::default(),
            publisher: Publisher::new(cfg.cert, cfg.source_id, now),
            air: AirData::default(),
            drive: MotorDrive::default(),
            recent: HashMap::new(),
            not_allowed_said: HashMap::new(),
            last_tick: now,
            stats: GatewayStats::default(),
            cfg,
        }
    }

    pub fn config(&self) -> &GatewayConfig {
        &self.cfg
    }

    /// Takes one datagram from the network. Returns packets for the VP-X (circuit
    /// commands, and the first move message of a motor request) to send at once.
    /// Malformed, duplicate, out-of-order and our own datagrams are counted and dropped.
    /// Motor requests run through `ctl`, the controller every origin's runs go through.
    pub fn receive(
        &mut self,
        datagram: &[u8],
        model: &mut Model,
        ctl: &mut Controller,
        now: Instant,
    ) -> Vec<Packet> {
        if Header::parse(datagram).is_ok_and(|h| h.src_id == self.cfg.source_id) {
            self.stats.own += 1;
            return Vec::new();
        }
        let mut commands = Vec::new();
        let params: Vec<(u16, Result<Parameter, super::Error>)> =
            match self.receiver.receive(datagram, now) {
                Received::Fresh(view) => {
                    let src = view.header().src_id;
                    view.params().map(|p| (src, p.to_parameter())).collect()
                }
                _ => Vec::new(),
            };
        for (src, p) in params {
            match p {
                Ok(p) => self.take(src, &p, model, now, &mut commands),
                Err(_) => self.stats.undecodable += 1,
            }
        }
        let mut out: Vec<Packet> = commands
            .into_iter()
            .map(|m| Packet::request(ctl.next_cnt(), m))
            .collect();
        out.extend(self.drive.tick(ctl, model, now));
        out
    }

    /// Everything due at `now`: the motor stream, EXTERNAL_DATA at 1 Hz, and the
    /// published parameters packed into datagrams.
    pub fn tick(&mut self, model: &mut Model, ctl: &mut Controller, now: Instant) -> TickOutput {
        let mut to_unit = self.drive.tick(ctl, model, now);
        if let Some(d) = self.air.due(now) {
            to_unit.push(Packet::request(ctl.next_cnt(), d));
        }
        let params = self.publisher.poll(model, now);
        let mut datagrams = Vec::new();
        if !params.is_empty() {
            match self
                .sender
                .pack(MsgKind::flight_data(self.cfg.cert), &params)
            {
                Ok(d) => datagrams = d,
                Err(e) => {
                    self.stats.build_errors += 1;
                    model.log(
                        now,
                        LogLevel::Warning,
                        format!("XFSp: could not build a datagram: {e}"),
                    );
                }
            }
        }
        self.stats.datagrams_built += datagrams.len() as u64;
        self.last_tick = now;
        TickOutput { to_unit, datagrams }
    }

    /// When [`tick`](Self::tick) must next be called.
    pub fn next_deadline(&self) -> Instant {
        [
            self.publisher.next_deadline(),
            self.air.next_deadline(),
            self.drive.next_deadline(),
            Some(self.last_tick + POLL),
        ]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(self.last_tick + POLL)
    }

    /// Leaving: stop messages for every motor, running or not, since a stop that is
    /// not needed is harmless and a missing one is not.
    pub fn shutdown(
        &mut self,
        model: &mut Model,
        ctl: &mut Controller,
        now: Instant,
    ) -> Vec<Packet> {
        let mut out = self.drive.stop(ctl, model, now, StopReason::Quit);
        if out.is_empty() {
            out.extend(MotorStreamer::emergency_stop_packets());
        }
        out
    }

    /// What is being forwarded to the VP-X as EXTERNAL_DATA (the page shows it).
    pub fn forwarding(&self, now: Instant) -> [Forwarded; 5] {
        self.air.forwarded(now)
    }

    /// The CAS messages we have standing on the network.
    pub fn standing_cas(&self) -> Vec<(u16, CasMsg)> {
        self.publisher.standing_cas()
    }

    /// The motor a network request runs, while `ctl` runs it.
    pub fn running_motor(&self, ctl: &Controller) -> Option<Motor> {
        self.drive.running(ctl)
    }

    pub fn stats(&self) -> GatewayStats {
        let drive = self.drive.counts();
        GatewayStats {
            rx: self.receiver.stats(),
            commands_taken: self.stats.commands_taken + drive.taken,
            commands_refused: self.stats.commands_refused + drive.refused,
            ..self.stats
        }
    }

    /// Whether a master annunciator is TRUE on the network now.
    pub fn master_active(&self, master: Master) -> bool {
        self.publisher.master_active(master)
    }

    fn take(
        &mut self,
        src: u16,
        p: &Parameter,
        model: &mut Model,
        now: Instant,
        out: &mut Vec<Message>,
    ) {
        if self.air.offer(src, p, now).is_some() {
            return;
        }
        let commanding = matches!(p.confidence, Confidence::UserSel | Confidence::SysSel);
        if !commanding {
            // Status from other nodes (their own ECBs, their positions) is not for us.
            return;
        }
        let who = format!("XFSp {src:#06x} ({})", confidence_name(p.confidence));
        let is_command = Master::from_ident(p.ident).is_some()
            || [
                idents::ECBSTAT,
                idents::FLAPREQ,
                idents::PTRIMREQ,
                idents::RTRIMREQ,
            ]
            .contains(&p.ident);
        if !is_command {
            return;
        }
        if let Some(why) = self.cfg.control.refusal(src) {
            return self.not_allowed(&who, src, p.ident, &why, model, now);
        }
        if let Some(master) = Master::from_ident(p.ident) {
            return self.master_reset(&who, master, p, model, now);
        }
        let motor = match p.ident {
            idents::ECBSTAT => return self.circuit_command(&who, p, model, now, out),
            idents::FLAPREQ => Motor::Flaps,
            idents::PTRIMREQ => Motor::Trim(TrimKind::Pitch),
            idents::RTRIMREQ => Motor::Trim(TrimKind::Roll),
            _ => return,
        };
        let Value::Sint(target) = p.value else {
            return self.refuse(
                model,
                now,
                format!("{who}: {} request refused: not a SINT", motor.name()),
            );
        };
        let held = self.drive.request_for(motor);
        if held.is_none_or(|r| r.target != target) {
            // Heard; the drive counts it as taken or refused when it answers it.
            model.log(
                now,
                LogLevel::Info,
                format!("{who}: {} to {target}", motor.name()),
            );
        }
        self.drive
            .request(motor, target, src, p.expire.duration(), now);
    }

    /// A command from a source that may not command: counted always, said once per
    /// source every [`NOT_ALLOWED_SAID_EVERY`], with the count so far.
    fn not_allowed(
        &mut self,
        who: &str,
        src: u16,
        ident: Ident,
        why: &str,
        model: &mut Model,
        now: Instant,
    ) {
        self.stats.commands_not_allowed += 1;
        if self
            .not_allowed_said
            .get(&src)
            .is_some_and(|&t| now.saturating_duration_since(t) < NOT_ALLOWED_SAID_EVERY)
        {
            return;
        }
        // Keyed by a 16-bit id, so bounded; pruned so it holds only recent talkers.
        if self.not_allowed_said.len() >= 64 {
            self.not_allowed_said
                .retain(|_, t| now.saturating_duration_since(*t) < NOT_ALLOWED_SAID_EVERY);
        }
        self.not_allowed_said.insert(src, now);
        let name = idents::name(ident).map_or_else(|| ident.to_string(), str::to_string);
        let n = self.stats.commands_not_allowed;
        model.log(
            now,
            LogLevel::Warning,
            format!(
                "{who}: {name} refused: {why}; {n} network command{} refused so far",
                if n == 1 { "" } else { "s" }
            ),
        );
    }

    fn refuse(&mut self, model: &mut Model, now: Instant, text: String) {
        self.stats.commands_refused += 1;
        model.log(now, LogLevel::Warning, text);
    }

    /// Whether the same request was seen within the repeat window; notes it if not.
    fn repeated(&mut self, key: (Ident, u16, u8, Vec<u8>), now: Instant) -> bool {
        if self
            .recent
            .get(&key)
            .is_some_and(|&t| now.saturating_duration_since(t) < COMMAND_REPEAT_WINDOW)
        {
            return true;
        }
        self.remember(key, now);
        false
    }

    /// Notes a request as seen at `now`, keeping at most [`RECENT_MAX`].
    fn remember(&mut self, key: (Ident, u16, u8, Vec<u8>), now: Instant) {
        if self.recent.len() >= RECENT_MAX && !self.recent.contains_key(&key) {
            self.recent
                .retain(|_, t| now.saturating_duration_since(*t) < COMMAND_REPEAT_WINDOW);
            if self.recent.len() >= RECENT_MAX
                && let Some(oldest) = self
                    .recent
                    .iter()
                    .min_by_key(|(_, t)| **t)
                    .map(|(k, _)| k.clone())
            {
                self.recent.remove(&oldest);
            }
        }
        self.recent.insert(key, now);
    }

    /// MSTRCAUTN/MSTRWARN with SYSSEL/USERSEL: FALSE resets, anything else is refused.
    fn master_reset(
        &mut self,
        who: &str,
        master: Master,
        p: &Parameter,
        model: &mut Model,
        now: Instant,
    ) {
        let name = master.name();
        match &p.value {
            Value::Bool(b) if b.as_bool() == Some(false) => {
                let acknowledged = self.publisher.reset_master(master);
                // A reset that finds nothing new is harmless; repeats of it (a display
                // sending its reset a few times against loss) are taken once.
                let key = (master.ident(), 0, 0, Vec::new());
                if acknowledged == 0 && self.repeated(key, now) {
                    return;
                }
                if acknowledged > 0 {
                    self.remember((master.ident(), 0, 0, Vec::new()), now);
                }
                self.stats.commands_taken += 1;
                let what = match acknowledged {
                    0 => "nothing new was standing".to_string(),
                    1 => "1 message acknowledged".to_string(),
                    n => format!("{n} messages acknowledged"),
                };
                model.log(now, LogLevel::Info, format!("{who}: {name} reset ({what})"));
            }
            Value::Bool(_) => self.refuse(
                model,
                now,
                format!("{who}: {name} refused: only FALSE resets it; the VP-X's faults raise it"),
            ),
            _ => self.refuse(model, now, format!("{who}: {name} refused: not a BOOL")),
        }
    }

    fn circuit_command(
        &mut self,
        who: &str,
        p: &Parameter,
        model: &mut Model,
        now: Instant,
        out: &mut Vec<Message>,
    ) {
        let Value::Bus(bus) = &p.value else {
            return self.refuse(model, now, format!("{who}: ECBSTAT refused: not a BUS"));
        };
        let state_name = bus
            .state
            .spec_name()
            .map_or_else(|| format!("state {}", u8::from(bus.state)), str::to_string);
        let label = latin1(&bus.label);
        let id = match match_circuit(model, now, p.unit, &label) {
            Ok(id) => id,
            Err(why) => {
                // A requester repeating a request that names nothing gets one answer a
                // window, not one per datagram.
                let key = (
                    idents::ECBSTAT,
                    p.unit,
                    u8::from(bus.state),
                    bus.label.clone(),
                );
                if !self.repeated(key, now) {
                    self.refuse(
                        model,
                        now,
                        format!("{who}: ECBSTAT {state_name} refused: {why}"),
                    );
                }
                return;
            }
        };
        let name = model.display_name(id);
        let key = (
            idents::ECBSTAT,
            u16::from(id),
            u8::from(bus.state),
            Vec::new(),
        );
        if self
            .recent
            .get(&key)
            .is_some_and(|&t| now.saturating_duration_since(t) < COMMAND_REPEAT_WINDOW)
        {
            return;
        }
        let action = match bus.state {
            EcbState::On => Action::PowerOn(id),
            EcbState::Off => Action::PowerOff(id),
            EcbState::Reset => Action::Reset(id),
            _ => {
                return self.refuse(
                    model,
                    now,
                    format!("{who}: {name} {state_name}: only ON, OFF and RESET are commands"),
                );
            }
        };
        match command(&action, model, now) {
            Ok(message) => {
                // Only a command taken is suppressed on repeat: a retry after a refusal
                // may find the circuit in the state it needed.
                self.remember(key, now);
                self.stats.commands_taken += 1;
                model.log(
                    now,
                    LogLevel::Info,
                    format!("{who}: {name} {state_name} -> {}", message.name()),
                );
                out.push(message);
            }
            Err(why) => {
                // A refusal no retry can change (the starter, a motor, no such
                // circuit) is answered once a window, as a request naming nothing is;
                // any other may pass on a retry once the state it needed comes.
                if why.reason.lasts() {
                    self.remember(key, now);
                }
                self.refuse(
                    model,
                    now,
                    format!("{who}: {name} {state_name} refused: {why}"),
                )
            }
        }
    }
}

/// The circuit an ECBSTAT request names (see the module's notes): by label when the
/// unit is 0, by unit when there is no label, by both otherwise; a "System/Item" label
/// by its item when the system is ours. `Err` says why none.
pub fn match_circuit(model: &Model, now: Instant, unit: u16, label: &str) -> Result<u8, String> {
    let label = label.trim();
    let whole_is_a_name = || {
        model
            .circuits(now)
            .iter()
            .any(|c| model.display_name(c.id).trim().eq_ignore_ascii_case(label))
    };
    let label = match label.split_once('/') {
        Some(_) if whole_is_a_name() => label,
        Some((system, item)) if system.trim().eq_ignore_ascii_case(SYSTEM_LABEL) => item.trim(),
        Some((system, _)) => {
            return Err(format!(
                "{label:?} is for system {:?}, not {SYSTEM_LABEL}",
                system.trim()
            ));
        }
        None => label,
    };
    let by_unit = u8::try_from(unit)
        .ok()
        .filter(|&id| usize::from(id) < DEVICE_COUNT);
    if label.is_empty() {
        return by_unit.ok_or_else(|| {
            format!(
                "no label, and unit {unit} is no circuit (units are device ids 0-{})",
                DEVICE_COUNT - 1
            )
        });
    }
    let named = |id: u8| model.display_name(id).trim().eq_ignore_ascii_case(label);
    if unit != 0 {
        return match by_unit {
            Some(id) if named(id) => Ok(id),
            Some(id) => Err(format!(
                "unit {unit} is {:?}, not {label:?}",
                model.display_name(id).trim()
            )),
            None => Err(format!(
                "unit {unit} is no circuit, and the label is {label:?}"
            )),
        };
    }
    let found: Vec<u8> = model
        .circuits(now)
        .iter()
        .map(|c| c.id)
        .filter(|&id| named(id))
        .collect();
    match found.as_slice() {
        [id] => Ok(*id),
        [] => Err(format!("no circuit is named {label:?}")),
        ids => Err(format!(
            "{} circuits are named {label:?} (units {}); give the unit too",
            ids.len(),
            ids.iter().map(u8::to_string).collect::<Vec<_>>().join(", ")
        )),
    }
}

fn confidence_name(c: Confidence) -> String {
    c.spec_name()
        .map_or_else(|| format!("confidence {}", u8::from(c)), str::to_string)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Refused requests naming labels nobody has, each one different, all within the
    /// repeat window: the memory of them stays bounded, and the newest is remembered.
    #[test]
    fn a_flood_of_distinct_labels_keeps_the_recent_map_bounded() {
        let t0 = Instant::now();
        let mut gw = Gateway::new(GatewayConfig::default(), t0);
        for i in 0..5 * RECENT_MAX as u32 {
            let key = (idents::ECBSTAT, 0, 1, i.to_be_bytes().to_vec());
            assert!(!gw.repeated(key, t0 + Duration::from_micros(u64::from(i))));
        }
        assert!(gw.recent.len() <= RECENT_MAX, "{}", gw.recent.len());
        let last = (5 * RECENT_MAX as u32 - 1).to_be_bytes().to_vec();
        let now = t0 + Duration::from_millis(100);
        assert!(gw.repeated((idents::ECBSTAT, 0, 1, last), now));
    }
}

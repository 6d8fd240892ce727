//! What the gateway tells the network about the VP-X, decided from the model at `now`.
//!
//! Each item is sent when it changes (but not more often than [`MIN_INTERVAL`]) and at
//! least every [`REFRESH`], with an Expire of [`LIFETIME`]: a receiver that misses two
//! refreshes in a row sees our data go stale rather than showing it as current.
//!
//! Items (unit numbers are ours where the draft says "None"; see below):
//! - ECBSTAT, unit = device id, label "VP-X/" and the device's name (Table 18's
//!   "System/Item"): state from [`ecb_state`], drawn amps, breaker as `maxamps`, volts
//!   fields unused (0, no INPUTVOLTS flag: the VP-X measures no per-pin voltage).
//! - BUSSTAT unit 0 "VP-X/MAIN BUS": main bus volts as `outvolts`, total system current
//!   as `drawamps`. BUSSTAT unit 1 "VP-X/AUX BATTERY": aux battery volts; the VP-X
//!   measures no aux battery current, so `drawamps` is 0; state OFF below 1 V.
//! - FLAPPOS/PTRIMPOS/RTRIMPOS, unit 0, scaled by [`super::scale`]; only while the motor
//!   is enabled and its position is live.
//! - CASMSG, unit = our CAS system id (the draft's "Unit Usage: CAS System ID": the
//!   system raising the alert, which is us; the gateway gives its XFSp source id), one
//!   per fault: level by [`cas_level`], label "NAME: FAULT" (which tells the alerts
//!   apart). When it goes away, a CLEAR with the same unit and label is sent
//!   [`CLEAR_REPEATS`] times, one per refresh, so one lost datagram does not leave it
//!   standing on another display. Inside, each alert is still keyed by its device id
//!   (255 system fault, 256 lost communication): [`Publisher::standing_cas`].
//!
//! Why ECBSTAT and BUSSTAT carry a unit although the draft says "Unit Usage: None":
//! "None" gives the field no meaning; it does not say "set to 0" as the draft does
//! where a field must be zero ("Reserved, set to 0" in CASMSG). A receiver that follows
//! the draft ignores it and tells circuits apart by their "System/Item" label; one that
//! keys every parameter by ident and unit, as the rest of the draft's parameters are
//! keyed, keeps our 31 circuits and 2 buses apart instead of folding them onto unit 0.
//! Requests are taken with unit 0 (see `gateway`).
//! - MSTRCAUTN and MSTRWARN, unit 0: TRUE while a CAUTION (for MSTRCAUTN) or a WARNING
//!   (for MSTRWARN) we issued stands that nobody has reset. The draft: "Resets by
//!   SYSSEL/USERSEL with value of FALSE". A reset ([`Publisher::reset_master`])
//!   acknowledges every message of its level standing at that moment; the master stays
//!   FALSE until a message of that level arises that was not standing then (a new fault,
//!   or one that cleared and came back). Each level raises only its own master, as on a
//!   glass cockpit's two annunciators: a short circuit lights Master Warning, an open
//!   breaker Master Caution.
//!
//! Items that stop being published (a pin found disabled once the unit's DEVICE_ENABLE
//! replies arrive, a position that is no longer live) are forgotten at once: nothing is
//! due for them, so [`Publisher::next_deadline`] never points at a refresh that no poll
//! will make (that was a busy loop). When one comes back it goes out at once.
//!
//! Lost communication: [`Model::circuits`] already says UNKNOWN and gives no amps, so
//! ECBSTAT goes UNKNOWN (confidence USELESS), BUSSTAT goes UNKNOWN with zeros,
//! positions stop (and expire at receivers), fault messages are withdrawn (they can no
//! longer be vouched for) and "VP-X COMM LOST" is raised instead. That message waits
//! for [`COMM_LOST_AFTER`] after the gateway starts, so the first seconds of opening
//! the port do not flash an alert on every display.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::time::{Duration, Instant};

use crate::model::{COMM_LOST_AFTER, Circuit, CircuitState, Model, Motor, Setting, TrimKind};
use crate::protocol::device::SYSTEM_FAULT_ID;
use crate::protocol::fault::FaultCode;

use super::dict::{Boolean, CasLevel, CertLevel, Confidence, EcbFlags, EcbState};
use super::expire::Expire;
use super::format::{Bus, CasMsg, Value};
use super::idents::{self, Ident};
use super::param::Parameter;
use super::scale::Travel;

/// Every item is re-sent at least this often (the draft's status rates are 1 Hz).
pub const REFRESH: Duration = Duration::from_secs(1);
/// A changing item is not re-sent more often than this: FLAP_TRIM_STATUS is 10 Hz, so
/// a moving flap is published at the rate it changes, and nothing faster.
pub const MIN_INTERVAL: Duration = Duration::from_millis(100);
/// The lifetime our items claim: two refreshes and half a refresh of jitter, the same
/// 2.5 s the page itself allows the VP-X's 1 Hz broadcasts.
pub const LIFETIME: Duration = Duration::from_millis(2500);
/// How many times a CLEAR is sent.
pub const CLEAR_REPEATS: u8 = 3;
/// The key of "VP-X COMM LOST" among our alerts (above every device id and 255).
pub const CAS_UNIT_COMM_LOST: u16 = 256;
/// The system part of our BUS labels (draft Table 18: "Label for BUS Message
/// (System/Item)").
pub const SYSTEM_LABEL: &str = "VP-X";

/// A BUS label in the draft's "System/Item" form: "VP-X/LANDING LT".
pub fn bus_label(item: &str) -> Vec<u8> {
    super::format::latin1_bytes(&format!("{SYSTEM_LABEL}/{item}"))
}
/// A circuit's name as the network is told it. While the name is not known (being
/// read again after a loss of communication, or left unknown by an unanswered write)
/// the screen's "? (name re-reading…)" would give every such circuit one and the same
/// label, and a receiver that follows the draft tells circuits apart by label alone.
/// So the network gets the pin's own Table 40 name, marked: "5A-3 (name re-reading)",
/// longer than the 16 bytes a DEVICE_NAME can be (ICD Table 21), so it can be no
/// circuit's real name either.
pub fn network_name(model: &Model, c: &Circuit) -> String {
    let name = Setting::Name(c.id);
    if model.is_unknown(name) || model.rereading_setting(name) {
        format!("{} (name re-reading)", c.pin)
    } else {
        c.name.clone()
    }
}

/// BUSSTAT units.
pub const BUS_MAIN: u16 = 0;
pub const BUS_AUX: u16 = 1;

/// The Expire octet sent with every published item.
pub fn lifetime_expire() -> Expire {
    Expire::at_least(LIFETIME)
}

/// ECB state for a circuit state. Every Appendix E code maps:
///
/// | VP-X fault (Table 43) | ecb-state |
/// |---|---|
/// | OVER_VOLTAGE 0x06 | OVERVOL |
/// | SHORT_CIRCUIT 0x07 | SHORTED |
/// | OVER_CURRENT 0x08 | OVERCUR |
/// | CURRENT_FAULT 0x09 | DISABLED (a current fault that is neither of the above) |
/// | FLAP_RUNAWAY 0x0A, TRIM_RUNAWAY 0x0E | RUNAWAY |
/// | FLAP_ACTIVE 0x0B, TRIM_ACTIVE 0x10 | DISABLED (not cleared: switch held) |
/// | FLAP_DISABLED 0x0C, TRIM_DISABLED 0x0F | DISABLED (until power cycle) |
/// | reserved or unlisted codes | DISABLED (the pin is off; why is not known) |
///
/// A fault whose reset the unit has not yet answered is UNKNOWN: it may be gone, and
/// an ecb-state has no words to say "reset sent" (its RESET is a request).
pub fn ecb_state(state: CircuitState) -> EcbState {
    match state {
        CircuitState::On => EcbState::On,
        CircuitState::Off => EcbState::Off,
        CircuitState::Unknown | CircuitState::ResetSent(_) => EcbState::Unknown0,
        CircuitState::Fault(code) => fault_ecb_state(code),
    }
}

pub fn fault_ecb_state(code: FaultCode) -> EcbState {
    match code {
        FaultCode::NoFault => EcbState::Unknown0,
        FaultCode::OverVoltage => EcbState::OverVol,
        FaultCode::ShortCircuit => EcbState::Shorted,
        FaultCode::OverCurrent => EcbState::OverCur,
        FaultCode::FlapRunaway | FaultCode::TrimRunaway => EcbState::Runaway,
        FaultCode::CurrentFault
        | FaultCode::FlapActive
        | FaultCode::FlapDisabled
        | FaultCode::TrimDisabled
        | FaultCode::TrimActive
        | FaultCode::Unknown(_) => EcbState::Disabled,
    }
}

/// WARNING for what needs immediate action (a short, over-voltage, a runaway motor);
/// CAUTION for the rest, which leave a circuit off until someone resets it.
pub fn cas_level(code: FaultCode) -> CasLevel {
    match code {
        FaultCode::ShortCircuit
        | FaultCode::OverVoltage
        | FaultCode::FlapRunaway
        | FaultCode::TrimRunaway => CasLevel::Warning,
        _ => CasLevel::Caution,
    }
}

/// The CAS text for a device fault.
pub fn fault_label(name: &str, code: FaultCode) -> String {
    format!("{}: {}", name.trim(), code.name().replace('_', " "))
}

#[derive(Debug, Clone)]
struct Sent {
    param: Parameter,
    at: Instant,
}

/// The two master annunciators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Master {
    /// MSTRCAUTN, raised by CAUTION-level CAS messages.
    Caution,
    /// MSTRWARN, raised by WARNING-level CAS messages.
    Warning,
}

impl Master {
    pub const ALL: [Master; 2] = [Master::Caution, Master::Warning];

    pub fn ident(self) -> Ident {
        match self {
            Master::Caution => idents::MSTRCAUTN,
            Master::Warning => idents::MSTRWARN,
        }
    }

    pub fn from_ident(ident: Ident) -> Option<Master> {
        Master::ALL.into_iter().find(|m| m.ident() == ident)
    }

    /// The CAS level that raises it.
    pub fn level(self) -> CasLevel {
        match self {
            Master::Caution => CasLevel::Caution,
            Master::Warning => CasLevel::Warning,
        }
    }

    /// For the event log.
    pub fn name(self) -> &'static str {
        match self {
            Master::Caution => "Master Caution",
            Master::Warning => "Master Warning",
        }
    }
}

/// A CAS message as the masters see it: its unit and words.
type CasKey = (u16, Vec<u8>);

#[derive(Debug, Clone)]
struct Clearing {
    label: Vec<u8>,
    left: u8,
    next: Instant,
}

/// The publishing half of the gateway. Pure: it reads the model and the clock it is
/// given and returns parameters to send.
#[derive(Debug, Clone)]
pub struct Publisher {
    cert: CertLevel,
    /// CASMSG's unit: "CAS System ID", ours.
    cas_system: u16,
    started: Instant,
    sent: HashMap<(Ident, u16), Sent>,
    /// CAS messages standing, by unit.
    cas: BTreeMap<u16, Sent>,
    clearing: BTreeMap<u16, Vec<Clearing>>,
    /// The earliest a held-back change may go out.
    pending: Option<Instant>,
    /// Per master, the messages of its level standing when it was last reset.
    acked_caution: BTreeSet<CasKey>,
    acked_warning: BTreeSet<CasKey>,
}

impl Publisher {
    /// `cas_system` is the unit our CASMSGs carry (the gateway gives its source id).
    pub fn new(cert: CertLevel, cas_system: u16, now: Instant) -> Publisher {
        Publisher {
            cert,
            cas_system,
            started: now,
            sent: HashMap::new(),
            cas: BTreeMap::new(),
            clearing: BTreeMap::new(),
            pending: None,
            acked_caution: BTreeSet::new(),
            acked_warning: BTreeSet::new(),
        }
    }

    /// The parameters due at `now`.
    pub fn poll(&mut self, model: &Model, now: Instant) -> Vec<Parameter> {
        let mut out = Vec::new();
        self.pending = None;
        let mut offered = HashSet::new();
        for p in self.status(model, now) {
            offered.insert((p.ident, p.unit));
            self.offer(p, now, &mut out);
        }
        let cas = self.wanted_cas(model, now);
        self.update_cas(cas, now, &mut out);
        self.forget_withdrawn_acknowledgements();
        for master in Master::ALL {
            let on = self.master_active(master);
            let p = self.param(master.ident(), 0, Value::Bool(Boolean::from(on)));
            offered.insert((p.ident, p.unit));
            self.offer(p, now, &mut out);
        }
        // What was not offered is no longer published: keeping it would leave a refresh
        // due in the past that no poll ever makes, and the caller's loop would spin.
        self.sent.retain(|key, _| offered.contains(key));
        out
    }

    /// When `poll` next has something to send even if the model does not change. After
    /// a `poll(.., now)` this is always later than `now`.
    pub fn next_deadline(&self) -> Option<Instant> {
        let refresh = self
            .sent
            .values()
            .chain(self.cas.values())
            .map(|s| s.at + REFRESH);
        let clears = self.clearing.values().flatten().map(|c| c.next);
        refresh.chain(clears).chain(self.pending).min()
    }

    /// Whether `master` is TRUE now (as published at the last poll, or the next one
    /// after a reset).
    pub fn master_active(&self, master: Master) -> bool {
        let acked = self.acked(master);
        self.standing_keys(master.level())
            .any(|key| !acked.contains(&key))
    }

    /// A SYSSEL/USERSEL FALSE for `master`: every message of its level standing now is
    /// acknowledged, and the master goes FALSE at the next poll. Returns how many
    /// messages were acknowledged that were not before (0: nothing to reset).
    pub fn reset_master(&mut self, master: Master) -> usize {
        let keys: Vec<CasKey> = self.standing_keys(master.level()).collect();
        let acked = self.acked_mut(master);
        keys.into_iter().filter(|k| acked.insert(k.clone())).count()
    }

    fn acked(&self, master: Master) -> &BTreeSet<CasKey> {
        match master {
            Master::Caution => &self.acked_caution,
            Master::Warning => &self.acked_warning,
        }
    }

    fn acked_mut(&mut self, master: Master) -> &mut BTreeSet<CasKey> {
        match master {
            Master::Caution => &mut self.acked_caution,
            Master::Warning => &mut self.acked_warning,
        }
    }

    fn standing_keys(&self, level: CasLevel) -> impl Iterator<Item = CasKey> + '_ {
        self.cas
            .iter()
            .filter_map(move |(&unit, s)| match &s.param.value {
                Value::CasMsg(m) if m.level == level => Some((unit, m.label.clone())),
                _ => None,
            })
    }

    /// A message that was withdrawn is no longer acknowledged: if it comes back it is a
    /// new caution and raises its master again.
    fn forget_withdrawn_acknowledgements(&mut self) {
        for master in Master::ALL {
            let standing: BTreeSet<CasKey> = self.standing_keys(master.level()).collect();
            self.acked_mut(master).retain(|k| standing.contains(k));
        }
    }

    /// CAS messages standing now, by unit (for the page and the tests).
    pub fn standing_cas(&self) -> Vec<(u16, CasMsg)> {
        self.cas
            .iter()
            .filter_map(|(&u, s)| match &s.param.value {
                Value::CasMsg(m) => Some((u, m.clone())),
                _ => None,
            })
            .collect()
    }

    fn param(&self, ident: Ident, unit: u16, value: Value) -> Parameter {
        Parameter::new(ident, value)
            .unit(unit)
            .expire(lifetime_expire())
            .cert(self.cert)
    }

    /// Sends `p` if it is new, changed (and not too soon), or due for a refresh.
    fn offer(&mut self, p: Parameter, now: Instant, out: &mut Vec<Parameter>) {
        let key = (p.ident, p.unit);
        let due = match self.sent.get(&key) {
            None => true,
            Some(s) if now >= s.at + REFRESH => true,
            Some(s) if s.param != p => {
                let earliest = s.at + MIN_INTERVAL;
                if now < earliest {
                    self.pending = Some(self.pending.map_or(earliest, |e| e.min(earliest)));
                }
                now >= earliest
            }
            Some(_) => false,
        };
        if due {
            self.sent.insert(
                key,
                Sent {
                    param: p.clone(),
                    at: now,
                },
            );
            out.push(p);
        }
    }

    fn status(&mut self, model: &Model, now: Instant) -> Vec<Parameter> {
        let mut out = Vec::new();
        let lost = model.comm_lost(now);
        for c in model.circuits(now) {
            let state = ecb_state(c.state);
            let bus = Bus {
                state,
                flags: EcbFlags::default(),
                draw_amps: c.amps.map_or(0, Bus::to_tenths),
                max_amps: c.breaker.map_or(0, |b| Bus::to_tenths(f32::from(b))),
                label: bus_label(&network_name(model, &c)),
                ..Bus::default()
            };
            let confidence = if state == EcbState::Unknown0 {
                Confidence::Useless
            } else {
                Confidence::High
            };
            out.push(
                self.param(idents::ECBSTAT, u16::from(c.id), Value::Bus(bus))
                    .confidence(confidence),
            );
        }
        let system = if lost { None } else { model.live_system(now) };
        let (main, aux) = match system {
            Some(s) => {
                let aux_v = s.aux_battery_volts.value();
                (
                    Bus {
                        state: EcbState::On,
                        out_volts: Bus::to_tenths(s.main_bus_volts.value()),
                        draw_amps: Bus::to_tenths(s.system_current.value()),
                        ..Bus::default()
                    },
                    Bus {
                        state: if aux_v >= 1.0 {
                            EcbState::On
                        } else {
                            EcbState::Off
                        },
                        out_volts: Bus::to_tenths(aux_v),
                        ..Bus::default()
                    },
                )
            }
            None => (Bus::default(), Bus::default()),
        };
        for (unit, mut bus, label) in [(BUS_MAIN, main, "MAIN BUS"), (BUS_AUX, aux, "AUX BATTERY")]
        {
            bus.label = bus_label(label);
            let confidence = if bus.state == EcbState::Unknown0 {
                Confidence::Useless
            } else {
                Confidence::High
            };
            out.push(
                self.param(idents::BUSSTAT, unit, Value::Bus(bus))
                    .confidence(confidence),
            );
        }
        if let Some(ft) = model.live_flap_trim(now).filter(|_| !lost) {
            for (motor, ident) in [
                (Motor::Flaps, idents::FLAPPOS),
                (Motor::Trim(TrimKind::Pitch), idents::PTRIMPOS),
                (Motor::Trim(TrimKind::Roll), idents::RTRIMPOS),
            ] {
                let a = ft.axis(motor.axis());
                if let Some(travel) = Travel::for_motor(motor, ft).filter(|_| a.enabled) {
                    out.push(self.param(ident, 0, Value::Sint(travel.to_scale(a.position))));
                }
            }
        }
        out
    }

    fn wanted_cas(&self, model: &Model, now: Instant) -> BTreeMap<u16, CasMsg> {
        let mut want = BTreeMap::new();
        if model.comm_lost(now) {
            if now.saturating_duration_since(self.started) >= COMM_LOST_AFTER {
                want.insert(
                    CAS_UNIT_COMM_LOST,
                    CasMsg::new(CasLevel::Caution, "VP-X COMM LOST"),
                );
            }
            return want;
        }
        for c in model.circuits(now) {
            if let CircuitState::Fault(code) = c.state {
                want.insert(
                    u16::from(c.id),
                    CasMsg::new(
                        cas_level(code),
                        &fault_label(&network_name(model, &c), code),
                    ),
                );
            }
        }
        if let Some((_, true)) = model.live_faults(now) {
            want.insert(
                u16::from(SYSTEM_FAULT_ID),
                CasMsg::new(CasLevel::Caution, "VP-X SYSTEM FAULT"),
            );
        }
        want
    }

    fn update_cas(&mut self, want: BTreeMap<u16, CasMsg>, now: Instant, out: &mut Vec<Parameter>) {
        // Withdraw what no longer stands, or stands with other words.
        let gone: Vec<u16> = self
            .cas
            .iter()
            .filter(|(u, s)| {
                want.get(u)
                    .is_none_or(|m| Value::CasMsg(m.clone()) != s.param.value)
            })
            .map(|(&u, _)| u)
            .collect();
        for unit in gone {
            if let Some(Sent {
                param:
                    Parameter {
                        value: Value::CasMsg(old),
                        ..
                    },
                ..
            }) = self.cas.remove(&unit)
            {
                self.clearing.entry(unit).or_default().push(Clearing {
                    label: old.label,
                    left: CLEAR_REPEATS,
                    next: now,
                });
            }
        }
        // CLEARs first, so a receiver never sees the new words withdrawn.
        let mut clears = Vec::new();
        for (&unit, list) in self.clearing.iter_mut() {
            for c in list.iter_mut().filter(|c| now >= c.next && c.left > 0) {
                let mut m = CasMsg::new(CasLevel::Clear, "");
                m.label = c.label.clone();
                clears.push((unit, m));
                c.left -= 1;
                c.next = now + REFRESH;
            }
            list.retain(|c| c.left > 0);
        }
        self.clearing.retain(|_, l| !l.is_empty());
        for (_, m) in clears {
            out.push(self.param(idents::CASMSG, self.cas_system, Value::CasMsg(m)));
        }
        for (unit, msg) in want {
            let p = self.param(idents::CASMSG, self.cas_system, Value::CasMsg(msg.clone()));
            let due = self.cas.get(&unit).is_none_or(|s| now >= s.at + REFRESH);
            if due {
                if !self.cas.contains_key(&unit)
                    && let Some(list) = self.clearing.get_mut(&unit)
                {
                    // A CLEAR still going out for these very words would withdraw the
                    // message we are raising again.
                    list.retain(|c| c.label != msg.label);
                }
                self.cas.insert(
                    unit,
                    Sent {
                        param: p.clone(),
                        at: now,
                    },
                );
                out.push(p);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Source;
    use crate::protocol::message::{
        DeviceEnable, DeviceStatus, EnableFlag, FaultStatus, FlapFlags, FlapTrimStatus, Packet,
        SignedTenths, SystemStatus, Tenths,
    };

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    fn model() -> Model {
        Model::new(Source::Simulated {
            scenario: "test".into(),
        })
    }

    /// The unit's two 1 Hz broadcasts, EFIS on.
    fn status(m: &mut Model, at: Instant) {
        let mut d = DeviceStatus::default();
        d.on[2] = true;
        d.current[2] = Tenths(25);
        let s = SystemStatus {
            system_current: Tenths(40),
            main_bus_volts: SignedTenths(138),
            aux_battery_volts: Tenths(126),
            internal_temp: 30,
            ..Default::default()
        };
        m.apply_packet(at, &Packet::from_vpx(0, s));
        m.apply_packet(at, &Packet::from_vpx(1, d));
    }

    /// A unit whose 1 Hz broadcasts were heard at `at`, and a publisher started then.
    fn heard(at: Instant) -> (Model, Publisher) {
        let mut m = model();
        status(&mut m, at);
        (m, Publisher::new(CertLevel::Experimental, 0x5650, at))
    }

    fn flaps_live(m: &mut Model, at: Instant) {
        let ft = FlapTrimStatus {
            flap: FlapFlags {
                enabled: true,
                ..Default::default()
            },
            flap_position: 60,
            flap_up: 40,
            flap_down: 200,
            ..Default::default()
        };
        m.apply_packet(at, &Packet::from_vpx(3, ft));
    }

    fn disable(m: &mut Model, at: Instant, id: u8) {
        let e = DeviceEnable {
            device_id: id,
            flag: EnableFlag::Disabled,
        };
        m.apply_packet(at, &Packet::from_vpx(4, e));
    }

    fn fault(m: &mut Model, at: Instant, faults: &[(u8, FaultCode)]) {
        m.apply_packet(at, &Packet::from_vpx(5, FaultStatus::with_faults(faults)));
    }

    /// Drives `p` the way a main loop does, from `from` to `until`: poll, then sleep to
    /// the deadline. Every deadline must be later than the poll before it; returns the
    /// number of polls, which a spinning loop would make in the millions.
    fn run(p: &mut Publisher, m: &mut Model, from: Instant, until: Instant) -> usize {
        let mut now = from;
        let mut polls = 0;
        while now < until {
            // The unit's 1 Hz broadcasts, on their own schedule.
            let second = from + ms(1000 * ((now - from).as_millis() as u64 / 1000));
            status(m, second);
            p.poll(m, now);
            polls += 1;
            let next = p.next_deadline().expect("something is always refreshed");
            assert!(
                next > now,
                "poll at +{:?} left a deadline at +{:?}",
                now - from,
                next.saturating_duration_since(from)
            );
            now = next;
        }
        polls
    }

    #[test]
    fn disabled_circuits_leave_no_deadline_in_the_past() {
        let t0 = Instant::now();
        let (mut m, mut p) = heard(t0);
        flaps_live(&mut m, t0);
        // Before the DEVICE_ENABLE replies every pin is published once…
        let first = p.poll(&m, t0);
        let ecb = |ps: &[Parameter]| ps.iter().filter(|p| p.ident == idents::ECBSTAT).count();
        assert!(ecb(&first) > 20, "{}", ecb(&first));
        assert!(first.iter().any(|p| p.ident == idents::FLAPPOS));
        // …then the replies say most are disabled, as on a real installation, and the
        // flap status stops (its position is no longer live).
        for id in 4..=28 {
            if id != 5 {
                disable(&mut m, t0 + ms(50), id);
            }
        }
        let polls = run(&mut p, &mut m, t0 + ms(50), t0 + ms(10_000));
        // One poll per second of refresh plus the moments things changed; a loop
        // spinning on a past deadline would never get to 10 s at all.
        assert!(polls <= 30, "{polls} polls in 10 s");
        let last = p.poll(&m, t0 + ms(10_000));
        assert!(last.iter().all(|p| p.ident != idents::FLAPPOS));
        assert!(ecb(&last) <= 6, "only the six pins still published");
        assert!(p.next_deadline().unwrap() > t0 + ms(10_000));
    }

    #[test]
    fn a_circuit_that_returns_is_published_at_once() {
        let t0 = Instant::now();
        let (mut m, mut p) = heard(t0);
        p.poll(&m, t0);
        disable(&mut m, t0 + ms(10), 7);
        p.poll(&m, t0 + ms(20));
        let enable = DeviceEnable {
            device_id: 7,
            flag: EnableFlag::Enabled,
        };
        m.apply_packet(t0 + ms(30), &Packet::from_vpx(6, enable));
        let ps = p.poll(&m, t0 + ms(40));
        assert!(
            ps.iter().any(|p| p.ident == idents::ECBSTAT && p.unit == 7),
            "not held back by the interval of the old one"
        );
    }

    fn master(ps: &[Parameter], which: Master) -> Option<bool> {
        ps.iter()
            .find(|p| p.ident == which.ident())
            .map(|p| p.value == Value::Bool(Boolean::True))
    }

    #[test]
    fn master_caution_reset_holds_until_a_new_caution() {
        let t0 = Instant::now();
        let (mut m, mut p) = heard(t0);
        p.poll(&m, t0);
        fault(&mut m, t0 + ms(200), &[(5, FaultCode::OverCurrent)]);
        let ps = p.poll(&m, t0 + ms(200));
        assert_eq!(master(&ps, Master::Caution), Some(true));
        assert_eq!(master(&ps, Master::Warning), None, "unchanged: FALSE");
        assert!(!p.master_active(Master::Warning));

        assert_eq!(p.reset_master(Master::Caution), 1);
        let ps = p.poll(&m, t0 + ms(400));
        assert_eq!(master(&ps, Master::Caution), Some(false), "reset goes out");
        // The fault still stands; refreshes keep saying FALSE.
        let mut now = t0 + ms(400);
        while now < t0 + ms(3500) {
            fault(&mut m, now, &[(5, FaultCode::OverCurrent)]);
            status(&mut m, now);
            let ps = p.poll(&m, now);
            assert_ne!(master(&ps, Master::Caution), Some(true), "at {now:?}");
            now = p.next_deadline().unwrap();
        }
        assert_eq!(p.reset_master(Master::Caution), 0, "nothing new to reset");
        // A second caution is new: up again.
        fault(
            &mut m,
            now,
            &[(5, FaultCode::OverCurrent), (6, FaultCode::CurrentFault)],
        );
        status(&mut m, now);
        let ps = p.poll(&m, now);
        assert_eq!(master(&ps, Master::Caution), Some(true));
        assert_eq!(p.reset_master(Master::Caution), 1, "only the new one");
    }

    #[test]
    fn a_caution_that_clears_and_returns_raises_the_master_again() {
        let t0 = Instant::now();
        let (mut m, mut p) = heard(t0);
        fault(&mut m, t0, &[(5, FaultCode::OverCurrent)]);
        p.poll(&m, t0);
        assert!(p.master_active(Master::Caution));
        p.reset_master(Master::Caution);
        p.poll(&m, t0 + ms(100));
        assert!(!p.master_active(Master::Caution));
        // No FAULT_STATUS for 2.5 s: the fault has cleared.
        status(&mut m, t0 + ms(2700));
        p.poll(&m, t0 + ms(2700));
        assert!(p.standing_cas().is_empty());
        // The same fault again.
        fault(&mut m, t0 + ms(3000), &[(5, FaultCode::OverCurrent)]);
        let ps = p.poll(&m, t0 + ms(3000));
        assert_eq!(master(&ps, Master::Caution), Some(true));
    }

    #[test]
    fn a_short_circuit_raises_master_warning_which_resets_the_same_way() {
        let t0 = Instant::now();
        let (mut m, mut p) = heard(t0);
        let ps = p.poll(&m, t0);
        assert_eq!(master(&ps, Master::Warning), Some(false));
        assert_eq!(master(&ps, Master::Caution), Some(false));
        fault(&mut m, t0 + ms(200), &[(5, FaultCode::ShortCircuit)]);
        let ps = p.poll(&m, t0 + ms(200));
        assert_eq!(master(&ps, Master::Warning), Some(true));
        assert_eq!(
            master(&ps, Master::Caution),
            None,
            "a warning is not a caution"
        );
        // Resetting the caution does nothing to the warning.
        assert_eq!(p.reset_master(Master::Caution), 0);
        assert!(p.master_active(Master::Warning));
        assert_eq!(p.reset_master(Master::Warning), 1);
        let ps = p.poll(&m, t0 + ms(400));
        assert_eq!(master(&ps, Master::Warning), Some(false));
        fault(
            &mut m,
            t0 + ms(1500),
            &[(5, FaultCode::ShortCircuit), (9, FaultCode::OverVoltage)],
        );
        let ps = p.poll(&m, t0 + ms(1500));
        assert_eq!(master(&ps, Master::Warning), Some(true), "a new warning");
    }
}

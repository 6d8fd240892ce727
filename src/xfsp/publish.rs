//! What the gateway tells the network about the VP-X, decided from the model at `now`.
//!
//! Each item is sent when it changes (but not more often than [`MIN_INTERVAL`]) and at
//! least every [`REFRESH`], with an Expire of [`LIFETIME`]: a receiver that misses two
//! refreshes in a row sees our data go stale rather than showing it as current.
//!
//! Items (unit numbers are ours where the draft says "None"):
//! - ECBSTAT, unit = device id, label = the device's name: state from
//!   [`ecb_state`], drawn amps, breaker as `maxamps`, volts fields unused (0, no
//!   INPUTVOLTS flag: the VP-X measures no per-pin voltage).
//! - BUSSTAT unit 0 "MAIN BUS": main bus volts as `outvolts`, total system current as
//!   `drawamps`. BUSSTAT unit 1 "AUX BATTERY": aux battery volts; the VP-X measures no
//!   aux battery current, so `drawamps` is 0; state OFF below 1 V (none fitted).
//! - FLAPPOS/PTRIMPOS/RTRIMPOS, unit 0, scaled by [`super::scale`]; only while the motor
//!   is enabled and its position is live.
//! - CASMSG, unit = device id (255 for the system fault, 256 for lost communication),
//!   one per fault: level by [`cas_level`], label "NAME: FAULT". When it goes away, a
//!   CLEAR with the same unit and label is sent [`CLEAR_REPEATS`] times, one per
//!   refresh, so one lost datagram does not leave it standing on another display.
//! - MSTRCAUTN: TRUE while any CAUTION or WARNING we issued stands, else FALSE.
//!
//! Lost communication: [`Model::circuits`] already says UNKNOWN and gives no amps, so
//! ECBSTAT goes UNKNOWN (confidence USELESS), BUSSTAT goes UNKNOWN with zeros,
//! positions stop (and expire at receivers), fault messages are withdrawn (they can no
//! longer be vouched for) and "VP-X COMM LOST" is raised instead. That message waits
//! for [`COMM_LOST_AFTER`] after the gateway starts, so the first seconds of opening
//! the port do not flash an alert on every display.

use std::collections::{BTreeMap, HashMap};
use std::time::{Duration, Instant};

use crate::model::{COMM_LOST_AFTER, CircuitState, Model, Motor, TrimKind};
use crate::protocol::device::SYSTEM_FAULT_ID;
use crate::protocol::fault::FaultCode;

use super::dict::{Boolean, CasLevel, CertLevel, Confidence, EcbFlags, EcbState};
use super::expire::Expire;
use super::format::{Bus, CasMsg, Value};
use super::idents::{self, Ident};
use super::param::Parameter;
use super::scale::Axis;

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
/// CASMSG unit for "VP-X COMM LOST" (above every device id and 255).
pub const CAS_UNIT_COMM_LOST: u16 = 256;
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
pub fn ecb_state(state: CircuitState) -> EcbState {
    match state {
        CircuitState::On => EcbState::On,
        CircuitState::Off => EcbState::Off,
        CircuitState::Unknown => EcbState::Unknown0,
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
    started: Instant,
    sent: HashMap<(Ident, u16), Sent>,
    /// CAS messages standing, by unit.
    cas: BTreeMap<u16, Sent>,
    clearing: BTreeMap<u16, Vec<Clearing>>,
    /// The earliest a held-back change may go out.
    pending: Option<Instant>,
}

impl Publisher {
    pub fn new(cert: CertLevel, now: Instant) -> Publisher {
        Publisher {
            cert,
            started: now,
            sent: HashMap::new(),
            cas: BTreeMap::new(),
            clearing: BTreeMap::new(),
            pending: None,
        }
    }

    /// The parameters due at `now`.
    pub fn poll(&mut self, model: &Model, now: Instant) -> Vec<Parameter> {
        let mut out = Vec::new();
        self.pending = None;
        for p in self.status(model, now) {
            self.offer(p, now, &mut out);
        }
        let cas = self.wanted_cas(model, now);
        let caution = cas
            .values()
            .any(|m| matches!(m.level, CasLevel::Caution | CasLevel::Warning));
        self.update_cas(cas, now, &mut out);
        let master = self.param(idents::MSTRCAUTN, 0, Value::Bool(Boolean::from(caution)));
        self.offer(master, now, &mut out);
        out
    }

    /// When `poll` next has something to send even if the model does not change.
    pub fn next_deadline(&self) -> Option<Instant> {
        let refresh = self
            .sent
            .values()
            .chain(self.cas.values())
            .map(|s| s.at + REFRESH);
        let clears = self.clearing.values().flatten().map(|c| c.next);
        refresh.chain(clears).chain(self.pending).min()
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
                label: super::format::latin1_bytes(&c.name),
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
            bus.label = label.as_bytes().to_vec();
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
            for (motor, ident, enabled, raw) in [
                (
                    Motor::Flaps,
                    idents::FLAPPOS,
                    ft.flap.enabled,
                    ft.flap_position,
                ),
                (
                    Motor::Trim(TrimKind::Pitch),
                    idents::PTRIMPOS,
                    ft.pitch_trim.enabled,
                    ft.pitch_trim_position,
                ),
                (
                    Motor::Trim(TrimKind::Roll),
                    idents::RTRIMPOS,
                    ft.roll_trim.enabled,
                    ft.roll_trim_position,
                ),
            ] {
                if let Some(axis) = Axis::for_motor(motor, ft).filter(|_| enabled) {
                    out.push(self.param(ident, 0, Value::Sint(axis.to_scale(raw))));
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
                    CasMsg::new(cas_level(code), &fault_label(&c.name, code)),
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
        for (unit, m) in clears {
            out.push(self.param(idents::CASMSG, unit, Value::CasMsg(m)));
        }
        for (unit, msg) in want {
            let p = self.param(idents::CASMSG, unit, Value::CasMsg(msg.clone()));
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

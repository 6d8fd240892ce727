//! Writes to the unit from the setup screens, one at a time, on the page's own clock.
//!
//! Each write is sent, then waits for its SPEC_ACK in `Model::last_spec_ack` (stamped
//! after the send, with the device id the unit answers that message with), resent on
//! a timeout up to [`TRIES`] times, and then re-read with its query so the screen shows
//! what the unit really holds. DEVICE_ENABLE gets no SPEC_ACK (ICD Table 23): its
//! re-read is its acknowledgement. Nothing here blocks or reads a clock; the app calls
//! [`WriteQueue::tick`] with `now` and sends what comes back.
//!
//! One write is in flight at a time because SPEC_ACK says only which device it is for:
//! DEVICE_SPEC and DEVICE_NAME of one pin are answered alike, so two in flight could
//! not be told apart. A failed write stops the rest, as a restore does, so the screen
//! can say exactly what was applied.

use std::time::{Duration, Instant};

use crate::link::request::{setting_name, spec_ack_id};
use crate::model::Model;
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{FLAPS, SYSTEM_SPEC_ID, TRIM_P, TRIM_R, WIG_WAG_SPEC_ID};
use crate::protocol::message::{
    DeviceEnable, DeviceNameQuery, DeviceSpecQuery, EnableFlag, Message, TrimType,
};
use crate::protocol::validate;
use crate::ui::setup::state::{WriteLine, WriteStatus, switch_text};

/// How long to wait for a SPEC_ACK or a re-read answer before sending again. The unit
/// answers within a few frames; a second is generous and still quick to give up.
pub const ANSWER_TIMEOUT: Duration = Duration::from_secs(1);
/// Sends of one write (or one re-read) before "no answer".
pub const TRIES: u8 = 3;

#[derive(Debug, Clone, PartialEq, Eq)]
enum Phase {
    Queued,
    Sending {
        attempt: u8,
        sent_at: Instant,
    },
    Rereading {
        attempt: u8,
        sent_at: Instant,
        /// `None`: acknowledged; `Some`: the unit's refusal in words.
        refused: Option<String>,
    },
    Done(WriteStatus),
}

#[derive(Debug, Clone)]
struct Item {
    message: Message,
    phase: Phase,
}

/// The writes of one batch (one Enter, or one backup load), in order.
#[derive(Debug, Clone, Default)]
pub struct WriteQueue {
    items: Vec<Item>,
}

impl WriteQueue {
    /// Replaces the last batch with `messages`, sent from the next tick on.
    pub fn start(&mut self, messages: Vec<Message>) {
        self.items = messages
            .into_iter()
            .map(|message| Item {
                message,
                phase: Phase::Queued,
            })
            .collect();
    }

    /// A batch refused before sending: shown with the reason, nothing goes out.
    pub fn refused_here(&mut self, messages: &[Message], first_refused: usize, why: String) {
        self.items = messages
            .iter()
            .enumerate()
            .map(|(i, &message)| Item {
                message,
                phase: Phase::Done(if i == first_refused {
                    WriteStatus::Refused {
                        why: why.clone(),
                        by_unit: false,
                    }
                } else {
                    WriteStatus::NotSent
                }),
            })
            .collect();
    }

    pub fn busy(&self) -> bool {
        self.items
            .iter()
            .any(|i| !matches!(i.phase, Phase::Done(_)))
    }

    /// Whether every write of the batch was acknowledged.
    pub fn all_saved(&self) -> bool {
        !self.items.is_empty()
            && self
                .items
                .iter()
                .all(|i| matches!(i.phase, Phase::Done(WriteStatus::Saved { .. })))
    }

    pub fn lines(&self) -> Vec<WriteLine> {
        self.items
            .iter()
            .map(|i| WriteLine {
                what: setting_name(&i.message),
                status: match &i.phase {
                    Phase::Queued => WriteStatus::Queued,
                    Phase::Sending { attempt, .. } => WriteStatus::Sending {
                        attempt: *attempt,
                        of: TRIES,
                    },
                    Phase::Rereading { .. } => WriteStatus::Rereading,
                    Phase::Done(s) => s.clone(),
                },
            })
            .collect()
    }

    /// When `tick` must run again for a timeout.
    pub fn next_deadline(&self) -> Option<Instant> {
        self.items.iter().find_map(|i| match i.phase {
            Phase::Sending { sent_at, .. } | Phase::Rereading { sent_at, .. } => {
                Some(sent_at + ANSWER_TIMEOUT)
            }
            _ => None,
        })
    }

    /// Moves the batch on at `now` given what the model has heard; returns the
    /// messages to send now.
    pub fn tick(&mut self, model: &Model, now: Instant) -> Vec<Message> {
        let mut out = Vec::new();
        while let Some(idx) = self
            .items
            .iter()
            .position(|i| !matches!(i.phase, Phase::Done(_)))
        {
            let item = &mut self.items[idx];
            let m = item.message;
            let before = item.phase.clone();
            item.phase = match item.phase.clone() {
                Phase::Queued => {
                    out.push(m);
                    if is_enable(&m) {
                        // No SPEC_ACK comes: ask straight after the set, which the
                        // unit handles in order.
                        out.push(reread_query(&m));
                        Phase::Rereading {
                            attempt: 1,
                            sent_at: now,
                            refused: None,
                        }
                    } else {
                        Phase::Sending {
                            attempt: 1,
                            sent_at: now,
                        }
                    }
                }
                Phase::Sending { attempt, sent_at } => match ack_for(model, &m, sent_at) {
                    Some(error) => {
                        out.push(reread_query(&m));
                        Phase::Rereading {
                            attempt: 1,
                            sent_at: now,
                            refused: error.map(|e| {
                                let cfg = unit_config(model).0;
                                format!("{}: {}", e.description(), validate::explain(e, &cfg, &m))
                            }),
                        }
                    }
                    None if now >= sent_at + ANSWER_TIMEOUT && attempt < TRIES => {
                        out.push(m);
                        Phase::Sending {
                            attempt: attempt + 1,
                            sent_at: now,
                        }
                    }
                    None if now >= sent_at + ANSWER_TIMEOUT => Phase::Done(WriteStatus::NoAnswer),
                    None => Phase::Sending { attempt, sent_at },
                },
                Phase::Rereading {
                    attempt,
                    sent_at,
                    refused,
                } => match held_after(model, &m, sent_at) {
                    Some((holds, matches)) => Phase::Done(match refused {
                        Some(why) => WriteStatus::Refused {
                            why: format!("{why}; the unit holds {holds}"),
                            by_unit: true,
                        },
                        None if is_enable(&m) && !matches => WriteStatus::Refused {
                            why: format!("the unit still says {holds}"),
                            by_unit: true,
                        },
                        None => WriteStatus::Saved { holds, matches },
                    }),
                    None if now >= sent_at + ANSWER_TIMEOUT && attempt < TRIES => {
                        if is_enable(&m) {
                            out.push(m);
                        }
                        out.push(reread_query(&m));
                        Phase::Rereading {
                            attempt: attempt + 1,
                            sent_at: now,
                            refused,
                        }
                    }
                    None if now >= sent_at + ANSWER_TIMEOUT => Phase::Done(match refused {
                        Some(why) => WriteStatus::Refused { why, by_unit: true },
                        // DEVICE_ENABLE is only known set by its answer.
                        None if is_enable(&m) => WriteStatus::NoAnswer,
                        None => WriteStatus::Saved {
                            holds: "(acknowledged; the re-read got no answer)".into(),
                            matches: false,
                        },
                    }),
                    None => Phase::Rereading {
                        attempt,
                        sent_at,
                        refused,
                    },
                },
                Phase::Done(s) => Phase::Done(s),
            };
            let failed = matches!(
                item.phase,
                Phase::Done(WriteStatus::NoAnswer | WriteStatus::Refused { .. })
            );
            if failed {
                for later in &mut self.items[idx + 1..] {
                    later.phase = Phase::Done(WriteStatus::NotSent);
                }
            }
            if !matches!(self.items[idx].phase, Phase::Done(_)) || self.items[idx].phase == before {
                break;
            }
        }
        out
    }
}

fn is_enable(m: &Message) -> bool {
    matches!(m, Message::DeviceEnable(_))
}

/// The SPEC_ACK id the unit answers `m` with. TRIM_SPEC carries no id; the virtual
/// unit (and, we take it, the real one) answers with the axis's device id.
fn ack_id(m: &Message) -> Option<u8> {
    match m {
        Message::TrimSpec(t) if t.trim_type == TrimType::Roll => Some(TRIM_R),
        Message::TrimSpec(_) => Some(TRIM_P),
        m => spec_ack_id(m),
    }
}

/// `Some(error)` once the SPEC_ACK for `m` arrived after `sent_at`.
fn ack_for(
    model: &Model,
    m: &Message,
    sent_at: Instant,
) -> Option<Option<crate::protocol::message::SpecAckError>> {
    let ack = model.last_spec_ack?;
    (ack.at >= sent_at && Some(ack.value.device_id) == ack_id(m)).then_some(ack.value.error)
}

/// The query whose answer shows what the unit holds after `m`.
pub fn reread_query(m: &Message) -> Message {
    match *m {
        Message::DeviceSpec(s) => DeviceSpecQuery {
            device_id: s.device_id,
        }
        .into(),
        Message::DeviceName(n) => DeviceNameQuery {
            device_id: n.device_id,
        }
        .into(),
        Message::DeviceEnable(e) => DeviceEnable {
            device_id: e.device_id,
            flag: EnableFlag::Query,
        }
        .into(),
        Message::SystemSpec(_) => DeviceSpecQuery {
            device_id: SYSTEM_SPEC_ID,
        }
        .into(),
        Message::WigWagSpec(_) => DeviceSpecQuery {
            device_id: WIG_WAG_SPEC_ID,
        }
        .into(),
        Message::FlapSpec(_) => DeviceSpecQuery { device_id: FLAPS }.into(),
        Message::TrimSpec(t) => DeviceSpecQuery {
            device_id: if t.trim_type == TrimType::Roll {
                TRIM_R
            } else {
                TRIM_P
            },
        }
        .into(),
        m => m,
    }
}

/// What the unit holds for `m`'s setting, heard after `since`, in words, and whether
/// it is what `m` set.
fn held_after(model: &Model, m: &Message, since: Instant) -> Option<(String, bool)> {
    let fresh = |at: Instant| at >= since;
    match m {
        Message::DeviceSpec(s) => {
            let h = model.device_specs.get(s.device_id as usize)?.as_ref()?;
            fresh(h.at).then(|| (describe(&h.value.into()), h.value == *s))
        }
        Message::DeviceName(n) => {
            let h = model.names.get(n.device_id as usize)?.as_ref()?;
            fresh(h.at).then(|| (describe(&h.value.into()), h.value.text() == n.text()))
        }
        Message::DeviceEnable(e) => {
            let h = model.enabled.get(e.device_id as usize)?.as_ref()?;
            let want = e.flag == EnableFlag::Enabled;
            fresh(h.at).then(|| {
                (
                    if h.value { "shown" } else { "hidden" }.to_string(),
                    h.value == want,
                )
            })
        }
        Message::SystemSpec(s) => {
            let h = model.system_spec?;
            fresh(h.at).then(|| (describe(&h.value.into()), h.value == *s))
        }
        Message::WigWagSpec(s) => {
            let h = model.wig_wag_spec?;
            fresh(h.at).then(|| (describe(&h.value.into()), h.value == *s))
        }
        Message::FlapSpec(s) => {
            let h = model.flap_spec?;
            fresh(h.at).then(|| (describe(&h.value.into()), h.value == *s))
        }
        Message::TrimSpec(s) => {
            let h = if s.trim_type == TrimType::Roll {
                model.roll_trim_spec?
            } else {
                model.pitch_trim_spec?
            };
            fresh(h.at).then(|| (describe(&h.value.into()), h.value == *s))
        }
        _ => None,
    }
}

/// A spec in a few words, in real units.
pub fn describe(m: &Message) -> String {
    let pin = |id| crate::ui::setup::state::pin_text(id);
    match m {
        Message::DeviceSpec(s) => format!(
            "{} A, {}, current fault {}",
            s.circuit_breaker,
            switch_text(s.switch_id),
            if s.current_fault { "on" } else { "off" }
        ),
        Message::DeviceName(n) => format!("\"{}\"", n.text()),
        Message::SystemSpec(s) => format!(
            "overvoltage {} V, secondary alternator {}",
            if s.overvoltage_limit.to_byte() == 1 {
                32
            } else {
                16
            },
            s.secondary_alternator.map_or("none".into(), pin)
        ),
        Message::WigWagSpec(w) => format!(
            "{} / {}, warm-up {} s, below {} kt",
            w.device_one.map_or("none".into(), pin),
            w.device_two.map_or("none".into(), pin),
            w.warm_up_period,
            w.speed
        ),
        Message::FlapSpec(f) => format!(
            "{}up {} mid {}/{} down {}, {} A, overspeed {} above {} kt, run-on {:.1} s",
            if f.enabled { "" } else { "not fitted, " },
            f.up,
            f.midpoint_1,
            f.midpoint_2,
            f.down,
            f.circuit_breaker,
            f.overspeed_position,
            f.max_speed,
            f.endpoint_duration.value()
        ),
        Message::TrimSpec(t) => format!(
            "{}up {} neutral {} down {}, {} % above {} kt",
            if t.enabled { "" } else { "not fitted, " },
            t.up,
            t.neutral,
            t.down,
            t.power,
            t.speed
        ),
        m => m.name().to_string(),
    }
}

/// The unit's configuration as the model knows it, for the §6.2 checks and a backup,
/// and what the model has not been told (those parts keep their Appendix F defaults).
pub fn unit_config(model: &Model) -> (UnitConfig, Vec<String>) {
    let mut cfg = UnitConfig::default();
    let mut missing = Vec::new();
    for id in 1..TRIM_R {
        match model.device_specs[id as usize] {
            Some(s) => cfg.apply_device_spec(&s.value),
            None => missing.push(format!("DEVICE_SPEC {}", pin_short(id))),
        }
    }
    match model.flap_spec {
        Some(s) => cfg.apply_flap_spec(&s.value),
        None => missing.push("FLAP_SPEC".into()),
    }
    for (t, name) in [
        (model.pitch_trim_spec, "TRIM_SPEC (pitch)"),
        (model.roll_trim_spec, "TRIM_SPEC (roll)"),
    ] {
        match t {
            Some(s) => cfg.apply_trim_spec(&s.value),
            None => missing.push(name.into()),
        }
    }
    match model.system_spec {
        Some(s) => cfg.apply_system_spec(&s.value),
        None => missing.push("SYSTEM_SPEC".into()),
    }
    match model.wig_wag_spec {
        Some(s) => cfg.apply_wig_wag_spec(&s.value),
        None => missing.push("WIG_WAG_SPEC".into()),
    }
    for (i, n) in model.names.iter().enumerate() {
        match n {
            Some(n) => cfg.names[i] = n.value.name,
            None => missing.push(format!("DEVICE_NAME {}", pin_short(i as u8))),
        }
    }
    for (i, e) in model.enabled.iter().enumerate() {
        if !crate::protocol::device::enable_flag_allowed(i as u8) {
            continue;
        }
        match e {
            Some(e) => cfg.enabled[i] = e.value,
            None => missing.push(format!("DEVICE_ENABLE {}", pin_short(i as u8))),
        }
    }
    (cfg, missing)
}

fn pin_short(id: u8) -> String {
    crate::protocol::device::device(id).map_or_else(|| id.to_string(), |d| d.system_name.into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Source;
    use crate::protocol::Packet;
    use crate::protocol::message::{
        DeviceName, DeviceSpec, FlapSpec, SpecAck, SpecAckError, SwitchId, TrimSpec,
    };

    fn model() -> Model {
        Model::new(Source::Simulated {
            scenario: "t".into(),
        })
    }

    fn hear(m: &mut Model, at: Instant, msg: impl Into<Message>) {
        m.apply_packet(at, &Packet::from_vpx(1, msg));
    }

    fn spec9() -> DeviceSpec {
        DeviceSpec {
            device_id: 9,
            circuit_breaker: 4,
            switch_id: SwitchId::Input(3),
            current_fault: true,
        }
    }

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    #[test]
    fn saved_only_after_the_ack_and_shows_the_reread() {
        let t0 = Instant::now();
        let mut m = model();
        let mut q = WriteQueue::default();
        q.start(vec![spec9().into()]);
        assert_eq!(q.tick(&m, t0), vec![Message::DeviceSpec(spec9())]);
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::Sending { attempt: 1, of: 3 }
        );
        // An ack for another device, and one from before the send, do not count.
        hear(
            &mut m,
            ms(t0, 50),
            SpecAck {
                device_id: 8,
                error: None,
            },
        );
        assert!(q.tick(&m, ms(t0, 60)).is_empty());
        assert!(matches!(q.lines()[0].status, WriteStatus::Sending { .. }));
        hear(
            &mut m,
            ms(t0, 80),
            SpecAck {
                device_id: 9,
                error: None,
            },
        );
        assert_eq!(
            q.tick(&m, ms(t0, 90)),
            vec![Message::DeviceSpecQuery(DeviceSpecQuery { device_id: 9 })]
        );
        assert_eq!(q.lines()[0].status, WriteStatus::Rereading);
        assert!(q.tick(&m, ms(t0, 100)).is_empty());
        hear(&mut m, ms(t0, 120), spec9());
        q.tick(&m, ms(t0, 130));
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::Saved {
                holds: "4 A, switch 3, current fault on".into(),
                matches: true
            }
        );
        assert!(!q.busy());
        assert!(q.all_saved());
    }

    #[test]
    fn a_stale_ack_is_not_taken_for_this_send() {
        let t0 = Instant::now();
        let mut m = model();
        hear(
            &mut m,
            t0,
            SpecAck {
                device_id: 9,
                error: None,
            },
        );
        let mut q = WriteQueue::default();
        q.start(vec![spec9().into()]);
        q.tick(&m, ms(t0, 10));
        q.tick(&m, ms(t0, 20));
        assert!(matches!(q.lines()[0].status, WriteStatus::Sending { .. }));
    }

    #[test]
    fn silence_retries_three_times_then_says_no_answer_and_stops_the_rest() {
        let t0 = Instant::now();
        let m = model();
        let mut q = WriteQueue::default();
        q.start(vec![
            spec9().into(),
            DeviceName::new(9, "GPS 1").unwrap().into(),
        ]);
        assert_eq!(q.tick(&m, t0).len(), 1);
        assert_eq!(q.next_deadline(), Some(t0 + ANSWER_TIMEOUT));
        assert!(q.tick(&m, ms(t0, 999)).is_empty());
        assert_eq!(q.tick(&m, ms(t0, 1000)), vec![Message::DeviceSpec(spec9())]);
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::Sending { attempt: 2, of: 3 }
        );
        assert_eq!(q.tick(&m, ms(t0, 2000)).len(), 1);
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::Sending { attempt: 3, of: 3 }
        );
        assert!(q.tick(&m, ms(t0, 3000)).is_empty());
        assert_eq!(q.lines()[0].status, WriteStatus::NoAnswer);
        assert_eq!(q.lines()[1].status, WriteStatus::NotSent);
        assert!(!q.busy());
        assert_eq!(q.next_deadline(), None);
    }

    #[test]
    fn a_refusal_is_in_words_and_the_reread_shows_what_the_unit_kept() {
        let t0 = Instant::now();
        let mut m = model();
        let kept = DeviceSpec {
            circuit_breaker: 2,
            ..spec9()
        };
        hear(&mut m, t0, kept);
        let bad = DeviceSpec {
            circuit_breaker: 9,
            ..spec9()
        };
        let mut q = WriteQueue::default();
        q.start(vec![bad.into()]);
        q.tick(&m, ms(t0, 10));
        hear(
            &mut m,
            ms(t0, 40),
            SpecAck {
                device_id: 9,
                error: Some(SpecAckError::InvalidBreaker),
            },
        );
        q.tick(&m, ms(t0, 50));
        hear(&mut m, ms(t0, 70), kept);
        q.tick(&m, ms(t0, 80));
        match &q.lines()[0].status {
            WriteStatus::Refused { why, by_unit: true } => {
                assert!(
                    why.starts_with("Invalid circuit breaker value: 9 A is outside 1–5 A for 5A-6"),
                    "{why}"
                );
                assert!(
                    why.ends_with("the unit holds 2 A, switch 3, current fault on"),
                    "{why}"
                );
            }
            s => panic!("{s:?}"),
        }
    }

    #[test]
    fn trim_and_flap_acks_are_matched_by_their_ids() {
        let t0 = Instant::now();
        let mut m = model();
        let roll = TrimSpec {
            up: 10,
            ..crate::protocol::defaults::trim_spec(TrimType::Roll)
        };
        let flap = FlapSpec {
            down: 200,
            ..crate::protocol::defaults::flap_spec()
        };
        let mut q = WriteQueue::default();
        q.start(vec![roll.into(), flap.into()]);
        q.tick(&m, t0);
        hear(
            &mut m,
            ms(t0, 10),
            SpecAck {
                device_id: TRIM_P,
                error: None,
            },
        );
        q.tick(&m, ms(t0, 20));
        assert!(
            matches!(q.lines()[0].status, WriteStatus::Sending { .. }),
            "pitch's ack is not roll's"
        );
        hear(
            &mut m,
            ms(t0, 30),
            SpecAck {
                device_id: TRIM_R,
                error: None,
            },
        );
        assert_eq!(
            q.tick(&m, ms(t0, 40)),
            vec![Message::DeviceSpecQuery(DeviceSpecQuery {
                device_id: TRIM_R
            })]
        );
        hear(&mut m, ms(t0, 50), roll);
        // The roll write is saved and the flap write goes out in the same tick.
        assert_eq!(q.tick(&m, ms(t0, 60)), vec![Message::FlapSpec(flap)]);
        hear(
            &mut m,
            ms(t0, 70),
            SpecAck {
                device_id: FLAPS,
                error: None,
            },
        );
        q.tick(&m, ms(t0, 80));
        hear(&mut m, ms(t0, 90), flap);
        q.tick(&m, ms(t0, 100));
        assert!(q.all_saved());
    }

    #[test]
    fn device_enable_is_saved_only_when_the_unit_says_so() {
        let t0 = Instant::now();
        let mut m = model();
        let set = DeviceEnable {
            device_id: 7,
            flag: EnableFlag::Disabled,
        };
        let mut q = WriteQueue::default();
        q.start(vec![set.into()]);
        assert_eq!(
            q.tick(&m, t0),
            vec![
                Message::DeviceEnable(set),
                Message::DeviceEnable(DeviceEnable {
                    device_id: 7,
                    flag: EnableFlag::Query
                })
            ]
        );
        hear(
            &mut m,
            ms(t0, 20),
            DeviceEnable {
                device_id: 7,
                flag: EnableFlag::Enabled,
            },
        );
        q.tick(&m, ms(t0, 30));
        assert!(
            matches!(&q.lines()[0].status, WriteStatus::Refused { why, .. } if why == "the unit still says shown")
        );

        let mut q = WriteQueue::default();
        q.start(vec![set.into()]);
        q.tick(&m, ms(t0, 100));
        for s in [1100, 2100, 3100] {
            q.tick(&m, ms(t0, s));
        }
        assert_eq!(q.lines()[0].status, WriteStatus::NoAnswer);
    }

    #[test]
    fn unit_config_says_what_the_model_has_not_heard() {
        let t0 = Instant::now();
        let mut m = model();
        hear(&mut m, t0, spec9());
        let (cfg, missing) = unit_config(&m);
        assert_eq!(cfg.devices[9], spec9());
        assert!(missing.contains(&"FLAP_SPEC".to_string()));
        assert!(missing.contains(&"DEVICE_SPEC 5A-1".to_string()));
        assert!(!missing.contains(&"DEVICE_SPEC 5A-6".to_string()));
    }
}

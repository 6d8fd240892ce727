//! Writes to the unit from the setup screens, one at a time, on the page's own clock.
//!
//! Each write is sent, then waits for its SPEC_ACK in `Model::last_spec_ack` (stamped
//! after the send, with the device id the unit answers that message with), resent on
//! a timeout up to [`TRIES`] times, and then re-read with its query so the screen shows
//! what the unit really holds. DEVICE_ENABLE gets no SPEC_ACK (ICD Table 23): its
//! re-read is its acknowledgement. Nothing here blocks or reads a clock; the app calls
//! [`WriteQueue::tick`] with `now` and sends what comes back.
//!
//! A write that goes unanswered did not leave the setting "unchanged": the unit may
//! have stored it and lost only its answer. So every path ends in one of two places:
//! the unit said what it holds (a re-read answered), or the setting is marked unknown
//! in the model ([`Model::mark_unknown`]) and the app's [`Rereader`] asks for it until
//! the unit answers, when the write's line says what it holds. No path ends in a value
//! nobody confirmed.
//!
//! One write is in flight at a time because SPEC_ACK says only which device it is for:
//! DEVICE_SPEC and DEVICE_NAME of one pin are answered alike, so two in flight could
//! not be told apart. A failed write stops the rest, as a restore does, so the screen
//! can say exactly what was applied.
//!
//! [`Rereader`]: crate::model::Rereader
//! [`TRIES`]: crate::exchange::TRIES

use std::time::Instant;

use super::view::{WriteLine, WriteStatus, switch_text};
use crate::exchange::{Try, Verdict};
use crate::link::request::{setting_name, spec_ack_id};
use crate::model::{Model, Setting};
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{FLAPS, TRIM_P, TRIM_R};
use crate::protocol::message::{EnableFlag, Message, TrimType};
use crate::protocol::validate;

#[derive(Debug, Clone, PartialEq, Eq)]
enum Phase {
    Queued,
    Sending(Try),
    Rereading {
        try_: Try,
        /// `None`: acknowledged; `Some`: the unit's refusal in words.
        refused: Option<String>,
    },
    /// The unit did not answer: the model holds the setting as unknown since `since`
    /// and the app re-reads it; this line waits for that answer.
    Unknown {
        since: Instant,
        acked: bool,
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

    /// Whether a write is still waiting for the unit's SPEC_ACK or re-read. A write
    /// left unknown is not: its re-read goes on in the background while the person
    /// carries on.
    pub fn busy(&self) -> bool {
        self.items
            .iter()
            .any(|i| !matches!(i.phase, Phase::Done(_) | Phase::Unknown { .. }))
    }

    /// Whether every write has ended, a re-read of one left unknown included.
    pub fn settled(&self) -> bool {
        self.items.iter().all(|i| matches!(i.phase, Phase::Done(_)))
    }

    /// Whether the unit holds every write of the batch: acknowledged, or read back
    /// as sent after its answer was lost.
    pub fn all_saved(&self) -> bool {
        !self.items.is_empty()
            && self.items.iter().all(|i| {
                matches!(
                    i.phase,
                    Phase::Done(
                        WriteStatus::Saved { .. } | WriteStatus::ReadBack { matches: true, .. }
                    )
                )
            })
    }

    pub fn lines(&self) -> Vec<WriteLine> {
        self.items
            .iter()
            .map(|i| WriteLine {
                what: setting_name(&i.message),
                status: match &i.phase {
                    Phase::Queued => WriteStatus::Queued,
                    Phase::Sending(t) => WriteStatus::Sending {
                        attempt: t.attempt,
                        of: t.of(),
                    },
                    Phase::Rereading { .. } => WriteStatus::Rereading,
                    Phase::Unknown { acked: false, .. } => WriteStatus::NoAnswer,
                    Phase::Unknown { acked: true, .. } => WriteStatus::AckedUnread,
                    Phase::Done(s) => s.clone(),
                },
            })
            .collect()
    }

    /// When `tick` must run again for a timeout.
    pub fn next_deadline(&self) -> Option<Instant> {
        self.items.iter().find_map(|i| match &i.phase {
            Phase::Sending(t) | Phase::Rereading { try_: t, .. } => Some(t.deadline()),
            _ => None,
        })
    }

    /// Moves the batch on at `now` given what the model has heard; returns the
    /// messages to send now. A write that goes unanswered marks its setting unknown
    /// in `model`.
    pub fn tick(&mut self, model: &mut Model, now: Instant) -> Vec<Message> {
        let mut out = Vec::new();
        // A line left unknown says what the unit holds once a re-read is answered.
        for item in &mut self.items {
            if let Phase::Unknown { since, acked } = item.phase
                && let Some((holds, matches)) = held_after(model, &item.message, since)
            {
                item.phase = Phase::Done(WriteStatus::ReadBack {
                    holds,
                    matches,
                    acked,
                });
            }
        }
        while let Some(idx) = self
            .items
            .iter()
            .position(|i| !matches!(i.phase, Phase::Done(_) | Phase::Unknown { .. }))
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
                            try_: Try::first(now),
                            refused: None,
                        }
                    } else {
                        Phase::Sending(Try::first(now))
                    }
                }
                Phase::Sending(mut t) => {
                    let ack = ack_for(model, &m, t.sent_at);
                    match t.judge(ack.is_some(), now) {
                        Verdict::Answered => {
                            out.push(reread_query(&m));
                            Phase::Rereading {
                                try_: Try::first(now),
                                refused: ack.flatten().map(|e| refusal(e, model, &m)),
                            }
                        }
                        Verdict::Resend => {
                            out.push(m);
                            Phase::Sending(t)
                        }
                        Verdict::NoAnswer => unknown(model, &m, now, false),
                        Verdict::Waiting => Phase::Sending(t),
                    }
                }
                Phase::Rereading { mut try_, refused } => {
                    let held = held_after(model, &m, try_.sent_at);
                    match try_.judge(held.is_some(), now) {
                        Verdict::Answered => {
                            let (holds, matches) = held.unwrap_or_default();
                            Phase::Done(match refused {
                                Some(why) => WriteStatus::Refused {
                                    why: format!("{why}; the unit holds {holds}"),
                                    by_unit: true,
                                },
                                None if is_enable(&m) && !matches => WriteStatus::Refused {
                                    why: format!("the unit still says {holds}"),
                                    by_unit: true,
                                },
                                None => WriteStatus::Saved { holds, matches },
                            })
                        }
                        Verdict::Resend => {
                            if is_enable(&m) {
                                out.push(m);
                            }
                            out.push(reread_query(&m));
                            Phase::Rereading { try_, refused }
                        }
                        // Refused: the unit kept what it held, which the model still
                        // has from before (a refusal changes nothing).
                        Verdict::NoAnswer if refused.is_some() => {
                            Phase::Done(WriteStatus::Refused {
                                why: refused.unwrap_or_default(),
                                by_unit: true,
                            })
                        }
                        // DEVICE_ENABLE is only known set by its answer; an
                        // acknowledged spec is not known held until it is read.
                        Verdict::NoAnswer => unknown(model, &m, now, !is_enable(&m)),
                        Verdict::Waiting => Phase::Rereading { try_, refused },
                    }
                }
                p @ (Phase::Done(_) | Phase::Unknown { .. }) => p,
            };
            let failed = matches!(
                item.phase,
                Phase::Unknown { .. } | Phase::Done(WriteStatus::Refused { .. })
            );
            if failed {
                for later in &mut self.items[idx + 1..] {
                    later.phase = Phase::Done(WriteStatus::NotSent);
                }
            }
            let settled = matches!(
                self.items[idx].phase,
                Phase::Done(_) | Phase::Unknown { .. }
            );
            if !settled || self.items[idx].phase == before {
                break;
            }
        }
        out
    }
}

/// The write went unanswered: nobody knows what the unit holds until it is asked.
fn unknown(model: &mut Model, m: &Message, now: Instant, acked: bool) -> Phase {
    if let Some(setting) = Setting::written_by(m) {
        model.mark_unknown(setting, now);
    }
    Phase::Unknown { since: now, acked }
}

/// The unit's refusal in words: Table 20's words once, then why, with the range of
/// this pin (Appendix B) or of this motor.
fn refusal(e: crate::protocol::message::SpecAckError, model: &Model, m: &Message) -> String {
    let cfg = unit_config(model).0;
    format!("{}: {}", e.description(), validate::explain(e, &cfg, m))
}

fn is_enable(m: &Message) -> bool {
    matches!(m, Message::DeviceEnable(_))
}

/// The SPEC_ACK id the unit answers `m` with. TRIM_SPEC and FLAP_SPEC carry no id;
/// the virtual unit (and, we take it, the real one) answers with the motor's device
/// id. (The model keeps no command number to match by, unlike `link::request`.)
fn ack_id(m: &Message) -> Option<u8> {
    match m {
        Message::TrimSpec(t) if t.trim_type == TrimType::Roll => Some(TRIM_R),
        Message::TrimSpec(_) => Some(TRIM_P),
        Message::FlapSpec(_) => Some(FLAPS),
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
    Setting::written_by(m).map_or(*m, Setting::query)
}

/// What the unit holds for `m`'s setting, heard after `since`, in words, and whether
/// it is what `m` set.
fn held_after(model: &Model, m: &Message, since: Instant) -> Option<(String, bool)> {
    held_where(model, m, |at| at >= since)
}

/// What the unit holds now for `m`'s setting, as far as the model knows, in words
/// (the old value of a write, for the logbook).
pub fn held_now(model: &Model, m: &Message) -> Option<String> {
    held_where(model, m, |_| true).map(|(words, _)| words)
}

fn held_where(
    model: &Model,
    m: &Message,
    fresh: impl Fn(Instant) -> bool,
) -> Option<(String, bool)> {
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
    let pin = |id| super::view::pin_text(id);
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
    use crate::setup::tests::{hear, model, ms};

    use crate::protocol::device::FLAPS;
    use crate::protocol::message::{DeviceEnable, DeviceSpecQuery};
    use crate::protocol::message::{
        DeviceName, DeviceSpec, FlapSpec, SpecAck, SpecAckError, SwitchId, TrimSpec,
    };

    fn spec9() -> DeviceSpec {
        DeviceSpec {
            device_id: 9,
            circuit_breaker: 4,
            switch_id: SwitchId::Input(3),
            current_fault: true,
            switch_raw: None,
        }
    }

    /// Device 9 with a breaker of `amps`.
    fn spec9_at(amps: u8) -> DeviceSpec {
        DeviceSpec {
            circuit_breaker: amps,
            ..spec9()
        }
    }

    /// A unit heard at `t0` holding `held` on device 9, and a write of `written`
    /// started.
    fn writing(t0: Instant, held: DeviceSpec, written: DeviceSpec) -> (Model, WriteQueue) {
        let mut m = model();
        hear(&mut m, t0, held);
        let mut q = WriteQueue::default();
        q.start(vec![written.into()]);
        (m, q)
    }

    #[test]
    fn saved_only_after_the_ack_and_shows_the_reread() {
        let t0 = Instant::now();
        let mut m = model();
        let mut q = WriteQueue::default();
        q.start(vec![spec9().into()]);
        assert_eq!(q.tick(&mut m, t0), vec![Message::DeviceSpec(spec9())]);
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
        assert!(q.tick(&mut m, ms(t0, 60)).is_empty());
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
            q.tick(&mut m, ms(t0, 90)),
            vec![Message::DeviceSpecQuery(DeviceSpecQuery { device_id: 9 })]
        );
        assert_eq!(q.lines()[0].status, WriteStatus::Rereading);
        assert!(q.tick(&mut m, ms(t0, 100)).is_empty());
        hear(&mut m, ms(t0, 120), spec9());
        q.tick(&mut m, ms(t0, 130));
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
        q.tick(&mut m, ms(t0, 10));
        q.tick(&mut m, ms(t0, 20));
        assert!(matches!(q.lines()[0].status, WriteStatus::Sending { .. }));
    }

    #[test]
    fn silence_retries_three_times_then_says_no_answer_and_stops_the_rest() {
        let t0 = Instant::now();
        let mut m = model();
        let mut q = WriteQueue::default();
        q.start(vec![
            spec9().into(),
            DeviceName::new(9, "GPS 1").unwrap().into(),
        ]);
        assert_eq!(q.tick(&mut m, t0).len(), 1);
        assert_eq!(
            q.next_deadline(),
            Some(t0 + crate::exchange::ANSWER_TIMEOUT)
        );
        assert!(q.tick(&mut m, ms(t0, 999)).is_empty());
        assert_eq!(
            q.tick(&mut m, ms(t0, 1000)),
            vec![Message::DeviceSpec(spec9())]
        );
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::Sending { attempt: 2, of: 3 }
        );
        assert_eq!(q.tick(&mut m, ms(t0, 2000)).len(), 1);
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::Sending { attempt: 3, of: 3 }
        );
        assert!(q.tick(&mut m, ms(t0, 3000)).is_empty());
        assert_eq!(q.lines()[0].status, WriteStatus::NoAnswer);
        assert_eq!(q.lines()[1].status, WriteStatus::NotSent);
        assert!(!q.busy());
        assert_eq!(q.next_deadline(), None);
    }

    #[test]
    fn a_refusal_is_in_words_and_the_reread_shows_what_the_unit_kept() {
        let t0 = Instant::now();
        let kept = spec9_at(2);
        let (mut m, mut q) = writing(t0, kept, spec9_at(9));
        q.tick(&mut m, ms(t0, 10));
        hear(
            &mut m,
            ms(t0, 40),
            SpecAck {
                device_id: 9,
                error: Some(SpecAckError::InvalidBreaker),
            },
        );
        q.tick(&mut m, ms(t0, 50));
        hear(&mut m, ms(t0, 70), kept);
        q.tick(&mut m, ms(t0, 80));
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
        q.tick(&mut m, t0);
        hear(
            &mut m,
            ms(t0, 10),
            SpecAck {
                device_id: TRIM_P,
                error: None,
            },
        );
        q.tick(&mut m, ms(t0, 20));
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
            q.tick(&mut m, ms(t0, 40)),
            vec![Message::DeviceSpecQuery(DeviceSpecQuery {
                device_id: TRIM_R
            })]
        );
        hear(&mut m, ms(t0, 50), roll);
        // The roll write is saved and the flap write goes out in the same tick.
        assert_eq!(q.tick(&mut m, ms(t0, 60)), vec![Message::FlapSpec(flap)]);
        hear(
            &mut m,
            ms(t0, 70),
            SpecAck {
                device_id: FLAPS,
                error: None,
            },
        );
        q.tick(&mut m, ms(t0, 80));
        hear(&mut m, ms(t0, 90), flap);
        q.tick(&mut m, ms(t0, 100));
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
            q.tick(&mut m, t0),
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
        q.tick(&mut m, ms(t0, 30));
        assert!(
            matches!(&q.lines()[0].status, WriteStatus::Refused { why, .. } if why == "the unit still says shown")
        );

        let mut q = WriteQueue::default();
        q.start(vec![set.into()]);
        q.tick(&mut m, ms(t0, 100));
        for s in [1100, 2100, 3100] {
            q.tick(&mut m, ms(t0, s));
        }
        assert_eq!(q.lines()[0].status, WriteStatus::NoAnswer);
    }

    #[test]
    fn a_lost_ack_leaves_the_breaker_unknown_until_the_reread_says_what_the_unit_holds() {
        let t0 = Instant::now();
        let new = spec9_at(3);
        let (mut m, mut q) = writing(t0, spec9_at(4), new);
        q.tick(&mut m, t0);
        q.tick(&mut m, ms(t0, 1000));
        q.tick(&mut m, ms(t0, 2000));
        assert!(q.tick(&mut m, ms(t0, 3000)).is_empty());
        // Not "unchanged": the old 4 A is gone from the model, the line says unknown.
        assert_eq!(q.lines()[0].status, WriteStatus::NoAnswer);
        assert!(m.is_unknown(Setting::DeviceSpec(9)));
        assert_eq!(m.device_specs[9], None);
        let row = m
            .circuits(ms(t0, 3000))
            .into_iter()
            .find(|c| c.id == 9)
            .unwrap();
        assert_eq!((row.breaker, row.spec_unknown), (None, true));
        assert!(!q.busy(), "the person can carry on while it is re-read");
        // The unit answers a re-read with what it stored.
        hear(&mut m, ms(t0, 3100), new);
        q.tick(&mut m, ms(t0, 3110));
        assert_eq!(
            q.lines()[0].status,
            WriteStatus::ReadBack {
                holds: "3 A, switch 3, current fault on".into(),
                matches: true,
                acked: false
            }
        );
        assert!(!m.is_unknown(Setting::DeviceSpec(9)));
    }

    #[test]
    fn a_name_and_a_trim_spec_left_unknown_are_marked_so_in_the_model() {
        let t0 = Instant::now();
        let mut m = model();
        hear(&mut m, t0, DeviceName::new(9, "GPS 1").unwrap());
        let mut q = WriteQueue::default();
        q.start(vec![DeviceName::new(9, "GPS 2").unwrap().into()]);
        for s in [0, 1000, 2000, 3000] {
            q.tick(&mut m, ms(t0, s));
        }
        assert!(m.is_unknown(Setting::Name(9)));
        assert_eq!(m.display_name(9), "? (name re-reading…)");
        let roll = TrimSpec {
            up: 10,
            ..crate::protocol::defaults::trim_spec(TrimType::Roll)
        };
        q.start(vec![roll.into()]);
        // Acknowledged, but the re-read goes unanswered three times: still unknown.
        q.tick(&mut m, ms(t0, 4000));
        hear(
            &mut m,
            ms(t0, 4010),
            SpecAck {
                device_id: TRIM_R,
                error: None,
            },
        );
        q.tick(&mut m, ms(t0, 4020));
        for s in [5020, 6020, 7020] {
            q.tick(&mut m, ms(t0, s));
        }
        assert_eq!(q.lines()[0].status, WriteStatus::AckedUnread);
        assert!(m.is_unknown(Setting::Trim(crate::model::TrimKind::Roll)));
        assert_eq!(m.roll_trim_spec, None);
    }

    /// Every way a write can go, on the fake clock: whether the SPEC_ACK comes (and
    /// refuses), whether each re-read is answered. Each ends either with the unit's
    /// own answer on the line, or with the setting unknown in the model and a line
    /// that says so; never with a value nobody confirmed.
    #[test]
    fn every_path_ends_in_what_the_unit_holds_or_unknown_and_rereading() {
        #[derive(Debug, Clone, Copy)]
        enum Ack {
            None,
            Ok,
            Refused,
        }
        for ack in [Ack::None, Ack::Ok, Ack::Refused] {
            for reread_answered in [false, true] {
                for late_answer in [false, true] {
                    let t0 = Instant::now();
                    let mut m = model();
                    let kept = DeviceSpec {
                        circuit_breaker: 2,
                        ..spec9()
                    };
                    hear(&mut m, t0, kept);
                    let sent = DeviceSpec {
                        circuit_breaker: 4,
                        ..spec9()
                    };
                    let mut q = WriteQueue::default();
                    q.start(vec![sent.into()]);
                    let mut t = 0;
                    let mut unit_holds = kept;
                    for _ in 0..40 {
                        t += 250;
                        let now = ms(t0, t);
                        for out in q.tick(&mut m, now) {
                            match (out, ack) {
                                (Message::DeviceSpec(_), Ack::None) => unit_holds = sent,
                                (Message::DeviceSpec(_), Ack::Ok) => {
                                    unit_holds = sent;
                                    hear(
                                        &mut m,
                                        now,
                                        SpecAck {
                                            device_id: 9,
                                            error: None,
                                        },
                                    );
                                }
                                (Message::DeviceSpec(_), Ack::Refused) => hear(
                                    &mut m,
                                    now,
                                    SpecAck {
                                        device_id: 9,
                                        error: Some(SpecAckError::InvalidBreaker),
                                    },
                                ),
                                (Message::DeviceSpecQuery(_), _) if reread_answered => {
                                    hear(&mut m, now, unit_holds)
                                }
                                _ => {}
                            }
                        }
                    }
                    if late_answer {
                        // The app's re-reader is answered at last.
                        hear(&mut m, ms(t0, t + 100), unit_holds);
                        q.tick(&mut m, ms(t0, t + 200));
                    }
                    let case = format!("{ack:?} reread {reread_answered} late {late_answer}");
                    let status = q.lines()[0].status.clone();
                    let holds_words = describe(&unit_holds.into());
                    match &status {
                        WriteStatus::Saved {
                            holds,
                            matches: true,
                        }
                        | WriteStatus::ReadBack {
                            holds,
                            matches: true,
                            ..
                        } => {
                            assert_eq!(holds, &holds_words, "{case}")
                        }
                        WriteStatus::Refused { why, by_unit: true } => {
                            assert!(matches!(ack, Ack::Refused), "{case}");
                            if reread_answered {
                                assert!(why.ends_with(&holds_words), "{case}: {why}")
                            }
                            assert_eq!(m.device_specs[9].unwrap().value, kept, "{case}");
                        }
                        WriteStatus::NoAnswer | WriteStatus::AckedUnread => {
                            assert!(!late_answer, "{case}");
                            assert!(m.is_unknown(Setting::DeviceSpec(9)), "{case}");
                            assert_eq!(m.device_specs[9], None, "{case}: no old value left");
                        }
                        s => panic!("{case}: ended in {s:?}"),
                    }
                    // Whatever the model shows now is what the unit said, or nothing.
                    if let Some(h) = m.device_specs[9] {
                        assert!(
                            h.value == unit_holds || matches!(ack, Ack::Refused),
                            "{case}: model shows {:?}",
                            h.value
                        );
                    }
                    assert!(!q.busy(), "{case}");
                }
            }
        }
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

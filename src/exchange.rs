//! Asking the unit something on the caller's clock, for the page's flows (the setup
//! screens today, an installation check tomorrow): send, wait for the answer, send
//! again on a timeout, give up after a few tries; and for a setting left unknown by
//! an unanswered write, keep asking, paced, until the unit says what it holds.
//!
//! Pure: nothing here reads a clock, blocks or touches the link. A flow keeps a
//! [`Try`] per request and asks it what to do at `now` given whether the model has
//! heard the answer; the app keeps one [`Rereader`] and sends what it returns. The
//! blocking client of the commands (`link::request`) uses the same numbers.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crate::model::{Model, Setting};
use crate::protocol::message::Message;

/// How long to wait for a SPEC_ACK or a query's answer before sending again. The unit
/// answers within a few frames; a second is generous and still quick to give up.
pub const ANSWER_TIMEOUT: Duration = Duration::from_secs(1);
/// Sends of one request before "no answer".
pub const TRIES: u8 = 3;

/// One request in flight: which send this is and when it went out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Try {
    pub attempt: u8,
    pub sent_at: Instant,
    timeout: Duration,
    tries: u8,
}

/// What a request needs now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The answer arrived.
    Answered,
    /// Nothing yet, and it is not time to send again.
    Waiting,
    /// Send the request again now (the try has moved on to the next attempt).
    Resend,
    /// Every try went unanswered.
    NoAnswer,
}

impl Try {
    /// The first send, at `now`, with [`ANSWER_TIMEOUT`] and [`TRIES`].
    pub fn first(now: Instant) -> Try {
        Try::with(now, ANSWER_TIMEOUT, TRIES)
    }

    /// The first send with a timeout and a number of tries of the caller's own.
    pub fn with(now: Instant, timeout: Duration, tries: u8) -> Try {
        Try {
            attempt: 1,
            sent_at: now,
            timeout,
            tries: tries.max(1),
        }
    }

    pub fn of(&self) -> u8 {
        self.tries
    }

    /// When this try times out.
    pub fn deadline(&self) -> Instant {
        self.sent_at + self.timeout
    }

    /// Judges the request at `now`; `answered` says whether the answer to it (heard
    /// at or after [`sent_at`](Self::sent_at) of any try) is in.
    pub fn judge(&mut self, answered: bool, now: Instant) -> Verdict {
        if answered {
            Verdict::Answered
        } else if now < self.deadline() {
            Verdict::Waiting
        } else if self.attempt < self.tries {
            self.attempt += 1;
            self.sent_at = now;
            Verdict::Resend
        } else {
            Verdict::NoAnswer
        }
    }
}

/// The first re-read of an unknown setting goes out at once; while it stays
/// unanswered the gap doubles from this …
pub const REREAD_GAP: Duration = ANSWER_TIMEOUT;
/// … up to this, so a unit that stays silent costs one short query per setting every
/// few seconds: a DEVICE_SPEC_QUERY is 8 bytes, 1.4 ms of a 57600-baud line, which
/// leaves the line free for the broadcasts and a motor's 4 Hz stream.
pub const REREAD_MAX_GAP: Duration = Duration::from_secs(4);
/// At most this many re-reads leave in one tick, so many unknown settings (a restore
/// cut short) go out a few at a time, like the connect-time queries.
pub const REREAD_BATCH: usize = 4;
/// … with this between batches. Without it the settings a full batch left behind
/// were due already, the loop's deadline was in the past, and every batch went out
/// back to back.
pub const REREAD_BATCH_GAP: Duration = Duration::from_millis(60);

#[derive(Debug, Clone, Copy)]
struct Asked {
    at: Instant,
    times: u32,
}

/// Asks again for every setting the model marks unknown until the unit answers.
#[derive(Debug, Default)]
pub struct Rereader {
    asked: BTreeMap<Setting, Asked>,
    /// A full batch went out: nothing more before this.
    held_until: Option<Instant>,
}

impl Rereader {
    fn gap(times: u32) -> Duration {
        REREAD_GAP
            .saturating_mul(1 << times.saturating_sub(1).min(8))
            .min(REREAD_MAX_GAP)
    }

    /// The queries to send at `now`.
    pub fn due(&mut self, model: &Model, now: Instant) -> Vec<Message> {
        self.asked.retain(|s, _| model.unknown.contains_key(s));
        if self.held_until.is_some_and(|t| now < t) {
            return Vec::new();
        }
        self.held_until = None;
        let mut out = Vec::new();
        for &setting in model.unknown.keys() {
            let due = self
                .asked
                .get(&setting)
                .is_none_or(|a| now >= a.at + Rereader::gap(a.times));
            if due && out.len() == REREAD_BATCH {
                self.held_until = Some(now + REREAD_BATCH_GAP);
                break;
            }
            if due {
                let a = self
                    .asked
                    .entry(setting)
                    .or_insert(Asked { at: now, times: 0 });
                a.at = now;
                a.times += 1;
                out.push(setting.query());
            }
        }
        out
    }

    /// When [`due`](Self::due) next has something to send. After `due(.., now)` this
    /// is later than `now` (a setting marked unknown since then is due at once).
    pub fn next_deadline(&self, model: &Model) -> Option<Instant> {
        model
            .unknown
            .keys()
            .map(|s| {
                let at = self
                    .asked
                    .get(s)
                    .map_or_else(Instant::now, |a| a.at + Rereader::gap(a.times));
                self.held_until.map_or(at, |h| at.max(h))
            })
            .min()
    }

    /// The port came back: ask everything unknown at once instead of waiting out
    /// the gaps built up while nothing answered.
    pub fn reconnected(&mut self) {
        self.asked.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Source;
    use crate::protocol::Packet;
    use crate::protocol::message::{DeviceSpec, DeviceSpecQuery, SwitchId};

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    #[test]
    fn a_try_waits_resends_twice_then_gives_up() {
        let t0 = Instant::now();
        let mut t = Try::first(t0);
        assert_eq!(t.judge(false, ms(t0, 999)), Verdict::Waiting);
        assert_eq!(t.judge(false, ms(t0, 1000)), Verdict::Resend);
        assert_eq!((t.attempt, t.sent_at), (2, ms(t0, 1000)));
        assert_eq!(t.judge(false, ms(t0, 2000)), Verdict::Resend);
        assert_eq!(t.judge(false, ms(t0, 2999)), Verdict::Waiting);
        assert_eq!(t.judge(false, ms(t0, 3000)), Verdict::NoAnswer);
        let mut t = Try::first(t0);
        assert_eq!(t.judge(true, ms(t0, 5000)), Verdict::Answered);
    }

    #[test]
    fn an_unknown_setting_is_asked_at_once_then_paced_until_answered() {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        let mut r = Rereader::default();
        assert!(r.due(&m, t0).is_empty());
        assert_eq!(r.next_deadline(&m), None);
        m.mark_unknown(Setting::DeviceSpec(9), t0);
        let q: Message = DeviceSpecQuery { device_id: 9 }.into();
        assert_eq!(r.due(&m, t0), vec![q]);
        assert!(r.due(&m, ms(t0, 999)).is_empty());
        assert_eq!(r.next_deadline(&m), Some(ms(t0, 1000)));
        // Gaps of 1, 2, 4, 4 s while nothing answers.
        assert_eq!(r.due(&m, ms(t0, 1000)), vec![q]);
        assert!(r.due(&m, ms(t0, 2999)).is_empty());
        assert_eq!(r.due(&m, ms(t0, 3000)), vec![q]);
        assert!(r.due(&m, ms(t0, 6999)).is_empty());
        assert_eq!(r.due(&m, ms(t0, 7000)), vec![q]);
        assert_eq!(r.due(&m, ms(t0, 11000)), vec![q]);
        // A reconnect asks at once.
        r.reconnected();
        assert_eq!(r.due(&m, ms(t0, 11100)), vec![q]);
        // The answer makes it known: no more queries.
        let held = DeviceSpec {
            device_id: 9,
            circuit_breaker: 3,
            switch_id: SwitchId::Input(2),
            current_fault: false,
            switch_raw: None,
        };
        m.apply_packet(ms(t0, 11200), &Packet::from_vpx(1, held));
        assert!(!m.is_unknown(Setting::DeviceSpec(9)));
        assert_eq!(m.device_specs[9].unwrap().value, held);
        assert!(r.due(&m, ms(t0, 20000)).is_empty());
        assert_eq!(r.next_deadline(&m), None);
    }
}

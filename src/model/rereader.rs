//! For a setting left unknown by an unanswered write, or not heard since the port
//! opened, keep asking, paced, until the unit says what it holds.
//!
//! Pure: nothing here reads a clock, blocks or touches the link. The app keeps one
//! [`Rereader`] and sends what it returns.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use super::{Model, Setting};
use crate::exchange::ANSWER_TIMEOUT;
use crate::protocol::message::Message;

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

/// The connect-time queries go out in about a second (`app::queries`) and the unit
/// answers each within a few frames. A setting still not heard this long after the
/// port opened was lost on the line (a unit silent at connect, noise) and is asked
/// again, rather than left to the minute's refresh while screens have nothing to show.
pub const CONNECT_GRACE: Duration = Duration::from_secs(3);

#[derive(Debug, Clone, Copy)]
struct Asked {
    at: Instant,
    times: u32,
}

/// Asks again, paced, until the unit answers: for every setting the model marks
/// unknown (a write to it went unanswered), and from [`CONNECT_GRACE`] after a
/// connect for every setting not heard since it (the connect-time query was lost).
#[derive(Debug, Default)]
pub struct Rereader {
    asked: BTreeMap<Setting, Asked>,
    /// A full batch went out: nothing more before this.
    held_until: Option<Instant>,
    /// When the port last opened; `None` while it is down.
    connected_at: Option<Instant>,
    /// Whether the unit's broadcasts were live at the last `due`.
    live: bool,
    /// Every setting has been heard since the connect, so the look for those the
    /// connect-time queries did not bring is over until the next connect: a setting
    /// once heard stays heard (one a write leaves unknown is in `model.unknown`).
    /// Without this the page's loop went through every setting twice a tick, half
    /// of an idle tick's work.
    all_heard: bool,
}

impl Rereader {
    fn gap(times: u32) -> Duration {
        REREAD_GAP
            .saturating_mul(1 << times.saturating_sub(1).min(8))
            .min(REREAD_MAX_GAP)
    }

    /// The settings to keep asking for, each with the earliest moment its first
    /// re-read may go (`None`: at once).
    fn wanted(&self, model: &Model) -> Vec<(Setting, Option<Instant>)> {
        let mut out: Vec<(Setting, Option<Instant>)> =
            model.unknown.keys().map(|&s| (s, None)).collect();
        if let Some(since) = self.connected_at
            && !self.all_heard
        {
            let from = since + CONNECT_GRACE;
            out.extend(
                Setting::all()
                    .filter(|s| !model.unknown.contains_key(s))
                    .filter(|&s| model.setting_heard(s).is_none_or(|at| at < since))
                    .map(|s| (s, Some(from))),
            );
        }
        out
    }

    /// When `setting`'s next query may go; `None`: at once.
    fn due_at(&self, setting: Setting, from: Option<Instant>) -> Option<Instant> {
        match self.asked.get(&setting) {
            Some(a) => Some(a.at + Rereader::gap(a.times)),
            None => from,
        }
    }

    /// The queries to send at `now`: at most [`REREAD_BATCH`], those waiting longest
    /// first, so settings never asked are not held back behind repeats.
    pub fn due(&mut self, model: &Model, now: Instant) -> Vec<Message> {
        let wanted = self.wanted(model);
        self.all_heard =
            self.connected_at.is_some() && wanted.iter().all(|(_, from)| from.is_none());
        self.asked.retain(|s, _| wanted.iter().any(|(w, _)| w == s));
        // The unit talks again after a silence: ask now rather than wait out the
        // gaps that grew while nothing could answer.
        let live = !model.comm_lost(now);
        if live && !self.live {
            self.asked.clear();
            self.held_until = None;
        }
        self.live = live;
        if self.held_until.is_some_and(|t| now < t) {
            return Vec::new();
        }
        self.held_until = None;
        let mut due: Vec<(Option<Instant>, Setting)> = wanted
            .into_iter()
            .map(|(s, from)| (self.due_at(s, from), s))
            .filter(|(at, _)| at.is_none_or(|t| now >= t))
            .collect();
        // Stable: equal times keep the settings' order.
        due.sort_by_key(|(at, _)| *at);
        if due.len() > REREAD_BATCH {
            self.held_until = Some(now + REREAD_BATCH_GAP);
            due.truncate(REREAD_BATCH);
        }
        let mut out = Vec::new();
        for (_, setting) in due {
            let a = self
                .asked
                .entry(setting)
                .or_insert(Asked { at: now, times: 0 });
            a.at = now;
            a.times += 1;
            out.push(setting.query());
        }
        out
    }

    /// When [`due`](Self::due) next has something to send, on the caller's clock:
    /// `now` for a setting due at once. After `due(.., now)` this is later than `now`
    /// (a setting marked unknown since then is due at once).
    pub fn next_deadline(&self, model: &Model, now: Instant) -> Option<Instant> {
        self.wanted(model)
            .into_iter()
            .map(|(s, from)| {
                let at = self.due_at(s, from).unwrap_or(now);
                self.held_until.map_or(at, |h| at.max(h))
            })
            .min()
    }

    /// The port opened (or came back) at `now`: ask everything unknown at once
    /// instead of waiting out the gaps built up while nothing answered, and from
    /// [`CONNECT_GRACE`] on, everything the connect-time queries did not bring.
    pub fn connected(&mut self, now: Instant) {
        self.asked.clear();
        self.held_until = None;
        self.connected_at = Some(now);
        self.all_heard = false;
    }

    /// The port is down: nothing can be heard, so nothing new is counted unheard.
    pub fn link_down(&mut self) {
        self.connected_at = None;
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

    /// The unit's answer to `s`'s query, as a factory-fresh unit gives it.
    fn answer(s: Setting) -> Message {
        crate::model::factory_answer(s)
    }

    /// The unit answers every setting's query but `except`'s.
    fn hear_all_but(m: &mut Model, at: Instant, except: Setting) {
        for s in Setting::all().filter(|&s| s != except) {
            m.apply_packet(at, &Packet::from_vpx(1, answer(s)));
        }
    }

    fn model() -> Model {
        Model::new(Source::Simulated {
            scenario: "t".into(),
        })
    }

    /// A unit silent at connect: nothing the connect-time queries asked for is heard,
    /// so from CONNECT_GRACE on every setting is asked again, a batch at a time, and
    /// then paced; what the unit answers is no longer asked; the rest goes on.
    #[test]
    fn settings_unheard_since_connect_are_asked_again_after_the_grace() {
        let t0 = Instant::now();
        let mut m = model();
        let mut r = Rereader::default();
        assert!(r.due(&m, t0).is_empty(), "not connected: nothing to ask");
        assert_eq!(r.next_deadline(&m, t0), None);
        r.connected(t0);
        // The connect queries have their chance first.
        assert!(r.due(&m, ms(t0, 2999)).is_empty());
        assert_eq!(r.next_deadline(&m, ms(t0, 2999)), Some(t0 + CONNECT_GRACE));
        let total = Setting::all().count();
        let spec9: Message = DeviceSpecQuery { device_id: 9 }.into();
        let mut distinct = std::collections::BTreeSet::new();
        let mut spec9_at = Vec::new();
        let mut t = 3000;
        while distinct.len() < total {
            let batch = r.due(&m, ms(t0, t));
            assert!(batch.len() <= REREAD_BATCH, "{batch:?}");
            if batch.contains(&spec9) {
                spec9_at.push(t);
            }
            distinct.extend(batch.iter().map(|q| format!("{q:?}")));
            let next = r.next_deadline(&m, ms(t0, t)).unwrap();
            assert!(next > ms(t0, t), "the next deadline is ahead");
            t = (next - t0).as_millis() as u64;
            assert!(t < 5000, "the whole set goes out in under two seconds");
        }
        assert_eq!(spec9_at[0], 3120, "the third batch of four, 60 ms apart");
        assert!(
            spec9_at.windows(2).all(|w| w[1] - w[0] >= 1000),
            "paced: {spec9_at:?}"
        );
        // ICD Table 18: the flaps are read with DEVICE_SPEC_QUERY 0.
        let flaps: Message = DeviceSpecQuery { device_id: 0 }.into();
        assert!(distinct.contains(&format!("{flaps:?}")));
        // The unit talks: all but device 9's spec answered.
        hear_all_but(&mut m, ms(t0, 4500), Setting::DeviceSpec(9));
        assert_eq!(r.due(&m, ms(t0, 6_500)), vec![spec9]);
        let q = r.due(&m, ms(t0, 8_000));
        assert!(q.is_empty(), "paced while silent: {q:?} {spec9_at:?}");
        // Its broadcasts come back: what it has not answered is asked at once.
        let status = crate::protocol::message::DeviceStatus {
            on: [false; crate::protocol::device::DEVICE_COUNT],
            current: [crate::protocol::message::Tenths(0); crate::protocol::device::DEVICE_COUNT],
        };
        m.apply_packet(ms(t0, 8_100), &Packet::from_vpx(1, status));
        let later = r.due(&m, ms(t0, 8_100));
        assert_eq!(later, vec![spec9], "only what is still unheard, at once");
        m.apply_packet(
            ms(t0, 8_200),
            &Packet::from_vpx(1, answer(Setting::DeviceSpec(9))),
        );
        assert!(r.due(&m, ms(t0, 20_000)).is_empty());
        assert_eq!(r.next_deadline(&m, ms(t0, 20_000)), None, "all heard: idle");
        // A reconnect: what was heard before it is asked again if the new
        // connection's queries do not bring it; the port going down stops that.
        r.connected(ms(t0, 30_000));
        assert!(r.due(&m, ms(t0, 32_000)).is_empty());
        assert_eq!(r.due(&m, ms(t0, 33_000)).len(), REREAD_BATCH);
        r.link_down();
        assert!(r.due(&m, ms(t0, 40_000)).is_empty());
        assert_eq!(r.next_deadline(&m, ms(t0, 40_000)), None);
    }

    #[test]
    fn an_unknown_setting_is_asked_at_once_then_paced_until_answered() {
        let t0 = Instant::now();
        let mut m = model();
        let mut r = Rereader::default();
        assert!(r.due(&m, t0).is_empty());
        assert_eq!(r.next_deadline(&m, t0), None);
        m.mark_unknown(Setting::DeviceSpec(9), t0);
        // Due at once, on the caller's clock (a fake one here, an hour ahead of the
        // real one), not the real clock's now.
        let fake = ms(t0, 3_600_000);
        assert_eq!(r.next_deadline(&m, fake), Some(fake));
        let q: Message = DeviceSpecQuery { device_id: 9 }.into();
        assert_eq!(r.due(&m, t0), vec![q]);
        assert!(r.due(&m, ms(t0, 999)).is_empty());
        assert_eq!(r.next_deadline(&m, ms(t0, 999)), Some(ms(t0, 1000)));
        // Gaps of 1, 2, 4, 4 s while nothing answers.
        assert_eq!(r.due(&m, ms(t0, 1000)), vec![q]);
        assert!(r.due(&m, ms(t0, 2999)).is_empty());
        assert_eq!(r.due(&m, ms(t0, 3000)), vec![q]);
        assert!(r.due(&m, ms(t0, 6999)).is_empty());
        assert_eq!(r.due(&m, ms(t0, 7000)), vec![q]);
        assert_eq!(r.due(&m, ms(t0, 11000)), vec![q]);
        // A reconnect asks at once.
        r.connected(ms(t0, 11100));
        hear_all_but(&mut m, ms(t0, 11100), Setting::DeviceSpec(9));
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
        assert_eq!(r.next_deadline(&m, ms(t0, 20000)), None);
    }
}

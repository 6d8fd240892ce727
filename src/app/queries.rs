//! What the page asks the unit for at connect, and the pacing of those requests.
//!
//! **How fast the unit can be asked.** ICD v2.1 gives no request rate and says
//! nothing of how the VP-X queues requests; the real unit's buffers are not
//! published. What the ICD does fix is the line (§3.2.1: 57600 baud, 8N1, so 5760
//! bytes a second each way) and the size of every frame (8 + payload + 1, icd-reading
//! R1). The connect set below is 91 requests, 936 bytes towards the unit
//! (163 ms of line), and its answers are 1608 bytes back (279 ms): 31 DEVICE_NAMEs
//! of 26 bytes, 28 DEVICE_SPECs of 13, 25 DEVICE_ENABLEs of 11, FLAP_SPEC 20, two
//! TRIM_SPECs 16, SYSTEM_SPEC 11, WIG_WAG_SPEC 13, VERSION 12, DEVICE_STATUS 75.
//! The same line also carries the unit's broadcasts, about 400 bytes a second
//! (FLAP_TRIM_STATUS 27 bytes at 10 Hz; SYSTEM_STATUS 21, DEVICE_STATUS 75 and
//! FAULT_STATUS 44 at 1 Hz). So the unit's transmit side is the bottleneck: every
//! answer is larger than its question, and a page that asks faster than the answers
//! can leave only makes requests pile up inside the unit — in a receive buffer of
//! unknown size on a small microcontroller, where an overflow loses requests
//! silently.
//!
//! **Decision.** Rather than a fixed rate (which is either slow or, on a busier
//! line, too fast), requests are clocked by the answers: at most [`IN_FLIGHT`]
//! requests are unanswered at any time, and the next goes out as soon as an answer
//! comes back. Four requests are at most 44 bytes (four DEVICE_ENABLEs), so the unit
//! never holds more than that of ours waiting, whatever its speed, while its
//! transmit line is kept busy: the set is answered about as fast as the line can
//! carry the answers (~0.3 s plus the broadcasts). A request whose answer does not
//! come within [`ANSWER_WAIT`] (noise on the line, a unit that ignores it) gives up
//! its place; the setting it asked for is asked again later by the re-reads
//! (`model::Rereader`) or the minute's refresh. A unit older than software 2.0,
//! which has no DEVICE_NAME_QUERY or DEVICE_ENABLE to answer, so costs 0.2 s per
//! four of those 56 requests: under 3 s for the set, and never a burst.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::model::{Model, Setting, TrimKind};
use crate::protocol::device::{DEVICE_COUNT, FLAPS, TRIM_P, TRIM_R, enable_flag_allowed};
use crate::protocol::message::{DeviceStatusQuery, Message, Packet, Version};

/// Requests sent and not yet answered, at most.
pub const IN_FLIGHT: usize = 4;
/// How long a request holds its place waiting for its answer. Four answers, the
/// broadcasts queued before them and the requests on their way take under 60 ms of
/// line; three times that is a lost answer, not a slow one.
pub const ANSWER_WAIT: Duration = Duration::from_millis(200);
/// Specs and names are asked again this often, so a change made elsewhere (another
/// EFIS, a restore) shows up without a reconnect.
pub const REFRESH_EVERY: Duration = Duration::from_secs(60);

/// One connect-time request, by what answers it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Ask {
    /// VERSION (ICD Table 11), answered with VERSION.
    Version,
    /// DEVICE_STATUS_QUERY (icd-reading R6), answered with DEVICE_STATUS.
    Status,
    /// A setting's query (ICD Tables 18, 22, 23), answered with the setting's message.
    Setting(Setting),
}

impl Ask {
    fn message(self) -> Message {
        match self {
            Ask::Version => Version::REQUEST.into(),
            Ask::Status => DeviceStatusQuery.into(),
            Ask::Setting(s) => s.query(),
        }
    }

    /// When the model last heard what answers this request.
    fn heard(self, model: &Model) -> Option<Instant> {
        match self {
            Ask::Version => model.version.as_ref().map(|v| v.at),
            // A broadcast heard after the query says as much as the answer would.
            Ask::Status => model.device_status.as_ref().map(|s| s.at),
            Ask::Setting(s) => model.setting_heard(s),
        }
    }
}

/// The setting DEVICE_SPEC_QUERY `id` reads (icd-reading R13).
fn spec_setting(id: u8) -> Setting {
    match id {
        FLAPS => Setting::Flaps,
        TRIM_R => Setting::Trim(TrimKind::Roll),
        TRIM_P => Setting::Trim(TrimKind::Pitch),
        id => Setting::DeviceSpec(id),
    }
}

/// Everything the page needs to show the unit, in the order asked: VERSION, a
/// DEVICE_STATUS_QUERY so the list fills before the next 1 Hz broadcast,
/// SYSTEM_SPEC, the enable flag of every device 4–28, every spec (device 0 →
/// FLAP_SPEC, 29/30 → TRIM_SPEC), every DEVICE_NAME, then WIG_WAG_SPEC.
fn connect_asks() -> Vec<Ask> {
    let ids = || 0..DEVICE_COUNT as u8;
    let mut q = vec![Ask::Version, Ask::Status, Ask::Setting(Setting::System)];
    q.extend(
        ids()
            .filter(|&id| enable_flag_allowed(id))
            .map(|id| Ask::Setting(Setting::Enable(id))),
    );
    q.extend(ids().map(|id| Ask::Setting(spec_setting(id))));
    q.extend(ids().map(|id| Ask::Setting(Setting::Name(id))));
    q.push(Ask::Setting(Setting::WigWag));
    q
}

/// The connect-time requests let out as answers come back, with their own command
/// numbers; again every [`REFRESH_EVERY`].
#[derive(Debug, Default)]
pub struct QueryPacer {
    queue: VecDeque<Ask>,
    /// Sent and not yet answered, with when each was sent.
    in_flight: Vec<(Ask, Instant)>,
    /// When the round started: the first requests are due then.
    round: Option<Instant>,
    next_refresh: Option<Instant>,
}

impl QueryPacer {
    /// Starts (or restarts, after a reconnect) the connect sequence.
    pub fn start(&mut self, now: Instant) {
        self.queue = connect_asks().into();
        self.in_flight.clear();
        self.round = Some(now);
        self.next_refresh = Some(now + REFRESH_EVERY);
    }

    pub fn stop(&mut self) {
        self.queue.clear();
        self.in_flight.clear();
        self.round = None;
        self.next_refresh = None;
    }

    /// Requests not sent yet.
    pub fn pending(&self) -> usize {
        self.queue.len()
    }

    /// Requests sent and not yet answered (as of the last [`QueryPacer::due`]).
    pub fn in_flight(&self) -> usize {
        self.in_flight.len()
    }

    /// When the main loop must next call [`QueryPacer::due`] if no answer comes
    /// first (an answer wakes the loop anyway: it is data from the link).
    pub fn next_deadline(&self) -> Option<Instant> {
        if self.queue.is_empty() {
            return self.next_refresh;
        }
        if self.in_flight.len() < IN_FLIGHT {
            return self.round;
        }
        self.in_flight
            .iter()
            .map(|&(_, sent)| sent + ANSWER_WAIT)
            .min()
    }

    /// The requests due at `now`, given what `model` has heard; `next_cnt` supplies
    /// command numbers.
    pub fn due(
        &mut self,
        now: Instant,
        model: &Model,
        mut next_cnt: impl FnMut() -> u8,
    ) -> Vec<Packet> {
        if self.queue.is_empty() && self.next_refresh.is_some_and(|t| now >= t) {
            self.start(now);
        }
        if self.queue.is_empty() || self.round.is_none_or(|t| now < t) {
            return Vec::new();
        }
        // Answered (heard since it was sent), or waited for long enough.
        self.in_flight.retain(|&(ask, sent)| {
            now < sent + ANSWER_WAIT && ask.heard(model).is_none_or(|at| at < sent)
        });
        let n = IN_FLIGHT
            .saturating_sub(self.in_flight.len())
            .min(self.queue.len());
        let out = self
            .queue
            .drain(..n)
            .map(|ask| {
                self.in_flight.push((ask, now));
                Packet::request(next_cnt(), ask.message())
            })
            .collect();
        if self.queue.is_empty() {
            // Nothing left to let out: the last answers need no watching.
            self.in_flight.clear();
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Source;
    use crate::protocol::message::{DeviceEnable, EnableFlag};
    use crate::protocol::{Decoder, Event};
    use crate::sim::line_rate::{BYTES_PER_SECOND, LinePacer};
    use crate::sim::{self, SimOptions};

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    fn model() -> Model {
        Model::new(Source::Simulated {
            scenario: "t".into(),
        })
    }

    /// A pacer started at `t0` on a unit that has said nothing, and its command numbers.
    fn started(t0: Instant) -> (Model, QueryPacer, impl FnMut() -> u8) {
        let mut p = QueryPacer::default();
        p.start(t0);
        (model(), p, counter())
    }

    fn counter() -> impl FnMut() -> u8 {
        let mut cnt = 0u8;
        move || {
            cnt = cnt.wrapping_add(1);
            cnt
        }
    }

    /// The unit's answer to a DEVICE_ENABLE query for `id` (ICD Table 23).
    fn enable_answer(id: u8) -> Packet {
        Packet::request(
            0,
            DeviceEnable {
                device_id: id,
                flag: EnableFlag::Enabled,
            },
        )
    }

    #[test]
    fn connect_asks_for_everything_the_page_shows() {
        let q: Vec<Message> = connect_asks().into_iter().map(Ask::message).collect();
        let count = |name: &str| q.iter().filter(|m| m.name() == name).count();
        assert_eq!(q.len(), 91);
        assert_eq!(count("VERSION"), 1);
        assert_eq!(count("DEVICE_STATUS_QUERY"), 1);
        assert_eq!(count("DEVICE_ENABLE"), 25, "devices 4–28");
        assert_eq!(count("DEVICE_NAME_QUERY"), 31);
        assert_eq!(count("DEVICE_SPEC_QUERY"), 33, "0–30, 253 and 254");
        assert!(q.iter().all(|m| !matches!(
            m,
            Message::DeviceEnable(DeviceEnable {
                device_id: 1..=3,
                ..
            })
        )));
        // Every setting the page shows is asked for.
        let asked: Vec<Setting> = connect_asks()
            .into_iter()
            .filter_map(|a| match a {
                Ask::Setting(s) => Some(s),
                _ => None,
            })
            .collect();
        assert!(Setting::all().all(|s| asked.contains(&s)));
    }

    #[test]
    fn four_go_out_at_once_and_an_answer_lets_the_next_one_out() {
        let t0 = Instant::now();
        let (mut m, mut p, mut cnt) = started(t0);
        assert_eq!(
            p.next_deadline(),
            Some(t0),
            "the first requests are due at once"
        );
        let first: Vec<&str> = p
            .due(t0, &m, &mut cnt)
            .iter()
            .map(|q| q.message.name())
            .collect();
        assert_eq!(
            first,
            [
                "VERSION",
                "DEVICE_STATUS_QUERY",
                "DEVICE_SPEC_QUERY",
                "DEVICE_ENABLE"
            ]
        );
        assert_eq!(p.in_flight(), IN_FLIGHT);
        assert!(
            p.due(t0 + ms(5), &m, &mut cnt).is_empty(),
            "four unanswered: wait"
        );
        assert_eq!(p.next_deadline(), Some(t0 + ANSWER_WAIT));
        // The unit answers DEVICE_ENABLE 4: one place is free, one request goes.
        m.apply_packet(t0 + ms(7), &enable_answer(4));
        let next = p.due(t0 + ms(7), &m, &mut cnt);
        assert_eq!(next.len(), 1);
        assert_eq!(
            next[0].message,
            Message::DeviceEnable(DeviceEnable {
                device_id: 5,
                flag: EnableFlag::Query
            })
        );
        assert_eq!(p.in_flight(), IN_FLIGHT);
    }

    #[test]
    fn an_unanswered_request_gives_its_place_up_after_the_wait() {
        let t0 = Instant::now();
        let (m, mut p, mut cnt) = started(t0);
        assert_eq!(p.due(t0, &m, &mut cnt).len(), IN_FLIGHT);
        assert!(p.due(t0 + ANSWER_WAIT - ms(1), &m, &mut cnt).is_empty());
        assert_eq!(p.due(t0 + ANSWER_WAIT, &m, &mut cnt).len(), IN_FLIGHT);
        // A unit that answers nothing is asked no faster than four per wait.
        let mut t = t0 + ANSWER_WAIT;
        let mut sent = 2 * IN_FLIGHT;
        while p.pending() > 0 {
            let next = p.next_deadline().unwrap();
            assert_eq!(next, t + ANSWER_WAIT);
            t = next;
            sent += p.due(t, &m, &mut cnt).len();
        }
        assert_eq!(sent, 91);
    }

    #[test]
    fn an_answer_heard_before_the_request_does_not_free_its_place() {
        let t0 = Instant::now();
        let (mut m, mut p, mut cnt) = started(t0);
        // Answered in an earlier round (a minute ago).
        m.apply_packet(t0, &enable_answer(4));
        let t1 = t0 + ms(1);
        p.start(t1);
        assert_eq!(p.due(t1, &m, &mut cnt).len(), IN_FLIGHT);
        assert!(p.due(t1 + ms(10), &m, &mut cnt).is_empty());
    }

    #[test]
    fn the_round_restarts_on_refresh_and_stops_with_the_link() {
        let t0 = Instant::now();
        let m = model();
        let mut p = QueryPacer::default();
        let mut cnt = counter();
        assert_eq!(
            p.next_deadline(),
            None,
            "nothing to ask before a connection"
        );
        assert!(p.due(t0, &m, &mut cnt).is_empty());
        p.start(t0);
        let mut t = t0;
        while p.pending() > 0 {
            p.due(t, &m, &mut cnt);
            t = p.next_deadline().unwrap();
        }
        assert_eq!(p.next_deadline(), Some(t0 + REFRESH_EVERY));
        assert!(p.due(t0 + REFRESH_EVERY - ms(1), &m, &mut cnt).is_empty());
        assert_eq!(p.due(t0 + REFRESH_EVERY, &m, &mut cnt).len(), IN_FLIGHT);
        p.stop();
        assert_eq!(p.next_deadline(), None);
        assert!(p.due(t0 + REFRESH_EVERY * 2, &m, &mut cnt).is_empty());
    }

    /// The pacer against the virtual VP-X's unit (`install` scenario, broadcasting)
    /// behind a line of 5760 bytes a second each way, all on a fake clock: the whole
    /// set is answered in about the time the line needs to carry the answers, and the
    /// unit never has more than four of our requests unanswered.
    #[test]
    fn against_a_unit_at_line_rate_the_set_is_answered_in_the_lines_time() {
        let t0 = Instant::now();
        let opts = SimOptions::new(sim::load_scenario("install").unwrap());
        let mut unit = sim::build_unit(&opts, t0);
        let (mut up, mut down) = (
            LinePacer::new(BYTES_PER_SECOND),
            LinePacer::new(BYTES_PER_SECOND),
        );
        let mut m = model();
        let mut p = QueryPacer::default();
        let mut cnt = counter();
        let mut decoder = Decoder::new();
        // Bytes on their way, by when they have crossed: to the unit, to the page.
        let mut to_unit: Vec<(Instant, Vec<u8>)> = Vec::new();
        let mut to_page: Vec<(Instant, Vec<u8>)> = Vec::new();
        let mut unanswered: Vec<u8> = Vec::new();
        let mut most_unanswered = 0;
        p.start(t0);
        let mut now = t0;
        let done = loop {
            // The unit's own clock first (broadcasts), then what reached it.
            unit.tick(now);
            let (arrived, later): (Vec<_>, Vec<_>) =
                to_unit.drain(..).partition(|(at, _)| *at <= now);
            to_unit = later;
            for (at, bytes) in arrived {
                unit.feed(&bytes, at);
            }
            let out = unit.take_output();
            if !out.is_empty() {
                let end = down.schedule(now, out.len()).last().unwrap().1;
                to_page.push((end, out));
            }
            let (arrived, later): (Vec<_>, Vec<_>) =
                to_page.drain(..).partition(|(at, _)| *at <= now);
            to_page = later;
            for (at, bytes) in arrived {
                let mut packets = Vec::new();
                decoder.push(&bytes, |e| {
                    if let Event::Frame(f) = e {
                        packets.push(Packet::parse(&f).unwrap());
                    }
                });
                for pk in packets {
                    // Broadcasts carry the unit's own count; DEVICE_STATUS also answers.
                    let broadcast = matches!(
                        pk.message,
                        Message::SystemStatus(_)
                            | Message::FlapTrimStatus(_)
                            | Message::FaultStatus(_)
                    );
                    if !broadcast {
                        unanswered.retain(|&c| c != pk.cnt);
                    }
                    m.apply_packet(at, &pk);
                }
            }
            if m.live_devices(now).is_some() && Setting::all().all(|s| m.setting_heard(s).is_some())
            {
                break now;
            }
            for q in p.due(now, &m, &mut cnt) {
                let bytes = q.to_bytes();
                let end = up.schedule(now, bytes.len()).last().unwrap().1;
                unanswered.push(q.cnt);
                to_unit.push((end, bytes));
            }
            most_unanswered = most_unanswered.max(unanswered.len());
            let next = [
                p.next_deadline(),
                Some(unit.next_deadline()),
                to_unit.iter().map(|(at, _)| *at).min(),
                to_page.iter().map(|(at, _)| *at).min(),
            ]
            .into_iter()
            .flatten()
            .min()
            .unwrap();
            now = next.max(now + Duration::from_micros(1));
            assert!(now < t0 + Duration::from_secs(3), "not answered in 3 s");
        };
        let took = done - t0;
        assert!(most_unanswered <= IN_FLIGHT, "{most_unanswered} unanswered");
        // 1608 bytes of answers alone take 279 ms of line, broadcasts come between.
        assert!(
            took >= ms(279) && took < ms(400),
            "the set took {took:?} on the line"
        );
    }
}

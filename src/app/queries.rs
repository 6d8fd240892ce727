//! What the page asks the unit for at connect, and the pacing of those requests.
//!
//! ICD v2.1 gives no request-rate limit. A burst of ~90 requests would be 1.5 kB in a
//! few milliseconds into a unit that is also broadcasting; we send a few at a time
//! instead, so the whole set goes out in about a second and the unit's receive buffer
//! never has more than a handful to work through.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::protocol::device::{DEVICE_COUNT, SYSTEM_SPEC_ID, WIG_WAG_SPEC_ID, enable_flag_allowed};
use crate::protocol::message::{
    DeviceEnable, DeviceNameQuery, DeviceSpecQuery, DeviceStatusQuery, EnableFlag, Message, Packet,
    Version,
};

/// Requests sent per batch, and the gap between batches.
pub const BATCH: usize = 6;
pub const BATCH_GAP: Duration = Duration::from_millis(60);
/// Specs and names are asked again this often, so a change made elsewhere (another
/// EFIS, a restore) shows up without a reconnect.
pub const REFRESH_EVERY: Duration = Duration::from_secs(60);

/// Everything the page needs to show the unit: VERSION, the enable flag of every
/// device 4–28, every DEVICE_NAME, every spec (device 0 → FLAP_SPEC, 29/30 →
/// TRIM_SPEC, 253 → SYSTEM_SPEC, 254 → WIG_WAG_SPEC), then a DEVICE_STATUS_QUERY so
/// the list fills before the next 1 Hz broadcast.
pub fn connect_queries() -> Vec<Message> {
    let mut q: Vec<Message> = vec![Version::REQUEST.into(), DeviceStatusQuery.into()];
    q.push(
        DeviceSpecQuery {
            device_id: SYSTEM_SPEC_ID,
        }
        .into(),
    );
    for id in 0..DEVICE_COUNT as u8 {
        if enable_flag_allowed(id) {
            q.push(
                DeviceEnable {
                    device_id: id,
                    flag: EnableFlag::Query,
                }
                .into(),
            );
        }
    }
    for id in 0..DEVICE_COUNT as u8 {
        q.push(DeviceSpecQuery { device_id: id }.into());
    }
    for id in 0..DEVICE_COUNT as u8 {
        q.push(DeviceNameQuery { device_id: id }.into());
    }
    q.push(
        DeviceSpecQuery {
            device_id: WIG_WAG_SPEC_ID,
        }
        .into(),
    );
    q
}

/// A queue of requests let out a batch at a time, with their own command numbers.
#[derive(Debug, Default)]
pub struct QueryPacer {
    queue: VecDeque<Message>,
    next_batch: Option<Instant>,
    next_refresh: Option<Instant>,
}

impl QueryPacer {
    /// Starts (or restarts, after a reconnect) the connect sequence.
    pub fn start(&mut self, now: Instant) {
        self.queue = connect_queries().into();
        self.next_batch = Some(now);
        self.next_refresh = Some(now + REFRESH_EVERY);
    }

    pub fn stop(&mut self) {
        self.queue.clear();
        self.next_batch = None;
        self.next_refresh = None;
    }

    pub fn pending(&self) -> usize {
        self.queue.len()
    }

    /// When the main loop must next call [`QueryPacer::due`].
    pub fn next_deadline(&self) -> Option<Instant> {
        if self.queue.is_empty() {
            self.next_refresh
        } else {
            self.next_batch
        }
    }

    /// The requests due at `now`; `next_cnt` supplies command numbers.
    pub fn due(&mut self, now: Instant, mut next_cnt: impl FnMut() -> u8) -> Vec<Packet> {
        if self.queue.is_empty() && self.next_refresh.is_some_and(|t| now >= t) {
            self.start(now);
        }
        match self.next_batch {
            Some(t) if now >= t && !self.queue.is_empty() => {
                let n = BATCH.min(self.queue.len());
                self.next_batch = Some(now + BATCH_GAP);
                self.queue
                    .drain(..n)
                    .map(|m| Packet::request(next_cnt(), m))
                    .collect()
            }
            _ => Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn connect_asks_for_everything_the_page_shows() {
        let q = connect_queries();
        let count = |name: &str| q.iter().filter(|m| m.name() == name).count();
        assert_eq!(count("VERSION"), 1);
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
    }

    #[test]
    fn requests_go_out_in_small_batches_and_restart_on_refresh() {
        let t0 = Instant::now();
        let mut p = QueryPacer::default();
        p.start(t0);
        let total = p.pending();
        let mut cnt = 0u8;
        let mut next = || {
            cnt = cnt.wrapping_add(1);
            cnt
        };
        assert_eq!(p.due(t0, &mut next).len(), BATCH);
        assert!(
            p.due(t0 + Duration::from_millis(10), &mut next).is_empty(),
            "no second batch before the gap"
        );
        let mut sent = BATCH;
        let mut t = t0;
        while p.pending() > 0 {
            t += BATCH_GAP;
            sent += p.due(t, &mut next).len();
        }
        assert_eq!(sent, total);
        assert!(
            t - t0 < Duration::from_millis(1500),
            "the whole set goes out in about a second"
        );
        assert_eq!(p.next_deadline(), Some(t0 + REFRESH_EVERY));
        assert!(!p.due(t0 + REFRESH_EVERY, &mut next).is_empty());
    }
}

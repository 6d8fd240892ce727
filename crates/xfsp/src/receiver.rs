//! §4.4 reception: each source's messages are processed in order and only once.
//!
//! Message numbers are compared in 16-bit serial-number arithmetic (RFC 1982,
//! reading note 7): `n` is newer than `last` when `(n - last) mod 65536` is in
//! 1..=32767. Equal is a duplicate; anything else is late (out of order) and is
//! discarded, as §2 requires ("if received out of order, a message MUST be ignored").
//!
//! To tell a late duplicate from a late first arrival (both are discarded, but they
//! mean different things on the network: a looping switch versus reordering), each
//! source keeps a 64-message bitmap of numbers already seen, as IPsec anti-replay does.
//!
//! Memory is bounded: at most `max_sources` sources are tracked, and a new source
//! beyond that evicts the one heard from least recently. An evicted source that comes
//! back is treated as new, so its next message is accepted.
//!
//! A node that restarts with a lower message number is ignored until its numbers pass
//! the last one seen (up to 32767 messages) or it is forgotten; the gateway, which has
//! a clock, can call [`Receiver::forget`] for sources silent for a while.

use std::collections::HashMap;

use super::error::Error;
use super::header::Header;
use super::message::MessageView;

/// Sources tracked by default: far more nodes than any aircraft network has, small
/// enough that a flood of forged source ids costs a few kilobytes.
pub const DEFAULT_MAX_SOURCES: usize = 256;

/// Whether `n` comes after `last` in 16-bit serial-number arithmetic (RFC 1982, reading
/// note 7).
pub fn serial_newer(n: u16, last: u16) -> bool {
    (1..=32767).contains(&n.wrapping_sub(last))
}

/// What to do with a message number from a known or unknown source (§2, §4.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Process it.
    Fresh,
    /// Already seen: drop.
    Duplicate,
    /// Older than one already processed: drop.
    OutOfOrder,
}

/// The result of offering a datagram to the receiver (§4.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Received<'a> {
    /// Newer than every message processed from its source (§2, §4.4, reading note 7):
    /// process it.
    Fresh(MessageView<'a>),
    /// A message number already processed from this source (§2: "MUST ignore all duplicate
    /// messages").
    Duplicate(Header),
    /// Older than one already processed from this source (§2: out of order "MUST be
    /// ignored").
    OutOfOrder(Header),
    /// Not a well-formed XFSp datagram.
    Malformed(Error),
}

/// Running totals, for the gateway's status line and logs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RxStats {
    /// Datagrams taken as [`Received::Fresh`].
    pub fresh: u64,
    /// Datagrams dropped as [`Received::Duplicate`].
    pub duplicate: u64,
    /// Datagrams dropped as [`Received::OutOfOrder`].
    pub out_of_order: u64,
    /// Datagrams dropped as [`Received::Malformed`].
    pub malformed: u64,
    /// Sources dropped from the table to make room for new ones.
    pub evicted: u64,
}

#[derive(Debug, Clone, Copy)]
struct Source {
    last: u16,
    /// Bit `k` set: message `last - k` has been seen (bit 0 is `last` itself).
    seen: u64,
    /// When this source last had a fresh message, in receiver ticks.
    touched: u64,
}

/// Per-source ordering and duplicate suppression (§2, §4.4).
#[derive(Debug, Clone)]
pub struct Receiver {
    sources: HashMap<u16, Source>,
    max_sources: usize,
    tick: u64,
    stats: RxStats,
}

impl Default for Receiver {
    fn default() -> Self {
        Receiver::new(DEFAULT_MAX_SOURCES)
    }
}

impl Receiver {
    /// Tracks at most `max_sources` sources (at least one).
    pub fn new(max_sources: usize) -> Receiver {
        let max_sources = max_sources.max(1);
        Receiver {
            sources: HashMap::with_capacity(max_sources.min(1024)),
            max_sources,
            tick: 0,
            stats: RxStats::default(),
        }
    }

    /// Frames the datagram, then applies the ordering rules to its source and number.
    /// Only a well-formed datagram affects the source table.
    pub fn receive<'a>(&mut self, datagram: &'a [u8]) -> Received<'a> {
        match MessageView::parse(datagram) {
            Err(e) => {
                self.stats.malformed += 1;
                Received::Malformed(e)
            }
            Ok(view) => {
                let h = *view.header();
                match self.check(h.src_id, h.msg_num) {
                    Verdict::Fresh => Received::Fresh(view),
                    Verdict::Duplicate => Received::Duplicate(h),
                    Verdict::OutOfOrder => Received::OutOfOrder(h),
                }
            }
        }
    }

    /// Applies the ordering rules to a message number, recording it, and counts it.
    pub fn check(&mut self, src: u16, num: u16) -> Verdict {
        self.tick += 1;
        let tick = self.tick;
        let verdict = match self.sources.get_mut(&src) {
            None => {
                self.make_room();
                self.sources.insert(
                    src,
                    Source {
                        last: num,
                        seen: 1,
                        touched: tick,
                    },
                );
                Verdict::Fresh
            }
            Some(s) => {
                let ahead = num.wrapping_sub(s.last);
                if serial_newer(num, s.last) {
                    s.seen = s.seen.checked_shl(u32::from(ahead)).unwrap_or(0) | 1;
                    s.last = num;
                    s.touched = tick;
                    Verdict::Fresh
                } else {
                    let behind = s.last.wrapping_sub(num);
                    let bit = 1u64.checked_shl(u32::from(behind)).unwrap_or(0);
                    if s.seen & bit != 0 {
                        Verdict::Duplicate
                    } else {
                        s.seen |= bit;
                        Verdict::OutOfOrder
                    }
                }
            }
        };
        match verdict {
            Verdict::Fresh => self.stats.fresh += 1,
            Verdict::Duplicate => self.stats.duplicate += 1,
            Verdict::OutOfOrder => self.stats.out_of_order += 1,
        }
        verdict
    }

    fn make_room(&mut self) {
        while self.sources.len() >= self.max_sources {
            let Some(oldest) = self
                .sources
                .iter()
                .min_by_key(|(_, s)| s.touched)
                .map(|(&id, _)| id)
            else {
                return;
            };
            self.sources.remove(&oldest);
            self.stats.evicted += 1;
        }
    }

    /// Forgets a source, so its next message is accepted whatever its number (for a
    /// node that has restarted).
    pub fn forget(&mut self, src: u16) {
        self.sources.remove(&src);
    }

    /// The last message number processed from `src`, if it is tracked.
    pub fn last_number(&self, src: u16) -> Option<u16> {
        self.sources.get(&src).map(|s| s.last)
    }

    /// Sources currently tracked.
    pub fn tracked_sources(&self) -> usize {
        self.sources.len()
    }

    /// The totals so far.
    pub fn stats(&self) -> RxStats {
        self.stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dict::CertLevel;
    use crate::format::Value;
    use crate::idents;
    use crate::message::Message;
    use crate::param::Parameter;
    use proptest::prelude::*;

    #[test]
    fn serial_arithmetic_wraps() {
        assert!(serial_newer(1, 0));
        assert!(serial_newer(0, 65535), "0 follows 65535");
        assert!(serial_newer(5, 65530));
        assert!(serial_newer(32767, 0));
        assert!(!serial_newer(32768, 0), "exactly half way is not newer");
        assert!(!serial_newer(0, 32768));
        assert!(!serial_newer(65535, 0), "65535 is just before 0");
        assert!(!serial_newer(7, 7));
    }

    #[test]
    fn in_order_fresh_duplicates_and_late_ones() {
        let mut r = Receiver::default();
        assert_eq!(r.check(1, 65534), Verdict::Fresh);
        assert_eq!(r.check(1, 65535), Verdict::Fresh);
        assert_eq!(
            r.check(1, 2),
            Verdict::Fresh,
            "skipping 0 and 1 across the wrap"
        );
        assert_eq!(r.check(1, 2), Verdict::Duplicate);
        assert_eq!(
            r.check(1, 65535),
            Verdict::Duplicate,
            "seen before the wrap"
        );
        assert_eq!(r.check(1, 0), Verdict::OutOfOrder, "skipped, now late");
        assert_eq!(r.check(1, 0), Verdict::Duplicate, "the late one again");
        assert_eq!(r.check(2, 0), Verdict::Fresh, "sources are independent");
        assert_eq!(r.check(1, 3), Verdict::Fresh);
        assert_eq!(
            r.stats(),
            RxStats {
                fresh: 5,
                duplicate: 3,
                out_of_order: 1,
                malformed: 0,
                evicted: 0
            }
        );
        assert_eq!(r.last_number(1), Some(3));
    }

    #[test]
    fn a_jump_beyond_the_window_clears_it() {
        let mut r = Receiver::default();
        r.check(9, 100);
        assert_eq!(r.check(9, 1000), Verdict::Fresh);
        assert_eq!(r.check(9, 100), Verdict::OutOfOrder, "out of the 64 window");
        assert_eq!(r.check(9, 30_000), Verdict::Fresh);
        assert_eq!(
            r.check(9, 62_768),
            Verdict::OutOfOrder,
            "32768 ahead is not newer"
        );
    }

    #[test]
    fn datagrams_are_counted_by_kind() {
        let m = Message::flight_data(
            7,
            40,
            CertLevel::LevelD,
            vec![Parameter::new(idents::IAS, Value::Sint(1200))],
        );
        let b = m.emit().unwrap();
        let mut r = Receiver::default();
        assert!(matches!(r.receive(&b), Received::Fresh(v) if v.header().src_id == 7));
        assert!(matches!(r.receive(&b), Received::Duplicate(h) if h.msg_num == 40));
        assert_eq!(
            r.receive(&b[..7]),
            Received::Malformed(Error::ShortHeader { len: 7 })
        );
        let mut older = m.clone();
        older.msg_num = 39;
        assert!(matches!(
            r.receive(&older.emit().unwrap()),
            Received::OutOfOrder(_)
        ));
        let s = r.stats();
        assert_eq!(
            (s.fresh, s.duplicate, s.malformed, s.out_of_order),
            (1, 1, 1, 1)
        );
    }

    #[test]
    fn a_flood_of_sources_stays_bounded_and_evicts_the_oldest() {
        let mut r = Receiver::new(4);
        for src in 0..4 {
            r.check(src, 0);
        }
        r.check(0, 1); // source 0 is now the most recent, 1 the oldest
        for src in 100..1100 {
            r.check(src, 0);
            assert!(r.tracked_sources() <= 4);
        }
        assert_eq!(r.stats().evicted, 1000);
        assert_eq!(r.last_number(1099), Some(0));
        let mut r = Receiver::new(4);
        for src in 0..4 {
            r.check(src, 0);
        }
        r.check(0, 1);
        r.check(50, 0);
        assert_eq!(r.last_number(1), None, "oldest went first");
        assert_eq!(r.last_number(0), Some(1), "recently heard from stays");
        assert_eq!(
            r.check(1, 0),
            Verdict::Fresh,
            "an evicted source starts over"
        );
    }

    #[test]
    fn forget_lets_a_restarted_node_back_in() {
        let mut r = Receiver::default();
        r.check(3, 5000);
        assert_eq!(r.check(3, 0), Verdict::OutOfOrder);
        r.forget(3);
        assert_eq!(r.check(3, 0), Verdict::Fresh);
    }

    proptest! {
        /// Against a model that remembers every number: whatever the order, a number
        /// is fresh only if newer than the last fresh one, and never fresh twice.
        #[test]
        fn never_accepts_twice_or_backwards(
            start in any::<u16>(),
            steps in proptest::collection::vec(-70i32..200, 1..200),
        ) {
            let mut r = Receiver::default();
            let mut last: Option<u16> = None;
            let mut fresh = std::collections::HashSet::new();
            let mut n = start;
            for step in steps {
                n = n.wrapping_add(step as u16);
                let v = r.check(1, n);
                let expect_fresh = last.is_none_or(|l| serial_newer(n, l));
                prop_assert_eq!(v == Verdict::Fresh, expect_fresh);
                if v == Verdict::Fresh {
                    prop_assert!(fresh.insert(n) || step > 0, "fresh twice: {}", n);
                    last = Some(n);
                }
            }
        }
    }
}

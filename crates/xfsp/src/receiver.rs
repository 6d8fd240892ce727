//! §4.4 reception: each source's messages are processed in order and only once.
//!
//! Message numbers are compared in 16-bit serial-number arithmetic (RFC 1982,
//! icd-reading X7): `n` is newer than `last` when `(n - last) mod 65536` is in
//! 1..=32767. Equal is a duplicate; anything else is late (out of order) and is
//! discarded, as §2 requires ("if received out of order, a message MUST be ignored").
//!
//! To tell a late duplicate from a late first arrival (both are discarded, but they
//! mean different things on the network: a looping switch versus reordering), each
//! source keeps a 64-message bitmap of numbers already seen, as IPsec anti-replay does.
//!
//! A source silent for [`FORGET_AFTER`] (10 s) is forgotten: its next message is
//! taken whatever its number. A node that restarts numbers "with an arbitrary initial
//! value" (§4.1), and would otherwise be ignored until its numbers passed the old
//! ones (up to 32767 messages); a source silent that long is gone from the network
//! anyway (draft §4.4's lifetimes, our 10 s rule). An old message replayed after 10 s
//! of silence is taken once.
//!
//! Decision, memory: the table is bounded by time, never by a count.
//! A count (we had 256) is passed by a busy network or a flood of forged source ids,
//! and evicting a source that is still talking makes its next duplicate or late
//! message look fresh: an old IAS taken as new. So a source is dropped only once it
//! has been silent for [`FORGET_AFTER`] (swept at most once a second, by the
//! caller's clock). The bound in memory is the id space itself: source ids are 16
//! bits, so a flood that forges every one of them within 10 s holds at most 65,536
//! entries of a few dozen bytes (about 4.5 MB with the map's spare room, checked in
//! the tests), and 10 s after
//! it stops the table is swept back to the real nodes. Refusing new sources
//! when full was the other choice; it would let such a flood lock out a real node
//! that restarts.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use super::error::Error;
use super::header::Header;
use super::message::MessageView;

/// A source silent this long is forgotten (see the module's notes).
pub const FORGET_AFTER: Duration = Duration::from_secs(10);
/// Silent sources are swept from the table at most this often.
pub const SWEEP_EVERY: Duration = Duration::from_secs(1);

/// Whether `n` comes after `last` in 16-bit serial-number arithmetic (RFC 1982, icd-reading
/// X7).
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
    /// Newer than every message processed from its source (§2, §4.4, icd-reading X7):
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
    /// Sources forgotten after [`FORGET_AFTER`] of silence.
    pub forgotten: u64,
}

#[derive(Debug, Clone, Copy)]
struct Source {
    last: u16,
    /// Bit `k` set: message `last - k` has been seen (bit 0 is `last` itself).
    seen: u64,
    /// When this source was last heard (any well-formed message).
    heard: Instant,
}

/// Per-source ordering and duplicate suppression (§2, §4.4).
#[derive(Debug, Clone)]
pub struct Receiver {
    sources: HashMap<u16, Source>,
    forget_after: Duration,
    next_sweep: Option<Instant>,
    stats: RxStats,
}

impl Default for Receiver {
    fn default() -> Self {
        Receiver::new(FORGET_AFTER)
    }
}

impl Receiver {
    /// Forgets a source after `forget_after` of silence.
    pub fn new(forget_after: Duration) -> Receiver {
        Receiver {
            sources: HashMap::new(),
            forget_after,
            next_sweep: None,
            stats: RxStats::default(),
        }
    }

    /// Frames the datagram, then applies the ordering rules to its source and number.
    /// Only a well-formed datagram affects the source table.
    pub fn receive<'a>(&mut self, datagram: &'a [u8], now: Instant) -> Received<'a> {
        match MessageView::parse(datagram) {
            Err(e) => {
                self.stats.malformed += 1;
                Received::Malformed(e)
            }
            Ok(view) => {
                let h = *view.header();
                match self.check(h.src_id, h.msg_num, now) {
                    Verdict::Fresh => Received::Fresh(view),
                    Verdict::Duplicate => Received::Duplicate(h),
                    Verdict::OutOfOrder => Received::OutOfOrder(h),
                }
            }
        }
    }

    /// Applies the ordering rules to a message number heard at `now`, recording it,
    /// and counts it.
    pub fn check(&mut self, src: u16, num: u16, now: Instant) -> Verdict {
        self.sweep(now);
        let forget_after = self.forget_after;
        if self
            .sources
            .get(&src)
            .is_some_and(|s| now.saturating_duration_since(s.heard) > forget_after)
        {
            self.sources.remove(&src);
            self.stats.forgotten += 1;
        }
        let verdict = match self.sources.get_mut(&src) {
            None => {
                self.sources.insert(
                    src,
                    Source {
                        last: num,
                        seen: 1,
                        heard: now,
                    },
                );
                Verdict::Fresh
            }
            Some(s) => {
                s.heard = now;
                let ahead = num.wrapping_sub(s.last);
                if serial_newer(num, s.last) {
                    s.seen = s.seen.checked_shl(u32::from(ahead)).unwrap_or(0) | 1;
                    s.last = num;
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

    /// Drops the sources silent past `forget_after`, at most once per
    /// [`SWEEP_EVERY`]: the table holds only the sources of the last seconds.
    fn sweep(&mut self, now: Instant) {
        if self.next_sweep.is_some_and(|t| now < t) {
            return;
        }
        self.next_sweep = Some(now + SWEEP_EVERY);
        let before = self.sources.len();
        let forget_after = self.forget_after;
        self.sources
            .retain(|_, s| now.saturating_duration_since(s.heard) <= forget_after);
        self.stats.forgotten += (before - self.sources.len()) as u64;
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

    /// One instant for the tests that are not about time.
    static T0: std::sync::LazyLock<Instant> = std::sync::LazyLock::new(Instant::now);

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

    /// Checks `(source, number)` in turn, each against the verdict it must get and why.
    #[track_caller]
    fn verdicts(r: &mut Receiver, steps: &[(u16, u16, Verdict, &str)]) {
        for &(src, num, want, why) in steps {
            assert_eq!(
                r.check(src, num, *T0),
                want,
                "source {src} number {num}: {why}"
            );
        }
    }

    #[test]
    fn in_order_fresh_duplicates_and_late_ones() {
        let mut r = Receiver::default();
        verdicts(
            &mut r,
            &[
                (1, 65534, Verdict::Fresh, "the first"),
                (1, 65535, Verdict::Fresh, "the next"),
                (1, 2, Verdict::Fresh, "skipping 0 and 1 across the wrap"),
                (1, 2, Verdict::Duplicate, "the same again"),
                (1, 65535, Verdict::Duplicate, "seen before the wrap"),
                (1, 0, Verdict::OutOfOrder, "skipped, now late"),
                (1, 0, Verdict::Duplicate, "the late one again"),
                (2, 0, Verdict::Fresh, "sources are independent"),
                (1, 3, Verdict::Fresh, "on from the newest"),
            ],
        );
        assert_eq!(
            r.stats(),
            RxStats {
                fresh: 5,
                duplicate: 3,
                out_of_order: 1,
                malformed: 0,
                forgotten: 0
            }
        );
        assert_eq!(r.last_number(1), Some(3));
    }

    #[test]
    fn a_jump_beyond_the_window_clears_it() {
        let mut r = Receiver::default();
        verdicts(
            &mut r,
            &[
                (9, 100, Verdict::Fresh, "the first"),
                (9, 1000, Verdict::Fresh, "a jump ahead"),
                (9, 100, Verdict::OutOfOrder, "out of the 64 window"),
                (9, 30_000, Verdict::Fresh, "another jump ahead"),
                (9, 62_768, Verdict::OutOfOrder, "32768 ahead is not newer"),
            ],
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
        assert!(matches!(r.receive(&b, *T0), Received::Fresh(v) if v.header().src_id == 7));
        assert!(matches!(r.receive(&b, *T0), Received::Duplicate(h) if h.msg_num == 40));
        assert_eq!(
            r.receive(&b[..7], *T0),
            Received::Malformed(Error::ShortHeader { len: 7 })
        );
        let mut older = m.clone();
        older.msg_num = 39;
        assert!(matches!(
            r.receive(&older.emit().unwrap(), *T0),
            Received::OutOfOrder(_)
        ));
        let s = r.stats();
        assert_eq!(
            (s.fresh, s.duplicate, s.malformed, s.out_of_order),
            (1, 1, 1, 1)
        );
    }

    /// 300 sources (more than the 256 the table once held) all talking
    /// within 10 s: none is forgotten, so a duplicate from the first is still a
    /// duplicate. After 10 s of silence a source is forgotten and its next message
    /// taken; a second later the table holds only the sources still talking.
    #[test]
    fn sources_are_forgotten_by_silence_never_by_count() {
        let t0 = *T0;
        let mut r = Receiver::default();
        for src in 0..300u16 {
            assert_eq!(r.check(src, 100, t0), Verdict::Fresh);
        }
        let t1 = t0 + Duration::from_secs(9);
        for src in 0..300u16 {
            assert_eq!(
                r.check(src, 100, t1),
                Verdict::Duplicate,
                "source {src} was forgotten while it talked"
            );
        }
        assert_eq!(r.tracked_sources(), 300);
        assert_eq!(r.stats().forgotten, 0);
        // Only source 7 talks on; the rest fall silent.
        assert_eq!(r.check(7, 101, t1 + Duration::from_secs(5)), Verdict::Fresh);
        let t2 = t1 + Duration::from_millis(10_500);
        assert_eq!(r.check(7, 101, t2), Verdict::Duplicate, "7 is remembered");
        assert_eq!(r.tracked_sources(), 1, "the silent ones are swept");
        assert_eq!(r.stats().forgotten, 299);
        assert_eq!(
            r.check(8, 100, t2),
            Verdict::Fresh,
            "silent 10 s: forgotten, its next message taken"
        );
    }

    /// Every one of the 65,536 source ids forged within a second: the table holds
    /// them all (the id space is its bound) and nothing panics; 10 s after the flood
    /// stops it is back to the one real source.
    #[test]
    fn a_flood_of_every_source_id_is_bounded_by_the_id_space_and_swept() {
        let t0 = *T0;
        let mut r = Receiver::default();
        for src in 0..=u16::MAX {
            r.check(src, 1, t0 + Duration::from_micros(u64::from(src) * 10));
        }
        assert_eq!(r.tracked_sources(), 65_536);
        let size = r.sources.capacity() * (std::mem::size_of::<(u16, Source)>() + 1);
        assert!(size < 5 << 20, "{size} bytes");
        let later = t0 + Duration::from_secs(12);
        assert_eq!(r.check(0x1234, 2, later), Verdict::Fresh);
        assert_eq!(r.tracked_sources(), 1);
    }

    #[test]
    fn forget_lets_a_restarted_node_back_in() {
        let mut r = Receiver::default();
        r.check(3, 5000, *T0);
        assert_eq!(r.check(3, 0, *T0), Verdict::OutOfOrder);
        r.forget(3);
        assert_eq!(r.check(3, 0, *T0), Verdict::Fresh);
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
                let v = r.check(1, n, *T0);
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

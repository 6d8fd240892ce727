//! The traffic log: what crossed the wire, both ways, kept where the UI can draw it.
//!
//! A bounded ring of the last [`TRAFFIC_LEN`] frames and decoder drops, in the order
//! the link reported them, plus per-message counters that keep counting while the
//! view is paused or the ring has long forgotten a frame. Pure data: it is fed by the
//! app's link sink (`note_rx`, `note_tx`) and read by `ui::traffic`, and, like the
//! rest of the model, judges freshness only against a `now` it is given.
//!
//! The traffic view's own state (pause, filters, search, cursor) lives here too,
//! because pausing is a position in this ring and the UI renders from the model.

use std::collections::{BTreeMap, VecDeque};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

use crate::link::RxItem;
use crate::protocol::Crossing;
use crate::protocol::Packet;
use crate::protocol::describe::{describe, node_label};
use crate::protocol::message::{
    DeviceStatus, ExternalData, FaultStatus, FlapTrimStatus, Payload, SystemStatus,
};
use crate::staleness::{COMM_LOST_AFTER, FAULT_STATUS_QUIET_AFTER, FLAP_TRIM_STALE_AFTER};

/// How many entries the ring keeps (about three minutes of normal traffic).
pub const TRAFFIC_LEN: usize = 2000;
/// Rates are averaged over this window, so a broadcast that slows shows within seconds.
pub const RATE_WINDOW: Duration = Duration::from_secs(5);
/// A broadcast arriving at less than this share of its ICD rate is "slow".
pub const SLOW_SHARE: f64 = 0.8;

/// What one entry is.
#[derive(Debug, Clone, PartialEq)]
pub enum What {
    Packet(Packet),
    /// An intact frame of a known message whose payload does not decode.
    Malformed(String),
    /// Bytes that were not part of any frame.
    Dropped,
    BadChecksum,
    BadLength,
    UnknownMessage,
    /// Bytes we wrote that are not a packet (e.g. a bootloader frame).
    RawTx,
}

/// One frame or one decoder drop.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Position in the whole session (not the ring): stable while the ring rolls.
    pub seq: u64,
    pub at: Instant,
    pub dir: Crossing,
    pub what: What,
    pub raw: Vec<u8>,
    /// The lower-cased search text, built the first time a search looks at this entry:
    /// a search runs over every visible entry at every redraw, and building
    /// describe() and the hex each time cost tens of milliseconds under the lock.
    search_text: SearchCache,
}

/// A cache is not part of what an entry is: two entries are equal whether or not a
/// search has looked at them yet.
#[derive(Debug, Clone, Default)]
struct SearchCache(std::cell::OnceCell<String>);

impl PartialEq for SearchCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// "positions flap 20, pitch 128, roll 120 · " before a FLAP_TRIM_STATUS's fields.
fn positions_first(m: &crate::protocol::message::Message) -> String {
    match m {
        crate::protocol::message::Message::FlapTrimStatus(f) => format!(
            "positions flap {}, pitch {}, roll {} · ",
            f.flap_position, f.pitch_trim_position, f.roll_trim_position
        ),
        _ => String::new(),
    }
}

impl Entry {
    /// The message name, or what the decoder made of the bytes, in capitals.
    pub fn name(&self) -> &'static str {
        match &self.what {
            What::Packet(p) => p.message.name(),
            What::Malformed(_) => "UNDECODABLE",
            What::Dropped => "DROPPED BYTES",
            What::BadChecksum => "BAD CHECKSUM",
            What::BadLength => "BAD LENGTH",
            What::UnknownMessage => "UNKNOWN MESSAGE",
            What::RawTx => "RAW BYTES",
        }
    }

    pub fn is_error(&self) -> bool {
        !matches!(self.what, What::Packet(_) | What::RawTx)
    }

    /// The decoded fields (via `protocol::describe`), or why the bytes were dropped.
    /// FLAP_TRIM_STATUS's three positions come first: its whole text is longer than
    /// the fields column of a 200-column terminal, which would hide pitch and roll.
    pub fn text(&self) -> String {
        match &self.what {
            What::Packet(p) => format!(
                "cnt {} {}→{}: {}{}",
                p.cnt,
                node_label(p.src),
                node_label(p.dst),
                positions_first(&p.message),
                describe(&p.message)
            ),
            What::Malformed(e) => e.clone(),
            What::Dropped => format!("{} byte(s) outside any frame", self.raw.len()),
            What::BadChecksum => "checksum does not match; resyncing one byte on".into(),
            What::BadLength => "length impossible for this message; resyncing".into(),
            What::UnknownMessage => "intact frame of a message the ICD does not define".into(),
            What::RawTx => format!("{} byte(s) written", self.raw.len()),
        }
    }

    /// Everything a search looks at: name, fields and hex.
    pub fn haystack(&self) -> String {
        format!("{} {} {}", self.name(), self.text(), hex(&self.raw))
    }

    /// [`Entry::haystack`] lower-cased, built once.
    fn search_text(&self) -> &str {
        self.search_text
            .0
            .get_or_init(|| self.haystack().to_lowercase())
    }
}

/// Bytes as spaced upper-case hex.
pub fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 3);
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{b:02X}");
    }
    s
}

/// Counters for one message type in one direction.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TypeStat {
    pub count: u64,
    pub last: Instant,
    /// Arrival times within the rate window (pruned as new ones come).
    recent: VecDeque<Instant>,
}

impl TypeStat {
    /// Messages per second over the last [`RATE_WINDOW`] before `now`, from the gaps
    /// between arrivals (so a steady 1 Hz reads 1.0 whatever its phase); `None` until a
    /// whole window of the session has passed, so a start-up is not called slow.
    pub fn rate_hz(&self, now: Instant, origin: Instant) -> Option<f64> {
        let inside: Vec<Instant> = self
            .recent
            .iter()
            .copied()
            .filter(|&t| t <= now && now.saturating_duration_since(t) < RATE_WINDOW)
            .collect();
        let span = match (inside.first(), inside.last()) {
            (Some(a), Some(b)) => b.saturating_duration_since(*a).as_secs_f64(),
            _ => 0.0,
        };
        if inside.len() >= 2 && span > 0.0 {
            Some((inside.len() - 1) as f64 / span)
        } else if now.saturating_duration_since(origin) >= RATE_WINDOW {
            Some(inside.len() as f64 / RATE_WINDOW.as_secs_f64())
        } else {
            None
        }
    }
}

/// The rate the ICD gives a message, and how to judge it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Expected {
    pub dir: Crossing,
    pub name: &'static str,
    pub hz: f64,
    /// Silence longer than this is "missing".
    pub missing_after: Duration,
    pub kind: ExpectKind,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExpectKind {
    Always,
    /// FAULT_STATUS: only while a fault exists (icd-reading R9), so silence is good news.
    WhileFault,
    /// EXTERNAL_DATA: only when we have air data to send.
    WhenWeHaveData,
}

/// The broadcasts whose rates the ICD specifies.
pub const EXPECTED: &[Expected] = &[
    Expected {
        dir: Crossing::Rx,
        name: SystemStatus::NAME,
        hz: 1.0,
        missing_after: COMM_LOST_AFTER,
        kind: ExpectKind::Always,
    },
    Expected {
        dir: Crossing::Rx,
        name: DeviceStatus::NAME,
        hz: 1.0,
        missing_after: COMM_LOST_AFTER,
        kind: ExpectKind::Always,
    },
    Expected {
        dir: Crossing::Rx,
        name: FlapTrimStatus::NAME,
        hz: 10.0,
        missing_after: FLAP_TRIM_STALE_AFTER,
        kind: ExpectKind::Always,
    },
    Expected {
        dir: Crossing::Rx,
        name: FaultStatus::NAME,
        hz: 1.0,
        missing_after: FAULT_STATUS_QUIET_AFTER,
        kind: ExpectKind::WhileFault,
    },
    Expected {
        dir: Crossing::Tx,
        name: ExternalData::NAME,
        hz: 1.0,
        missing_after: COMM_LOST_AFTER,
        kind: ExpectKind::WhenWeHaveData,
    },
];

/// How a message type is doing against the ICD.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Health {
    Ok,
    Slow,
    Missing,
    /// Silent, and that is fine (no fault, no air data).
    Quiet,
    /// Too early in the session to judge.
    Starting,
    /// Sent on request only: nothing to judge.
    NoRate,
}

/// Which entries the list shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KindFilter {
    #[default]
    All,
    /// Only what the decoder dropped.
    Errors,
    Message(&'static str),
}

/// The traffic view's state.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TrafficView {
    /// Paused: the list shows entries before this sequence number only.
    pub frozen_at: Option<u64>,
    pub dir: Option<Crossing>,
    pub kind: KindFilter,
    pub search: String,
    /// The search line is being typed.
    pub typing: bool,
    /// A selected entry (by seq) the list keeps in view; `None` follows the newest.
    pub cursor: Option<u64>,
}

/// Where a replay is, for the screen (set by the app's replay thread).
#[derive(Debug, Clone, PartialEq)]
pub struct ReplayStatus {
    pub file: String,
    pub position: Duration,
    pub length: Duration,
    pub speed: f64,
    pub paused: bool,
    pub finished: bool,
    /// A truncated or corrupt capture, in words: what was replayed is up to the cut.
    pub problem: Option<String>,
}

#[derive(Debug, Clone, Default)]
pub struct TrafficLog {
    entries: VecDeque<Entry>,
    next_seq: u64,
    /// Time zero of the timestamps shown: the first connection.
    pub origin: Option<Instant>,
    rx: BTreeMap<&'static str, TypeStat>,
    tx: BTreeMap<&'static str, TypeStat>,
    /// Drops by kind name ("BAD CHECKSUM" …), counted for the whole session.
    pub errors: BTreeMap<&'static str, u64>,
    pub view: TrafficView,
    pub replay: Option<ReplayStatus>,
}

impl TrafficLog {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn note_connected(&mut self, at: Instant) {
        self.origin.get_or_insert(at);
    }

    /// One item from the decoder.
    pub fn note_rx(&mut self, at: Instant, item: &RxItem, raw: &[u8]) {
        let what = match item {
            RxItem::Packet(p) => What::Packet(*p),
            RxItem::Malformed(e) => What::Malformed(e.to_string()),
            RxItem::Skipped => What::Dropped,
            RxItem::BadChecksum => What::BadChecksum,
            RxItem::BadLength => What::BadLength,
            RxItem::UnknownMessage => What::UnknownMessage,
        };
        self.push(at, Crossing::Rx, what, raw);
    }

    /// One write to the unit.
    pub fn note_tx(&mut self, at: Instant, packet: Option<&Packet>, raw: &[u8]) {
        let what = packet.map_or(What::RawTx, |p| What::Packet(*p));
        self.push(at, Crossing::Tx, what, raw);
    }

    fn push(&mut self, at: Instant, dir: Crossing, what: What, raw: &[u8]) {
        self.origin.get_or_insert(at);
        let entry = Entry {
            seq: self.next_seq,
            at,
            dir,
            what,
            raw: raw.to_vec(),
            search_text: SearchCache::default(),
        };
        self.next_seq += 1;
        if entry.is_error() {
            *self.errors.entry(entry.name()).or_default() += 1;
        }
        if let What::Packet(p) = &entry.what {
            let map = match dir {
                Crossing::Rx => &mut self.rx,
                Crossing::Tx => &mut self.tx,
            };
            let s = map.entry(p.message.name()).or_insert(TypeStat {
                count: 0,
                last: at,
                recent: VecDeque::new(),
            });
            s.count += 1;
            s.last = at;
            while s
                .recent
                .front()
                .is_some_and(|&t| at.saturating_duration_since(t) >= RATE_WINDOW)
            {
                s.recent.pop_front();
            }
            s.recent.push_back(at);
        }
        if self.entries.len() == TRAFFIC_LEN {
            self.entries.pop_front();
        }
        self.entries.push_back(entry);
    }

    /// Everything received or sent so far, including entries the ring has dropped.
    pub fn total(&self) -> u64 {
        self.next_seq
    }

    pub fn entries(&self) -> impl DoubleEndedIterator<Item = &Entry> + ExactSizeIterator {
        self.entries.iter()
    }

    pub fn stat(&self, dir: Crossing, name: &str) -> Option<&TypeStat> {
        match dir {
            Crossing::Rx => self.rx.get(name),
            Crossing::Tx => self.tx.get(name),
        }
    }

    /// Every type seen, received first, each direction by name.
    pub fn seen(&self) -> Vec<(Crossing, &'static str, &TypeStat)> {
        let rx = self.rx.iter().map(|(n, s)| (Crossing::Rx, *n, s));
        let tx = self.tx.iter().map(|(n, s)| (Crossing::Tx, *n, s));
        rx.chain(tx).collect()
    }

    /// Entries the list shows under the view's pause and filters, oldest first.
    pub fn visible(&self) -> Vec<&Entry> {
        let v = &self.view;
        self.entries
            .iter()
            .filter(|e| v.frozen_at.is_none_or(|f| e.seq < f))
            .filter(|e| v.dir.is_none_or(|d| e.dir == d))
            .filter(|e| match v.kind {
                KindFilter::All => true,
                KindFilter::Errors => e.is_error(),
                KindFilter::Message(n) => e.name() == n,
            })
            .collect()
    }

    /// Whether an entry matches the search (case-insensitive); never with no search.
    pub fn matches(&self, e: &Entry) -> bool {
        let s = self.view.search.trim();
        !s.is_empty() && e.search_text().contains(&s.to_lowercase())
    }

    /// New entries hidden by the pause.
    pub fn held_back(&self) -> u64 {
        self.view
            .frozen_at
            .map_or(0, |f| self.next_seq.saturating_sub(f))
    }

    /// How `name` in `dir` is doing against the ICD at `now`.
    pub fn health(&self, dir: Crossing, name: &str, now: Instant) -> Health {
        let Some(exp) = EXPECTED.iter().find(|e| e.dir == dir && e.name == name) else {
            return Health::NoRate;
        };
        let origin = self.origin.unwrap_or(now);
        let stat = self.stat(dir, name);
        let silent_for = stat.map(|s| now.saturating_duration_since(s.last));
        if exp.kind != ExpectKind::Always && silent_for.is_none_or(|d| d > exp.missing_after) {
            return match (exp.kind, stat) {
                // It was flowing and stopped: for air data that means the source went away.
                (ExpectKind::WhenWeHaveData, Some(_)) => Health::Missing,
                _ => Health::Quiet,
            };
        }
        match silent_for {
            None if now.saturating_duration_since(origin) > exp.missing_after => Health::Missing,
            None => Health::Starting,
            Some(d) if d > exp.missing_after => Health::Missing,
            Some(_) => match stat.and_then(|s| s.rate_hz(now, origin)) {
                None => Health::Starting,
                Some(r) if r < exp.hz * SLOW_SHARE => Health::Slow,
                Some(_) => Health::Ok,
            },
        }
    }

    /// Message names a type filter can cycle through, in table order.
    pub fn filter_choices(&self) -> Vec<KindFilter> {
        let mut names: Vec<&'static str> = Vec::new();
        for e in EXPECTED {
            if !names.contains(&e.name) {
                names.push(e.name);
            }
        }
        for (_, n, _) in self.seen() {
            if !names.contains(&n) {
                names.push(n);
            }
        }
        let mut out = vec![KindFilter::All, KindFilter::Errors];
        out.extend(names.into_iter().map(KindFilter::Message));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::{Ping, SignedTenths, Tenths};

    fn sys() -> Packet {
        Packet::from_vpx(
            0,
            SystemStatus {
                system_current: Tenths(10),
                main_bus_volts: SignedTenths(140),
                internal_temp: 20,
                ..Default::default()
            },
        )
    }

    #[test]
    fn the_ring_is_bounded_and_counters_outlive_it() {
        let t0 = Instant::now();
        let mut log = TrafficLog::new();
        let p = Packet::from_vpx(1, Ping { ack: true });
        for i in 0..(TRAFFIC_LEN as u64 + 10) {
            log.note_rx(t0 + Duration::from_millis(i), &RxItem::Packet(p), &[1]);
        }
        assert_eq!(log.entries().len(), TRAFFIC_LEN);
        assert_eq!(log.entries().next().unwrap().seq, 10);
        assert_eq!(
            log.stat(Crossing::Rx, "PING").unwrap().count,
            TRAFFIC_LEN as u64 + 10
        );
    }

    #[test]
    fn pause_holds_the_list_while_counting_goes_on() {
        let t0 = Instant::now();
        let mut log = TrafficLog::new();
        log.note_rx(t0, &RxItem::Packet(sys()), &[1]);
        log.view.frozen_at = Some(log.total());
        log.note_rx(t0, &RxItem::BadChecksum, &[0xE7]);
        assert_eq!(log.visible().len(), 1);
        assert_eq!(log.held_back(), 1);
        assert_eq!(log.errors.get("BAD CHECKSUM"), Some(&1));
    }

    #[test]
    fn a_slow_or_silent_broadcast_is_judged_against_the_icd() {
        let t0 = Instant::now();
        let mut log = TrafficLog::new();
        log.note_connected(t0);
        let s = |secs: f64| t0 + Duration::from_secs_f64(secs);
        // 1 Hz for six seconds: ok.
        for i in 0..7 {
            log.note_rx(s(i as f64), &RxItem::Packet(sys()), &[1]);
        }
        assert_eq!(
            log.health(Crossing::Rx, SystemStatus::NAME, s(6.5)),
            Health::Ok
        );
        // Then every two seconds: slow; then nothing: missing.
        log.note_rx(s(8.0), &RxItem::Packet(sys()), &[1]);
        log.note_rx(s(10.0), &RxItem::Packet(sys()), &[1]);
        for (name, at, want) in [
            (SystemStatus::NAME, 10.5, Health::Slow),
            (SystemStatus::NAME, 13.0, Health::Missing),
            // DEVICE_STATUS never came: missing; FAULT_STATUS never came: quiet.
            (DeviceStatus::NAME, 3.0, Health::Missing),
            (FaultStatus::NAME, 3.0, Health::Quiet),
            ("PING", 3.0, Health::NoRate),
        ] {
            let got = log.health(Crossing::Rx, name, s(at));
            assert_eq!(got, want, "{name} at {at} s");
        }
    }
}

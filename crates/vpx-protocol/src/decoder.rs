//! The streaming frame decoder.
//!
//! Bytes arrive in chunks split anywhere. The decoder yields every intact frame and
//! reports everything it throws away, as it happens, so a traffic view can show the
//! error where it occurred and the page can show link quality.
//!
//! Resync follows mavlink's frame decoder: when a candidate frame is bad (checksum,
//! impossible length) we advance **one byte**, never a whole frame, so a real frame
//! hidden inside garbage is still found. Memory is one maximal frame.
//!
//! A frame is `8 + len + 1` bytes (ICD §3.2.2, Table 1, icd-reading R1). A *candidate*
//! is any `E7 7E` pair; what the decoder does with one, in this order:
//!
//! 1. **Impossible at the header.** A known id whose length field is not the length its
//!    Appendix D table gives (or not within its range, FAULT_STATUS), or any id with a
//!    length above [`MAX_MESSAGE_LEN`] (66, DEVICE_STATUS: no message of the ICD is
//!    longer), is rejected as soon as its eighth byte arrives, without waiting for
//!    `len` more bytes. So one corrupt length byte holds back nothing, and no candidate
//!    ever spans more than 75 bytes. (A later firmware's unknown message longer than 66
//!    bytes would be reported as a bad length rather than an unknown message.)
//! 2. **A candidate gives way to an intact known frame inside it.** If an intact frame
//!    of a known message (possible length, good checksum) lies wholly within the bytes
//!    a candidate claims, the candidate is given up: its first byte is skipped and the
//!    scan goes on from the next byte, which finds that frame. This is decided as soon
//!    as the inner frame is complete, so a false header, known id or unknown, never
//!    holds back a real frame past the moment its last byte arrives. Because the inner
//!    frame ends no later than the candidate does, the same decision is reached
//!    whatever the read boundaries: with the whole candidate in hand the rule applies
//!    before its checksum is looked at. The price is a real frame whose payload
//!    contains a whole intact known frame of at least 9 bytes, checksum included: it is
//!    lost in favour of that inner frame. Random payload bytes do that about once in
//!    10^14 frames; a real frame that merely *straddles* a false header's end is never
//!    lost to this rule (it is found when the false header fails its checksum).
//! 3. **Otherwise the candidate is judged when all its bytes are in:** a good checksum
//!    makes it a frame (an unknown id with a possible length is an intact frame we
//!    cannot interpret: counted as an unknown message, which is useful link health,
//!    and skipped whole); a bad one advances one byte.
//!
//! **At the end of the input** ([`Decoder::finish`]: the end of a capture, a replay, or
//! a closed port) a candidate still waiting for bytes can never complete: it is given
//! up one byte at a time and the held bytes are scanned on, so every intact frame among
//! them comes out and only real junk is reported. The last candidate that nothing
//! intact follows is reported as [`Event::Truncated`], a frame the input was cut in.
//!
//! The goal these serve: on a live line a false header delays no real frame at all
//! beyond the arrival of that frame's last byte (the test
//! `false_header_on_a_paced_line_delays_no_frame` feeds the unit's real traffic at
//! 57600 baud on a fake clock and holds every frame to 50 ms).

use super::frame::{FrameRef, HEADER_LEN, MAX_FRAME, MessageId, SYNC1, SYNC2, checksum};
use super::message::{self, MAX_MESSAGE_LEN, MIN_FRAME};

/// The longest candidate the decoder ever holds: rule 1 of the module documentation.
const MAX_CANDIDATE: usize = HEADER_LEN + MAX_MESSAGE_LEN + 1;
const _: () = assert!(MAX_CANDIDATE <= MAX_FRAME);

/// What the decoder found: a frame of ICD Table 1, or what was wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event<'a> {
    /// An intact frame of a message the ICD defines.
    Frame(FrameRef<'a>),
    /// Bytes that were not part of any frame (including the first byte of a candidate
    /// that gave way to an intact frame inside it).
    Skipped(&'a [u8]),
    /// A candidate frame whose checksum did not match (all of its claimed bytes). Only
    /// its first byte is consumed; the rest is scanned again.
    BadChecksum(&'a [u8]),
    /// A header whose length field no message with its id can have (the header's 8
    /// bytes). Only its first byte is consumed.
    BadLength(&'a [u8]),
    /// An intact frame (checksum good) whose major/minor the ICD does not define.
    UnknownMessage(&'a [u8]),
    /// The start of a frame the input ended in, reported only by [`Decoder::finish`]:
    /// nothing intact follows it.
    Truncated(&'a [u8]),
}

/// Running counts of what the decoder accepted and dropped (frames of ICD Table 1).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DecoderStats {
    /// Frames decoded whole with a good checksum (ICD §4.1).
    pub frames: u64,
    /// Bytes given to the decoder.
    pub bytes_in: u64,
    /// Bytes discarded outside of any frame (including the first byte of each bad
    /// candidate).
    pub skipped_bytes: u64,
    /// Frames whose checksum byte did not match (ICD §4.1.3).
    pub bad_checksum: u64,
    /// Intact frames whose payload length does not fit their message (ICD §6).
    pub bad_length: u64,
    /// Intact frames with a major/minor that ICD Table 42 does not define.
    pub unknown_message: u64,
    /// Bytes of a frame the input ended in ([`Event::Truncated`]).
    pub truncated_bytes: u64,
}

impl DecoderStats {
    /// Total number of dropped things (frames and runs of bytes): a quick link-quality number.
    pub fn errors(&self) -> u64 {
        self.bad_checksum + self.bad_length + self.unknown_message
    }
}

/// Streaming decoder of ICD Table 1 frames; see the module documentation.
pub struct Decoder {
    buf: [u8; MAX_FRAME],
    len: usize,
    stats: DecoderStats,
}

impl Default for Decoder {
    fn default() -> Self {
        Self::new()
    }
}

enum Scan {
    /// The candidate's first byte was plain garbage (or the candidate gave way); the
    /// run of skipped bytes goes on.
    Garbage,
    /// The candidate was reported (frame or error); scanning resumes at this offset
    /// and the run of skipped bytes starts afresh there.
    Reported(usize),
    /// The rest of the slice, from the candidate on, is an incomplete frame.
    Incomplete,
    /// End of input: the rest of the slice, from the candidate on, was reported as
    /// truncated.
    Truncated,
}

/// Whether more input may follow the slice being scanned.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Input {
    MoreMayCome,
    Ended,
}

impl Decoder {
    /// An empty decoder.
    pub fn new() -> Self {
        Decoder {
            buf: [0; MAX_FRAME],
            len: 0,
            stats: DecoderStats::default(),
        }
    }

    /// The counters so far.
    pub fn stats(&self) -> DecoderStats {
        self.stats
    }

    /// Bytes held back as the start of an incomplete frame. They never contain an
    /// intact frame of a known message (rule 2 of the module documentation).
    pub fn pending(&self) -> usize {
        self.len
    }

    /// How many more bytes the held candidate needs before it can be judged: 0 when
    /// nothing is held. A reader can wait for them to cross the line instead of
    /// waking for each piece of the frame.
    pub fn awaiting(&self) -> usize {
        if self.len == 0 {
            return 0;
        }
        self.need().saturating_sub(self.len)
    }

    /// Forgets a partial frame without looking at it, for when the bytes before are
    /// meaningless (a unit rebooting, a switch to the bootloader protocol). Counted as
    /// skipped. Where the input simply ended, use [`Decoder::finish`].
    pub fn reset(&mut self) {
        self.stats.skipped_bytes += self.len as u64;
        self.len = 0;
    }

    /// Feeds bytes; `on_event` is called for each frame found and each thing dropped.
    pub fn push(&mut self, mut input: &[u8], mut on_event: impl FnMut(Event<'_>)) {
        self.stats.bytes_in += input.len() as u64;
        while self.len > 0 && !input.is_empty() {
            // Top up only to the next byte that can decide the candidate: the second
            // (sync) byte first, then the header, then its claimed end. Taking more
            // would judge the held candidate with bytes a split elsewhere would not
            // have given it, so `pending` and the events would depend on the reads.
            let upto = self.need();
            let take = upto.saturating_sub(self.len).min(input.len());
            let (Some((now, later)), Some(dst)) = (
                input.split_at_checked(take),
                self.buf.get_mut(self.len..self.len + take),
            ) else {
                // `need` never asks past the buffer (it holds the largest frame).
                break;
            };
            dst.copy_from_slice(now);
            self.len += take;
            input = later;
            // Re-scan the held bytes in place (no copy of the buffer): a candidate
            // still incomplete may now give way to a frame completed inside it.
            // Whatever is left over is again an incomplete candidate that starts with
            // the sync byte, moved to the front.
            let n = self.len;
            let done = Self::scan(
                &mut self.stats,
                self.buf.get(..n).unwrap_or_default(),
                Input::MoreMayCome,
                &mut on_event,
            );
            self.buf.copy_within(done..n, 0);
            self.len = n - done;
        }
        if self.len > 0 {
            return;
        }
        let done = Self::scan(&mut self.stats, input, Input::MoreMayCome, &mut on_event);
        let rest = input.get(done..).unwrap_or_default();
        // What is left is one incomplete candidate, shorter than the largest frame.
        self.len = match self.buf.get_mut(..rest.len()) {
            Some(dst) => {
                dst.copy_from_slice(rest);
                rest.len()
            }
            None => 0,
        };
    }

    /// The input has ended (end of a capture or replay, a port closed): the held bytes
    /// can never complete a frame, so they are scanned again one byte at a time. Every
    /// intact frame among them is yielded, junk is skipped, and the frame the input was
    /// cut in, if any, is reported as [`Event::Truncated`]. Afterwards nothing is
    /// pending and the decoder starts afresh on the next `push`.
    pub fn finish(&mut self, mut on_event: impl FnMut(Event<'_>)) {
        let n = self.len;
        let held = self.buf.get(..n).unwrap_or_default();
        let done = Self::scan(&mut self.stats, held, Input::Ended, &mut on_event);
        debug_assert_eq!(done, n, "at the end of input everything is decided");
        self.len = 0;
    }

    /// How many bytes the held candidate must reach before it can be judged.
    fn need(&self) -> usize {
        let b = self.buf.get(..self.len).unwrap_or_default();
        if b.get(1).is_some_and(|&x| x != SYNC2) {
            return b.len();
        }
        if b.len() < HEADER_LEN {
            return HEADER_LEN;
        }
        match possible_length(b) {
            Some(len) => HEADER_LEN + len + 1,
            None => b.len(),
        }
    }

    /// Scans a contiguous slice and returns how many bytes it consumed; the remainder
    /// (at most one candidate) is an incomplete frame. With [`Input::Ended`] it
    /// consumes everything.
    fn scan<'a>(
        stats: &mut DecoderStats,
        data: &'a [u8],
        input: Input,
        on_event: &mut impl FnMut(Event<'a>),
    ) -> usize {
        let mut at = 0;
        let mut skip_from = 0;
        loop {
            // Find the next candidate start.
            let from = data.get(at..).unwrap_or_default();
            let start = match from.iter().position(|&b| b == SYNC1) {
                Some(i) => at + i,
                None => {
                    Self::skip(stats, data.get(skip_from..).unwrap_or_default(), on_event);
                    return data.len();
                }
            };
            match Self::candidate(stats, data, start, input, on_event, skip_from) {
                Scan::Garbage => at = start + 1,
                Scan::Reported(next) => {
                    at = next;
                    skip_from = next;
                }
                Scan::Incomplete => {
                    Self::skip(stats, between(data, skip_from, start), on_event);
                    return start;
                }
                Scan::Truncated => return data.len(),
            }
        }
    }

    /// Judges the candidate at `start` by the rules of the module documentation.
    /// Before reporting anything it flushes the run of skipped bytes that precedes the
    /// candidate, so events come out in wire order.
    fn candidate<'a>(
        stats: &mut DecoderStats,
        data: &'a [u8],
        start: usize,
        input: Input,
        on_event: &mut impl FnMut(Event<'a>),
        skip_from: usize,
    ) -> Scan {
        let rest = data.get(start..).unwrap_or_default();
        if rest.get(1).is_some_and(|&x| x != SYNC2) {
            return Scan::Garbage;
        }
        let after_sync = rest.get(1..).unwrap_or_default();
        let total = if rest.len() < HEADER_LEN {
            None
        } else {
            match possible_length(rest) {
                Some(len) => Some(HEADER_LEN + len + 1),
                None => {
                    // Rule 1: impossible at the header.
                    Self::skip(stats, between(data, skip_from, start), on_event);
                    stats.bad_length += 1;
                    stats.skipped_bytes += 1;
                    on_event(Event::BadLength(rest.get(..HEADER_LEN).unwrap_or(rest)));
                    return Scan::Reported(start + 1);
                }
            }
        };
        let Some(frame) = total.and_then(|t| rest.get(..t)) else {
            // Incomplete. Rule 2: every intact frame in the held bytes lies within
            // the bytes this candidate claims.
            if holds_known_frame(after_sync) {
                return Scan::Garbage;
            }
            return match input {
                Input::MoreMayCome => Scan::Incomplete,
                // It can never complete. Give it up one byte, unless nothing intact
                // follows: then it is the frame the input was cut in.
                Input::Ended if holds_any_frame(after_sync) => Scan::Garbage,
                Input::Ended => {
                    Self::skip(stats, between(data, skip_from, start), on_event);
                    stats.truncated_bytes += rest.len() as u64;
                    on_event(Event::Truncated(rest));
                    Scan::Truncated
                }
            };
        };
        let total = frame.len();
        // Rule 2 before the checksum, so a candidate is judged the same whether the
        // inner frame completed while it was still incomplete or in the same read.
        // First a branch-free look for a sync byte where an inner frame could start
        // (most frames have none), so that every good frame does not pay the search.
        let inner_starts = frame.get(1..total.saturating_sub(MIN_FRAME - 1));
        if inner_starts.is_some_and(|b| b.iter().fold(false, |any, &x| any | (x == SYNC1)))
            && holds_known_frame(frame.get(1..).unwrap_or_default())
        {
            return Scan::Garbage;
        }
        if !checksum_holds(frame) {
            Self::skip(stats, between(data, skip_from, start), on_event);
            stats.bad_checksum += 1;
            stats.skipped_bytes += 1;
            on_event(Event::BadChecksum(frame));
            return Scan::Reported(start + 1);
        }
        Self::skip(stats, between(data, skip_from, start), on_event);
        if message::lookup(id_of(frame)).is_some() {
            stats.frames += 1;
            on_event(Event::Frame(FrameRef::new_unchecked(frame)));
        } else {
            stats.unknown_message += 1;
            on_event(Event::UnknownMessage(frame));
        }
        Scan::Reported(start + total)
    }

    fn skip<'a>(stats: &mut DecoderStats, bytes: &'a [u8], on_event: &mut impl FnMut(Event<'a>)) {
        if !bytes.is_empty() {
            stats.skipped_bytes += bytes.len() as u64;
            on_event(Event::Skipped(bytes));
        }
    }
}

/// The payload length a whole header (at least 8 bytes, sync bytes included) claims,
/// if some message with its id can have it: the length its table gives for a known id,
/// at most [`MAX_MESSAGE_LEN`] for an unknown one.
fn possible_length(header: &[u8]) -> Option<usize> {
    let &[_, _, major, minor, _, _, _, len, ..] = header else {
        return None;
    };
    let len = len as usize;
    let possible = match message::lookup(MessageId::new(major, minor)) {
        Some((_, rule)) => rule.allows(len),
        None => len <= MAX_MESSAGE_LEN,
    };
    possible.then_some(len)
}

/// `data[from..to]`, or nothing where that is not a range of `data`.
fn between(data: &[u8], from: usize, to: usize) -> &[u8] {
    data.get(from..to).unwrap_or_default()
}

/// The id in a header's bytes 3 and 4 (0/0, no message, for fewer bytes).
fn id_of(header: &[u8]) -> MessageId {
    match header {
        &[_, _, major, minor, ..] => MessageId::new(major, minor),
        _ => MessageId::new(0, 0),
    }
}

/// Whether a frame's last byte is the checksum of the bytes before it.
fn checksum_holds(frame: &[u8]) -> bool {
    frame
        .split_last()
        .is_some_and(|(&sum, body)| checksum(body) == sum)
}

/// Whether `span` holds, wholly, an intact frame of a known message.
fn holds_known_frame(span: &[u8]) -> bool {
    holds_frame(span, true)
}

/// Whether `span` holds, wholly, an intact frame with a possible header.
fn holds_any_frame(span: &[u8]) -> bool {
    holds_frame(span, false)
}

fn holds_frame(span: &[u8], known_only: bool) -> bool {
    if span.len() < MIN_FRAME {
        return false;
    }
    // The last place a frame can start and still fit.
    let last = span.len() - MIN_FRAME;
    let mut at = 0;
    while let Some(i) = span
        .get(at..=last)
        .and_then(|s| s.iter().position(|&b| b == SYNC1))
    {
        let rest = span.get(at + i..).unwrap_or_default();
        if rest.get(1) == Some(&SYNC2)
            && (!known_only || message::lookup(id_of(rest)).is_some())
            && let Some(len) = possible_length(rest)
            && let Some(frame) = rest.get(..HEADER_LEN + len + 1)
            && checksum_holds(frame)
        {
            return true;
        }
        at += i + 1;
        if at > last {
            break;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PING request, cnt 1, EFIS → VP-X, worked by hand from ICD Tables 1 and 10:
    /// E7^7E^10^00^01^01^00^01^00 = 0x88, inverted = 0x77.
    const PING: [u8; 10] = [0xE7, 0x7E, 0x10, 0x00, 0x01, 0x01, 0x00, 0x01, 0x00, 0x77];

    /// An event in a word and its length (the whole bytes of a frame).
    fn word(e: Event<'_>) -> String {
        match e {
            Event::Frame(f) => format!("frame {:02X?}", f.as_bytes()),
            Event::Skipped(b) => format!("skip {}", b.len()),
            Event::BadChecksum(b) => format!("badsum {}", b.len()),
            Event::BadLength(b) => format!("badlen {}", b.len()),
            Event::UnknownMessage(b) => format!("unknown {}", b.len()),
            Event::Truncated(b) => format!("truncated {}", b.len()),
        }
    }

    fn collect(dec: &mut Decoder, bytes: &[u8]) -> Vec<String> {
        let mut out = Vec::new();
        dec.push(bytes, |e| out.push(word(e)));
        out
    }

    fn finish(dec: &mut Decoder) -> Vec<String> {
        let mut out = Vec::new();
        dec.finish(|e| out.push(word(e)));
        out
    }

    /// Adjacent skipped runs merged: where a run of garbage is cut depends on the
    /// reads, what was skipped does not.
    fn merged(events: Vec<String>) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for e in events {
            if let (Some(prev), Some(n)) = (out.last_mut(), e.strip_prefix("skip "))
                && let Some(m) = prev.strip_prefix("skip ")
            {
                let sum = m.parse::<usize>().unwrap() + n.parse::<usize>().unwrap();
                *prev = format!("skip {sum}");
                continue;
            }
            out.push(e);
        }
        out
    }

    /// Feeds `stream` in the given reads; the events of the reads (merged), what was
    /// pending after them, and the events of `finish`.
    fn feed(reads: &[&[u8]]) -> (Vec<String>, usize, Vec<String>) {
        let mut d = Decoder::new();
        let mut out = Vec::new();
        for r in reads {
            out.extend(collect(&mut d, r));
        }
        let pending = d.pending();
        let end = finish(&mut d);
        assert_eq!(d.pending(), 0);
        let s = d.stats();
        // Every byte accounted for: frames, skipped (incl. the first byte of each
        // rejected candidate), truncated.
        let frame_bytes: usize = out
            .iter()
            .chain(&end)
            .filter_map(|e| e.strip_prefix("frame "))
            .map(|f| f.split(',').count())
            .sum();
        let unknown_bytes: usize = out
            .iter()
            .chain(&end)
            .filter_map(|e| e.strip_prefix("unknown "))
            .map(|n| n.parse::<usize>().unwrap())
            .sum();
        assert_eq!(
            s.bytes_in,
            (frame_bytes + unknown_bytes) as u64 + s.skipped_bytes + s.truncated_bytes,
            "{out:?} {end:?}"
        );
        (merged(out), pending, end)
    }

    /// The same bytes in one read, one byte per read, and cut once at every place:
    /// each gives the same events and leaves the same bytes pending.
    fn same_however_read(stream: &[u8]) -> (Vec<String>, usize, Vec<String>) {
        let whole = feed(&[stream]);
        let bytes: Vec<&[u8]> = stream.chunks(1).collect();
        assert_eq!(feed(&bytes), whole, "byte by byte");
        for cut in 1..stream.len() {
            let (a, b) = stream.split_at(cut);
            assert_eq!(feed(&[a, b]), whole, "cut at {cut}");
        }
        whole
    }

    fn cat(parts: &[&[u8]]) -> Vec<u8> {
        parts.concat()
    }

    fn frame(f: &[u8]) -> String {
        format!("frame {f:02X?}")
    }

    /// DEVICE_POWER device 5 on, cnt 2, EFIS → VP-X, by hand from ICD Tables 1 and 31:
    /// E7^7E^13^00^02^01^00^02^05^01 = 0x8F, inverted = 0x70.
    const DEVICE_POWER: [u8; 11] = [
        0xE7, 0x7E, 0x13, 0x00, 0x02, 0x01, 0x00, 0x02, 0x05, 0x01, 0x70,
    ];
    /// SPEC_ACK device 5 no error, cnt 3, VP-X → EFIS (0x11/0x06, icd-reading R4):
    /// E7^7E^11^06^03^00^01^02^05^00 = 0x8B, inverted = 0x74.
    const SPEC_ACK: [u8; 11] = [
        0xE7, 0x7E, 0x11, 0x06, 0x03, 0x00, 0x01, 0x02, 0x05, 0x00, 0x74,
    ];
    /// A false header: an unknown id (0x20/0x00) claiming 250 bytes, a
    /// length no message of the ICD has.
    const UNKNOWN_250: [u8; 8] = [0xE7, 0x7E, 0x20, 0x00, 0x00, 0x00, 0x00, 0xFA];
    /// An unknown id claiming 64 bytes: possible, so it is held (73 bytes).
    const UNKNOWN_64: [u8; 8] = [0xE7, 0x7E, 0x20, 0x00, 0x00, 0x00, 0x00, 0x40];
    /// DEVICE_STATUS claiming its own 66 bytes: possible, so it is held (75 bytes).
    const STATUS_66: [u8; 8] = [0xE7, 0x7E, 0x12, 0x01, 0x00, 0x00, 0x00, 0x42];
    /// DEVICE_STATUS claiming 2 bytes: impossible (Table 26 gives 66).
    const STATUS_2: [u8; 8] = [0xE7, 0x7E, 0x12, 0x01, 0x00, 0x00, 0x00, 0x02];

    #[test]
    fn a_capture_with_false_headers_yields_every_frame() {
        // PING, the false header, DEVICE_POWER, PING, SPEC_ACK, end of capture.
        let stream = cat(&[&PING, &UNKNOWN_250, &DEVICE_POWER, &PING, &SPEC_ACK]);
        let (events, pending, end) = same_however_read(&stream);
        assert_eq!(
            events,
            [
                frame(&PING),
                "badlen 8".into(),
                "skip 7".into(),
                frame(&DEVICE_POWER),
                frame(&PING),
                frame(&SPEC_ACK),
            ]
        );
        assert_eq!((pending, end), (0, vec![]));
    }

    #[test]
    fn a_held_false_header_gives_way_to_the_frames_after_it() {
        // Possible headers, known id or not, in the middle: each gives way as soon as
        // DEVICE_POWER is complete inside the 73 or 75 bytes it claims, and the bytes
        // of the false header are all that is dropped.
        for header in [UNKNOWN_64, STATUS_66] {
            let stream = cat(&[&PING, &header, &DEVICE_POWER, &PING, &SPEC_ACK]);
            let (events, pending, end) = same_however_read(&stream);
            assert_eq!(
                events,
                [
                    frame(&PING),
                    "skip 8".into(),
                    frame(&DEVICE_POWER),
                    frame(&PING),
                    frame(&SPEC_ACK),
                ],
                "{header:02X?}"
            );
            assert_eq!((pending, end), (0, vec![]));
        }
    }

    #[test]
    fn a_false_header_gives_way_at_the_byte_that_completes_the_frame() {
        // Live: the false header arrives, then DEVICE_POWER one byte at a time. Nothing
        // comes out until its last byte, and then it does, without waiting for the 73
        // bytes the header claims.
        let mut d = Decoder::new();
        assert!(collect(&mut d, &UNKNOWN_64).is_empty());
        for b in &DEVICE_POWER[..10] {
            assert!(collect(&mut d, std::slice::from_ref(b)).is_empty());
        }
        assert_eq!(d.pending(), 18);
        assert_eq!(
            collect(&mut d, &DEVICE_POWER[10..]),
            ["skip 8".to_string(), frame(&DEVICE_POWER)]
        );
        assert_eq!(d.pending(), 0);
    }

    #[test]
    fn a_known_id_with_a_wrong_length_is_rejected_at_its_header() {
        let stream = cat(&[&STATUS_2, &DEVICE_POWER, &PING]);
        let (events, pending, end) = same_however_read(&stream);
        assert_eq!(
            events,
            [
                "badlen 8".to_string(),
                "skip 7".into(),
                frame(&DEVICE_POWER),
                frame(&PING)
            ]
        );
        assert_eq!((pending, end), (0, vec![]));
    }

    #[test]
    fn false_headers_at_the_end_of_the_input() {
        // Impossible ones are decided at once; possible ones are held until the input
        // ends, then reported as the frame it was cut in.
        for (header, held) in [
            (STATUS_2, false),
            (UNKNOWN_250, false),
            (UNKNOWN_64, true),
            (STATUS_66, true),
        ] {
            let stream = cat(&[&PING, &DEVICE_POWER, &header]);
            let (events, pending, end) = same_however_read(&stream);
            let mut expected = vec![frame(&PING), frame(&DEVICE_POWER)];
            if held {
                assert_eq!((pending, end), (8, vec!["truncated 8".to_string()]));
            } else {
                expected.extend(["badlen 8".to_string(), "skip 7".into()]);
                assert_eq!((pending, end), (0, vec![]));
            }
            assert_eq!(events, expected, "{header:02X?}");
        }
    }

    #[test]
    fn at_the_end_held_bytes_are_rescanned_for_unknown_frames_too() {
        // A held DEVICE_STATUS header with, inside what it claims, an intact message of
        // an id the ICD does not define (0x16/0x00, no payload; checksum by hand
        // E7^7E^16^00^01^00^01^00 = 0x8F, inverted 0x70) and a cut-off PING. A known
        // frame would make the header give way at once; an unknown one is only found
        // when the input ends.
        const UNKNOWN: [u8; 9] = [0xE7, 0x7E, 0x16, 0x00, 0x01, 0x00, 0x01, 0x00, 0x70];
        let stream = cat(&[&STATUS_66, &UNKNOWN, &PING[..4]]);
        let (events, pending, end) = same_however_read(&stream);
        assert_eq!(events, Vec::<String>::new());
        assert_eq!(pending, stream.len());
        assert_eq!(
            end,
            [
                "skip 8".to_string(),
                "unknown 9".into(),
                "truncated 4".into()
            ]
        );
    }

    #[test]
    fn an_intact_candidate_gives_way_to_a_known_frame_inside_it() {
        // An unknown id claiming 11 bytes, which are exactly DEVICE_POWER, and a
        // checksum that holds over all of it (E7^7E^20^0B = 0xB2 for the header, 0xFF
        // for DEVICE_POWER with its checksum, 0xB2^0xFF = 0x4D, inverted 0xB2). Read
        // whole it would be an unknown message swallowing the real frame; it gives way.
        let stream = cat(&[
            &[0xE7, 0x7E, 0x20, 0x00, 0x00, 0x00, 0x00, 0x0B],
            &DEVICE_POWER,
            &[0xB2],
        ]);
        let (events, pending, end) = same_however_read(&stream);
        assert_eq!(
            events,
            ["skip 8".to_string(), frame(&DEVICE_POWER), "skip 1".into()]
        );
        assert_eq!((pending, end), (0, vec![]));
    }

    #[test]
    fn a_frame_straddling_the_end_of_a_false_header_is_found_when_it_fails() {
        // An unknown id claiming 4 bytes (13 in all): DEVICE_POWER starts inside it and
        // ends after it, so the header is judged on its checksum (bad) and the frame is
        // found when it completes.
        let stream = cat(&[
            &[0xE7, 0x7E, 0x20, 0x00, 0x00, 0x00, 0x00, 0x04],
            &DEVICE_POWER,
        ]);
        let (events, pending, end) = same_however_read(&stream);
        assert_eq!(
            events,
            [
                "badsum 13".to_string(),
                "skip 7".into(),
                frame(&DEVICE_POWER)
            ]
        );
        assert_eq!((pending, end), (0, vec![]));
    }

    #[test]
    fn a_false_header_split_across_reads_holds_nothing_back() {
        // The header itself arrives in three reads, the frames in two.
        for header in [UNKNOWN_64, STATUS_66, STATUS_2, UNKNOWN_250] {
            let tail = cat(&[&DEVICE_POWER, &PING]);
            let (events, pending, end) = feed(&[
                &header[..1],
                &header[1..5],
                &header[5..],
                &tail[..15],
                &tail[15..],
            ]);
            let mut expected = match header[7] {
                0x02 | 0xFA => vec!["badlen 8".to_string(), "skip 7".into()],
                _ => vec!["skip 8".to_string()],
            };
            expected.extend([frame(&DEVICE_POWER), frame(&PING)]);
            assert_eq!(events, expected, "{header:02X?}");
            assert_eq!((pending, end), (0, vec![]));
        }
    }

    #[test]
    fn a_frame_cut_off_at_the_end_is_truncated_not_lost() {
        let stream = cat(&[&PING, &DEVICE_POWER[..6]]);
        let (events, pending, end) = same_however_read(&stream);
        assert_eq!(events, [frame(&PING)]);
        assert_eq!((pending, end), (6, vec!["truncated 6".to_string()]));
        // A lone sync byte at the end, too.
        let (events, pending, end) = same_however_read(&cat(&[&PING, &[0xE7]]));
        assert_eq!(events, [frame(&PING)]);
        assert_eq!((pending, end), (1, vec!["truncated 1".to_string()]));
    }

    /// One byte on the wire at 57600 baud, 8N1 (10 bits), in nanoseconds.
    const BYTE_NS: u64 = 1_000_000_000 * 10 / 57_600;
    const MS: u64 = 1_000_000;

    /// A broadcast frame (VP-X → EFIS) of message `major/minor` with `len` payload
    /// bytes, each `fill`.
    fn broadcast(major: u8, minor: u8, cnt: u8, len: usize, fill: u8) -> Vec<u8> {
        let header = crate::FrameHeader {
            id: MessageId::new(major, minor),
            cnt,
            src: crate::Node::Vpx,
            dst: crate::Node::External,
        };
        let mut out = [0u8; MAX_FRAME];
        let n = crate::frame::emit_frame(&header, &vec![fill; len], &mut out).unwrap();
        out[..n].to_vec()
    }

    /// Two seconds of what the unit broadcasts (ICD Table 6: SYSTEM_STATUS and
    /// DEVICE_STATUS at 1 Hz, FLAP_TRIM_STATUS at 10 Hz), each burst sent at the line
    /// rate from the start of its 100 ms slot, with `false_header` put in at `place`.
    /// Every byte with the time its stop bit ends; the real frames in order.
    fn paced_traffic(false_header: &[u8], place: Place) -> (Vec<(u64, u8)>, Vec<Vec<u8>>) {
        let mut timeline = Vec::new();
        let mut frames = Vec::new();
        let mut cnt = 0u8;
        for slot in 0..20u64 {
            let mut burst: Vec<Vec<u8>> = Vec::new();
            let fill = slot as u8;
            if slot % 10 == 0 {
                burst.push(broadcast(0x12, 0x00, cnt, 12, fill));
                burst.push(broadcast(0x12, 0x01, cnt.wrapping_add(1), 66, fill));
                cnt = cnt.wrapping_add(2);
            }
            burst.push(broadcast(0x12, 0x02, cnt, 18, fill));
            cnt = cnt.wrapping_add(1);
            let mut bytes = Vec::new();
            for (i, f) in burst.iter().enumerate() {
                if slot == 3 && place == Place::BeforeFrame(i) {
                    bytes.extend_from_slice(false_header);
                }
                bytes.extend_from_slice(f);
            }
            if slot == 3 && place == Place::EndOfBurst {
                bytes.extend_from_slice(false_header);
            }
            frames.extend(burst);
            let start = slot * 100 * MS;
            for (i, b) in bytes.into_iter().enumerate() {
                timeline.push((start + (i as u64 + 1) * BYTE_NS, b));
            }
        }
        (timeline, frames)
    }

    #[derive(Clone, Copy, PartialEq, Eq, Debug)]
    enum Place {
        BeforeFrame(usize),
        /// Followed by the silence until the next burst: the case that froze the page.
        EndOfBurst,
    }

    /// Feeds the timeline in reads of everything that arrived within each `tick` (a
    /// serial read's latency), on a fake clock; each frame with the delay between the
    /// arrival of its last byte and the read that yielded it.
    fn delays(timeline: &[(u64, u8)], tick: u64) -> Vec<(Vec<u8>, u64)> {
        let mut d = Decoder::new();
        let mut out = Vec::new();
        let mut at = 0;
        // Where the next frame's bytes can begin: after the last one yielded.
        let mut base = 0;
        while at < timeline.len() {
            let read_at = timeline[at].0.div_ceil(tick) * tick;
            let end = timeline[at..]
                .iter()
                .position(|&(t, _)| t > read_at)
                .map_or(timeline.len(), |n| at + n);
            let bytes: Vec<u8> = timeline[at..end].iter().map(|&(_, b)| b).collect();
            d.push(&bytes, |e| {
                if let Event::Frame(f) = e {
                    // The frame's last byte: in this read or an earlier one.
                    let f = f.as_bytes();
                    let last = (base + f.len() - 1..end)
                        .find(|&i| {
                            let wire = &timeline[i + 1 - f.len()..=i];
                            wire.iter().map(|&(_, b)| b).eq(f.iter().copied())
                        })
                        .expect("a frame yielded ends at a byte that arrived");
                    base = last + 1;
                    out.push((f.to_vec(), read_at - timeline[last].0));
                }
            });
            at = end;
        }
        out
    }

    #[test]
    fn false_header_on_a_paced_line_delays_no_frame() {
        // A false header delays no real frame by more than 50 ms at
        // the real line rate. Reads of one byte (each judged as it comes) and reads
        // every 1 ms and 16 ms (a USB-serial adapter's latency timer).
        let headers: [&[u8]; 5] = [
            &UNKNOWN_64,
            &STATUS_66,
            &STATUS_2,
            &UNKNOWN_250,
            &[0xE7, 0x7E],
        ];
        let places = [Place::BeforeFrame(0), Place::EndOfBurst];
        for header in headers {
            for place in places {
                let (timeline, frames) = paced_traffic(header, place);
                for tick in [1, MS, 16 * MS] {
                    let got = delays(&timeline, tick);
                    let out: Vec<&Vec<u8>> = got.iter().map(|(f, _)| f).collect();
                    assert_eq!(
                        out,
                        frames.iter().collect::<Vec<_>>(),
                        "{header:02X?} {place:?}"
                    );
                    let worst = got.iter().map(|&(_, d)| d).max().unwrap();
                    // Nothing waits beyond the read its last byte came in.
                    assert!(
                        worst <= tick.max(1),
                        "{header:02X?} {place:?} tick {tick}: {worst} ns"
                    );
                    assert!(worst <= 50 * MS);
                }
            }
        }
    }

    #[test]
    fn after_finish_the_decoder_starts_afresh() {
        let mut d = Decoder::new();
        collect(&mut d, &UNKNOWN_64);
        assert_eq!(finish(&mut d), ["truncated 8".to_string()]);
        assert_eq!(collect(&mut d, &PING), [frame(&PING)]);
        assert_eq!(finish(&mut d), Vec::<String>::new());
    }

    #[test]
    fn frame_split_byte_by_byte() {
        let mut d = Decoder::new();
        let mut out = Vec::new();
        for b in PING {
            out.extend(collect(&mut d, &[b]));
        }
        assert_eq!(out, vec![format!("frame {:02X?}", PING)]);
        assert_eq!(d.stats().frames, 1);
        assert_eq!(d.pending(), 0);
    }

    #[test]
    fn bad_checksum_advances_one_byte_and_finds_hidden_frame() {
        // A corrupt candidate whose claimed 14 bytes run into a real frame (it cannot
        // give way to it: the frame does not end inside it).
        let mut bytes = vec![0x00, 0xE7, 0x7E, 0x99, 0x00, 0x00, 0x00, 0x00, 0x05];
        bytes.extend_from_slice(&PING);
        bytes.push(0x55);
        let mut d = Decoder::new();
        let out = collect(&mut d, &bytes);
        assert_eq!(
            out,
            vec![
                "skip 1".to_string(),
                "badsum 14".into(),
                "skip 7".into(),
                format!("frame {:02X?}", PING),
                "skip 1".into()
            ]
        );
        assert_eq!(d.pending(), 0);
        let s = d.stats();
        assert_eq!((s.frames, s.bad_checksum, s.skipped_bytes), (1, 1, 10));
    }

    #[test]
    fn held_sync_byte_followed_by_garbage_is_judged_at_once() {
        // A read ends on 0xE7 and the next read brings one byte that is not 0x7E: the
        // held byte is garbage now, not once 8 bytes have arrived.
        let mut d = Decoder::new();
        assert_eq!(collect(&mut d, &[0x00, 0xE7]), vec!["skip 1".to_string()]);
        assert_eq!(collect(&mut d, &[0xE7]), vec!["skip 1".to_string()]);
        assert_eq!(d.pending(), 1);
        assert_eq!(collect(&mut d, &[0x55]), vec!["skip 2".to_string()]);
        assert_eq!(d.pending(), 0);
    }

    #[test]
    fn impossible_length_is_rejected_at_the_header() {
        // DEVICE_STATUS header claiming 2 bytes: impossible, so no waiting for them.
        let mut bytes = vec![0xE7, 0x7E, 0x12, 0x01, 0x00, 0x00, 0x01, 0x02];
        bytes.extend_from_slice(&PING);
        let mut d = Decoder::new();
        let out = collect(&mut d, &bytes);
        assert_eq!(
            out,
            vec![
                "badlen 8".to_string(),
                "skip 7".into(),
                format!("frame {:02X?}", PING)
            ]
        );
    }
}

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
//! A candidate whose id is a known message but whose length field cannot be that
//! message's length is rejected at its header, without waiting for `len` more bytes:
//! otherwise one corrupt length byte could hold back up to 255 bytes of good frames.
//! A candidate with an id the ICD does not define is read to its end: if its checksum
//! holds it is a whole frame we cannot interpret (counted as an unknown message and
//! skipped entirely); if not, it was garbage and we advance one byte.

use super::frame::{FrameRef, HEADER_LEN, MAX_FRAME, MessageId, SYNC1, SYNC2, checksum};
use super::message;

/// What the decoder found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event<'a> {
    /// An intact frame of a message the ICD defines.
    Frame(FrameRef<'a>),
    /// Bytes that were not part of any frame.
    Skipped(&'a [u8]),
    /// A candidate frame whose checksum did not match (all of its claimed bytes). Only
    /// its first byte is consumed; the rest is scanned again.
    BadChecksum(&'a [u8]),
    /// A header of a known message whose length field is impossible for it. Only its
    /// first byte is consumed.
    BadLength(&'a [u8]),
    /// An intact frame (checksum good) whose major/minor the ICD does not define.
    UnknownMessage(&'a [u8]),
}

/// Running counts of what the decoder accepted and dropped.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DecoderStats {
    pub frames: u64,
    pub bytes_in: u64,
    /// Bytes discarded outside of any frame (including the first byte of each bad
    /// candidate).
    pub skipped_bytes: u64,
    pub bad_checksum: u64,
    pub bad_length: u64,
    pub unknown_message: u64,
}

impl DecoderStats {
    /// Total number of dropped things (frames and runs of bytes): a quick link-quality number.
    pub fn errors(&self) -> u64 {
        self.bad_checksum + self.bad_length + self.unknown_message
    }
}

/// Streaming decoder; see the module documentation.
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

enum Step {
    /// The candidate's first byte was plain garbage; the run of skipped bytes goes on.
    Garbage,
    /// The candidate was reported (frame or error); scanning resumes at this offset
    /// and the run of skipped bytes starts afresh there.
    Reported(usize),
    /// The rest of the slice, from the candidate on, is an incomplete frame.
    Incomplete,
}

impl Decoder {
    pub fn new() -> Self {
        Decoder {
            buf: [0; MAX_FRAME],
            len: 0,
            stats: DecoderStats::default(),
        }
    }

    pub fn stats(&self) -> DecoderStats {
        self.stats
    }

    /// Bytes held back as the start of an incomplete frame.
    pub fn pending(&self) -> usize {
        self.len
    }

    /// Forgets a partial frame, e.g. after the port was reopened. Counted as skipped.
    pub fn reset(&mut self) {
        self.stats.skipped_bytes += self.len as u64;
        self.len = 0;
    }

    /// Feeds bytes; `on_event` is called for each frame found and each thing dropped.
    pub fn push(&mut self, mut input: &[u8], mut on_event: impl FnMut(Event<'_>)) {
        self.stats.bytes_in += input.len() as u64;
        while self.len > 0 {
            let need = self.need();
            if self.len < need {
                if input.is_empty() {
                    return;
                }
                // Top up only to the next byte that can decide the candidate: the second
                // (sync) byte first, then `need`, which the header may shorten. Taking
                // straight to a `need` computed from fewer bytes would hold on to a
                // candidate that is already known to be garbage when the input runs out,
                // so `pending` and the events would depend on where reads were split.
                let upto = if self.len < 2 { 2 } else { need };
                let take = (upto - self.len).min(input.len());
                self.buf[self.len..self.len + take].copy_from_slice(&input[..take]);
                self.len += take;
                input = &input[take..];
                continue;
            }
            // Re-scan the held bytes in place (no copy of the buffer: this runs at every
            // read boundary); whatever is left over is again an incomplete candidate that
            // starts with the sync byte, moved to the front.
            let n = self.len;
            let done = Self::scan(&mut self.stats, &self.buf[..n], &mut on_event);
            self.buf.copy_within(done..n, 0);
            self.len = n - done;
        }
        let done = Self::scan(&mut self.stats, input, &mut on_event);
        let rest = &input[done..];
        self.buf[..rest.len()].copy_from_slice(rest);
        self.len = rest.len();
    }

    /// How many bytes the held candidate must reach before it can be judged.
    fn need(&self) -> usize {
        let b = &self.buf[..self.len];
        if b.len() >= 2 && b[1] != SYNC2 {
            return b.len();
        }
        if b.len() < HEADER_LEN {
            return HEADER_LEN;
        }
        let len = b[7] as usize;
        match message::lookup(MessageId::new(b[2], b[3])) {
            Some((_, rule)) if !rule.allows(len) => b.len(),
            _ => HEADER_LEN + len + 1,
        }
    }

    /// Scans a contiguous slice and returns how many bytes it consumed; the remainder
    /// (at most one frame) is an incomplete candidate.
    fn scan<'a>(
        stats: &mut DecoderStats,
        data: &'a [u8],
        on_event: &mut impl FnMut(Event<'a>),
    ) -> usize {
        let mut at = 0;
        let mut skip_from = 0;
        loop {
            // Find the next candidate start.
            let start = match data[at..].iter().position(|&b| b == SYNC1) {
                Some(i) => at + i,
                None => {
                    Self::skip(stats, &data[skip_from..], on_event);
                    return data.len();
                }
            };
            match Self::candidate(stats, data, start, on_event, skip_from) {
                Step::Garbage => at = start + 1,
                Step::Reported(next) => {
                    at = next;
                    skip_from = next;
                }
                Step::Incomplete => {
                    Self::skip(stats, &data[skip_from..start], on_event);
                    return start;
                }
            }
        }
    }

    /// Judges the candidate at `start`. Before reporting anything it flushes the run of
    /// skipped bytes that precedes the candidate, so events come out in wire order.
    fn candidate<'a>(
        stats: &mut DecoderStats,
        data: &'a [u8],
        start: usize,
        on_event: &mut impl FnMut(Event<'a>),
        skip_from: usize,
    ) -> Step {
        let rest = &data[start..];
        if rest.len() < 2 {
            return Step::Incomplete;
        }
        if rest[1] != SYNC2 {
            return Step::Garbage;
        }
        if rest.len() < HEADER_LEN {
            return Step::Incomplete;
        }
        let id = MessageId::new(rest[2], rest[3]);
        let len = rest[7] as usize;
        let known = message::lookup(id);
        if let Some((_, rule)) = known
            && !rule.allows(len)
        {
            Self::skip(stats, &data[skip_from..start], on_event);
            stats.bad_length += 1;
            stats.skipped_bytes += 1;
            on_event(Event::BadLength(&rest[..HEADER_LEN]));
            return Step::Reported(start + 1);
        }
        let total = HEADER_LEN + len + 1;
        if rest.len() < total {
            return Step::Incomplete;
        }
        let frame = &rest[..total];
        if checksum(&frame[..total - 1]) != frame[total - 1] {
            Self::skip(stats, &data[skip_from..start], on_event);
            stats.bad_checksum += 1;
            stats.skipped_bytes += 1;
            on_event(Event::BadChecksum(frame));
            return Step::Reported(start + 1);
        }
        Self::skip(stats, &data[skip_from..start], on_event);
        if known.is_some() {
            stats.frames += 1;
            on_event(Event::Frame(FrameRef::new_unchecked(frame)));
        } else {
            stats.unknown_message += 1;
            on_event(Event::UnknownMessage(frame));
        }
        Step::Reported(start + total)
    }

    fn skip<'a>(stats: &mut DecoderStats, bytes: &'a [u8], on_event: &mut impl FnMut(Event<'a>)) {
        if !bytes.is_empty() {
            stats.skipped_bytes += bytes.len() as u64;
            on_event(Event::Skipped(bytes));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PING request, cnt 1, EFIS → VP-X, worked by hand from ICD Tables 1 and 10:
    /// E7^7E^10^00^01^01^00^01^00 = 0x88, inverted = 0x77.
    const PING: [u8; 10] = [0xE7, 0x7E, 0x10, 0x00, 0x01, 0x01, 0x00, 0x01, 0x00, 0x77];

    fn collect(dec: &mut Decoder, bytes: &[u8]) -> Vec<String> {
        let mut out = Vec::new();
        dec.push(bytes, |e| {
            out.push(match e {
                Event::Frame(f) => format!("frame {:02X?}", f.as_bytes()),
                Event::Skipped(b) => format!("skip {}", b.len()),
                Event::BadChecksum(b) => format!("badsum {}", b.len()),
                Event::BadLength(b) => format!("badlen {}", b.len()),
                Event::UnknownMessage(b) => format!("unknown {}", b.len()),
            })
        });
        out
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
        // A corrupt candidate whose claimed length swallows a real frame.
        let mut bytes = vec![0x00, 0xE7, 0x7E, 0x99, 0x00, 0x00, 0x00, 0x00, 0x0A];
        bytes.extend_from_slice(&PING);
        bytes.push(0x55);
        let mut d = Decoder::new();
        let out = collect(&mut d, &bytes);
        assert_eq!(
            out,
            vec![
                "skip 1".to_string(),
                "badsum 19".into(),
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

//! The serial line's own speed: at 57600 baud, 8N1, a byte takes ten bit times, so
//! at most 5760 bytes a second cross in each direction. A pseudo-terminal or a TCP
//! socket carries a whole frame in microseconds; paced, the virtual VP-X's bytes
//! leave (and the page's bytes reach it) no faster than they would through a real
//! cable, so what a page takes against it is what it takes against a unit.
//!
//! Pure: [`LinePacer`] says when each piece of a chunk has crossed the line, on the
//! caller's clock; the sim's reader and writer threads sleep until then.

use std::ops::Range;
use std::time::{Duration, Instant};

/// ICD §3 (RS-232, 57600 baud, 8 data bits, no parity, 1 stop bit): a start bit,
/// eight data bits and a stop bit per byte.
pub const BAUD: u32 = 57_600;
pub const BITS_PER_BYTE: u32 = 10;
/// Bytes a second on the real line: 5760.
pub const BYTES_PER_SECOND: u32 = BAUD / BITS_PER_BYTE;

/// Bytes handed on in one go while pacing: about 1.4 ms of line time, so a reader
/// sees a frame arrive over its real duration, without a wake-up for every byte.
pub const PIECE: usize = 8;

/// One direction of a line: when it is next free, and how long a byte takes.
#[derive(Debug, Clone)]
pub struct LinePacer {
    byte_time: Duration,
    free_at: Option<Instant>,
}

impl LinePacer {
    /// A line carrying `bytes_per_second` (at least 1).
    pub fn new(bytes_per_second: u32) -> Self {
        LinePacer {
            byte_time: Duration::from_secs(1) / bytes_per_second.max(1),
            free_at: None,
        }
    }

    /// How long one byte occupies the line.
    pub fn byte_time(&self) -> Duration {
        self.byte_time
    }

    /// A chunk of `len` bytes handed to the line at `now`: its pieces (ranges into
    /// the chunk, at most [`PIECE`] bytes each) and the instant each piece's last
    /// byte has crossed. The chunk starts when the line is free (at `now`, or when
    /// the bytes before it have crossed), and the line is busy until its end.
    pub fn schedule(&mut self, now: Instant, len: usize) -> Vec<(Range<usize>, Instant)> {
        let start = self.free_at.map_or(now, |t| t.max(now));
        let mut out = Vec::with_capacity(len.div_ceil(PIECE));
        let mut from = 0;
        while from < len {
            let to = (from + PIECE).min(len);
            // From the chunk's start, so rounding never accumulates over pieces.
            out.push((from..to, start + self.byte_time * to as u32));
            from = to;
        }
        self.free_at = Some(start + self.byte_time * len as u32);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn us(d: Duration) -> u128 {
        d.as_micros()
    }

    #[test]
    fn the_line_carries_5760_bytes_a_second() {
        assert_eq!(BYTES_PER_SECOND, 5760);
        let p = LinePacer::new(BYTES_PER_SECOND);
        // 1 s / 5760 = 173.6 µs a byte.
        assert_eq!(us(p.byte_time()), 173);
    }

    #[test]
    fn a_frame_arrives_over_its_real_duration_in_pieces() {
        let t0 = Instant::now();
        let mut p = LinePacer::new(BYTES_PER_SECOND);
        // A DEVICE_STATUS frame: 8 + 66 + 1 = 75 bytes.
        let pieces = p.schedule(t0, 75);
        assert_eq!(pieces.len(), 10, "nine pieces of 8 and one of 3");
        assert_eq!(pieces[0].0, 0..8);
        assert_eq!(pieces[9].0, 72..75);
        assert_eq!(us(pieces[0].1 - t0), 1_388, "8 × 173.61 µs");
        // The last byte is through 75 / 5760 s = 13.02 ms after the first started.
        assert_eq!(us(pieces[9].1 - t0), 13_020);
        assert!(pieces.windows(2).all(|w| w[0].1 < w[1].1));
    }

    #[test]
    fn a_chunk_waits_for_the_line_and_an_idle_line_starts_at_once() {
        let t0 = Instant::now();
        let mut p = LinePacer::new(1000);
        let a = p.schedule(t0, 10);
        assert_eq!(a.last().unwrap().1 - t0, Duration::from_millis(10));
        // Handed over 4 ms later, while the first is still crossing: queued behind it.
        let b = p.schedule(t0 + Duration::from_millis(4), 5);
        assert_eq!(b.last().unwrap().1 - t0, Duration::from_millis(15));
        // Handed over after a quiet spell: starts then, not back in the past.
        let c = p.schedule(t0 + Duration::from_secs(1), 2);
        assert_eq!(
            c.last().unwrap().1 - t0,
            Duration::from_secs(1) + Duration::from_millis(2)
        );
        assert!(p.schedule(t0, 0).is_empty(), "nothing to send, no piece");
    }
}

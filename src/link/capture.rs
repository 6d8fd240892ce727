//! The capture file: every byte in both directions, with when and which way.
//!
//! Format (all integers big-endian):
//!
//! ```text
//! file    = magic record*
//! magic   = "VPXCAP1\n"  (8 bytes)
//!           start_unix_us: u64   wall-clock time of offset 0, for the reader's benefit
//! record  = dir: u8              'R' (0x52) from the unit, 'T' (0x54) to the unit
//!           offset_us: u64       microseconds since the start of the capture
//!           len: u16             1..=4096
//!           bytes: [u8; len]
//! ```
//!
//! Eleven bytes of overhead per read or write; at the VP-X's 5.7 kB/s that is a few
//! kilobytes a minute. The writer flushes at least once a second, so a crash or a
//! pulled cable loses at most the last second. A reader stops cleanly at a record
//! cut short by such a crash and says where.

use std::io::{self, Write};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use super::connection::Crossing;

pub const MAGIC: &[u8; 8] = b"VPXCAP1\n";
pub const MAX_RECORD: usize = 4096;
const FLUSH_EVERY: Duration = Duration::from_secs(1);

/// One record of a capture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Record {
    pub dir: Crossing,
    pub offset: Duration,
    pub bytes: Vec<u8>,
}

/// Writes a capture; see the module documentation for the format.
pub struct CaptureWriter<W: Write> {
    out: io::BufWriter<W>,
    start: Instant,
    last_flush: Instant,
}

impl<W: Write> CaptureWriter<W> {
    pub fn new(out: W, start: Instant) -> io::Result<Self> {
        let mut out = io::BufWriter::new(out);
        let wall = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_micros() as u64);
        out.write_all(MAGIC)?;
        out.write_all(&wall.to_be_bytes())?;
        out.flush()?;
        Ok(CaptureWriter {
            out,
            start,
            last_flush: start,
        })
    }

    /// Appends bytes seen at `at`; long chunks are split into several records.
    pub fn record(&mut self, at: Instant, dir: Crossing, bytes: &[u8]) -> io::Result<()> {
        let offset = at.saturating_duration_since(self.start).as_micros() as u64;
        for chunk in bytes.chunks(MAX_RECORD) {
            self.out.write_all(&[dir_byte(dir)])?;
            self.out.write_all(&offset.to_be_bytes())?;
            self.out.write_all(&(chunk.len() as u16).to_be_bytes())?;
            self.out.write_all(chunk)?;
        }
        if at.saturating_duration_since(self.last_flush) >= FLUSH_EVERY {
            self.flush(at)?;
        }
        Ok(())
    }

    /// Flushes buffered records; call at least once a second when idle.
    pub fn flush(&mut self, at: Instant) -> io::Result<()> {
        self.last_flush = at;
        self.out.flush()
    }
}

fn dir_byte(d: Crossing) -> u8 {
    match d {
        Crossing::Rx => b'R',
        Crossing::Tx => b'T',
    }
}

#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum CaptureError {
    #[error("not a vpx-efis capture (it does not start with {:?})", "VPXCAP1")]
    NotACapture,
    #[error(
        "the capture is cut short at byte {offset}: the last record is incomplete (the recording was interrupted); everything before it was read"
    )]
    Truncated { offset: u64 },
    #[error("the capture is corrupt at byte {offset}: {what}")]
    Corrupt { offset: u64, what: String },
}

/// Whether bytes start like a capture (so `decode` can tell captures from raw bytes).
pub fn is_capture(prefix: &[u8]) -> bool {
    prefix.starts_with(MAGIC)
}

/// Reads a whole capture held in memory. Returns the records read and, if the file
/// did not end cleanly, why; what was read before the problem is kept.
pub fn parse_capture(data: &[u8]) -> (Vec<Record>, Option<CaptureError>, Option<u64>) {
    let mut records = Vec::new();
    if data.len() < 16 || !is_capture(data) {
        let err = if data.len() < 16 && data.starts_with(&MAGIC[..data.len().min(8)]) {
            CaptureError::Truncated {
                offset: data.len() as u64,
            }
        } else {
            CaptureError::NotACapture
        };
        return (records, Some(err), None);
    }
    let start_unix_us = u64::from_be_bytes(data[8..16].try_into().unwrap_or([0; 8]));
    let mut at = 16usize;
    while at < data.len() {
        let last = records.last().map_or(Duration::ZERO, |r: &Record| r.offset);
        match record_at(&data[at..], at as u64, last) {
            Ok(record) => {
                at += 11 + record.bytes.len();
                records.push(record);
            }
            Err(e) => return (records, Some(e), Some(start_unix_us)),
        }
    }
    (records, None, Some(start_unix_us))
}

/// The record that starts a capture's `rest` (byte `at` of the file); its time may
/// not be before the `last` record's.
fn record_at(rest: &[u8], at: u64, last: Duration) -> Result<Record, CaptureError> {
    let corrupt = |what: String| CaptureError::Corrupt { offset: at, what };
    let truncated = CaptureError::Truncated { offset: at };
    if rest.len() < 11 {
        return Err(truncated);
    }
    let dir = match rest[0] {
        b'R' => Crossing::Rx,
        b'T' => Crossing::Tx,
        b => return Err(corrupt(format!("unknown direction byte {b:#04x}"))),
    };
    let offset = Duration::from_micros(u64::from_be_bytes(rest[1..9].try_into().unwrap_or([0; 8])));
    let len = u16::from_be_bytes([rest[9], rest[10]]) as usize;
    if len == 0 || len > MAX_RECORD {
        return Err(corrupt(format!(
            "record length {len} is outside 1..={MAX_RECORD}"
        )));
    }
    if offset < last {
        return Err(corrupt("time goes backwards".to_string()));
    }
    let bytes = rest.get(11..11 + len).ok_or(truncated)?;
    Ok(Record {
        dir,
        offset,
        bytes: bytes.to_vec(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Vec<u8> {
        let t0 = Instant::now();
        let mut buf = Vec::new();
        {
            let mut w = CaptureWriter::new(&mut buf, t0).unwrap();
            w.record(
                t0 + Duration::from_millis(5),
                Crossing::Rx,
                &[0xE7, 0x7E, 1],
            )
            .unwrap();
            w.record(t0 + Duration::from_millis(7), Crossing::Tx, &[9, 8])
                .unwrap();
            w.flush(t0).unwrap();
        }
        buf
    }

    #[test]
    fn layout_is_as_documented() {
        let buf = sample();
        assert_eq!(&buf[..8], b"VPXCAP1\n");
        // First record: 'R', offset 5000 µs, length 3.
        assert_eq!(&buf[16..27], &[b'R', 0, 0, 0, 0, 0, 0, 0x13, 0x88, 0, 3]);
        assert_eq!(&buf[27..30], &[0xE7, 0x7E, 1]);
        let (recs, err, _) = parse_capture(&buf);
        assert_eq!(err, None);
        assert_eq!(recs.len(), 2);
        assert_eq!(
            recs[1],
            Record {
                dir: Crossing::Tx,
                offset: Duration::from_millis(7),
                bytes: vec![9, 8]
            }
        );
    }

    #[test]
    fn a_capture_cut_at_any_byte_keeps_what_came_before_and_says_so() {
        let buf = sample();
        for cut in 0..buf.len() {
            let (recs, err, _) = parse_capture(&buf[..cut]);
            let complete = [16 + 11 + 3, 16 + 11 + 3 + 11 + 2]
                .iter()
                .filter(|&&end| end <= cut)
                .count();
            assert_eq!(recs.len(), complete, "cut at {cut}");
            if cut < buf.len() && cut != 30 && cut != 16 {
                assert!(
                    matches!(err, Some(CaptureError::Truncated { .. })),
                    "cut at {cut}: {err:?}"
                );
            }
        }
    }

    #[test]
    fn corruption_is_an_error_not_a_panic() {
        let mut buf = sample();
        buf[16] = b'X';
        let (recs, err, _) = parse_capture(&buf);
        assert!(recs.is_empty());
        assert!(
            matches!(err, Some(CaptureError::Corrupt { offset: 16, .. })),
            "{err:?}"
        );
        assert_eq!(
            parse_capture(b"hello world, not a capture").1,
            Some(CaptureError::NotACapture)
        );
    }
}

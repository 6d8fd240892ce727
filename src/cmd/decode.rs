//! `vpx-efis decode`: a byte capture as one readable line per frame.
//!
//! Input comes from a [`RecordSource`]: chunks of bytes, each with an optional time
//! offset and direction. A raw capture (what `cat /dev/ttyUSB0 > file` gives) has
//! neither, so none is printed; a capture format that records them only needs its own
//! source. Each direction has its own decoder, because bytes of the two directions
//! interleave in a capture but never within one frame.
//!
//! Everything the decoder drops is a line of its own, where it happened, so a bad
//! cable shows as what it did to the stream rather than as missing frames.

use std::fmt::Write as _;
use std::io::{self, BufWriter, Read, Write};
use std::time::Duration;

use clap::Args;
use serde_json::{Map, Value, json};

use crate::protocol::Crossing;
use crate::protocol::describe::{describe, node_label, to_json};
use crate::protocol::frame::{FrameRef, HEADER_LEN, MessageId, checksum};
use crate::protocol::{Decoder, DecoderStats, Event, Packet, message};

/// One chunk of a capture, as it was read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Record {
    /// Offset from the start of the capture, when the capture knows it.
    pub time: Option<Duration>,
    /// Which way the bytes went, when the capture knows it.
    pub direction: Option<Crossing>,
    pub bytes: Vec<u8>,
}

/// Where records come from: a raw byte stream now, a capture file format later.
pub trait RecordSource {
    /// The next chunk, or `None` at the end.
    fn next_record(&mut self) -> io::Result<Option<Record>>;
}

/// A raw byte capture: no times, no directions.
pub struct RawSource<R> {
    reader: R,
    buf: Vec<u8>,
}

impl<R: Read> RawSource<R> {
    pub fn new(reader: R) -> Self {
        RawSource {
            reader,
            buf: vec![0; 64 * 1024],
        }
    }
}

impl<R: Read> RecordSource for RawSource<R> {
    fn next_record(&mut self) -> io::Result<Option<Record>> {
        loop {
            match self.reader.read(&mut self.buf) {
                Ok(0) => return Ok(None),
                Ok(n) => {
                    return Ok(Some(Record {
                        time: None,
                        direction: None,
                        bytes: self.buf[..n].to_vec(),
                    }));
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            }
        }
    }
}

/// Totals over the whole capture, all directions together.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Summary {
    pub decoder: DecoderStats,
    /// Intact frames of a known message whose payload did not decode.
    pub undecodable: u64,
    /// Bytes of a frame still incomplete when the capture ended.
    pub incomplete_bytes: u64,
}

fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 3);
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{b:02X}");
    }
    s
}

fn direction_label(d: Crossing) -> &'static str {
    match d {
        Crossing::Rx => "rx",
        Crossing::Tx => "tx",
    }
}

/// One output line before formatting: what happened, with the record's columns.
enum Line<'a> {
    Packet(Packet),
    Undecodable(FrameRef<'a>, crate::protocol::Error),
    Skipped(&'a [u8]),
    BadChecksum(&'a [u8]),
    BadLength(&'a [u8]),
    Unknown(&'a [u8]),
    Incomplete(&'a [u8]),
}

struct Writer<W: Write> {
    out: W,
    json: bool,
}

impl<W: Write> Writer<W> {
    fn line(
        &mut self,
        time: Option<Duration>,
        dir: Option<Crossing>,
        line: Line<'_>,
    ) -> io::Result<()> {
        if self.json {
            let mut obj = Map::new();
            if let Some(t) = time {
                obj.insert("time".into(), json!(t.as_secs_f64()));
            }
            if let Some(d) = dir {
                obj.insert("dir".into(), json!(direction_label(d)));
            }
            match line {
                Line::Packet(p) => {
                    obj.insert("name".into(), json!(p.message.name()));
                    obj.insert("cnt".into(), json!(p.cnt));
                    obj.insert("src".into(), json!(p.src.to_byte()));
                    obj.insert("dst".into(), json!(p.dst.to_byte()));
                    if let Value::Object(fields) = to_json(&p.message) {
                        obj.extend(fields);
                    }
                }
                Line::Undecodable(f, e) => {
                    let h = f.header();
                    obj.insert("name".into(), json!("UNDECODABLE"));
                    obj.insert("message".into(), json!(name_of(h.id)));
                    obj.insert("cnt".into(), json!(h.cnt));
                    obj.insert("src".into(), json!(h.src.to_byte()));
                    obj.insert("dst".into(), json!(h.dst.to_byte()));
                    obj.insert("error".into(), json!(e.to_string()));
                    obj.insert("hex".into(), json!(hex(f.as_bytes())));
                }
                Line::Skipped(b) => {
                    obj.insert("name".into(), json!("SKIPPED"));
                    obj.insert("bytes".into(), json!(b.len()));
                    obj.insert("hex".into(), json!(hex(b)));
                }
                Line::BadChecksum(b) => {
                    let (computed, found) = sums(b);
                    obj.insert("name".into(), json!("BAD_CHECKSUM"));
                    obj.insert("computed".into(), json!(computed));
                    obj.insert("found".into(), json!(found));
                    obj.insert("hex".into(), json!(hex(b)));
                }
                Line::BadLength(b) => {
                    let id = MessageId::new(b[2], b[3]);
                    obj.insert("name".into(), json!("BAD_LENGTH"));
                    obj.insert("message".into(), json!(name_of(id)));
                    obj.insert("len".into(), json!(b[HEADER_LEN - 1]));
                    obj.insert("hex".into(), json!(hex(b)));
                }
                Line::Unknown(b) => {
                    obj.insert("name".into(), json!("UNKNOWN_MESSAGE"));
                    obj.insert("major".into(), json!(b[2]));
                    obj.insert("minor".into(), json!(b[3]));
                    obj.insert("hex".into(), json!(hex(b)));
                }
                Line::Incomplete(b) => {
                    obj.insert("name".into(), json!("INCOMPLETE"));
                    obj.insert("bytes".into(), json!(b.len()));
                    obj.insert("hex".into(), json!(hex(b)));
                }
            }
            writeln!(self.out, "{}", Value::Object(obj))
        } else {
            let mut prefix = String::new();
            if let Some(t) = time {
                let _ = write!(prefix, "{:>10.3} ", t.as_secs_f64());
            }
            if let Some(d) = dir {
                let _ = write!(prefix, "{} ", direction_label(d));
            }
            let text = match line {
                Line::Packet(p) => format!(
                    "{} cnt {} {}→{}: {}",
                    p.message.name(),
                    p.cnt,
                    node_label(p.src),
                    node_label(p.dst),
                    describe(&p.message)
                ),
                Line::Undecodable(f, e) => {
                    let h = f.header();
                    format!(
                        "undecodable {} cnt {} {}→{}: {e}: {}",
                        name_of(h.id),
                        h.cnt,
                        node_label(h.src),
                        node_label(h.dst),
                        hex(f.as_bytes())
                    )
                }
                Line::Skipped(b) => format!("skipped {} bytes: {}", b.len(), hex(b)),
                Line::BadChecksum(b) => {
                    let (computed, found) = sums(b);
                    format!(
                        "bad checksum (computed {computed:#04x}, frame carries {found:#04x}), \
                         resyncing one byte on: {}",
                        hex(b)
                    )
                }
                Line::BadLength(b) => {
                    let id = MessageId::new(b[2], b[3]);
                    let allowed = match message::lookup(id) {
                        Some((_, rule)) => format!("the ICD gives {rule}"),
                        None => format!(
                            "no message of the ICD is longer than {}",
                            message::MAX_MESSAGE_LEN
                        ),
                    };
                    format!(
                        "bad length: {} header claims {} bytes, {allowed}: {}",
                        name_of(id),
                        b[HEADER_LEN - 1],
                        hex(b)
                    )
                }
                Line::Unknown(b) => {
                    format!("unknown message {}: {}", MessageId::new(b[2], b[3]), hex(b))
                }
                Line::Incomplete(b) => {
                    format!("incomplete frame at end: {} bytes: {}", b.len(), hex(b))
                }
            };
            writeln!(self.out, "{prefix}{text}")
        }
    }

    fn summary(&mut self, s: &Summary) -> io::Result<()> {
        let d = &s.decoder;
        if self.json {
            let v = json!({
                "name": "SUMMARY",
                "bytes_in": d.bytes_in,
                "frames": d.frames,
                "undecodable": s.undecodable,
                "skipped_bytes": d.skipped_bytes,
                "bad_checksum": d.bad_checksum,
                "bad_length": d.bad_length,
                "unknown_message": d.unknown_message,
                "incomplete_bytes": s.incomplete_bytes,
            });
            writeln!(self.out, "{v}")
        } else {
            writeln!(
                self.out,
                "summary: {} bytes in, {} frames ({} undecodable), {} bytes skipped, \
                 {} bad checksum, {} bad length, {} unknown message, {} bytes incomplete at end",
                d.bytes_in,
                d.frames,
                s.undecodable,
                d.skipped_bytes,
                d.bad_checksum,
                d.bad_length,
                d.unknown_message,
                s.incomplete_bytes
            )
        }
    }
}

fn name_of(id: MessageId) -> String {
    message::lookup(id).map_or_else(|| id.to_string(), |(n, _)| n.to_string())
}

/// Computed and carried checksums of a candidate frame.
fn sums(b: &[u8]) -> (u8, u8) {
    match b.split_last() {
        Some((&found, body)) => (checksum(body), found),
        None => (0, 0),
    }
}

fn add(total: &mut DecoderStats, s: DecoderStats) {
    total.frames += s.frames;
    total.bytes_in += s.bytes_in;
    total.skipped_bytes += s.skipped_bytes;
    total.bad_checksum += s.bad_checksum;
    total.bad_length += s.bad_length;
    total.unknown_message += s.unknown_message;
    total.truncated_bytes += s.truncated_bytes;
}

/// Decodes every record of `source` and writes one line per event, then the summary.
/// At the end each direction's decoder is finished: the bytes it held are scanned
/// again, so frames after a false header still come out, stamped with the time of the
/// last record they arrived in.
pub fn decode(source: &mut dyn RecordSource, json: bool, out: impl Write) -> io::Result<Summary> {
    let mut w = Writer { out, json };
    // At most three (none, rx, tx), in order of first appearance so the end-of-capture
    // lines come out in a stable order; each with the time of its last record.
    let mut decoders: Vec<(Option<Crossing>, Decoder, Option<Duration>)> = Vec::new();
    let mut undecodable = 0u64;
    while let Some(rec) = source.next_record()? {
        let i = match decoders.iter().position(|(d, _, _)| *d == rec.direction) {
            Some(i) => i,
            None => {
                decoders.push((rec.direction, Decoder::new(), None));
                decoders.len() - 1
            }
        };
        let (_, dec, last) = &mut decoders[i];
        *last = rec.time;
        let mut result = Ok(());
        dec.push(&rec.bytes, |e| {
            if result.is_ok() {
                result = w.line(rec.time, rec.direction, line(e, &mut undecodable));
            }
        });
        result?;
    }
    for (dir, dec, last) in &mut decoders {
        let mut result = Ok(());
        dec.finish(|e| {
            if result.is_ok() {
                result = w.line(*last, *dir, line(e, &mut undecodable));
            }
        });
        result?;
    }
    let mut summary = Summary {
        undecodable,
        ..Summary::default()
    };
    for (_, dec, _) in &decoders {
        add(&mut summary.decoder, dec.stats());
    }
    summary.incomplete_bytes = summary.decoder.truncated_bytes;
    w.summary(&summary)?;
    w.out.flush()?;
    Ok(summary)
}

/// The output line for one decoder event.
fn line<'a>(e: Event<'a>, undecodable: &mut u64) -> Line<'a> {
    match e {
        Event::Frame(f) => match Packet::parse(&f) {
            Ok(p) => Line::Packet(p),
            Err(err) => {
                *undecodable += 1;
                Line::Undecodable(f, err)
            }
        },
        Event::Skipped(b) => Line::Skipped(b),
        Event::BadChecksum(b) => Line::BadChecksum(b),
        Event::BadLength(b) => Line::BadLength(b),
        Event::UnknownMessage(b) => Line::Unknown(b),
        Event::Truncated(b) => Line::Incomplete(b),
    }
}

#[derive(Debug, Args)]
pub struct DecodeArgs {
    /// Capture file, or `-` (the default) for standard input.
    #[arg(default_value = "-")]
    pub file: String,
    /// One JSON object per line.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: DecodeArgs) -> anyhow::Result<()> {
    let reader: Box<dyn Read> = if args.file == "-" {
        Box::new(io::stdin().lock())
    } else {
        let f = std::fs::File::open(&args.file)
            .map_err(|e| anyhow::anyhow!("cannot open {}: {e}", args.file))?;
        Box::new(f)
    };
    // A vpx-efis capture (`--record`) brings its own times and directions.
    let mut reader = reader;
    let mut head = Vec::new();
    (&mut reader).take(8).read_to_end(&mut head)?;
    if crate::link::is_capture(&head) {
        return decode_capture(head, reader, args.json);
    }
    let reader = io::Cursor::new(head).chain(reader);
    let stdout = io::stdout().lock();
    match decode(
        &mut RawSource::new(reader),
        args.json,
        BufWriter::new(stdout),
    ) {
        Ok(_) => Ok(()),
        // `vpx-efis decode cap | head` is normal use, not an error.
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(e.into()),
    }
}

/// The records of a vpx-efis capture file (see `link::capture` for the format).
pub struct CaptureSource(std::vec::IntoIter<crate::link::Record>);

impl CaptureSource {
    pub fn new(records: Vec<crate::link::Record>) -> Self {
        CaptureSource(records.into_iter())
    }
}

impl RecordSource for CaptureSource {
    fn next_record(&mut self) -> io::Result<Option<Record>> {
        Ok(self.0.next().map(|r| Record {
            time: Some(r.offset),
            direction: Some(r.dir),
            bytes: r.bytes,
        }))
    }
}

/// Decodes a capture: everything up to a cut or damage, then says what stopped it (a
/// cut is a note, since a crash or pulled cable leaves one; damage is an error).
fn decode_capture(head: Vec<u8>, mut rest: impl Read, json: bool) -> anyhow::Result<()> {
    let mut data = head;
    rest.read_to_end(&mut data)?;
    let (records, problem, _) = crate::link::parse_capture(&data);
    let stdout = io::stdout().lock();
    match decode(
        &mut CaptureSource::new(records),
        json,
        BufWriter::new(stdout),
    ) {
        Ok(_) => {}
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => return Ok(()),
        Err(e) => return Err(e.into()),
    }
    match problem {
        None => Ok(()),
        Some(e @ crate::link::CaptureError::Truncated { .. }) => {
            eprintln!("vpx-efis decode: note: {e}");
            Ok(())
        }
        Some(e) => Err(e.into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A source with times and directions, as a capture format will give.
    struct Recs(std::vec::IntoIter<Record>);

    impl RecordSource for Recs {
        fn next_record(&mut self) -> io::Result<Option<Record>> {
            Ok(self.0.next())
        }
    }

    /// PING request, cnt 1, EFIS → VP-X: E7^7E^10^00^01^01^00^01^00 = 0x88, !0x88 = 0x77.
    const PING_REQ: [u8; 10] = [0xE7, 0x7E, 0x10, 0x00, 0x01, 0x01, 0x00, 0x01, 0x00, 0x77];
    /// PING response, cnt 1, VP-X → EFIS, ack 1: same XOR with src/dst swapped (no
    /// change) and 0x01 for the payload: 0x88 ^ 0x01 = 0x89, !0x89 = 0x76.
    const PING_ACK: [u8; 10] = [0xE7, 0x7E, 0x10, 0x00, 0x01, 0x00, 0x01, 0x01, 0x01, 0x76];

    #[test]
    fn directions_get_their_own_decoder_and_columns() {
        // The request is split across two tx records with an rx frame between them:
        // one shared decoder would see garbage, per-direction decoders see both frames.
        let recs = vec![
            Record {
                time: Some(Duration::from_millis(0)),
                direction: Some(Crossing::Tx),
                bytes: PING_REQ[..4].to_vec(),
            },
            Record {
                time: Some(Duration::from_millis(5)),
                direction: Some(Crossing::Rx),
                bytes: PING_ACK.to_vec(),
            },
            Record {
                time: Some(Duration::from_millis(7)),
                direction: Some(Crossing::Tx),
                bytes: PING_REQ[4..].to_vec(),
            },
        ];
        let mut out = Vec::new();
        let s = decode(&mut Recs(recs.into_iter()), false, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[..2],
            [
                "     0.005 rx PING cnt 1 VP-X→EFIS: ack flag 1 (response)",
                "     0.007 tx PING cnt 1 EFIS→VP-X: ack flag 0 (request)",
            ]
        );
        assert_eq!((s.decoder.frames, s.decoder.skipped_bytes), (2, 0));
    }
}

//! The link's threads: a supervisor that opens the port, reads and decodes, and
//! reopens it after a failure; and a writer that owns the write half.

use std::io::{self, Read, Write};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, Sender, unbounded};

use crate::protocol::decoder::{Decoder, DecoderStats, Event};
use crate::protocol::frame::MAX_FRAME;
use crate::protocol::{Error, Packet};
use crate::transient::is_transient;

/// Opens (or reopens) the byte stream: a read half, a write half, and a name to show.
pub type Connector =
    Box<dyn FnMut() -> io::Result<(Box<dyn Read + Send>, Box<dyn Write + Send>, String)> + Send>;

/// How long the supervisor waits between attempts to reopen a port.
pub const RECONNECT_INTERVAL: Duration = Duration::from_millis(500);

/// One byte on the ICD's line (§3.2.1: 57600 baud, 8N1, ten bits a byte): 173.6 µs.
const LINE_BYTE_TIME: Duration = Duration::from_nanos(1_000_000_000 * 10 / 57_600);

pub use crate::protocol::Crossing;

/// What the decoder made of received bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RxItem {
    Packet(Packet),
    /// An intact frame of a known message whose payload does not decode (wrong length
    /// for it, or a field outside its range).
    Malformed(Error),
    Skipped,
    BadChecksum,
    BadLength,
    UnknownMessage,
}

/// Everything the link sees, reported in order on the link's own threads.
#[derive(Debug, Clone)]
pub enum LinkEvent {
    Connected {
        port: String,
    },
    /// The open port failed (read error, end of file); the link is reopening it.
    Disconnected {
        reason: String,
    },
    /// An attempt to open the port failed; reported when the reason changes.
    OpenFailed {
        reason: String,
    },
    /// Raw bytes in either direction, as they crossed the wire (for recording).
    Bytes {
        at: Instant,
        dir: Crossing,
        bytes: Vec<u8>,
    },
    /// One decoded item with the bytes it was made from.
    Rx {
        at: Instant,
        item: RxItem,
        raw: Vec<u8>,
        stats: DecoderStats,
    },
    /// A frame written to the port.
    Tx {
        at: Instant,
        packet: Option<Packet>,
        raw: Vec<u8>,
    },
    /// A write failed or there is no open port: whatever was being sent did not go out.
    WriteError {
        at: Instant,
        reason: String,
    },
}

#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SendError {
    #[error("the link has shut down")]
    Closed,
}

enum Outgoing {
    Packet(Packet),
    Port(Option<Box<dyn Write + Send>>),
    Shutdown,
}

/// A cheap, cloneable way to send on the link from any thread.
#[derive(Clone)]
pub struct LinkHandle {
    tx: Sender<Outgoing>,
}

impl LinkHandle {
    /// Queues a packet for the writer; it reaches the wire as soon as the writer runs.
    pub fn send(&self, packet: Packet) -> Result<(), SendError> {
        self.tx
            .send(Outgoing::Packet(packet))
            .map_err(|_| SendError::Closed)
    }
}

type Sink = Arc<dyn Fn(LinkEvent) + Send + Sync>;

/// A running link. Dropping it (or [`Link::shutdown`]) stops its threads.
pub struct Link {
    handle: LinkHandle,
    stop: Arc<AtomicBool>,
    threads: Vec<JoinHandle<()>>,
}

impl Link {
    /// Starts the supervisor and writer threads. `on_event` is called from both.
    pub fn start(
        connector: Connector,
        on_event: impl Fn(LinkEvent) + Send + Sync + 'static,
    ) -> Link {
        let sink: Sink = Arc::new(on_event);
        let (tx, rx) = unbounded();
        let stop = Arc::new(AtomicBool::new(false));
        let writer = {
            let sink = sink.clone();
            std::thread::Builder::new()
                .name("link-writer".into())
                .spawn(move || writer_loop(rx, sink))
                .expect("spawning the link writer thread")
        };
        let supervisor = {
            let (sink, stop, tx) = (sink.clone(), stop.clone(), tx.clone());
            std::thread::Builder::new()
                .name("link-reader".into())
                .spawn(move || supervise(connector, sink, stop, tx))
                .expect("spawning the link reader thread")
        };
        Link {
            handle: LinkHandle { tx },
            stop,
            threads: vec![writer, supervisor],
        }
    }

    pub fn handle(&self) -> LinkHandle {
        self.handle.clone()
    }

    /// Stops and joins the threads. Anything already queued is written first.
    pub fn shutdown(mut self) {
        self.stop_threads();
    }

    fn stop_threads(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        let _ = self.handle.tx.send(Outgoing::Shutdown);
        for t in self.threads.drain(..) {
            let _ = t.join();
        }
    }
}

impl Drop for Link {
    fn drop(&mut self) {
        self.stop_threads();
    }
}

fn writer_loop(rx: Receiver<Outgoing>, sink: Sink) {
    let mut port: Option<Box<dyn Write + Send>> = None;
    let mut frame = [0u8; MAX_FRAME];
    for msg in rx {
        let (packet, bytes): (Option<Packet>, Vec<u8>) = match msg {
            Outgoing::Shutdown => break,
            Outgoing::Port(p) => {
                port = p;
                continue;
            }
            Outgoing::Packet(p) => {
                let n = p.emit_into(&mut frame);
                (Some(p), frame[..n].to_vec())
            }
        };
        let at = Instant::now();
        let result = match port.as_mut() {
            None => Err(io::Error::new(io::ErrorKind::NotConnected, "no open port")),
            Some(w) => w.write_all(&bytes).and_then(|_| w.flush()),
        };
        match result {
            Ok(()) => {
                sink(LinkEvent::Bytes {
                    at,
                    dir: Crossing::Tx,
                    bytes: bytes.clone(),
                });
                sink(LinkEvent::Tx {
                    at,
                    packet,
                    raw: bytes,
                });
            }
            Err(e) => {
                // The port is kept: the stop message a write error triggers must still
                // be tried on it. Only the supervisor, which sees the read side fail,
                // replaces the port.
                sink(LinkEvent::WriteError {
                    at,
                    reason: e.to_string(),
                });
            }
        }
    }
}

fn supervise(
    mut connector: Connector,
    sink: Sink,
    stop: Arc<AtomicBool>,
    writer: Sender<Outgoing>,
) {
    let mut decoder = Decoder::new();
    let mut last_open_error = String::new();
    while !stop.load(Ordering::SeqCst) {
        match connector() {
            Ok((mut reader, w, name)) => {
                last_open_error.clear();
                let _ = writer.send(Outgoing::Port(Some(w)));
                sink(LinkEvent::Connected { port: name });
                let reason = read_until_failure(&mut *reader, &mut decoder, &sink, &stop);
                let _ = writer.send(Outgoing::Port(None));
                // The stream ended: frames held back as a possible longer frame are
                // still real (they arrived), so they come out before the news.
                decode_end(&mut decoder, Instant::now(), &sink);
                if let Some(reason) = reason {
                    sink(LinkEvent::Disconnected { reason });
                } else {
                    return;
                }
            }
            Err(e) => {
                let reason = e.to_string();
                if reason != last_open_error {
                    sink(LinkEvent::OpenFailed {
                        reason: reason.clone(),
                    });
                    last_open_error = reason;
                }
            }
        }
        sleep_unless_stopped(RECONNECT_INTERVAL, &stop);
    }
}

fn sleep_unless_stopped(d: Duration, stop: &AtomicBool) {
    let end = Instant::now() + d;
    while !stop.load(Ordering::SeqCst) && Instant::now() < end {
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Reads and decodes until the port fails (returns the reason) or we are stopped (None).
fn read_until_failure(
    reader: &mut dyn Read,
    decoder: &mut Decoder,
    sink: &Sink,
    stop: &AtomicBool,
) -> Option<String> {
    let mut buf = [0u8; 1024];
    loop {
        if stop.load(Ordering::SeqCst) {
            return None;
        }
        match reader.read(&mut buf) {
            Ok(0) => return Some("the port reported end of file".into()),
            Ok(n) => {
                let at = Instant::now();
                sink(LinkEvent::Bytes {
                    at,
                    dir: Crossing::Rx,
                    bytes: buf[..n].to_vec(),
                });
                decode_chunk(decoder, &buf[..n], at, sink);
                // A frame is still crossing the line: read again once the rest of it
                // can be there, not for each piece a serial port hands over (at most
                // a frame's 13 ms; on a faster link a frame rarely arrives in parts).
                // Nothing is later for it: the frame cannot be judged before then.
                // An idle page read a paced line about 50 times a second for 13
                // frames; this halves that.
                let rest = decoder.awaiting();
                if rest > 0 {
                    std::thread::sleep(LINE_BYTE_TIME * rest as u32);
                }
            }
            // A replay's last record: the port stays, the byte stream is over.
            Err(e) if super::pipe::is_stream_end(&e) => decode_end(decoder, Instant::now(), sink),
            Err(e) if is_transient(&e) => {}
            Err(e) => return Some(e.to_string()),
        }
    }
}

/// Decodes one chunk into events. Public to the crate so replay can reuse it.
pub(crate) fn decode_chunk(decoder: &mut Decoder, bytes: &[u8], at: Instant, sink: &Sink) {
    report(decoder, at, sink, |d, on| d.push(bytes, on));
}

/// The byte stream ended (the port closed, a replay ran out): whatever the decoder
/// held is scanned again, so no intact frame among it is lost.
pub(crate) fn decode_end(decoder: &mut Decoder, at: Instant, sink: &Sink) {
    report(decoder, at, sink, |d, on| d.finish(on));
}

fn report(
    decoder: &mut Decoder,
    at: Instant,
    sink: &Sink,
    run: impl FnOnce(&mut Decoder, &mut dyn FnMut(Event<'_>)),
) {
    let mut items: Vec<(RxItem, Vec<u8>)> = Vec::new();
    run(decoder, &mut |e| {
        items.push(match e {
            Event::Frame(f) => match Packet::parse(&f) {
                Ok(p) => (RxItem::Packet(p), f.as_bytes().to_vec()),
                Err(err) => (RxItem::Malformed(err), f.as_bytes().to_vec()),
            },
            Event::Skipped(b) | Event::Truncated(b) => (RxItem::Skipped, b.to_vec()),
            Event::BadChecksum(b) => (RxItem::BadChecksum, b.to_vec()),
            Event::BadLength(b) => (RxItem::BadLength, b.to_vec()),
            Event::UnknownMessage(b) => (RxItem::UnknownMessage, b.to_vec()),
        })
    });
    let stats = decoder.stats();
    for (item, raw) in items {
        sink(LinkEvent::Rx {
            at,
            item,
            raw,
            stats,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::{duplex_pipe, pipe_connector};
    use crate::protocol::message::{DevicePower, Ping};
    use std::sync::Mutex;

    /// A link on a pipe, connected: the link, every event it has sent, and the
    /// unit's end of the pipe.
    fn connected() -> (Link, Arc<Mutex<Vec<LinkEvent>>>, crate::link::PipeEnd) {
        let (ours, theirs) = duplex_pipe(Duration::from_millis(20));
        let store = Arc::new(Mutex::new(Vec::new()));
        let s = store.clone();
        let link = Link::start(pipe_connector(ours, "pipe"), move |e| {
            s.lock().unwrap().push(e)
        });
        assert!(wait_for(&store, |e| matches!(
            e,
            LinkEvent::Connected { .. }
        )));
        (link, store, theirs)
    }

    fn wait_for(store: &Mutex<Vec<LinkEvent>>, pred: impl Fn(&LinkEvent) -> bool) -> bool {
        let end = Instant::now() + Duration::from_secs(3);
        while Instant::now() < end {
            if store.lock().unwrap().iter().any(&pred) {
                return true;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        false
    }

    #[test]
    fn sends_frames_and_decodes_what_arrives() {
        let (link, store, mut theirs) = connected();
        link.handle()
            .send(Packet::request(
                7,
                DevicePower {
                    device_id: 9,
                    on: true,
                },
            ))
            .unwrap();
        let mut got = [0u8; 11];
        theirs.reader.read_exact(&mut got).unwrap();
        // DEVICE_POWER 9 on, cnt 7, EFIS→VP-X (ICD Tables 1, 29), checksum by hand:
        // E7^7E^13^00^07^01^00^02^09^01 = 0x86, inverted = 0x79.
        assert_eq!(
            got,
            [
                0xE7, 0x7E, 0x13, 0x00, 0x07, 0x01, 0x00, 0x02, 0x09, 0x01, 0x79
            ]
        );
        // A PING reply split in two, with garbage before it.
        let reply = Packet::from_vpx(7, Ping { ack: true }).to_bytes();
        theirs.writer.write_all(&[0x00, 0x11]).unwrap();
        theirs.writer.write_all(&reply[..4]).unwrap();
        theirs.writer.write_all(&reply[4..]).unwrap();
        assert!(wait_for(
            &store,
            |e| matches!(e, LinkEvent::Rx { item: RxItem::Packet(p), .. } if p.message == Ping { ack: true }.into())
        ));
        assert!(wait_for(
            &store,
            |e| matches!(e, LinkEvent::Rx { item: RxItem::Skipped, raw, .. } if raw == &[0x00, 0x11])
        ));
        link.shutdown();
    }

    #[test]
    fn when_the_port_closes_the_held_bytes_are_scanned_before_the_news() {
        let (link, store, theirs) = connected();
        // A DEVICE_STATUS header claiming its own 66 bytes (possible, so held), and
        // inside what it claims an intact message of an id the ICD does not define
        // (0x16/0x00, no payload; E7^7E^16^00^01^00^01^00 = 0x8F, inverted 0x70).
        let mut w = theirs.writer;
        w.write_all(&[0xE7, 0x7E, 0x12, 0x01, 0x00, 0x00, 0x00, 0x42])
            .unwrap();
        w.write_all(&[0xE7, 0x7E, 0x16, 0x00, 0x01, 0x00, 0x01, 0x00, 0x70])
            .unwrap();
        std::thread::sleep(Duration::from_millis(50));
        assert!(
            !store
                .lock()
                .unwrap()
                .iter()
                .any(|e| matches!(e, LinkEvent::Rx { .. }))
        );
        drop(w);
        assert!(wait_for(&store, |e| matches!(
            e,
            LinkEvent::Disconnected { .. }
        )));
        let events = store.lock().unwrap();
        let rx: Vec<(&RxItem, usize)> = events
            .iter()
            .filter_map(|e| match e {
                LinkEvent::Rx { item, raw, .. } => Some((item, raw.len())),
                _ => None,
            })
            .collect();
        assert!(
            matches!(rx[..], [(RxItem::Skipped, 8), (RxItem::UnknownMessage, 9)]),
            "{rx:?}"
        );
        let unknown_at = events.iter().position(|e| {
            matches!(
                e,
                LinkEvent::Rx {
                    item: RxItem::UnknownMessage,
                    ..
                }
            )
        });
        let gone_at = events
            .iter()
            .position(|e| matches!(e, LinkEvent::Disconnected { .. }));
        assert!(unknown_at < gone_at);
        drop(events);
        link.shutdown();
    }

    #[test]
    fn a_closed_peer_is_reported_and_sending_then_fails_in_words() {
        let (link, store, theirs) = connected();
        drop(theirs);
        assert!(wait_for(&store, |e| matches!(
            e,
            LinkEvent::Disconnected { .. }
        )));
        assert!(wait_for(
            &store,
            |e| matches!(e, LinkEvent::OpenFailed { reason } if reason.contains("cannot be reopened"))
        ));
        link.handle()
            .send(Packet::request(1, Ping { ack: false }))
            .unwrap();
        assert!(wait_for(&store, |e| matches!(
            e,
            LinkEvent::WriteError { .. }
        )));
        link.shutdown();
    }

    #[test]
    fn after_a_write_error_the_next_write_is_still_tried_on_the_port() {
        // The unit's reading end is gone but its writing end is not: our reads go on,
        // our writes fail. The stop message that follows a failed write must still be
        // attempted on the port, not dropped as "no open port".
        let (link, store, theirs) = connected();
        let crate::link::PipeEnd {
            reader,
            writer: _keep_writing_end,
        } = theirs;
        drop(reader);
        link.handle()
            .send(Packet::request(1, Ping { ack: false }))
            .unwrap();
        link.handle()
            .send(Packet::request(2, Ping { ack: false }))
            .unwrap();
        let errors = |store: &Mutex<Vec<LinkEvent>>| {
            store
                .lock()
                .unwrap()
                .iter()
                .filter_map(|e| match e {
                    LinkEvent::WriteError { reason, .. } => Some(reason.clone()),
                    _ => None,
                })
                .collect::<Vec<_>>()
        };
        let end = Instant::now() + Duration::from_secs(3);
        while errors(&store).len() < 2 {
            assert!(Instant::now() < end, "two write errors expected");
            std::thread::sleep(Duration::from_millis(5));
        }
        let reasons = errors(&store);
        assert!(
            reasons.iter().all(|r| !r.contains("no open port")),
            "{reasons:?}"
        );
        link.shutdown();
    }
}

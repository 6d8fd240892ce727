//! An in-process byte pipe with the same shape as a serial port (`Read` with a
//! timeout, `Write`), so the built-in virtual VP-X and the page talk through the same
//! `link` code a real cable uses.

use std::io::{self, Read, Write};
use std::time::Duration;

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, unbounded};

/// The reading end. `read` waits at most `timeout`, then fails with `TimedOut` like a
/// serial port does; it returns `Ok(0)` (end of file) once the writer is gone, and
/// fails once with [`StreamEnded`] where the writer said the stream ended but stays.
pub struct PipeReader {
    rx: Receiver<Vec<u8>>,
    pending: Vec<u8>,
    at: usize,
    timeout: Duration,
}

#[derive(Clone)]
pub struct PipeWriter {
    /// An empty chunk is the end-of-stream mark; `write` never sends one.
    tx: Sender<Vec<u8>>,
}

/// The error a [`PipeReader`] returns, once, where its writer called
/// [`PipeWriter::end_of_stream`]: no more bytes will come, though the pipe stays open
/// (a replay after its last record, whose page goes on seeing silence).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamEnded;

impl std::fmt::Display for StreamEnded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("the byte stream has ended")
    }
}

impl std::error::Error for StreamEnded {}

/// Whether a read failed because the stream ended ([`StreamEnded`]).
pub fn is_stream_end(e: &io::Error) -> bool {
    e.get_ref().is_some_and(|inner| inner.is::<StreamEnded>())
}

impl PipeWriter {
    /// Says no more bytes will come, without closing the pipe.
    pub fn end_of_stream(&mut self) -> io::Result<()> {
        self.tx.send(Vec::new()).map_err(|_| closed())
    }
}

fn closed() -> io::Error {
    io::Error::new(
        io::ErrorKind::BrokenPipe,
        "the other end of the pipe is closed",
    )
}

/// One direction of a pipe.
pub fn pipe_pair(timeout: Duration) -> (PipeWriter, PipeReader) {
    let (tx, rx) = unbounded();
    (
        PipeWriter { tx },
        PipeReader {
            rx,
            pending: Vec::new(),
            at: 0,
            timeout,
        },
    )
}

impl Read for PipeReader {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if self.at >= self.pending.len() {
            match self.rx.recv_timeout(self.timeout) {
                Ok(chunk) if chunk.is_empty() => {
                    return Err(io::Error::other(StreamEnded));
                }
                Ok(chunk) => {
                    self.pending = chunk;
                    self.at = 0;
                }
                Err(RecvTimeoutError::Timeout) => return Err(io::ErrorKind::TimedOut.into()),
                Err(RecvTimeoutError::Disconnected) => return Ok(0),
            }
        }
        let n = buf.len().min(self.pending.len() - self.at);
        buf[..n].copy_from_slice(&self.pending[self.at..self.at + n]);
        self.at += n;
        Ok(n)
    }
}

impl Write for PipeWriter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if !buf.is_empty() {
            self.tx.send(buf.to_vec()).map_err(|_| closed())?;
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// One end of a two-way pipe: what a port looks like to the code that holds it.
pub struct PipeEnd {
    pub reader: PipeReader,
    pub writer: PipeWriter,
}

/// Two connected ends: bytes written at one are read at the other.
pub fn duplex_pipe(timeout: Duration) -> (PipeEnd, PipeEnd) {
    let (a_w, b_r) = pipe_pair(timeout);
    let (b_w, a_r) = pipe_pair(timeout);
    (
        PipeEnd {
            reader: a_r,
            writer: a_w,
        },
        PipeEnd {
            reader: b_r,
            writer: b_w,
        },
    )
}

/// A connector over an in-process pipe. A pipe cannot be reopened: once its other end
/// is gone, later attempts fail with a clear reason.
pub fn pipe_connector(end: PipeEnd, name: &str) -> super::Connector {
    let mut end = Some(end);
    let name = name.to_string();
    Box::new(move || match end.take() {
        Some(e) => Ok((
            Box::new(e.reader) as _,
            Box::new(e.writer) as _,
            name.clone(),
        )),
        None => Err(io::Error::new(
            io::ErrorKind::NotConnected,
            "the in-process link has closed and cannot be reopened",
        )),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_arrive_in_order_and_timeout_and_eof_are_distinct() {
        let (mut w, mut r) = pipe_pair(Duration::from_millis(10));
        w.write_all(&[1, 2, 3]).unwrap();
        w.write_all(&[4]).unwrap();
        let mut buf = [0u8; 2];
        assert_eq!(r.read(&mut buf).unwrap(), 2);
        assert_eq!(buf, [1, 2]);
        let mut rest = [0u8; 8];
        assert_eq!(r.read(&mut rest).unwrap(), 1);
        assert_eq!(r.read(&mut rest).unwrap(), 1);
        assert_eq!(rest[0], 4);
        assert_eq!(
            r.read(&mut rest).unwrap_err().kind(),
            io::ErrorKind::TimedOut
        );
        drop(w);
        assert_eq!(r.read(&mut rest).unwrap(), 0);
    }

    #[test]
    fn end_of_stream_is_reported_once_and_the_pipe_stays_open() {
        let (mut w, mut r) = pipe_pair(Duration::from_millis(10));
        // An empty write is not the mark.
        assert_eq!(w.write(&[]).unwrap(), 0);
        w.write_all(&[7]).unwrap();
        w.end_of_stream().unwrap();
        let mut buf = [0u8; 4];
        assert_eq!(r.read(&mut buf).unwrap(), 1);
        assert!(is_stream_end(&r.read(&mut buf).unwrap_err()));
        assert_eq!(
            r.read(&mut buf).unwrap_err().kind(),
            io::ErrorKind::TimedOut
        );
        w.write_all(&[8]).unwrap();
        assert_eq!(r.read(&mut buf).unwrap(), 1);
        assert_eq!(buf[0], 8);
    }
}

//! An in-process byte pipe with the same shape as a serial port (`Read` with a
//! timeout, `Write`), so the built-in virtual VP-X and the page talk through the same
//! `link` code a real cable uses.

use std::io::{self, Read, Write};
use std::time::Duration;

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, unbounded};

/// The reading end. `read` waits at most `timeout`, then fails with `TimedOut` like a
/// serial port does; it returns `Ok(0)` (end of file) once the writer is gone.
pub struct PipeReader {
    rx: Receiver<Vec<u8>>,
    pending: Vec<u8>,
    at: usize,
    timeout: Duration,
}

#[derive(Clone)]
pub struct PipeWriter {
    tx: Sender<Vec<u8>>,
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
        self.tx.send(buf.to_vec()).map_err(|_| {
            io::Error::new(
                io::ErrorKind::BrokenPipe,
                "the other end of the pipe is closed",
            )
        })?;
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
}

//! Opening whatever `--port` names, serial or TCP, through one door, so the page,
//! `backup`, `restore`, `gateway` and `flash` treat both alike.

use std::io;

use super::address::PortAddr;
use super::connection::Connector;
use super::serial::{open_serial, serial_connector};
use super::tcp::{open_tcp, tcp_connector};

/// The connector the link's supervisor calls to open, and reopen, the port.
pub fn port_connector(addr: &PortAddr, baud: u32) -> Connector {
    match addr {
        PortAddr::Serial(path) => serial_connector(path.clone(), baud),
        PortAddr::Tcp { host, port } => tcp_connector(host.clone(), *port),
    }
}

/// Opens the port once and closes it again: a command that is about to take the
/// terminal fails first, with the likely fix in words, if the port cannot be opened.
pub fn check_port(addr: &PortAddr, baud: u32) -> anyhow::Result<()> {
    match addr {
        PortAddr::Serial(path) => drop(open_serial(path, baud)?),
        PortAddr::Tcp { host, port } => drop(open_tcp(host, *port)?),
    }
    Ok(())
}

/// A port as one byte stream (for `flash`, which drives the bootloader itself): a
/// serial port, or a TCP stream whose reads time out like a serial port's.
pub enum RawPort {
    Serial(Box<dyn serialport::SerialPort>),
    Tcp(std::net::TcpStream),
}

pub fn open_raw(addr: &PortAddr, baud: u32) -> anyhow::Result<RawPort> {
    Ok(match addr {
        PortAddr::Serial(path) => RawPort::Serial(open_serial(path, baud)?),
        PortAddr::Tcp { host, port } => RawPort::Tcp(open_tcp(host, *port)?),
    })
}

impl io::Read for RawPort {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        match self {
            RawPort::Serial(p) => p.read(buf),
            RawPort::Tcp(s) => match s.read(buf) {
                // A serial port never ends; a TCP stream that does has lost its bridge.
                Ok(0) if !buf.is_empty() => Err(io::Error::new(
                    io::ErrorKind::ConnectionAborted,
                    "the bridge closed the connection",
                )),
                r => r,
            },
        }
    }
}

impl io::Write for RawPort {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            RawPort::Serial(p) => p.write(buf),
            RawPort::Tcp(s) => s.write(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            RawPort::Serial(p) => p.flush(),
            RawPort::Tcp(s) => s.flush(),
        }
    }
}

impl RawPort {
    /// Bytes received and not yet read, where the port can say without waiting.
    pub fn bytes_waiting(&mut self) -> Option<usize> {
        match self {
            RawPort::Serial(p) => p.bytes_to_read().ok().map(|n| n as usize),
            // A socket cannot say how much it holds, but a non-blocking peek can say
            // whether anything is there, which is all a drain needs: without it every
            // drain would wait out a read timeout, twice a page over a whole flash.
            RawPort::Tcp(s) => {
                let mut buf = [0u8; 1024];
                s.set_nonblocking(true).ok()?;
                let peeked = s.peek(&mut buf);
                // Back to blocking whatever the peek said: a socket left non-blocking
                // would make every later read fail at once.
                s.set_nonblocking(false).ok()?;
                match peeked {
                    Ok(0) => None, // closed: the next read says so
                    Ok(n) => Some(n),
                    Err(e) if e.kind() == io::ErrorKind::WouldBlock => Some(0),
                    Err(_) => None,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::{Read, Write};
    use std::time::{Duration, Instant};

    #[test]
    fn a_tcp_port_says_at_once_whether_bytes_wait_and_a_closed_one_reads_as_an_error() {
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let addr: PortAddr = format!("tcp://{}", listener.local_addr().unwrap())
            .parse()
            .unwrap();
        let mut port = open_raw(&addr, 57_600).unwrap();
        let (mut peer, _) = listener.accept().unwrap();

        let asked = Instant::now();
        assert_eq!(port.bytes_waiting(), Some(0));
        assert!(asked.elapsed() < Duration::from_millis(40), "it waited");

        peer.write_all(&[1, 2, 3]).unwrap();
        let end = Instant::now() + Duration::from_secs(2);
        while port.bytes_waiting() != Some(3) {
            assert!(Instant::now() < end, "the bytes never showed");
        }
        let mut buf = [0u8; 8];
        assert_eq!(port.read(&mut buf).unwrap(), 3);
        // Reads still time out like a serial port's after a peek.
        let e = port.read(&mut buf).unwrap_err();
        assert!(matches!(
            e.kind(),
            io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
        ));

        drop(peer);
        let end = Instant::now() + Duration::from_secs(2);
        while port.bytes_waiting().is_some() {
            assert!(Instant::now() < end, "the close never showed");
        }
        let e = port.read(&mut buf).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::ConnectionAborted);
    }
}

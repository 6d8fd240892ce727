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
            RawPort::Tcp(_) => None,
        }
    }
}

//! Bytes in and out: serial ports, serial over TCP, pseudo-terminals and in-process
//! pipes.
//!
//! A [`Link`] turns bytes into [`Packet`](crate::protocol::Packet)s and packets into
//! bytes. It knows nothing of the model: everything it sees is reported to a callback
//! as a [`LinkEvent`], on the link's own threads. A writer thread owns the write half
//! of the port; a supervisor thread owns the read half and reopens the port when it
//! fails (a pulled USB cable), so the page keeps running and reconnects by itself.

mod address;
mod capture;
mod connection;
mod open;
mod pipe;
mod pty;
pub mod request;
mod serial;
mod tcp;

pub use address::PortAddr;
pub use capture::{CaptureError, CaptureWriter, Record, is_capture, parse_capture};
pub use connection::{Connector, Crossing, Link, LinkEvent, LinkHandle, RxItem, SendError};
pub use open::{RawPort, check_port, open_raw, port_connector};
pub use pipe::{PipeEnd, PipeReader, PipeWriter, duplex_pipe, pipe_connector, pipe_pair};
#[cfg(unix)]
pub use pty::{PtyPair, open_pty_pair};
pub use pty::{PtyUnit, open_pty_unit};
pub use request::{RequestError, SpecError, UnitClient};
pub use serial::{OpenError, PortInfo, list_ports, open_serial, serial_connector};
pub use tcp::{TcpLine, TcpOpenError, serve_line};

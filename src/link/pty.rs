//! Pseudo-terminals: how `vpx-efis sim --pty` offers the virtual VP-X to any program
//! that opens a serial path, and how the end-to-end tests join page and unit.

use serialport::{SerialPort, TTYPort};

/// Both ends of a pseudo-terminal. The unit side holds the master; `path` is the
/// slave's device path that a page opens as a serial port.
pub struct PtyPair {
    pub master: TTYPort,
    /// Kept open so that the master does not see end-of-file (EIO) whenever the page
    /// closes its end; a closed and reopened port must find the unit still there.
    pub slave: TTYPort,
    pub path: String,
}

pub fn open_pty_pair() -> anyhow::Result<PtyPair> {
    let (mut master, slave) =
        TTYPort::pair().map_err(|e| anyhow::anyhow!("cannot create a pseudo-terminal: {e}"))?;
    let path = slave
        .name()
        .ok_or_else(|| anyhow::anyhow!("the pseudo-terminal has no device path"))?;
    master.set_timeout(std::time::Duration::from_millis(50))?;
    Ok(PtyPair {
        master,
        slave,
        path,
    })
}

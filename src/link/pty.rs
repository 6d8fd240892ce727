//! Pseudo-terminals: how `vpx-efis sim --pty` offers the virtual VP-X to any program
//! that opens a serial path, and how the end-to-end tests join page and unit.
//!
//! They exist only on Unix. [`open_pty_unit`] is there on every OS (on others it says
//! what to use instead), so its callers need no `cfg`; [`PtyPair`], with both ends as
//! serial ports, is Unix-only, like the tests that use it.

use std::io::{Read, Write};

#[cfg(unix)]
pub use unix::{PtyPair, open_pty_pair};

/// The unit's side of a pseudo-terminal: what the virtual VP-X reads and writes, and
/// the path a page opens as its serial port.
pub struct PtyUnit {
    pub reader: Box<dyn Read + Send>,
    pub writer: Box<dyn Write + Send>,
    pub path: String,
    /// The slave end, held so that the master does not see end-of-file whenever the
    /// page closes its end: a closed and reopened port must find the unit still there.
    pub keep_open: Box<dyn std::any::Any + Send>,
}

/// A new pseudo-terminal for the virtual VP-X.
pub fn open_pty_unit() -> anyhow::Result<PtyUnit> {
    #[cfg(unix)]
    {
        let pty = open_pty_pair()?;
        let reader = pty
            .master
            .try_clone_native()
            .map_err(|e| anyhow::anyhow!("cannot clone the pseudo-terminal: {e}"))?;
        Ok(PtyUnit {
            reader: Box::new(reader),
            writer: Box::new(pty.master),
            path: pty.path,
            keep_open: Box::new(pty.slave),
        })
    }
    #[cfg(not(unix))]
    {
        anyhow::bail!(
            "pseudo-terminals exist only on Unix (Linux, macOS). Here, serve the virtual VP-X on \
             TCP instead: `vpx-efis sim --tcp 127.0.0.1:0`"
        )
    }
}

#[cfg(unix)]
mod unix {
    use serialport::{SerialPort, TTYPort};

    /// Both ends of a pseudo-terminal. The unit side holds the master; `path` is the
    /// slave's device path that a page opens as a serial port.
    pub struct PtyPair {
        pub master: TTYPort,
        /// Kept open so that the master does not see end-of-file (EIO) whenever the
        /// page closes its end; a closed and reopened port must find the unit still there.
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
}

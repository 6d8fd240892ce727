//! Which I/O errors mean "nothing yet, try again", decided in one place.
//!
//! A serial port's read timeout, a socket's (`TimedOut` on Windows, `WouldBlock` on
//! Unix) and a read cut short by a signal (`Interrupted`) say nothing about the link:
//! every reader loop (the link, the virtual unit's port, the XFSp socket, the
//! firmware updater) goes round again on them, and treats anything else as a fault.

use std::io;

/// Whether `e` is a timeout or an interruption that a reader simply retries.
pub fn is_transient(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock | io::ErrorKind::Interrupted
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timeouts_and_interruptions_are_retried_and_nothing_else_is() {
        for kind in [
            io::ErrorKind::TimedOut,
            io::ErrorKind::WouldBlock,
            io::ErrorKind::Interrupted,
        ] {
            assert!(is_transient(&kind.into()), "{kind:?}");
            // With words of its own (as a port's read timeout comes), still a retry.
            assert!(
                is_transient(&io::Error::new(kind, "read timed out")),
                "{kind:?}"
            );
        }
        for kind in [
            io::ErrorKind::UnexpectedEof,
            io::ErrorKind::BrokenPipe,
            io::ErrorKind::ConnectionReset,
            io::ErrorKind::NotFound,
            io::ErrorKind::PermissionDenied,
            io::ErrorKind::Other,
        ] {
            assert!(!is_transient(&kind.into()), "{kind:?}");
        }
        assert!(!is_transient(&io::Error::other("the cable has gone")));
    }
}

//! Being told to stop from outside: SIGTERM (`kill`), SIGHUP (the terminal window
//! closed, the ssh session dropped) and SIGINT on Unix; Ctrl-C, Ctrl-Break and the
//! console window closing on Windows. Each arrives as a [`Termination`] on a channel,
//! so the page, the gateway and `flash` stop on their own thread, by their normal path
//! (motor stop on the wire first, then the terminal given back), and the process then
//! exits with 128 + the signal's number, as a shell reports a death by that signal.
//!
//! Only the two small `os` modules below differ per OS; everything they decide is a
//! pure function here, tested on every build.

use std::io;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use crossbeam_channel::{Receiver, unbounded};

/// Why the OS asked us to stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Termination {
    /// SIGHUP; on Windows the console window closing, logging off or shutting down.
    HangUp,
    /// SIGINT; Ctrl-C on a Windows console not in raw mode.
    Interrupt,
    /// SIGTERM.
    Terminate,
    /// Ctrl-Break on a Windows console (the C runtime's SIGBREAK).
    Break,
}

impl Termination {
    /// The signal's number. HUP, INT and TERM are 1, 2 and 15 on every Unix (POSIX
    /// fixes them for `kill -s`); SIGBREAK is 21 in the Windows C runtime.
    pub const fn signal_number(self) -> u8 {
        match self {
            Termination::HangUp => 1,
            Termination::Interrupt => 2,
            Termination::Terminate => 15,
            Termination::Break => 21,
        }
    }

    /// The process's exit status: 128 + n (143 for SIGTERM, 129 for SIGHUP).
    pub const fn exit_status(self) -> u8 {
        128 + self.signal_number()
    }

    pub const fn name(self) -> &'static str {
        match self {
            Termination::HangUp => "SIGHUP",
            Termination::Interrupt => "SIGINT",
            Termination::Terminate => "SIGTERM",
            Termination::Break => "Ctrl-Break",
        }
    }

    /// The Unix signal `n`, if it is one we stop for.
    pub const fn from_signal(n: i32) -> Option<Termination> {
        match n {
            1 => Some(Termination::HangUp),
            2 => Some(Termination::Interrupt),
            15 => Some(Termination::Terminate),
            _ => None,
        }
    }

    /// A Windows console control event (`SetConsoleCtrlHandler`'s argument).
    pub const fn from_console_event(event: u32) -> Option<Termination> {
        match event {
            console::CTRL_C_EVENT => Some(Termination::Interrupt),
            console::CTRL_BREAK_EVENT => Some(Termination::Break),
            console::CTRL_CLOSE_EVENT => Some(Termination::HangUp),
            console::CTRL_LOGOFF_EVENT | console::CTRL_SHUTDOWN_EVENT => {
                Some(Termination::Terminate)
            }
            _ => None,
        }
    }

    /// Windows ends the process as soon as the handler of a close, log-off or
    /// shut-down event returns, so for those the handler must hold on until our own
    /// stop path has exited the process. Ctrl-C and Ctrl-Break let the process live on.
    pub const fn console_handler_must_wait(event: u32) -> bool {
        matches!(
            event,
            console::CTRL_CLOSE_EVENT | console::CTRL_LOGOFF_EVENT | console::CTRL_SHUTDOWN_EVENT
        )
    }
}

/// The run was stopped by the OS and has already done its clean stop; `cli::main`
/// turns this into exit status 128 + n.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("stopped by {}", .0.name())]
pub struct Terminated(pub Termination);

/// Starts listening: from now on those signals no longer kill the process, and each
/// arrives on the returned channel.
pub fn listen() -> io::Result<Receiver<Termination>> {
    let (tx, rx) = unbounded();
    os::listen(tx)?;
    Ok(rx)
}

/// A flag the OS's request to stop raises, and what asked, for a command that runs
/// its own loop (`flash`, `gateway`) rather than selecting over [`listen`]'s channel.
#[derive(Debug, Clone, Default)]
pub struct StopFlag {
    pub raised: Arc<AtomicBool>,
    by: Arc<Mutex<Option<Termination>>>,
}

impl StopFlag {
    /// What asked to stop, once the flag is raised.
    pub fn by(&self) -> Option<Termination> {
        *self.by.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Records what asked, then raises the flag: in that order, so a run that sees
    /// the flag and returns always finds the signal for its exit status (the other
    /// order let a quick return find nothing and exit 1). Only the first counts;
    /// returns whether this was it.
    pub fn note(&self, t: Termination) -> bool {
        {
            let mut by = self.by.lock().unwrap_or_else(|p| p.into_inner());
            if by.is_some() {
                return false;
            }
            *by = Some(t);
        }
        self.raised.store(true, Ordering::SeqCst);
        true
    }
}

/// Starts listening ([`listen`]) and a thread `name` that raises the returned flag
/// at the first request to stop; `first` is told of it there.
pub fn stop_flag(name: &str, first: impl Fn(Termination) + Send + 'static) -> io::Result<StopFlag> {
    let terminations = listen()?;
    let flag = StopFlag::default();
    let noted = flag.clone();
    std::thread::Builder::new()
        .name(name.into())
        .spawn(move || {
            while let Ok(t) = terminations.recv() {
                if noted.note(t) {
                    first(t);
                }
            }
        })?;
    Ok(flag)
}

/// Windows' console control events (wincon.h). Here as numbers so the mapping above is
/// tested on every OS; the Windows build checks them against `windows-sys`.
mod console {
    pub const CTRL_C_EVENT: u32 = 0;
    pub const CTRL_BREAK_EVENT: u32 = 1;
    pub const CTRL_CLOSE_EVENT: u32 = 2;
    pub const CTRL_LOGOFF_EVENT: u32 = 5;
    pub const CTRL_SHUTDOWN_EVENT: u32 = 6;
}

#[cfg(unix)]
mod os {
    use std::io;

    use crossbeam_channel::Sender;
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    use signal_hook::iterator::Signals;

    use super::Termination;

    pub fn listen(tx: Sender<Termination>) -> io::Result<()> {
        let mut signals = Signals::new([SIGHUP, SIGINT, SIGTERM])?;
        std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || {
                for n in signals.forever() {
                    if let Some(t) = Termination::from_signal(n)
                        && tx.send(t).is_err()
                    {
                        return;
                    }
                }
            })?;
        Ok(())
    }

    // The numbers `from_signal` relies on are this OS's.
    const _: () = assert!(SIGHUP == 1 && SIGINT == 2 && SIGTERM == 15);
}

#[cfg(windows)]
mod os {
    use std::io;
    use std::sync::Mutex;
    use std::time::Duration;

    use crossbeam_channel::Sender;
    use windows_sys::Win32::System::Console as con;
    use windows_sys::core::BOOL;

    use super::{Termination, console};

    static SENDER: Mutex<Option<Sender<Termination>>> = Mutex::new(None);

    pub fn listen(tx: Sender<Termination>) -> io::Result<()> {
        *SENDER.lock().unwrap_or_else(|p| p.into_inner()) = Some(tx);
        // SAFETY: `handler` is a plain function that lives as long as the process.
        if unsafe { con::SetConsoleCtrlHandler(Some(handler), 1) } == 0 {
            return Err(io::Error::last_os_error());
        }
        Ok(())
    }

    /// Runs on a thread Windows creates for the event.
    unsafe extern "system" fn handler(event: u32) -> BOOL {
        let Some(t) = Termination::from_console_event(event) else {
            return 0; // not ours: the next handler (the default) decides
        };
        if let Ok(slot) = SENDER.lock()
            && let Some(tx) = slot.as_ref()
        {
            let _ = tx.send(t);
        }
        if Termination::console_handler_must_wait(event) {
            // Returning would end the process now; the stop path exits it once the
            // motors are stopped (Windows itself allows about 5 s).
            std::thread::sleep(Duration::from_secs(10));
        }
        1
    }

    const _: () = assert!(
        console::CTRL_C_EVENT == con::CTRL_C_EVENT
            && console::CTRL_BREAK_EVENT == con::CTRL_BREAK_EVENT
            && console::CTRL_CLOSE_EVENT == con::CTRL_CLOSE_EVENT
            && console::CTRL_LOGOFF_EVENT == con::CTRL_LOGOFF_EVENT
            && console::CTRL_SHUTDOWN_EVENT == con::CTRL_SHUTDOWN_EVENT
    );
}

#[cfg(not(any(unix, windows)))]
mod os {
    use std::io;

    use crossbeam_channel::Sender;

    use super::Termination;

    /// No signals to catch: the channel simply never delivers.
    pub fn listen(tx: Sender<Termination>) -> io::Result<()> {
        std::mem::forget(tx);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A command returns as soon as it sees the flag, and its caller then looks for
    /// the signal to name the exit status: the signal must be recorded before the
    /// flag is raised, never after (that order let a quick return exit 1).
    #[test]
    fn the_signal_is_recorded_before_the_flag_is_raised() {
        let flag = StopFlag::default();
        // Someone is reading the record: the signal cannot be written yet, so the
        // flag must not be raised yet either.
        let reading = flag.by.lock().unwrap();
        let noting = {
            let flag = flag.clone();
            std::thread::spawn(move || flag.note(Termination::Terminate))
        };
        std::thread::sleep(std::time::Duration::from_millis(50));
        assert!(
            !flag.raised.load(Ordering::SeqCst),
            "raised before the signal was recorded"
        );
        drop(reading);
        assert!(noting.join().unwrap());
        assert!(flag.raised.load(Ordering::SeqCst));
        assert_eq!(flag.by(), Some(Termination::Terminate));
        // A second signal changes nothing: the first names the exit.
        assert!(!flag.note(Termination::HangUp));
        assert_eq!(flag.by(), Some(Termination::Terminate));
    }

    #[test]
    fn exit_status_is_128_plus_the_signal() {
        assert_eq!(Termination::Terminate.exit_status(), 143);
        assert_eq!(Termination::HangUp.exit_status(), 129);
        assert_eq!(Termination::Interrupt.exit_status(), 130);
        assert_eq!(Termination::Break.exit_status(), 149);
    }

    #[test]
    fn unix_signals_we_stop_for() {
        assert_eq!(Termination::from_signal(15), Some(Termination::Terminate));
        assert_eq!(Termination::from_signal(1), Some(Termination::HangUp));
        assert_eq!(Termination::from_signal(2), Some(Termination::Interrupt));
        // SIGQUIT, SIGKILL, SIGUSR1: not ours.
        for n in [3, 9, 10] {
            assert_eq!(Termination::from_signal(n), None, "{n}");
        }
    }

    #[test]
    fn windows_console_events_map_to_the_same_stops() {
        use Termination::*;
        let cases = [
            (0, Some(Interrupt), false), // CTRL_C_EVENT
            (1, Some(Break), false),     // CTRL_BREAK_EVENT
            (2, Some(HangUp), true),     // CTRL_CLOSE_EVENT: the window's close button
            (5, Some(Terminate), true),  // CTRL_LOGOFF_EVENT
            (6, Some(Terminate), true),  // CTRL_SHUTDOWN_EVENT
            (3, None, false),
            (4, None, false),
        ];
        for (event, want, waits) in cases {
            assert_eq!(Termination::from_console_event(event), want, "{event}");
            assert_eq!(
                Termination::console_handler_must_wait(event),
                waits,
                "{event}"
            );
        }
    }

    #[test]
    fn the_error_names_the_signal() {
        let e = anyhow::Error::from(Terminated(Termination::Terminate)).context("the page");
        assert_eq!(
            e.downcast_ref::<Terminated>(),
            Some(&Terminated(Termination::Terminate))
        );
        assert_eq!(
            Terminated(Termination::HangUp).to_string(),
            "stopped by SIGHUP"
        );
    }
}

//! The real page binary in a real terminal: a pseudo-terminal that is the page's
//! controlling terminal and standard streams, as a shell in a terminal window has,
//! with everything the page writes kept for the test to look at.

use std::fs::File;
use std::io::{Read, Write};
use std::os::fd::{FromRawFd, OwnedFd};
use std::os::unix::process::CommandExt;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The terminal the page runs in: the master side, with everything the page wrote.
pub struct Term {
    master: File,
    screen: Arc<Mutex<Vec<u8>>>,
}

impl Term {
    /// A 120×40 pty; `answer` makes it reply to the page's terminal queries as a
    /// terminal without the kitty keyboard protocol would (so keys auto-repeat).
    pub fn open() -> (Term, OwnedFd) {
        let (mut m, mut s) = (0, 0);
        let mut size = libc::winsize {
            ws_row: 40,
            ws_col: 120,
            ws_xpixel: 0,
            ws_ypixel: 0,
        };
        // SAFETY: openpty writes two descriptors; the size is read only (macOS
        // declares it `*mut`, Linux `*const`: a raw `*mut` suits both).
        let r = unsafe {
            libc::openpty(
                &mut m,
                &mut s,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                &raw mut size,
            )
        };
        assert_eq!(r, 0, "openpty: {}", std::io::Error::last_os_error());
        // SAFETY: both descriptors are fresh and owned by nothing else.
        let (master, slave) = unsafe { (File::from_raw_fd(m), OwnedFd::from_raw_fd(s)) };
        let screen = Arc::new(Mutex::new(Vec::new()));
        let mut reader = master.try_clone().unwrap();
        let mut answer = master.try_clone().unwrap();
        let seen = screen.clone();
        std::thread::spawn(move || {
            let mut buf = [0u8; 4096];
            // Ends with EIO once the page and every copy of the slave are gone.
            while let Ok(n) = reader.read(&mut buf) {
                if n == 0 {
                    break;
                }
                let mut all = seen.lock().unwrap();
                let before = all.len();
                all.extend_from_slice(&buf[..n]);
                // Primary device attributes asked (after the kitty flags query): a
                // VT220's answer, and no flags.
                let from = before.saturating_sub(3);
                if find(&all[from..], b"\x1b[c").is_some() {
                    let _ = answer.write_all(b"\x1b[?62;22c");
                }
            }
        });
        (Term { master, screen }, slave)
    }

    pub fn typed(&mut self, keys: &[u8]) {
        self.master.write_all(keys).unwrap();
    }

    pub fn output(&self) -> Vec<u8> {
        self.screen.lock().unwrap().clone()
    }

    /// Waits until the page has written every one of `words` since byte `from` (it
    /// draws changes, so each is looked for on its own); fails after `limit`, naming
    /// `what` and showing all it wrote.
    #[track_caller]
    pub fn wait_for(&self, what: &str, words: &[&[u8]], from: usize, limit: Duration) {
        let end = Instant::now() + limit;
        loop {
            let out = self.output();
            let since = out.get(from..).unwrap_or_default();
            if words.iter().all(|w| find(since, w).is_some()) {
                return;
            }
            assert!(
                Instant::now() < end,
                "the page never showed {what} in {limit:?}: {}",
                String::from_utf8_lossy(&out)
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// How many bytes the page has written so far.
    pub fn written(&self) -> usize {
        self.screen.lock().unwrap().len()
    }

    /// The terminal's line settings: on Linux the master reads the slave's termios.
    pub fn echo_and_line_mode(&self) -> (bool, bool) {
        use std::os::fd::AsRawFd;
        // SAFETY: tcgetattr fills the termios it is given.
        let mut t: libc::termios = unsafe { std::mem::zeroed() };
        let r = unsafe { libc::tcgetattr(self.master.as_raw_fd(), &mut t) };
        assert_eq!(r, 0, "tcgetattr: {}", std::io::Error::last_os_error());
        (t.c_lflag & libc::ECHO != 0, t.c_lflag & libc::ICANON != 0)
    }
}

pub fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// The page binary with `args`, and `term`'s slave as its controlling terminal and
/// standard streams.
pub fn page(args: &[&str], slave: OwnedFd) -> Child {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_vpx-efis"));
    cmd.args(args)
        .env("TERM", "xterm-256color")
        .stdin(Stdio::from(slave.try_clone().unwrap()))
        .stdout(Stdio::from(slave.try_clone().unwrap()))
        .stderr(Stdio::from(slave));
    // SAFETY: only async-signal-safe calls between fork and exec.
    unsafe {
        cmd.pre_exec(|| {
            // A session of its own, with the pty as its controlling terminal, as a
            // shell in a terminal window has.
            if libc::setsid() < 0 || libc::ioctl(0, libc::TIOCSCTTY as _, 0) < 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    cmd.spawn().expect("the page starts")
}

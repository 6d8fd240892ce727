//! The update itself: ICD §6.1.3 and §7 as a sequence of steps over one byte stream,
//! each with a timeout and a bounded number of tries, every byte reported to a
//! callback for the support log.
//!
//! ```text
//! detect:  VERSION (main protocol) ── answered ──▶ Found::Running(version)
//!             └─ silent ─▶ QUERY_PORT ── "VP_AVRBOOT" ──▶ Found::Bootloader (resume)
//! update:  [SOFTWARE_UPDATE] ▶ SERIAL_CONF "!!!" ▶ QUERY_PORT "VP_AVRBOOT"
//!          ▶ SIGNATURE 01 98 1E ▶ VERSION ▶ FLASH_ERASE "e"
//!          ▶ FLASH_PROG × pages "P" ▶ FLASH_READ × pages, compared byte for byte
//!          ▶ EXIT "x" ▶ VERSION (main protocol) from the rebooted unit
//! ```
//!
//! Decisions:
//!
//! * **Address unit**: page numbers, as [`crate::protocol::bootloader`] decides (icd-reading
//!   R24); every address sent is logged as page and byte address.
//! * **Detection order.** VERSION first, so a unit running its software never sees a
//!   bootloader frame unless an update was decided; QUERY_PORT only when VERSION gets
//!   no answer. Each protocol ignores the other's frames (`0xE7 0x7E` vs `0x69 0x96`).
//! * **Resume** means: a unit found answering QUERY_PORT is taken from there (no
//!   SOFTWARE_UPDATE, whose hardware check is then the file name's alone), and the
//!   update starts again from FLASH_ERASE. Erase is whole-chip and idempotent, and the
//!   state of a half-written flash cannot be trusted, so starting over is the one resume
//!   that is right whatever the last run got to.
//! * **Never EXIT into a half-written image.** Once FLASH_ERASE has been sent, EXIT is
//!   sent only after every page has read back equal to the image. Before FLASH_ERASE the
//!   old software is still whole, so a failure there (a wrong signature, say) sends EXIT
//!   to give the aircraft its old software back, but only if this run put the unit in
//!   its bootloader: a unit found there may hold a half-written image from before.
//! * **Interrupted** ([`Options::cancel`], Ctrl-C): checked between steps only, so the
//!   page being programmed or verified is finished first. Before FLASH_ERASE this is a
//!   failure like any other (EXIT back to the old software if this run entered the
//!   bootloader); after it the unit stays in its bootloader, and a re-run resumes.
//!   Once every page has verified, the update goes on to EXIT: the image is whole.
//! * **Repair.** A page that reads back wrong is programmed again, up to
//!   [`Options::reprogram_tries`] times. On flash that can only clear bits without an
//!   erase (the sim ANDs programmed bytes into the page, as NOR flash does), programming
//!   the same data again never spoils a byte that is right and clears bits that should
//!   be clear, so it is harmless; it is the whole repair if the bootloader erases each
//!   page before writing it, as AVR bootloaders generally do. What it cannot fix is a 0
//!   where the image has a 1: only an erase sets bits, and erase is whole-chip here, so
//!   the update then starts another pass (erase, program, verify), up to
//!   [`Options::passes`] passes in all.
//! * **Stale input** is thrown away (and logged) before every bootloader command:
//!   binary replies (SIGNATURE, VERSION, FLASH_READ) cannot be searched for, and a stale
//!   byte could pass for a one-letter reply. After a try that failed, the line is left
//!   to go quiet first, so a late answer is not taken for the next one.
//! * **Timeouts** (at 57600 baud a whole FLASH_PROG frame takes 46 ms and a page of
//!   FLASH_READ 44 ms): 1 s a try and 3 tries for every command, 30 s and 2 tries for
//!   FLASH_ERASE (a chip erase of the ATmega2560 page by page is about 4.6 s), SOFTWARE_UPDATE
//!   sent up to 3 times, 20 s for the rebooted unit to answer VERSION.

use std::io::{Read, Write};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::exchange::{ANSWER_TIMEOUT, TRIES, Try, Verdict};
use crate::protocol::bootloader::{
    BootCommand, BootError, BootResponse, BootResponseReader, PAGE_SIZE,
};
use crate::protocol::message::{Message, SoftwareUpdate, Version};
use crate::protocol::{Decoder, Event as WireEvent, Node, Packet};
use crate::transient::is_transient;

use super::hex::Image;

/// A byte stream to the unit: `read` waits a short while and then fails with
/// `TimedOut` (or `WouldBlock`) when nothing came, as a serial port does.
pub trait Port: Read + Write {
    /// Bytes received and not yet read, if the port can tell without waiting. Ports
    /// that cannot are drained by reading until a read comes back empty.
    fn bytes_waiting(&mut self) -> Option<usize> {
        None
    }
}

impl Port for Box<dyn serialport::SerialPort> {
    fn bytes_waiting(&mut self) -> Option<usize> {
        self.bytes_to_read().ok().map(|n| n as usize)
    }
}

impl Port for crate::link::RawPort {
    fn bytes_waiting(&mut self) -> Option<usize> {
        crate::link::RawPort::bytes_waiting(self)
    }
}

#[cfg(unix)]
impl Port for serialport::TTYPort {
    fn bytes_waiting(&mut self) -> Option<usize> {
        serialport::SerialPort::bytes_to_read(self)
            .ok()
            .map(|n| n as usize)
    }
}

/// Timeouts and bounds; see the module documentation for why these values.
#[derive(Debug, Clone)]
pub struct Options {
    /// One try of any command but FLASH_ERASE.
    pub timeout: Duration,
    /// Tries of each command, the first included.
    pub tries: u8,
    pub erase_timeout: Duration,
    pub erase_tries: u8,
    /// Times SOFTWARE_UPDATE is sent when the bootloader does not answer SERIAL_CONF.
    pub enter_tries: u32,
    /// Time the unit gets after SOFTWARE_UPDATE to start its bootloader: bytes sent
    /// while it jumps may be lost (the sim drops what shares a read with
    /// SOFTWARE_UPDATE), and the tail of its last broadcast is thrown away meanwhile.
    pub enter_delay: Duration,
    /// Extra FLASH_PROGs of a page that failed to verify, within one pass.
    pub reprogram_tries: u32,
    /// Erase–program–verify passes in all.
    pub passes: u32,
    /// How long the rebooted unit has to answer VERSION after EXIT.
    pub reboot_timeout: Duration,
    /// The line must be this long without a byte before a failed command is tried again.
    pub quiet: Duration,
    /// Set from outside (Ctrl-C) to stop at the next safe point: the page being
    /// programmed or verified is finished first, and EXIT is never sent into a
    /// half-written image.
    pub cancel: Option<Arc<AtomicBool>>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            timeout: ANSWER_TIMEOUT,
            tries: TRIES,
            erase_timeout: Duration::from_secs(30),
            erase_tries: 2,
            enter_tries: 3,
            enter_delay: Duration::from_millis(250),
            reprogram_tries: 2,
            passes: 2,
            reboot_timeout: Duration::from_secs(20),
            quiet: Duration::from_millis(200),
            cancel: None,
        }
    }
}

/// What the updater reports as it goes, for the log and the progress bar.
#[derive(Debug, Clone, Copy)]
pub enum Event<'a> {
    /// A frame sent, described (command, page and byte address).
    Sent {
        what: &'a str,
        bytes: &'a [u8],
    },
    /// Bytes as they came from the port.
    Received(&'a [u8]),
    /// Bytes that arrived when no answer was expected, thrown away.
    Discarded(&'a [u8]),
    /// What happened, in words.
    Note(&'a str),
    Progress(Progress),
}

/// Pages programmed and verified in the current pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    pub pass: u32,
    pub pages: usize,
    pub programmed: usize,
    pub verified: usize,
}

/// What answered at the start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Found {
    /// The unit runs its software and reported this VERSION.
    Running(Version),
    /// The unit answered QUERY_PORT: it is already in its bootloader (an interrupted
    /// update).
    Bootloader,
}

/// A finished update.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UpdateReport {
    /// The bootloader's VERSION reply (§7.5.7).
    pub boot_version: u16,
    /// VERSION from the rebooted unit.
    pub version: Version,
    /// Erase–program–verify passes it took.
    pub passes: u32,
    /// Pages that read back wrong at first and were repaired.
    pub repaired_pages: Vec<u16>,
    /// The SYSTEM_STATUS Software Update flag after the reboot, if a status came.
    pub software_update_flag: Option<bool>,
}

/// Where a failed update leaves the unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Left {
    /// Nothing that changes the unit was sent, or the unit still runs its software.
    Untouched,
    /// This run entered the bootloader, stopped before erasing, and EXIT was answered:
    /// the unit is rebooting into the software it had.
    BackToOldSoftware,
    /// In its bootloader. `flash_changed`: erased or partly written (or unknown, when
    /// the unit was found there).
    InBootloader { flash_changed: bool },
    /// The image was written and verified and EXIT was sent, but the unit did not
    /// answer VERSION afterwards.
    ExitedNoAnswer,
}

/// Why the update stopped, and what state it leaves the unit in.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UpdateError {
    pub reason: String,
    pub left: Left,
}

impl UpdateError {
    /// What a person should do now, in plain words.
    pub fn advice(&self) -> &'static str {
        match self.left {
            Left::Untouched => "Nothing was changed on the unit; it still runs its software.",
            Left::BackToOldSoftware => {
                "Nothing was erased: the unit was told to leave its bootloader and is restarting the software it had."
            }
            Left::InBootloader {
                flash_changed: true,
            } => {
                "THE UNIT IS STILL IN ITS BOOTLOADER and its program flash is erased or only partly written, so it will \
                 not run its software. Do not switch it off or unplug it. Check the cable and run the same command again: \
                 it will find the unit in its bootloader and resume (erase, program and verify from the start)."
            }
            Left::InBootloader {
                flash_changed: false,
            } => {
                "The unit may be in its bootloader (nothing was erased). Run the same command again: it will find the \
                 unit in its bootloader and resume from there."
            }
            Left::ExitedNoAnswer => {
                "The new software was written and verified and the unit was told to restart, but it has not answered \
                 since. Check the cable and run `vpx-efis --port PATH`; if it still does not answer, run the same flash \
                 command again: it will find the unit in its bootloader if it is there and resume."
            }
        }
    }
}

impl std::fmt::Display for UpdateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}\n{}", self.reason, self.advice())
    }
}

impl std::error::Error for UpdateError {}

/// Why one step failed.
#[derive(Debug)]
enum Fail {
    /// No usable answer after every try.
    NoAnswer(String),
    /// The port failed: unplugged, closed.
    Link(String),
    /// An answer that rules out going on (a wrong signature).
    Refused(String),
    /// Stopped on request ([`Options::cancel`]) between two steps.
    Interrupted(String),
}

impl Fail {
    fn text(self) -> String {
        match self {
            Fail::NoAnswer(s) | Fail::Link(s) | Fail::Refused(s) | Fail::Interrupted(s) => s,
        }
    }
}

struct Session<'a, P: Port + ?Sized> {
    port: &'a mut P,
    opts: &'a Options,
    on: &'a mut dyn FnMut(Event<'_>),
    decoder: Decoder,
    cnt: u8,
    update_flag: Option<bool>,
}

/// Finds out what the unit is running: its software (VERSION answers) or its
/// bootloader (QUERY_PORT answers). Sends nothing that changes the unit.
pub fn detect<P: Port + ?Sized>(
    port: &mut P,
    opts: &Options,
    on: &mut dyn FnMut(Event<'_>),
) -> Result<Found, UpdateError> {
    let mut s = Session::new(port, opts, on);
    let untouched = |reason: String| UpdateError {
        reason,
        left: Left::Untouched,
    };
    s.discard_pending().map_err(|f| untouched(f.text()))?;
    if let Some(v) = s
        .version(opts.timeout, opts.tries)
        .map_err(|f| untouched(f.text()))?
    {
        return Ok(Found::Running(v));
    }
    s.note("no answer to VERSION: asking whether the unit is in its bootloader (QUERY_PORT)");
    match s.boot(&BootCommand::QueryPort, opts.timeout, opts.tries) {
        Ok(_) => {
            s.note("QUERY_PORT answered VP_AVRBOOT: the unit is already in its bootloader");
            Ok(Found::Bootloader)
        }
        Err(f @ Fail::Link(_)) => Err(untouched(f.text())),
        Err(_) => Err(untouched(format!(
            "the unit answered neither VERSION nor QUERY_PORT ({} tries of {} ms each). Check that it is powered, \
             that the cable is plugged in and that --port names its serial port",
            opts.tries,
            opts.timeout.as_millis(),
        ))),
    }
}

/// Writes `image` into the unit found by [`detect`], verifies it, and restarts the unit.
pub fn update<P: Port + ?Sized>(
    port: &mut P,
    image: &Image,
    found: Found,
    opts: &Options,
    on: &mut dyn FnMut(Event<'_>),
) -> Result<UpdateReport, UpdateError> {
    let mut s = Session::new(port, opts, on);
    let entered_here = matches!(found, Found::Running(_));
    if let Err(f) = s.check_cancel("before anything was sent") {
        return Err(UpdateError {
            reason: f.text(),
            left: if entered_here {
                Left::Untouched
            } else {
                Left::InBootloader {
                    flash_changed: true,
                }
            },
        });
    }

    // ---- into the bootloader and identify it; nothing is erased yet.
    let boot_version = match s
        .identify(entered_here)
        .and_then(|v| s.check_cancel("before erasing").map(|()| v))
    {
        Ok(v) => v,
        Err(f) => return Err(s.abandon_before_erase(f, entered_here)),
    };

    // ---- erase, program, verify: from here on the old software is gone.
    let in_boot = |reason: String| UpdateError {
        reason,
        left: Left::InBootloader {
            flash_changed: true,
        },
    };
    let mut repaired = Vec::new();
    let mut passes = 0;
    let mut last_bad: Option<u16> = None;
    for pass in 1..=opts.passes.max(1) {
        passes = pass;
        s.note(&format!(
            "pass {pass}: erase, program {} pages, verify",
            image.page_count()
        ));
        match s.pass(image, pass, &mut repaired) {
            Ok(None) => {
                last_bad = None;
                break;
            }
            Ok(Some(page)) => {
                s.note(&format!(
                    "pass {pass}: page {page} still reads back wrong; only an erase can set its bits again"
                ));
                last_bad = Some(page);
            }
            Err(f) => return Err(in_boot(f.text())),
        }
    }
    if let Some(page) = last_bad {
        return Err(in_boot(format!(
            "page {page} (byte address {:#07x}) did not read back as written after {passes} erase-program-verify passes",
            page as u32 * PAGE_SIZE as u32
        )));
    }
    s.note("every page reads back equal to the image: leaving the bootloader (EXIT)");

    // ---- EXIT and wait for the new software.
    match s.boot(&BootCommand::Exit, opts.timeout, opts.tries) {
        Ok(_) => s.note("EXIT answered 'x': the unit is restarting"),
        Err(Fail::Link(l)) => return Err(in_boot(l)),
        Err(f) => s.note(&format!(
            "{} — it may have restarted with the answer lost; waiting for it",
            f.text()
        )),
    }
    let version = s.wait_for_version()?;
    // SYSTEM_STATUS comes once a second; give it a moment to report the flag.
    let end = Instant::now() + Duration::from_millis(1500);
    while s.update_flag.is_none() && Instant::now() < end {
        if let Err(f) = s.listen_normal(end) {
            s.note(&format!("while waiting for SYSTEM_STATUS: {}", f.text()));
            break;
        }
    }
    match s.update_flag {
        Some(true) => s.note("SYSTEM_STATUS reports the Software Update flag"),
        Some(false) => s.note("SYSTEM_STATUS does NOT report the Software Update flag"),
        None => s.note("no SYSTEM_STATUS seen after the restart"),
    }
    Ok(UpdateReport {
        boot_version,
        version,
        passes,
        repaired_pages: repaired,
        software_update_flag: s.update_flag,
    })
}

fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 3);
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        s.push_str(&format!("{b:02X}"));
    }
    s
}

impl<'a, P: Port + ?Sized> Session<'a, P> {
    fn new(port: &'a mut P, opts: &'a Options, on: &'a mut dyn FnMut(Event<'_>)) -> Self {
        Session {
            port,
            opts,
            on,
            decoder: Decoder::new(),
            cnt: 1,
            update_flag: None,
        }
    }

    fn note(&mut self, s: &str) {
        (self.on)(Event::Note(s));
    }

    fn send(&mut self, what: &str, bytes: &[u8]) -> Result<(), Fail> {
        (self.on)(Event::Sent { what, bytes });
        self.port
            .write_all(bytes)
            .and_then(|_| self.port.flush())
            .map_err(|e| {
                Fail::Link(format!(
                    "cannot write to the port while sending {what}: {e}"
                ))
            })
    }

    /// One read: bytes, or `None` once `deadline` has passed with nothing.
    fn read_some(&mut self, deadline: Instant) -> Result<Option<Vec<u8>>, Fail> {
        let mut buf = [0u8; 1024];
        loop {
            if Instant::now() >= deadline {
                return Ok(None);
            }
            match self.port.read(&mut buf) {
                Ok(0) => {
                    return Err(Fail::Link(
                        "the port reported end of file: the cable or the other end has gone".into(),
                    ));
                }
                Ok(n) => {
                    (self.on)(Event::Received(&buf[..n]));
                    return Ok(Some(buf[..n].to_vec()));
                }
                Err(e) if is_transient(&e) => {}
                Err(e) => return Err(Fail::Link(format!("cannot read from the port: {e}"))),
            }
        }
    }

    /// Throws away what has already arrived.
    fn discard_pending(&mut self) -> Result<(), Fail> {
        let end = Instant::now() + Duration::from_millis(500);
        let mut buf = [0u8; 1024];
        loop {
            let waiting = match self.port.bytes_waiting() {
                Some(0) => return Ok(()),
                Some(n) => n.min(buf.len()),
                // One read, which waits at most the port's own timeout.
                None => buf.len(),
            };
            match self.port.read(&mut buf[..waiting]) {
                Ok(0) => {
                    return Err(Fail::Link(
                        "the port reported end of file: the cable or the other end has gone".into(),
                    ));
                }
                Ok(n) => {
                    (self.on)(Event::Discarded(&buf[..n]));
                }
                Err(e) if is_transient(&e) => {
                    return Ok(());
                }
                Err(e) => return Err(Fail::Link(format!("cannot read from the port: {e}"))),
            }
            if Instant::now() >= end {
                // A unit that keeps talking (its software broadcasting) never empties the
                // line; what is left is sorted out by the reply's matching.
                return Ok(());
            }
        }
    }

    /// Reads for `d`, throwing away what comes.
    fn wait_discarding(&mut self, d: Duration) -> Result<(), Fail> {
        let end = Instant::now() + d;
        while let Some(b) = self.read_some(end)? {
            (self.on)(Event::Discarded(&b));
        }
        Ok(())
    }

    /// Waits until the line has been quiet for `opts.quiet` (at most 2 s), discarding
    /// what comes: a late answer to a failed try must not pass for the next one's.
    fn settle(&mut self) -> Result<(), Fail> {
        let give_up = Instant::now() + Duration::from_secs(2);
        loop {
            let quiet_until = (Instant::now() + self.opts.quiet).min(give_up);
            match self.read_some(quiet_until)? {
                None => return Ok(()),
                Some(b) => (self.on)(Event::Discarded(&b)),
            }
            if Instant::now() >= give_up {
                return Ok(());
            }
        }
    }

    /// One bootloader command with its reply, retried on silence or a garbled reply.
    fn boot(
        &mut self,
        cmd: &BootCommand,
        timeout: Duration,
        tries: u8,
    ) -> Result<BootResponse, Fail> {
        let what = cmd.to_string();
        let frame = cmd.emit();
        let mut try_ = Try::with(Instant::now(), timeout, tries);
        let tries = try_.of();
        loop {
            let attempt = try_.attempt;
            if attempt > 1 {
                self.settle()?;
            }
            self.discard_pending()?;
            self.send(&what, &frame)?;
            let mut reader = BootResponseReader::new(cmd);
            let deadline = Instant::now() + timeout;
            loop {
                let Some(chunk) = self.read_some(deadline)? else {
                    self.note(&format!(
                        "no complete answer to {} within {} ms (try {attempt} of {tries})",
                        cmd.name(),
                        timeout.as_millis()
                    ));
                    break;
                };
                let Some((result, used)) = reader.feed(&chunk) else {
                    continue;
                };
                if reader.skipped() > 0 {
                    self.note(&format!(
                        "{} bytes before the answer to {} were not part of it",
                        reader.skipped(),
                        cmd.name()
                    ));
                }
                if used < chunk.len() {
                    (self.on)(Event::Discarded(&chunk[used..]));
                }
                match result {
                    Ok(r) => return Ok(r),
                    Err(e @ BootError::WrongSignature(_)) => {
                        return Err(Fail::Refused(e.to_string()));
                    }
                    Err(e) => {
                        self.note(&format!("{e} (try {attempt} of {tries})"));
                        break;
                    }
                }
            }
            if try_.spent(Instant::now()) == Verdict::NoAnswer {
                break;
            }
        }
        Err(Fail::NoAnswer(format!(
            "the bootloader did not answer {} after {tries} tries of {} ms",
            cmd.name(),
            timeout.as_millis()
        )))
    }

    fn take_cnt(&mut self) -> u8 {
        let c = self.cnt;
        self.cnt = self.cnt.wrapping_add(1).max(1);
        c
    }

    /// Feeds bytes read before `deadline` to the main-protocol decoder; the packets.
    fn listen_normal(&mut self, deadline: Instant) -> Result<Option<Vec<Packet>>, Fail> {
        let Some(chunk) = self.read_some(deadline)? else {
            return Ok(None);
        };
        let mut packets = Vec::new();
        self.decoder.push(&chunk, |e| {
            if let WireEvent::Frame(f) = e
                && let Ok(p) = Packet::parse(&f)
            {
                packets.push(p);
            }
        });
        for p in &packets {
            if let Message::SystemStatus(st) = &p.message {
                self.update_flag = Some(st.misc.software_update);
            }
        }
        Ok(Some(packets))
    }

    /// VERSION in the main protocol; `None` if no try was answered.
    fn version(&mut self, timeout: Duration, tries: u8) -> Result<Option<Version>, Fail> {
        let mut sent = Vec::new();
        let mut try_ = Try::with(Instant::now(), timeout, tries);
        loop {
            let attempt = try_.attempt;
            let cnt = self.take_cnt();
            sent.push(cnt);
            let bytes = Packet::request(cnt, Version::REQUEST).to_bytes();
            self.send(
                &format!("VERSION (main protocol, command number {cnt})"),
                &bytes,
            )?;
            let deadline = Instant::now() + timeout;
            while let Some(packets) = self.listen_normal(deadline)? {
                for p in packets {
                    // A slow answer to an earlier try answers the same question.
                    if p.src == Node::Vpx
                        && sent.contains(&p.cnt)
                        && let Message::Version(v) = p.message
                    {
                        self.note(&format!(
                            "VERSION: hardware {} ({}), software {}.{}",
                            v.hardware_version.to_byte(),
                            v.hardware_version.name(),
                            v.software_major,
                            v.software_minor
                        ));
                        return Ok(Some(v));
                    }
                }
            }
            self.note(&format!(
                "no answer to VERSION within {} ms (try {attempt} of {})",
                timeout.as_millis(),
                try_.of()
            ));
            if try_.spent(Instant::now()) == Verdict::NoAnswer {
                return Ok(None);
            }
        }
    }

    /// SOFTWARE_UPDATE if needed, then SERIAL_CONF, QUERY_PORT, SIGNATURE and VERSION.
    fn identify(&mut self, enter: bool) -> Result<u16, Fail> {
        let o = self.opts;
        if enter {
            let mut entered = false;
            for attempt in 1..=o.enter_tries.max(1) {
                let cnt = self.take_cnt();
                let bytes = Packet::request(cnt, SoftwareUpdate).to_bytes();
                self.send(
                    &format!(
                        "SOFTWARE_UPDATE (main protocol, try {attempt} of {})",
                        o.enter_tries
                    ),
                    &bytes,
                )?;
                self.wait_discarding(o.enter_delay)?;
                match self.boot(&BootCommand::serial_conf(), o.timeout, o.tries) {
                    Ok(_) => {
                        entered = true;
                        break;
                    }
                    Err(Fail::NoAnswer(n)) => self.note(&n),
                    Err(f) => return Err(f),
                }
            }
            if !entered {
                return Err(Fail::NoAnswer(format!(
                    "the unit did not enter its bootloader: SOFTWARE_UPDATE was sent {} times and SERIAL_CONF never answered",
                    o.enter_tries
                )));
            }
        } else {
            self.boot(&BootCommand::serial_conf(), o.timeout, o.tries)?;
        }
        self.note("SERIAL_CONF answered '!!!'");
        self.boot(&BootCommand::QueryPort, o.timeout, o.tries)?;
        self.note("QUERY_PORT answered 'VP_AVRBOOT'");
        self.boot(&BootCommand::Signature, o.timeout, o.tries)?;
        self.note("SIGNATURE is 01 98 1E (ATmega2560)");
        let v = match self.boot(&BootCommand::Version, o.timeout, o.tries)? {
            BootResponse::Version(v) => v,
            other => return Err(Fail::Refused(format!("VERSION answered {other:?}"))),
        };
        self.note(&format!("bootloader version {}.{}", v >> 8, v & 0xFF));
        Ok(v)
    }

    /// A failure before FLASH_ERASE: the old software is whole. Leave the bootloader
    /// if this run entered it; a unit found there may hold a half-written image.
    fn abandon_before_erase(&mut self, f: Fail, entered_here: bool) -> UpdateError {
        let reason = f.text();
        self.note(&format!("stopping before erase: {reason}"));
        if !entered_here {
            return UpdateError {
                reason,
                left: Left::InBootloader {
                    flash_changed: true,
                },
            };
        }
        // Did the unit never leave its software (SOFTWARE_UPDATE lost)?
        if let Ok(Some(_)) = self.version(self.opts.timeout, 1) {
            return UpdateError {
                reason,
                left: Left::Untouched,
            };
        }
        self.note("nothing was erased: sending EXIT to restart the old software");
        match self.boot(&BootCommand::Exit, self.opts.timeout, self.opts.tries) {
            Ok(_) => UpdateError {
                reason,
                left: Left::BackToOldSoftware,
            },
            Err(e) => {
                self.note(&e.text());
                UpdateError {
                    reason,
                    left: Left::InBootloader {
                        flash_changed: false,
                    },
                }
            }
        }
    }

    /// One erase–program–verify pass. `Ok(None)`: every page verified; `Ok(Some(p))`:
    /// page `p` could not be repaired without another erase.
    fn pass(
        &mut self,
        image: &Image,
        pass: u32,
        repaired: &mut Vec<u16>,
    ) -> Result<Option<u16>, Fail> {
        let o = self.opts;
        let mut progress = Progress {
            pass,
            pages: image.page_count(),
            programmed: 0,
            verified: 0,
        };
        (self.on)(Event::Progress(progress));
        self.boot(&BootCommand::FlashErase, o.erase_timeout, o.erase_tries)?;
        self.note("FLASH_ERASE answered 'e': the old software is erased");
        for (page, data) in image.pages() {
            self.program(page, data)?;
            progress.programmed += 1;
            self.page_done(progress, "programming", page, progress.programmed)?;
        }
        for (page, data) in image.pages() {
            let mut ok = self.verify(page, data)?;
            let mut extra = 0;
            while !ok && extra < o.reprogram_tries {
                extra += 1;
                self.note(&format!(
                    "programming page {page} again (repair {extra} of {})",
                    o.reprogram_tries
                ));
                self.program(page, data)?;
                ok = self.verify(page, data)?;
                if ok {
                    repaired.push(page);
                    self.note(&format!("page {page} repaired"));
                }
            }
            if !ok {
                return Ok(Some(page));
            }
            progress.verified += 1;
            self.page_done(progress, "verifying", page, progress.verified)?;
        }
        Ok(None)
    }

    /// A stop asked for from outside, between two steps: never in the middle of a
    /// command, so the page in progress is whole.
    /// A page programmed or verified: says how far the pass is, then stops here if
    /// the person cancelled.
    fn page_done(
        &mut self,
        progress: Progress,
        doing: &str,
        page: impl std::fmt::Display,
        done: usize,
    ) -> Result<(), Fail> {
        (self.on)(Event::Progress(progress));
        self.check_cancel(&format!(
            "after {doing} page {page} ({done} of {})",
            progress.pages
        ))
    }

    fn check_cancel(&mut self, at: &str) -> Result<(), Fail> {
        if self
            .opts
            .cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::SeqCst))
        {
            let why = format!("interrupted {at}");
            self.note(&why);
            return Err(Fail::Interrupted(why));
        }
        Ok(())
    }

    fn program(&mut self, page: u16, data: &[u8; PAGE_SIZE]) -> Result<(), Fail> {
        let cmd = BootCommand::flash_prog(page, data).map_err(|e| Fail::Refused(e.to_string()))?;
        self.boot(&cmd, self.opts.timeout, self.opts.tries)?;
        Ok(())
    }

    /// FLASH_READ of the page, compared byte for byte.
    fn verify(&mut self, page: u16, want: &[u8; PAGE_SIZE]) -> Result<bool, Fail> {
        let got = match self.boot(
            &BootCommand::flash_read_page(page),
            self.opts.timeout,
            self.opts.tries,
        )? {
            BootResponse::Flash(b) => b,
            other => return Err(Fail::Refused(format!("FLASH_READ answered {other:?}"))),
        };
        if got[..] == want[..] {
            return Ok(true);
        }
        let diffs: Vec<usize> = (0..PAGE_SIZE).filter(|&i| got[i] != want[i]).collect();
        let first = diffs[0];
        let needs_erase = (0..PAGE_SIZE).any(|i| want[i] & !got[i] != 0);
        self.note(&format!(
            "VERIFY FAILED page {page} (byte address {:#07x}): {} byte(s) differ, first at offset {first}: \
             read {:02X}, image {:02X}{}",
            page as u32 * PAGE_SIZE as u32,
            diffs.len(),
            got[first],
            want[first],
            if needs_erase {
                "; some bits read 0 where the image has 1"
            } else {
                ""
            }
        ));
        self.note(&format!("page {page} as read: {}", hex(&got)));
        Ok(false)
    }

    /// After EXIT: VERSION in the main protocol until the unit answers.
    fn wait_for_version(&mut self) -> Result<Version, UpdateError> {
        let end = Instant::now() + self.opts.reboot_timeout;
        self.decoder.reset();
        while Instant::now() < end {
            match self.version(self.opts.timeout, 1) {
                Ok(Some(v)) => return Ok(v),
                Ok(None) => {}
                Err(f) => {
                    return Err(UpdateError {
                        reason: f.text(),
                        left: Left::ExitedNoAnswer,
                    });
                }
            }
        }
        // Still in the bootloader (EXIT lost both ways)? Then say so: a re-run resumes.
        let in_boot = self
            .boot(&BootCommand::QueryPort, self.opts.timeout, 1)
            .is_ok();
        Err(UpdateError {
            reason: format!(
                "the unit did not answer VERSION within {} s of EXIT{}",
                self.opts.reboot_timeout.as_secs(),
                if in_boot {
                    "; it still answers QUERY_PORT, so it is in its bootloader with a verified image"
                } else {
                    ""
                }
            ),
            left: if in_boot {
                Left::InBootloader {
                    flash_changed: true,
                }
            } else {
                Left::ExitedNoAnswer
            },
        })
    }
}

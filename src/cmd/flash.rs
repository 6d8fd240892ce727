//! `vpx-efis flash --port PATH FILE.hex`: update the VP-X software (ICD §6.1.3, §7).
//!
//! Order, so that nothing reaches the unit that a person has not agreed to:
//! 0. a port is named (a flag, `VPX_EFIS_PORT` or the config file), or we refuse;
//! 1. the whole file is read and checked, and must be able to be a whole program
//!    (`flash::whole`; `--force-image` takes the risk): refused files never open the
//!    port;
//! 2. the file's hardware (name suffix or `--force-hardware`) is known, or refused;
//! 3. the support log is opened (a log that cannot be written stops us here);
//! 4. the port is opened and the unit detected with VERSION (QUERY_PORT only if VERSION
//!    gets no answer); a hardware mismatch is refused here, before any bootloader frame;
//! 5. the §7.3 precautions are printed, with the image's size and coverage, always;
//!    then the person confirms (`--yes` skips only the question; without a terminal
//!    and without `--yes` we refuse);
//! 6. the update runs with a progress bar; every byte goes to the log.
//!
//! Without `--port` we refuse: flashing the built-in virtual unit would only show the
//! sim's flash changing inside this process. `vpx-efis sim --pty` (or `--tcp`) gives a
//! virtual VP-X on a pseudo-terminal (or a TCP port) that can be passed as `--port`,
//! which exercises exactly the code a real unit gets.

use std::fs::{File, OpenOptions};
use std::io::{BufRead, IsTerminal, LineWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant, SystemTime};

use anyhow::{Context, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::app::{StopFlag, Terminated};
use crate::flash::hardware::hw_name;
use crate::flash::{self, Event, Found, Image, Options};
use crate::link::PortAddr;
use crate::link::open_raw;
use crate::protocol::bootloader::PAGE_SIZE;
use crate::settings::{BAUD_ENV, PORT_ENV, values};

/// `flash` talks to a real port only: flashing the built-in unit would show nothing
/// but the sim's memory changing inside this process.
#[derive(Debug, Clone, Args)]
pub struct FlashPortArgs {
    /// The VP-X's serial port (or tcp://HOST:PORT for a network bridge; the path or
    /// address printed by `vpx-efis sim --pty` or `--tcp` for the virtual VP-X). Also
    /// read from VPX_EFIS_PORT or the config file.
    #[arg(long, value_name = "PATH|tcp://HOST:PORT", env = PORT_ENV, value_parser = values::port)]
    pub port: Option<PortAddr>,

    /// Baud rate of a serial port. The VP-X talks 57600 8N1 (ICD §3.2.1).
    #[arg(long, default_value_t = values::VPX_BAUD, env = BAUD_ENV, value_parser = values::baud)]
    pub baud: u32,
}

#[derive(Debug, Args)]
pub struct FlashArgs {
    #[command(flatten)]
    pub port: FlashPortArgs,
    /// Intel HEX image, named like `cu_2.hex` for hardware version 2.
    pub file: PathBuf,
    /// Accept this hardware version even if the file name's suffix disagrees.
    #[arg(long, value_name = "N")]
    pub force_hardware: Option<u8>,
    /// Flash an image that cannot be a whole program (under 8 KiB of data, no reset
    /// vector, or data outside the program range 0x00000-0x3DFFF), at your own risk:
    /// the unit is erased first and may not start again.
    #[arg(long)]
    pub force_image: bool,
    /// Don't ask for confirmation (the precautions are printed all the same).
    #[arg(long)]
    pub yes: bool,
    /// Where to write the exchange log (default: next to the hex file).
    #[arg(long, value_name = "FILE")]
    pub log: Option<PathBuf>,
}

pub fn run(args: FlashArgs) -> anyhow::Result<()> {
    let Some(port_path) = args.port.port.clone() else {
        return Err(crate::program::UsageError(
            "flash needs the unit's port: --port PATH or tcp://HOST:PORT, VPX_EFIS_PORT, or `port` in \
             the config file (`vpx-efis ports` lists serial ports). To try it on the virtual VP-X, run \
             `vpx-efis sim --pty` (or `vpx-efis sim --tcp 127.0.0.1:0`) and pass what it prints as --port"
                .into(),
        )
        .into());
    };
    let image = flash::load_hex(&args.file)
        .with_context(|| format!("refusing {}: it is not a usable image", args.file.display()))?;
    eprintln!("{}: {}", args.file.display(), image.summary());
    let coverage = flash::Coverage::of(&image);
    let problems = coverage.problems();
    if !problems.is_empty() {
        let why: String = problems.iter().map(|p| format!("\n  - {p}")).collect();
        if !args.force_image {
            bail!(
                "refusing {}: it cannot be a whole VP-X program, and the update erases the \
                 unit's program memory before it writes anything:{why}\nNothing was sent to the \
                 unit. If you are sure this image is right, --force-image flashes it at your \
                 own risk.",
                args.file.display()
            );
        }
        eprintln!(
            "WARNING (--force-image): {} cannot be a whole program; flashing it anyway:{why}",
            args.file.display()
        );
    }
    let file_hw = flash::file_hardware(&args.file, args.force_hardware)?;

    let log_path = args
        .log
        .clone()
        .unwrap_or_else(|| default_log_path(&args.file));
    let mut log = FlashLog::open(&log_path)?;
    log.line(&format!(
        "==== vpx-efis {} flash {} to {} at {} baud",
        env!("CARGO_PKG_VERSION"),
        args.file.display(),
        port_path,
        args.port.baud
    ));
    log.line(&format!("-- image: {}", image.summary()));
    log.line(&format!("-- covers: {coverage}"));
    for p in &problems {
        log.line(&format!("-- flashed with --force-image although {p}"));
    }
    log.line(&format!(
        "-- file is for hardware {file_hw}{}",
        if args.force_hardware.is_some() {
            " (--force-hardware)"
        } else {
            " (file name)"
        }
    ));

    let mut port = open_raw(&port_path, args.port.baud)?;
    let mut opts = Options::default();

    let found = flash::detect(&mut port, &opts, &mut |e| log.event(&e)).map_err(|e| {
        log.line(&format!("-- stopped: {e}"));
        anyhow::anyhow!("{e}")
    })?;
    let unit_line = match found {
        Found::Running(v) => {
            let unit_hw = v.hardware_version.to_byte();
            if let Err(e) = flash::check_hardware(&args.file, args.force_hardware, unit_hw) {
                log.line(&format!(
                    "-- refused before anything was sent to the bootloader: {e}"
                ));
                bail!("{e}\nNothing was sent to the bootloader; the unit still runs its software.");
            }
            format!(
                "hardware {unit_hw} ({}), software {}.{}",
                hw_name(unit_hw),
                v.software_major,
                v.software_minor
            )
        }
        Found::Bootloader => format!(
            "ALREADY IN ITS BOOTLOADER (an earlier update did not finish). Its hardware version cannot be read \
             there: make sure it is hardware {file_hw} ({}) before you go on",
            hw_name(file_hw)
        ),
    };
    eprintln!("unit on {port_path}: {unit_line}");

    precautions(&args.file, &image, file_hw, &unit_line, args.port.baud);
    if !args.yes && !confirm()? {
        log.line("-- not confirmed: nothing sent to the bootloader");
        match found {
            Found::Running(_) => bail!("not confirmed; nothing was changed on the unit"),
            Found::Bootloader => bail!(
                "not confirmed. The unit is still in its bootloader and will not run its software until an \
                 update completes: run the same command again when ready"
            ),
        }
    }

    // From here Ctrl-C (or SIGTERM, SIGHUP, a closed console) stops at the next safe
    // point instead of killing us mid-page; see `flash::updater`.
    let interrupted = stop_on_termination(&mut opts)?;
    let _panic = stop_on_panic(&opts);
    let _awake = keep_awake(&mut log);
    let pages = image.page_count() as u64;
    let before = match found {
        Found::Running(v) => Some(version_words(&v)),
        Found::Bootloader => None,
    };
    let record = |after: Option<String>, outcome: String| {
        log_update(&args.file, before.clone(), after, outcome);
    };
    let bar = progress_bar(pages * 2);
    let started = Instant::now();
    let result = flash::update(&mut port, &image, found, &opts, &mut |e| {
        log.event(&e);
        match e {
            Event::Progress(p) => {
                bar.set_length(p.pages as u64 * 2);
                bar.set_position((p.programmed + p.verified) as u64);
                bar.set_message(if p.programmed < p.pages {
                    format!("pass {}: programming", p.pass)
                } else {
                    format!("pass {}: verifying", p.pass)
                });
            }
            // Long notes (a page's bytes) are for the log only.
            // indicatif drops println when it draws nothing (no terminal): print plainly.
            Event::Note(n) if n.len() <= 300 && bar.is_hidden() => eprintln!("  {n}"),
            Event::Note(n) if n.len() <= 300 => bar.println(format!("  {n}")),
            _ => {}
        }
    });
    match result {
        Ok(out) => {
            bar.finish_with_message("done");
            let summary = format!(
                "updated in {:.0} s: the unit reports hardware {} ({}), software {}.{}; bootloader {}.{}; \
                 {} pages programmed and verified{}{}",
                started.elapsed().as_secs_f64(),
                out.version.hardware_version.to_byte(),
                out.version.hardware_version.name(),
                out.version.software_major,
                out.version.software_minor,
                out.boot_version >> 8,
                out.boot_version & 0xFF,
                pages,
                if out.repaired_pages.is_empty() {
                    String::new()
                } else {
                    format!(
                        " ({} page(s) repaired: {:?})",
                        out.repaired_pages.len(),
                        out.repaired_pages
                    )
                },
                if out.passes > 1 {
                    format!(" in {} passes", out.passes)
                } else {
                    String::new()
                }
            );
            log.line(&format!("-- {summary}"));
            log.finish();
            eprintln!("{summary}\nlog: {}", log_path.display());
            record(Some(version_words(&out.version)), "updated".into());
            Ok(())
        }
        Err(e) => {
            bar.abandon_with_message("stopped");
            if crate::app::panicked() {
                log.line("-- a thread of vpx-efis panicked: stopping at the next safe point");
            }
            log.line(&format!("-- STOPPED: {e}"));
            log.finish();
            record(None, format!("stopped: {e}"));
            let by = interrupted.by();
            match by {
                // Our words, then the exit status of the signal (130 for Ctrl-C).
                Some(t) => {
                    eprintln!(
                        "vpx-efis: {e}\nThe whole exchange is in {}",
                        log_path.display()
                    );
                    Err(Terminated(t).into())
                }
                None => bail!("{e}\nThe whole exchange is in {}", log_path.display()),
            }
        }
    }
}

/// Keeps the machine from sleeping until dropped: a laptop that suspends mid-update
/// leaves the unit in its bootloader. Best effort: a machine with no power manager to
/// ask (Linux without D-Bus or logind, a container) flashes all the same, with a word.
/// "VP-X Pro 2.1": a VERSION as the logbook keeps it.
fn version_words(v: &crate::protocol::message::Version) -> String {
    format!(
        "{} {}.{}",
        v.hardware_version.name(),
        v.software_major,
        v.software_minor
    )
}

/// The update into the logbook: the image's SHA-256, the versions before and after,
/// and how it ended. A logbook that cannot take it is said; the update stands.
fn log_update(file: &Path, before: Option<String>, after: Option<String>, outcome: String) {
    use sha2::Digest;
    let sha = match std::fs::read(file) {
        Ok(bytes) => hex(&sha2::Sha256::digest(&bytes)),
        Err(e) => format!("not read again: {e}"),
    };
    let entry = crate::logbook::Entry {
        at: std::time::SystemTime::now(),
        origin: crate::logbook::record::COMMAND_LINE,
        summary: format!(
            "firmware {}: {} → {}: {outcome}",
            file.display(),
            before.as_deref().unwrap_or("(in its bootloader)"),
            after.as_deref().unwrap_or("?")
        ),
        what: crate::logbook::What::Firmware(crate::logbook::record::Firmware {
            image_sha256: sha,
            image_path: file.display().to_string(),
            version_before: before,
            version_after: after,
            outcome,
        }),
    };
    if let Some(why) = crate::logbook::record_now(entry, None) {
        eprintln!("vpx-efis: {why}");
    }
}

fn keep_awake(log: &mut FlashLog) -> Option<keepawake::KeepAwake> {
    match keepawake::Builder::default()
        .idle(true)
        .sleep(true)
        .reason("VP-X firmware update in progress")
        .app_name("vpx-efis")
        .app_reverse_domain("io.github.vpx-efis")
        .create()
    {
        Ok(k) => {
            log.line("-- the machine is kept awake until the update ends");
            Some(k)
        }
        Err(e) => {
            log.line(&format!("-- cannot keep the machine awake: {e}"));
            eprintln!(
                "note: cannot keep this machine awake ({e}); do not let it sleep until the update is done"
            );
            None
        }
    }
}

/// Sets `opts.cancel` when the OS asks us to stop, and says so once; the flag says
/// what asked, for the exit status.
fn stop_on_termination(opts: &mut Options) -> anyhow::Result<StopFlag> {
    let flag = crate::app::stop_flag("flash-stop", |t| {
        eprintln!(
            "\nvpx-efis: {}: finishing the page in progress, then stopping (the unit is never \
             restarted into a half-written image)",
            t.name()
        );
    })?;
    opts.cancel = Some(flag.raised.clone());
    Ok(flag)
}

/// The app's panic path, for flash: the same hook as every process (the panic is
/// flagged, the terminal given back, the message printed), whose first act is the
/// process's emergency stop. Flash sends no motor command, so there is no stop gate
/// to close; its emergency stop is the one a signal gets: finish the page in
/// progress, then stop, never restarting the unit into a half-written image. Until
/// dropped.
fn stop_on_panic(opts: &Options) -> PanicStop {
    crate::app::install_panic_hook();
    if let Some(cancel) = opts.cancel.clone() {
        crate::app::set_emergency_stop(move || cancel.store(true, Ordering::SeqCst));
    }
    PanicStop
}

/// Disarms flash's emergency stop when the update is over.
struct PanicStop;

impl Drop for PanicStop {
    fn drop(&mut self) {
        crate::app::clear_emergency_stop();
    }
}

/// `FILE.hex.log`, next to the file.
pub fn default_log_path(file: &Path) -> PathBuf {
    let mut s = file.as_os_str().to_owned();
    s.push(".log");
    PathBuf::from(s)
}

/// Time on the wire for the whole update at `baud` (10 bits a byte): FLASH_PROG
/// frames (5 + 2 + 256 bytes) and their 'P', FLASH_READ frames (9) and their page,
/// plus a few seconds for the erase.
fn estimate(pages: usize, baud: u32) -> Duration {
    let bytes = pages * (5 + 2 + PAGE_SIZE + 1 + 9 + PAGE_SIZE);
    Duration::from_secs_f64(bytes as f64 * 10.0 / baud.max(1) as f64 + 5.0)
}

/// What is about to happen and the §7.3 precautions: printed before every update,
/// `--yes` or not.
fn precautions(file: &Path, image: &Image, file_hw: u8, unit: &str, baud: u32) {
    let secs = estimate(image.page_count(), baud).as_secs();
    eprintln!();
    eprintln!("About to replace the VP-X software.");
    eprintln!("  unit: {unit}");
    eprintln!(
        "  file: {} for hardware {file_hw} ({}), {}",
        file.display(),
        hw_name(file_hw),
        image.summary()
    );
    eprintln!("  covers: {}", flash::Coverage::of(image));
    eprintln!("  time: about {} min {} s", secs / 60, secs % 60);
    eprintln!();
    eprintln!("PRECAUTIONS (ICD §7.3). Until this command says it is done:");
    eprintln!("  - NEVER switch off or cycle power to the VP-X;");
    eprintln!("  - NEVER unplug the serial cable.");
    eprintln!(
        "  If either happens the unit will probably not start, and may have to go back to Vertical Power."
    );
    eprintln!(
        "  The aircraft's electrical system is not controlled by the VP-X while the update runs."
    );
    eprintln!();
}

/// The question, on a terminal only.
fn confirm() -> anyhow::Result<bool> {
    if !std::io::stdin().is_terminal() {
        bail!(
            "not asking for confirmation: standard input is not a terminal. Pass --yes to update without asking"
        );
    }
    eprint!("Type \"yes\" to update: ");
    std::io::stderr().flush().ok();
    let mut answer = String::new();
    std::io::stdin()
        .lock()
        .read_line(&mut answer)
        .context("cannot read the answer")?;
    Ok(answer.trim().eq_ignore_ascii_case("yes"))
}

fn progress_bar(len: u64) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{msg:22} [{bar:40}] {pos}/{len} page steps (programmed + verified), {eta} left",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// The support log: every frame both ways in hex with a timestamp, every address, and
/// every decision. Appended to, so the runs of one update (a failure, then the resume)
/// stay together. Written line by line, so a crash or a pulled plug loses nothing.
struct FlashLog {
    out: Option<LineWriter<File>>,
    path: PathBuf,
    start: Instant,
    failed: bool,
}

impl FlashLog {
    fn open(path: &Path) -> anyhow::Result<FlashLog> {
        let f = OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .with_context(|| format!("cannot write the log {} (use --log FILE)", path.display()))?;
        Ok(FlashLog {
            out: Some(LineWriter::new(f)),
            path: path.to_path_buf(),
            start: Instant::now(),
            failed: false,
        })
    }

    fn line(&mut self, text: &str) {
        let Some(out) = &mut self.out else { return };
        let stamp = format!(
            "{} +{:9.3}s",
            crate::utc::utc_text(SystemTime::now()),
            self.start.elapsed().as_secs_f64()
        );
        if let Err(e) = writeln!(out, "{stamp} {text}") {
            if !self.failed {
                eprintln!(
                    "vpx-efis: cannot write the log {}: {e} (the update goes on)",
                    self.path.display()
                );
            }
            self.failed = true;
        }
    }

    fn event(&mut self, e: &Event<'_>) {
        match e {
            Event::Sent { what, bytes } => self.line(&format!("TX {what}: {}", hex(bytes))),
            Event::Received(b) => self.line(&format!("RX {}", hex(b))),
            Event::Discarded(b) => self.line(&format!("DISCARDED {}", hex(b))),
            Event::Note(n) => self.line(&format!("-- {n}")),
            Event::Progress(p) if p.programmed == 0 && p.verified == 0 => {
                self.line(&format!("-- pass {}: {} pages", p.pass, p.pages))
            }
            Event::Progress(_) => {}
        }
    }

    fn finish(&mut self) {
        if let Some(out) = &mut self.out {
            let _ = out.flush();
        }
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|b| format!("{b:02X}"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_log_goes_next_to_the_file() {
        assert_eq!(
            default_log_path(Path::new("/fw/cu_2.hex")),
            PathBuf::from("/fw/cu_2.hex.log")
        );
    }

    #[test]
    fn a_full_flash_takes_minutes_not_seconds() {
        // 1024 pages at 57600 baud: 1024 * 529 * 10 / 57600 ≈ 94 s, plus the erase.
        let t = estimate(1024, 57_600).as_secs();
        assert!((95..=105).contains(&t), "{t}");
    }
}

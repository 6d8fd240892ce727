//! `vpx-efis flash` as a mechanic runs it: the binary on a pseudo-terminal whose other
//! end is the virtual VP-X, checking what reaches the unit and what is written down.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};

use vpx_efis::flash::hex::to_hex_text;
use vpx_efis::protocol::bootloader::PAGE_SIZE;
use vpx_efis::sim::{self, SimOptions};

mod common;
use common::process;
use common::rig::PtyUnit;

fn start() -> PtyUnit {
    PtyUnit::start(SimOptions::new(sim::load_scenario("demo").unwrap()))
}

fn bytes() -> Vec<u8> {
    (0..5 * PAGE_SIZE + 17)
        .map(|i| (i * 13 + 5) as u8)
        .collect()
}

fn write_hex(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn flash(args: &[&str]) -> Output {
    process::vpx(&[&["flash"], args].concat(), process::NO_CONFIG)
        .output()
        .unwrap()
}

/// `vpx-efis flash --port UNIT --yes --force-image FILE`: the update with no question
/// asked, whether or not the image is a whole program.
fn flash_forced(rig: &PtyUnit, file: &Path) -> Output {
    flash(&[
        "--port",
        &rig.path,
        "--yes",
        "--force-image",
        file.to_str().unwrap(),
    ])
}

/// `text`, as the program printed or wrote it, holds `words`; else the test fails
/// showing all of it.
#[track_caller]
fn assert_says(text: &str, words: &str) {
    assert!(text.contains(words), "no {words:?} in:\n{text}");
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The exchange log written beside the hex file `name`.
fn log_beside(rig: &PtyUnit, name: &str) -> String {
    std::fs::read_to_string(rig.dir.path().join(format!("{name}.log"))).unwrap()
}

/// Nothing reached the bootloader and the flash is as it was.
fn untouched(rig: &PtyUnit) {
    let st = rig.sim.stats();
    assert!(!st.in_bootloader);
    assert_eq!(st.boot.commands, 0);
    assert!(rig.sim.flash().iter().all(|&b| b == 0xFF));
}

#[test]
fn a_full_update_from_the_command_line_writes_the_image_and_a_log_beside_it() {
    let rig = start();
    let data = bytes();
    let file = write_hex(rig.dir.path(), "cu_2.hex", &to_hex_text(0x400, &data));
    // Five pages and a bit at 0x400, no reset vector: not a whole program.
    let o = flash_forced(&rig, &file);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("6 pages"),
        "image size and pages are shown: {err}"
    );
    assert_says(&err, "software 2.1");
    let flash = rig.sim.flash();
    assert_eq!(&flash[0x400..0x400 + data.len()], &data[..]);
    assert!(flash[..0x400].iter().all(|&b| b == 0xFF));

    let log = log_beside(&rig, "cu_2.hex");
    // Every frame in hex with a timestamp, every address.
    assert!(
        log.contains(
            "TX FLASH_PROG page 4 (byte address 0x00400, 256 bytes): 69 96 70 81 00 04 00"
        ),
        "{log}"
    );
    assert!(
        log.contains(
            "TX FLASH_READ page 9 (byte address 0x00900, 256 bytes): 69 96 52 02 00 09 00 00 01"
        ),
        "{log}"
    );
    assert!(
        log.lines()
            .any(|l| l.contains("Z +") && l.contains(" RX 50")),
        "{log}"
    );
    assert_says(&log, "SYSTEM_STATUS reports the Software Update flag");
}

#[test]
fn a_file_for_other_hardware_is_refused_before_anything_reaches_the_bootloader() {
    let rig = start();
    let file = write_hex(rig.dir.path(), "cu_3.hex", &to_hex_text(0, &bytes()));
    let o = flash_forced(&rig, &file);
    let err = stderr(&o);
    assert!(!o.status.success());
    assert!(
        err.contains("hardware 3") && err.contains("hardware 2"),
        "{err}"
    );
    untouched(&rig);
    let log = log_beside(&rig, "cu_3.hex");
    assert_says(&log, "refused before anything was sent to the bootloader");
}

#[test]
fn force_hardware_lets_an_unsuffixed_file_through_only_for_the_units_hardware() {
    let rig = start();
    let file = write_hex(rig.dir.path(), "cu.hex", &to_hex_text(0, &bytes()));
    let f = file.to_str().unwrap();
    let risk = ["--port", &rig.path, "--yes", "--force-image"];
    let o = flash(&[&risk[..], &[f]].concat());
    assert_says(&stderr(&o), "--force-hardware");
    let o = flash(&[&risk[..], &["--force-hardware", "3", f]].concat());
    assert!(!o.status.success());
    untouched(&rig);
    let o = flash(&[&risk[..], &["--force-hardware", "2", f]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn without_a_terminal_or_yes_nothing_is_sent_to_the_bootloader() {
    let rig = start();
    let file = write_hex(rig.dir.path(), "cu_2.hex", &to_hex_text(0, &bytes()));
    let o = flash(&["--port", &rig.path, "--force-image", file.to_str().unwrap()]);
    assert!(!o.status.success());
    assert_says(&stderr(&o), "--yes");
    untouched(&rig);
}

#[test]
fn a_damaged_file_is_refused_with_its_line_before_the_port_is_opened() {
    let dir = tempfile::tempdir().unwrap();
    let text = to_hex_text(0, &bytes()).replacen(":10001000", ":10001001", 1);
    let file = write_hex(dir.path(), "cu_2.hex", &text);
    // The port does not exist: the file is judged first, so the error is the file's.
    let o = flash(&[
        "--port",
        "/dev/does-not-exist-vpx",
        "--yes",
        file.to_str().unwrap(),
    ]);
    let err = stderr(&o);
    assert!(!o.status.success());
    assert_says(&err, "line 3:");
    assert!(!dir.path().join("cu_2.hex.log").exists());
}

#[test]
fn without_a_port_flash_says_how_to_try_it_on_the_virtual_unit() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_hex(dir.path(), "cu_2.hex", &to_hex_text(0, &bytes()));
    let o = flash(&["--yes", file.to_str().unwrap()]);
    assert!(!o.status.success());
    assert_says(&stderr(&o), "vpx-efis sim --pty");
}

/// SIGTERM mid-update: flash finishes the page in progress, leaves the unit in its
/// bootloader (never restarted into a half-written image), says to run it again, and
/// exits 128 + 15 as the exit codes (program::exit::MEANINGS) promise, not 1.
#[test]
fn a_signal_mid_update_stops_at_a_safe_point_and_exits_128_plus_n() {
    let rig = start();
    // Many pages, so the update is still running when the signal comes.
    let data: Vec<u8> = (0..400 * PAGE_SIZE).map(|i| (i * 7 + 3) as u8).collect();
    let file = write_hex(rig.dir.path(), "cu_2.hex", &to_hex_text(0x400, &data));
    let args = ["flash", "--port", &rig.path, "--yes", "--force-image"];
    let child = process::vpx(&args, process::NO_CONFIG)
        .arg(&file)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let until = std::time::Instant::now() + std::time::Duration::from_secs(20);
    while rig.sim.stats().boot.commands < 5 {
        assert!(std::time::Instant::now() < until, "the update never began");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    // SAFETY: a plain kill(2) of the child we spawned.
    unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) };
    let o = child.wait_with_output().unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(143), "{err}");
    assert_says(&err, "SIGTERM");
    assert!(rig.sim.stats().in_bootloader, "left in its bootloader");
}

/// A whole program as far as `flash` can tell: a reset vector at 0 (a JMP, written by
/// hand) and 9 KiB of code after it, in 16-byte records.
fn whole_program() -> String {
    let code: Vec<u8> = (0..9 * 1024).map(|i| (i * 31 + 7) as u8).collect();
    let body = to_hex_text(0x100, &code);
    // Page 0: the reset vector, JMP 0x0100 (0C 94 80 00), by hand.
    format!(":040000000C948000DC\n{body}")
}

/// Three images written by hand that cannot be a whole program, each
/// refused with its reason and numbers before the port is even opened: the unit
/// never hears a byte (no SOFTWARE_UPDATE, no bootloader command), its flash is as
/// it was, and it still runs its software.
#[test]
fn an_image_that_cannot_be_a_whole_program_is_refused_before_anything_is_sent() {
    let rig = start();
    let whole = whole_program();
    let (body, eof) = whole.rsplit_once(":00000001FF").unwrap();
    assert!(eof.trim().is_empty());
    for (name, text, why) in [
        (
            "four bytes",
            ":040000000C947200EA\n:00000001FF\n".to_string(),
            "it holds 4 bytes of data: far smaller than a whole program (at least 8192 bytes; \
             the unit's program memory is 253952 bytes, 0x00000–0x3dfff)",
        ),
        (
            "vector page missing",
            to_hex_text(0x100, &[0x5A; 9 * 1024]),
            "its reset/vector page (page 0, 0x00000–0x000ff) leaves the reset vector empty: the \
             unit would not start",
        ),
        (
            "a record outside the range",
            // The whole program, then 4 bytes at 0x3E000 (extended linear address 0x0003,
            // offset 0xE000): the bootloader's section.
            format!("{body}:020000040003F7\n:04E000000C9400007C\n:00000001FF\n"),
            "it has data outside the program range (0x00000–0x3dfff): 1 page up to 0x3e003, in \
             the bootloader's section",
        ),
    ] {
        let file = write_hex(rig.dir.path(), "cu_2.hex", &text);
        let o = flash(&["--port", &rig.path, "--yes", file.to_str().unwrap()]);
        let err = stderr(&o);
        assert!(!o.status.success(), "{name}: {err}");
        assert!(err.contains(why), "{name}: {err}");
        assert!(
            err.contains("Nothing was sent to the unit"),
            "{name}: {err}"
        );
        assert!(err.contains("--force-image"), "{name}: {err}");
        assert!(
            !err.contains("PRECAUTIONS"),
            "{name}: never got that far: {err}"
        );
        untouched(&rig);
        assert_eq!(rig.sim.stats().boot.commands, 0);
    }
    // The whole program itself is taken.
    let file = write_hex(rig.dir.path(), "cu_2.hex", &whole);
    let o = flash(&["--port", &rig.path, "--yes", file.to_str().unwrap()]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains(
            "covers: 9220 bytes of data, 37 of 992 program pages (3.7 %), reset vector given"
        ),
        "{err}"
    );
    assert_eq!(&rig.sim.flash()[..4], &[0x0C, 0x94, 0x80, 0x00]);
}

/// `--force-image` takes the risk: the four bytes go to the unit, with a warning
/// that names why it could not be whole, and the coverage beside the precautions.
#[test]
fn force_image_flashes_an_image_that_cannot_be_whole_with_a_warning() {
    let rig = start();
    let file = write_hex(
        rig.dir.path(),
        "cu_2.hex",
        ":040000000C947200EA\n:00000001FF\n",
    );
    let o = flash_forced(&rig, &file);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("WARNING (--force-image)") && err.contains("it holds 4 bytes of data"),
        "{err}"
    );
    assert_says(
        &err,
        "covers: 4 bytes of data, 1 of 992 program pages (0.1 %), reset vector given",
    );
    let flash = rig.sim.flash();
    assert_eq!(&flash[..4], &[0x0C, 0x94, 0x72, 0x00]);
    assert!(flash[4..].iter().all(|&b| b == 0xFF));
    let log = log_beside(&rig, "cu_2.hex");
    assert_says(&log, "flashed with --force-image although it holds 4 bytes");
}

/// `--yes` skips only the question. The §7.3 precautions are printed on
/// every update, before the erase.
#[test]
fn flash_yes_still_states_the_precautions_before_the_erase() {
    let rig = start();
    let file = write_hex(rig.dir.path(), "cu_2.hex", &whole_program());
    let o = flash(&["--port", &rig.path, "--yes", file.to_str().unwrap()]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let at = |what: &str| {
        err.find(what)
            .unwrap_or_else(|| panic!("no {what:?} in: {err}"))
    };
    let precautions = at("PRECAUTIONS (ICD §7.3). Until this command says it is done:");
    assert!(precautions < at("  - NEVER switch off or cycle power to the VP-X;"));
    assert!(precautions < at("  - NEVER unplug the serial cable."));
    assert!(at("  - NEVER unplug the serial cable.") < at("FLASH_ERASE answered 'e'"));
    assert!(!err.contains("Type \"yes\""), "--yes asks nothing: {err}");
}

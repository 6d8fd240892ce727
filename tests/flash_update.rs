//! The firmware update against the virtual VP-X's modelled bootloader, over a real
//! pseudo-terminal (the sim on the master, the updater on the slave's path, opened as a
//! serial port like a real cable), plus a small scripted bootloader for what the sim
//! cannot be told to do (a wrong signature).
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::io::{Read, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use vpx_efis::flash::hex::to_hex_text;
use vpx_efis::flash::{self, Event, Found, Image, Left, Options, UpdateError, UpdateReport};
use vpx_efis::link::{PtyPair, open_pty_pair, open_serial};
use vpx_efis::protocol::bootloader::{
    BootCommand, BootCommandDecoder, BootResponse, PAGE_SIZE, SIGNATURE,
};
use vpx_efis::protocol::message::{HardwareVersion, Message, Version};
use vpx_efis::protocol::{Decoder, Event as WireEvent, Packet};
use vpx_efis::sim::{self, SimCommand, SimOptions};

mod common;
use common::rig::PtyUnit;

/// Short timeouts: on a pty answers come in microseconds, and the failure tests wait
/// out every try.
fn fast() -> Options {
    Options {
        timeout: Duration::from_millis(300),
        tries: 3,
        erase_timeout: Duration::from_secs(2),
        erase_tries: 2,
        enter_tries: 2,
        enter_delay: Duration::from_millis(100),
        reprogram_tries: 2,
        passes: 2,
        reboot_timeout: Duration::from_secs(5),
        quiet: Duration::from_millis(50),
        cancel: None,
    }
}

/// For a detection that must find the unit: the same, with time for a first answer from
/// a sim thread just started on a loaded machine (detection returns at the answer,
/// so this costs nothing when it comes at once).
fn answering() -> Options {
    Options {
        timeout: Duration::from_secs(2),
        ..fast()
    }
}

fn start_sim() -> PtyUnit {
    let opts = SimOptions::new(sim::load_scenario("demo").unwrap());
    assert_eq!(opts.hardware_version, 2, "these tests flash cu_2 images");
    PtyUnit::start(opts)
}

fn port(path: &str) -> Box<dyn serialport::SerialPort> {
    open_serial(std::path::Path::new(path), 57_600).unwrap()
}

/// Two regions: 9 pages from 0 (the last one partial) and 3 pages behind an Extended
/// Linear Address record at 0x1F000; byte 128 of every page set by `byte128`.
fn image_text(byte128: u8) -> String {
    let mut a: Vec<u8> = (0..(8 * PAGE_SIZE + 100))
        .map(|i| (i as u32).wrapping_mul(2_654_435_761).rotate_right(13) as u8)
        .collect();
    let mut b: Vec<u8> = (0..3 * PAGE_SIZE).map(|i| (i * 31 + 7) as u8).collect();
    for page in a.chunks_mut(PAGE_SIZE).chain(b.chunks_mut(PAGE_SIZE)) {
        if page.len() > 128 {
            page[128] = byte128;
        }
    }
    let first = to_hex_text(0, &a);
    let first = first.trim_end().strip_suffix(":00000001FF").unwrap();
    format!("{first}{}", to_hex_text(0x1F000, &b))
}

fn image(byte128: u8) -> Image {
    flash::parse_hex(&image_text(byte128)).unwrap()
}

/// Everything the updater reported, as lines, plus the commands sent.
#[derive(Default)]
struct Seen {
    lines: Vec<String>,
    sent: Vec<String>,
}

impl Seen {
    fn take(&mut self, e: &Event<'_>) {
        match e {
            Event::Sent { what, .. } => {
                self.sent.push(what.to_string());
                self.lines.push(format!("TX {what}"));
            }
            Event::Note(n) => self.lines.push(format!("-- {n}")),
            _ => {}
        }
    }
    fn sent_any(&self, name: &str) -> bool {
        self.sent.iter().any(|s| s.starts_with(name))
    }
    fn dump(&self) -> String {
        self.lines.join("\n")
    }
}

/// One run of the updater: what it found, what the update came to, and all it reported.
struct Run {
    found: Found,
    result: Result<UpdateReport, UpdateError>,
    seen: Seen,
}

impl Run {
    fn done(self) -> (UpdateReport, Seen) {
        let Run { result, seen, .. } = self;
        (
            result.unwrap_or_else(|e| panic!("{e}\n{}", seen.dump())),
            seen,
        )
    }

    fn stopped(self, why: &str) -> (UpdateError, Seen) {
        let Run { result, seen, .. } = self;
        match result {
            Ok(r) => panic!("{why}: {r:?}\n{}", seen.dump()),
            Err(e) => (e, seen),
        }
    }
}

/// Detects the unit on `path` with `detect` and updates it to `img` with `opts`, as
/// `vpx-efis flash` does, `during` seeing each event of the update as it comes. The
/// port is closed on return, as by a pulled cable if the update did not end.
fn flash_unit(
    path: &str,
    img: &Image,
    detect: &Options,
    opts: &Options,
    mut during: impl FnMut(&Event<'_>),
) -> Run {
    let mut p = port(path);
    let mut seen = Seen::default();
    let found = flash::detect(&mut p, detect, &mut |e| seen.take(&e))
        .unwrap_or_else(|e| panic!("{e}\n{}", seen.dump()));
    let result = flash::update(&mut p, img, found, opts, &mut |e| {
        during(&e);
        seen.take(&e)
    });
    Run {
        found,
        result,
        seen,
    }
}

/// The re-run an interrupted update advises: it finds the unit in its bootloader and
/// finishes, with `img` in flash.
fn rerun(rig: &PtyUnit, img: &Image) -> (UpdateReport, Seen) {
    let run = flash_unit(&rig.path, img, &fast(), &fast(), |_| {});
    assert_eq!(run.found, Found::Bootloader, "{}", run.seen.dump());
    let done = run.done();
    assert!(rig.sim.flash() == img.to_flash());
    assert!(!rig.sim.stats().in_bootloader);
    done
}

/// An update stopped partway: the unit is left in its bootloader, never sent EXIT into
/// a half-written image, and the error says `what` and how to resume.
fn left_in_its_bootloader(rig: &PtyUnit, err: &UpdateError, seen: &Seen, what: &str) {
    assert_eq!(
        err.left,
        Left::InBootloader {
            flash_changed: true
        },
        "{err}"
    );
    let text = err.to_string();
    assert!(text.contains(what), "{text}");
    assert!(text.contains("run the same command again"), "{text}");
    assert!(
        !seen.sent_any("EXIT"),
        "never EXIT into a half-written image: {}",
        seen.dump()
    );
    assert!(rig.sim.stats().in_bootloader);
}

/// An update of `img` cancelled (Ctrl-C) when the updater sends the command whose
/// description starts with `at`.
fn interrupted_at(rig: &PtyUnit, img: &Image, at: &str) -> (UpdateError, Seen) {
    let cancel = Arc::new(AtomicBool::new(false));
    let opts = Options {
        cancel: Some(cancel.clone()),
        ..fast()
    };
    let run = flash_unit(&rig.path, img, &opts, &opts, |e| {
        if let Event::Sent { what, .. } = e
            && what.starts_with(at)
        {
            cancel.store(true, Ordering::SeqCst);
        }
    });
    run.stopped("an interrupted update is not a success")
}

#[test]
fn a_full_update_leaves_the_image_in_flash_and_the_unit_back_with_the_flag() {
    let rig = start_sim();
    let img = image(0x33);
    assert_eq!(img.page_count(), 12);
    let run = flash_unit(&rig.path, &img, &answering(), &fast(), |_| {});
    let Found::Running(v) = run.found else {
        panic!("a fresh sim runs its software: {:?}", run.found)
    };
    assert_eq!(v.hardware_version, HardwareVersion::VpxPro);
    let (out, seen) = run.done();

    assert!(
        rig.sim.flash() == img.to_flash(),
        "flash differs from the image"
    );
    let st = rig.sim.stats();
    assert!(!st.in_bootloader);
    assert!(st.software_update_flag);
    assert_eq!(st.boot.erases, 1);
    assert_eq!(st.boot.pages_programmed, 12);
    assert_eq!(out.passes, 1);
    assert!(out.repaired_pages.is_empty());
    assert_eq!(out.version.hardware_version, HardwareVersion::VpxPro);
    assert_eq!(out.software_update_flag, Some(true));
    // The order of §7 and every page addressed by its page number.
    let order: Vec<&str> = [
        "SOFTWARE_UPDATE",
        "SERIAL_CONF",
        "QUERY_PORT",
        "SIGNATURE",
        "VERSION",
        "FLASH_ERASE",
        "FLASH_PROG page 0 ",
        "FLASH_PROG page 496 ",
        "FLASH_READ page 0 ",
        "FLASH_READ page 498 ",
        "EXIT",
    ]
    .to_vec();
    let mut at = 0;
    for want in order {
        let i = seen.sent[at..]
            .iter()
            .position(|s| s.starts_with(want))
            .unwrap_or_else(|| panic!("{want} not sent after {at}:\n{}", seen.dump()));
        at += i + 1;
    }
    assert!(seen.sent_any("FLASH_PROG page 496 (byte address 0x1f000"));
}

/// Corrupts the FLASH_PROG of the image's 4th page: the injection is made once the 3rd
/// page's 'P' has come back, well before the 4th page's frame is written.
fn corrupt_fourth_page(rig: &PtyUnit, byte128: u8) -> (UpdateReport, Seen) {
    let img = image(byte128);
    let armed = AtomicBool::new(true);
    let (out, seen) = flash_unit(&rig.path, &img, &answering(), &fast(), |e| {
        if let Event::Progress(pr) = e
            && pr.programmed == 3
            && armed.swap(false, Ordering::SeqCst)
        {
            rig.sim.inject(SimCommand::CorruptNextFlashProg);
            // Commands are taken in order: once stats answers, the injection is in,
            // before the next frame is written (else the sim may read it first).
            let _ = rig.sim.stats();
        }
    })
    .done();
    assert!(
        rig.sim.flash() == img.to_flash(),
        "flash differs from the image:\n{}",
        seen.dump()
    );
    assert!(
        seen.lines
            .iter()
            .any(|l| l.contains("VERIFY FAILED page 3 ")),
        "verify did not catch it:\n{}",
        seen.dump()
    );
    (out, seen)
}

#[test]
fn corruption_that_programming_again_can_fix_is_repaired_in_place() {
    // The sim flips byte 128 with 0x5A and ANDs into flash. 0xA5 has none of 0x5A's
    // bits, so the corrupt write left extra 1s and a second FLASH_PROG clears them.
    let rig = start_sim();
    let (out, seen) = corrupt_fourth_page(&rig, 0xA5);
    assert_eq!(out.repaired_pages, vec![3], "{}", seen.dump());
    assert_eq!(out.passes, 1);
    assert_eq!(rig.sim.stats().boot.erases, 1);
}

#[test]
fn corruption_that_cleared_bits_is_repaired_by_a_second_erase_pass() {
    // 0xFF & (0xFF ^ 0x5A) leaves 0s where the image has 1s: only an erase sets them.
    let rig = start_sim();
    let (out, seen) = corrupt_fourth_page(&rig, 0xFF);
    assert_eq!(out.passes, 2, "{}", seen.dump());
    assert_eq!(rig.sim.stats().boot.erases, 2);
    assert!(seen.lines.iter().any(|l| l.contains("only an erase")));
}

#[test]
fn a_link_dropped_mid_update_leaves_the_unit_in_its_bootloader_and_a_rerun_resumes() {
    let rig = start_sim();
    let img = image(0x42);
    let armed = AtomicBool::new(true);
    let (err, seen) = flash_unit(&rig.path, &img, &answering(), &fast(), |e| {
        if let Event::Progress(pr) = e
            && pr.programmed == 5
            && armed.swap(false, Ordering::SeqCst)
        {
            // Nothing comes back for 4 s: the unit hears us, we do not hear it.
            rig.sim.inject(SimCommand::Silent(Duration::from_secs(4)));
            let _ = rig.sim.stats();
        }
    })
    .stopped("an update whose answers stop must not succeed");
    left_in_its_bootloader(&rig, &err, &seen, "STILL IN ITS BOOTLOADER");
    assert!(rig.sim.flash() != img.to_flash());
    std::thread::sleep(Duration::from_millis(3500));

    let (out, again) = rerun(&rig, &img);
    // A resumed unit is not sent SOFTWARE_UPDATE: it is already in its bootloader.
    assert!(!again.sent_any("SOFTWARE_UPDATE"), "{}", again.dump());
    assert_eq!(
        rig.sim.stats().boot.erases,
        2,
        "the resume starts over from the erase"
    );
    assert_eq!(out.version.hardware_version, HardwareVersion::VpxPro);
}

/// Ctrl-C while a page is being programmed: that page is finished (its 'P' awaited),
/// nothing more is sent, EXIT above all, the error says how to resume, and a re-run
/// does resume. Ctrl-C before the erase returns the unit to its software.
#[test]
fn an_interrupt_mid_update_finishes_the_page_never_exits_and_a_rerun_resumes() {
    let rig = start_sim();
    let img = image(0x24);
    // Pressed while page 3's frame is on its way, before its answer.
    let (err, seen) = interrupted_at(&rig, &img, "FLASH_PROG page 3 ");
    left_in_its_bootloader(
        &rig,
        &err,
        &seen,
        "interrupted after programming page 3 (4 of 12)",
    );
    let progs = seen
        .sent
        .iter()
        .filter(|s| s.starts_with("FLASH_PROG"))
        .count();
    assert_eq!(progs, 4, "pages 0-3 and nothing after:\n{}", seen.dump());
    assert!(!seen.sent_any("FLASH_READ"), "{}", seen.dump());
    assert_eq!(
        rig.sim.stats().boot.pages_programmed,
        4,
        "page 3 was finished, not cut"
    );
    rerun(&rig, &img);
}

#[test]
fn an_interrupt_before_the_erase_gives_the_unit_its_software_back() {
    let rig = start_sim();
    let img = image(0x25);
    let before = rig.sim.flash();
    let (err, seen) = interrupted_at(&rig, &img, "SIGNATURE");
    assert_eq!(err.left, Left::BackToOldSoftware, "{err}\n{}", seen.dump());
    assert!(!seen.sent_any("FLASH_ERASE"), "{}", seen.dump());
    assert!(seen.sent_any("EXIT"), "{}", seen.dump());
    assert!(rig.sim.flash() == before, "nothing was erased");
}

// ---------------------------------------------------------------- scripted bootloader

/// A unit that answers VERSION (hardware 2) in the main protocol, enters a bootloader
/// on SOFTWARE_UPDATE, and there answers SIGNATURE with `signature`. Records every
/// bootloader command it takes. Enough to see what the updater does with a chip that
/// is not the VP-X's, which the sim cannot be told to be.
struct Scripted {
    commands: Arc<Mutex<Vec<BootCommand>>>,
    stop: Arc<AtomicBool>,
    _pty_slave: serialport::TTYPort,
    path: String,
}

impl Drop for Scripted {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
    }
}

fn scripted(signature: [u8; 3], start_in_bootloader: bool) -> Scripted {
    let PtyPair {
        mut master,
        slave,
        path,
    } = open_pty_pair().unwrap();
    let commands = Arc::new(Mutex::new(Vec::new()));
    let stop = Arc::new(AtomicBool::new(false));
    let (c, s) = (commands.clone(), stop.clone());
    std::thread::spawn(move || {
        let mut in_boot = start_in_bootloader;
        let mut normal = Decoder::new();
        let mut boot = BootCommandDecoder::new();
        let mut buf = [0u8; 1024];
        while !s.load(Ordering::SeqCst) {
            let n = match master.read(&mut buf) {
                Ok(n) => n,
                Err(_) => continue,
            };
            let mut out = Vec::new();
            for &b in &buf[..n] {
                if in_boot {
                    let Some(cmd) = boot.push(b) else { continue };
                    c.lock().unwrap().push(cmd.clone());
                    let reply = match cmd {
                        BootCommand::SerialConf { .. } => BootResponse::SerialConf,
                        BootCommand::QueryPort => BootResponse::Port,
                        BootCommand::Signature => BootResponse::Signature(signature),
                        BootCommand::Version => BootResponse::Version(0x0100),
                        BootCommand::Exit => {
                            in_boot = false;
                            BootResponse::Exit
                        }
                        BootCommand::FlashErase => BootResponse::Erased,
                        BootCommand::FlashProg { .. } => BootResponse::Programmed,
                        BootCommand::FlashRead { size, .. } => {
                            BootResponse::Flash(vec![0xFF; size as usize])
                        }
                    };
                    out.extend(reply.emit());
                } else {
                    let mut got = Vec::new();
                    normal.push(&[b], |e| {
                        if let WireEvent::Frame(f) = e
                            && let Ok(p) = Packet::parse(&f)
                        {
                            got.push(p);
                        }
                    });
                    for p in got {
                        match p.message {
                            Message::Version(_) => out.extend(
                                Packet::from_vpx(
                                    p.cnt,
                                    Version {
                                        hardware_version: HardwareVersion::VpxPro,
                                        software_major: 2,
                                        software_minor: 1,
                                    },
                                )
                                .to_bytes(),
                            ),
                            Message::SoftwareUpdate(_) => in_boot = true,
                            _ => {}
                        }
                    }
                }
            }
            if !out.is_empty() {
                let _ = master.write_all(&out);
            }
        }
    });
    Scripted {
        commands,
        stop,
        _pty_slave: slave,
        path,
    }
}

#[test]
fn the_scripted_bootloader_with_the_right_signature_takes_a_whole_update() {
    // Guards the double itself: with the VP-X's signature it must let an update through,
    // so the wrong-signature test below fails for the signature and nothing else.
    let s = scripted(SIGNATURE, false);
    let img = flash::parse_hex(&to_hex_text(0, &[0xFF; 300])).unwrap();
    flash_unit(&s.path, &img, &answering(), &fast(), |_| {}).done();
    assert!(
        s.commands
            .lock()
            .unwrap()
            .contains(&BootCommand::FlashErase)
    );
}

#[test]
fn a_wrong_signature_stops_before_erase_and_returns_the_unit_to_its_software() {
    // The ATmega2560's signature in forward order: the VP-X sends it reversed.
    let s = scripted([0x1E, 0x98, 0x01], false);
    let run = flash_unit(&s.path, &image(0x11), &answering(), &fast(), |_| {});
    assert!(matches!(run.found, Found::Running(_)));
    let (err, _) = run.stopped("a wrong signature must stop the update");
    assert!(err.reason.contains("1E 98 01"), "{err}");
    assert_eq!(err.left, Left::BackToOldSoftware, "{err}");
    let cmds = s.commands.lock().unwrap().clone();
    assert!(
        !cmds
            .iter()
            .any(|c| matches!(c, BootCommand::FlashErase | BootCommand::FlashProg { .. })),
        "erased or programmed after a wrong signature: {cmds:?}"
    );
    // Nothing was erased and this run entered the bootloader: EXIT gives the aircraft
    // its old software back.
    assert_eq!(cmds.last(), Some(&BootCommand::Exit));
}

#[test]
fn a_wrong_signature_on_a_unit_found_in_its_bootloader_does_not_exit() {
    // Found there, the flash may be half written by an earlier run: no EXIT.
    let s = scripted([0x00, 0x00, 0x00], true);
    let run = flash_unit(&s.path, &image(0x11), &answering(), &fast(), |_| {});
    assert_eq!(run.found, Found::Bootloader);
    let (err, _) = run.stopped("a wrong signature must stop the update");
    assert_eq!(
        err.left,
        Left::InBootloader {
            flash_changed: true
        }
    );
    let cmds = s.commands.lock().unwrap().clone();
    assert!(!cmds.contains(&BootCommand::Exit), "{cmds:?}");
    assert!(!cmds.contains(&BootCommand::FlashErase), "{cmds:?}");
}

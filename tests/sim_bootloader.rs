//! ICD §7 against the sim over a pty: SOFTWARE_UPDATE, then the bootloader frames of
//! `protocol::bootloader`, then EXIT back to the main protocol with the flag set.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

mod sim_common;

use sim_common::{scenario, start};
use vpx_efis::protocol::bootloader::{BootCommand, PAGE_SIZE};
use vpx_efis::protocol::message::*;
use vpx_efis::sim::SimCommand;

#[test]
fn update_then_exit_sets_the_software_update_flag() {
    let (sim, mut c) = start(scenario(""), |_| {});
    c.send(SoftwareUpdate);
    // Wait until the unit has gone quiet, then talk bootloader.
    let t = std::time::Instant::now();
    while !sim.stats().in_bootloader {
        assert!(t.elapsed() < sim_common::TIMEOUT);
        c.poll();
    }
    c.pump(std::time::Duration::from_millis(300));
    let exchange = |c: &mut sim_common::Client, cmd: BootCommand, n: usize| {
        let from = c.raw.len();
        c.send_raw(&cmd.emit());
        c.raw_after(from, n)
    };
    assert_eq!(exchange(&mut c, BootCommand::QueryPort, 10), b"VP_AVRBOOT");
    assert_eq!(
        exchange(&mut c, BootCommand::Signature, 3),
        [0x01, 0x98, 0x1E]
    );
    assert_eq!(exchange(&mut c, BootCommand::serial_conf(), 3), b"!!!");
    assert_eq!(exchange(&mut c, BootCommand::FlashErase, 1), b"e");
    let page: Vec<u8> = (0..PAGE_SIZE).map(|i| (i * 7) as u8).collect();
    let prog = BootCommand::flash_prog(5, &page).unwrap();
    assert_eq!(exchange(&mut c, prog.clone(), 1), b"P");
    assert_eq!(
        exchange(&mut c, BootCommand::flash_read_page(5), PAGE_SIZE),
        page
    );
    // An injected bad write is caught by reading back.
    sim.inject(SimCommand::CorruptNextFlashProg);
    // stats() answers through the same control channel, after the injection: the
    // corruption is armed before the page's bytes can overtake it.
    let _ = sim.stats();
    let prog6 = BootCommand::flash_prog(6, &page).unwrap();
    assert_eq!(exchange(&mut c, prog6, 1), b"P");
    assert_ne!(
        exchange(&mut c, BootCommand::flash_read_page(6), PAGE_SIZE),
        page
    );
    assert_eq!(&sim.flash()[5 * PAGE_SIZE..6 * PAGE_SIZE], &page[..]);
    assert_eq!(exchange(&mut c, BootCommand::Exit, 1), b"x");

    let s = c.next("SYSTEM_STATUS after the reboot", |m| match m {
        Message::SystemStatus(s) => Some(*s),
        _ => None,
    });
    assert!(s.misc.software_update, "Table 24 note 1");
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
    sim.inject(SimCommand::PowerCycle);
    c.next("SYSTEM_STATUS after a power cycle", |m| match m {
        Message::SystemStatus(s) if !s.misc.software_update => Some(()),
        _ => None,
    });
}

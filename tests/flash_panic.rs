//! `vpx-efis flash` on the app's panic path, in a process of its own (the panic hook
//! is global): a panic on any thread mid-update stops the update as a signal does, at
//! the next safe point, with the unit left in its bootloader (never restarted into a
//! half-written image) and the reason in the exchange log.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

use vpx_efis::cmd::flash::{FlashArgs, FlashPortArgs, run};
use vpx_efis::flash::hex::to_hex_text;
use vpx_efis::link::open_pty_pair;
use vpx_efis::protocol::bootloader::PAGE_SIZE;
use vpx_efis::sim::{self, SimOptions};

#[test]
fn a_panic_mid_update_stops_it_at_a_safe_point_with_the_unit_in_its_bootloader() {
    let pty = open_pty_pair().unwrap();
    let reader = pty.master.try_clone_native().unwrap();
    // The real line's pace, so the update lasts long enough to panic in its middle.
    let opts = SimOptions::new(sim::load_scenario("demo").unwrap()).paced();
    let sim = sim::spawn(opts, Box::new(reader), Box::new(pty.master));
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("cu_2.hex");
    let data: Vec<u8> = (0..16 * PAGE_SIZE).map(|i| (i * 7 + 3) as u8).collect();
    std::fs::write(&file, to_hex_text(0, &data)).unwrap();
    let log = dir.path().join("flash.log");
    let args = FlashArgs {
        port: FlashPortArgs {
            port: Some(pty.path.parse().unwrap()),
            baud: 57_600,
        },
        file,
        force_hardware: None,
        force_image: true,
        yes: true,
        log: Some(log.clone()),
    };
    let update = std::thread::spawn(move || run(args));

    let end = Instant::now() + Duration::from_secs(30);
    while sim.stats().boot.pages_programmed < 2 {
        assert!(Instant::now() < end, "the update never got under way");
        assert!(!update.is_finished(), "{:?}", update.join());
        std::thread::sleep(Duration::from_millis(5));
    }
    let crashed = std::thread::spawn(|| panic!("simulated crash beside the update")).join();
    assert!(crashed.is_err());
    let result = update
        .join()
        .expect("the update's own thread did not panic");
    let err = result.expect_err("an update after a panic is not finished as a success");
    let s = sim.stats();
    assert!(
        s.in_bootloader,
        "restarted after a panic: {err:#}\n{}",
        std::fs::read_to_string(&log).unwrap()
    );
    assert!(
        s.boot.pages_programmed < 16,
        "every page was programmed after the panic: {err:#}"
    );
    let text = std::fs::read_to_string(&log).unwrap();
    assert!(
        text.contains("-- a thread of vpx-efis panicked: stopping at the next safe point"),
        "{text}"
    );
    assert!(
        format!("{err:#}").contains("run the same command again"),
        "{err:#}"
    );
    vpx_efis::app::clear_emergency_stop();
    sim.stop();
    drop(pty.slave);
}

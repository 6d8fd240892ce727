//! Serial over TCP end to end: the page against `vpx-efis sim --tcp` (a second
//! process, as a Windows user runs it), the page reconnecting after that process goes
//! away and comes back on the same port, and `flash` through a TCP line to the virtual
//! unit's bootloader.

use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use vpx_efis::app::{App, AppOptions};
use vpx_efis::flash::hex::to_hex_text;
use vpx_efis::link::{self, PortAddr};
use vpx_efis::model::{Connection, Source};
use vpx_efis::protocol::bootloader::PAGE_SIZE;

mod common;
#[path = "common/tcp_unit.rs"]
mod tcp_unit;
use common::app::until;
use common::process::{self, NO_CONFIG, Sim};
use tcp_unit::unit_over_tcp;

/// `vpx-efis sim --tcp ADDR` as a child process; killed when dropped.
struct SimProcess {
    _sim: Sim,
    addr: PortAddr,
}

impl SimProcess {
    fn start(bind: &str) -> SimProcess {
        let sim = common::process::sim(&["--tcp", bind, "--scenario", "demo"]);
        let addr: PortAddr = sim.line.parse().expect("tcp://HOST:PORT first");
        assert!(addr.is_tcp(), "{}", sim.line);
        SimProcess { _sim: sim, addr }
    }

    fn port(&self) -> u16 {
        match &self.addr {
            PortAddr::Tcp { port, .. } => *port,
            PortAddr::Serial(_) => unreachable!(),
        }
    }
}

fn page(addr: &PortAddr) -> App {
    App::new(
        Source::Serial {
            path: addr.to_string(),
        },
        link::port_connector(addr, 57_600),
        AppOptions::default(),
    )
}

fn ready(app: &App, now: Instant) -> bool {
    let m = app.model();
    m.live_system(now).is_some()
        && m.live_devices(now).is_some()
        && m.names.iter().all(Option::is_some)
}

fn key(app: &mut App, c: char) {
    let mut k = KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE);
    k.kind = KeyEventKind::Press;
    app.handle_term_event(Event::Key(k), Instant::now());
}

#[test]
fn the_page_against_sim_tcp_switches_a_device_and_sees_it_on() {
    let sim = SimProcess::start("127.0.0.1:0");
    let mut app = page(&sim.addr);
    until(
        &mut app,
        "the device list over TCP",
        Duration::from_secs(8),
        ready,
    );
    match &app.model().connection {
        Connection::Connected { port, .. } => assert_eq!(*port, sim.addr.to_string()),
        other => panic!("{other:?}"),
    }
    // The first device that is off, selected with the keys, switched on with `o`.
    let now = Instant::now();
    let off = {
        let m = app.model();
        let d = m.live_devices(now).unwrap();
        (4..=28u8)
            .find(|&i| !d.on[i as usize])
            .expect("an off device in demo")
    };
    for _ in 0..40 {
        if app.view().selected == Some(off) {
            break;
        }
        key(&mut app, 'j');
    }
    assert_eq!(
        app.view().selected,
        Some(off),
        "could not select device {off}"
    );
    key(&mut app, 'o');
    until(
        &mut app,
        "DEVICE_STATUS with the device on, from the other process",
        Duration::from_secs(3),
        |app, now| {
            app.model()
                .live_devices(now)
                .is_some_and(|d| d.on[off as usize])
        },
    );
    app.shutdown();
}

#[test]
fn the_page_reconnects_when_the_tcp_peer_closes_and_comes_back() {
    let sim = SimProcess::start("127.0.0.1:0");
    let port = sim.port();
    let mut app = page(&sim.addr);
    until(&mut app, "live data", Duration::from_secs(8), ready);

    // The bridge goes away: its connection closes and nothing listens any more.
    drop(sim);
    until(
        &mut app,
        "the page to notice the closed connection",
        Duration::from_secs(5),
        |app, _| matches!(app.model().connection, Connection::Lost { .. }),
    );
    let reason = match &app.model().connection {
        Connection::Lost { reason, .. } => reason.clone(),
        _ => unreachable!(),
    };
    assert!(
        reason.contains("closed the connection") || reason.contains("connection refused"),
        "{reason}"
    );

    // It comes back on the same port: the page finds it by itself.
    let again = SimProcess::start(&format!("127.0.0.1:{port}"));
    until(
        &mut app,
        "reconnected with live data",
        Duration::from_secs(8),
        |app, now| {
            matches!(app.model().connection, Connection::Connected { .. })
                && !app.model().comm_lost(now)
                && ready(app, now)
        },
    );
    let connects = app
        .model()
        .events
        .iter()
        .filter(|e| e.text.starts_with("connected to tcp://127.0.0.1:"))
        .count();
    assert_eq!(connects, 2);
    drop(again);
    app.shutdown();
}

#[test]
fn flash_over_tcp_programs_and_verifies_the_image() {
    let (unit, addr) = unit_over_tcp("demo");
    let dir = tempfile::tempdir().unwrap();
    let data: Vec<u8> = (0..3 * PAGE_SIZE + 5).map(|i| (i * 7 + 3) as u8).collect();
    let file = dir.path().join("cu_2.hex");
    std::fs::write(&file, to_hex_text(0x200, &data)).unwrap();
    // A small image, not a whole program: --force-image takes that risk (the refusal
    // itself is tested in flash_cli), so the test stays about the TCP path.
    let args = ["flash", "--port", &addr, "--yes", "--force-image"];
    let o = process::vpx(&args, NO_CONFIG).arg(&file).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains(&format!("unit on {addr}: hardware 2")),
        "{err}"
    );
    assert!(err.contains("4 pages programmed and verified"), "{err}");
    let flash = unit.flash();
    assert_eq!(&flash[0x200..0x200 + data.len()], &data[..]);
    assert!(flash[..0x200].iter().all(|&b| b == 0xFF));
    let log = std::fs::read_to_string(dir.path().join("cu_2.hex.log")).unwrap();
    assert!(
        log.contains(&format!("flash {} to {addr} at", file.display())),
        "{log}"
    );
}

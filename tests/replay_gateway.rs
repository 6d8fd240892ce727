//! `vpx-efis gateway --record FILE`: the headless bridge writes a capture that is
//! readable while it runs (flushed within a second even when idle) and replays.

use std::net::{Ipv4Addr, SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use vpx_efis::app::Capture;
use vpx_efis::cmd::gateway::{BridgeOptions, run_bridge};
use vpx_efis::link::Crossing;
use vpx_efis::xfsp::gateway::GatewayConfig;
use vpx_efis::xfsp::net::Target;

#[test]
fn the_gateway_records_both_directions_flushed_while_running() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("gw.vpxcap");
    // Somewhere harmless for the datagrams to go.
    let sink = UdpSocket::bind((Ipv4Addr::LOCALHOST, 0)).unwrap();
    let SocketAddr::V4(peer) = sink.local_addr().unwrap() else {
        unreachable!("bound on IPv4")
    };
    let opts = BridgeOptions {
        port: None,
        baud: 57_600,
        scenario: "demo".into(),
        target: Target::Unicast(peer),
        iface: Ipv4Addr::LOCALHOST,
        gateway: GatewayConfig::default(),
        record: Some(path.clone()),
        logbook: None,
    };
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let bridge = std::thread::spawn(move || run_bridge(&opts, &s, |_| {}));

    // While it runs, the file already holds what crossed the wire up to the last second.
    std::thread::sleep(Duration::from_millis(2500));
    let running = Capture::from_bytes("gw", &std::fs::read(&path).unwrap()).unwrap();
    assert!(
        running.records.iter().any(|r| r.dir == Crossing::Rx),
        "nothing flushed while running"
    );
    assert!(
        running.length() >= Duration::from_millis(1000),
        "{:?}",
        running.length()
    );

    stop.store(true, Ordering::SeqCst);
    bridge.join().unwrap().unwrap();
    let done = Capture::from_bytes("gw", &std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(done.problem, None);
    assert!(done.records.len() >= running.records.len());
    assert!(
        done.records.iter().any(|r| r.dir == Crossing::Tx),
        "the bridge's queries"
    );
}

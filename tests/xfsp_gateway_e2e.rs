//! End to end: the virtual VP-X on a real pseudo-terminal, the headless bridge
//! (`cmd::gateway::run_bridge`) on a serial port to it, and a peer on real UDP sockets
//! on 127.0.0.1. Every wait is bounded.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use vpx_efis::cmd::gateway::{BridgeOptions, run_bridge};
use vpx_efis::sim::{self, SimCommand, SimHandle, SimOptions};
use vpx_efis::xfsp::format::latin1;
use vpx_efis::xfsp::gateway::{Control, GatewayConfig};
use vpx_efis::xfsp::net::{Target, XfspNet};
mod common;
use common::rig::PtyUnit;
#[path = "common/xfsp_request.rs"]
mod xfsp_request;

use vpx_efis::xfsp::{
    Body, CasLevel, CertLevel, Confidence, EcbState, Message, MsgKind, Parameter, Sender, Value,
    idents,
};

const GW: u16 = 0x5650;
const PEER: u16 = 0x0777;
const EFIS: u16 = 2;

struct Bridge {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<anyhow::Result<()>>>,
    lines: Arc<Mutex<Vec<String>>>,
}

impl Bridge {
    fn start(opts: BridgeOptions) -> Bridge {
        let stop = Arc::new(AtomicBool::new(false));
        let lines = Arc::new(Mutex::new(Vec::new()));
        let thread = {
            let (stop, lines) = (stop.clone(), lines.clone());
            std::thread::spawn(move || {
                run_bridge(&opts, &stop, |l| lines.lock().unwrap().push(l.to_string()))
            })
        };
        Bridge {
            stop,
            thread: Some(thread),
            lines,
        }
    }

    fn lines(&self) -> Vec<String> {
        self.lines.lock().unwrap().clone()
    }
}

impl Drop for Bridge {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let r = t.join().expect("bridge thread panicked");
            if !std::thread::panicking() {
                r.expect("bridge failed");
            }
        }
    }
}

/// The other node: receives what the gateway publishes, sends requests back to it.
struct Peer {
    sock: UdpSocket,
    gateway: Option<SocketAddr>,
    sender: Sender,
    id: u16,
}

impl Peer {
    fn new() -> Peer {
        Peer::with_id(PEER)
    }

    fn with_id(id: u16) -> Peer {
        let sock = UdpSocket::bind("127.0.0.1:0").unwrap();
        sock.set_read_timeout(Some(Duration::from_millis(100)))
            .unwrap();
        Peer {
            sock,
            gateway: None,
            sender: Sender::new(id, 1000),
            id,
        }
    }

    fn addr(&self) -> SocketAddrV4 {
        match self.sock.local_addr().unwrap() {
            SocketAddr::V4(a) => a,
            a => panic!("{a}"),
        }
    }

    /// Waits up to `limit` for a parameter from the gateway that satisfies `want`.
    fn wait_for(&mut self, limit: Duration, mut want: impl FnMut(&Parameter) -> bool) -> bool {
        let end = Instant::now() + limit;
        let mut buf = [0u8; 2048];
        while Instant::now() < end {
            let Ok((n, from)) = self.sock.recv_from(&mut buf) else {
                continue;
            };
            let Ok(m) = Message::parse(&buf[..n]) else {
                continue;
            };
            if m.src_id != GW {
                continue;
            }
            self.gateway = Some(from);
            if let Body::Params(ps) = m.body
                && ps.iter().any(&mut want)
            {
                return true;
            }
        }
        false
    }

    /// Builds one datagram numbered `num`.
    fn datagram(&mut self, num: u16, params: Vec<Parameter>) -> Vec<u8> {
        self.sender = Sender::new(self.id, num);
        self.sender
            .pack(MsgKind::flight_data(CertLevel::Experimental), &params)
            .unwrap()
            .remove(0)
    }

    fn send(&self, d: &[u8]) {
        let to = self.gateway.expect("heard the gateway first");
        self.sock.send_to(d, to).unwrap();
    }
}

fn ecb_is(p: &Parameter, unit: u16, state: EcbState) -> bool {
    p.ident == idents::ECBSTAT
        && p.unit == unit
        && matches!(&p.value, Value::Bus(b) if b.state == state)
}

/// A person's request for circuit `unit` in `state`.
fn ecb_request(unit: u16, state: EcbState) -> Parameter {
    xfsp_request::ecb_request(unit, state, Confidence::UserSel)
}

fn wait_sim(sim: &SimHandle, limit: Duration, mut ok: impl FnMut(&sim::SimStats) -> bool) -> bool {
    let end = Instant::now() + limit;
    while Instant::now() < end {
        if ok(&sim.stats()) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    false
}

/// `--xfsp-control`: commands from any source.
fn commanded() -> GatewayConfig {
    GatewayConfig {
        control: Control::Any,
        ..GatewayConfig::default()
    }
}

/// The bridge's options: the unit on `port` (None: the built-in one playing
/// `scenario`), publishing to `target` on 127.0.0.1.
fn bridge_to(
    port: Option<&str>,
    scenario: &str,
    target: Target,
    gateway: GatewayConfig,
) -> BridgeOptions {
    BridgeOptions {
        port: port.map(|p| p.to_string().into()),
        baud: 57_600,
        scenario: scenario.into(),
        target,
        iface: Ipv4Addr::LOCALHOST,
        gateway,
        record: None,
        logbook: None,
    }
}

/// The `install` unit on a pty, its flaps parked at 200, short of their down endpoint.
fn install_with_flaps_at_200() -> PtyUnit {
    let mut scenario = sim::load_scenario("install").unwrap();
    scenario.flap.as_mut().unwrap().position = Some(200);
    PtyUnit::start(SimOptions::new(scenario))
}

fn secs(n: u64) -> Duration {
    Duration::from_secs(n)
}

#[test]
fn the_vpx_on_the_network_over_a_pty_and_udp() {
    let PtyUnit {
        sim, path, slave, ..
    } = PtyUnit::start(SimOptions::new(sim::load_scenario("hangar").unwrap()));
    let mut peer = Peer::new();
    let target = Target::Unicast(peer.addr());
    let bridge = Bridge::start(bridge_to(Some(&path), "hangar", target, commanded()));

    // Hangar: the EFIS is on switch 1, which is open.
    assert!(
        peer.wait_for(secs(8), |p| ecb_is(p, EFIS, EcbState::Off)),
        "EFIS OFF never published; bridge said {:#?}",
        bridge.lines()
    );

    // A device switched on in the unit appears as ECBSTAT ON.
    sim.inject(SimCommand::Switch {
        switch: 1,
        on: true,
    });
    assert!(peer.wait_for(secs(5), |p| ecb_is(p, EFIS, EcbState::On)));

    // An ECBSTAT request switches the circuit.
    let off = peer.datagram(1000, vec![ecb_request(EFIS, EcbState::Off)]);
    peer.send(&off);
    assert!(wait_sim(&sim, secs(5), |s| !s.powered[EFIS as usize]));
    assert!(peer.wait_for(secs(5), |p| ecb_is(p, EFIS, EcbState::Off)));

    // A duplicate number and an older one are ignored, whatever they ask.
    let dup = peer.datagram(1000, vec![ecb_request(EFIS, EcbState::On)]);
    let old = peer.datagram(999, vec![ecb_request(EFIS, EcbState::On)]);
    peer.send(&dup);
    peer.send(&old);
    std::thread::sleep(Duration::from_millis(1500));
    assert!(
        !sim.stats().powered[EFIS as usize],
        "an ignored message switched"
    );
    // …while the next number is taken, so the two above were ignored by number.
    let on = peer.datagram(1001, vec![ecb_request(EFIS, EcbState::On)]);
    peer.send(&on);
    assert!(wait_sim(&sim, secs(5), |s| s.powered[EFIS as usize]));
    let lines = bridge.lines();
    assert_eq!(
        lines
            .iter()
            .filter(|l| l.contains("EFIS ON -> DEVICE_POWER"))
            .count(),
        1,
        "{lines:#?}"
    );

    // IAS on the network reaches the unit as EXTERNAL_DATA.
    assert!(sim.stats().external_data_missing, "nothing forwarded yet");
    let ias = peer.datagram(
        1002,
        vec![Parameter::new(idents::IAS, Value::Sint(92)).unit(1)],
    );
    peer.send(&ias);
    assert!(wait_sim(&sim, secs(5), |s| !s.external_data_missing));

    // Losing the unit: states go UNKNOWN and a CAS message says so.
    sim.inject(SimCommand::Silent(secs(10)));
    assert!(peer.wait_for(secs(6), |p| ecb_is(p, EFIS, EcbState::Unknown0)));
    assert!(peer.wait_for(secs(3), |p| {
        p.ident == idents::CASMSG
            && matches!(&p.value, Value::CasMsg(c)
                if c.level == CasLevel::Caution && latin1(&c.label) == "VP-X COMM LOST")
    }));
    drop(bridge);
    sim.stop();
    drop(slave);
}

#[test]
fn multicast_pinned_to_loopback_reaches_a_listener_on_the_same_host() {
    let port = UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let target = Target::Multicast {
        group: Ipv4Addr::new(224, 0, 2, 69),
        port,
    };
    let listener = match XfspNet::listen(&target, Ipv4Addr::LOCALHOST) {
        Ok(l) => l,
        Err(e) => {
            // Some sandboxes have no multicast on lo; unicast is covered above.
            eprintln!("skipped: cannot join {target} on 127.0.0.1: {e}");
            return;
        }
    };
    let _bridge = Bridge::start(bridge_to(None, "demo", target, GatewayConfig::default()));
    let end = Instant::now() + secs(8);
    let mut seen = false;
    while Instant::now() < end && !seen {
        if let Ok(d) = listener.incoming().recv_timeout(Duration::from_millis(200))
            && let Ok(m) = Message::parse(&d.bytes)
            && m.src_id == GW
            && let Body::Params(ps) = m.body
        {
            seen = ps.iter().any(|p| ecb_is(p, EFIS, EcbState::On));
        }
    }
    assert!(seen, "no ECBSTAT ON for the demo's EFIS on {target}");
}

/// Sends `ident` = `target` every 250 ms for `for_` (numbering from `*num`), and
/// reads the unit's position of that motor meanwhile: (lowest, highest) seen.
fn drive(
    peer: &mut Peer,
    num: &mut u16,
    sim: &SimHandle,
    ident: vpx_efis::xfsp::Ident,
    target: i32,
    for_: Duration,
) -> (u8, u8) {
    let pos = |s: &sim::SimStats| {
        if ident == idents::FLAPREQ {
            s.flap_position
        } else {
            s.pitch_trim_position
        }
    };
    let first = pos(&sim.stats());
    let (mut lo, mut hi) = (first, first);
    let end = Instant::now() + for_;
    let mut next = Instant::now();
    while Instant::now() < end {
        if Instant::now() >= next {
            let d = peer.datagram(
                *num,
                vec![
                    Parameter::new(ident, Value::Sint(target))
                        .confidence(Confidence::UserSel)
                        .expire(vpx_efis::xfsp::Expire::at_least(Duration::from_millis(600))),
                ],
            );
            *num += 1;
            peer.send(&d);
            next += Duration::from_millis(250);
        }
        let p = pos(&sim.stats());
        (lo, hi) = (lo.min(p), hi.max(p));
        std::thread::sleep(Duration::from_millis(20));
    }
    (lo, hi)
}

/// Over real parts: the `install` scenario's pitch trim has its leads
/// swapped. Sent nose-down from neutral (PTRIMREQ −80000, raw 201 from 125), it runs
/// nose-up, against its command: the gateway stops it within a few counts (not at
/// the unit's run cap, some 250 counts, far past the endpoint at 30), with the
/// stop on the wire (no starved stream, no move late) and the reason on its standard
/// error. The flaps, wired right and parked at 200, sent to their down endpoint 220
/// (FLAPREQ 100000) stop just before it, by the endpoint rule, not past it.
#[test]
fn network_motor_runs_keep_to_their_endpoints_and_a_reversed_trim_stops_on_the_wire() {
    let PtyUnit {
        sim, path, slave, ..
    } = install_with_flaps_at_200();
    let mut peer = Peer::new();
    let target = Target::Unicast(peer.addr());
    let bridge = Bridge::start(bridge_to(Some(&path), "install", target, commanded()));
    assert!(
        peer.wait_for(secs(8), |p| p.ident == idents::PTRIMPOS),
        "no PTRIMPOS published; bridge said {:#?}",
        bridge.lines()
    );
    assert!(peer.wait_for(secs(3), |p| p.ident == idents::FLAPPOS));
    let mut num = 2000;

    let (lo, hi) = drive(
        &mut peer,
        &mut num,
        &sim,
        idents::PTRIMREQ,
        -80_000,
        Duration::from_millis(2500),
    );
    let s = sim.stats();
    eprintln!("reversed trim sent nose-down from 125: went {lo}..={hi}");
    assert!(
        !s.pitch_trim_running,
        "still running at {}",
        s.pitch_trim_position
    );
    assert!(
        lo >= 125 - 10 && hi <= 125,
        "the trim went {lo}..={hi} from 125; bridge said {:#?}",
        bridge.lines()
    );
    assert!(
        bridge.lines().iter().any(|l| l.contains(
            "pitch trim stopped: it moved up when asked down: its leads or its sensor may \
                 be swapped"
        )),
        "{:#?}",
        bridge.lines()
    );

    let (lo, hi) = drive(
        &mut peer,
        &mut num,
        &sim,
        idents::FLAPREQ,
        100_000,
        Duration::from_millis(2500),
    );
    let s = sim.stats();
    eprintln!("flaps sent to their endpoint 220 from 200: went {lo}..={hi}");
    assert!(!s.flap_running, "still running at {}", s.flap_position);
    assert!(
        lo >= 200 && (210..=220).contains(&hi),
        "the flaps went {lo}..={hi} from 200 toward 220; bridge said {:#?}",
        bridge.lines()
    );
    assert!(
        bridge
            .lines()
            .iter()
            .any(|l| l.contains("flaps stopped: at its endpoint (position 220)")),
        "{:#?}",
        bridge.lines()
    );

    // Every run ended by its stop message, and no move came late.
    let s = sim.stats();
    assert_eq!(
        (
            s.flap_starvations,
            s.pitch_trim_starvations,
            s.roll_trim_starvations
        ),
        (0, 0, 0)
    );
    assert_eq!(
        (s.flap_late, s.pitch_trim_late, s.roll_trim_late),
        (0, 0, 0)
    );
    drop(bridge);
    sim.stop();
    drop(slave);
}

/// Over real parts: the bridge started without `--xfsp-control` publishes
/// (the peer hears ECBSTAT) but a peer's ECBSTAT OFF and PTRIMREQ change nothing on the
/// unit; its standard error gives the reason once, and its closing line the count.
/// With `--xfsp-control-from` naming another source, the peer is still refused and
/// the listed source's command goes through.
#[test]
fn network_commands_reach_the_unit_only_when_allowed_and_only_from_listed_sources() {
    let PtyUnit {
        sim, path, slave, ..
    } = install_with_flaps_at_200();
    let mut peer = Peer::new();
    let opts = |control: Control, to: SocketAddrV4| {
        let gateway = GatewayConfig {
            control,
            ..GatewayConfig::default()
        };
        bridge_to(Some(&path), "install", Target::Unicast(to), gateway)
    };
    let bridge = Bridge::start(opts(Control::Off, peer.addr()));
    assert!(
        peer.wait_for(secs(8), |p| p.ident == idents::PTRIMPOS),
        "nothing published; bridge said {:#?}",
        bridge.lines()
    );
    assert!(peer.wait_for(secs(5), |p| ecb_is(p, EFIS, EcbState::On)));
    let trim = sim.stats().pitch_trim_position;
    let mut num = 3000;
    for _ in 0..8 {
        let d = peer.datagram(
            num,
            vec![
                ecb_request(EFIS, EcbState::Off),
                Parameter::new(idents::PTRIMREQ, Value::Sint(-80_000))
                    .confidence(Confidence::UserSel),
            ],
        );
        num += 1;
        peer.send(&d);
        std::thread::sleep(Duration::from_millis(250));
    }
    let s = sim.stats();
    assert!(s.powered[EFIS as usize], "the EFIS was switched off");
    assert!(
        !s.pitch_trim_running && s.pitch_trim_position == trim,
        "the trim moved"
    );
    let lines = stop(bridge);
    assert!(
        lines[0].contains("network commands off"),
        "the start says so: {lines:#?}"
    );
    let said = lines
        .iter()
        .filter(|l| l.contains("refused: commands from the network are off"))
        .count();
    assert_eq!(said, 1, "once per source per 10 s: {lines:#?}");
    assert!(
        lines
            .last()
            .unwrap()
            .contains("16 refused as not allowed (network commands off)"),
        "{lines:#?}"
    );

    // A fresh socket, so nothing the first bridge sent is taken for the second's.
    let mut peer = Peer::new();
    let bridge = Bridge::start(opts(Control::From(vec![0x0999]), peer.addr()));
    assert!(peer.wait_for(secs(8), |p| ecb_is(p, EFIS, EcbState::On)));
    for _ in 0..4 {
        let d = peer.datagram(num, vec![ecb_request(EFIS, EcbState::Off)]);
        num += 1;
        peer.send(&d);
        std::thread::sleep(Duration::from_millis(250));
    }
    assert!(
        sim.stats().powered[EFIS as usize],
        "a stranger switched the EFIS off"
    );
    let lines = stop(bridge);
    assert_eq!(
        lines
            .iter()
            .filter(|l| l.contains("0x0777 is not in --xfsp-control-from (0x0999)"))
            .count(),
        1,
        "{lines:#?}"
    );
    assert!(
        lines
            .last()
            .unwrap()
            .contains("4 refused as not allowed (network commands only from 0x0999)"),
        "{lines:#?}"
    );

    let mut listed = Peer::with_id(0x0999);
    let bridge = Bridge::start(opts(Control::From(vec![0x0999]), listed.addr()));
    assert!(listed.wait_for(secs(8), |p| ecb_is(p, EFIS, EcbState::On)));
    let d = listed.datagram(10, vec![ecb_request(EFIS, EcbState::Off)]);
    listed.send(&d);
    assert!(
        wait_sim(&sim, secs(5), |s| !s.powered[EFIS as usize]),
        "the listed source's command did not go through: {:#?}",
        bridge.lines()
    );
    drop(bridge);
    sim.stop();
    drop(slave);
}

/// Stops the bridge and returns everything it said, its closing counts included.
fn stop(mut bridge: Bridge) -> Vec<String> {
    bridge.stop.store(true, Ordering::SeqCst);
    if let Some(t) = bridge.thread.take() {
        t.join()
            .expect("bridge thread panicked")
            .expect("bridge failed");
    }
    bridge.lines()
}

/// Over real UDP: one source's IAS, then 300 other sources (past the 256
/// the receiver once held, which then evicted the first), then the first source's
/// message again, replayed with another IAS. It must still be a duplicate: the
/// bridge's closing counts say 301 fresh and 1 duplicate (with a count-bound table
/// the replay was taken as fresh: 302 fresh, 0 duplicate).
#[test]
fn three_hundred_sources_do_not_make_an_old_message_fresh_again() {
    let mut peer = Peer::new();
    let target = Target::Unicast(peer.addr());
    let bridge = Bridge::start(bridge_to(None, "demo", target, GatewayConfig::default()));
    assert!(
        peer.wait_for(secs(8), |_| true),
        "nothing published: {:#?}",
        bridge.lines()
    );
    let ias = |v: i32| vec![Parameter::new(idents::IAS, Value::Sint(v)).unit(1)];
    let first = peer.datagram(10, ias(92));
    peer.send(&first);
    for id in 1..=300u16 {
        let d = Sender::new(0x1000 + id, 1)
            .pack(MsgKind::flight_data(CertLevel::Experimental), &ias(80))
            .unwrap()
            .remove(0);
        peer.send(&d);
        if id % 25 == 0 {
            // Loopback drops nothing, but a burst should not outrun the bridge's
            // socket buffer on a loaded machine.
            std::thread::sleep(Duration::from_millis(20));
        }
    }
    let replay = peer.datagram(10, ias(50));
    peer.send(&replay);
    std::thread::sleep(Duration::from_millis(500));
    let lines = stop(bridge);
    let last = lines.last().cloned().unwrap_or_default();
    assert!(
        last.contains("received 301 fresh, 1 duplicate, 0 out of order"),
        "{lines:#?}"
    );
}

//! The gateway inside the page (`vpx-efis --xfsp`): the real `App` with the built-in
//! virtual VP-X publishes its circuits to a UDP peer on 127.0.0.1.

use std::net::UdpSocket;
use std::time::{Duration, Instant};

use vpx_efis::app::{App, AppOptions, builtin_sim};
use vpx_efis::xfsp::gateway::GatewayConfig;
use vpx_efis::xfsp::net::Target;
use vpx_efis::xfsp::{Body, EcbState, Message, Value, idents};

#[test]
fn the_page_publishes_its_circuits_on_xfsp() {
    let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
    peer.set_read_timeout(Some(Duration::from_millis(50)))
        .unwrap();
    let target = Target::parse(&peer.local_addr().unwrap().to_string()).unwrap();

    let (source, connector, sim) = builtin_sim("demo").unwrap();
    let mut app = App::new(source, connector, AppOptions::default());
    app.enable_xfsp(
        &target,
        "127.0.0.1".parse().unwrap(),
        GatewayConfig::default(),
    )
    .unwrap();

    // The demo's EFIS (device 2, named "EFIS 1") is always on.
    let end = Instant::now() + Duration::from_secs(8);
    let mut buf = [0u8; 2048];
    let mut efis_on = false;
    while !efis_on {
        assert!(
            Instant::now() < end,
            "no ECBSTAT ON for the EFIS reached the peer"
        );
        app.pump_until(Instant::now() + Duration::from_millis(50));
        while let Ok(n) = peer.recv(&mut buf) {
            let Ok(m) = Message::parse(&buf[..n]) else {
                continue;
            };
            if let Body::Params(ps) = m.body {
                efis_on |= ps.iter().any(|p| {
                    p.ident == idents::ECBSTAT
                        && p.unit == 2
                        && matches!(&p.value, Value::Bus(b) if b.state == EcbState::On && b.label == b"EFIS 1")
                });
            }
        }
    }
    app.shutdown();
    sim.stop();
}

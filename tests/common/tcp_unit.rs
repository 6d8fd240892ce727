//! The virtual VP-X in the test's own process behind a TCP server on 127.0.0.1, as a
//! serial-to-network bridge puts a unit on the network: for the tests that reach it
//! with `--port tcp://…` and read its state directly. Included by `#[path]`.

use vpx_efis::link::serve_line;
use vpx_efis::sim::{self, SimHandle, SimOptions};

/// The built-in scenario `scenario`'s unit, served on a free port; its handle and its
/// `tcp://` address.
pub fn unit_over_tcp(scenario: &str) -> (SimHandle, String) {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let line = serve_line(listener, |_| {}).unwrap();
    let addr = format!("tcp://{}", line.local_addr);
    let sim = sim::spawn(
        SimOptions::new(sim::load_scenario(scenario).unwrap()),
        Box::new(line.reader),
        Box::new(line.writer),
    );
    (sim, addr)
}

//! Broadcast rates measured on the wire (ICD §6.3): 1 Hz and 10 Hz within 5 %.
//! In a file of its own so nothing else in the same test binary competes for the CPU.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

mod sim_common;

use std::time::{Duration, Instant};

use sim_common::{scenario, start};
use vpx_efis::protocol::FaultCode;
use vpx_efis::protocol::Message;
use vpx_efis::sim::SimCommand;

/// Messages per second from first to last arrival: (n − 1) / span. Measuring the span
/// rather than counting in a window makes the result independent of where the window
/// falls, and of a late first read.
fn rate(times: &[Instant]) -> f64 {
    assert!(times.len() >= 3, "only {} messages", times.len());
    let span = (*times.last().unwrap() - times[0]).as_secs_f64();
    (times.len() - 1) as f64 / span
}

#[test]
fn broadcast_rates_are_1_hz_and_10_hz_within_5_percent() {
    let (sim, mut c) = start(scenario("[electrical]\nswitches = [1]\n"), |_| {});
    // A fault, so FAULT_STATUS is broadcast too.
    sim.inject(SimCommand::Fault {
        device: 9,
        code: FaultCode::OverCurrent,
    });
    c.pump(Duration::from_millis(5_300));
    let times = |f: fn(&Message) -> bool| -> Vec<Instant> {
        c.log
            .iter()
            .filter(|(_, p)| f(&p.message))
            .map(|(t, _)| *t)
            .collect()
    };
    let system = rate(&times(|m| matches!(m, Message::SystemStatus(_))));
    let device = rate(&times(|m| matches!(m, Message::DeviceStatus(_))));
    let fault = rate(&times(|m| matches!(m, Message::FaultStatus(_))));
    let fast = rate(&times(|m| matches!(m, Message::FlapTrimStatus(_))));
    eprintln!(
        "measured: SYSTEM_STATUS {system:.3} Hz, DEVICE_STATUS {device:.3} Hz, \
         FAULT_STATUS {fault:.3} Hz, FLAP_TRIM_STATUS {fast:.3} Hz"
    );
    for (name, r, want) in [
        ("SYSTEM_STATUS", system, 1.0),
        ("DEVICE_STATUS", device, 1.0),
        ("FAULT_STATUS", fault, 1.0),
        ("FLAP_TRIM_STATUS", fast, 10.0),
    ] {
        assert!(
            (r - want).abs() <= 0.05 * want,
            "{name}: {r:.3} Hz, want {want} Hz ± 5 %"
        );
    }
    // The unit's own count runs on across every broadcast (icd-reading R14).
    let cnts: Vec<u8> = c.log.iter().map(|(_, p)| p.cnt).collect();
    assert!(
        cnts.windows(2).all(|w| w[1] == w[0].wrapping_add(1)),
        "{cnts:?}"
    );
}

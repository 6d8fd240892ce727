//! What the setup tests hear from the unit, on a clock they set: shared by the test
//! modules of the setup flow.

use std::time::{Duration, Instant};

use crate::model::{Model, Source};
use crate::protocol::Packet;
use crate::protocol::message::{DeviceEnable, DeviceName, EnableFlag, Message};

/// A model that has heard nothing yet.
pub fn model() -> Model {
    Model::new(Source::Simulated {
        scenario: "t".into(),
    })
}

/// `n` ms after `t0`.
pub fn ms(t0: Instant, n: u64) -> Instant {
    t0 + Duration::from_millis(n)
}

/// The unit reports `msg` at `at`.
pub fn hear(m: &mut Model, at: Instant, msg: impl Into<Message>) {
    m.apply_packet(at, &Packet::from_vpx(1, msg));
}

/// The unit reports pin `id`'s name and that the pin is shown.
pub fn hear_named(m: &mut Model, at: Instant, id: u8, name: &str) {
    hear(
        m,
        at,
        DeviceName::new(id, name).expect("a name the ICD takes"),
    );
    hear(
        m,
        at,
        DeviceEnable {
            device_id: id,
            flag: EnableFlag::Enabled,
        },
    );
}

//! The check's clocks: how long each wait and each run lasts.

use std::time::Duration;

/// The check's clocks. Defaults suit a real unit (1 Hz status, 10 Hz flap/trim status).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// How long the person has to flip a switch on and off.
    pub switch_timeout: Duration,
    /// After an input changed, how long its circuits have to follow (DEVICE_STATUS
    /// comes once a second).
    pub follow_wait: Duration,
    /// DEVICE_POWER has no answer of its own: the unit's DEVICE_STATUS showing the
    /// circuit in the new state is the answer. Wait this long before sending again …
    pub power_timeout: Duration,
    /// … this many times in all.
    pub power_tries: u8,
    /// The longest a circuit stays on: two fresh DEVICE_STATUS take about two seconds.
    pub on_for: Duration,
    /// The longest a light is held on for the person to answer "Is it lit?". Decision:
    /// a minute. Long enough to walk from the laptop to the farthest light of a light
    /// aircraft (a wingtip, the tail) and look, or to answer from the phone; short
    /// enough that a landing light in a wingtip, which has no cooling air on the
    /// ground, is not left burning for nobody, nor the battery drawn down.
    pub lit_for: Duration,
    /// Each direction's run of a motor.
    pub motor_run: Duration,
    /// After a run, FLAP_TRIM_STATUS (10 Hz) has this long to show where it stopped.
    pub motor_settle: Duration,
    /// After an interruption, how long the check waits to see a circuit go back off.
    pub stop_wait: Duration,
}

impl Default for Timing {
    fn default() -> Self {
        Timing {
            switch_timeout: Duration::from_secs(30),
            follow_wait: Duration::from_millis(2500),
            power_timeout: Duration::from_millis(2500),
            power_tries: 2,
            on_for: Duration::from_secs(5),
            lit_for: Duration::from_secs(60),
            motor_run: Duration::from_millis(600),
            motor_settle: Duration::from_millis(400),
            stop_wait: Duration::from_secs(3),
        }
    }
}

impl Timing {
    /// How long one motor's test takes at most: two runs, their settling, and the
    /// run back.
    pub fn motor_for(&self) -> Duration {
        (self.motor_run + self.motor_settle) * 3
    }
}

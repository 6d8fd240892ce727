//! The aircraft as the unit sees it: the speeds and RPM of a fresh EXTERNAL_DATA,
//! and each motor's geometry from its configuration and wiring.

use std::time::{Duration, Instant};

use super::{EXTERNAL_DATA_TIMEOUT, Unit, motor_index};
use crate::protocol::message::{ExternalData, FlapMode, Polarity};
use crate::sim::motors::{FLAP_RATE, Geometry, TRIM_RATE};
use crate::sim::scenario::MotorId;

impl Unit {
    fn fresh_external(&self, now: Instant) -> Option<&ExternalData> {
        self.external
            .as_ref()
            .filter(|(at, _)| now.saturating_duration_since(*at) <= EXTERNAL_DATA_TIMEOUT)
            .map(|(_, d)| d)
    }

    pub(super) fn external_missing(&self, now: Instant) -> bool {
        let since = self.external.map_or(self.booted_at, |(at, _)| at);
        now.saturating_duration_since(since) > EXTERNAL_DATA_TIMEOUT
    }

    fn ias(&self, now: Instant) -> Option<u16> {
        self.fresh_external(now)
            .filter(|d| d.valid.indicated_airspeed)
            .map(|d| d.indicated_airspeed)
    }

    /// IAS, else ground speed (Table 15 note 5, Table 17 note 4).
    pub(super) fn speed(&self, now: Instant) -> Option<u16> {
        self.ias(now).or_else(|| {
            self.fresh_external(now)
                .filter(|d| d.valid.ground_speed)
                .map(|d| d.ground_speed)
        })
    }

    pub(super) fn rpm(&self, now: Instant) -> Option<u16> {
        let ext = self
            .fresh_external(now)
            .filter(|d| d.valid.rpm)
            .map(|d| d.rpm);
        ext.or(self.engine_rpm)
    }

    pub(super) fn flap_down_inhibited(&self, now: Instant) -> bool {
        let max = self.config.flap.max_speed;
        max > 0 && self.ias(now).is_some_and(|ias| ias > max)
    }

    pub(super) fn geometry(&self, m: MotorId, now: Instant) -> Geometry {
        let c = &self.config;
        match m {
            MotorId::Flap => Geometry {
                enabled: c.flap.enabled,
                up: c.flap.up,
                down: c.flap.down,
                stops: [c.flap.midpoint_1, c.flap.midpoint_2],
                position_mode: c.flap.mode == FlapMode::PositionBased,
                endpoint_run: Duration::from_millis(c.flap.endpoint_duration.0 as u64 * 100),
                rate: FLAP_RATE,
                reversed: self.runs_reversed(m, c.flap.polarity),
                stuck: self.motor_wiring[motor_index(m)].stuck,
            },
            MotorId::Pitch | MotorId::Roll => {
                let t = if m == MotorId::Pitch {
                    &c.pitch_trim
                } else {
                    &c.roll_trim
                };
                // Table 15 notes 5, 6: reduced power above the speed, pitch only.
                let reduced = m == MotorId::Pitch
                    && self.speed(now).is_some_and(|s| s > t.speed)
                    && t.power < 100;
                let rate = if reduced {
                    TRIM_RATE * t.power as f32 / 100.0
                } else {
                    TRIM_RATE
                };
                Geometry {
                    enabled: t.enabled,
                    up: t.up,
                    down: t.down,
                    stops: [0, 0],
                    position_mode: false,
                    endpoint_run: Duration::ZERO,
                    rate,
                    reversed: self.runs_reversed(m, t.polarity),
                    stuck: self.motor_wiring[motor_index(m)].stuck,
                }
            }
        }
    }

    /// Table 15/16 note 3: the polarity flag sets the direction the motor runs, so
    /// an inverted setting undoes leads that are swapped (and swaps good ones).
    fn runs_reversed(&self, m: MotorId, polarity: Polarity) -> bool {
        self.motor_wiring[motor_index(m)].reversed ^ (polarity == Polarity::Inverted)
    }
}

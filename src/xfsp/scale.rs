//! Flap and trim positions between the VP-X's raw sensor counts and the draft's scale.
//!
//! The VP-X reports each motor's position as a raw sensor count (0–255, ICD Table 27)
//! together with the endpoints configured for it (flap up/down, trim up/down/neutral).
//! The draft (§3.4) gives FLAPREQ/FLAPPOS a scale: "0 = up, 100000 = fully down,
//! -100000 is fully negative". For PTRIM*/RTRIM* it only gives the sign ("negative nose
//! down, 0 neutral, positive nose up"; "negative left bank, 0 neutral, positive right
//! bank"); we use the same ±100000 full scale for them, so every actuator on the
//! network reads alike.
//!
//! Our mapping, linear on each side of the zero point:
//! - Flaps: zero = the up endpoint, +100000 = the down endpoint. A VP-X has no reflex
//!   travel, so a count beyond the up endpoint (sensor slop) is scaled with the down
//!   side's span and comes out slightly negative; requests below 0 are taken as 0.
//! - Pitch trim: zero = neutral, +100000 = the up (nose-up) endpoint, −100000 = the down
//!   endpoint.
//! - Roll trim: zero = neutral, +100000 = the down endpoint, −100000 = the up endpoint,
//!   because TRIM_MOVE's "up" direction is roll left (ICD Table 30) and the draft
//!   calls left negative.
//!
//! Values are clamped to ±100000. Endpoints that coincide (a motor not configured, for
//! which FLAP_TRIM_STATUS reports zeros) give no scale at all: nothing is published and
//! requests are refused.

use crate::control::Direction;
use crate::control::endpoints::{Way, opposite};
use crate::model::{Motor, TrimKind};
use crate::protocol::message::FlapTrimStatus;

/// The draft's full travel: FLAPPOS 100000 = fully down.
pub const FULL_SCALE: i32 = 100_000;

/// One motor's travel in raw counts: the zero point and the two ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Travel {
    zero: i32,
    /// Raw count at +[`FULL_SCALE`].
    positive: i32,
    /// Raw count at −[`FULL_SCALE`]; `None` for flaps, which have no negative travel.
    negative: Option<i32>,
}

impl Travel {
    /// The travel from the endpoints FLAP_TRIM_STATUS carries, or `None` when they do not
    /// describe any travel.
    pub fn for_motor(motor: Motor, ft: &FlapTrimStatus) -> Option<Travel> {
        let a = ft.axis(motor.axis());
        let (zero, positive, negative) = match (motor, a.neutral) {
            (Motor::Trim(TrimKind::Pitch), Some(neutral)) => (neutral, a.up, Some(a.down)),
            (Motor::Trim(TrimKind::Roll), Some(neutral)) => (neutral, a.down, Some(a.up)),
            _ => (a.up, a.down, None),
        };
        Travel::new(zero, positive, negative)
    }

    /// Both sides must have travel, in opposite directions from the zero point.
    pub fn new(zero: u8, positive: u8, negative: Option<u8>) -> Option<Travel> {
        let (zero, positive) = (i32::from(zero), i32::from(positive));
        let negative = negative.map(i32::from);
        if positive == zero {
            return None;
        }
        if let Some(n) = negative
            && Way::of(n - zero) != Way::of(positive - zero).map(Way::reversed)
        {
            return None;
        }
        Some(Travel {
            zero,
            positive,
            negative,
        })
    }

    /// The way the raw count goes toward +full scale.
    fn positive_way(&self) -> Way {
        if self.positive > self.zero {
            Way::Grows
        } else {
            Way::Shrinks
        }
    }

    /// A raw count on the draft's scale.
    pub fn to_scale(&self, raw: u8) -> i32 {
        let d = i32::from(raw) - self.zero;
        let span_pos = self.positive - self.zero;
        let v = match self.negative {
            Some(n) if Way::of(d) == Some(self.positive_way().reversed()) => {
                // On the negative side: scaled by that side's own span.
                -ratio(d, n - self.zero)
            }
            _ => ratio(d, span_pos),
        };
        v.clamp(-FULL_SCALE, FULL_SCALE)
    }

    /// The raw count for a value on the draft's scale, clamped into the travel.
    pub fn to_raw(&self, value: i32) -> u8 {
        let lowest = if self.negative.is_some() {
            -FULL_SCALE
        } else {
            0
        };
        let v = i64::from(value.clamp(lowest, FULL_SCALE));
        let span = match self.negative {
            Some(n) if v < 0 => i64::from(n - self.zero),
            _ => i64::from(self.positive - self.zero),
        };
        let offset =
            (v.abs() * span + i64::from(FULL_SCALE) / 2 * span.signum()) / i64::from(FULL_SCALE);
        (i64::from(self.zero) + offset).clamp(0, 255) as u8
    }

    /// Which way to drive `motor` to take the raw position from `from` to `to`;
    /// `None` when it is already there.
    pub fn direction(&self, motor: Motor, from: u8, to: u8) -> Option<Direction> {
        let positive = Way::of(i32::from(to) - i32::from(from))? == self.positive_way();
        Some(if positive {
            toward_positive(motor)
        } else {
            opposite(toward_positive(motor))
        })
    }

    /// How far (in raw counts) `pos` still is from `target` when driving `direction`;
    /// zero or negative once it is there or past it.
    pub fn remaining(&self, motor: Motor, direction: Direction, pos: u8, target: u8) -> i32 {
        let way = if direction == toward_positive(motor) {
            self.positive_way()
        } else {
            self.positive_way().reversed()
        };
        way.along(i32::from(target) - i32::from(pos))
    }
}

/// The direction that drives `motor` toward +full scale (see the module's notes):
/// flaps down, pitch trim up (nose up), roll trim right.
fn toward_positive(motor: Motor) -> Direction {
    match motor {
        Motor::Flaps => Direction::Down,
        Motor::Trim(TrimKind::Pitch) => Direction::Up,
        Motor::Trim(TrimKind::Roll) => Direction::Right,
    }
}

/// `d / span` of full scale, rounded to nearest (`span` is never 0 here).
fn ratio(d: i32, span: i32) -> i32 {
    // Both fit f64 exactly; the result is clamped by the caller.
    (f64::from(d) * f64::from(FULL_SCALE) / f64::from(span)).round() as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const PITCH: Motor = Motor::Trim(TrimKind::Pitch);
    const ROLL: Motor = Motor::Trim(TrimKind::Roll);

    #[test]
    fn flaps_up_is_zero_and_down_is_full_scale_either_way_round() {
        let a = Travel::new(40, 200, None).unwrap();
        assert_eq!(a.to_scale(40), 0);
        assert_eq!(a.to_scale(200), FULL_SCALE);
        assert_eq!(a.to_scale(120), 50_000);
        assert_eq!(
            a.to_scale(36),
            -2_500,
            "slop above up reads slightly negative"
        );
        assert_eq!(a.direction(Motor::Flaps, 40, 120), Some(Direction::Down));
        // A sensor wired the other way round: up is the high count.
        let b = Travel::new(200, 40, None).unwrap();
        assert_eq!(b.to_scale(120), 50_000);
        assert_eq!(b.to_raw(FULL_SCALE), 40);
        assert_eq!(b.direction(Motor::Flaps, 200, 120), Some(Direction::Down));
        assert_eq!(
            b.to_raw(-50_000),
            200,
            "no reflex: negative requests mean up"
        );
    }

    #[test]
    fn trims_scale_each_side_by_its_own_span() {
        // Pitch: neutral 100, nose-up endpoint 200, nose-down endpoint 50.
        let p = Travel::new(100, 200, Some(50)).unwrap();
        assert_eq!(p.to_scale(150), 50_000);
        assert_eq!(p.to_scale(75), -50_000);
        assert_eq!(p.to_scale(0), -FULL_SCALE, "clamped");
        assert_eq!(p.to_raw(-FULL_SCALE), 50);
        assert_eq!(p.direction(PITCH, 100, 50), Some(Direction::Down));
        // Roll: up endpoint (left) 30 is negative, down endpoint (right) 230 positive.
        let r = Travel::new(130, 230, Some(30)).unwrap();
        assert_eq!(r.to_scale(30), -FULL_SCALE);
        assert_eq!(r.direction(ROLL, 130, 30), Some(Direction::Left));
        assert_eq!(r.direction(ROLL, 130, 131), Some(Direction::Right));
        assert_eq!(r.direction(ROLL, 130, 130), None);
    }

    #[test]
    fn unconfigured_endpoints_give_no_scale() {
        assert_eq!(Travel::new(0, 0, None), None);
        assert_eq!(Travel::new(100, 200, Some(100)), None);
        assert_eq!(
            Travel::new(100, 200, Some(150)),
            None,
            "both ends on one side"
        );
    }

    #[test]
    fn remaining_goes_to_zero_at_the_target_and_negative_past_it() {
        let a = Travel::new(200, 40, None).unwrap();
        assert_eq!(a.remaining(Motor::Flaps, Direction::Down, 150, 120), 30);
        assert_eq!(a.remaining(Motor::Flaps, Direction::Down, 118, 120), -2);
    }

    proptest! {
        #[test]
        fn raw_to_scale_and_back_is_within_one_count(
            zero in 0u8..=255, pos in 0u8..=255, neg in 0u8..=255, raw in 0u8..=255, flaps in any::<bool>(),
        ) {
            let Some(a) = Travel::new(zero, pos, (!flaps).then_some(neg)) else { return Ok(()) };
            let lo = if flaps { zero } else { neg };
            let (lo, hi) = (lo.min(pos), lo.max(pos));
            prop_assume!((lo..=hi).contains(&raw));
            let back = a.to_raw(a.to_scale(raw));
            prop_assert!((i32::from(back) - i32::from(raw)).abs() <= 1, "{raw} -> {back}");
        }
    }
}

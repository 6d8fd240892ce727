//! Where a motor may go: its configured endpoints, as FLAP_TRIM_STATUS carries them
//! (ICD Table 27; set by TRIM_SPEC and FLAP_SPEC, Tables 15 and 16).
//!
//! The unit stops the runs of its own flap and trim switches at those endpoints, but
//! not a TRIM_MOVE or FLAP_MOVE stream (Table 15 note 4, Table 16 note 1): only the page
//! can stop its own runs there. So a run of the page that keeps to the endpoints (the
//! installation check's timed runs, a motor key on the device list) is refused when
//! the position is already at the endpoint it heads for, and ends, with its stop on
//! the wire like any other end ([`StopReason::AtEndpoint`]), once the position reaches
//! the endpoint it is moving toward, or would pass it before the page looks again at
//! the rate it is moving ([`LOOKAHEAD`]). It also ends when the position is older than
//! [`POSITION_FRESH`] ([`StopReason::PositionStale`]): no stale position drives a motor
//! toward an endpoint.
//!
//! The setup screens' motor keys do not keep to them: they are how a person runs the
//! motor to where the new endpoint should be, to capture it.
//!
//! Which way is which: a direction heads for its endpoint, "down" (pitch down, roll
//! right, flaps down) for the down endpoint. Endpoints not configured (both the same,
//! typically 0) give no endpoint to stop at; the installation check then reads the
//! sensor's direction as the virtual VP-X has it ([`expected_sign`]).

use std::time::{Duration, Instant};

use super::streamer::{Direction, StopReason};
use crate::model::{Model, Motor, TrimKind};
use crate::protocol::message::FlapTrimStatus;

/// The oldest position a run that keeps to the endpoints may go on by: four
/// FLAP_TRIM_STATUS (10 Hz) missed in a row. At the virtual VP-X's trim speed (25
/// counts a second) that is 10 counts travelled unseen, against the model's second
/// for "no live status at all" ([`crate::model::FLAP_TRIM_STALE_AFTER`], 25 counts).
pub const POSITION_FRESH: Duration = Duration::from_millis(400);
/// How far ahead a run's position is projected at its rate: the page looks again at
/// the next FLAP_TRIM_STATUS (100 ms) or loop tick (125 ms at most while a run is on),
/// and the stop takes a few milliseconds to reach the unit.
pub const LOOKAHEAD: Duration = Duration::from_millis(150);
/// Samples closer together than this give no rate (one count of jitter over 10 ms
/// would read as 100 counts a second).
const RATE_SPAN: Duration = Duration::from_millis(80);
/// Within this many counts of the endpoint it heads for, a run does not start: until
/// a run has shown its rate (a second position, 100 ms on) the page cannot project
/// it, and 100 ms is 2.5 counts at the virtual VP-X's trim speed.
pub const START_ROOM: i32 = 3;
/// Slower than this (counts a second) the motor is taken as not moving, and its way
/// is the commanded one.
const STILL_RATE: f32 = 2.0;

/// A motor's two endpoints, raw sensor counts 0–255.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ends {
    /// The endpoint "down" runs toward: flaps down, pitch trim down, roll trim right.
    pub down: u8,
    /// The endpoint "up" runs toward: flaps up, pitch trim up, roll trim left.
    pub up: u8,
}

/// The motor's endpoints, or `None` when they are not configured (the same value).
pub fn ends(motor: Motor, ft: &FlapTrimStatus) -> Option<Ends> {
    let (down, up) = match motor {
        Motor::Flaps => (ft.flap_down, ft.flap_up),
        Motor::Trim(TrimKind::Pitch) => (ft.pitch_trim_down, ft.pitch_trim_up),
        Motor::Trim(TrimKind::Roll) => (ft.roll_trim_down, ft.roll_trim_up),
    };
    (down != up).then_some(Ends { down, up })
}

/// The motor's position, raw sensor counts.
pub fn position(motor: Motor, ft: &FlapTrimStatus) -> u8 {
    match motor {
        Motor::Flaps => ft.flap_position,
        Motor::Trim(TrimKind::Pitch) => ft.pitch_trim_position,
        Motor::Trim(TrimKind::Roll) => ft.roll_trim_position,
    }
}

/// +1 when running `motor` `direction` should make the position grow, −1 when shrink.
/// Endpoints not configured: "down" grows (the virtual VP-X's sensor).
pub fn expected_sign(motor: Motor, direction: Direction, ft: &FlapTrimStatus) -> i32 {
    let down_grows = match ends(motor, ft) {
        Some(e) if e.down < e.up => -1,
        _ => 1,
    };
    match direction {
        Direction::Down | Direction::Right => down_grows,
        Direction::Up | Direction::Left => -down_grows,
    }
}

/// The endpoint `direction` heads for.
pub fn heads_for(motor: Motor, direction: Direction, ft: &FlapTrimStatus) -> Option<u8> {
    let e = ends(motor, ft)?;
    Some(match direction {
        Direction::Down | Direction::Right => e.down,
        Direction::Up | Direction::Left => e.up,
    })
}

/// How many counts `direction` may run from `pos` before its endpoint: 0 at it,
/// negative past it; `None` with no endpoints configured.
pub fn room(motor: Motor, direction: Direction, pos: u8, ft: &FlapTrimStatus) -> Option<i32> {
    let end = heads_for(motor, direction, ft)?;
    Some((i32::from(end) - i32::from(pos)) * expected_sign(motor, direction, ft))
}

/// Words for a refused start (no more than [`START_ROOM`] toward the endpoint), or
/// `None` when `direction` has room (or there are no endpoints).
pub fn no_room(motor: Motor, direction: Direction, ft: &FlapTrimStatus) -> Option<String> {
    let pos = position(motor, ft);
    let room = room(motor, direction, pos, ft)?;
    let end = heads_for(motor, direction, ft)?;
    (room <= START_ROOM).then(|| {
        format!(
            "the {} is at its {} endpoint (position {pos}, endpoint {end}): it does not run \
             past it from here",
            motor.name(),
            direction.name()
        )
    })
}

/// One run's watch over its position (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Watch {
    pub motor: Motor,
    pub direction: Direction,
    /// The way the position is expected to go (+1 grow, −1 shrink) until the run
    /// shows its own: the direction's ([`expected_sign`]), or what the caller saw
    /// this motor do (a reversed motor run back by the installation check).
    way: Option<i32>,
    /// The latest positions with when the page heard them, oldest first.
    samples: Vec<(Instant, u8)>,
}

impl Watch {
    pub fn new(motor: Motor, direction: Direction) -> Watch {
        Watch {
            motor,
            direction,
            way: None,
            samples: Vec::new(),
        }
    }

    /// A run whose position the caller expects to go `way` (+1 grow, −1 shrink).
    pub fn moving(motor: Motor, direction: Direction, way: i32) -> Watch {
        Watch {
            way: Some(way.signum()),
            ..Watch::new(motor, direction)
        }
    }

    /// Counts a second over the latest samples at least [`RATE_SPAN`] apart.
    pub fn rate(&self) -> Option<f32> {
        let &(t1, p1) = self.samples.last()?;
        let &(t0, p0) = self
            .samples
            .iter()
            .rev()
            .find(|(t, _)| t1.saturating_duration_since(*t) >= RATE_SPAN)?;
        let dt = t1.saturating_duration_since(t0).as_secs_f32();
        Some((f32::from(p1) - f32::from(p0)) / dt)
    }

    /// Whether the run may go on: takes the model's latest position, and says why not.
    pub fn check(&mut self, model: &Model, now: Instant) -> Result<(), StopReason> {
        let Some(st) = model.flap_trim.as_ref() else {
            return Err(StopReason::MotorStatusLost);
        };
        let age = now.saturating_duration_since(st.at);
        if age > POSITION_FRESH {
            return Err(StopReason::PositionStale);
        }
        let ft = &st.value;
        let pos = position(self.motor, ft);
        if self.samples.last().is_none_or(|(t, _)| *t != st.at) {
            self.samples.push((st.at, pos));
            if self.samples.len() > 6 {
                self.samples.remove(0);
            }
        }
        let Some(e) = ends(self.motor, ft) else {
            return Ok(());
        };
        let (lo, hi) = (e.down.min(e.up), e.down.max(e.up));
        let rate = self.rate().unwrap_or(0.0);
        // The way it really moves (a reversed motor heads for the other endpoint),
        // or the commanded way while it has not shown one.
        let way = if rate.abs() >= STILL_RATE {
            rate.signum() as i32
        } else {
            self.way
                .unwrap_or_else(|| expected_sign(self.motor, self.direction, ft))
        };
        let ahead = f32::from(pos) + rate * (age + LOOKAHEAD).as_secs_f32();
        let end = if way > 0 { hi } else { lo };
        let reached = if way > 0 {
            ahead >= f32::from(hi)
        } else {
            ahead <= f32::from(lo)
        };
        if reached {
            Err(StopReason::AtEndpoint(end))
        } else {
            Ok(())
        }
    }
}

/// Whether a run that keeps to the endpoints may start `direction` now, in words.
pub fn permit(
    model: &Model,
    motor: Motor,
    direction: Direction,
    now: Instant,
) -> Result<(), String> {
    permit_moving(model, motor, direction, None, now)
}

/// [`permit`] for a run whose position the caller expects to go `way` (+1 grow,
/// −1 shrink; `None`: the direction's way): the room is toward the endpoint that way.
pub fn permit_moving(
    model: &Model,
    motor: Motor,
    direction: Direction,
    way: Option<i32>,
    now: Instant,
) -> Result<(), String> {
    let Some(st) = model.flap_trim.as_ref() else {
        return Ok(()); // `motor_permit` already says there is no live status.
    };
    if st.age(now) > POSITION_FRESH {
        return Err(format!(
            "{} cannot run: {}",
            motor.name(),
            StopReason::PositionStale.describe()
        ));
    }
    let ft = &st.value;
    match way {
        Some(w) if w.signum() != expected_sign(motor, direction, ft) => {
            // Run one way to move the other: the room is toward the endpoint it will
            // really reach, which is the other direction's.
            no_room(motor, opposite(direction), ft).map_or(Ok(()), Err)
        }
        _ => no_room(motor, direction, ft).map_or(Ok(()), Err),
    }
}

fn opposite(d: Direction) -> Direction {
    match d {
        Direction::Up => Direction::Down,
        Direction::Down => Direction::Up,
        Direction::Left => Direction::Right,
        Direction::Right => Direction::Left,
    }
}

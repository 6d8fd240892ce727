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
//! motor to where the new endpoint should be, to capture it. They are still watched
//! ([`Watch::capture`]): a motor moving against its command is stopped whoever runs
//! it ([`super::against`]).
//!
//! Which way is which: a direction heads for its endpoint, "down" (pitch down, roll
//! right, flaps down) for the down endpoint. Endpoints not configured (both the same,
//! typically 0) give no endpoint to stop at; the installation check then reads the
//! sensor's direction as the virtual VP-X has it ([`expected_way`]).

use std::time::{Duration, Instant};

use super::streamer::{Direction, StopReason};
use crate::model::{Model, Motor};
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
/// Slower than this (counts a second) the motor is taken as not moving: no rate
/// projects its position.
const STILL_RATE: f32 = 2.0;
/// A run is taken to go the other way from the expected one only once its position
/// has moved this many counts that way (as the installation check's "moved").
pub const MOVED: i32 = 3;
/// Counts of sensor noise: a motor started at an endpoint may read this far past it
/// without having moved.
pub const NOISE: i32 = 1;

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
    let a = ft.axis(motor.axis());
    let (down, up) = (a.down, a.up);
    (down != up).then_some(Ends { down, up })
}

/// The motor's position, raw sensor counts.
pub fn position(motor: Motor, ft: &FlapTrimStatus) -> u8 {
    ft.position(motor.axis())
}

/// The way running `motor` `direction` should move its position: "down" toward the
/// down endpoint. Endpoints not configured: "down" grows (the virtual VP-X's sensor).
pub fn expected_way(motor: Motor, direction: Direction, ft: &FlapTrimStatus) -> Way {
    let down = match ends(motor, ft) {
        Some(e) if e.down < e.up => Way::Shrinks,
        _ => Way::Grows,
    };
    match direction {
        Direction::Down | Direction::Right => down,
        Direction::Up | Direction::Left => down.reversed(),
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
    Some(expected_way(motor, direction, ft).along(i32::from(end) - i32::from(pos)))
}

/// Which way a run moves its motor's position, in raw sensor counts: the sensor's
/// sense, as opposed to the [`Direction`] asked (which is the unit's and the keys').
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Way {
    Grows,
    Shrinks,
}

impl Way {
    /// The way of a change of position; `None` for none.
    pub fn of(change: i32) -> Option<Way> {
        match change.signum() {
            1 => Some(Way::Grows),
            -1 => Some(Way::Shrinks),
            _ => None,
        }
    }

    /// How far a change of position goes this way, in counts: negative for a change
    /// the other way.
    pub fn along(self, change: i32) -> i32 {
        match self {
            Way::Grows => change,
            Way::Shrinks => -change,
        }
    }

    /// Whether `pos` is at `end` or beyond it, going this way.
    fn at_or_past(self, pos: f32, end: f32) -> bool {
        match self {
            Way::Grows => pos >= end,
            Way::Shrinks => pos <= end,
        }
    }

    pub fn reversed(self) -> Way {
        match self {
            Way::Grows => Way::Shrinks,
            Way::Shrinks => Way::Grows,
        }
    }
}

/// Why a run that keeps to the endpoints may not start ([`room_to_run`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoRoom {
    /// Its position is older than [`POSITION_FRESH`].
    Stale,
    /// No more than [`START_ROOM`] from the endpoint it would reach, which is the one
    /// `toward` heads for.
    At {
        toward: Direction,
        position: u8,
        endpoint: u8,
    },
}

/// The endpoint `direction` heads for, if `pos` is no more than [`START_ROOM`] from it.
fn at_end(motor: Motor, direction: Direction, ft: &FlapTrimStatus) -> Option<NoRoom> {
    let pos = position(motor, ft);
    let room = room(motor, direction, pos, ft)?;
    let end = heads_for(motor, direction, ft)?;
    (room <= START_ROOM).then_some(NoRoom::At {
        toward: direction,
        position: pos,
        endpoint: end,
    })
}

/// One run's watch over its position (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Watch {
    pub motor: Motor,
    pub direction: Direction,
    /// The way the position is expected to go until the run shows its own: the
    /// direction's ([`expected_way`]), or what the caller saw this motor do (a
    /// reversed motor run back by the installation check).
    way: Option<Way>,
    /// Whether the run keeps to the endpoints: all but the setup screens' capture.
    keep_ends: bool,
    /// The latest positions with when the page heard them, oldest first.
    samples: Vec<(Instant, u8)>,
    /// The run's first position.
    first: Option<u8>,
    /// The farthest the run has gone its expected way from `first`, in counts.
    farthest: i32,
}

impl Watch {
    pub fn new(motor: Motor, direction: Direction) -> Watch {
        Watch {
            motor,
            direction,
            way: None,
            keep_ends: true,
            samples: Vec::new(),
            first: None,
            farthest: 0,
        }
    }

    /// The setup screens' endpoint capture: it may run past the endpoints (it is how
    /// new ones are found), but not against its command ([`super::against`]), nor on
    /// a stale position. `way`: the way a motor known to move against its command
    /// moves (a confirmed run), which is then not stopped for it.
    pub fn capture(motor: Motor, direction: Direction, way: Option<Way>) -> Watch {
        Watch {
            way,
            keep_ends: false,
            ..Watch::new(motor, direction)
        }
    }

    /// A run whose position the caller expects to go `way`.
    pub fn moving(motor: Motor, direction: Direction, way: Way) -> Watch {
        Watch {
            way: Some(way),
            ..Watch::new(motor, direction)
        }
    }

    /// The run's watch from `model`'s position when it starts (if fresh), rather than
    /// from the first it checks: a motor that moves at once is judged from where it
    /// was, not from a position heard a tick into its run.
    pub fn from_start(mut self, model: &Model, now: Instant) -> Watch {
        if let Some(st) = model
            .flap_trim
            .as_ref()
            .filter(|st| st.age(now) <= POSITION_FRESH)
        {
            self.first = Some(position(self.motor, &st.value));
        }
        self
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
    ///
    /// A run expected to go its direction's own way ([`Watch::new`],
    /// [`Watch::capture`] with no way) ends as soon as the position has gone
    /// [`MOVED`] counts the other way since the run's first sample
    /// ([`StopReason::MovedAgainst`]); one count of sensor noise does not end it. A
    /// run whose way the caller gave ([`Watch::moving`]) takes that way as the real
    /// one until the position has gone [`MOVED`] counts the other way, and then the
    /// other. Either ends by position against both endpoints (unless it is a
    /// capture): at or past the one it is moving toward (or about to pass it, at a
    /// rate that agrees with that way), and at or past the one behind it once it has
    /// moved toward that one, beyond one count of noise ([`NOISE`]) when it started at
    /// it. So a motor that runs the wrong way is stopped at the endpoint behind it
    /// without waiting for [`MOVED`] counts; for a run expected to go its own way
    /// that is moving against its command too.
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
        let first = *self.first.get_or_insert(pos);
        if self.samples.last().is_none_or(|(t, _)| *t != st.at) {
            self.samples.push((st.at, pos));
            if self.samples.len() > 6 {
                self.samples.remove(0);
            }
        }
        let expected = self
            .way
            .unwrap_or_else(|| expected_way(self.motor, self.direction, ft));
        let (pos, first) = (i32::from(pos), i32::from(first));
        let against = Err(StopReason::MovedAgainst(self.direction));
        // Gone MOVED counts back from the farthest it got its own way (from where it
        // started, at the least): moving against its command. A motor that starts
        // its own way and then turns back (a slipping drive, a sensor losing its
        // reference, air loads back-driving a weak trim) is caught there, not once it
        // is back past where it started.
        let gone = expected.along(pos - first);
        self.farthest = self.farthest.max(gone);
        if self.way.is_none() && self.farthest - gone >= MOVED {
            return against;
        }
        let Some(e) = ends(self.motor, ft).filter(|_| self.keep_ends) else {
            return Ok(());
        };
        let (lo, hi) = (i32::from(e.down.min(e.up)), i32::from(e.down.max(e.up)));
        let way = if expected.reversed().along(pos - first) >= MOVED {
            expected.reversed()
        } else {
            expected
        };
        let end = |w: Way| match w {
            Way::Grows => hi,
            Way::Shrinks => lo,
        };
        // Ahead: at or past it now, or before the page looks again at a rate that
        // agrees with the way it moves (noise the other way projects nothing).
        let rate = self
            .rate()
            .filter(|r| r.abs() >= STILL_RATE && Way::of(r.signum() as i32) == Some(way))
            .unwrap_or(0.0);
        let ahead = pos as f32 + rate * (age + LOOKAHEAD).as_secs_f32();
        if way.at_or_past(ahead, end(way) as f32) {
            return Err(StopReason::AtEndpoint(end(way) as u8));
        }
        // Behind: reached having moved toward it, beyond the noise it started in.
        let back = way.reversed();
        let behind = end(back);
        let toward = back.along(pos - first);
        let noise = if back.at_or_past(first as f32, behind as f32) {
            NOISE
        } else {
            0
        };
        if back.at_or_past(pos as f32, behind as f32) && toward > noise {
            return match self.way {
                None => against,
                Some(_) => Err(StopReason::AtEndpoint(behind as u8)),
            };
        }
        Ok(())
    }
}

/// The fastest a flap or trim motor is taken to move, counts a second: the virtual
/// VP-X's trim (25; its flaps run at 20). A probe is sized by it.
pub const MAX_RATE: f32 = 25.0;
/// Within this many counts of the endpoint behind it, a run whose real way is not
/// known yet starts as a probe ([`probe`]): 10 Hz positions at [`MAX_RATE`] are 2.5
/// counts apart, and a motor wired the wrong way would pass that endpoint between two.
pub const NEAR: i32 = 10;

/// How long a run `direction` from `pos`, whose real way is not known yet, may go
/// before a motor running the wrong way could pass the endpoint behind it by more
/// than [`NOISE`] (half a count kept for the sensor's rounding); `None` when that
/// endpoint is [`NEAR`] or farther, or there are no endpoints. The caller runs that
/// long, looks which way it went, and only then runs the rest.
pub fn probe(motor: Motor, direction: Direction, pos: u8, ft: &FlapTrimStatus) -> Option<Duration> {
    let behind = room(motor, opposite(direction), pos, ft)?;
    (behind < NEAR).then(|| {
        let counts = (behind.max(0) + NOISE) as f32 - 0.5;
        Duration::from_secs_f32(counts / MAX_RATE)
    })
}

/// After a probe's stop, how long before its way is judged: two FLAP_TRIM_STATUS
/// (10 Hz), the later one heard after the motor stopped.
pub const PROBE_SETTLE: Duration = Duration::from_millis(200);

/// A run going as probes ([`probe`]) until its position shows its way: a key's run
/// at the page ([`super::Controller`]) or a network run (`xfsp::drive`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Probing {
    pub motor: Motor,
    pub direction: Direction,
    /// The position when the run started: the way is judged from it.
    pub start: u8,
}

/// What a probing run does next ([`Probing::next`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProbeNext {
    /// Still moving, or waiting for a position heard after its stop.
    Wait,
    /// It went the commanded way: it streams on as any run.
    Go,
    /// It went the other way: stopped as moving against its command.
    Against,
    /// It did not move: another probe this long, from where it is.
    Again(Duration),
}

impl Probing {
    /// The probe a run of `motor` `direction` starts as, with its length, if the
    /// run's way is not known and it starts within [`NEAR`] of the endpoint behind
    /// it on a fresh position; `None` for a run that starts as any run.
    pub fn start(
        model: &Model,
        motor: Motor,
        direction: Direction,
        now: Instant,
    ) -> Option<(Probing, Duration)> {
        let st = model
            .flap_trim
            .as_ref()
            .filter(|st| st.age(now) <= POSITION_FRESH)?;
        let start = position(motor, &st.value);
        let length = probe(motor, direction, start, &st.value)?;
        Some((
            Probing {
                motor,
                direction,
                start,
            },
            length,
        ))
    }

    /// After the probe's stop (`paused`, when it went out) and [`PROBE_SETTLE`], with
    /// a position heard at least half of that after the stop: which way it went
    /// from its start. The decision for a motor that never shows its way: another
    /// probe, for as long as the run lasts (each sized so the fastest motor cannot
    /// pass the endpoint behind it beyond [`NOISE`]); a slow motor creeps off in
    /// probes, a stuck one moves nothing, and the run's every other end (its key let
    /// go, its requests stopping, the run cap) still ends it.
    pub fn next(&self, model: &Model, paused: Option<Instant>, now: Instant) -> ProbeNext {
        let (Some(paused), Some(st)) = (paused, model.flap_trim.as_ref()) else {
            return ProbeNext::Wait;
        };
        if now < paused + PROBE_SETTLE || st.at < paused + PROBE_SETTLE / 2 {
            return ProbeNext::Wait;
        }
        let ft = &st.value;
        let pos = position(self.motor, ft);
        let went = expected_way(self.motor, self.direction, ft)
            .along(i32::from(pos) - i32::from(self.start));
        if went < 0 {
            return ProbeNext::Against;
        }
        match probe(self.motor, self.direction, pos, ft).filter(|_| went == 0) {
            Some(length) => ProbeNext::Again(length),
            None => ProbeNext::Go,
        }
    }

    /// The notice while it probes: "pitch trim near its down endpoint: trying a short
    /// run first".
    pub fn words(&self) -> String {
        format!(
            "{} near its {} endpoint: trying a short run first",
            self.motor.name(),
            opposite(self.direction).name()
        )
    }
}

/// Whether a run that keeps to the endpoints may start `direction` now: its position
/// fresh, and room to the endpoint it will reach. `way`: the way the caller knows the
/// run moves the position (`None`: the direction's own).
pub fn room_to_run(
    model: &Model,
    motor: Motor,
    direction: Direction,
    way: Option<Way>,
    now: Instant,
) -> Result<(), NoRoom> {
    let Some(st) = model.flap_trim.as_ref() else {
        return Ok(()); // `motor_check` already says there is no live status.
    };
    if st.age(now) > POSITION_FRESH {
        return Err(NoRoom::Stale);
    }
    let ft = &st.value;
    let toward = match way {
        // Run one way to move the other: the room is toward the endpoint it will
        // really reach, which is the other direction's.
        Some(w) if w != expected_way(motor, direction, ft) => opposite(direction),
        _ => direction,
    };
    at_end(motor, toward, ft).map_or(Ok(()), Err)
}

/// The other way.
pub fn opposite(d: Direction) -> Direction {
    match d {
        Direction::Up => Direction::Down,
        Direction::Down => Direction::Up,
        Direction::Left => Direction::Right,
        Direction::Right => Direction::Left,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Source, Stamped, TrimKind};
    use crate::protocol::fault::FaultCode;
    use crate::protocol::message::{FlapFlags, TrimFlags};

    /// Flaps up 20 / down 220 and pitch trim up 30 / down 220, at `flap` and `pitch`.
    fn status(flap: u8, pitch: u8) -> FlapTrimStatus {
        FlapTrimStatus {
            flap: FlapFlags::default(),
            pitch_trim: TrimFlags::default(),
            roll_trim: TrimFlags::default(),
            flap_position: flap,
            pitch_trim_position: pitch,
            roll_trim_position: 0,
            flap_fault: FaultCode::NoFault,
            pitch_trim_fault: FaultCode::NoFault,
            roll_trim_fault: FaultCode::NoFault,
            flap_up: 20,
            flap_down: 220,
            flap_midpoint_1: 0,
            flap_midpoint_2: 0,
            pitch_trim_up: 30,
            pitch_trim_down: 220,
            pitch_trim_neutral: 125,
            roll_trim_up: 0,
            roll_trim_down: 0,
            roll_trim_neutral: 0,
        }
    }

    /// What the watch says at each of `positions`, heard 100 ms apart (10 Hz).
    fn watch(motor: Motor, direction: Direction, positions: &[u8]) -> Vec<Result<(), StopReason>> {
        watch_with(Watch::new(motor, direction), positions)
    }

    fn watch_with(mut w: Watch, positions: &[u8]) -> Vec<Result<(), StopReason>> {
        let (motor, t0) = (w.motor, Instant::now());
        let mut model = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        positions
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                let at = t0 + Duration::from_millis(100 * i as u64);
                let ft = match motor {
                    Motor::Flaps => status(p, 125),
                    _ => status(20, p),
                };
                model.flap_trim = Some(Stamped::new(ft, at));
                w.check(&model, at + Duration::from_millis(5))
            })
            .collect()
    }

    const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

    /// Flaps at their up endpoint running down read one count of noise
    /// (20, 19, 20) before they move: the run goes on.
    #[test]
    fn one_count_of_noise_at_the_endpoint_behind_does_not_stop_a_run() {
        let seen = watch(Motor::Flaps, Direction::Down, &[20, 19, 20, 21, 23, 25, 27]);
        assert!(seen.iter().all(|r| r.is_ok()), "{seen:?}");
        // Nor one count of noise back once it has moved off.
        let seen = watch(Motor::Flaps, Direction::Down, &[40, 39, 40, 42]);
        assert!(seen.iter().all(|r| r.is_ok()), "{seen:?}");
    }

    /// A run down whose motor really goes up (leads swapped) is stopped
    /// the moment its position reaches the up endpoint, without waiting for the
    /// counts that would show its way anywhere else: from 31, at 30. That is moving
    /// against its command; a run whose way the caller gave stops there as at an
    /// endpoint.
    #[test]
    fn a_wrong_way_run_stops_at_the_endpoint_behind_by_position() {
        let against = Err(StopReason::MovedAgainst(Direction::Down));
        let seen = watch(PITCH, Direction::Down, &[31, 30]);
        assert_eq!(seen, vec![Ok(()), against]);
        let seen = watch(PITCH, Direction::Down, &[33, 32, 30]);
        assert_eq!(seen[2], against);
        // Started at it: one count past is the sensor's noise, two is not.
        let seen = watch(PITCH, Direction::Down, &[30, 29, 28]);
        assert_eq!(seen, vec![Ok(()), Ok(()), against]);
        // A run the check sends down expecting it to shrink (it saw it so), that then
        // goes back up to 30 and past: an endpoint.
        let seen = watch_with(
            Watch::moving(PITCH, Direction::Down, Way::Grows),
            &[32, 31, 30],
        );
        assert_eq!(seen[2], Err(StopReason::AtEndpoint(30)));
    }

    /// Asked up from neutral, a pitch trim with swapped leads goes down
    /// (the position grows): stopped once it has gone MOVED (3) counts, not at the
    /// down endpoint 220; one count of noise the wrong way does not stop it.
    #[test]
    fn a_run_moving_against_its_command_stops_within_a_few_counts() {
        let seen = watch(PITCH, Direction::Up, &[128, 129, 128, 130, 131, 133]);
        assert_eq!(
            seen,
            vec![
                Ok(()),
                Ok(()),
                Ok(()),
                Ok(()),
                Err(StopReason::MovedAgainst(Direction::Up)),
                Err(StopReason::MovedAgainst(Direction::Up)),
            ]
        );
        // Flaps asked down going up, and so for the roll trim's left and right.
        let seen = watch(Motor::Flaps, Direction::Down, &[120, 118, 117]);
        assert_eq!(seen[2], Err(StopReason::MovedAgainst(Direction::Down)));
        // Its own way, no stop for it.
        let seen = watch(PITCH, Direction::Up, &[128, 126, 123, 120]);
        assert!(seen.iter().all(Result::is_ok), "{seen:?}");
    }

    /// Gone 3 counts back from the nearest it came to its target, for every origin. Asked up (shrinking) from
    /// 128, a trim that goes to 120 and then turns back is stopped at 123, three
    /// counts from the farthest it got, though still 5 short of where it started
    /// (the rule from the start alone waited for 131). Two counts back is noise.
    #[test]
    fn a_run_that_turns_back_is_stopped_a_few_counts_from_the_farthest_it_got() {
        let seen = watch(PITCH, Direction::Up, &[128, 125, 122, 120, 121, 122, 123]);
        let against = Err(StopReason::MovedAgainst(Direction::Up));
        assert_eq!(&seen[..6], &[Ok(()); 6], "{seen:?}");
        assert_eq!(seen[6], against);
        let seen = watch(PITCH, Direction::Up, &[128, 125, 122, 120, 122, 121, 119]);
        assert!(seen.iter().all(Result::is_ok), "{seen:?}");
    }

    /// At the down endpoint 220, `u` on a motor that goes down is not taken as moving
    /// away from it: a run that in fact goes further past the endpoint is stopped
    /// beyond the one count of noise.
    #[test]
    fn at_an_endpoint_a_run_going_further_past_it_is_stopped_within_the_noise() {
        let seen = watch(PITCH, Direction::Up, &[220, 221, 222]);
        assert_eq!(
            seen,
            vec![Ok(()), Ok(()), Err(StopReason::MovedAgainst(Direction::Up))]
        );
        let seen = watch(PITCH, Direction::Up, &[223, 224, 225]);
        assert_eq!(seen[2], Err(StopReason::MovedAgainst(Direction::Up)));
    }

    /// The setup screens' capture runs past the endpoints, but not against its
    /// command; once confirmed knowing its way, not that either.
    #[test]
    fn a_capture_passes_the_endpoints_but_not_against_its_command() {
        let seen = watch_with(
            Watch::capture(PITCH, Direction::Up, None),
            &[34, 31, 28, 25, 22],
        );
        assert!(seen.iter().all(Result::is_ok), "past 30: {seen:?}");
        let seen = watch_with(Watch::capture(PITCH, Direction::Up, None), &[34, 36, 38]);
        assert_eq!(seen[2], Err(StopReason::MovedAgainst(Direction::Up)));
        let seen = watch_with(
            Watch::capture(PITCH, Direction::Up, Some(Way::Grows)),
            &[34, 36, 38, 40],
        );
        assert!(seen.iter().all(Result::is_ok), "confirmed: {seen:?}");
    }

    /// Going its own way it still ends at the endpoint ahead, by position or just
    /// before it passes it at its rate.
    #[test]
    fn a_run_still_ends_at_the_endpoint_ahead() {
        let seen = watch(PITCH, Direction::Up, &[40, 38, 35, 33]);
        assert_eq!(seen[3], Err(StopReason::AtEndpoint(30)), "{seen:?}");
        let seen = watch(PITCH, Direction::Down, &[200, 203, 206, 220]);
        assert!(seen[..3].iter().all(|r| r.is_ok()), "{seen:?}");
        assert_eq!(seen[3], Err(StopReason::AtEndpoint(220)));
    }

    /// A probe is sized so a motor going the wrong way at the fastest rate passes the
    /// endpoint behind it by less than one count and a half; far from it, no probe.
    #[test]
    fn a_probe_near_the_endpoint_behind_is_short() {
        let ft = status(20, 30);
        let p = probe(PITCH, Direction::Down, 30, &ft).unwrap();
        assert_eq!(p, Duration::from_millis(20));
        let p = probe(PITCH, Direction::Down, 35, &ft).unwrap();
        assert_eq!(
            p.as_millis(),
            219,
            "5.5 counts at 25 a second, rounded down"
        );
        assert_eq!(probe(PITCH, Direction::Down, 40, &ft), None);
        let p = probe(PITCH, Direction::Up, 215, &ft).unwrap();
        assert_eq!(p.as_millis(), 219);
    }
}

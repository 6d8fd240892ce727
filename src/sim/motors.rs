//! The flap and trim motors (ICD §6.2.3, §6.2.4, §6.4.2, §6.4.3, Table 27).
//!
//! A motor has a position 0–255 (the position sensor) and moves it while driven. What
//! drives it:
//!
//! * **TRIM_MOVE / FLAP_MOVE streams** (icd-reading R19). §6.4.2 asks the EFIS for
//!   "at least 4Hz", an interval of 250 ms at most, so a message exactly 250 ms after
//!   the last (or a few ms later, through a USB adapter's jitter) must keep the motor
//!   running. Decision: each "on" message keeps it running for [`STREAM_TIMEOUT`]
//!   (300 ms, the 250 ms the EFIS is held to plus 50 ms of margin); when nothing
//!   comes in that time the motor stops at that instant and a **starvation** is
//!   counted: the real unit's runaway protection. A message that keeps the run going
//!   but came more than [`STREAM_INTERVAL`] (250 ms) after the one before is counted
//!   as **late**: the unit forgives it, our own tests do not (they prove the page never
//!   leaves a gap over 250 ms). "Off" stops at once and is neither. Streamed
//!   movement is momentary and ignores the endpoints (Table 15 note 4, Table 16 note 1);
//!   only the sensor's 0–255 range stops it.
//! * **The external flap/trim switches** (held inputs). They stop at the configured
//!   endpoints; position-mode flaps step to the next midpoint or endpoint on "down" and
//!   run fully up on "up" (Table 16 note 1). At an endpoint the motor runs on for the
//!   flap endpoint duration (note 6) without the position changing.
//! * **An injected runaway**: the motor runs with nobody asking until the unit notices
//!   ([`RUNAWAY_DETECT`]) and faults it (FLAP_RUNAWAY / TRIM_RUNAWAY, Appendix E).
//!
//! Decisions where the ICD is silent: speeds are [`TRIM_RATE`] and [`FLAP_RATE`]
//! position units a second; pitch trim runs at its `power` percent when the airspeed
//! (IAS, else ground speed) is above its `speed` (Table 15 note 5); any continuous run
//! stops after the Appendix F flap "Max Run Time" of 30 s.

use std::time::{Duration, Instant};

use super::scenario::{MotorDirection, MotorId};
use crate::protocol::FaultCode;

/// The longest interval the EFIS may leave between two TRIM_MOVE / FLAP_MOVE
/// messages (ICD §6.4.2 "at least 4Hz", icd-reading R19). A longer one is *late*.
pub const STREAM_INTERVAL: Duration = Duration::from_millis(250);
/// A streamed move lasts this long after the last "on" message: 50 ms later than
/// [`STREAM_INTERVAL`], so an EFIS streaming at exactly 4 Hz does not stutter on a few
/// ms of line or scheduler jitter.
pub const STREAM_TIMEOUT: Duration = Duration::from_millis(300);
/// How long an uncommanded run lasts before the unit faults the motor.
pub const RUNAWAY_DETECT: Duration = Duration::from_millis(500);
/// Longest continuous run (Appendix F flap Max Run Time; used for the trims as well).
pub const MAX_RUN: Duration =
    Duration::from_secs(crate::protocol::defaults::FLAP_MAX_RUN_TIME_S as u64);
/// Trim travel, position units per second at 100 % power.
pub const TRIM_RATE: f32 = 25.0;
/// Flap travel, position units per second.
pub const FLAP_RATE: f32 = 20.0;

/// Where a motor may go: its configured points, from FLAP_SPEC or TRIM_SPEC.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    pub enabled: bool,
    pub up: u8,
    pub down: u8,
    /// Position-mode flap stops between up and down (non-zero ones only).
    pub stops: [u8; 2],
    pub position_mode: bool,
    /// Extra run at an endpoint (flap endpoint duration).
    pub endpoint_run: Duration,
    /// Position units per second right now (speed-reduced for pitch trim).
    pub rate: f32,
    /// The motor runs the other way from the one it is driven: its leads swapped,
    /// unless the polarity setting undoes it (a wiring fault, `reversed`).
    pub reversed: bool,
    /// Driven, but the position never changes (a wiring fault, `stuck`).
    pub stuck: bool,
}

impl Geometry {
    /// +1 when "down" makes the number grow, −1 when it shrinks.
    fn down_sign(&self) -> f32 {
        if self.down >= self.up { 1.0 } else { -1.0 }
    }

    fn sign(&self, dir: MotorDirection) -> f32 {
        match dir {
            MotorDirection::Down => self.down_sign(),
            MotorDirection::Up => -self.down_sign(),
        }
    }

    /// How far `pos` is from `up` toward `down` (grows as the flaps extend).
    pub fn extension(&self, pos: f32) -> f32 {
        (pos - self.up as f32) * self.down_sign()
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    Stream {
        /// When the last "on" message came.
        last: Instant,
        deadline: Instant,
    },
    Switch,
    /// Position mode: run to this position and stop.
    Target(u8),
    Runaway {
        trip_at: Instant,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Drive {
    dir: MotorDirection,
    source: Source,
    started: Instant,
}

/// One motor; see the module documentation.
#[derive(Debug, Clone)]
pub struct Motor {
    pub id: MotorId,
    pub position: f32,
    pub fault: FaultCode,
    /// Streams that ended because no message came within [`STREAM_TIMEOUT`].
    pub starvations: u64,
    /// "On" messages that kept a run going but came more than [`STREAM_INTERVAL`]
    /// after the one before (a diagnostic: the unit forgives them).
    pub late: u64,
    drive: Option<Drive>,
    /// Running on at an endpoint until then (position fixed).
    overrun_until: Option<Instant>,
    last: Instant,
    switch_held: Option<MotorDirection>,
}

impl Motor {
    pub fn new(id: MotorId, position: f32, now: Instant) -> Self {
        Motor {
            id,
            position: position.clamp(0.0, 255.0),
            fault: FaultCode::NoFault,
            starvations: 0,
            late: 0,
            drive: None,
            overrun_until: None,
            last: now,
            switch_held: None,
        }
    }

    pub fn running(&self, now: Instant) -> bool {
        self.drive.is_some() || self.overrun_until.is_some_and(|t| now < t)
    }

    pub fn faulted(&self) -> bool {
        self.fault.is_fault()
    }

    /// The 0–255 byte FLAP_TRIM_STATUS carries.
    pub fn position_byte(&self) -> u8 {
        self.position.round().clamp(0.0, 255.0) as u8
    }

    pub fn switch_held(&self) -> Option<MotorDirection> {
        self.switch_held
    }

    /// TRIM_MOVE / FLAP_MOVE. Returns `false` when the motor cannot run (disabled or
    /// faulted) and the message changed nothing.
    pub fn stream(&mut self, on: bool, dir: MotorDirection, g: &Geometry, now: Instant) -> bool {
        self.advance(g, now);
        if !on {
            if matches!(
                self.drive,
                Some(Drive {
                    source: Source::Stream { .. },
                    ..
                })
            ) {
                self.drive = None;
            }
            return true;
        }
        if !g.enabled || self.faulted() {
            return false;
        }
        let started = match self.drive {
            Some(Drive {
                dir: was,
                source: Source::Stream { last, .. },
                started,
            }) if was == dir => {
                if now.saturating_duration_since(last) > STREAM_INTERVAL {
                    self.late += 1;
                }
                started
            }
            Some(Drive {
                source: Source::Runaway { .. },
                ..
            }) => return false,
            _ => now,
        };
        self.overrun_until = None;
        self.drive = Some(Drive {
            dir,
            source: Source::Stream {
                last: now,
                deadline: now + STREAM_TIMEOUT,
            },
            started,
        });
        true
    }

    /// The external flap/trim switch input, held (`Some`) or released (`None`).
    pub fn switch(&mut self, held: Option<MotorDirection>, g: &Geometry, now: Instant) {
        self.advance(g, now);
        let pressed = held.filter(|h| self.switch_held != Some(*h));
        self.switch_held = held;
        if self.faulted() || !g.enabled {
            return;
        }
        if g.position_mode {
            // Position mode acts on the press; release does not stop the run.
            if let Some(dir) = pressed {
                let target = self.next_stop(dir, g);
                self.drive = Some(Drive {
                    dir,
                    source: Source::Target(target),
                    started: now,
                });
            }
            return;
        }
        match held {
            Some(dir) => {
                self.overrun_until = None;
                self.drive = Some(Drive {
                    dir,
                    source: Source::Switch,
                    started: now,
                })
            }
            None => {
                if matches!(
                    self.drive,
                    Some(Drive {
                        source: Source::Switch,
                        ..
                    })
                ) {
                    self.drive = None;
                }
            }
        }
    }

    /// Position mode: down goes to the next configured point, up all the way up.
    fn next_stop(&self, dir: MotorDirection, g: &Geometry) -> u8 {
        if dir == MotorDirection::Up {
            return g.up;
        }
        let here = g.extension(self.position);
        let mut points: Vec<u8> = g.stops.iter().copied().filter(|&p| p != 0).collect();
        points.push(g.down);
        points
            .into_iter()
            .filter(|&p| g.extension(p as f32) > here + 0.5)
            .min_by(|a, b| g.extension(*a as f32).total_cmp(&g.extension(*b as f32)))
            .unwrap_or(g.down)
    }

    /// The motor starts running by itself.
    pub fn runaway(&mut self, dir: MotorDirection, g: &Geometry, now: Instant) {
        self.advance(g, now);
        self.overrun_until = None;
        self.drive = Some(Drive {
            dir,
            source: Source::Runaway {
                trip_at: now + RUNAWAY_DETECT,
            },
            started: now,
        });
    }

    /// Stops everything (power cycle, disabled in a new spec).
    pub fn halt(&mut self, now: Instant) {
        self.drive = None;
        self.overrun_until = None;
        self.last = now;
    }

    /// DEVICE_CLEAR of this motor (Appendix E): the fault stays, as FLAP_ACTIVE /
    /// TRIM_ACTIVE, while its switch input is held.
    pub fn clear(&mut self) {
        if !self.faulted() {
            return;
        }
        self.fault = if self.switch_held.is_some() {
            match self.id {
                MotorId::Flap => FaultCode::FlapActive,
                _ => FaultCode::TrimActive,
            }
        } else {
            FaultCode::NoFault
        };
    }

    pub fn set_fault(&mut self, code: FaultCode, now: Instant) {
        self.fault = code;
        if code.is_fault() {
            self.halt(now);
        }
    }

    /// Moves the position up to `now`, stopping where the drive ends.
    pub fn advance(&mut self, g: &Geometry, now: Instant) {
        if now <= self.last {
            return;
        }
        let from = self.last;
        self.last = now;
        if self.overrun_until.is_some_and(|t| now >= t) {
            self.overrun_until = None;
        }
        let Some(d) = self.drive else {
            return;
        };
        let mut until = now.min(d.started + MAX_RUN);
        let mut stop = until < now;
        match d.source {
            Source::Stream { deadline, .. } if deadline <= now => {
                until = until.min(deadline);
                stop = true;
                if deadline < d.started + MAX_RUN {
                    self.starvations += 1;
                }
            }
            Source::Runaway { trip_at } if trip_at <= now => {
                until = until.min(trip_at);
                stop = true;
                self.fault = match self.id {
                    MotorId::Flap => FaultCode::FlapRunaway,
                    _ => FaultCode::TrimRunaway,
                };
            }
            _ => {}
        }
        let secs = until.saturating_duration_since(from).as_secs_f32();
        // `sign` is where the unit drives the motor, and what its endpoint logic
        // watches for; the wiring decides where the position really goes. A reversed
        // motor so runs away from its endpoint until the run cap or the sensor's end,
        // and a stuck one until the run cap. An injected runaway's direction is
        // already the one the position takes.
        let sign = g.sign(d.dir);
        let travel = match d.source {
            _ if g.stuck => 0.0,
            Source::Runaway { .. } => sign,
            _ if g.reversed => -sign,
            _ => sign,
        };
        let mut pos = self.position + travel * g.rate * secs;
        // Switch and position-mode runs stop at their endpoint or target.
        let limit = match d.source {
            Source::Switch => Some(match d.dir {
                MotorDirection::Up => g.up,
                MotorDirection::Down => g.down,
            }),
            Source::Target(t) => Some(t),
            _ => None,
        };
        if let Some(l) = limit {
            let l = l as f32;
            if (l - pos) * sign <= 0.0 {
                pos = l;
                stop = true;
                let at_end = l == g.up as f32 || l == g.down as f32;
                if at_end && !g.endpoint_run.is_zero() {
                    self.overrun_until = Some(now + g.endpoint_run);
                }
            }
        }
        if !(0.0..=255.0).contains(&pos) {
            pos = pos.clamp(0.0, 255.0);
        }
        self.position = pos;
        if stop {
            self.drive = None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geom() -> Geometry {
        Geometry {
            enabled: true,
            up: 20,
            down: 220,
            stops: [90, 160],
            position_mode: false,
            endpoint_run: Duration::ZERO,
            rate: 20.0,
            reversed: false,
            stuck: false,
        }
    }

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    /// The motor is at `want`, within a hundredth.
    #[track_caller]
    fn at(m: &Motor, want: f32, why: &str) {
        assert!((m.position - want).abs() < 0.01, "{why} {}", m.position);
    }

    #[test]
    fn a_stream_every_200_ms_runs_on_and_a_400_ms_gap_starves_once() {
        let t0 = Instant::now();
        let g = geom();
        let mut m = Motor::new(MotorId::Flap, 100.0, t0);
        for i in 0..5 {
            assert!(m.stream(true, MotorDirection::Down, &g, ms(t0, i * 200)));
        }
        m.advance(&g, ms(t0, 800));
        assert!(m.running(ms(t0, 800)));
        assert_eq!(m.starvations, 0);
        at(&m, 116.0, "");
        // The next message comes 400 ms after the last: the motor stopped at 1100 ms,
        // 300 ms after the last message.
        m.advance(&g, ms(t0, 1200));
        assert!(!m.running(ms(t0, 1200)));
        assert_eq!(m.starvations, 1);
        assert_eq!(m.late, 0, "a stop is a starvation, not a late message");
        at(&m, 122.0, "");
    }

    #[test]
    fn a_stream_at_exactly_4_hz_or_a_little_late_runs_on_and_late_ones_are_counted() {
        let t0 = Instant::now();
        let g = geom();
        let mut m = Motor::new(MotorId::Flap, 100.0, t0);
        // 4 Hz exactly (ICD §6.4.2 "at least 4Hz"): never late, never stopped.
        for i in 0..5 {
            assert!(m.stream(true, MotorDirection::Down, &g, ms(t0, i * 250)));
        }
        assert!(m.running(ms(t0, 1000)));
        assert_eq!((m.starvations, m.late), (0, 0));
        // 290 ms later: within the unit's margin, so the run goes on, counted late.
        m.stream(true, MotorDirection::Down, &g, ms(t0, 1290));
        assert!(m.running(ms(t0, 1290)));
        assert_eq!((m.starvations, m.late), (0, 1));
        at(&m, 100.0 + 20.0 * 1.29, "");
        // 299 ms without a message still runs; at 300 ms it stops.
        m.advance(&g, ms(t0, 1589));
        assert!(m.running(ms(t0, 1589)));
        m.advance(&g, ms(t0, 1590));
        assert!(!m.running(ms(t0, 1590)));
        assert_eq!((m.starvations, m.late), (1, 1));
    }

    #[test]
    fn off_stops_at_once_without_a_starvation() {
        let t0 = Instant::now();
        let g = geom();
        let mut m = Motor::new(MotorId::Pitch, 100.0, t0);
        m.stream(true, MotorDirection::Up, &g, t0);
        m.stream(false, MotorDirection::Up, &g, ms(t0, 100));
        m.advance(&g, ms(t0, 1000));
        assert_eq!(m.starvations, 0);
        at(&m, 98.0, "up is toward the smaller number:");
    }

    #[test]
    fn streams_ignore_endpoints_but_switches_stop_at_them() {
        let t0 = Instant::now();
        let g = geom();
        let mut m = Motor::new(MotorId::Flap, 215.0, t0);
        m.stream(true, MotorDirection::Down, &g, t0);
        m.advance(&g, ms(t0, 200));
        assert!(m.position > 218.0);
        let mut s = Motor::new(MotorId::Flap, 215.0, t0);
        s.switch(Some(MotorDirection::Down), &g, t0);
        s.advance(&g, ms(t0, 2000));
        assert_eq!(s.position, 220.0);
        assert!(!s.running(ms(t0, 2000)));
    }

    #[test]
    fn position_mode_steps_down_through_the_midpoints_and_runs_fully_up() {
        let t0 = Instant::now();
        let g = Geometry {
            position_mode: true,
            ..geom()
        };
        let mut m = Motor::new(MotorId::Flap, 20.0, t0);
        m.switch(Some(MotorDirection::Down), &g, t0);
        m.switch(None, &g, ms(t0, 100));
        m.advance(&g, ms(t0, 10_000));
        assert_eq!(m.position, 90.0);
        m.switch(Some(MotorDirection::Down), &g, ms(t0, 10_000));
        m.switch(None, &g, ms(t0, 10_100));
        m.advance(&g, ms(t0, 20_000));
        assert_eq!(m.position, 160.0);
        m.switch(Some(MotorDirection::Up), &g, ms(t0, 20_000));
        m.switch(None, &g, ms(t0, 20_100));
        m.advance(&g, ms(t0, 40_000));
        assert_eq!(m.position, 20.0);
    }

    #[test]
    fn a_reversed_motor_runs_the_other_way_and_past_its_endpoint_to_the_run_cap() {
        let t0 = Instant::now();
        let g = Geometry {
            reversed: true,
            ..geom()
        };
        let mut m = Motor::new(MotorId::Flap, 100.0, t0);
        m.stream(true, MotorDirection::Down, &g, t0);
        m.advance(&g, ms(t0, 200));
        at(&m, 96.0, "down shrinks:");
        // The switch drives it toward `down` (220); it never gets there, so it runs
        // until the sensor's end (0) and stops at the 30 s cap.
        let mut s = Motor::new(MotorId::Flap, 100.0, t0);
        s.switch(Some(MotorDirection::Down), &g, t0);
        s.advance(&g, ms(t0, 2_000));
        at(&s, 60.0, "");
        assert!(s.running(ms(t0, 2_000)));
        s.advance(&g, ms(t0, 31_000));
        assert_eq!(s.position, 0.0);
        assert!(!s.running(ms(t0, 31_000)), "stopped by the run cap");
    }

    #[test]
    fn a_stuck_motor_runs_without_moving() {
        let t0 = Instant::now();
        let g = Geometry {
            stuck: true,
            ..geom()
        };
        let mut m = Motor::new(MotorId::Pitch, 120.0, t0);
        m.stream(true, MotorDirection::Up, &g, t0);
        m.advance(&g, ms(t0, 200));
        assert!(m.running(ms(t0, 200)));
        assert_eq!(m.position, 120.0);
    }

    #[test]
    fn a_runaway_trips_the_fault_and_the_clear_is_refused_while_the_switch_is_held() {
        let t0 = Instant::now();
        let g = geom();
        let mut m = Motor::new(MotorId::Pitch, 100.0, t0);
        m.runaway(MotorDirection::Down, &g, t0);
        m.advance(&g, ms(t0, 1000));
        assert_eq!(m.fault, FaultCode::TrimRunaway);
        at(&m, 110.0, "");
        assert!(!m.stream(true, MotorDirection::Up, &g, ms(t0, 1000)));
        m.switch(Some(MotorDirection::Up), &g, ms(t0, 1100));
        m.clear();
        assert_eq!(m.fault, FaultCode::TrimActive);
        m.switch(None, &g, ms(t0, 1200));
        m.clear();
        assert_eq!(m.fault, FaultCode::NoFault);
    }
}

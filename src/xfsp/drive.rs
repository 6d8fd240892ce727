//! FLAPREQ/PTRIMREQ/RTRIMREQ: drive a motor toward a requested position with control's
//! [`MotorStreamer`], so the network gets exactly the safe 4 Hz stream the keys get.
//!
//! A request is held for the shorter of its Expire and [`REQUEST_HOLD`]; a requester
//! keeps a motor running only by repeating the request (we recommend 4 Hz). The run
//! ends, with a stop message, on the first of: the target reached or passed, the
//! request expiring (requests stopped), any reason control's `motor_check` gives (lost
//! communication, motor fault, disabled, flap-down inhibit, lost motor status), the
//! streamer's own limits (maximum run time, starved stream), a link error, or shutdown.
//!
//! The unit does not stop a TRIM_MOVE/FLAP_MOVE stream at the motor's endpoints (ICD
//! Tables 15 and 16), so a network run keeps to them by the same rule as the page's own
//! runs ([`endpoints::Watch`]): it is refused within [`endpoints::START_ROOM`] of the
//! endpoint it heads for, and ends at the endpoint ahead (or just before it would pass
//! it at the rate it is moving), at the endpoint behind once it moves toward it, and on
//! a position older than [`endpoints::POSITION_FRESH`]. Started within
//! [`endpoints::NEAR`] of the endpoint behind it, it goes as probes until the motor
//! shows its way ([`endpoints::Probing`]), as the page's keys do, so a motor wired
//! the wrong way is not driven past that endpoint beyond [`endpoints::NOISE`].
//!
//! Like every run, it also ends as soon as it moves [`endpoints::MOVED`] counts back
//! from the farthest it got the way it was driven (the watch's rule,
//! [`StopReason::MovedAgainst`]): a motor with swapped leads or polarity runs away
//! from where it was sent, and is stopped there rather than at the far endpoint. A
//! motor seen doing so, here or by any other origin sharing the record
//! ([`MotorDrive::share_against`]), is refused from then on: the network cannot
//! confirm such a run ([`crate::control::against`]).
//!
//! After a run ends for any reason the target is *latched*: the same target does not
//! start the motor again, so a position that settles a count away from the target, or a
//! fault that clears, never makes the motor hunt or restart by itself. A different
//! target, or the requests stopping and starting again, is a new request.
//!
//! One motor runs at a time (the streamer has one run); other requests wait their turn.
//!
//! Every request gets an answer in the event log and in [`MotorDrive::counts`]: taken
//! (a run started, or the motor was already there) or refused (no live position or
//! scale, a motor check failed, at its endpoint, or it expired waiting for another
//! run to end).
//!
//! [`endpoints::MOVED`]: crate::control::endpoints::MOVED
//! [`endpoints::NEAR`]: crate::control::endpoints::NEAR
//! [`endpoints::NOISE`]: crate::control::endpoints::NOISE
//! [`endpoints::POSITION_FRESH`]: crate::control::endpoints::POSITION_FRESH
//! [`endpoints::Probing`]: crate::control::endpoints::Probing
//! [`endpoints::Probing::next`]: crate::control::endpoints::Probing::next
//! [`endpoints::START_ROOM`]: crate::control::endpoints::START_ROOM
//! [`endpoints::Watch`]: crate::control::endpoints::Watch

use std::time::{Duration, Instant};

use crate::audit::Origin;
use crate::control::endpoints::{self, ProbeNext, Probing, Watch};
use crate::control::run::{self, Known};
use crate::control::run_state::ReleaseMode;
use crate::control::{Against, Direction, MotorStreamer, StopReason, StreamerConfig, motor_check};
use crate::model::{LogLevel, Model, Motor};
use crate::protocol::message::Packet;

use super::scale::Axis;

/// How long a request is held without a repeat: one 1 Hz period plus 200 ms of jitter.
pub const REQUEST_HOLD: Duration = Duration::from_millis(1200);
/// Raw counts short of the target at which the motor is stopped: the 10 Hz position
/// reports lag the motor, so stopping a count early lands on the target, not past it.
pub const STOP_MARGIN: i32 = 1;

/// A motor request as heard.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MotorRequest {
    /// On the draft's ±100000 scale.
    pub target: i32,
    pub src: u16,
    pub until: Instant,
}

#[derive(Debug, Clone, Copy)]
struct Slot {
    req: Option<MotorRequest>,
    /// A target already served (reached, refused or stopped).
    latched: Option<i32>,
}

/// The run going on now.
#[derive(Debug, Clone)]
struct Active {
    motor: Motor,
    direction: Direction,
    /// The request's target on the draft's scale, and in raw counts.
    target: i32,
    raw_target: u8,
    /// Its watch over the endpoints, the position's age and its way.
    watch: Watch,
    /// Going as probes until the motor shows its way ([`endpoints::Probing`]).
    probe: Option<Probing>,
}

/// How the requests this drive served ended, for the gateway's counters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DriveCounts {
    /// A run started toward the target, or the motor was already there.
    pub taken: u64,
    /// Refused, or expired before it could be served; each logged with the reason.
    pub refused: u64,
}

#[derive(Debug, Clone)]
pub struct MotorDrive {
    streamer: MotorStreamer,
    slots: [Slot; 3],
    active: Option<Active>,
    /// The page's own keys are running a motor: the network waits, so two streams
    /// (perhaps in opposite directions) never share the link.
    local_busy: bool,
    counts: DriveCounts,
    /// Motors seen moving against their command, shared with the page's keys.
    against: Against,
}

impl MotorDrive {
    /// `config.release_mode` is forced to key-release: a network request has no key
    /// repeats, and its dead man is the request hold instead.
    pub fn new(mut config: StreamerConfig) -> MotorDrive {
        config.release_mode = ReleaseMode::KeyRelease;
        // A request's own expiry is this drive's dead man; there are no key repeats.
        config.key_release_repeat_guard = None;
        MotorDrive {
            streamer: MotorStreamer::new(config),
            slots: [Slot {
                req: None,
                latched: None,
            }; 3],
            active: None,
            local_busy: false,
            counts: DriveCounts::default(),
            against: Against::default(),
        }
    }

    /// Shares the record of motors seen moving against their command with the other
    /// origins of runs (the page's controller): what one saw, every one refuses.
    pub fn share_against(&mut self, against: Against) {
        self.against = against;
    }

    pub fn counts(&self) -> DriveCounts {
        self.counts
    }

    /// A command number from the streamer's counter, so every request the gateway
    /// sends is numbered from one sequence.
    pub fn next_cnt(&mut self) -> u8 {
        self.streamer.next_cnt()
    }

    /// Records a request; `life` is its Expire (`None` for never).
    pub fn request(
        &mut self,
        motor: Motor,
        target: i32,
        src: u16,
        life: Option<Duration>,
        now: Instant,
    ) {
        let hold = life.map_or(REQUEST_HOLD, |l| l.min(REQUEST_HOLD));
        let slot = self.slot(motor);
        if slot.latched.is_some_and(|t| t != target) {
            slot.latched = None;
        }
        slot.req = Some(MotorRequest {
            target,
            src,
            until: now + hold,
        });
    }

    pub fn running(&self) -> Option<(Motor, Direction)> {
        self.streamer.running_key()
    }

    /// The request held for `motor`.
    pub fn request_for(&self, motor: Motor) -> Option<MotorRequest> {
        self.slots[motor.index()].req
    }

    fn slot(&mut self, motor: Motor) -> &mut Slot {
        &mut self.slots[motor.index()]
    }

    pub fn next_deadline(&self) -> Option<Instant> {
        let reqs = self.slots.iter().filter_map(|s| s.req.map(|r| r.until));
        reqs.chain(self.streamer.next_deadline()).min()
    }

    /// Stops any run now (link error, shutdown).
    /// Whether the page's own keys run a motor: while they do, a network run stops
    /// (its target done with) and none starts.
    pub fn set_local_busy(&mut self, model: &mut Model, now: Instant, busy: bool) -> Vec<Packet> {
        self.local_busy = busy;
        if busy && self.active.is_some() {
            self.stop(model, now, StopReason::OtherKey)
        } else {
            Vec::new()
        }
    }

    /// A key at the page stops a network run, as any other key stops a keyed one.
    pub fn local_key(&mut self, model: &mut Model, now: Instant) -> Vec<Packet> {
        if self.active.is_some() {
            self.stop(model, now, StopReason::OtherKey)
        } else {
            Vec::new()
        }
    }

    pub fn stop(&mut self, model: &mut Model, now: Instant, reason: StopReason) -> Vec<Packet> {
        let out = self.streamer.stop(now, reason);
        if let Some(a) = self.active.take() {
            log_stop(model, now, a.motor, &reason.describe());
            self.slot(a.motor).latched = Some(a.target);
        }
        out
    }

    /// Expires requests, ends a run that must end, re-sends, and starts a waiting one.
    /// Call it at [`next_deadline`](Self::next_deadline) and after every packet applied
    /// to the model, so a reached target or a fault stops the motor at once.
    pub fn tick(&mut self, model: &mut Model, now: Instant) -> Vec<Packet> {
        let mut out = Vec::new();
        let running = self.active.as_ref().map(|a| a.motor);
        for motor in Motor::ALL {
            let local_busy = self.local_busy;
            let slot = self.slot(motor);
            let Some(r) = slot.req.filter(|r| now >= r.until) else {
                continue;
            };
            let served = slot.latched == Some(r.target) || running == Some(motor);
            slot.req = None;
            slot.latched = None;
            if !served {
                // Never dropped in silence: it waited for another run and ran out.
                self.counts.refused += 1;
                let why = if local_busy {
                    "the page's keys were running a motor"
                } else {
                    "another motor was running"
                };
                model.log(
                    now,
                    LogLevel::Warning,
                    format!(
                        "XFSp {:#06x}: {} request to {} refused: it expired while {why}",
                        r.src,
                        motor.name(),
                        r.target
                    ),
                );
            }
        }
        if let Some(mut a) = self.active.take() {
            // (reason, words for the log, whether this target is done with)
            let stop = match self.slot(a.motor).req {
                None => Some((
                    StopReason::Released,
                    "requests stopped or expired".into(),
                    true,
                )),
                // The new target starts below, from wherever the motor stopped.
                Some(r) if r.target != a.target => Some((
                    StopReason::Released,
                    "a new target was requested".into(),
                    false,
                )),
                Some(_) => match motor_check(model, a.motor, a.direction, now)
                    .and_then(|()| a.watch.check(model, now))
                {
                    Err(reason) => Some((reason, reason.describe(), true)),
                    Ok(()) => a.progress(model, now),
                },
            };
            match stop {
                Some((reason, why, done)) => {
                    if let Some(asked) = crate::control::against::asked(reason) {
                        self.against.record(a.motor, asked);
                    }
                    out.extend(self.streamer.stop(now, reason));
                    log_stop(model, now, a.motor, &why);
                    if done {
                        self.slot(a.motor).latched = Some(a.target);
                    }
                }
                None => self.active = Some(a),
            }
        }
        out.extend(self.streamer.tick(now));
        out.extend(self.probe_step(model, now));
        if let Some(a) = self
            .active
            .take_if(|_| self.streamer.running_key().is_none())
        {
            // The streamer ended the run itself (maximum run time, starved stream).
            let why = self
                .streamer
                .last_stop()
                .map_or_else(|| "stream ended".to_string(), |s| s.reason.describe());
            log_stop(model, now, a.motor, &why);
            self.slot(a.motor).latched = Some(a.target);
        }
        if self.active.is_none() {
            out.extend(self.start_next(model, now));
        }
        out
    }

    fn start_next(&mut self, model: &mut Model, now: Instant) -> Vec<Packet> {
        if self.local_busy {
            return Vec::new();
        }
        for motor in Motor::ALL {
            let slot = *self.slot(motor);
            let Some(req) = slot.req else { continue };
            if slot.latched == Some(req.target) {
                continue;
            }
            // Whatever happens next, this target has had its answer.
            self.slot(motor).latched = Some(req.target);
            let Some((axis, pos)) = position(model, motor, now) else {
                self.counts.refused += 1;
                model.log(
                    now,
                    LogLevel::Warning,
                    format!(
                        "XFSp {:#06x}: {} request refused: no live position or no endpoints configured",
                        req.src,
                        motor.name()
                    ),
                );
                continue;
            };
            let raw_target = axis.to_raw(req.target);
            let Some(direction) = axis
                .direction(motor, pos, raw_target)
                .filter(|&d| axis.remaining(motor, d, pos, raw_target) > STOP_MARGIN)
            else {
                self.counts.taken += 1;
                model.log(
                    now,
                    LogLevel::Info,
                    format!(
                        "XFSp {:#06x}: {} already at {}",
                        req.src,
                        motor.name(),
                        req.target
                    ),
                );
                continue;
            };
            // The page's own rule for a run that keeps to the endpoints: no start at
            // (or within a run's first unwatched travel of) the endpoint ahead, nor on
            // a position too old to keep it off it.
            let known = Known {
                way: None,
                confirmed: false,
                keep_ends: true,
            };
            let permit = run::permit(
                Origin::Xfsp,
                model,
                &self.against,
                motor,
                direction,
                known,
                now,
            );
            if let Err(why) = permit {
                self.counts.refused += 1;
                model.log(
                    now,
                    LogLevel::Warning,
                    format!(
                        "XFSp {:#06x}: {} request refused: {why}",
                        req.src,
                        motor.name()
                    ),
                );
                continue;
            }
            // A fresh press: forget any key the streamer still holds from a last run.
            let mut out = self.streamer.release(now);
            out.extend(self.streamer.press(now, motor, direction));
            if self.streamer.running_key() == Some((motor, direction)) {
                self.counts.taken += 1;
                self.slot(motor).latched = None;
                let probe = Probing::start(model, motor, direction, now).map(|(p, length)| {
                    out.extend(self.streamer.probe(now, length));
                    p
                });
                self.active = Some(Active {
                    motor,
                    direction,
                    target: req.target,
                    raw_target,
                    watch: Watch::new(motor, direction).from_start(model, now),
                    probe,
                });
                model.log(
                    now,
                    LogLevel::Info,
                    format!(
                        "XFSp {:#06x}: moving {} {} toward {} (raw {pos} -> {raw_target})",
                        req.src,
                        motor.name(),
                        direction.name(),
                        req.target
                    ),
                );
                if let Some(p) = probe {
                    model.log(now, LogLevel::Info, format!("XFSp: {}", p.words()));
                }
            } else {
                self.counts.refused += 1;
                model.log(
                    now,
                    LogLevel::Warning,
                    format!(
                        "XFSp {:#06x}: {} request refused: the motor stream did not start",
                        req.src,
                        motor.name()
                    ),
                );
            }
            return out;
        }
        Vec::new()
    }
}

impl MotorDrive {
    /// A probing run ([`endpoints::Probing::next`]), as the page's keys': on the
    /// commanded way it streams on; the other way it is stopped as moving against
    /// its command, recorded for every origin; not moved, another probe.
    fn probe_step(&mut self, model: &mut Model, now: Instant) -> Vec<Packet> {
        let Some(a) = self.active.as_mut() else {
            return Vec::new();
        };
        let Some(p) = a.probe else {
            return Vec::new();
        };
        match p.next(model, self.streamer.paused_since(), now) {
            ProbeNext::Wait => Vec::new(),
            ProbeNext::Again(length) => self.streamer.probe(now, length),
            ProbeNext::Go => {
                a.probe = None;
                self.streamer.resume(now)
            }
            ProbeNext::Against => {
                let reason = StopReason::MovedAgainst(p.direction);
                self.against.record(p.motor, p.direction);
                self.stop(model, now, reason)
            }
        }
    }
}

/// The live position of `motor` and its scale, if the unit reports both.
fn position(model: &Model, motor: Motor, now: Instant) -> Option<(Axis, u8)> {
    let ft = model.live_flap_trim(now)?;
    let axis = Axis::for_motor(motor, ft)?;
    Some((axis, endpoints::position(motor, ft)))
}

impl Active {
    /// Whether the run ends by its position against its target (the endpoints, the
    /// position's age and its way are the watch's): reached.
    fn progress(&mut self, model: &Model, now: Instant) -> Option<(StopReason, String, bool)> {
        // motor_check and the watch have already made sure the position is live.
        let (axis, pos) = position(model, self.motor, now)?;
        let remaining = axis.remaining(self.motor, self.direction, pos, self.raw_target);
        (remaining <= STOP_MARGIN)
            .then(|| (StopReason::Released, "target reached".to_string(), true))
    }
}

fn log_stop(model: &mut Model, now: Instant, motor: Motor, why: &str) {
    model.log(
        now,
        LogLevel::Info,
        format!("XFSp: {} stopped: {why}", motor.name()),
    );
}

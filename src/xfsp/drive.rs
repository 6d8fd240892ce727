//! FLAPREQ/PTRIMREQ/RTRIMREQ: drive a motor toward a requested position through
//! control's one entry for a motor run ([`Controller::start`], [`How::Target`]), on the
//! page's own stream, so the network gets exactly the safe 4 Hz stream, the permit,
//! the endpoint watch, the probes and the wrong-way rule the keys get.
//!
//! A request is held for the shorter of its Expire and [`REQUEST_HOLD`]; a requester
//! keeps a motor running only by repeating the request (we recommend 4 Hz): each
//! request renews the run's lease to its own end ([`Controller::renew_target`]), and
//! the stream's dead man ends the run when the requests stop
//! ([`StopReason::RequestsStopped`]). The run ends, with a stop message, on the first
//! of: the target reached ([`StopReason::TargetReached`]), the requests stopping, and
//! every end control gives any run (lost communication, a motor fault, the motor
//! disabled, flap-down inhibit, lost motor status, an endpoint, a stale position,
//! moving against its command, the run cap, a starved stream, a link error, quit).
//!
//! One stream on the link: a network request starts only while no other run goes on
//! (the page's keys, setup, the check or the remote), and waits for it; any of them
//! starting a run ends the network's, and any key at the page does too, as do the
//! terminal losing focus or becoming too small (every run ends then). A person at
//! the laptop or the wingtip comes before the network.
//!
//! After a run ends for any reason the target is *latched*: the same target does not
//! start the motor again, so a position that settles a count away from the target, or a
//! fault that clears, never makes the motor hunt or restart by itself. A different
//! target, or the requests stopping and starting again, is a new request.
//!
//! Every request gets an answer in the event log and in [`MotorDrive::counts`]: taken
//! (a run started, or the motor was already there) or refused (no live position or
//! scale, the permit refused it, or it expired waiting for another run to end).

use std::time::{Duration, Instant};

use crate::audit::Origin;
use crate::control::endpoints;
use crate::control::{Controller, Direction, How, StopReason, TARGET_MARGIN};
use crate::model::{LogLevel, Model, Motor};
use crate::protocol::message::Packet;

use super::scale::Travel;

/// How long a request is held without a repeat: one 1 Hz period plus 200 ms of jitter.
pub const REQUEST_HOLD: Duration = Duration::from_millis(1200);

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

/// The run this drive started, as it asked for it.
#[derive(Debug, Clone, Copy)]
struct Active {
    motor: Motor,
    direction: Direction,
    /// The request's target on the draft's scale, and in raw counts.
    target: i32,
    raw_target: u8,
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
    slots: [Slot; 3],
    active: Option<Active>,
    counts: DriveCounts,
}

impl Default for MotorDrive {
    fn default() -> Self {
        MotorDrive {
            slots: [Slot {
                req: None,
                latched: None,
            }; 3],
            active: None,
            counts: DriveCounts::default(),
        }
    }
}

impl MotorDrive {
    pub fn counts(&self) -> DriveCounts {
        self.counts
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

    /// The motor this drive's run moves, while the controller runs it.
    pub fn running(&self, ctl: &Controller) -> Option<Motor> {
        let a = self.active?;
        ctl.target_running()
            .filter(|t| (t.motor, t.direction, t.position) == (a.motor, a.direction, a.raw_target))
            .map(|t| t.motor)
    }

    /// The request held for `motor`.
    pub fn request_for(&self, motor: Motor) -> Option<MotorRequest> {
        self.slots[motor.index()].req
    }

    fn slot(&mut self, motor: Motor) -> &mut Slot {
        &mut self.slots[motor.index()]
    }

    /// When a held request runs out (the controller's own deadlines are its own).
    pub fn next_deadline(&self) -> Option<Instant> {
        self.slots
            .iter()
            .filter_map(|s| s.req.map(|r| r.until))
            .min()
    }

    /// Ends this drive's run, if the controller still runs it (shutdown).
    pub fn stop(
        &mut self,
        ctl: &mut Controller,
        model: &mut Model,
        now: Instant,
        reason: StopReason,
    ) -> Vec<Packet> {
        let out = match self.running(ctl) {
            Some(_) => ctl.stop_target(now, reason),
            None => Vec::new(),
        };
        if let Some(a) = self.active.take() {
            log_stop(model, now, a.motor, &reason.describe());
            self.slot(a.motor).latched = Some(a.target);
        }
        out
    }

    /// Expires requests, renews or ends this drive's run, and starts a waiting one.
    /// Call it at [`next_deadline`](Self::next_deadline) and after every packet
    /// applied to the model and every request heard. The controller's own checks
    /// (the target, the watch, the probes, the model) run in its tick, which the App
    /// calls on every pass; they run here too while this drive's run goes on, so the
    /// gateway's core is whole without the App.
    pub fn tick(&mut self, ctl: &mut Controller, model: &mut Model, now: Instant) -> Vec<Packet> {
        let mut out = Vec::new();
        if self.running(ctl).is_some() {
            out.extend(ctl.tick(model, now));
        }
        let running = self.running(ctl);
        let other = ctl.running().is_some() && running.is_none();
        // This drive's run, going on or ended just now by its own lease's lapse.
        let ours = self.active.map(|a| a.motor);
        for motor in Motor::ALL {
            let slot = self.slot(motor);
            let Some(r) = slot.req.filter(|r| now >= r.until) else {
                continue;
            };
            let served = slot.latched == Some(r.target) || ours == Some(motor);
            slot.req = None;
            slot.latched = None;
            if !served {
                // Never dropped in silence: it waited for another run and ran out.
                self.counts.refused += 1;
                let why = if other {
                    "another run (the page's keys, the check or the remote) was going on"
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
        if let Some(a) = self.active.take() {
            if running.is_some() {
                match self.slot(a.motor).req {
                    None => {
                        out.extend(ctl.stop_target(now, StopReason::RequestsStopped));
                        log_stop(model, now, a.motor, "requests stopped or expired");
                        self.slot(a.motor).latched = Some(a.target);
                    }
                    // The new target starts below, from wherever the motor stopped.
                    Some(r) if r.target != a.target => {
                        out.extend(ctl.stop_target(now, StopReason::Released));
                        log_stop(model, now, a.motor, "a new target was requested");
                    }
                    Some(r) => {
                        out.extend(ctl.renew_target(now, r.until.saturating_duration_since(now)));
                        self.active = Some(a);
                    }
                }
            } else {
                // The controller ended it: the target, the requests stopping, or any
                // end of a run.
                let why = ctl.last_stop().filter(|s| s.motor == a.motor).map_or_else(
                    || "its run ended".to_string(),
                    |s| match s.reason {
                        StopReason::RequestsStopped => "requests stopped or expired".into(),
                        r => r.describe(),
                    },
                );
                log_stop(model, now, a.motor, &why);
                self.slot(a.motor).latched = Some(a.target);
            }
        }
        if self.active.is_none() && ctl.running().is_none() {
            out.extend(self.start_next(ctl, model, now));
        }
        out
    }

    fn start_next(&mut self, ctl: &mut Controller, model: &mut Model, now: Instant) -> Vec<Packet> {
        for motor in Motor::ALL {
            let slot = *self.slot(motor);
            let Some(req) = slot.req else { continue };
            if slot.latched == Some(req.target) {
                continue;
            }
            // Whatever happens next, this target has had its answer.
            self.slot(motor).latched = Some(req.target);
            let Some((travel, pos)) = position(model, motor, now) else {
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
            let raw_target = travel.to_raw(req.target);
            let Some(direction) = travel
                .direction(motor, pos, raw_target)
                .filter(|&d| travel.remaining(motor, d, pos, raw_target) > TARGET_MARGIN)
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
            let how = How::Target {
                position: raw_target,
                lease: req.until.saturating_duration_since(now),
            };
            match ctl.start(Origin::Xfsp, model, motor, direction, how, now) {
                Err(why) => {
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
                }
                Ok(out) => {
                    self.counts.taken += 1;
                    self.slot(motor).latched = None;
                    self.active = Some(Active {
                        motor,
                        direction,
                        target: req.target,
                        raw_target,
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
                    if let Some(words) = ctl.probe_words() {
                        model.log(now, LogLevel::Info, format!("XFSp: {words}"));
                    }
                    return out;
                }
            }
        }
        Vec::new()
    }
}

/// The live position of `motor` and its scale, if the unit reports both.
fn position(model: &Model, motor: Motor, now: Instant) -> Option<(Travel, u8)> {
    let ft = model.live_flap_trim(now)?;
    let travel = Travel::for_motor(motor, ft)?;
    Some((travel, endpoints::position(motor, ft)))
}

fn log_stop(model: &mut Model, now: Instant, motor: Motor, why: &str) {
    model.log(
        now,
        LogLevel::Info,
        format!("XFSp: {} stopped: {why}", motor.name()),
    );
}

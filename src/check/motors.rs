//! Step 4, motors: flaps and each enabled trim run briefly one way, then the other,
//! through the controller's one entry for motor runs ([`Controller::start`]): the same
//! 4 Hz stream, permit, endpoint watch, probes and every stop cause as the page's keys. The position in FLAP_TRIM_STATUS (ICD Table 27)
//! before and after each run says whether it moved, and which way; then it is run
//! back to where it was.
//!
//! Which way the position should go comes from the endpoints FLAP_TRIM_STATUS
//! carries: flaps down, pitch trim down and roll trim right move toward the "down"
//! endpoint. Where the ICD is silent (endpoints not configured, both 0) the decision
//! is that those directions make the number grow, as the virtual VP-X does
//! ([`expected_way`]).
//!
//! The unit does not keep TRIM_MOVE/FLAP_MOVE to the endpoints (ICD Table 15 note 4,
//! Table 16 note 1), so the runs do, through the controller's one rule for keys and
//! check alike ([`crate::control::endpoints`]): a run ends at the endpoint it is moving
//! toward (or just before it would pass), with its stop on the wire, and on a position
//! gone stale. Here: the first run goes toward the side with more room; the second
//! run is no longer than the first run's rate says reaches its endpoint; a run with
//! no room (within [`endpoints::START_ROOM`] of its endpoint) is not made (it counts
//! as not moving, at its limit); a motor with no room either way is not run at all,
//! and its line says why. A run ended at its endpoint
//! that still moved is a pass; one that could not move for it "runs against a limit".
//! A run started near the endpoint behind it goes as probes until the motor shows its
//! way ([`endpoints::Probing`], the controller's): a motor found moving against its
//! command that way is stopped there and recorded, and refused to every origin after.
//!
//! [`Controller::start`]: crate::control::Controller::start

use std::time::{Duration, Instant};

use super::calls::Command;
use super::state::{CheckView, LeftBehind, MotorFinding, MotorResult, Outcome, Prompt};
use super::step::{Call, CallContext, Item, Next, StepRun, Stopped, motor_name, result_line};
use crate::audit::Origin;
use crate::control::endpoints::{
    self, Way, ends, expected_way, heads_for, opposite, position, room,
};
use crate::control::run::Refused;
use crate::control::{Direction, How, StopReason};
use crate::model::{Model, Motor, TrimKind};
use crate::protocol::message::FlapTrimStatus;

/// A run moved the motor if its position changed at least this many counts (the
/// same count the controller's watch needs before it takes a run to go the other way).
pub use crate::control::endpoints::MOVED;
/// Within this many counts of an endpoint (or the sensor's 0 / 255), the motor is at
/// that limit.
pub const AT_LIMIT: i32 = 3;
/// Put back when it ends within this many counts of where it was.
pub const BACK_WITHIN: i32 = 3;

pub(super) fn rows(view: &CheckView) -> Vec<MotorResult> {
    view.planned_motors
        .iter()
        .map(|(motor, _)| MotorResult {
            motor: *motor,
            positions: Vec::new(),
            outcome: Outcome::NotRun,
        })
        .collect()
}

/// The two directions a motor is run.
fn directions(motor: Motor) -> [Direction; 2] {
    match motor {
        Motor::Flaps | Motor::Trim(TrimKind::Pitch) => [Direction::Down, Direction::Up],
        Motor::Trim(TrimKind::Roll) => [Direction::Right, Direction::Left],
    }
}

/// Whether `pos` is at the limit `direction` runs toward: its endpoint, or the end of
/// the sensor's range.
pub fn at_limit(motor: Motor, direction: Direction, pos: u8, ft: &FlapTrimStatus) -> bool {
    let configured = room(motor, direction, pos, ft).is_some_and(|r| r <= AT_LIMIT);
    let pos = i32::from(pos);
    let sensor = match expected_way(motor, direction, ft) {
        Way::Grows => pos >= 255 - AT_LIMIT,
        Way::Shrinks => pos <= AT_LIMIT,
    };
    configured || sensor
}

/// The finding from the two runs: `moves[k]` is the change of position while running
/// `dirs[k]`, which started at `starts[k]`.
pub fn judge(
    motor: Motor,
    dirs: [Direction; 2],
    starts: [u8; 2],
    moves: [i32; 2],
    ft: &FlapTrimStatus,
) -> MotorFinding {
    judge_runs(motor, dirs, starts, moves, [None; 2], ft)
}

/// [`judge`], where `ended_at[k]` is the endpoint run `k` was stopped at (or was not
/// made for, having no room): a run stopped at the endpoint it heads for that did not
/// move ran against its limit; one stopped at the other endpoint went the wrong way
/// if its position did go that way, however little, before it was stopped (a run
/// that ended there having gone its own way is not called reversed).
pub fn judge_runs(
    motor: Motor,
    dirs: [Direction; 2],
    starts: [u8; 2],
    moves: [i32; 2],
    ended_at: [Option<u8>; 2],
    ft: &FlapTrimStatus,
) -> MotorFinding {
    let moved = moves.map(|m| m.abs() >= MOVED);
    let right = [0, 1].map(|k| Way::of(moves[k]) == Some(expected_way(motor, dirs[k], ft)));
    let own = [0, 1].map(|k| heads_for(motor, dirs[k], ft));
    let limited = [0, 1].map(|k| ended_at[k].is_some() && ended_at[k] == own[k]);
    let wrong = (0..2).any(|k| {
        !right[k] && (moved[k] || (moves[k] != 0 && ended_at[k].is_some() && ended_at[k] != own[k]))
    });
    if wrong {
        return MotorFinding::Reversed;
    }
    match moved {
        [true, true] => MotorFinding::Moves,
        [false, false] => MotorFinding::NoMovement,
        _ => {
            let still = if moved[0] { 1 } else { 0 };
            if limited[still] || at_limit(motor, dirs[still], starts[still], ft) {
                MotorFinding::AgainstLimit
            } else {
                MotorFinding::NoMovement
            }
        }
    }
}

/// Which of a motor's runs the item is at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Leg {
    /// The first test run, `dirs[0]`.
    First,
    /// The second test run, `dirs[1]`.
    Second,
    /// The test runs are over (or were skipped): it is run back to where it was, if
    /// it is not there.
    Back,
    /// The run back was started: no run follows it.
    RunningBack,
}

impl Leg {
    /// The test run's index into the item's per-run arrays, for the two test runs.
    fn test(self) -> Option<usize> {
        match self {
            Leg::First => Some(0),
            Leg::Second => Some(1),
            Leg::Back | Leg::RunningBack => None,
        }
    }
}

#[derive(Debug, Clone, Copy)]
enum Stage {
    /// Waiting for a live position to start from.
    Start,
    Running {
        since: Instant,
        length: Duration,
    },
    Settle {
        until: Instant,
    },
    /// A run was cut short (a key, focus, the terminal too small) after running
    /// `ran`: retry or skip.
    Paused {
        ran: Duration,
    },
}

/// The motor under test.
#[derive(Debug, Clone)]
pub(super) struct MotorItem {
    pub idx: usize,
    pub motor: Motor,
    dirs: [Direction; 2],
    p0: Option<u8>,
    leg: Leg,
    starts: [u8; 2],
    moves: [i32; 2],
    /// The endpoint each test run was stopped at, or had no room to be made for.
    ended_at: [Option<u8>; 2],
    /// How long each test run drove its motor: the whole run, or until it was cut
    /// short, less the pauses of its probes. With `moves` it gives the rate for the
    /// run back.
    ran: [Duration; 2],
    stage: Stage,
    run: Duration,
    settle: Duration,
    /// The item is done once back (or skipped while out).
    skipped: bool,
}

impl MotorItem {
    pub fn name(&self) -> String {
        motor_name(self.motor)
    }

    /// Where the check left it, if not where it found it.
    pub fn left_words(&self, model: &Model, now: Instant) -> Option<String> {
        let p0 = self.p0?;
        match model.live_flap_trim(now).map(|ft| position(self.motor, ft)) {
            Some(p) if (i32::from(p) - i32::from(p0)).abs() <= BACK_WITHIN => None,
            Some(p) => Some(format!(
                "stopped at position {p}, it was at {p0}: not run back"
            )),
            None if matches!(self.stage, Stage::Start) => None,
            None => Some(format!(
                "stopped; position unknown (no live FLAP_TRIM_STATUS), it was at {p0}"
            )),
        }
    }
}

impl Item for MotorItem {
    fn deadline(&self) -> Option<Instant> {
        match self.stage {
            Stage::Running { since, length } => Some(since + length + Duration::from_millis(50)),
            Stage::Settle { until } => Some(until),
            Stage::Start | Stage::Paused { .. } => None,
        }
    }

    fn under_test(&self) -> Vec<u8> {
        vec![self.motor.device_id()]
    }

    #[cfg(test)]
    fn stage(&self) -> &'static str {
        match &self.stage {
            Stage::Start => "start",
            Stage::Running { .. } if self.leg == Leg::RunningBack => "running back",
            Stage::Running { .. } => "running",
            Stage::Settle { .. } => "settle",
            Stage::Paused { .. } => "paused",
        }
    }
}

impl Motors {
    /// Runs the motor back toward where it was, once, if it is not there; else the
    /// next motor.
    fn run_back(&mut self, pos: u8, c: &mut Call) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        let idx = item.idx;
        let back = item.p0.map_or(0, |p0| i32::from(p0) - i32::from(pos));
        // The leg that moved most tells the rate and which way is which.
        let k = if item.moves[0].abs() >= item.moves[1].abs() {
            0
        } else {
            1
        };
        let (moved, dir, ran) = (item.moves[k], item.dirs[k], item.ran[k]);
        if item.leg == Leg::RunningBack
            || back.abs() <= BACK_WITHIN
            || moved.abs() < MOVED
            || ran.is_zero()
        {
            if back.abs() > BACK_WITHIN
                && let Some(p0) = item.p0
            {
                // Not back, and no run left that would bring it: say where it is.
                let motor = item.motor;
                not_back(c.view, idx, motor, pos, p0, c.cx);
            }
            return Next::From(idx + 1);
        }
        item.leg = Leg::RunningBack;
        let dir = if Way::of(back) == Way::of(moved) {
            dir
        } else {
            opposite(dir)
        };
        let ratio = back.abs() as f32 / moved.abs() as f32;
        let length = ran.mul_f32(ratio).min(item.run * 2);
        self.run(dir, length, Way::of(back), c)
    }

    /// Runs the motor `d` for `length`; `way` is which way the check expects the
    /// position to go when it knows better than the direction (the run back, after it
    /// saw the motor go), so the run keeps off the endpoint it will really reach.
    fn run(&mut self, d: Direction, length: Duration, way: Option<Way>, c: &mut Call) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        let now = c.cx.now;
        if let Some(ft) = c.cx.model.live_flap_trim(now)
            && let Some(k) = item.leg.test()
            && way.is_none()
        {
            let pos = position(item.motor, ft);
            item.starts[k] = pos;
            if room(item.motor, d, pos, ft).is_some_and(|r| r <= endpoints::START_ROOM) {
                // At (or past) the endpoint it heads for: this run is not made; it
                // counts as not moving, against its limit.
                item.ended_at[k] = heads_for(item.motor, d, ft);
                item.stage = Stage::Settle { until: now };
                return Next::Stay;
            }
        }
        let how = How::For { length, way };
        match c
            .cx
            .ctl
            .start(Origin::Check, c.cx.model, item.motor, d, how, now)
        {
            Ok(p) => {
                c.cx.out.packets.extend(p);
                if let Some(k) = item.leg.test() {
                    // As planned; the run's stop says how long it drove the motor.
                    item.ran[k] = length;
                }
                item.stage = Stage::Running { since: now, length };
            }
            Err(why) => {
                let idx = item.idx;
                match why.reason {
                    Refused::Unseen(unseen) => {
                        // Nobody can see the page: nothing moves until the person is
                        // back and asks (r), as after a run the same cause cut short.
                        let why = format!(
                            "the {} did not start: {}; nothing moves while the page cannot \
                             be seen",
                            item.motor.name(),
                            unseen.describe()
                        );
                        return self.pause(&why, c.view, c.cx);
                    }
                    // Seen moving against its command (by this check's first run, or
                    // before it): no test run is made until the person confirms one at
                    // the page's keys; the finding is that, and the run back goes the
                    // way it was seen to go.
                    Refused::Against(asked) if item.leg.test().is_some() => {
                        if c.view.motors[idx].outcome == Outcome::NotRun {
                            if item.leg == Leg::First {
                                c.cx.out.progress.push(format!(
                                    "  {}: not run",
                                    crate::control::against::words(item.motor, asked)
                                ));
                            }
                            record(c.view, idx, MotorFinding::Reversed, c.cx);
                        }
                        item.leg = Leg::Back;
                        return match c
                            .cx
                            .model
                            .live_flap_trim(now)
                            .map(|ft| position(item.motor, ft))
                        {
                            Some(pos) => self.run_back(pos, c),
                            None => Next::From(idx + 1),
                        };
                    }
                    Refused::Model(StopReason::MotorFault(code)) => {
                        c.shared.known_faults.insert(item.motor.device_id());
                        record(c.view, idx, MotorFinding::Faulted(code), c.cx);
                    }
                    Refused::Model(StopReason::CommLost) => {
                        c.shared.trouble_ahead = Some("COMMUNICATION LOST".into());
                        return Next::Stay;
                    }
                    // No position to go by (none fresh enough to keep it off its
                    // endpoint, or none at all): it waits, as a run cut short does,
                    // for the person to try again or skip it (which runs it back).
                    Refused::Model(StopReason::MotorStatusLost) | Refused::PositionStale => {
                        return self.pause(&why.words, c.view, c.cx);
                    }
                    _ if c.view.motors[idx].outcome == Outcome::NotRun => {
                        c.view.motors[idx].outcome = Outcome::Skipped(why.words.clone());
                        c.cx.out.progress.push(format!(
                            "– {}: {}",
                            motor_name(item.motor),
                            why.words
                        ));
                    }
                    _ => {}
                }
                // A run back that could not be made leaves it where it is: said so.
                let pos =
                    c.cx.model
                        .live_flap_trim(now)
                        .map(|ft| position(item.motor, ft));
                if item.leg == Leg::RunningBack
                    && let (Some(p0), Some(pos)) = (item.p0, pos)
                    && (i32::from(p0) - i32::from(pos)).abs() > BACK_WITHIN
                {
                    let motor = item.motor;
                    c.cx.out.progress.push(format!(
                        "  {}: not run back: {}",
                        motor_name(motor),
                        why.words
                    ));
                    not_back(c.view, idx, motor, pos, p0, c.cx);
                }
                return Next::From(idx + 1);
            }
        }
        Next::Stay
    }

    /// The motor under test waits for the person: `why` (a sentence without its
    /// full stop), then retry or skip.
    fn pause(&mut self, why: &str, view: &mut CheckView, cx: &mut CallContext) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        if !matches!(item.stage, Stage::Paused { .. }) {
            item.stage = Stage::Paused {
                ran: Duration::ZERO,
            };
        }
        let mut c = why.chars();
        let why = c
            .next()
            .map(|f| f.to_uppercase().collect::<String>() + c.as_str())
            .unwrap_or_default();
        view.prompt = Some(Prompt {
            todo: format!("{why}. r: run the test again; s: skip it."),
            watching: format!("the {} position", item.motor.name()),
            time_left: None,
            keys: vec![("r", "retry"), ("s", "skip"), ("Esc", "stop")],
        });
        cx.out.progress.push(format!("  {why}"));
        Next::Stay
    }
}

fn running_prompt(motor: Motor) -> Prompt {
    Prompt {
        todo: format!(
            "Running the {} briefly each way, then back: keep clear of it.",
            motor.name()
        ),
        watching: format!("the {} position (FLAP_TRIM_STATUS)", motor.name()),
        time_left: None,
        keys: vec![("s", "skip"), ("S", "skip step"), ("Esc", "stop")],
    }
}

/// The motor ends its item away from where the check found it: said in the result_line, and
/// in the result when it was skipped (a finding keeps its words; its positions show
/// where it ended).
fn not_back(view: &mut CheckView, idx: usize, motor: Motor, pos: u8, p0: u8, cx: &mut CallContext) {
    let words = format!("stopped at position {pos}, it was at {p0}: not run back");
    cx.out
        .progress
        .push(format!("  {}: {words}", motor_name(motor)));
    let row = &mut view.motors[idx];
    if row.positions.last() != Some(&pos) {
        row.positions.push(pos);
    }
    if let Outcome::Skipped(why) = &mut row.outcome
        && !why.contains("not run back")
    {
        *why = format!("{why}; {words}");
    }
    view.message = Some(format!("{}: {words}", motor_name(motor)));
}

fn record(view: &mut CheckView, idx: usize, f: MotorFinding, cx: &mut CallContext) {
    let row = &mut view.motors[idx];
    let what = motor_name(row.motor);
    let words = f.words();
    cx.out.progress.push(result_line(f.mark(), &what, &words));
    view.message = Some(format!("{what}: {words}"));
    row.outcome = Outcome::Found(f);
}

/// Step 4: the motors, one at a time.
#[derive(Debug, Default)]
pub(super) struct Motors {
    item: Option<MotorItem>,
}

impl StepRun for Motors {
    fn start(&mut self, idx: usize, c: &mut Call) -> Next {
        let motor = c.view.motors[idx].motor;
        c.view.motors[idx].positions.clear();
        c.view.prompt = Some(running_prompt(motor));
        self.item = Some(MotorItem {
            idx,
            motor,
            dirs: directions(motor),
            p0: None,
            leg: Leg::First,
            starts: [0; 2],
            moves: [0; 2],
            ended_at: [None; 2],
            ran: [Duration::ZERO; 2],
            stage: Stage::Start,
            run: c.shared.timing.motor_run,
            settle: c.shared.timing.motor_settle,
            skipped: false,
        });
        self.tick(c)
    }

    fn tick(&mut self, c: &mut Call) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        let now = c.cx.now;
        let Some(ft) = c.cx.model.live_flap_trim(now).copied() else {
            return Next::Stay;
        };
        let pos = position(item.motor, &ft);
        match item.stage {
            Stage::Paused { .. } => {}
            Stage::Start => {
                item.p0 = Some(pos);
                c.view.motors[item.idx].positions.push(pos);
                let [a, b] = directions(item.motor);
                item.dirs = match (room(item.motor, a, pos, &ft), room(item.motor, b, pos, &ft)) {
                    // No room to show a movement either way: not run.
                    (Some(ra), Some(rb)) if ra.max(rb) <= endpoints::START_ROOM => {
                        let e = ends(item.motor, &ft).expect("rooms come from endpoints");
                        let why = format!(
                            "not run: no room to move it either way (position {pos}, {} \
                             endpoint {}, {} endpoint {})",
                            b.name(),
                            e.up,
                            a.name(),
                            e.down
                        );
                        let (idx, motor) = (item.idx, item.motor);
                        c.cx.out
                            .progress
                            .push(format!("– {}: {why}", motor_name(motor)));
                        c.view.motors[idx].outcome = Outcome::Skipped(why);
                        return Next::From(idx + 1);
                    }
                    // Toward the side with more room first.
                    (Some(ra), Some(rb)) if rb > ra => [b, a],
                    (Some(_), Some(_)) => [a, b],
                    // No endpoints: away from the nearer end of the sensor first.
                    _ if at_limit(item.motor, a, pos, &ft) => [b, a],
                    _ => [a, b],
                };
                let d = item.dirs[0];
                let length = item.run;
                return self.run(d, length, None, c);
            }
            Stage::Running { since, .. } => {
                if c.cx.ctl.running().is_some_and(|r| r.motor == item.motor) {
                    return Next::Stay;
                }
                let stop =
                    c.cx.ctl
                        .last_stop()
                        .filter(|s| s.at >= since && s.motor == item.motor)
                        .map(|s| (s.reason, s.at, s.driven));
                let stopped_at = stop.map_or(now, |(_, at, _)| at);
                if let (Some(k), Some((_, _, driven))) = (item.leg.test(), stop) {
                    item.ran[k] = driven;
                }
                match stop.map(|(r, _, _)| r) {
                    Some(StopReason::RunDone) | None => {
                        item.stage = Stage::Settle {
                            until: now + item.settle,
                        };
                    }
                    // Stopped at its endpoint by the controller: the run is over, for
                    // as far as it went.
                    Some(StopReason::AtEndpoint(end)) => {
                        if let Some(k) = item.leg.test() {
                            item.ended_at[k] = Some(end);
                        }
                        c.cx.out.progress.push(format!(
                            "  {} stopped at its endpoint ({end}), position {pos}",
                            motor_name(item.motor)
                        ));
                        item.stage = Stage::Settle {
                            until: now + item.settle,
                        };
                    }
                    // Moved against its command: stopped by the controller, the
                    // run over where it went (the other direction's endpoint is
                    // where it was really heading), which the finding will say.
                    Some(StopReason::MovedAgainst(asked)) => {
                        if let Some(k) = item.leg.test() {
                            item.ended_at[k] = heads_for(item.motor, opposite(asked), &ft);
                        }
                        c.cx.out.progress.push(format!(
                            "  {}, position {pos}",
                            crate::control::against::stopped(item.motor, asked)
                        ));
                        item.stage = Stage::Settle {
                            until: now + item.settle,
                        };
                    }
                    Some(StopReason::MotorFault(code)) => {
                        let code = if code.is_fault() {
                            code
                        } else {
                            item.motor.fault(&ft)
                        };
                        c.shared.known_faults.insert(item.motor.device_id());
                        let idx = item.idx;
                        record(c.view, idx, MotorFinding::Faulted(code), c.cx);
                        return Next::From(idx + 1);
                    }
                    Some(
                        r @ (StopReason::CommLost
                        | StopReason::LinkError
                        | StopReason::Panic
                        | StopReason::Quit
                        | StopReason::MotorStatusLost
                        | StopReason::PageStalled
                        | StopReason::Starved),
                    ) => {
                        c.shared.trouble_ahead = Some(format!(
                            "the {} stopped: {}",
                            item.motor.name(),
                            r.describe()
                        ));
                    }
                    Some(r) => {
                        item.stage = Stage::Paused {
                            ran: stopped_at.saturating_duration_since(since),
                        };
                        let why = format!("The {} stopped: {}", item.motor.name(), r.describe());
                        return self.pause(&why, c.view, c.cx);
                    }
                }
            }
            Stage::Settle { until } => {
                if now < until {
                    return Next::Stay;
                }
                c.view.motors[item.idx].positions.push(pos);
                if let Some(k) = item.leg.test() {
                    item.moves[k] = i32::from(pos) - i32::from(item.starts[k]);
                    item.leg = if k == 0 { Leg::Second } else { Leg::Back };
                }
                if item.leg == Leg::Second {
                    let d = item.dirs[1];
                    // No longer than the first run's rate says reaches its endpoint.
                    let rate = item.moves[0].abs() as f32 / item.ran[0].as_secs_f32().max(1e-3);
                    let length = match room(item.motor, d, pos, &ft) {
                        Some(r) if item.moves[0].abs() >= MOVED && r > 0 => {
                            item.run.min(Duration::from_secs_f32(r as f32 / rate))
                        }
                        _ => item.run,
                    };
                    return self.run(d, length, None, c);
                }
                let idx = item.idx;
                if item.leg == Leg::Back
                    && c.view.motors[idx].outcome == Outcome::NotRun
                    && !item.skipped
                {
                    let f = judge_runs(
                        item.motor,
                        item.dirs,
                        item.starts,
                        item.moves,
                        item.ended_at,
                        &ft,
                    );
                    record(c.view, idx, f, c.cx);
                }
                return self.run_back(pos, c);
            }
        }
        Next::Stay
    }

    fn command(&mut self, cmd: Command, c: &mut Call) -> Next {
        let Some(item) = &mut self.item else {
            return Next::Stay;
        };
        let idx = item.idx;
        match cmd {
            Command::SkipItem => {
                c.cx.stop_run(StopReason::OtherKey);
                if c.view.motors[idx].outcome == Outcome::NotRun {
                    c.view.motors[idx].outcome = Outcome::Skipped("you skipped it".into());
                    c.cx.out
                        .progress
                        .push(format!("– {}: skipped", motor_name(item.motor)));
                }
                item.skipped = true;
                let pos =
                    c.cx.model
                        .live_flap_trim(c.cx.now)
                        .map(|ft| position(item.motor, ft));
                // A test run cut short by this skip (or paused before it) counts
                // for as far as it went, so the run back knows the way and the rate.
                if let Some(pos) = pos
                    && let Some(k) = item.leg.test()
                {
                    let ran = match item.stage {
                        Stage::Running { since, length } => {
                            c.cx.now.saturating_duration_since(since).min(length)
                        }
                        Stage::Paused { ran } => ran,
                        Stage::Settle { .. } => item.run,
                        Stage::Start => Duration::ZERO,
                    };
                    item.moves[k] = i32::from(pos) - i32::from(item.starts[k]);
                    item.ran[k] = ran;
                }
                // Run it back first if it moved.
                match pos {
                    Some(pos) if item.p0.is_some() && item.leg != Leg::RunningBack => {
                        item.leg = Leg::Back;
                        self.run_back(pos, c)
                    }
                    Some(pos) if let Some(p0) = item.p0 => {
                        // Skipped during the run back: it stays where it is.
                        if (i32::from(p0) - i32::from(pos)).abs() > BACK_WITHIN {
                            let motor = item.motor;
                            not_back(c.view, idx, motor, pos, p0, c.cx);
                        }
                        Next::From(idx + 1)
                    }
                    _ => Next::From(idx + 1),
                }
            }
            Command::Retry if matches!(item.stage, Stage::Paused { .. }) => {
                // The same item again, from where it paused: where it started (p0),
                // the first direction and a run already measured are kept, so the
                // run back still goes to where the check found it.
                c.view.prompt = Some(running_prompt(item.motor));
                if let Some(k) = item.leg.test() {
                    let (d, length) = (item.dirs[k], item.run);
                    self.run(d, length, None, c)
                } else {
                    let pos =
                        c.cx.model
                            .live_flap_trim(c.cx.now)
                            .map(|ft| position(item.motor, ft));
                    item.leg = Leg::Back;
                    match pos {
                        Some(pos) => self.run_back(pos, c),
                        None => Next::From(idx + 1),
                    }
                }
            }
            _ => Next::Stay,
        }
    }

    /// Stopped here for the check's own reason, unless stopped already (by the flow,
    /// or the controller's own tick, whose reason stands); says where it stopped if
    /// it had moved.
    fn stop(&mut self, reason: StopReason, _view: &CheckView, cx: &mut CallContext) -> Stopped {
        let Some(item) = &self.item else {
            return Stopped::default();
        };
        cx.stop_run(reason);
        Stopped {
            powered: None,
            left: item
                .left_words(cx.model, cx.now)
                .map(|words| LeftBehind::new(item.motor.device_id(), item.name(), words)),
        }
    }

    fn item(&self) -> Option<&dyn Item> {
        self.item.as_ref().map(|i| i as &dyn Item)
    }
}

//! Keys become commands, and held motor keys become safe TRIM_MOVE/FLAP_MOVE streams.
//!
//! - [`keymap`]: a crossterm key event and the selection → an [`Action`].
//! - [`commands`]: an action and the model → a message, or a refusal in words.
//! - [`streamer`]: the 4 Hz move stream with its dead man (see its docs for every way
//!   a run ends).
//! - [`run`]: the one permit for a motor run and its refusal (a reason, and words for
//!   where it was asked from); [`Controller::start`] is the one entry for every run.
//!
//! [`Controller`] ties them together for the app's main loop. Nothing here reads a
//! clock, sleeps, spawns or does I/O: the loop passes `now`, sends the packets it gets
//! back on the link, and sleeps until [`Controller::next_deadline`] (or the next key,
//! or the next received packet). Its duties, each of which the streamer's safety
//! depends on:
//!
//! - call [`Controller::tick`] at `next_deadline()` and after applying received
//!   packets to the model (so a motor fault stops the run as soon as it is heard);
//! - call [`Controller::stop`] with its [`StopReason`] when a write fails
//!   (`LinkError`) and before leaving (`Quit`), and [`Controller::on_focus_lost`] on
//!   `Event::FocusLost`;
//! - install a panic hook and a drop guard that write
//!   [`MotorStreamer::emergency_stop_packets`].

pub mod against;
pub mod commands;
pub mod endpoints;
pub mod keymap;
pub mod release;
pub mod run;
pub mod run_state;
pub mod streamer;

use std::time::{Duration, Instant};

use crossterm::event::KeyEvent;

use self::endpoints::Way;
use self::run::{Known, MotorRefusal, Refused};
use self::run_state::{MotorRun, ReleaseMode, RepeatTiming};
use crate::audit::Origin;
use crate::model::{Model, Motor};
use crate::protocol::message::Packet;

pub use against::Against;
pub use commands::{Refusal, command, device_power, motor_check, put_back_off, reset, switchable};
pub use keymap::{Action, KeyContext, KeyPhase, Selected};
pub use release::release_mode_here;
pub use streamer::{
    Direction, MAX_WIRE_INTERVAL, MotorStreamer, RESEND_PERIOD, StopReason, StopRecord,
    StreamerConfig,
};

/// What a key did.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Handled {
    /// To send on the link, in order.
    pub packets: Vec<Packet>,
    /// The action for the app to carry out (selection, sort, overlays, views, quit).
    /// Commands and motor keys are already handled here and come back only for the
    /// app's log; a key that only stopped a running motor comes back as `None`.
    pub action: Option<Action>,
    /// A short message for the person: a refusal, or why a motor stopped.
    pub notice: Option<String>,
}

#[derive(Debug, Clone)]
pub struct Controller {
    streamer: MotorStreamer,
    /// A stop the person did not ask for, kept until the app takes it for the notice.
    pending_notice: Option<String>,
    /// Why no motor may run at all (the page cannot stream one safely), in words.
    motors_refused: Option<String>,
    /// The running motor's watch over its endpoints and its way ([`endpoints`],
    /// [`against`]); `None` with no run.
    watch: Option<endpoints::Watch>,
    /// The motors seen moving against their command, shared with every other origin
    /// of runs ([`Controller::against`]).
    against: Against,
    /// A key's run refused for a motor seen moving against its command: the same key
    /// pressed again before [`against::CONFIRM_WITHIN`] runs it.
    confirm: Option<(Motor, Direction, Instant)>,
    /// A run going as probes until its motor shows its way
    /// ([`Controller::probe_step`]).
    probe: Option<endpoints::Probing>,
    /// The terminal is too small to show the page ([`Controller::set_page_hidden`]).
    hidden: bool,
    /// The terminal lost focus and has not said it has it back.
    unfocused: bool,
    /// `r` was refused for this circuit at this moment because it faulted again after
    /// a reset: `Y` as the next key, within [`CONFIRM_RESET_WITHIN`], sends the reset
    /// all the same.
    reset_asked: Option<(u8, Instant)>,
    /// The remote's leased run ([`Controller::lease`]) as it was started, and one
    /// that ended without the remote's stop: its renewals are refused until the
    /// remote lets go.
    remote_run: Option<(Motor, Direction)>,
    lease_ended: Option<(Motor, Direction, StopReason)>,
    /// The network's run to a position ([`How::Target`]) as it was started.
    target: Option<TargetRun>,
}

/// A run to a position asked over the network ([`How::Target`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TargetRun {
    pub motor: Motor,
    pub direction: Direction,
    /// The target, in raw counts of FLAP_TRIM_STATUS.
    pub position: u8,
    /// Where it started, in raw counts: the target lies the way from here that the
    /// run is driven, whichever way the sensor counts.
    from: u8,
}

impl TargetRun {
    /// Raw counts still to go to the target: zero or less once there or past it.
    fn remaining(&self, position: u8) -> i32 {
        Way::of(i32::from(self.position) - i32::from(self.from)).map_or(0, |way| {
            way.along(i32::from(self.position) - i32::from(position))
        })
    }
}

/// Raw counts short of its target at which a run to a position ([`How::Target`])
/// ends: the 10 Hz position reports lag the motor, so stopping a count early lands
/// on the target, not past it.
pub const TARGET_MARGIN: i32 = 1;

/// How a motor run lasts ([`Controller::start`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum How {
    /// While its key is held: a fresh press at the page (the device list's keys,
    /// setup's endpoint capture), ended by the streamer's dead man.
    Press,
    /// For `length`, with no key behind it (the installation check). `way`: the way
    /// the caller saw this motor move (the check running back what it moved), which
    /// the run keeps to.
    For { length: Duration, way: Option<Way> },
    /// While the remote renews it ([`LEASE`]).
    Lease,
    /// To a position asked over the network (XFSp's FLAPREQ, PTRIMREQ, RTRIMREQ):
    /// toward raw `position`, ending there ([`StopReason::TargetReached`]), for as
    /// long as the requests renew it ([`Controller::renew_target`]) within `lease`
    /// ([`StopReason::RequestsStopped`]). It starts only when no other run is going
    /// on, and any run another origin starts ends it: a person at the keys, the
    /// remote or the check comes before the network.
    Target { position: u8, lease: Duration },
}

/// The walk-around remote's lease: a run lives this long past its last renewal.
pub const LEASE: Duration = Duration::from_millis(300);

/// How long after `r` was refused a second reset may be confirmed with `Y`: long
/// enough to read the notice, short enough that a `Y` much later is not taken for it.
pub const CONFIRM_RESET_WITHIN: Duration = Duration::from_secs(10);

/// The notice for a `Y` with nothing to confirm.
pub const NOTHING_TO_CONFIRM: &str =
    "Y confirms a second reset only right after r refused it for the selected device";

impl Controller {
    pub fn new(config: StreamerConfig) -> Self {
        Controller {
            streamer: MotorStreamer::new(config),
            pending_notice: None,
            motors_refused: None,
            watch: None,
            against: Against::default(),
            confirm: None,
            probe: None,
            hidden: false,
            unfocused: false,
            reset_asked: None,
            remote_run: None,
            lease_ended: None,
            target: None,
        }
    }

    /// The record of motors seen moving against their command: hand it to every
    /// other origin of runs (the XFSp gateway), so each refuses what one saw.
    pub fn against(&self) -> Against {
        self.against.clone()
    }

    /// Why the person cannot see the page now, if they cannot: the terminal too small
    /// for it, or not focused. A run stops the moment it happens; and while it lasts,
    /// a run with no key behind it ([`How::For`], the installation check's)
    /// is refused, since nobody is watching what it would move. A key's run needs a
    /// key, which an unseen page ignores ([`Controller::handle_key_hidden`]) or an
    /// unfocused terminal does not send.
    pub fn unseen(&self) -> Option<StopReason> {
        if self.hidden {
            Some(StopReason::PageHidden)
        } else if self.unfocused {
            Some(StopReason::FocusLost)
        } else {
            None
        }
    }

    /// Whether the terminal is too small to show the page.
    pub fn page_hidden(&self) -> bool {
        self.hidden
    }

    /// The page fits the terminal (`false`) or not (`true`): hidden, a running motor
    /// stops, with its stop message.
    pub fn set_page_hidden(&mut self, now: Instant, hidden: bool) -> Vec<Packet> {
        self.hidden = hidden;
        if hidden {
            self.stop(now, StopReason::PageHidden)
        } else {
            Vec::new()
        }
    }

    /// From now on every motor press is refused with `why` (shown at once as a
    /// notice too): for a page that cannot keep a move stream going on its own
    /// clock. Called before any run can start.
    pub fn refuse_motors(&mut self, why: String) {
        self.pending_notice = Some(why.clone());
        self.motors_refused = Some(why);
    }

    /// Why motor runs are refused, if they are.
    pub fn motors_refused(&self) -> Option<&str> {
        self.motors_refused.as_deref()
    }

    pub fn release_mode(&self) -> ReleaseMode {
        self.streamer.release_mode()
    }

    pub fn streamer(&self) -> &MotorStreamer {
        &self.streamer
    }

    /// The auto-repeat timing in use, for the screen.
    pub fn repeat_timing(&self) -> RepeatTiming {
        self.streamer.repeat_timing()
    }

    /// A command number for the app's own requests (queries at connect), from the
    /// same counter as the commands sent here.
    pub fn next_cnt(&mut self) -> u8 {
        self.streamer.next_cnt()
    }

    pub fn handle_key(
        &mut self,
        key: KeyEvent,
        ctx: &KeyContext,
        model: &Model,
        now: Instant,
    ) -> Handled {
        // The model's verdict comes first (the streamer applies its own timeouts on
        // every call): a key must not keep alive a run that already had to end. No
        // resend here: a move just before this key's stop would be noise.
        let mut out = Handled {
            packets: self.check_model(model, now),
            ..Handled::default()
        };
        out.notice = self.take_notice();
        self.handle_mapped(keymap::map(&key, ctx), ctx, model, now, &mut out);
        out
    }

    /// The one entry for a motor run, from every origin: the keys (`Key`, and
    /// `Setup` for the setup screens' endpoint capture, which runs past endpoints),
    /// the installation check (`Check`), the walk-around remote (`Remote`, through
    /// [`Controller::lease`]), the XFSp gateway (`Xfsp`, [`How::Target`]). In one
    /// place:
    /// - the permit: motors refused this session, a page nobody sees (for a run with
    ///   no key behind it), then [`run::permit`] (the model's checks, the endpoint
    ///   ahead, a motor seen moving against its command: a key's run confirmed by its
    ///   key pressed again, [`against`]);
    /// - the stream ([`MotorStreamer`]) as `how` says;
    /// - the endpoint watch ([`endpoints::Watch`]);
    /// - near the endpoint behind it with its way not known, probes first
    ///   ([`endpoints::Probing`], [`Controller::probe_step`]);
    /// - the wrong-way stop and its record ([`Controller::end_run`]), which refuses the
    ///   motor to every origin afterwards.
    ///
    /// Returns what to send; [`Controller::probe_words`] says whether it started as a
    /// probe.
    pub fn start(
        &mut self,
        origin: Origin,
        model: &Model,
        motor: Motor,
        direction: Direction,
        how: How,
        now: Instant,
    ) -> Result<Vec<Packet>, MotorRefusal> {
        if let Some(why) = &self.motors_refused {
            return Err(MotorRefusal {
                motor,
                direction,
                reason: Refused::MotorsOff,
                words: why.clone(),
            });
        }
        // A run with no key behind it is refused while nobody can see the page; a
        // key's needs a key, which an unseen page ignores; the remote's person is at
        // the wingtip, watching the motor itself.
        if let How::For { .. } = how
            && let Some(unseen) = self.unseen()
        {
            return Err(MotorRefusal::new(
                origin,
                motor,
                direction,
                Refused::Unseen(unseen),
            ));
        }
        if let How::Target { .. } = how
            && self.streamer.running_key().is_some()
        {
            return Err(MotorRefusal::new(origin, motor, direction, Refused::Busy));
        }
        let keys = matches!(origin, Origin::Key | Origin::Setup);
        let confirmed = keys
            && self.against.seen(motor).is_some()
            && self.confirm.take().is_some_and(|(m, d, at)| {
                (m, d) == (motor, direction)
                    && now.saturating_duration_since(at) <= against::CONFIRM_WITHIN
            });
        let known = Known {
            way: match how {
                How::For { way, .. } => way,
                How::Press | How::Lease | How::Target { .. } => None,
            },
            confirmed,
            keep_ends: origin != Origin::Setup,
        };
        let way = match run::permit(origin, model, &self.against, motor, direction, known, now) {
            Ok(way) => way,
            Err(why) => {
                if keys && let Refused::Against(_) = why.reason {
                    self.confirm = Some((motor, direction, now));
                }
                return Err(why);
            }
        };
        let mut out = match how {
            How::Press => self.streamer.press(now, motor, direction),
            How::For { length, .. } => self.streamer.run_for(now, motor, direction, length),
            How::Lease => self.streamer.lease(now, motor, direction, LEASE),
            How::Target { lease, .. } => {
                self.settle_remote();
                self.streamer.lease_ending(
                    now,
                    motor,
                    direction,
                    lease,
                    StopReason::RequestsStopped,
                )
            }
        };
        if self.streamer.running_key() != Some((motor, direction)) {
            return Err(MotorRefusal::new(
                origin,
                motor,
                direction,
                Refused::NotStarted,
            ));
        }
        let watch = match (known.keep_ends, way) {
            (false, _) => endpoints::Watch::capture(motor, direction, way),
            (true, Some(w)) => endpoints::Watch::moving(motor, direction, w),
            (true, None) => endpoints::Watch::new(motor, direction),
        };
        self.watch = Some(watch.from_start(model, now));
        self.probe = None;
        self.target = match how {
            How::Target { position, .. } => model.flap_trim.as_ref().map(|st| TargetRun {
                motor,
                direction,
                position,
                from: endpoints::position(motor, &st.value),
            }),
            _ => None,
        };
        if known.keep_ends
            && way.is_none()
            && let Some((probing, length)) = endpoints::Probing::start(model, motor, direction, now)
        {
            out.extend(self.streamer.probe(now, length));
            self.probe = Some(probing);
        }
        Ok(out)
    }

    /// The words while the run going on probes its way ("pitch trim near its down
    /// endpoint: trying a short run first").
    pub fn probe_words(&self) -> Option<String> {
        self.probe.map(|p| p.words())
    }

    /// A probing run, once its probe stopped and a position came after the stop
    /// ([`endpoints::Probing::next`]): gone the commanded way, it streams on as any
    /// run; gone the other way, it is stopped as moving against its command (with
    /// the words of [`against`] and its record); not moved, another probe, for as
    /// long as the run lasts.
    fn probe_step(&mut self, model: &Model, now: Instant) -> Vec<Packet> {
        let Some(p) = self.probe else {
            return Vec::new();
        };
        if self.streamer.running_key() != Some((p.motor, p.direction)) {
            self.probe = None;
            return Vec::new();
        }
        match p.next(model, self.streamer.paused_since(), now) {
            endpoints::ProbeNext::Wait => Vec::new(),
            endpoints::ProbeNext::Again(length) => self.streamer.probe(now, length),
            endpoints::ProbeNext::Go => {
                self.probe = None;
                self.streamer.resume(now)
            }
            endpoints::ProbeNext::Against => {
                self.probe = None;
                self.end_run(now, StopReason::MovedAgainst(p.direction))
            }
        }
    }

    /// Ends the run going on for `reason` the page found (the model, the watch, a
    /// probe); a run that moved against its command is recorded, so every origin
    /// refuses its motor from then on ([`against`]).
    fn end_run(&mut self, now: Instant, reason: StopReason) -> Vec<Packet> {
        if let (Some((motor, _)), Some(asked)) =
            (self.streamer.running_key(), against::asked(reason))
        {
            self.against.record(motor, asked);
        }
        self.stop(now, reason)
    }

    fn handle_mapped(
        &mut self,
        action: Option<Action>,
        ctx: &KeyContext,
        model: &Model,
        now: Instant,
        out: &mut Handled,
    ) {
        // A second reset is confirmed by the very next key, or not at all (a key's
        // release report is not a key).
        let reset_asked = match action {
            Some(Action::KeyReleased) => self.reset_asked,
            _ => self.reset_asked.take(),
        };
        if self.target_running().is_some() {
            // A person at the keys comes before the network: any key, a motor key
            // of the very run too, ends a run the network asked for.
            out.packets
                .extend(self.streamer.stop(now, StopReason::OtherKey));
            out.notice = self.stopped_notice();
            match action {
                // Held on, its repeats do not start a run of their own: the person
                // presses again for that, as after any stop.
                Some(Action::Motor {
                    motor, direction, ..
                }) => out
                    .packets
                    .extend(self.streamer.press_refused(now, motor, direction)),
                Some(Action::Quit) => out.action = action,
                _ => {}
            }
            return;
        }
        if self.streamer.running_key().is_some() {
            match action {
                Some(Action::Motor {
                    motor,
                    direction,
                    phase,
                }) => {
                    let p = match phase {
                        KeyPhase::Press => self.streamer.press(now, motor, direction),
                        KeyPhase::Repeat => self.streamer.repeat(now, motor, direction),
                    };
                    out.packets.extend(p);
                    out.action = action;
                }
                Some(Action::KeyReleased) => {
                    out.packets.extend(self.streamer.release(now));
                }
                Some(Action::Quit) => {
                    out.packets
                        .extend(self.streamer.stop(now, StopReason::Quit));
                    out.action = Some(Action::Quit);
                }
                // Any other key, bound or not, only stops the motor.
                _ => {
                    out.packets
                        .extend(self.streamer.stop(now, StopReason::OtherKey));
                }
            }
            if self.streamer.running_key().is_none() {
                out.notice = self.stopped_notice();
            }
            return;
        }

        match action {
            Some(Action::Motor {
                motor,
                direction,
                phase,
            }) => {
                let p = match phase {
                    KeyPhase::Repeat => self.streamer.repeat(now, motor, direction),
                    KeyPhase::Press if self.streamer.would_start(now, motor, direction) => {
                        let origin = if ctx.past_endpoints {
                            Origin::Setup
                        } else {
                            Origin::Key
                        };
                        match self.start(origin, model, motor, direction, How::Press, now) {
                            Ok(p) => {
                                if let Some(words) = self.probe_words() {
                                    out.notice.get_or_insert(words);
                                }
                                p
                            }
                            Err(why) => {
                                out.notice = Some(why.words);
                                self.streamer.press_refused(now, motor, direction)
                            }
                        }
                    }
                    KeyPhase::Press => self.streamer.press(now, motor, direction),
                };
                out.packets.extend(p);
                out.action = action;
            }
            Some(Action::KeyReleased) => {
                out.packets.extend(self.streamer.release(now));
            }
            Some(Action::Unavailable(why)) => {
                out.notice = Some(why.to_string());
                out.action = action;
            }
            Some(Action::ResetAgain(id)) => {
                match reset_asked {
                    Some((asked, at)) if asked == id && now <= at + CONFIRM_RESET_WITHIN => {
                        match reset(model, now, id, true) {
                            Ok(message) => {
                                let cnt = self.streamer.next_cnt();
                                out.packets.push(Packet::request(cnt, message));
                            }
                            Err(why) => out.notice = Some(why.words),
                        }
                    }
                    _ => out.notice = Some(NOTHING_TO_CONFIRM.into()),
                }
                out.action = action;
            }
            Some(a) if a.is_command() => {
                if let Action::Reset(id) = a
                    && model.faulted_again_after_reset(id, now)
                {
                    self.reset_asked = Some((id, now));
                }
                match command(&a, model, now) {
                    Ok(message) => {
                        let cnt = self.streamer.next_cnt();
                        out.packets.push(Packet::request(cnt, message));
                    }
                    Err(why) if self.reset_asked.is_some() => {
                        out.notice = Some(format!("{why} (Y: reset it anyway)"));
                    }
                    Err(why) => out.notice = Some(why.words),
                }
                out.action = Some(a);
            }
            other => out.action = other,
        }
    }

    /// Ends a run the model says must end (lost communication, a motor fault, lost
    /// motor status), then lets the streamer end timed-out runs and re-send.
    pub fn tick(&mut self, model: &Model, now: Instant) -> Vec<Packet> {
        let mut out = self.check_model(model, now);
        out.extend(self.streamer.tick(now));
        out.extend(self.probe_step(model, now));
        if !out.is_empty() && self.streamer.running_key().is_none() {
            // Keep an untaken notice rather than overwrite it with nothing.
            self.pending_notice = self.stopped_notice().or(self.pending_notice.take());
        }
        out
    }

    /// The stream alone, without the model: resends and the stream's own clocks
    /// (dead man, run cap, starvation). For a sender that must not wait on the model
    /// lock; [`Controller::tick`] still has to run when packets arrive.
    pub fn tick_stream(&mut self, now: Instant) -> Vec<Packet> {
        let out = self.streamer.tick(now);
        if !out.is_empty() && self.streamer.running_key().is_none() {
            self.pending_notice = self.stopped_notice().or(self.pending_notice.take());
        }
        out
    }

    /// A key while the page cannot be seen (a terminal too small for it): it does
    /// nothing but quit or toggle help. A motor key is only remembered as held, so
    /// its repeats cannot start the motor once the page is shown again; a run is
    /// stopped (it should already have been, by [`StopReason::PageHidden`]).
    pub fn handle_key_hidden(&mut self, key: KeyEvent, ctx: &KeyContext, now: Instant) -> Handled {
        let mut out = Handled {
            packets: self.stop(now, StopReason::PageHidden),
            ..Handled::default()
        };
        out.notice = self.take_notice();
        match keymap::map(&key, ctx) {
            Some(Action::Motor {
                motor, direction, ..
            }) => out
                .packets
                .extend(self.streamer.press_refused(now, motor, direction)),
            // A release still counts, or the key would stay "held" for good.
            Some(Action::KeyReleased) => out.packets.extend(self.streamer.release(now)),
            Some(a @ (Action::Quit | Action::ToggleHelp | Action::CloseOverlay)) => {
                out.action = Some(a)
            }
            _ => {}
        }
        out
    }

    fn check_model(&mut self, model: &Model, now: Instant) -> Vec<Packet> {
        let Some((motor, direction)) = self.streamer.running_key() else {
            return Vec::new();
        };
        let endpoint = match self.watch.as_mut() {
            Some(w) if w.motor == motor && w.direction == direction => w.check(model, now),
            _ => Ok(()),
        };
        match motor_check(model, motor, direction, now).and(endpoint) {
            Err(reason) => self.end_run(now, reason),
            Ok(()) => match (self.target_running(), &model.flap_trim) {
                (Some(t), Some(st))
                    if t.remaining(endpoints::position(motor, &st.value)) <= TARGET_MARGIN =>
                {
                    self.stop(now, StopReason::TargetReached)
                }
                _ => Vec::new(),
            },
        }
    }

    /// The network's run to a position ([`How::Target`]) going on, if one is.
    pub fn target_running(&self) -> Option<TargetRun> {
        self.target.filter(|t| {
            self.streamer.running_key() == Some((t.motor, t.direction))
                && self.streamer.lease_lapse() == Some(StopReason::RequestsStopped)
        })
    }

    /// A request renews the network's run to a position for `lease` from `now`
    /// (never past the run cap). Returns what to send (a stop, if the run's own
    /// clocks ran out first).
    pub fn renew_target(&mut self, now: Instant, lease: Duration) -> Vec<Packet> {
        match self.target_running() {
            Some(t) => self.streamer.lease_ending(
                now,
                t.motor,
                t.direction,
                lease,
                StopReason::RequestsStopped,
            ),
            None => Vec::new(),
        }
    }

    /// Ends the network's run to a position, if it is the one going on; any other
    /// run is left alone.
    pub fn stop_target(&mut self, now: Instant, reason: StopReason) -> Vec<Packet> {
        match self.target_running() {
            Some(_) => self.stop(now, reason),
            None => Vec::new(),
        }
    }

    /// The remote's run, if it ended without the remote's own stop, is remembered as
    /// ended, so its renewals do not take another leased run for it.
    fn settle_remote(&mut self) {
        if let Some(k) = self.remote_run
            && !(self.streamer.leased() && self.streamer.running_key() == Some(k))
        {
            self.remote_run = None;
            let reason = self
                .streamer
                .last_stop()
                .map_or(StopReason::LeaseExpired, |s| s.reason);
            self.lease_ended = Some((k.0, k.1, reason));
        }
    }

    /// The walk-around remote's hold-to-run: starts `motor` `direction` with a
    /// [`LEASE`], or renews the lease of the run it started
    /// ([`MotorStreamer::lease`]). A new run goes through [`Controller::start`] as
    /// every run does, but is not refused for a page nobody sees: the person is at
    /// the wingtip watching the motor itself. A run that ended for any reason but the
    /// remote's own stop is not restarted by renewals: they are refused, with the
    /// reason, until the remote lets go ([`Controller::lease_stop`]) or asks for
    /// another motor or direction. Returns what to send, and the refusal if any.
    pub fn lease(
        &mut self,
        model: &Model,
        motor: Motor,
        direction: Direction,
        now: Instant,
    ) -> (Vec<Packet>, Result<(), MotorRefusal>) {
        let key = (motor, direction);
        let mut out = self.check_model(model, now);
        out.extend(self.streamer.tick(now));
        self.settle_remote();
        if let Some((m, d, reason)) = self.lease_ended {
            if (m, d) == key {
                let why = MotorRefusal::new(
                    Origin::Remote,
                    motor,
                    direction,
                    Refused::LeaseEnded(reason),
                );
                return (out, Err(why));
            }
            self.lease_ended = None;
        }
        if self.remote_run == Some(key) {
            out.extend(self.streamer.lease(now, motor, direction, LEASE));
            return (out, Ok(()));
        }
        match self.start(Origin::Remote, model, motor, direction, How::Lease, now) {
            Ok(p) => {
                out.extend(p);
                self.remote_run = Some(key);
                (out, Ok(()))
            }
            Err(why) => (out, Err(why)),
        }
    }

    /// The remote let go (or sent another command): its leased run, if one is
    /// going, ends with its stop; its renewals may start a run again.
    pub fn lease_stop(&mut self, now: Instant, reason: StopReason) -> Vec<Packet> {
        self.lease_ended = None;
        match self.remote_run.take() {
            Some(k) if self.streamer.leased() && self.streamer.running_key() == Some(k) => {
                self.stop(now, reason)
            }
            _ => Vec::new(),
        }
    }

    /// The remote's leased run going on, if one is.
    pub fn remote_running(&self) -> Option<(Motor, Direction)> {
        self.remote_run
            .filter(|k| self.streamer.leased() && self.streamer.running_key() == Some(*k))
    }

    pub fn on_focus_lost(&mut self, now: Instant) -> Vec<Packet> {
        self.unfocused = true;
        self.stop(now, StopReason::FocusLost)
    }

    /// The terminal has focus again: see [`MotorStreamer::focus_gained`].
    pub fn on_focus_gained(&mut self, now: Instant) {
        self.unfocused = false;
        self.streamer.focus_gained(now);
    }

    pub fn next_deadline(&self) -> Option<Instant> {
        self.streamer.next_deadline()
    }

    pub fn running(&self) -> Option<MotorRun> {
        self.streamer.running()
    }

    pub fn last_stop(&self) -> Option<&StopRecord> {
        self.streamer.last_stop()
    }

    /// Why a motor stopped on its own since the last call, for the notice line.
    pub fn take_notice(&mut self) -> Option<String> {
        self.pending_notice.take()
    }

    /// Ends a running motor for `reason` (e.g. a key on another screen).
    pub fn stop(&mut self, now: Instant, reason: StopReason) -> Vec<Packet> {
        let out = self.streamer.stop(now, reason);
        if !out.is_empty() {
            self.pending_notice = self.stopped_notice();
        }
        out
    }

    /// Words for the last stop, unless the person simply let go.
    fn stopped_notice(&self) -> Option<String> {
        let s = self.streamer.last_stop()?;
        if let Some(asked) = against::asked(s.reason) {
            return Some(against::stopped(s.motor, asked));
        }
        let again = match s.reason {
            StopReason::MaxRunTime => "; press the key again",
            _ => "",
        };
        (!s.reason.is_normal())
            .then(|| format!("{} stopped: {}{again}", s.motor.name(), s.reason.describe()))
    }
}

impl Default for Controller {
    fn default() -> Self {
        Controller::new(StreamerConfig::default())
    }
}

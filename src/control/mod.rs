//! Keys become commands, and held motor keys become safe TRIM_MOVE/FLAP_MOVE streams.
//!
//! - [`keymap`]: a crossterm key event and the selection → an [`Action`].
//! - [`commands`]: an action and the model → a message, or a refusal in words.
//! - [`streamer`]: the 4 Hz move stream with its dead man (see its docs for every way
//!   a run ends).
//!
//! [`Controller`] ties them together for the app's main loop. Nothing here reads a
//! clock, sleeps, spawns or does I/O: the loop passes `now`, sends the packets it gets
//! back on the link, and sleeps until [`Controller::next_deadline`] (or the next key,
//! or the next received packet). Its duties, each of which the streamer's safety
//! depends on:
//!
//! - call [`Controller::tick`] at `next_deadline()` and after applying received
//!   packets to the model (so a motor fault stops the run as soon as it is heard);
//! - call [`Controller::on_link_error`] when a write fails, [`Controller::on_focus_lost`]
//!   on `Event::FocusLost`, [`Controller::on_quit`] before leaving;
//! - install a panic hook and a drop guard that write
//!   [`MotorStreamer::emergency_stop_packets`].

pub mod against;
pub mod commands;
pub mod endpoints;
pub mod keymap;
pub mod release;
pub mod run_state;
pub mod streamer;

use std::time::{Duration, Instant};

use crossterm::event::KeyEvent;

use self::run_state::{MotorRun, ReleaseMode, RepeatTiming};
use crate::model::{Model, Motor};
use crate::protocol::message::Packet;

pub use against::Against;
pub use commands::{
    Refusal, command, device_power, motor_check, motor_permit, put_back_off, reset,
};
pub use keymap::{Action, KeyContext, KeyPhase, Selected};
pub use release::{release_mode, release_mode_here};
pub use streamer::{
    Direction, MAX_WIRE_INTERVAL, MotorStreamer, RESEND_PERIOD, StopReason, StopRecord,
    StreamerConfig,
};

/// What a key did.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Outcome {
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
    /// The way the run a key is starting is known to move (a confirmed run), for its
    /// watch.
    starting_way: Option<i32>,
    /// A key's run going as probes until its motor shows its way
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
            starting_way: None,
            probe: None,
            hidden: false,
            unfocused: false,
            reset_asked: None,
            remote_run: None,
            lease_ended: None,
        }
    }

    /// The record of motors seen moving against their command: hand it to every
    /// other origin of runs (the XFSp gateway), so each refuses what one saw.
    pub fn against(&self) -> Against {
        self.against.clone()
    }

    /// Why the person cannot see the page now, if they cannot: the terminal too small
    /// for it, or not focused. A run stops the moment it happens; and while it lasts,
    /// a run with no key behind it ([`Controller::run_for`], the installation check's)
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

    /// Set once the app knows whether the terminal reports key releases.
    pub fn set_release_mode(&mut self, now: Instant, mode: ReleaseMode) -> Vec<Packet> {
        self.streamer.set_release_mode(now, mode)
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
    ) -> Outcome {
        // The model's verdict comes first (the streamer applies its own timeouts on
        // every call): a key must not keep alive a run that already had to end. No
        // resend here: a move just before this key's stop would be noise.
        let mut out = Outcome {
            packets: self.check_model(model, now),
            ..Outcome::default()
        };
        out.notice = self.take_notice();
        let before = self.streamer.running_key();
        self.starting_way = None;
        self.handle_mapped(keymap::map(&key, ctx), ctx, model, now, &mut out);
        // A run this key started keeps to the endpoints unless the screen runs motors
        // past them on purpose (the setup screens); either is watched for moving
        // against its command, unless it was confirmed knowing it does.
        if before.is_none()
            && let Some((motor, direction)) = self.streamer.running_key()
        {
            let way = self.starting_way;
            self.watch = Some(match (ctx.past_endpoints, way) {
                (true, _) => endpoints::Watch::capture(motor, direction, way),
                (false, Some(w)) => endpoints::Watch::moving(motor, direction, w),
                (false, None) => endpoints::Watch::new(motor, direction),
            });
            self.probe = None;
            if !ctx.past_endpoints
                && way.is_none()
                && let Some(words) = self.start_probe(model, motor, direction, now, &mut out)
            {
                out.notice.get_or_insert(words);
            }
        }
        out
    }

    /// A key's run that keeps to the endpoints, its motor's way not known, started
    /// within [`endpoints::NEAR`] of the endpoint behind it: a motor wired the wrong
    /// way would pass that endpoint between two positions, so the run goes as a probe
    /// first ([`endpoints::Probing`]), as the installation check's runs do. Returns the
    /// notice.
    fn start_probe(
        &mut self,
        model: &Model,
        motor: Motor,
        direction: Direction,
        now: Instant,
        out: &mut Outcome,
    ) -> Option<String> {
        let (probing, length) = endpoints::Probing::start(model, motor, direction, now)?;
        out.packets.extend(self.streamer.probe(now, length));
        self.probe = Some(probing);
        Some(probing.words())
    }

    /// A probing run, once its probe stopped and a position came after the stop
    /// ([`endpoints::Probing::next`]): gone the commanded way, it streams on as any
    /// run; gone the other way, it is stopped as moving against its command (with
    /// the words of [`against`] and its record); not moved, another probe, for as
    /// long as its key is held.
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
                self.against.record(p.motor, p.direction);
                self.stop(now, StopReason::MovedAgainst(p.direction))
            }
        }
    }

    fn handle_mapped(
        &mut self,
        action: Option<Action>,
        ctx: &KeyContext,
        model: &Model,
        now: Instant,
        out: &mut Outcome,
    ) {
        // A second reset is confirmed by the very next key, or not at all (a key's
        // release report is not a key).
        let reset_asked = match action {
            Some(Action::KeyReleased) => self.reset_asked,
            _ => self.reset_asked.take(),
        };
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
                        let permit = match &self.motors_refused {
                            Some(why) => Err(Refusal(why.clone())),
                            None => motor_permit(model, motor, direction, now)
                                .and_then(|()| self.key_permit(model, motor, direction, ctx, now)),
                        };
                        match permit {
                            Ok(()) => self.streamer.press(now, motor, direction),
                            Err(why) => {
                                out.notice = Some(why.0);
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
                            Err(why) => out.notice = Some(why.0),
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
                    Err(why) => out.notice = Some(why.0),
                }
                out.action = Some(a);
            }
            other => out.action = other,
        }
    }

    /// A key's run past the model's checks: kept off the endpoint it heads for
    /// (unless the screen runs past them), and for a motor seen moving against its
    /// command, refused until the same key comes again within
    /// [`against::CONFIRM_WITHIN`] ([`against`]); then it runs knowing its way.
    fn key_permit(
        &mut self,
        model: &Model,
        motor: Motor,
        direction: Direction,
        ctx: &KeyContext,
        now: Instant,
    ) -> Result<(), Refusal> {
        let known = model
            .flap_trim
            .as_ref()
            .and_then(|st| self.against.known_way(motor, direction, &st.value));
        if !ctx.past_endpoints {
            endpoints::permit_moving(model, motor, direction, known, now).map_err(Refusal)?;
        }
        let Some(seen) = self.against.seen(motor) else {
            return Ok(());
        };
        let confirmed = self.confirm.take().is_some_and(|(m, d, at)| {
            m == motor
                && d == direction
                && now.saturating_duration_since(at) <= against::CONFIRM_WITHIN
        });
        if confirmed {
            self.starting_way = known;
            return Ok(());
        }
        self.confirm = Some((motor, direction, now));
        Err(Refusal(against::confirm_words(motor, seen, direction)))
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
    pub fn handle_key_hidden(&mut self, key: KeyEvent, ctx: &KeyContext, now: Instant) -> Outcome {
        let mut out = Outcome {
            packets: self.stop(now, StopReason::PageHidden),
            ..Outcome::default()
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
            Err(reason) => {
                if let Some(asked) = against::asked(reason) {
                    self.against.record(motor, asked);
                }
                self.stop(now, reason)
            }
            Ok(()) => Vec::new(),
        }
    }

    /// Runs `motor` `direction` for `length` with no key behind it (the installation
    /// check), if the page may stream a motor at all ([`Controller::refuse_motors`]),
    /// the model permits it now ([`motor_permit`]) and it is not at the endpoint it
    /// heads for ([`endpoints::permit`]). From then on it is a run like any other:
    /// [`Controller::tick`] ends it on lost communication, a fault or lost status, at
    /// its endpoint or on a stale position ([`endpoints`]), any key or quit ends it,
    /// and the stream ends it at `length` ([`StopReason::RunDone`]).
    pub fn run_for(
        &mut self,
        model: &Model,
        motor: Motor,
        direction: Direction,
        length: Duration,
        now: Instant,
    ) -> Result<Vec<Packet>, Refusal> {
        // A page whose motor thread did not start has nothing to resend the move:
        // the unit would see one move and then a gap, not a stream.
        if let Some(why) = &self.motors_refused {
            return Err(Refusal(why.clone()));
        }
        self.run_for_moving(model, motor, direction, None, length, now)
    }

    /// [`Controller::run_for`] of a run whose position the caller expects to go `way`
    /// (+1 grow, −1 shrink) rather than the direction's own way: the installation
    /// check running back a motor it saw go the wrong way. The endpoint that way is
    /// the one the run keeps off; any other stop is as for every run.
    pub fn run_for_moving(
        &mut self,
        model: &Model,
        motor: Motor,
        direction: Direction,
        way: Option<i32>,
        length: Duration,
        now: Instant,
    ) -> Result<Vec<Packet>, Refusal> {
        if let Some(why) = &self.motors_refused {
            return Err(Refusal(why.clone()));
        }
        if let Some(unseen) = self.unseen() {
            return Err(Refusal(format!("not started: {}", unseen.describe())));
        }
        motor_permit(model, motor, direction, now)?;
        // A motor seen moving against its command runs only for a caller that says
        // the way it saw it go (the check running back what it moved); nobody here
        // can confirm a run of it.
        if way.is_none()
            && let Some(why) = self.against.refusal(motor)
        {
            return Err(Refusal(why));
        }
        endpoints::permit_moving(model, motor, direction, way, now).map_err(Refusal)?;
        let out = self.streamer.run_for(now, motor, direction, length);
        if self.streamer.running_key() == Some((motor, direction)) {
            self.watch = Some(match way {
                Some(w) => endpoints::Watch::moving(motor, direction, w),
                None => endpoints::Watch::new(motor, direction),
            });
        }
        Ok(out)
    }

    /// The walk-around remote's hold-to-run: starts `motor` `direction` with a
    /// [`LEASE`], or renews the lease of the run it started
    /// ([`MotorStreamer::lease`]). A new run is permitted as the installation
    /// check's are (the model's checks, the endpoints, a motor seen moving against
    /// its command), but not refused for a page nobody sees: the person is at the
    /// wingtip watching the motor itself. Started near the endpoint behind it, it goes
    /// as probes until the motor shows its way ([`endpoints::Probing`]), as a key's
    /// run does. A run that ended for any reason but the
    /// remote's own stop is not restarted by renewals: they are refused, with the
    /// reason, until the remote lets go ([`Controller::lease_stop`]) or asks for
    /// another motor or direction. Returns what to send, and the refusal if any.
    pub fn lease(
        &mut self,
        model: &Model,
        motor: Motor,
        direction: Direction,
        now: Instant,
    ) -> (Vec<Packet>, Result<(), Refusal>) {
        let key = (motor, direction);
        let mut out = self.check_model(model, now);
        out.extend(self.streamer.tick(now));
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
        if let Some((m, d, reason)) = self.lease_ended {
            if (m, d) == key {
                return (
                    out,
                    Err(Refusal(format!(
                        "{} stopped: {}; let go and press again",
                        motor.name(),
                        reason.describe()
                    ))),
                );
            }
            self.lease_ended = None;
        }
        if self.remote_run == Some(key) {
            out.extend(self.streamer.lease(now, motor, direction, LEASE));
            return (out, Ok(()));
        }
        let permit = match &self.motors_refused {
            Some(why) => Err(Refusal(why.clone())),
            None => motor_permit(model, motor, direction, now),
        }
        .and_then(|()| match self.against.refusal(motor) {
            Some(why) => Err(Refusal(why)),
            None => Ok(()),
        })
        .and_then(|()| {
            endpoints::permit_moving(model, motor, direction, None, now).map_err(Refusal)
        });
        if let Err(why) = permit {
            return (out, Err(why));
        }
        out.extend(self.streamer.lease(now, motor, direction, LEASE));
        if self.streamer.running_key() == Some(key) {
            self.watch = Some(endpoints::Watch::new(motor, direction));
            self.probe = None;
            self.remote_run = Some(key);
            // Near the endpoint behind it, as probes until the motor shows its way,
            // as a key's run goes.
            let mut probed = Outcome::default();
            self.start_probe(model, motor, direction, now, &mut probed);
            out.extend(probed.packets);
            (out, Ok(()))
        } else {
            (out, Err(Refusal(format!("{} did not start", motor.name()))))
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

    pub fn on_link_error(&mut self, now: Instant) -> Vec<Packet> {
        self.stop(now, StopReason::LinkError)
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

    pub fn on_quit(&mut self, now: Instant) -> Vec<Packet> {
        self.stop(now, StopReason::Quit)
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
        (!s.reason.is_normal())
            .then(|| format!("{} stopped: {}", s.motor.name(), s.reason.describe()))
    }
}

impl Default for Controller {
    fn default() -> Self {
        Controller::new(StreamerConfig::default())
    }
}

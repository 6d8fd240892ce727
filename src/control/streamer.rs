//! The motor streamer: a held key becomes a TRIM_MOVE/FLAP_MOVE stream with a dead man.
//!
//! ICD §6.4.2/§6.4.3 and icd-reading R19: while a motor should run, its move message
//! must reach the unit at 4 Hz or more (no gap over 250 ms), and the unit stops the
//! motor when they stop coming. That rule protects against a lost stop message; this
//! module protects against the other runaway, a page that keeps streaming after the
//! person let go. So a run ends, with a stop message (the same message, power 0), on
//! the first of: release, the dead-man timeout of the key auto-repeat, any other key,
//! quit, focus loss, a link error, lost communication, a motor fault, or the maximum
//! continuous run time. After an end the held key cannot restart the run: only a fresh
//! press after a release (or, without release reports, a gap in the repeats) can.
//!
//! Without release reports (auto-repeat mode) the streamer learns the terminal's own
//! repeat: the first hold waits up to [`FIRST_REPEAT_DEFAULT`] for the first repeat;
//! once a hold has shown a steady repeat, the first-repeat window becomes the measured
//! delay plus [`FIRST_REPEAT_MARGIN`] (within [`FIRST_WINDOW_MIN`]..=[`FIRST_WINDOW_MAX`])
//! and the end-of-run gap about three measured intervals (within
//! [`GAP_MIN`]..=[`GAP_MAX`]). A tap (a press with no repeat) is therefore a nudge of at
//! most the first window.
//!
//! Nothing here reads a clock, sleeps or does I/O: every call takes `now`, and
//! [`MotorStreamer::next_deadline`] tells the caller when to call
//! [`MotorStreamer::tick`] next, so tests drive it on a fake clock.

use std::time::{Duration, Instant};

use super::run_state::{MotorRun, ReleaseMode, RepeatTiming};
use crate::model::{Motor, TrimKind};
use crate::protocol::fault::FaultCode;
use crate::protocol::message::{FlapDirection, FlapMove, Packet, TrimDirection, TrimMove};

/// icd-reading R19: the longest gap the unit tolerates between move messages.
pub const MAX_WIRE_INTERVAL: Duration = Duration::from_millis(250);
/// The longest resend period accepted. The 50 ms left below [`MAX_WIRE_INTERVAL`] is
/// for a sender that wakes late (a loaded machine).
pub const MAX_RESEND_PERIOD: Duration = Duration::from_millis(200);
/// The resend period used: 8 Hz, so a sender that wakes up to 125 ms late still
/// meets the 250 ms rule (at 150 ms, two busy processes on a loaded 2-core machine
/// pushed 2 % of intervals past 220 ms in the page bench). A TRIM_MOVE frame is 12
/// bytes, so the stream costs about 1.7 % of the 57 600-baud line.
pub const RESEND_PERIOD: Duration = Duration::from_millis(125);
/// Auto-repeat mode, before anything is learned: how long the first hold waits for
/// the first repeat. Covers X (660 ms), KDE and sway (600 ms), GNOME, macOS and
/// Windows (500 ms) defaults.
pub const FIRST_REPEAT_DEFAULT: Duration = Duration::from_millis(700);
/// Added to a measured repeat delay to make the first-repeat window.
pub const FIRST_REPEAT_MARGIN: Duration = Duration::from_millis(100);
/// The learned first-repeat window stays within these.
pub const FIRST_WINDOW_MIN: Duration = Duration::from_millis(300);
pub const FIRST_WINDOW_MAX: Duration = Duration::from_millis(1200);
/// Auto-repeat mode, before an interval is learned: how long after a repeat the next
/// may take.
pub const GAP_DEFAULT: Duration = Duration::from_millis(200);
/// The learned end-of-run gap (three measured intervals) stays within these: never so
/// short that scheduling jitter ends a held run, never over the unit's own 250 ms.
pub const GAP_MIN: Duration = Duration::from_millis(90);
pub const GAP_MAX: Duration = Duration::from_millis(250);
/// Learning judges a hold: its repeats must come at least this fast (10 Hz; people
/// do not tap that fast for long) and the first must come at least twice the
/// interval after the press, as every auto-repeat's does.
const LEARN_MAX_INTERVAL: Duration = Duration::from_millis(100);
const LEARN_MIN_DELAY: Duration = Duration::from_millis(150);
const LEARN_MAX_DELAY: Duration = Duration::from_millis(1500);
/// How many intervals a hold must show before its rate is trusted.
const LEARN_MIN_INTERVALS: usize = 3;
/// Below this the stream would only crowd the 57 600-baud link.
pub const MIN_RESEND_PERIOD: Duration = Duration::from_millis(20);
/// A configured run cap is clamped to this: it must stay below the 30 s flap max run
/// time of ICD Appendix F, so the page's cap, not the unit's, is what people meet.
pub const MAX_RUN_LIMIT: Duration = Duration::from_secs(25);
/// The command number of [`MotorStreamer::emergency_stop_packets`]: the panic hook has
/// no counter to draw from, and the unit does not need the number to be fresh.
pub const EMERGENCY_CNT: u8 = 0;

/// Which way a motor key drives. Flaps and pitch trim go up/down, roll trim left/right.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    Up,
    Down,
    Left,
    Right,
}

impl Direction {
    pub fn name(self) -> &'static str {
        match self {
            Direction::Up => "up",
            Direction::Down => "down",
            Direction::Left => "left",
            Direction::Right => "right",
        }
    }

    /// Whether `motor` moves this way: a roll trim has no "up", flaps no "left".
    pub fn applies_to(self, motor: Motor) -> bool {
        match motor {
            Motor::Flaps | Motor::Trim(TrimKind::Pitch) => {
                matches!(self, Direction::Up | Direction::Down)
            }
            Motor::Trim(TrimKind::Roll) => matches!(self, Direction::Left | Direction::Right),
        }
    }
}

/// Why a run ended, for the screen and the event log.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The terminal reported the key's release (or any key's release).
    Released,
    /// Auto-repeat mode: no repeat arrived in time, so the key is taken as released.
    RepeatsStopped,
    OtherKey,
    Quit,
    FocusLost,
    LinkError,
    CommLost,
    /// FLAP_TRIM_STATUS went quiet: the motor can no longer be watched.
    MotorStatusLost,
    MotorFault(FaultCode),
    MotorDisabled,
    FlapDownInhibited,
    MaxRunTime,
    /// The terminal became too small to show the page: nothing the person cannot see
    /// may keep running.
    PageHidden,
    /// The caller did not call `tick` in time, so a gap over 250 ms already went out;
    /// the unit has stopped the motor and the page does not silently restart it.
    Starved,
    /// The page's loop stopped ticking (a blocked terminal write, say), so the model's
    /// checks no longer run: the stream must not go on alone.
    PageStalled,
    Panic,
    /// A timed run ([`MotorStreamer::run_for`]) reached its end.
    RunDone,
    /// A leased run ([`MotorStreamer::lease`], the walk-around remote's hold-to-run)
    /// was not renewed in time: the finger left the button, or the phone went quiet.
    LeaseExpired,
    /// A run to a target asked over the network (XFSp) was not renewed in time: the
    /// requests stopped coming, or the requester went quiet. A requester has no stop
    /// of its own, so this is how it lets go ([`StopReason::is_normal`]).
    RequestsStopped,
    /// A run to a target ([`super::How::Target`]) reached it.
    TargetReached,
    /// The remote asked for its run to stop (`{"stop":true}`: the finger let go).
    RemoteStop,
    /// A fault elsewhere on the unit (another circuit, or FAULT_STATUS's system
    /// fault) ended the installation check the run was part of.
    UnitFault,
    /// The position reached (or was about to pass) the configured endpoint it was
    /// moving toward, here (`control::endpoints`).
    AtEndpoint(u8),
    /// The position was no longer fresh enough to keep the run off its endpoint
    /// (`control::endpoints::POSITION_FRESH`).
    PositionStale,
    /// The position went the other way from the one the run's direction (here, the
    /// one asked) should move it (`control::against`): its leads or its sensor may be
    /// swapped.
    MovedAgainst(Direction),
}

impl StopReason {
    pub fn describe(self) -> String {
        match self {
            StopReason::Released => "key released".into(),
            StopReason::RepeatsStopped => "key released (key repeats stopped)".into(),
            StopReason::OtherKey => "another key was pressed".into(),
            StopReason::Quit => "quitting".into(),
            StopReason::FocusLost => "the terminal lost focus".into(),
            StopReason::LinkError => "the link could not send".into(),
            StopReason::CommLost => "COMMUNICATION LOST".into(),
            StopReason::MotorStatusLost => "no live flap/trim status".into(),
            StopReason::MotorFault(code) => format!("motor fault {}", code.name()),
            StopReason::MotorDisabled => "the motor is not enabled".into(),
            StopReason::FlapDownInhibited => "flap down is inhibited".into(),
            StopReason::MaxRunTime => "maximum run time reached".into(),
            StopReason::PageHidden => "the terminal is too small to show the page".into(),
            StopReason::Starved => "the page fell behind the 4 Hz stream".into(),
            StopReason::PageStalled => "the page stopped responding".into(),
            StopReason::Panic => "the program failed".into(),
            StopReason::RunDone => "the timed run ended".into(),
            StopReason::LeaseExpired => "the remote stopped renewing its run".into(),
            StopReason::RemoteStop => "released on the remote".into(),
            StopReason::RequestsStopped => "the network requests for it stopped".into(),
            StopReason::TargetReached => "target reached".into(),
            StopReason::UnitFault => "a fault elsewhere on the unit".into(),
            StopReason::AtEndpoint(end) => format!("at its endpoint (position {end})"),
            StopReason::PositionStale => format!(
                "its position is not fresh (no FLAP_TRIM_STATUS for over {:.1} s), so it \
                 cannot be kept off its endpoint",
                super::endpoints::POSITION_FRESH.as_secs_f32()
            ),
            StopReason::MovedAgainst(asked) => format!(
                "it moved {} when asked {}: its leads or its sensor may be swapped",
                super::endpoints::opposite(asked).name(),
                asked.name()
            ),
        }
    }

    /// Whether the person simply let go, as opposed to the run being cut short.
    pub fn is_normal(self) -> bool {
        matches!(
            self,
            StopReason::Released
                | StopReason::RepeatsStopped
                | StopReason::RunDone
                | StopReason::RemoteStop
                | StopReason::TargetReached
                | StopReason::RequestsStopped
        )
    }
}

/// The last run's end, kept for display and logging.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StopRecord {
    pub motor: Motor,
    pub direction: Direction,
    pub reason: StopReason,
    pub at: Instant,
    pub ran_for: Duration,
    /// How long the motor was driven: `ran_for` less the pauses between a run's
    /// probes ([`MotorStreamer::probe`]).
    pub driven: Duration,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamerConfig {
    pub release_mode: ReleaseMode,
    /// How often the move message is re-sent; clamped to
    /// [`MIN_RESEND_PERIOD`]..=[`MAX_RESEND_PERIOD`].
    pub resend_period: Duration,
    /// The longest continuous run; clamped to [`MAX_RUN_LIMIT`].
    pub max_run: Duration,
    /// Auto-repeat mode: how long after the press the first repeat may take, until a
    /// repeat delay is learned ([`FIRST_REPEAT_DEFAULT`], or `--repeat-delay`).
    pub first_repeat_timeout: Duration,
    /// `first_repeat_timeout` was set by hand (`--repeat-delay`): learning keeps it.
    pub first_repeat_fixed: bool,
    /// Auto-repeat mode: how long after a repeat the next may take, until a repeat
    /// interval is learned.
    pub repeat_timeout: Duration,
    /// Key-release mode's second dead man: a terminal with the kitty keyboard protocol
    /// also sends Repeat events while a key is held, so a release event that is lost
    /// (or a terminal that took the protocol but not its event types) cannot leave a
    /// run going until the cap. `(first, between)`: how long after the press the
    /// first event may take, and after that between events. Longer than auto-repeat's
    /// so slow desktop repeat settings still hold. `None` for a caller with a dead man
    /// of its own (the XFSp gateway's request expiry).
    pub key_release_repeat_guard: Option<(Duration, Duration)>,
}

impl Default for StreamerConfig {
    fn default() -> Self {
        StreamerConfig {
            release_mode: ReleaseMode::default(),
            resend_period: RESEND_PERIOD,
            max_run: Duration::from_secs(10),
            first_repeat_timeout: FIRST_REPEAT_DEFAULT,
            first_repeat_fixed: false,
            repeat_timeout: GAP_DEFAULT,
            // 1.3 s: Windows (which reports releases natively) lets people set a
            // repeat delay of up to 1 s.
            key_release_repeat_guard: Some((
                Duration::from_millis(1300),
                Duration::from_millis(500),
            )),
        }
    }
}

impl StreamerConfig {
    fn clamped(mut self) -> Self {
        self.resend_period = self
            .resend_period
            .clamp(MIN_RESEND_PERIOD, MAX_RESEND_PERIOD);
        self.max_run = self.max_run.min(MAX_RUN_LIMIT);
        self
    }
}

type MotorKey = (Motor, Direction);

/// The motor key we believe is held down.
#[derive(Debug, Clone, Copy)]
struct Held {
    /// `None` after a focus loss in auto-repeat mode: the next motor key event of any
    /// kind may be a repeat of a key held through the focus change, so it cannot start.
    key: Option<MotorKey>,
    last_event: Instant,
    repeats_seen: bool,
    /// With `key: None`: focus has not come back yet. Until it does, any motor key
    /// event is taken as a repeat; once it has, only one within the repeat gap of its
    /// return is (a key held through the change repeats at once), and a later press
    /// starts a run as any press does.
    awaiting_focus: bool,
}

/// The timing of the current hold, for learning the terminal's auto-repeat.
#[derive(Debug, Clone, Copy)]
struct HoldTiming {
    key: MotorKey,
    pressed: Instant,
    last: Instant,
    /// From the press to the first repeat.
    delay: Option<Duration>,
    /// The latest intervals between repeats (a ring), and how many were seen.
    intervals: [Duration; 8],
    seen: usize,
}

impl HoldTiming {
    fn new(key: MotorKey, now: Instant) -> Self {
        HoldTiming {
            key,
            pressed: now,
            last: now,
            delay: None,
            intervals: [Duration::ZERO; 8],
            seen: 0,
        }
    }

    fn repeat(&mut self, now: Instant) {
        let since = now.saturating_duration_since(self.last);
        match self.delay {
            None => self.delay = Some(now.saturating_duration_since(self.pressed)),
            Some(_) => {
                self.intervals[self.seen % self.intervals.len()] = since;
                self.seen += 1;
            }
        }
        self.last = now;
    }

    /// The median of the latest intervals, once there are enough to trust.
    fn interval(&self) -> Option<Duration> {
        let n = self.seen.min(self.intervals.len());
        if n < LEARN_MIN_INTERVALS {
            return None;
        }
        let mut v = self.intervals[..n].to_vec();
        v.sort();
        Some(v[n / 2])
    }
}

/// What the streamer learned of the terminal's auto-repeat.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Learned {
    delay: Option<Duration>,
    interval: Option<Duration>,
}

#[derive(Debug, Clone, Copy)]
struct Run {
    key: MotorKey,
    started: Instant,
    last_sent: Instant,
    /// A timed run ([`MotorStreamer::run_for`]): it ends here, and no key keeps it
    /// alive or ends it early but as any key does (another key, release).
    until: Option<Instant>,
    /// A leased run ([`MotorStreamer::lease`], [`MotorStreamer::lease_ending`]):
    /// `until` is its lease, renewed by each call, and its end is this reason.
    leased: Option<StopReason>,
    /// A probe ([`MotorStreamer::probe`]): the motor is stopped on the wire here,
    /// the run (and its key) going on.
    probe_until: Option<Instant>,
    /// When a probe's stop went out: the run is on, its motor stopped, nothing is
    /// resent until [`MotorStreamer::resume`].
    paused: Option<Instant>,
    /// The pauses after its probes so far, ended ones.
    paused_for: Duration,
}

/// Turns motor key events into the move stream. See the module docs.
#[derive(Debug, Clone)]
pub struct MotorStreamer {
    config: StreamerConfig,
    cnt: u8,
    run: Option<Run>,
    held: Option<Held>,
    hold: Option<HoldTiming>,
    learned: Learned,
    last_stop: Option<StopRecord>,
}

impl MotorStreamer {
    pub fn new(config: StreamerConfig) -> Self {
        MotorStreamer {
            config: config.clamped(),
            cnt: 0,
            run: None,
            held: None,
            hold: None,
            learned: Learned::default(),
            last_stop: None,
        }
    }

    /// The configuration in force (after clamping).
    pub fn config(&self) -> &StreamerConfig {
        &self.config
    }

    pub fn release_mode(&self) -> ReleaseMode {
        self.config.release_mode
    }

    /// The auto-repeat timing in use, for the screen.
    pub fn repeat_timing(&self) -> RepeatTiming {
        RepeatTiming {
            first_window: self.first_window(),
            delay: self.learned.delay,
            interval: self.learned.interval,
            end_gap: self.gap(),
            set_by_hand: self.config.first_repeat_fixed,
        }
    }

    /// Auto-repeat mode: how long after a fresh press the first repeat may take. A tap
    /// runs the motor at most this long.
    pub fn first_window(&self) -> Duration {
        match self.learned.delay {
            Some(d) if !self.config.first_repeat_fixed => {
                (d + FIRST_REPEAT_MARGIN).clamp(FIRST_WINDOW_MIN, FIRST_WINDOW_MAX)
            }
            _ => self.config.first_repeat_timeout,
        }
    }

    /// Auto-repeat mode: how long after a repeat the next may take before the key is
    /// taken as released.
    pub fn gap(&self) -> Duration {
        self.learned
            .interval
            .map_or(self.config.repeat_timeout, |i| {
                (i * 3).clamp(GAP_MIN, GAP_MAX)
            })
    }

    /// The next command number, shared by every request the page sends so the unit's
    /// echoes (icd-reading R14) can be told apart.
    pub fn next_cnt(&mut self) -> u8 {
        let c = self.cnt;
        self.cnt = self.cnt.wrapping_add(1);
        c
    }

    /// A key-down of a motor key. With key release reports, a press is fresh unless
    /// the key is already down. Without them a press may be a repeat, and is judged
    /// by the repeat timeouts. A fresh press starts a run when none is running; while
    /// another motor key runs it only stops that run.
    pub fn press(&mut self, now: Instant, motor: Motor, direction: Direction) -> Vec<Packet> {
        self.key_event(now, motor, direction, true, true)
    }

    /// A key repeat the terminal marked as such. Keeps a run of the same key alive;
    /// never starts one.
    pub fn repeat(&mut self, now: Instant, motor: Motor, direction: Direction) -> Vec<Packet> {
        self.key_event(now, motor, direction, false, true)
    }

    /// A fresh press the caller refused (fault, lost communication): the key is
    /// remembered as held, so its repeats cannot start the motor once the reason goes
    /// away; a run of another key is stopped as for any other key.
    pub fn press_refused(
        &mut self,
        now: Instant,
        motor: Motor,
        direction: Direction,
    ) -> Vec<Packet> {
        self.key_event(now, motor, direction, true, false)
    }

    /// Whether [`press`](Self::press) at `now` would start a run.
    pub fn would_start(&self, now: Instant, motor: Motor, direction: Direction) -> bool {
        direction.applies_to(motor)
            && self.run.is_none()
            && !self.is_repeat(now, (motor, direction))
    }

    /// Runs `motor` `direction` for `length` (at most the run cap) with no key behind
    /// it: the installation check's brief test runs. The same stream and stop causes
    /// as a held key, with the run's end as its dead man, so the stream's own thread
    /// ends it on time even when the caller is late. A run going on is stopped first
    /// (another key); a key held before is forgotten, so its repeats cannot extend or
    /// restart this run.
    pub fn run_for(
        &mut self,
        now: Instant,
        motor: Motor,
        direction: Direction,
        length: Duration,
    ) -> Vec<Packet> {
        let mut out = self.expire(now);
        out.extend(self.end(now, StopReason::OtherKey));
        self.held = None;
        self.hold = None;
        if !direction.applies_to(motor) {
            return out;
        }
        let key = (motor, direction);
        self.run = Some(Run {
            key,
            started: now,
            last_sent: now,
            until: Some(now + length.min(self.config.max_run)),
            leased: None,
            probe_until: None,
            paused: None,
            paused_for: Duration::ZERO,
        });
        out.push(self.move_packet(key, true));
        out
    }

    /// Hold-to-run by lease, the walk-around remote's release mode: the first call
    /// starts `motor` `direction` with a lease of `lease`; each later call for the
    /// same motor and direction while it runs renews the lease from `now` (never
    /// past the run cap). A lease not renewed in time ends the run with its stop
    /// ([`StopReason::LeaseExpired`]), on this caller's clock like every other end;
    /// every other end of a run (another key, quit, a fault, an endpoint…) ends it
    /// too. A call for another motor or direction stops the run going on first.
    /// Returns what to send; a renewal sends nothing (the resend is on its clock).
    pub fn lease(
        &mut self,
        now: Instant,
        motor: Motor,
        direction: Direction,
        lease: Duration,
    ) -> Vec<Packet> {
        self.lease_ending(now, motor, direction, lease, StopReason::LeaseExpired)
    }

    /// As [`lease`](Self::lease), for a lease whose lapse ends the run for `lapse`
    /// (a network requester's, [`StopReason::RequestsStopped`]); a call renews only
    /// a run leased with the same `lapse`.
    pub fn lease_ending(
        &mut self,
        now: Instant,
        motor: Motor,
        direction: Direction,
        lease: Duration,
        lapse: StopReason,
    ) -> Vec<Packet> {
        let out = self.expire(now);
        if let Some(run) = self.run.as_mut()
            && run.leased == Some(lapse)
            && run.key == (motor, direction)
        {
            run.until = Some((now + lease).min(run.started + self.config.max_run));
            return out;
        }
        let mut out = out;
        out.extend(self.run_for(now, motor, direction, lease));
        if let Some(run) = self.run.as_mut() {
            run.leased = Some(lapse);
        }
        out
    }

    /// What the lapse of the lease of the run going on would end it for, if it is
    /// leased.
    pub fn lease_lapse(&self) -> Option<StopReason> {
        self.run.and_then(|r| r.leased)
    }

    /// Whether the run going on is the remote's leased one ([`MotorStreamer::lease`]).
    pub fn leased(&self) -> bool {
        self.run
            .is_some_and(|r| r.leased == Some(StopReason::LeaseExpired))
    }

    /// Makes the run going on a probe: its motor runs only until `now + length`,
    /// when [`tick`](Self::tick) sends its stop and the run waits, its key still
    /// held and every one of its ends still in force, for [`resume`](Self::resume)
    /// or another probe. A paused run is resumed by this at once.
    pub fn probe(&mut self, now: Instant, length: Duration) -> Vec<Packet> {
        let mut out = self.expire(now);
        if self.run.is_some() {
            out.extend(self.resume(now));
        }
        if let Some(run) = self.run.as_mut() {
            run.probe_until = Some(now + length);
        }
        out
    }

    /// A run paused after its probe streams again, from now. A timed run gets back
    /// the time the pause took: its length is the time its motor is driven (the run
    /// cap still holds), so probes near an endpoint do not eat a check's test run.
    pub fn resume(&mut self, now: Instant) -> Vec<Packet> {
        let mut out = self.expire(now);
        if let Some(run) = self.run.as_mut()
            && let Some(paused) = run.paused.take()
        {
            let pause = now.saturating_duration_since(paused);
            run.paused_for += pause;
            if run.leased.is_none()
                && let Some(until) = run.until.as_mut()
            {
                *until += pause;
            }
            run.last_sent = now;
            let key = run.key;
            out.push(self.move_packet(key, true));
        }
        out
    }

    /// When the running motor's probe stopped it, while it waits.
    pub fn paused_since(&self) -> Option<Instant> {
        self.run.and_then(|r| r.paused)
    }

    /// Whether the run is a probe still moving.
    pub fn probing(&self) -> bool {
        self.run.is_some_and(|r| r.probe_until.is_some())
    }

    /// A key release (key release mode). Any release ends the run: with the key up
    /// there is nothing to keep it alive, and a release of some other key while the
    /// motor runs is still a key the person touched.
    pub fn release(&mut self, now: Instant) -> Vec<Packet> {
        let mut out = self.expire(now);
        out.extend(self.end(now, StopReason::Released));
        self.held = None;
        out
    }

    /// Ends the run, if any, with a stop message. The held key stays held, so neither
    /// its repeats nor a press the terminal cannot tell from a repeat restart it.
    pub fn stop(&mut self, now: Instant, reason: StopReason) -> Vec<Packet> {
        let mut out = self.expire(now);
        out.extend(self.end(now, reason));
        if reason == StopReason::FocusLost {
            self.hold = None;
            self.held = match self.config.release_mode {
                // Release events for keys let go while unfocused never arrive; repeats
                // are marked as such and cannot start a run, so forgetting is safe.
                ReleaseMode::KeyRelease => None,
                // Repeats of a key held through the focus change look like presses.
                ReleaseMode::AutoRepeat => Some(Held {
                    key: None,
                    last_event: now,
                    repeats_seen: true,
                    awaiting_focus: true,
                }),
            };
        }
        out
    }

    /// The terminal has focus again (after [`StopReason::FocusLost`]). A key held
    /// through the change repeats right away and is still not a fresh press; a press
    /// after that is.
    pub fn focus_gained(&mut self, now: Instant) {
        if let Some(h) = self.held.as_mut()
            && h.key.is_none()
        {
            h.awaiting_focus = false;
            h.last_event = now;
        }
    }

    /// Ends a run whose time is up and re-sends the move message when due. Call it at
    /// [`next_deadline`](Self::next_deadline) (and whenever else is convenient).
    pub fn tick(&mut self, now: Instant) -> Vec<Packet> {
        let mut out = self.expire(now);
        if let Some(run) = self.run.as_mut()
            && run.probe_until.is_some_and(|u| now >= u)
        {
            // The probe's end: its stop on the wire, the run kept for its key.
            run.probe_until = None;
            run.paused = Some(now);
            run.last_sent = now;
            let key = run.key;
            out.push(self.move_packet(key, false));
        }
        if let Some(run) = self.run
            && run.paused.is_none()
            && now >= run.last_sent + self.config.resend_period
        {
            out.push(self.move_packet(run.key, true));
            if let Some(r) = self.run.as_mut() {
                r.last_sent = now;
            }
        }
        out
    }

    /// When `tick` must next be called; `None` while no motor runs.
    pub fn next_deadline(&self) -> Option<Instant> {
        let run = self.run?;
        let mut at = run.started + self.config.max_run;
        if run.paused.is_none() {
            at = at.min(run.last_sent + self.config.resend_period);
        }
        if let Some(p) = run.probe_until {
            at = at.min(p);
        }
        if let Some(d) = self.dead_man_deadline() {
            at = at.min(d);
        }
        Some(at)
    }

    pub fn running(&self) -> Option<MotorRun> {
        self.run.map(|r| MotorRun {
            motor: r.key.0,
            direction: r.key.1.name(),
        })
    }

    /// The running motor and direction, typed.
    pub fn running_key(&self) -> Option<(Motor, Direction)> {
        self.run.map(|r| r.key)
    }

    pub fn last_stop(&self) -> Option<&StopRecord> {
        self.last_stop.as_ref()
    }

    /// Stop messages for every motor, needing no state: for the panic hook and the
    /// drop guard, which cannot trust (or reach) the streamer. Stopping a motor that
    /// is not running is harmless; leaving one running is not.
    pub fn emergency_stop_packets() -> [Packet; 3] {
        [
            Packet::request(
                EMERGENCY_CNT,
                FlapMove {
                    on: false,
                    direction: FlapDirection::Up,
                },
            ),
            Packet::request(
                EMERGENCY_CNT,
                TrimMove {
                    trim_type: TrimKind::Pitch.trim_type(),
                    on: false,
                    direction: TrimDirection::DownOrRight,
                },
            ),
            Packet::request(
                EMERGENCY_CNT,
                TrimMove {
                    trim_type: TrimKind::Roll.trim_type(),
                    on: false,
                    direction: TrimDirection::DownOrRight,
                },
            ),
        ]
    }

    // ----- internals -----

    fn key_event(
        &mut self,
        now: Instant,
        motor: Motor,
        direction: Direction,
        maybe_fresh: bool,
        may_start: bool,
    ) -> Vec<Packet> {
        let mut out = self.expire(now);
        if !direction.applies_to(motor) {
            return out;
        }
        let key = (motor, direction);
        let repeat = !maybe_fresh || self.is_repeat(now, key);
        self.learn(now, key, repeat);
        self.held = Some(Held {
            key: Some(key),
            last_event: now,
            // After the first repeat the next comes at the repeat rate, not the delay.
            repeats_seen: repeat,
            awaiting_focus: false,
        });
        match self.run {
            Some(run) if run.key == key => {}
            Some(_) => out.extend(self.end(now, StopReason::OtherKey)),
            None if !repeat && may_start => {
                self.run = Some(Run {
                    key,
                    started: now,
                    last_sent: now,
                    until: None,
                    leased: None,
                    probe_until: None,
                    paused: None,
                    paused_for: Duration::ZERO,
                });
                out.push(self.move_packet(key, true));
            }
            None => {}
        }
        out
    }

    /// Whether an event of `key` at `now` continues the key already held.
    fn is_repeat(&self, now: Instant, key: MotorKey) -> bool {
        let Some(h) = self.held else { return false };
        match h.key {
            None if h.awaiting_focus => true,
            None => now < h.last_event + self.window(&h),
            Some(k) if k != key => false,
            Some(_) => match self.config.release_mode {
                ReleaseMode::KeyRelease => true,
                ReleaseMode::AutoRepeat => now < h.last_event + self.window(&h),
            },
        }
    }

    fn window(&self, h: &Held) -> Duration {
        if h.repeats_seen {
            self.gap()
        } else {
            self.first_window()
        }
    }

    /// Times the hold: a fresh press starts a new one, a repeat of its key adds to
    /// it. A hold whose repeats are steady and fast teaches the interval, and the
    /// delay to its first repeat if that is plausibly an auto-repeat delay; taps and
    /// re-presses (slow, or a "first repeat" no longer than the rate) teach nothing.
    fn learn(&mut self, now: Instant, key: MotorKey, repeat: bool) {
        match self.hold.as_mut() {
            Some(h) if repeat && h.key == key => h.repeat(now),
            _ if repeat => return,
            _ => {
                self.hold = Some(HoldTiming::new(key, now));
                return;
            }
        }
        let Some(h) = self.hold else { return };
        let Some(interval) = h.interval() else { return };
        if interval > LEARN_MAX_INTERVAL {
            return;
        }
        self.learned.interval = Some(interval);
        if let Some(d) = h.delay
            && d >= interval * 2
            && (LEARN_MIN_DELAY..=LEARN_MAX_DELAY).contains(&d)
        {
            self.learned.delay = Some(d);
        }
    }

    /// When the run ends if no further event of its key arrives.
    fn dead_man_deadline(&self) -> Option<Instant> {
        if let Some(until) = self.run.and_then(|r| r.until) {
            return Some(until);
        }
        let h = self.held?;
        match self.config.release_mode {
            ReleaseMode::AutoRepeat => Some(h.last_event + self.window(&h)),
            ReleaseMode::KeyRelease => {
                let (first, between) = self.config.key_release_repeat_guard?;
                Some(h.last_event + if h.repeats_seen { between } else { first })
            }
        }
    }

    /// Ends the run if one of its clocks ran out.
    fn expire(&mut self, now: Instant) -> Vec<Packet> {
        let Some(run) = self.run else {
            return Vec::new();
        };
        let streaming = run.paused.is_none();
        let reason =
            if streaming && now.saturating_duration_since(run.last_sent) > MAX_WIRE_INTERVAL {
                Some(StopReason::Starved)
            } else if now >= run.started + self.config.max_run {
                Some(StopReason::MaxRunTime)
            } else if run.until.is_some_and(|u| now >= u) {
                Some(run.leased.unwrap_or(StopReason::RunDone))
            } else if self.dead_man_deadline().is_some_and(|d| now >= d) {
                Some(StopReason::RepeatsStopped)
            } else {
                None
            };
        reason.map_or_else(Vec::new, |r| self.end(now, r))
    }

    fn end(&mut self, now: Instant, reason: StopReason) -> Vec<Packet> {
        let Some(run) = self.run.take() else {
            return Vec::new();
        };
        let ran_for = now.saturating_duration_since(run.started);
        let paused = run.paused_for
            + run
                .paused
                .map_or(Duration::ZERO, |p| now.saturating_duration_since(p));
        self.last_stop = Some(StopRecord {
            motor: run.key.0,
            direction: run.key.1,
            reason,
            at: now,
            ran_for,
            driven: ran_for.saturating_sub(paused),
        });
        vec![self.move_packet(run.key, false)]
    }

    fn move_packet(&mut self, (motor, direction): MotorKey, on: bool) -> Packet {
        let cnt = self.next_cnt();
        move_packet(cnt, motor, direction, on)
    }
}

/// The move message for `motor` (ICD Tables 30, 31): TRIM_MOVE direction 1 is pitch up
/// or roll left, 0 pitch down or roll right; FLAP_MOVE 0 is up, 1 down.
pub fn move_packet(cnt: u8, motor: Motor, direction: Direction, on: bool) -> Packet {
    match motor {
        Motor::Flaps => Packet::request(
            cnt,
            FlapMove {
                on,
                direction: match direction {
                    Direction::Down => FlapDirection::Down,
                    _ => FlapDirection::Up,
                },
            },
        ),
        Motor::Trim(kind) => Packet::request(
            cnt,
            TrimMove {
                trim_type: kind.trim_type(),
                on,
                direction: match direction {
                    Direction::Up | Direction::Left => TrimDirection::UpOrLeft,
                    Direction::Down | Direction::Right => TrimDirection::DownOrRight,
                },
            },
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::{Message, TrimType};

    const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn direction_bytes_follow_tables_30_and_31() {
        let bytes = |m, d| move_packet(7, m, d, true).message.emit().to_vec();
        assert_eq!(bytes(PITCH, Direction::Up), [0, 1, 1]);
        assert_eq!(bytes(PITCH, Direction::Down), [0, 1, 0]);
        assert_eq!(
            bytes(Motor::Trim(TrimKind::Roll), Direction::Left),
            [1, 1, 1]
        );
        assert_eq!(
            bytes(Motor::Trim(TrimKind::Roll), Direction::Right),
            [1, 1, 0]
        );
        assert_eq!(bytes(Motor::Flaps, Direction::Up), [1, 0]);
        assert_eq!(bytes(Motor::Flaps, Direction::Down), [1, 1]);
    }

    #[test]
    fn a_resend_period_over_the_margin_is_clamped() {
        let s = MotorStreamer::new(StreamerConfig {
            resend_period: ms(400),
            max_run: Duration::from_secs(60),
            ..Default::default()
        });
        assert_eq!(s.config().resend_period, MAX_RESEND_PERIOD);
        assert_eq!(s.config().max_run, MAX_RUN_LIMIT);
    }

    /// The installation check's runs: no key, the same 8 Hz stream, and the run's end
    /// is its dead man (even in auto-repeat mode, whose 700 ms first window would
    /// otherwise end a 1.5 s run); a held key's repeats neither extend nor restart it.
    #[test]
    fn a_timed_run_streams_until_its_end_then_stops_with_its_reason() {
        let t0 = Instant::now();
        let mut s = MotorStreamer::new(StreamerConfig::default());
        let at = |n| t0 + ms(n);
        let start = s.run_for(t0, PITCH, Direction::Up, ms(1500));
        assert_eq!(start.len(), 1);
        assert_eq!(start[0].message.emit().to_vec(), [0, 1, 1], "pitch up, on");
        let mut t = 0;
        let mut resends = 0;
        while let Some(d) = s.next_deadline() {
            let n = (d - t0).as_millis() as u64;
            assert!(n - t <= 125, "a resend every period: {t} -> {n}");
            t = n;
            for p in s.tick(at(t)) {
                if p.message.emit()[1] == 1 {
                    resends += 1;
                } else {
                    assert_eq!(t, 1500, "the stop at the run's end");
                    assert_eq!(p.message.emit().to_vec(), [0, 0, 1]);
                }
            }
            // A key repeat of the same key arriving meanwhile changes nothing.
            if t == 1000 {
                assert!(s.repeat(at(t), PITCH, Direction::Up).is_empty());
            }
        }
        assert_eq!(resends, 11, "125 ms apart from 125 to 1375 ms");
        assert_eq!(s.last_stop().unwrap().reason, StopReason::RunDone);
        assert!(StopReason::RunDone.is_normal());
        // The run is capped by max_run, and any key stop ends it early.
        let mut s = MotorStreamer::new(StreamerConfig::default());
        s.run_for(t0, Motor::Flaps, Direction::Down, Duration::from_secs(60));
        assert_eq!(s.next_deadline(), Some(at(125)));
        let stop = s.stop(at(200), StopReason::OtherKey);
        assert_eq!(stop[0].message.emit().to_vec(), [0, 1]);
        assert!(s.running().is_none());
        // A direction the motor lacks starts nothing.
        assert_eq!(s.run_for(at(300), PITCH, Direction::Left, ms(500)).len(), 0);
        assert!(s.running().is_none());
    }

    /// A probe: the run's motor stops on the wire at the probe's end, nothing is
    /// resent while it waits (no stream, so no gap to keep and no starvation), its
    /// key's ends still hold; resumed, it streams again at once and every period.
    #[test]
    fn a_probe_stops_the_motor_and_keeps_the_run_until_it_resumes() {
        let t0 = Instant::now();
        let at = |n| t0 + ms(n);
        let on = |p: &[Packet]| -> Vec<bool> {
            p.iter()
                .map(|p| matches!(p.message, Message::TrimMove(TrimMove { on: true, .. })))
                .collect()
        };
        let mut s = MotorStreamer::new(StreamerConfig {
            release_mode: ReleaseMode::KeyRelease,
            ..Default::default()
        });
        assert_eq!(on(&s.press(t0, PITCH, Direction::Up)), [true]);
        assert!(s.probe(t0, ms(20)).is_empty());
        assert!(s.probing());
        assert_eq!(s.next_deadline(), Some(at(20)));
        assert_eq!(on(&s.tick(at(20))), [false], "the probe's stop");
        assert_eq!(s.paused_since(), Some(at(20)));
        assert!(s.running().is_some(), "the run goes on");
        // Waiting: no resend, no starvation, the key's repeats change nothing.
        for n in [100, 200, 300, 400] {
            assert!(s.repeat(at(n), PITCH, Direction::Up).is_empty());
            assert!(s.tick(at(n)).is_empty(), "at {n}");
        }
        assert!(s.running().is_some());
        assert_eq!(on(&s.resume(at(420))), [true]);
        assert_eq!(s.next_deadline(), Some(at(420) + RESEND_PERIOD));
        assert_eq!(on(&s.tick(at(545))), [true]);
        // Another probe from a paused run starts it at once; a release while it
        // waits ends the run with its stop, as any release does.
        assert_eq!(on(&s.tick(at(550))), Vec::<bool>::new());
        assert!(s.probe(at(560), ms(20)).is_empty());
        assert_eq!(on(&s.tick(at(580))), [false]);
        assert_eq!(on(&s.probe(at(700), ms(20))), [true]);
        assert_eq!(on(&s.tick(at(720))), [false]);
        assert_eq!(on(&s.release(at(800))), [false]);
        assert!(s.running().is_none());
        assert_eq!(s.last_stop().unwrap().reason, StopReason::Released);
    }

    #[test]
    fn a_direction_the_motor_lacks_starts_nothing() {
        let t0 = Instant::now();
        let mut s = MotorStreamer::new(StreamerConfig::default());
        assert!(s.press(t0, PITCH, Direction::Left).is_empty());
        assert!(s.running().is_none());
    }

    #[test]
    fn command_numbers_count_up_across_packets() {
        let t0 = Instant::now();
        let mut s = MotorStreamer::new(StreamerConfig::default());
        let a = s.press(t0, PITCH, Direction::Up);
        let b = s.tick(t0 + ms(200));
        assert_eq!(a[0].cnt + 1, b[0].cnt);
        assert!(matches!(
            b[0].message,
            Message::TrimMove(TrimMove {
                trim_type: TrimType::Pitch,
                on: true,
                ..
            })
        ));
    }

    #[test]
    fn a_late_tick_reports_starvation_and_stops() {
        let t0 = Instant::now();
        let mut s = MotorStreamer::new(StreamerConfig {
            release_mode: ReleaseMode::KeyRelease,
            ..Default::default()
        });
        s.press(t0, PITCH, Direction::Up);
        let out = s.tick(t0 + ms(260));
        assert_eq!(out.len(), 1);
        assert!(matches!(
            out[0].message,
            Message::TrimMove(TrimMove { on: false, .. })
        ));
        assert_eq!(s.last_stop().unwrap().reason, StopReason::Starved);
        // The key is still down: its repeats must not start the motor again.
        assert!(s.repeat(t0 + ms(270), PITCH, Direction::Up).is_empty());
        assert!(s.running().is_none());
    }
}

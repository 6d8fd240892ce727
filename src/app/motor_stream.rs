//! The motor stream's own thread: the 4 Hz resend and the dead man's stop go out on
//! their own clock, not when the UI loop gets round to it.
//!
//! The UI loop can be late by a redraw, a slow terminal write, or a wait for the model
//! lock; none of that may stretch a gap between move messages toward the unit's
//! 250 ms. So the controller lives behind its own lock, which nothing holds while
//! drawing or doing I/O, and this thread wakes at the controller's deadline, ticks the
//! stream (no model needed) and queues what it gets on the link.
//!
//! Order on the wire is order of decision: every packet the controller gives back is
//! queued while its lock is still held, by this thread and by the page alike, so a
//! resend decided before a stop can never reach the wire after it. The queueing goes
//! through the page's [`StopGate`], which the panic hook's emergency stop closes to
//! moves: a resend this thread decided just as another thread panicked is either on
//! the wire before the hook's stop or not at all.
//!
//! One wait on the model lock remains on the way to the wire: the link's writer
//! reports each frame it wrote to the model (traffic view, capture) before taking the
//! next. The page draws without holding that lock while writing to the terminal, so
//! it is held only for microseconds; reporting from another thread would cut even
//! that, but would let the model and the capture fall behind the wire.

use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, unbounded};

use crossterm::event::KeyEvent;

use super::stop_gate::StopGate;
use super::{Wake, terminal};
use crate::audit::Origin;
use crate::control::run_state::{MotorRun, ReleaseMode, RepeatTiming};
use crate::control::{Action, Controller, KeyContext, StopReason};
use crate::model::Model;
use crate::protocol::message::{Message, Packet};

/// What a key did, its packets already queued on the link.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Handled {
    pub action: Option<Action>,
    pub notice: Option<String>,
    /// The command a command action sent (DEVICE_POWER, DEVICE_CLEAR, WIG_WAG_MODE).
    pub sent: Option<Message>,
}

/// What the page's loop needs of the controller after its tick, read under the same
/// lock as the tick.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ticked {
    pub notice: Option<String>,
    pub running: Option<MotorRun>,
    pub release_mode: ReleaseMode,
    pub repeat: RepeatTiming,
}

/// The controller and the way to the link, shared by the page and the thread.
pub struct MotorPath {
    shared: Mutex<Shared>,
    /// `None` in replay: nothing reaches a wire.
    link: Option<Arc<StopGate>>,
}

/// Everything the page and the thread share, behind one lock: each pass of either
/// loop takes it once.
struct Shared {
    controller: Controller,
    /// When the page's loop last ticked this path (real time). The model's checks
    /// (COMMUNICATION LOST, a motor fault, lost motor status) run in that tick, so a
    /// stalled loop — a terminal write blocked on a paused tty, say — must not leave
    /// this thread streaming on its own.
    heartbeat: Option<Instant>,
    /// Wakes the thread early; `None` once the thread is told to end (or never ran).
    poke: Option<Sender<()>>,
    /// The deadline the thread last read and sleeps until (`None`: until poked).
    sleeping_until: Option<Instant>,
    /// Who last acted (a key, the check): the origin the audit log gives the run's
    /// resends and its stop.
    origin: Origin,
}

impl Shared {
    /// Wakes the thread if the controller now needs it before it would wake anyway:
    /// a run started, or a key moved a deadline earlier. A deadline moved later (a
    /// resend just sent, a run stopped) costs the thread at most one early look, so
    /// a page with no run never wakes it.
    fn poke_if_earlier(&mut self) {
        let Some(d) = self.controller.next_deadline() else {
            return;
        };
        if self.sleeping_until.is_none_or(|s| d < s)
            && let Some(tx) = &self.poke
        {
            let _ = tx.send(());
            self.sleeping_until = Some(d);
        }
    }
}

/// How long the page's loop may go without ticking while a motor runs. The loop ticks
/// at least every resend period while a run is on (App::next_deadline), so this is a
/// stall, not a slow frame.
pub const LOOP_STALL: Duration = Duration::from_millis(500);

impl MotorPath {
    pub fn new(controller: Controller, link: Option<Arc<StopGate>>) -> Arc<MotorPath> {
        Arc::new(MotorPath {
            shared: Mutex::new(Shared {
                controller,
                heartbeat: None,
                poke: None,
                sleeping_until: None,
                origin: Origin::Page,
            }),
            link,
        })
    }

    fn lock(&self) -> MutexGuard<'_, Shared> {
        // A panic elsewhere while holding the lock must not also stop the motor path:
        // the stop that follows a panic goes through here.
        self.shared.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Reads the controller (or takes its notice, or a command number): nothing that
    /// sends or moves its deadline.
    pub fn with<R>(&self, f: impl FnOnce(&mut Controller) -> R) -> R {
        f(&mut self.lock().controller)
    }

    /// Runs `f` for `origin` and queues the packets it returns before letting go of
    /// the controller; returns what else `f` gives.
    pub fn act_with<R>(
        &self,
        origin: Origin,
        f: impl FnOnce(&mut Controller) -> (Vec<Packet>, R),
    ) -> R {
        let mut s = self.lock();
        s.origin = origin;
        self.act_locked(s, f)
    }

    /// The XFSp gateway's turn (`f` runs it with the controller): what it sends is
    /// the network's; the resends and the stop of the run going on are the
    /// network's only while that run is one the network asked for
    /// ([`Controller::target_running`]), not a key's it waited behind.
    pub fn act_xfsp<R>(&self, f: impl FnOnce(&mut Controller) -> (Vec<Packet>, R)) -> R {
        let mut s = self.lock();
        let (packets, r) = f(&mut s.controller);
        if s.controller.target_running().is_some() {
            s.origin = Origin::Xfsp;
        }
        self.queue(Origin::Xfsp, packets);
        s.poke_if_earlier();
        r
    }

    /// As [`MotorPath::act_with`] for whatever started the run in progress (the page losing
    /// focus, or its being hidden, stops that run).
    pub fn act_on_run(&self, f: impl FnOnce(&mut Controller) -> Vec<Packet>) {
        let s = self.lock();
        self.act_locked(s, |c| (f(c), ()))
    }

    fn act_locked<R>(
        &self,
        mut s: MutexGuard<'_, Shared>,
        f: impl FnOnce(&mut Controller) -> (Vec<Packet>, R),
    ) -> R {
        let (packets, r) = f(&mut s.controller);
        self.queue(s.origin, packets);
        s.poke_if_earlier();
        r
    }

    // ----- the controller's calls the page makes, sending inside the lock -----

    pub fn handle_key(
        &self,
        key: KeyEvent,
        ctx: &KeyContext,
        model: &Model,
        now: Instant,
    ) -> Handled {
        self.act_with(Origin::Key, |c| {
            let o = c.handle_key(key, ctx, model, now);
            let sent = o
                .action
                .as_ref()
                .filter(|a| a.is_command())
                .and_then(|_| o.packets.first().map(|p| p.message));
            (
                o.packets,
                Handled {
                    action: o.action,
                    notice: o.notice,
                    sent,
                },
            )
        })
    }

    /// A key while the page cannot be seen: see [`Controller::handle_key_hidden`].
    pub fn handle_key_hidden(&self, key: KeyEvent, ctx: &KeyContext, now: Instant) -> Handled {
        self.act_with(Origin::Key, |c| {
            let o = c.handle_key_hidden(key, ctx, now);
            (
                o.packets,
                Handled {
                    action: o.action,
                    notice: o.notice,
                    sent: None,
                },
            )
        })
    }

    /// Ends a running motor for `reason`, its stop queued (recorded with the run's
    /// origin; the audit log's stop line names the run's).
    pub fn stop(&self, now: Instant, reason: StopReason) {
        self.act_on_run(|c| c.stop(now, reason));
    }

    /// The model's verdict and the stream's clocks, after packets arrived; what the
    /// page shows of the controller afterwards, read under the same lock.
    pub fn tick(&self, model: &Model, now: Instant) -> Ticked {
        let mut s = self.lock();
        s.heartbeat = Some(Instant::now());
        let packets = s.controller.tick(model, now);
        self.queue(s.origin, packets);
        s.poke_if_earlier();
        let c = &mut s.controller;
        Ticked {
            notice: c.take_notice(),
            running: c.running(),
            release_mode: c.release_mode(),
            repeat: c.repeat_timing(),
        }
    }

    pub fn running(&self) -> Option<MotorRun> {
        self.with(|c| c.running())
    }

    pub fn take_notice(&self) -> Option<String> {
        self.with(|c| c.take_notice())
    }

    pub fn next_cnt(&self) -> u8 {
        self.with(|c| c.next_cnt())
    }

    fn queue(&self, origin: Origin, packets: Vec<Packet>) {
        if let Some(link) = &self.link {
            link.send(origin, packets);
        }
    }

    /// Whether the panic hook's emergency stop has gone out (or is going out).
    fn halted(&self) -> bool {
        terminal::panicked() || self.link.as_ref().is_some_and(|l| l.halted())
    }

    /// Starts the thread. It runs until [`MotorPath::stop_thread`].
    pub fn spawn(self: &Arc<Self>, wake: Sender<Wake>) -> Option<JoinHandle<()>> {
        let (tx, rx) = unbounded();
        self.lock().poke = Some(tx);
        let path = self.clone();
        let spawned = std::thread::Builder::new()
            .name("motor-stream".into())
            .spawn(move || path.run(&rx, &wake));
        self.started(spawned)
    }

    /// Without its thread nothing would resend a held motor's move on time, so a
    /// page whose thread did not start refuses every motor run, and says why.
    fn started(&self, spawned: std::io::Result<JoinHandle<()>>) -> Option<JoinHandle<()>> {
        match spawned {
            Ok(t) => Some(t),
            Err(e) => {
                self.stop_thread();
                self.with(|c| {
                    c.refuse_motors(format!(
                        "motors unavailable: the motor-stream thread could not start ({e})"
                    ))
                });
                None
            }
        }
    }

    /// Ends the thread (it sees the poke channel close).
    pub fn stop_thread(&self) {
        self.lock().poke.take();
    }

    /// Sleeps until the controller's own deadline (or a poke that moved it earlier),
    /// then, under one lock, ticks the stream, queues what it gives and reads the
    /// next deadline.
    fn run(&self, poke: &Receiver<()>, wake: &Sender<Wake>) {
        let mut deadline = {
            let mut s = self.lock();
            s.sleeping_until = s.controller.next_deadline();
            s.sleeping_until
        };
        loop {
            let got = match deadline {
                Some(d) => poke.recv_timeout(d.saturating_duration_since(Instant::now())),
                None => poke.recv().map_err(|_| RecvTimeoutError::Disconnected),
            };
            if got == Err(RecvTimeoutError::Disconnected) {
                return;
            }
            // Pokes that came meanwhile are answered by this one look.
            while poke.try_recv().is_ok() {}
            let now = Instant::now();
            let ended = {
                let mut s = self.lock();
                let stalled = s
                    .heartbeat
                    .is_some_and(|b| now.saturating_duration_since(b) > LOOP_STALL);
                let origin = s.origin;
                let c = &mut s.controller;
                let was_running = c.running().is_some();
                let packets = if self.halted() {
                    // The hook sent the emergency stop; never resend after it.
                    c.stop(now, StopReason::Panic)
                } else if was_running && stalled {
                    c.stop(now, StopReason::PageStalled)
                } else {
                    c.tick_stream(now)
                };
                self.queue(origin, packets);
                let ended = was_running && c.running().is_none();
                deadline = c.next_deadline();
                s.sleeping_until = deadline;
                ended
            };
            if ended {
                // The page shows the stop and its reason.
                let _ = wake.send(Wake::Motor);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The page's loop ticks the path on every frame from the unit (13 a second at
    /// rest); with no run those ticks must not wake the thread, which has nothing to
    /// do until a run starts. (That a run's start does wake it is what every motor
    /// test through the page shows: without it nothing would resend the move.)
    #[test]
    fn ticks_without_a_run_leave_the_thread_asleep() {
        let path = MotorPath::new(Controller::default(), None);
        let (tx, rx) = unbounded();
        path.lock().poke = Some(tx);
        let model = Model::new(crate::model::Source::Simulated {
            scenario: "t".into(),
        });
        let t0 = Instant::now();
        for i in 0..20 {
            let ticked = path.tick(&model, t0 + Duration::from_millis(100 * i));
            assert_eq!(ticked.running, None);
        }
        path.stop(t0, StopReason::Quit);
        assert!(rx.try_recv().is_err(), "the thread was woken for nothing");
        assert!(path.lock().heartbeat.is_some(), "the ticks were seen");
    }

    /// A page whose motor-stream thread could not start refuses every motor run
    /// (tests/control_streamer.rs shows a refused controller refusing a press), and
    /// says why at once.
    #[test]
    fn no_motor_thread_means_motors_refused_and_the_page_says_so() {
        let path = MotorPath::new(Controller::default(), None);
        let t = path.started(Err(std::io::Error::other("out of threads")));
        assert!(t.is_none());
        let why = path.with(|c| c.motors_refused().map(str::to_owned));
        let why = why.expect("motor runs refused");
        assert!(why.contains("motors unavailable"), "{why}");
        assert!(why.contains("out of threads"), "{why}");
        assert_eq!(path.take_notice(), Some(why), "said at once");
    }
}

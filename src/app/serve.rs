//! The app's loop: the one every process runs (the page on its terminal, the headless
//! check, the gateway, and tests and replay through [`App::pump_until`]).
//!
//! Each pass: tick (motor resends and dead-man checks, queries, the re-read after a
//! loss, the flows' clocks, the XFSp gateway), let the front do its part (draw, print,
//! see whether it is done), then wait for the first of the link's wake-ups, a datagram,
//! a phone's request, the front's own input, a stop asked by the OS, or the next
//! deadline. What differs between processes is only the front: what it reads, what it
//! shows, when it leaves. The stop gate, the panic path and the audit log are the
//! app's, the same for all.

use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, select};

use super::{App, Termination};

/// What a front gets from outside the app.
pub(super) enum Outside<I> {
    /// One item of its input (a terminal event, a typed line).
    Input(I),
    /// Its input ended (a closed terminal, standard input at its end): no more comes
    /// in this call.
    InputEnded,
    /// The OS asked the process to stop.
    Signal(Termination),
}

/// What a front waits on beside the app's own, and for how long.
pub(super) struct Wait<'a, I> {
    pub input: &'a Receiver<I>,
    pub terminations: &'a Receiver<Termination>,
    /// The loop returns `None` once this comes.
    pub until: Option<Instant>,
    /// The longest single wait, for a front that polls a flag (the gateway's stop).
    pub poll: Option<Duration>,
}

impl App {
    /// Runs the loop until `after_tick` or `outside` gives something to return, or
    /// until `wait.until` (then `None`).
    ///
    /// `after_tick` runs after every tick: it draws, prints, or checks whether its work
    /// is done. `outside` takes the front's input and the OS's stop requests.
    pub(super) fn serve<I, T>(
        &mut self,
        wait: Wait<'_, I>,
        mut after_tick: impl FnMut(&mut App, Instant) -> Option<T>,
        mut outside: impl FnMut(&mut App, Outside<I>) -> Option<T>,
    ) -> Option<T> {
        let xfsp = self.xfsp_incoming();
        let ended = crossbeam_channel::never();
        // An ended input is always ready: selected on again, it would spin a core.
        let mut input = wait.input;
        loop {
            let now = Instant::now();
            self.tick(now);
            if let Some(out) = after_tick(self, now) {
                return Some(out);
            }
            let now = Instant::now();
            if wait.until.is_some_and(|u| now >= u) {
                return None;
            }
            let mut deadline = self.next_deadline(now);
            if let Some(u) = wait.until {
                deadline = deadline.min(u);
            }
            if let Some(p) = wait.poll {
                deadline = deadline.min(now + p);
            }
            let phones = self.remote_requests();
            let mut got = None;
            select! {
                recv(input) -> i => got = Some(match i {
                    Ok(i) => Outside::Input(i),
                    Err(_) => {
                        input = &ended;
                        Outside::InputEnded
                    }
                }),
                recv(wait.terminations) -> t => got = t.ok().map(Outside::Signal),
                recv(self.wake_rx) -> w => if let Ok(w) = w { self.on_wake(w, Instant::now()) },
                recv(xfsp) -> d => if let Ok(d) = d { self.xfsp_receive(d) },
                recv(phones) -> r => if let Ok(r) = r { self.remote_request(r, Instant::now()) },
                default(deadline.saturating_duration_since(Instant::now())) => {}
            }
            if let Some(o) = got
                && let Some(out) = outside(self, o)
            {
                return Some(out);
            }
            // Drain what else is waiting so a burst is one tick (and one redraw).
            while let Ok(w) = self.wake_rx.try_recv() {
                self.on_wake(w, Instant::now());
            }
        }
    }

    /// For a front with no screen: nothing is ever waiting to be drawn, so the redraw
    /// deadline never wakes the loop.
    pub(super) fn no_screen(&mut self, now: Instant) {
        self.dirty = false;
        self.news_at = None;
        self.last_draw = Some(now);
    }
}

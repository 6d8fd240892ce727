//! The one way to the unit's wire for everything that can start or keep a motor
//! going, closed to moves once the panic hook's emergency stop is on it.
//!
//! The hook runs on whichever thread panicked, while the motor-stream thread, the
//! page's loop or the gateway's loop may be between deciding a resend and queueing
//! it. Were the hook to queue its stops on the link directly, that resend could land
//! on the wire after them and run the motor on. So every send and the hook's stop
//! take the same lock, and the hook marks the gate halted *before* taking it: a send
//! that got the lock first is queued before the stop; any send after it sees the mark
//! and queues no move (stops and queries still go).
//!
//! Being the one way, it is also where every command is recorded in the audit log
//! ([`crate::audit`], kept in the logbook), with the origin each caller names and
//! whether it went.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, TryLockError};
use std::time::{Duration, Instant};

use crate::audit::Origin;
use crate::control::MotorStreamer;
use crate::link::LinkHandle;
use crate::logbook::Recorder;
use crate::protocol::message::{Message, Packet};

/// How long the emergency stop waits for a send in progress to finish. Queueing a few
/// packets takes microseconds; a holder that never lets go (a panic inside a send on
/// this very thread) must not keep the stop off the wire, so after this it goes
/// anyway.
const STOP_LOCK_WAIT: Duration = Duration::from_millis(50);

pub struct StopGate {
    link: LinkHandle,
    halted: AtomicBool,
    order: Mutex<()>,
    logbook: Option<Recorder>,
}

impl StopGate {
    pub fn new(link: LinkHandle) -> StopGate {
        StopGate {
            link,
            halted: AtomicBool::new(false),
            order: Mutex::new(()),
            logbook: None,
        }
    }

    /// As [`StopGate::new`], recording every command in the `logbook`'s audit log.
    pub fn with_logbook(link: LinkHandle, logbook: Option<Recorder>) -> StopGate {
        StopGate {
            logbook,
            ..StopGate::new(link)
        }
    }

    /// Queues one packet and records it (if it is a command) with how it went.
    fn put(&self, origin: Origin, p: Packet, refused: Option<&str>) {
        let result = match refused {
            Some(why) => Err(why),
            None => self
                .link
                .send(p)
                .map_err(|_| "the link to the unit is closed"),
        };
        if let Some(book) = &self.logbook {
            book.command(origin, &p, result);
        }
    }

    /// Queues `packets` in order, or, once halted, all of them but the moves that
    /// would start or keep a motor running. A closed link has already been reported.
    /// `origin` is who asked, for the audit log.
    pub fn send(&self, origin: Origin, packets: impl IntoIterator<Item = Packet>) {
        let _turn = self.order.lock().unwrap_or_else(|p| p.into_inner());
        let halted = self.halted();
        for p in packets {
            let refused = (halted && runs_a_motor(&p))
                .then_some("the emergency stop has gone out: no motor moves after it");
            self.put(origin, p, refused);
        }
    }

    /// The panic hook's stop: every motor's stop message, after whatever send was in
    /// progress and before any later one (which can no longer carry a move).
    pub fn emergency_stop(&self) {
        self.halted.store(true, Ordering::SeqCst);
        let until = Instant::now() + STOP_LOCK_WAIT;
        let _turn = loop {
            match self.order.try_lock() {
                Ok(turn) => break Some(turn),
                Err(TryLockError::Poisoned(p)) => break Some(p.into_inner()),
                Err(TryLockError::WouldBlock) if Instant::now() < until => {
                    std::thread::sleep(Duration::from_millis(1));
                }
                Err(TryLockError::WouldBlock) => break None,
            }
        };
        for p in MotorStreamer::emergency_stop_packets() {
            self.put(Origin::Panic, p, None);
        }
    }

    /// Whether the emergency stop has gone out: nothing may move a motor again.
    pub fn halted(&self) -> bool {
        self.halted.load(Ordering::SeqCst)
    }
}

/// A TRIM_MOVE or FLAP_MOVE with its on flag set (ICD Tables 30, 31): a motor starts
/// or keeps running.
fn runs_a_motor(p: &Packet) -> bool {
    match &p.message {
        Message::TrimMove(m) => m.on,
        Message::FlapMove(m) => m.on,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    use crate::control::streamer::move_packet;
    use crate::control::{Direction, RESEND_PERIOD};
    use crate::link::{Link, LinkEvent, duplex_pipe, pipe_connector};
    use crate::model::{Motor, TrimKind};
    use crate::protocol::message::DeviceSpecQuery;

    type Sent = Arc<Mutex<Vec<Packet>>>;

    /// A connected link over a pipe nobody reads, recording each packet the writer
    /// puts out.
    fn link() -> (Link, Sent, crate::link::PipeEnd) {
        let (ours, theirs) = duplex_pipe(Duration::from_millis(20));
        let sent: Sent = Arc::default();
        let log = sent.clone();
        let (up_tx, up) = crossbeam_channel::unbounded();
        let link = Link::start(pipe_connector(ours, "test"), move |e| match e {
            LinkEvent::Tx {
                packet: Some(p), ..
            } => log.lock().unwrap().push(p),
            LinkEvent::Connected { .. } => {
                let _ = up_tx.send(());
            }
            _ => {}
        });
        up.recv_timeout(Duration::from_secs(2)).expect("connected");
        (link, sent, theirs)
    }

    fn wait_for(sent: &Sent, n: usize) -> Vec<Packet> {
        let until = Instant::now() + Duration::from_secs(2);
        while sent.lock().unwrap().len() < n && Instant::now() < until {
            std::thread::sleep(Duration::from_millis(2));
        }
        std::thread::sleep(RESEND_PERIOD / 10);
        sent.lock().unwrap().clone()
    }

    fn pitch_up(on: bool) -> Packet {
        move_packet(7, Motor::Trim(TrimKind::Pitch), Direction::Up, on)
    }

    /// The race the hook used to lose: a resend decided just before the panic is
    /// queued just after the hook's stop. It must not reach the wire; a stop and a
    /// query sent then still do.
    #[test]
    fn nothing_sent_after_the_emergency_stop_moves_a_motor() {
        let (link, sent, _unit) = link();
        let gate = StopGate::new(link.handle());
        gate.send(Origin::Key, [pitch_up(true)]);
        let resend = pitch_up(true);
        gate.emergency_stop();
        assert!(gate.halted());
        let query = Packet::request(8, DeviceSpecQuery { device_id: 9 });
        gate.send(Origin::Key, [resend, pitch_up(false), query]);
        let wire = wait_for(&sent, 6);
        link.shutdown();
        let mut want = vec![pitch_up(true)];
        want.extend(MotorStreamer::emergency_stop_packets());
        want.extend([pitch_up(false), query]);
        assert_eq!(wire, want);
    }

    /// A send in progress when the hook runs finishes first: the stop is queued
    /// after it, never in the middle of it or before it.
    #[test]
    fn the_emergency_stop_waits_for_a_send_in_progress() {
        let (link, sent, _unit) = link();
        let gate = Arc::new(StopGate::new(link.handle()));
        let turn = gate.order.lock().unwrap();
        let hook = {
            let gate = gate.clone();
            std::thread::spawn(move || gate.emergency_stop())
        };
        while !gate.halted() {
            std::thread::yield_now();
        }
        // What the holder decided before the hook goes out, then the hook's stop.
        let _ = gate.link.send(pitch_up(true));
        std::thread::sleep(Duration::from_millis(10));
        drop(turn);
        hook.join().unwrap();
        let wire = wait_for(&sent, 4);
        link.shutdown();
        let mut want = vec![pitch_up(true)];
        want.extend(MotorStreamer::emergency_stop_packets());
        assert_eq!(wire, want);
    }
}

//! Asking the unit something: send, wait for the answer, send again when it does not
//! come in time, give up after a few tries. The one engine of every request to the
//! unit: the page's flows drive it on their caller's clock (the setup screens'
//! writes and diagnostics, the installation check), the blocking client of the
//! commands (`link::request`: backup, restore, `config`) and the flash updater
//! on the real one.
//!
//! Pure: nothing here reads a clock, blocks or touches the link. A caller keeps a
//! [`Try`] per request and asks it, at `now`, what to do.

use std::time::{Duration, Instant};

/// How long to wait for a SPEC_ACK or a query's answer before sending again. The unit
/// answers within a few frames at 57600 baud; a second is generous, still quick to
/// give up, and keeps a silent unit from looking like a hang ([`TRIES`] = 3 s).
pub const ANSWER_TIMEOUT: Duration = Duration::from_secs(1);
/// Sends of one request before "no answer", the first included.
pub const TRIES: u8 = 3;
/// EEPROM_ERASE rewrites the whole EEPROM of an ATmega2560 before it answers (4 KiB
/// at about 3.4 ms a byte is ~14 s), so its answer may take far longer than any
/// other's. It is sent once: a second erase while the first runs would gain nothing.
pub const ERASE_TIMEOUT: Duration = Duration::from_secs(20);

/// One request in flight: which send this is and when it went out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Try {
    pub attempt: u8,
    pub sent_at: Instant,
    timeout: Duration,
    tries: u8,
}

/// What a request needs now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The answer arrived.
    Answered,
    /// Nothing yet, and it is not time to send again.
    Waiting,
    /// Send the request again now (the try has moved on to the next attempt).
    Resend,
    /// Every try went unanswered.
    NoAnswer,
}

impl Try {
    /// The first send, at `now`, with [`ANSWER_TIMEOUT`] and [`TRIES`].
    pub fn first(now: Instant) -> Try {
        Try::with(now, ANSWER_TIMEOUT, TRIES)
    }

    /// The first send with a timeout and a number of tries of the caller's own (0 is
    /// taken as 1).
    pub fn with(now: Instant, timeout: Duration, tries: u8) -> Try {
        Try {
            attempt: 1,
            sent_at: now,
            timeout,
            tries: tries.max(1),
        }
    }

    /// The sends allowed in all.
    pub fn of(&self) -> u8 {
        self.tries
    }

    pub fn timeout(&self) -> Duration {
        self.timeout
    }

    /// When this try times out.
    pub fn deadline(&self) -> Instant {
        self.sent_at + self.timeout
    }

    /// Judges the request at `now`; `answered` says whether the answer to it (heard
    /// at or after [`sent_at`](Self::sent_at) of any try) is in.
    pub fn judge(&mut self, answered: bool, now: Instant) -> Verdict {
        if answered {
            Verdict::Answered
        } else if now < self.deadline() {
            Verdict::Waiting
        } else {
            self.spent(now)
        }
    }

    /// This send is over without an answer: its time ran out, or something showed
    /// before then that it cannot be answered (a garbled answer, the link went
    /// down). [`Verdict::Resend`] at `now` while tries are left, else
    /// [`Verdict::NoAnswer`].
    pub fn spent(&mut self, now: Instant) -> Verdict {
        if self.attempt < self.tries {
            self.attempt += 1;
            self.sent_at = now;
            Verdict::Resend
        } else {
            Verdict::NoAnswer
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    #[test]
    fn a_try_waits_resends_twice_then_gives_up() {
        let t0 = Instant::now();
        let mut t = Try::first(t0);
        assert_eq!(t.judge(false, ms(t0, 999)), Verdict::Waiting);
        assert_eq!(t.judge(false, ms(t0, 1000)), Verdict::Resend);
        assert_eq!((t.attempt, t.sent_at), (2, ms(t0, 1000)));
        assert_eq!(t.judge(false, ms(t0, 2000)), Verdict::Resend);
        assert_eq!(t.judge(false, ms(t0, 2999)), Verdict::Waiting);
        assert_eq!(t.judge(false, ms(t0, 3000)), Verdict::NoAnswer);
        let mut t = Try::first(t0);
        assert_eq!(t.judge(true, ms(t0, 5000)), Verdict::Answered);
    }

    /// A send known lost early (a garbled answer, a link gone) is sent again at once,
    /// with the whole timeout from then, and counts against the same tries.
    #[test]
    fn a_send_spent_early_goes_again_at_once_and_counts() {
        let t0 = Instant::now();
        let mut t = Try::with(t0, Duration::from_millis(500), 2);
        assert_eq!(t.spent(ms(t0, 10)), Verdict::Resend);
        assert_eq!((t.attempt, t.deadline()), (2, ms(t0, 510)));
        assert_eq!(t.judge(false, ms(t0, 509)), Verdict::Waiting);
        assert_eq!(t.spent(ms(t0, 100)), Verdict::NoAnswer, "both tries spent");
        assert_eq!(t.attempt, 2);
    }

    #[test]
    fn no_tries_is_one_and_one_is_never_resent() {
        let t0 = Instant::now();
        let mut t = Try::with(t0, ANSWER_TIMEOUT, 0);
        assert_eq!(t.of(), 1);
        assert_eq!(t.judge(false, t0 + ANSWER_TIMEOUT), Verdict::NoAnswer);
        assert_eq!(t.attempt, 1);
    }
}

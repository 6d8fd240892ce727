//! Pairing: a one-time six-digit code shown on the page, sessions for the phones
//! that gave it, and a lock after too many wrong codes. On the caller's clock, so
//! tests drive the lock on a fake one.
//!
//! - The code and every session token come from the OS's random source
//!   (`getrandom`); nothing here can be guessed from the time or a counter.
//! - A code pairs one phone, then a fresh one takes its place.
//! - [`MAX_WRONG`] wrong codes in a row lock pairing for [`LOCK_FOR`]; while locked
//!   even the right code is refused (a guesser must not learn it was right). A right
//!   code resets the count.
//! - A session is 32 random bytes in hex. [`Pairing::revoke_all`] ends every one.

use std::collections::HashSet;
use std::time::{Duration, Instant};

/// Wrong codes in a row before pairing locks.
pub const MAX_WRONG: u32 = 5;
/// How long pairing stays locked.
pub const LOCK_FOR: Duration = Duration::from_secs(60);

/// What a pairing attempt came to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PairResult {
    /// Paired: the new session's token.
    Paired(String),
    Wrong,
    /// Locked: whole seconds left, at least 1.
    Locked(u64),
}

#[derive(Debug)]
pub struct Pairing {
    code: String,
    wrong: u32,
    locked_until: Option<Instant>,
    sessions: HashSet<String>,
}

/// `n` bytes from the OS's random source. A system without one cannot pair safely,
/// so it is refused rather than filled with something guessable.
fn random<const N: usize>() -> Result<[u8; N], getrandom::Error> {
    let mut b = [0u8; N];
    getrandom::fill(&mut b)?;
    Ok(b)
}

/// A fresh six-digit code, uniform over 000000..=999999 (rejection sampling, so no
/// code is likelier than another).
fn fresh_code() -> Result<String, getrandom::Error> {
    loop {
        let n = u32::from_le_bytes(random::<4>()?);
        // 4 294 000 000 is the largest multiple of 10^6 below 2^32.
        if n < 4_294_000_000 {
            return Ok(format!("{:06}", n % 1_000_000));
        }
    }
}

impl Pairing {
    pub fn new() -> Result<Pairing, getrandom::Error> {
        Ok(Pairing {
            code: fresh_code()?,
            wrong: 0,
            locked_until: None,
            sessions: HashSet::new(),
        })
    }

    /// The code the page shows now.
    pub fn code(&self) -> &str {
        &self.code
    }

    /// A phone gives `code` at `now`.
    pub fn pair(&mut self, code: &str, now: Instant) -> PairResult {
        if let Some(until) = self.locked_until {
            if now < until {
                let left = until - now;
                return PairResult::Locked(left.as_secs() + u64::from(left.subsec_nanos() > 0));
            }
            self.locked_until = None;
            self.wrong = 0;
        }
        if !constant_time_eq(code.trim().as_bytes(), self.code.as_bytes()) {
            self.wrong += 1;
            if self.wrong >= MAX_WRONG {
                self.locked_until = Some(now + LOCK_FOR);
            }
            return PairResult::Wrong;
        }
        let token = match (random::<32>(), fresh_code()) {
            (Ok(bytes), Ok(next)) => {
                self.code = next;
                hex(&bytes)
            }
            // No random source now: refuse, as a wrong code, rather than pair weakly.
            _ => return PairResult::Wrong,
        };
        self.wrong = 0;
        self.sessions.insert(token.clone());
        PairResult::Paired(token)
    }

    pub fn is_session(&self, token: &str) -> bool {
        self.sessions.contains(token)
    }

    /// Ends one session (`/api/logout`).
    pub fn end(&mut self, token: &str) {
        self.sessions.remove(token);
    }

    /// Ends every session (the page's revoke key).
    pub fn revoke_all(&mut self) {
        self.sessions.clear();
    }

    pub fn paired(&self) -> usize {
        self.sessions.len()
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Compares without stopping at the first difference, so the time a wrong code
/// takes says nothing about how much of it was right.
fn constant_time_eq(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wrong_of(p: &Pairing) -> String {
        let c: u32 = p.code().parse().unwrap();
        format!("{:06}", (c + 1) % 1_000_000)
    }

    #[test]
    fn a_code_is_six_digits_and_pairs_once() {
        let mut p = Pairing::new().unwrap();
        let now = Instant::now();
        let code = p.code().to_string();
        assert_eq!(code.len(), 6);
        assert!(code.bytes().all(|b| b.is_ascii_digit()));
        let PairResult::Paired(token) = p.pair(&code, now) else {
            panic!("the right code did not pair");
        };
        assert_eq!(token.len(), 64);
        assert!(p.is_session(&token));
        assert_eq!(p.paired(), 1);
        assert_ne!(p.code(), code, "a used code is replaced");
        assert_eq!(p.pair(&code, now), PairResult::Wrong, "a code works once");
    }

    #[test]
    fn five_wrong_in_a_row_lock_for_sixty_seconds_on_the_callers_clock() {
        let mut p = Pairing::new().unwrap();
        let t0 = Instant::now();
        for _ in 0..MAX_WRONG {
            assert_eq!(p.pair(&wrong_of(&p), t0), PairResult::Wrong);
        }
        let right = p.code().to_string();
        assert_eq!(p.pair(&right, t0), PairResult::Locked(60));
        assert_eq!(
            p.pair(&right, t0 + Duration::from_millis(20_500)),
            PairResult::Locked(40)
        );
        assert_eq!(p.paired(), 0);
        assert!(matches!(
            p.pair(&right, t0 + LOCK_FOR),
            PairResult::Paired(_)
        ));
    }

    #[test]
    fn a_right_code_resets_the_count_of_wrong_ones() {
        let mut p = Pairing::new().unwrap();
        let now = Instant::now();
        for _ in 0..MAX_WRONG - 1 {
            p.pair(&wrong_of(&p), now);
        }
        let right = p.code().to_string();
        assert!(matches!(p.pair(&right, now), PairResult::Paired(_)));
        assert_eq!(p.pair(&wrong_of(&p), now), PairResult::Wrong);
        let right = p.code().to_string();
        assert!(matches!(p.pair(&right, now), PairResult::Paired(_)));
    }

    #[test]
    fn revoke_ends_every_session() {
        let mut p = Pairing::new().unwrap();
        let now = Instant::now();
        let c = p.code().to_string();
        let PairResult::Paired(a) = p.pair(&c, now) else {
            panic!()
        };
        let c = p.code().to_string();
        let PairResult::Paired(b) = p.pair(&c, now) else {
            panic!()
        };
        assert_ne!(a, b);
        assert_eq!(p.paired(), 2);
        p.end(&a);
        assert!(!p.is_session(&a) && p.is_session(&b));
        p.revoke_all();
        assert!(!p.is_session(&b));
        assert_eq!(p.paired(), 0);
    }
}

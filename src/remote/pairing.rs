//! Pairing: an offer shown on the page, sessions for the phones that took
//! it, and a lock after too many wrong attempts. On the caller's clocks, so tests
//! drive the lock and the verifier on fake ones.
//!
//! The offer holds two secrets, both from the OS's random source (`getrandom`), and
//! neither ever crosses the network:
//! - the QR code's key: [`KEY_BYTES`] random bytes, in the URL's fragment
//!   (`http://host:port/#k=…`, base64url), which a browser never sends;
//! - for a phone without a camera, [`WORDS`] words from the BIP-39 English list
//!   (2048 words, 11 bits each), typed; the key is then [`typed_key`] of them.
//!
//! The phone proves it holds one by signing `POST /api/pair` with it
//! ([`super::signing`]; session "" and counter 0, as no session exists yet). The
//! session that follows is signed with the same key, so it stays as strong as the
//! secret it came from.
//!
//! Decision (typed words): a signed request lets a listener test guesses offline, as
//! fast as its hardware computes HMACs. Six digits (20 bits) fall in a moment; five
//! BIP-39 words are 55 bits, about 3.6·10^16 guesses, some forty days for a rig doing
//! 10^10 HMACs a second, against a session that lasts a walk-around. They are
//! typed in about thirty letters, and BIP-39's words were chosen to be told apart
//! (unique in their first four letters). Still weaker than the QR code's 128 bits,
//! so a phone paired by typed words is marked as such on the laptop and on the phone.
//!
//! - An offer pairs one phone, then a fresh one takes its place.
//! - [`MAX_WRONG`] wrong attempts in a row lock pairing for [`LOCK_FOR`]; while locked
//!   even a right one is refused (a guesser must not learn it was right). A right one
//!   resets the count.
//! - A session's id is 16 random bytes in hex: public, it names the key.
//!   [`Pairing::revoke_all`] ends every one.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use super::signing::{self, BadSignature, Claim, Request, Verifier};

/// Wrong attempts in a row before pairing locks.
pub const MAX_WRONG: u32 = 5;
/// How long pairing stays locked.
pub const LOCK_FOR: Duration = Duration::from_secs(60);
/// The QR code's key: 128 bits.
pub const KEY_BYTES: usize = 16;
/// Words typed instead of scanning: 55 bits.
pub const WORDS: usize = 5;

/// How a phone was paired.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum How {
    /// By the QR code's key (128 bits).
    Scanned,
    /// By typed words (55 bits): weaker, and shown as such.
    Typed,
}

/// What a pairing attempt came to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PairResult {
    /// Paired: the new session's id, and how.
    Paired {
        session: String,
        how: How,
    },
    Wrong,
    /// Locked: whole seconds left, at least 1.
    Locked(u64),
}

/// Why a session's request was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Denied {
    /// No such session (never paired, ended or revoked).
    NotPaired,
    Signature(BadSignature),
}

#[derive(Debug)]
struct Offer {
    key: [u8; KEY_BYTES],
    words: String,
    typed: [u8; 32],
}

impl Offer {
    fn fresh() -> Result<Offer, getrandom::Error> {
        let key = random::<KEY_BYTES>()?;
        let list = bip39::Language::English.word_list();
        let mut words = Vec::with_capacity(WORDS);
        for _ in 0..WORDS {
            // 2048 divides 2^16: the low 11 bits of a random u16 are uniform.
            let n = u16::from_le_bytes(random::<2>()?);
            words.push(list[usize::from(n & 0x7ff)]);
        }
        let words = words.join(" ");
        let typed = typed_key(&words);
        Ok(Offer { key, words, typed })
    }
}

#[derive(Debug)]
struct Session {
    verifier: Verifier,
    how: How,
}

#[derive(Debug)]
pub struct Pairing {
    offer: Offer,
    wrong: u32,
    locked_until: Option<Instant>,
    sessions: HashMap<String, Session>,
}

/// `N` bytes from the OS's random source. A system without one cannot pair safely,
/// so it is refused rather than filled with something guessable.
fn random<const N: usize>() -> Result<[u8; N], getrandom::Error> {
    let mut b = [0u8; N];
    getrandom::fill(&mut b)?;
    Ok(b)
}

/// The words as the key is made from them: lower case, one space between, anything
/// but letters a separator. The phone's page does the same before hashing.
pub fn normalize_words(typed: &str) -> String {
    typed
        .split(|c: char| !c.is_ascii_alphabetic())
        .filter(|w| !w.is_empty())
        .map(str::to_ascii_lowercase)
        .collect::<Vec<_>>()
        .join(" ")
}

/// The key typed words stand for: SHA-256 of a tag and the words, normalized.
pub fn typed_key(words: &str) -> [u8; 32] {
    signing::sha256(format!("vpx-efis typed pairing\n{}", normalize_words(words)).as_bytes())
}

/// base64url without padding (RFC 4648 §5): the key as the URL's fragment holds it.
pub fn base64url(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, b)| n | u32::from(*b) << (16 - 8 * i));
        for i in 0..=chunk.len() {
            out.push(A[(n >> (18 - 6 * i) & 63) as usize] as char);
        }
    }
    out
}

impl Pairing {
    pub fn new() -> Result<Pairing, getrandom::Error> {
        Ok(Pairing {
            offer: Offer::fresh()?,
            wrong: 0,
            locked_until: None,
            sessions: HashMap::new(),
        })
    }

    /// The QR code's key, base64url, for the URL's fragment.
    pub fn key(&self) -> String {
        base64url(&self.offer.key)
    }

    /// The words a phone without a camera types.
    pub fn words(&self) -> &str {
        &self.offer.words
    }

    /// A phone sends `POST /api/pair` with `body`, signed as `claim`, at `now`.
    pub fn pair(&mut self, claim: &Claim, body: &[u8], now: Instant) -> PairResult {
        if let Some(until) = self.locked_until {
            if now < until {
                let left = until - now;
                return PairResult::Locked(left.as_secs() + u64::from(left.subsec_nanos() > 0));
            }
            self.locked_until = None;
            self.wrong = 0;
        }
        let signed_by = |key: &[u8]| {
            claim.session.is_empty()
                && claim.counter == 0
                && signing::check_mac(key, claim, Request::new("POST", "/api/pair", body)).is_ok()
        };
        // Both are checked whatever the first gave, so the time taken says nothing.
        let (scanned, typed) = (signed_by(&self.offer.key), signed_by(&self.offer.typed));
        let (key, how) = match (scanned, typed) {
            (true, _) => (self.offer.key.to_vec(), How::Scanned),
            (false, true) => (self.offer.typed.to_vec(), How::Typed),
            (false, false) => {
                self.wrong += 1;
                if self.wrong >= MAX_WRONG {
                    self.locked_until = Some(now + LOCK_FOR);
                }
                return PairResult::Wrong;
            }
        };
        let (session, next) = match (random::<16>(), Offer::fresh()) {
            (Ok(id), Ok(next)) => (signing::hex(&id), next),
            // No random source now: refuse, as a wrong attempt, rather than pair weakly.
            _ => return PairResult::Wrong,
        };
        self.offer = next;
        self.wrong = 0;
        self.sessions.insert(
            session.clone(),
            Session {
                verifier: Verifier::new(&key),
                how,
            },
        );
        PairResult::Paired { session, how }
    }

    /// Checks a session's signed request at `now_ms` (the laptop's clock).
    pub fn verify(&mut self, claim: &Claim, req: Request, now_ms: u64) -> Result<How, Denied> {
        let s = self
            .sessions
            .get_mut(&claim.session)
            .ok_or(Denied::NotPaired)?;
        s.verifier
            .verify(claim, req, now_ms)
            .map_err(Denied::Signature)?;
        Ok(s.how)
    }

    pub fn is_session(&self, id: &str) -> bool {
        self.sessions.contains_key(id)
    }

    /// Ends one session (`/api/logout`).
    pub fn end(&mut self, id: &str) {
        self.sessions.remove(id);
    }

    /// Ends every session (the page's revoke key).
    pub fn revoke_all(&mut self) {
        self.sessions.clear();
    }

    pub fn paired(&self) -> usize {
        self.sessions.len()
    }

    /// Phones paired by typed words, the weaker way.
    pub fn typed(&self) -> usize {
        self.sessions
            .values()
            .filter(|s| s.how == How::Typed)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair_claim(key: &[u8], body: &[u8]) -> Claim {
        Claim {
            session: String::new(),
            counter: 0,
            time_ms: 0,
            mac: signing::sign(key, "", 0, 0, Request::new("POST", "/api/pair", body)),
        }
    }

    fn qr_key(p: &Pairing) -> [u8; KEY_BYTES] {
        p.offer.key
    }

    #[test]
    fn base64url_matches_rfc_4648_vectors() {
        // RFC 4648 §10 ("f", "fo", "foo", "foob", "fooba", "foobar"), unpadded, and a
        // byte whose encoding differs between base64 and base64url.
        let got: Vec<String> = ["f", "fo", "foo", "foob", "fooba", "foobar"]
            .iter()
            .map(|s| base64url(s.as_bytes()))
            .collect();
        assert_eq!(got, ["Zg", "Zm8", "Zm9v", "Zm9vYg", "Zm9vYmE", "Zm9vYmFy"]);
        assert_eq!(base64url(&[0xfb, 0xff]), "-_8");
        assert_eq!(base64url(&[0u8; KEY_BYTES]).len(), 22);
    }

    #[test]
    fn the_qr_key_pairs_once_and_the_session_is_signed_with_it() {
        let mut p = Pairing::new().unwrap();
        let now = Instant::now();
        let key = qr_key(&p);
        let words = p.words().to_string();
        assert_eq!(words.split(' ').count(), WORDS);
        let c = pair_claim(&key, b"");
        let PairResult::Paired { session, how } = p.pair(&c, b"", now) else {
            panic!("the QR key did not pair");
        };
        assert_eq!(how, How::Scanned);
        assert_eq!(session.len(), 32);
        assert_eq!(p.paired(), 1);
        assert_eq!(p.typed(), 0);
        assert_ne!(qr_key(&p), key, "a used key is replaced");
        assert_ne!(p.words(), words, "and the words with it");
        assert_eq!(
            p.pair(&c, b"", now),
            PairResult::Wrong,
            "an offer pairs once"
        );
        let claim = Claim {
            session: session.clone(),
            counter: 1,
            time_ms: 100,
            mac: signing::sign(
                &key,
                &session,
                1,
                100,
                Request::new("GET", "/api/state", b""),
            ),
        };
        assert_eq!(
            p.verify(&claim, Request::new("GET", "/api/state", b""), 150),
            Ok(How::Scanned)
        );
        let mut other = claim.clone();
        other.session = "0".repeat(32);
        assert_eq!(
            p.verify(&other, Request::new("GET", "/api/state", b""), 150),
            Err(Denied::NotPaired)
        );
    }

    #[test]
    fn typed_words_pair_however_they_are_typed_and_are_marked() {
        let mut p = Pairing::new().unwrap();
        let typed = format!("  {}  ", p.words().to_uppercase().replace(' ', " ,  "));
        let key = typed_key(&typed);
        let PairResult::Paired { how, .. } = p.pair(&pair_claim(&key, b""), b"", Instant::now())
        else {
            panic!("typed words did not pair");
        };
        assert_eq!(how, How::Typed);
        assert_eq!(p.typed(), 1);
    }

    #[test]
    fn five_wrong_in_a_row_lock_for_sixty_seconds_on_the_callers_clock() {
        let mut p = Pairing::new().unwrap();
        let t0 = Instant::now();
        for _ in 0..MAX_WRONG {
            assert_eq!(
                p.pair(&pair_claim(b"a guess", b""), b"", t0),
                PairResult::Wrong
            );
        }
        let right = pair_claim(&qr_key(&p), b"");
        assert_eq!(p.pair(&right, b"", t0), PairResult::Locked(60));
        assert_eq!(
            p.pair(&right, b"", t0 + Duration::from_millis(20_500)),
            PairResult::Locked(40)
        );
        assert_eq!(p.paired(), 0);
        assert!(matches!(
            p.pair(&right, b"", t0 + LOCK_FOR),
            PairResult::Paired { .. }
        ));
    }

    #[test]
    fn a_right_key_resets_the_count_and_revoke_ends_every_session() {
        let mut p = Pairing::new().unwrap();
        let now = Instant::now();
        for _ in 0..MAX_WRONG - 1 {
            p.pair(&pair_claim(b"a guess", b""), b"", now);
        }
        let right = pair_claim(&qr_key(&p), b"");
        let PairResult::Paired { session: a, .. } = p.pair(&right, b"", now) else {
            panic!()
        };
        assert_eq!(
            p.pair(&pair_claim(b"a guess", b""), b"", now),
            PairResult::Wrong
        );
        let right = pair_claim(&qr_key(&p), b"");
        let PairResult::Paired { session: b, .. } = p.pair(&right, b"", now) else {
            panic!()
        };
        assert_ne!(a, b);
        assert_eq!(p.paired(), 2);
        p.end(&a);
        assert!(!p.is_session(&a) && p.is_session(&b));
        p.revoke_all();
        assert_eq!(p.paired(), 0);
    }
}

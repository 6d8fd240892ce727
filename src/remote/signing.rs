//! Signed requests: what a listener on the hangar's WiFi sees must not let
//! it act.
//!
//! The phone holds a key that never crossed the network (the QR code's URL carries it
//! in its fragment, which a browser never sends; or it is derived from typed words).
//! Every request it makes carries four headers:
//!
//! - `X-Vpx-Session`: the session's id (public: a listener sees it);
//! - `X-Vpx-Counter`: a number that only grows, per session;
//! - `X-Vpx-Time`: the laptop's clock as the phone reckons it, in ms since the remote
//!   started (every answer carries `X-Vpx-Now`, so the phone's clock does not matter);
//! - `X-Vpx-Mac`: HMAC-SHA-256 (RFC 2104, FIPS 180-4) under the key, in lowercase
//!   hex, of [`canonical`]: the session, the counter, the time, the method, the path
//!   and the body.
//!
//! The server refuses, before anything reaches a handler: a MAC that is not exactly 64
//! hex digits (a truncated one), a MAC that does not match (compared in constant time
//! by `hmac`'s `verify_slice`), a request more than [`MAX_AGE`] old or more than
//! [`MAX_AHEAD`] ahead of the laptop's clock, and a counter it has seen. Counters
//! are checked with the sliding window of IPsec's anti-replay service (RFC 4303
//! §3.4.3, [`REPLAY_WINDOW`]), so that the phone's requests that cross on the
//! network (a renewal and its stop, the event stream and a tap) are not refused for
//! arriving out of order, while none is ever taken twice.
//!
//! Decision (MAX_AGE): 5 s. A request is signed the moment it is sent and arrives in
//! milliseconds on a LAN; a phone's request held up for seconds on a bad WiFi is
//! better refused than carried out late (a tap on a switch seconds ago is not what
//! the person wants now), and the counter already refuses any replay however fresh.
//! The clock is the laptop's, so only the network's delay and the phone's estimate of
//! the offset (within one round trip) count against it.

use std::fmt::Write as _;
use std::time::Duration;

use hmac::{Hmac, Mac};
use sha2::{Digest, Sha256};

/// The oldest a request may be when it arrives.
pub const MAX_AGE: Duration = Duration::from_secs(5);
/// How far ahead of the laptop's clock a request may claim to be: the phone's
/// estimate of the laptop's clock is off by at most a round trip.
pub const MAX_AHEAD: Duration = Duration::from_secs(2);
/// Counters below the highest seen by this many or more are refused outright; those
/// within it are taken once each (RFC 4303 §3.4.3 uses 32 or more; 64 is one word).
pub const REPLAY_WINDOW: u64 = 64;
/// The MAC's length in hex digits: all of HMAC-SHA-256's 32 bytes. A truncated MAC is
/// refused (RFC 2104 §5 allows truncation; we do not).
pub const MAC_HEX: usize = 64;

pub const H_SESSION: &str = "x-vpx-session";
pub const H_COUNTER: &str = "x-vpx-counter";
pub const H_TIME: &str = "x-vpx-time";
pub const H_MAC: &str = "x-vpx-mac";
/// On every answer: the laptop's clock (ms since the remote started).
pub const H_NOW: &str = "x-vpx-now";

/// What the phone claims about a request, read from its headers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Claim {
    pub session: String,
    pub counter: u64,
    pub time_ms: u64,
    pub mac: String,
}

/// Why a signed request was refused, in the words the phone gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum BadSignature {
    #[error("unsigned or malformed signature")]
    Malformed,
    #[error("bad signature")]
    BadMac,
    #[error("stale request")]
    Stale,
    #[error("request from the future")]
    Ahead,
    #[error("replayed counter")]
    Replayed,
}

/// The request a MAC covers besides the claim's session, counter and time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request<'a> {
    pub method: &'a str,
    /// As sent, query included.
    pub path: &'a str,
    pub body: &'a [u8],
}

impl<'a> Request<'a> {
    pub fn new(method: &'a str, path: &'a str, body: &'a [u8]) -> Request<'a> {
        Request { method, path, body }
    }
}

/// The bytes the MAC covers: a version tag, then one field a line, then the body.
/// The method is upper case.
pub fn canonical(session: &str, counter: u64, time_ms: u64, req: Request) -> Vec<u8> {
    let mut out = format!(
        "vpx-efis/1\n{session}\n{counter}\n{time_ms}\n{}\n{}\n",
        req.method.to_ascii_uppercase(),
        req.path
    )
    .into_bytes();
    out.extend_from_slice(req.body);
    out
}

fn hmac(key: &[u8]) -> Hmac<Sha256> {
    // HMAC takes a key of any length (RFC 2104 §2: a long one is hashed first), so
    // `new_from_slice` cannot fail for it.
    match <Hmac<Sha256> as Mac>::new_from_slice(key) {
        Ok(m) => m,
        Err(_) => unreachable!("HMAC takes a key of any length"),
    }
}

/// HMAC-SHA-256 of `message` under `key`.
pub fn hmac_sha256(key: &[u8], message: &[u8]) -> [u8; 32] {
    let mut m = hmac(key);
    m.update(message);
    m.finalize().into_bytes().into()
}

/// SHA-256 of `data`.
pub fn sha256(data: &[u8]) -> [u8; 32] {
    Sha256::digest(data).into()
}

/// The MAC a phone sends for a request, in lowercase hex.
pub fn sign(key: &[u8], session: &str, counter: u64, time_ms: u64, req: Request) -> String {
    hex(&hmac_sha256(
        key,
        &canonical(session, counter, time_ms, req),
    ))
}

pub fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 2);
    for b in bytes {
        let _ = write!(s, "{b:02x}");
    }
    s
}

fn unhex(s: &str) -> Option<Vec<u8>> {
    if !s.len().is_multiple_of(2) || !s.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&s[i..i + 2], 16).ok())
        .collect()
}

/// Checks only the MAC: exactly [`MAC_HEX`] hex digits, equal in constant time.
pub fn check_mac(key: &[u8], claim: &Claim, req: Request) -> Result<(), BadSignature> {
    if claim.mac.len() != MAC_HEX {
        return Err(BadSignature::Malformed);
    }
    let tag = unhex(&claim.mac).ok_or(BadSignature::Malformed)?;
    let mut m = hmac(key);
    m.update(&canonical(
        &claim.session,
        claim.counter,
        claim.time_ms,
        req,
    ));
    m.verify_slice(&tag).map_err(|_| BadSignature::BadMac)
}

/// The counters a session has taken: the highest, and which of the
/// [`REPLAY_WINDOW`] below it (bit `n`: highest − n).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Replay {
    highest: u64,
    seen: u64,
}

impl Replay {
    /// Whether `counter` would be taken (0 never is: counters start at 1).
    pub fn fresh(&self, counter: u64) -> bool {
        if counter > self.highest {
            return true;
        }
        let back = self.highest - counter;
        back < REPLAY_WINDOW && self.seen & (1 << back) == 0 && counter != 0
    }

    /// Marks `counter` taken (after its MAC was checked: a forger burns nothing).
    fn take(&mut self, counter: u64) {
        if counter > self.highest {
            let shift = counter - self.highest;
            self.seen = if shift >= REPLAY_WINDOW {
                0
            } else {
                self.seen << shift
            };
            self.seen |= 1;
            self.highest = counter;
        } else if let Some(bit) = 1u64.checked_shl((self.highest - counter) as u32) {
            self.seen |= bit;
        }
    }
}

/// A session's key and the counters it has taken.
#[derive(Debug, Clone)]
pub struct Verifier {
    key: Vec<u8>,
    replay: Replay,
}

impl Verifier {
    pub fn new(key: &[u8]) -> Verifier {
        Verifier {
            key: key.to_vec(),
            replay: Replay::default(),
        }
    }

    /// Checks a request at `now_ms` on the laptop's clock: the MAC first (so nothing
    /// else is learnt without the key), then its age, then its counter; takes the
    /// counter only when all pass.
    pub fn verify(&mut self, claim: &Claim, req: Request, now_ms: u64) -> Result<(), BadSignature> {
        check_mac(&self.key, claim, req)?;
        if claim.time_ms.saturating_add(MAX_AGE.as_millis() as u64) < now_ms {
            return Err(BadSignature::Stale);
        }
        if claim.time_ms > now_ms.saturating_add(MAX_AHEAD.as_millis() as u64) {
            return Err(BadSignature::Ahead);
        }
        if !self.replay.fresh(claim.counter) {
            return Err(BadSignature::Replayed);
        }
        self.replay.take(claim.counter);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const KEY: &[u8] = b"0123456789abcdef";

    fn claim(counter: u64, time_ms: u64, body: &[u8]) -> Claim {
        Claim {
            session: "s1".into(),
            counter,
            time_ms,
            mac: sign(
                KEY,
                "s1",
                counter,
                time_ms,
                Request::new("POST", "/api/x", body),
            ),
        }
    }

    fn verify(v: &mut Verifier, c: &Claim, body: &[u8], now: u64) -> Result<(), BadSignature> {
        v.verify(c, Request::new("POST", "/api/x", body), now)
    }

    /// RFC 4231 §4.2 (test case 1) and §4.3 (test case 2), written from the RFC.
    #[test]
    fn hmac_sha256_matches_rfc_4231() {
        assert_eq!(
            hex(&hmac_sha256(&[0x0b; 20], b"Hi There")),
            "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7"
        );
        assert_eq!(
            hex(&hmac_sha256(b"Jefe", b"what do ya want for nothing?")),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"
        );
    }

    #[test]
    fn a_fresh_signed_request_passes_once() {
        let mut v = Verifier::new(KEY);
        let c = claim(1, 10_000, b"{}");
        assert_eq!(verify(&mut v, &c, b"{}", 10_050), Ok(()));
        assert_eq!(
            verify(&mut v, &c, b"{}", 10_060),
            Err(BadSignature::Replayed),
            "the same request again"
        );
    }

    #[test]
    fn a_request_older_than_max_age_is_stale_on_the_fake_clock() {
        let mut v = Verifier::new(KEY);
        let c = claim(1, 10_000, b"");
        assert_eq!(verify(&mut v, &c, b"", 15_001), Err(BadSignature::Stale));
        assert_eq!(
            verify(&mut v, &c, b"", 15_000),
            Ok(()),
            "5 s exactly is taken"
        );
        let ahead = claim(2, 20_001, b"");
        assert_eq!(
            verify(&mut v, &ahead, b"", 18_000),
            Err(BadSignature::Ahead)
        );
    }

    #[test]
    fn counters_are_taken_once_each_even_out_of_order() {
        let mut v = Verifier::new(KEY);
        for n in [5, 3, 4, 70] {
            assert_eq!(
                verify(&mut v, &claim(n, 1000, b""), b"", 1000),
                Ok(()),
                "{n}"
            );
        }
        for n in [3, 4, 5, 70] {
            assert_eq!(
                verify(&mut v, &claim(n, 1000, b""), b"", 1000),
                Err(BadSignature::Replayed),
                "{n} again"
            );
        }
        // 6 is more than REPLAY_WINDOW below 70: too old to tell, refused.
        assert_eq!(
            verify(&mut v, &claim(6, 1000, b""), b"", 1000),
            Err(BadSignature::Replayed)
        );
        assert_eq!(verify(&mut v, &claim(69, 1000, b""), b"", 1000), Ok(()));
        assert_eq!(
            verify(&mut v, &claim(0, 1000, b""), b"", 1000),
            Err(BadSignature::Replayed),
            "0 is never a counter"
        );
    }

    #[test]
    fn a_wrong_key_a_changed_body_or_path_and_a_truncated_mac_are_refused() {
        let mut v = Verifier::new(b"another key, not the phone's");
        let c = claim(1, 1000, b"{\"on\":true}");
        assert_eq!(
            verify(&mut v, &c, b"{\"on\":true}", 1000),
            Err(BadSignature::BadMac)
        );
        let mut v = Verifier::new(KEY);
        assert_eq!(
            verify(&mut v, &c, b"{\"on\":false}", 1000),
            Err(BadSignature::BadMac)
        );
        assert_eq!(
            v.verify(&c, Request::new("POST", "/api/y", b"{\"on\":true}"), 1000),
            Err(BadSignature::BadMac)
        );
        let mut short = c.clone();
        short.mac.truncate(32);
        assert_eq!(
            verify(&mut v, &short, b"{\"on\":true}", 1000),
            Err(BadSignature::Malformed)
        );
        let mut upper = c.clone();
        upper.mac = "zz".repeat(32);
        assert_eq!(
            verify(&mut v, &upper, b"{\"on\":true}", 1000),
            Err(BadSignature::Malformed)
        );
        // A refused request burns no counter: the right one still passes.
        assert_eq!(verify(&mut v, &c, b"{\"on\":true}", 1000), Ok(()));
    }
}

//! The parameter Expire octet (§3.2.2, icd-reading X4): upper five bits mantissa M,
//! lower three bits exponent E, lifetime = 3·(M+1)·10^(E+1) ms; 0xFF never expires.

use std::time::Duration;

/// A parameter's time to live, as its wire octet (§3.2.2, icd-reading X4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Expire(pub u8);

impl Default for Expire {
    /// Never expires: the safe default for a value that is re-sent whenever it changes.
    fn default() -> Self {
        Expire::NEVER
    }
}

impl Expire {
    /// %xFF: "the parameter does not expire" (§3.2.2).
    pub const NEVER: Expire = Expire(0xFF);

    /// The lifetime in milliseconds, 3·(M+1)·10^(E+1) (§3.2.2), or `None` for
    /// [`Expire::NEVER`].
    pub const fn millis(self) -> Option<u64> {
        if self.0 == 0xFF {
            return None;
        }
        let m = (self.0 >> 3) as u64;
        let e = (self.0 & 0x7) as u32;
        // Largest finite value is 3·31·10^8, far below u64::MAX.
        Some(3 * (m + 1) * 10u64.pow(e + 1))
    }

    /// The lifetime, or `None` for never.
    pub fn duration(self) -> Option<Duration> {
        self.millis().map(Duration::from_millis)
    }

    /// The code with the shortest lifetime that is still at least `ms` (the lowest code
    /// among equal lifetimes). Beyond the longest finite lifetime (9.3·10^9 ms, about
    /// 108 days) the only code that is "at least" as long is [`Expire::NEVER`].
    pub fn at_least_millis(ms: u64) -> Expire {
        let mut best: Option<(u64, u8)> = None;
        for code in 0u8..0xFF {
            let Some(life) = Expire(code).millis() else {
                continue;
            };
            if life >= ms && best.is_none_or(|(b, _)| life < b) {
                best = Some((life, code));
            }
        }
        best.map_or(Expire::NEVER, |(_, code)| Expire(code))
    }

    /// [`Expire::at_least_millis`] for a `Duration` (rounded up to whole ms).
    pub fn at_least(d: Duration) -> Expire {
        let ms = d.as_millis() + u128::from(!d.subsec_nanos().is_multiple_of(1_000_000));
        Expire::at_least_millis(u64::try_from(ms).unwrap_or(u64::MAX))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn the_three_worked_examples_of_3_2_2() {
        // 0x13 = M 00010, E 011 → 3·3·10^4 ms = 90 s.
        assert_eq!(Expire(0x13).millis(), Some(90_000));
        // 0xF7 = M 11110, E 111 → 3·31·10^8 ms = 9.3 million seconds.
        assert_eq!(Expire(0xF7).millis(), Some(9_300_000_000));
        // 0x00 → 3·1·10 ms = 30 ms.
        assert_eq!(Expire(0x00).millis(), Some(30));
    }

    #[test]
    fn ff_never_expires() {
        assert_eq!(Expire::NEVER.millis(), None);
        assert_eq!(Expire(0xFF).duration(), None);
        assert_eq!(Expire::default(), Expire::NEVER);
    }

    #[test]
    fn encoder_picks_the_examples_back() {
        assert_eq!(Expire::at_least_millis(90_000), Expire(0x13));
        assert_eq!(Expire::at_least_millis(30), Expire(0x00));
        assert_eq!(Expire::at_least_millis(0), Expire(0x00));
        assert_eq!(Expire::at_least_millis(31), Expire(0x08), "60 ms is next");
        assert_eq!(Expire::at_least(Duration::from_secs(90)), Expire(0x13));
        assert_eq!(
            Expire::at_least(Duration::from_micros(30_001)),
            Expire(0x08)
        );
    }

    #[test]
    fn beyond_the_longest_finite_lifetime_is_never() {
        assert_eq!(Expire::at_least_millis(9_300_000_000), Expire(0xF7));
        assert_eq!(Expire::at_least_millis(9_300_000_001), Expire::NEVER);
        assert_eq!(Expire::at_least(Duration::MAX), Expire::NEVER);
    }

    proptest! {
        #[test]
        fn encoder_gives_the_tightest_code_at_least_as_long(ms in 0u64..10_000_000_000) {
            let code = Expire::at_least_millis(ms);
            match code.millis() {
                None => prop_assert!(ms > 9_300_000_000),
                Some(life) => {
                    prop_assert!(life >= ms);
                    // No other finite code lies in [ms, life).
                    for c in 0u8..0xFF {
                        let l = Expire(c).millis().unwrap();
                        prop_assert!(!(l >= ms && l < life), "code {c:#x} ({l} ms) is tighter");
                    }
                }
            }
        }

        #[test]
        fn every_code_encodes_back_to_an_equal_lifetime(code in 0u8..0xFF) {
            let life = Expire(code).millis().unwrap();
            prop_assert_eq!(Expire::at_least_millis(life).millis(), Some(life));
        }
    }
}

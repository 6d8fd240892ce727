//! The fault resets (DEVICE_CLEAR) the page sent this session, per device, and whether
//! a circuit faulted again after one: the fact `control::commands`' reset rule judges
//! by (FAA AC 43.13-1B's breaker practice: reset once, then find the cause).
//!
//! Every sender's DEVICE_CLEAR goes through `Model::note_sent` (the page's keys, the
//! XFSp gateway's remote commands), so each is counted and logged whatever sent it.

use std::time::{Duration, Instant};

use super::{LogLevel, Model, Motor};

/// A status heard this long after a reset went out reflects it. The DEVICE_CLEAR
/// takes under 2 ms of a 57600-baud line, and a broadcast already on its way out of
/// the unit when the reset arrived (at most a few frames queued: FAULT_STATUS is 44
/// bytes, 8 ms) can still show the fault it cleared; 300 ms is well past both.
pub const RESET_SETTLE: Duration = Duration::from_millis(300);

/// The resets sent for one device this session.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ResetsSent {
    /// The last one.
    pub at: Instant,
    /// How many in this session.
    pub count: u32,
}

/// "1st", "2nd", "3rd", "4th" …
fn ordinal(n: u32) -> String {
    let suffix = match (n % 10, n % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    format!("{n}{suffix}")
}

impl Model {
    /// A DEVICE_CLEAR for `id` went out at `at`: counted and logged.
    pub(super) fn note_reset_sent(&mut self, at: Instant, id: u8) {
        let Some(slot) = self.resets.get_mut(id as usize) else {
            return;
        };
        let count = slot.map_or(0, |r| r.count) + 1;
        *slot = Some(ResetsSent { at, count });
        let name = self.display_name(id);
        let again = if count > 1 {
            " after it faulted again"
        } else {
            ""
        };
        self.log(
            at,
            if count > 1 {
                LogLevel::Warning
            } else {
                LogLevel::Info
            },
            format!(
                "{name}: reset sent{again} (DEVICE_CLEAR), the {} this session",
                ordinal(count)
            ),
        );
    }

    /// The resets sent for device `id` this session.
    pub fn resets_sent(&self, id: u8) -> Option<ResetsSent> {
        self.resets.get(id as usize).copied().flatten()
    }

    /// Whether circuit `id` is faulted now by a status heard after a reset had had
    /// time to act ([`RESET_SETTLE`]): it tripped again (or the reset did not take).
    pub fn faulted_again_after_reset(&self, id: u8, now: Instant) -> bool {
        self.circuits(now)
            .iter()
            .any(|c| c.id == id && c.faulted_again)
    }

    /// Whether the newest status that carries `id`'s fault (FAULT_STATUS, and for a
    /// motor its FLAP_TRIM_STATUS) was heard after a reset of it had settled, and
    /// shows it faulted.
    pub(super) fn fault_heard_after_reset(&self, id: u8) -> bool {
        let Some(reset) = self.resets_sent(id) else {
            return false;
        };
        let after = |at: Instant| at >= reset.at + RESET_SETTLE;
        let listed = self.fault_status.as_ref().is_some_and(|f| {
            after(f.at) && f.value.faulted.get(id as usize).copied().unwrap_or(false)
        });
        let motor = Motor::of_device(id).is_some_and(|m| {
            self.flap_trim
                .as_ref()
                .is_some_and(|ft| after(ft.at) && m.fault(&ft.value).is_fault())
        });
        listed || motor
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordinals_read_as_words_do() {
        let got: Vec<String> = [1, 2, 3, 4, 11, 12, 13, 21, 22, 102].map(ordinal).into();
        assert_eq!(
            got,
            [
                "1st", "2nd", "3rd", "4th", "11th", "12th", "13th", "21st", "22nd", "102nd"
            ]
        );
    }
}

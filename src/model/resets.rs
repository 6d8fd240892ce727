//! The fault resets (DEVICE_CLEAR) the page sent this session, per device, and whether
//! a circuit faulted again after one: the fact `control::commands`' reset rule judges
//! by (FAA AC 43.13-1B's breaker practice: reset once, then find the cause).
//!
//! Every sender's DEVICE_CLEAR goes through `Model::note_sent` (the page's keys, the
//! XFSp gateway's remote commands), so each is counted and logged whatever sent it.
//!
//! Between a reset and the unit's word on it, the fault is not shown as current
//! ([`AfterReset`]). The ICD says the next FAULT_STATUS reflects a DEVICE_CLEAR
//! (§6.4.5), but FAULT_STATUS is sent only while some fault exists (§6.3.4): once the
//! last one clears, no "next" FAULT_STATUS ever comes, and its silence is the answer.
//! Decision (icd-reading R31): the reset is answered by the
//! first of
//! - a DEVICE_STATUS heard after the reset with the circuit on (a faulted pin is off,
//!   Appendix E), or a FAULT_STATUS heard after it without the circuit: cleared;
//! - a status heard once the reset has settled ([`RESET_SETTLE`]) showing the fault:
//!   faulted again;
//! - FAULT_STATUS overdue: one period ([`FAULT_STATUS_PERIOD`]) after the newest one
//!   heard, or after the reset if that is later, plus [`FAULT_STATUS_MARGIN`]:
//!   cleared.

use std::time::{Duration, Instant};

use super::{FAULT_STATUS_MARGIN, FAULT_STATUS_PERIOD, LogLevel, Model, Motor};
use crate::protocol::fault::FaultCode;

/// A status heard this long after a reset went out reflects it. The DEVICE_CLEAR
/// takes under 2 ms of a 57600-baud line, and a broadcast already on its way out of
/// the unit when the reset arrived (at most a few frames queued: FAULT_STATUS is 44
/// bytes, 8 ms) can still show the fault it cleared; 300 ms is well past both.
pub const RESET_SETTLE: Duration = Duration::from_millis(300);

/// What the unit has said of a fault since the page last sent a reset for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AfterReset {
    /// Nothing heard yet that reflects the reset: the fault may be gone.
    Waiting {
        /// When the reset went out.
        sent: Instant,
        /// When FAULT_STATUS's silence will say the fault cleared; `None` for a
        /// motor's fault shown only by FLAP_TRIM_STATUS, which its next one answers.
        overdue_at: Option<Instant>,
    },
    /// The unit cleared it.
    Cleared,
    /// A status heard after the reset settled shows it faulted.
    FaultedAgain,
}

/// The words beside a fault whose reset is unanswered: "SHORT_CIRCUIT · reset sent",
/// on the page and on the phone alike.
pub fn reset_sent_words(code: FaultCode) -> String {
    format!("{} · reset sent", code.name())
}

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

    /// What the unit has said of `id`'s fault since the last reset sent for it, judged
    /// at `now` (see the module's docs); `None` if no reset was sent.
    pub fn after_reset(&self, id: u8, now: Instant) -> Option<AfterReset> {
        let sent = self.resets_sent(id)?.at;
        if self.fault_heard_after_reset(id) {
            return Some(AfterReset::FaultedAgain);
        }
        let i = id as usize;
        let switched_on = self
            .device_status
            .as_ref()
            .is_some_and(|d| d.at >= sent && d.value.on.get(i).copied().unwrap_or(false));
        // The newest FAULT_STATUS listing it was made before the reset acted (or it
        // would be "faulted again" above): its period, from it or from the reset.
        let overdue_at = self
            .fault_status
            .as_ref()
            .filter(|f| f.value.faulted.get(i).copied().unwrap_or(false))
            .map(|f| (f.at + FAULT_STATUS_PERIOD).max(sent) + FAULT_STATUS_MARGIN);
        let listing_over = overdue_at.is_none_or(|t| now >= t);
        // A motor's FLAP_TRIM_STATUS (10 Hz) still showing it was made before the
        // reset settled, for the same reason.
        let motor_over = Motor::of_device(id).is_none_or(|m| {
            self.flap_trim
                .as_ref()
                .is_none_or(|ft| !m.fault(&ft.value).is_fault())
        });
        Some(if switched_on || (listing_over && motor_over) {
            AfterReset::Cleared
        } else {
            AfterReset::Waiting { sent, overdue_at }
        })
    }

    /// The earliest instant after `after` at which a reset's answer changes by time
    /// alone (its FAULT_STATUS falling overdue), so the page redraws then: no packet
    /// marks the moment.
    pub fn next_change(&self, after: Instant) -> Option<Instant> {
        (0..self.resets.len() as u8)
            .filter_map(|id| match self.after_reset(id, after)? {
                AfterReset::Waiting { overdue_at, .. } => overdue_at,
                _ => None,
            })
            .filter(|t| *t > after)
            .min()
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
    use crate::model::{CircuitState, Source};
    use crate::protocol::message::{
        DeviceClear, DeviceStatus, FaultStatus, Packet, SignedTenths, SystemStatus, Tenths,
    };

    const LANDING: u8 = 17;
    const BEACON: u8 = 6;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    /// SYSTEM_STATUS and DEVICE_STATUS with `on` switched on.
    fn status(m: &mut Model, at: Instant, on: &[u8]) {
        let mut d = DeviceStatus::default();
        for &id in on {
            d.on[id as usize] = true;
        }
        let s = SystemStatus {
            system_current: Tenths(50),
            main_bus_volts: SignedTenths(138),
            internal_temp: 30,
            ..Default::default()
        };
        m.apply_packet(at, &Packet::from_vpx(0, s));
        m.apply_packet(at, &Packet::from_vpx(1, d));
    }

    /// FAULT_STATUS listing `faulted` as shorted.
    fn faults(m: &mut Model, at: Instant, faulted: &[u8]) {
        let shorted: Vec<_> = faulted
            .iter()
            .map(|&id| (id, FaultCode::ShortCircuit))
            .collect();
        let f = FaultStatus::with_faults(&shorted);
        m.apply_packet(at, &Packet::from_vpx(2, f));
    }

    fn reset(m: &mut Model, at: Instant, id: u8) {
        m.note_sent(at, &Packet::request(3, DeviceClear { device_id: id }));
    }

    fn state(m: &Model, at: Instant, id: u8) -> CircuitState {
        m.circuits(at)
            .into_iter()
            .find(|c| c.id == id)
            .map(|c| c.state)
            .unwrap()
    }

    const SHORTED: CircuitState = CircuitState::Fault(FaultCode::ShortCircuit);
    const RESET_SENT: CircuitState = CircuitState::ResetSent(FaultCode::ShortCircuit);

    /// Landing Lt (and `others`) shorted at t0, status and FAULT_STATUS heard, and
    /// Landing Lt reset at t0 + 200 ms.
    fn shorted_and_reset(others: &[u8]) -> (Model, Instant) {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        status(&mut m, t0, &[]);
        faults(&mut m, t0, &[&[LANDING], others].concat());
        assert_eq!(state(&m, t0, LANDING), SHORTED);
        reset(&mut m, t0 + ms(200), LANDING);
        (m, t0)
    }

    /// Its switch on: the unit's next DEVICE_STATUS shows it on, and so does the row,
    /// though FAULT_STATUS (heard before the reset) is still "fresh".
    #[test]
    fn a_reset_is_shown_as_sent_until_device_status_shows_the_circuit_on() {
        let (mut m, t0) = shorted_and_reset(&[]);
        assert_eq!(state(&m, t0 + ms(200), LANDING), RESET_SENT);
        status(&mut m, t0 + ms(1000), &[LANDING]);
        assert_eq!(state(&m, t0 + ms(1000), LANDING), CircuitState::On);
        assert!(m.live_faults(t0 + ms(1000)).unwrap().0[LANDING as usize] == FaultCode::NoFault);
    }

    /// Its switch off and no other fault: FAULT_STATUS just stops (ICD §6.3.4). Due at
    /// t0 + 1 s (its period after the last one), overdue 500 ms later: "reset sent"
    /// until then, OFF from then, never SHORT_CIRCUIT plain.
    #[test]
    fn with_its_switch_off_the_fault_clears_once_fault_status_is_overdue() {
        let (mut m, t0) = shorted_and_reset(&[]);
        status(&mut m, t0 + ms(1000), &[]);
        assert_eq!(state(&m, t0 + ms(1000), LANDING), RESET_SENT);
        assert_eq!(state(&m, t0 + ms(1499), LANDING), RESET_SENT);
        assert_eq!(m.next_change(t0 + ms(1000)), Some(t0 + ms(1500)));
        assert_eq!(state(&m, t0 + ms(1500), LANDING), CircuitState::Off);
        assert_eq!(
            m.after_reset(LANDING, t0 + ms(1500)),
            Some(AfterReset::Cleared)
        );
        assert_eq!(
            m.next_change(t0 + ms(1500)),
            None,
            "nothing left to wait for"
        );
    }

    /// Another fault stands, so FAULT_STATUS keeps coming: one without the circuit
    /// says at once that the reset cleared it.
    #[test]
    fn a_fault_status_without_the_circuit_clears_it_at_once() {
        let (mut m, t0) = shorted_and_reset(&[BEACON]);
        status(&mut m, t0 + ms(1000), &[]);
        faults(&mut m, t0 + ms(1000), &[BEACON]);
        assert_eq!(state(&m, t0 + ms(1000), LANDING), CircuitState::Off);
        assert_eq!(state(&m, t0 + ms(1000), BEACON), SHORTED);
    }

    /// A FAULT_STATUS still listing it, heard once the reset had time to act: it
    /// faulted again, shown plain. One heard within [`RESET_SETTLE`] of the reset may
    /// have been made before it: still "reset sent", now due a period after it.
    #[test]
    fn a_fault_status_listing_it_after_the_reset_settled_is_a_fault_again() {
        let (mut m, t0) = shorted_and_reset(&[]);
        faults(&mut m, t0 + ms(400), &[LANDING]);
        assert_eq!(state(&m, t0 + ms(400), LANDING), RESET_SENT);
        assert_eq!(m.next_change(t0 + ms(400)), Some(t0 + ms(1900)));
        status(&mut m, t0 + ms(1000), &[]);
        faults(&mut m, t0 + ms(1400), &[LANDING]);
        assert_eq!(state(&m, t0 + ms(1400), LANDING), SHORTED);
        assert!(m.faulted_again_after_reset(LANDING, t0 + ms(1400)));
    }

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

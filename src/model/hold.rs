//! DEVICE_POWER holds the page sent: which circuits the unit holds on or off against
//! their switch, and since when.
//!
//! ICD Appendix A: the soft keys "allow the user to manually turn on or off a device,
//! overriding the switch until the switch is cycled". Our reading of "cycled", the
//! same as the virtual VP-X's (`sim::unit`, `set_cockpit_switch`): ANY change of the
//! circuit's switch input ends the hold, not only a full off-on-off round. A
//! DEVICE_POWER the page sends (its soft keys, the installation check, the gateway
//! forwarding another display's command: everything written goes through
//! `Model::note_sent`) starts a hold; it ends when:
//! - SYSTEM_STATUS shows the input the circuit's DEVICE_SPEC assigns it (the freshest
//!   the model has) changed since the one before, and the hold was sent before that
//!   one came. A hold sent between the two broadcasts may have come before the change
//!   or after it (then the unit still holds it): the page cannot tell, keeps it, and
//!   the input's next change ends it. A circuit whose spec is unknown keeps its hold,
//!   as the page cannot tell which input would end it;
//! - the page sends DEVICE_CLEAR for it (Table 33 note 2: a cleared device is set to
//!   its switch's state; the switch-11 ones come back on, so theirs end too);
//! - the page (re)connects, or SYSTEM_STATUS was silent longer than
//!   `COMM_LOST_AFTER`, or its CU Warm Reset flag rises (Table 24 note 4): the unit
//!   may have restarted (every hold is lost with its RAM) or the input may have
//!   changed unseen, so the page no longer knows of a hold and says nothing of one.
//!
//! A switch flipped on and back within one SYSTEM_STATUS (1 Hz) is not seen: the unit
//! has ended the hold, the model still holds it. Nothing better can be known from the
//! broadcasts.

use std::time::Instant;

use crate::protocol::device::{DEVICE_COUNT, FLAPS, STARTER, TRIM_P, TRIM_R};
use crate::protocol::message::{DeviceSpec, Message, SwitchId, SystemStatus};

/// A DEVICE_POWER the page sent that the unit still holds, as far as the page knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Hold {
    /// The state it holds the circuit in.
    pub on: bool,
    /// When the page wrote it.
    pub at: Instant,
}

/// Every circuit's hold, by device id.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Holds([Option<Hold>; DEVICE_COUNT]);

impl Holds {
    pub fn get(&self, id: u8) -> Option<Hold> {
        self.0.get(usize::from(id)).copied().flatten()
    }

    /// The page wrote `message` at `at`.
    pub fn sent(&mut self, at: Instant, message: &Message, specs: &[Option<DeviceSpec>]) {
        match message {
            // Appendix B: the starter cannot be switched from outside (icd-reading
            // R18), and the motors run only by TRIM_MOVE / FLAP_MOVE.
            Message::DevicePower(d) if ![STARTER, FLAPS, TRIM_R, TRIM_P].contains(&d.device_id) => {
                if let Some(slot) = self.0.get_mut(usize::from(d.device_id)) {
                    *slot = Some(Hold { on: d.on, at });
                }
            }
            Message::DeviceClear(c) => {
                if let Some(slot) = self.0.get_mut(usize::from(c.device_id)) {
                    *slot = None;
                }
                for (slot, spec) in self.0.iter_mut().zip(specs) {
                    if spec.is_some_and(|s| s.switch_id == SwitchId::AlwaysOn) {
                        *slot = None;
                    }
                }
            }
            _ => {}
        }
    }

    /// A SYSTEM_STATUS arrived; `before` is the last one, when it came, and whether
    /// it is older than the unit may be silent without having restarted.
    pub fn status(
        &mut self,
        before: Option<(&SystemStatus, Instant, bool)>,
        now: &SystemStatus,
        specs: &[Option<DeviceSpec>],
    ) {
        let Some((before, before_at, gap)) = before else {
            return;
        };
        if gap || (now.faults.warm_reset && !before.faults.warm_reset) {
            self.forget();
            return;
        }
        for (slot, spec) in self.0.iter_mut().zip(specs) {
            let Some(SwitchId::Input(n @ 1..=10)) = spec.map(|s| s.switch_id) else {
                continue;
            };
            let i = usize::from(n - 1);
            if before.switches.switch[i] != now.switches.switch[i]
                && slot.is_some_and(|h| h.at <= before_at)
            {
                *slot = None;
            }
        }
    }

    /// The page no longer knows of any hold (see the module docs).
    pub fn forget(&mut self) {
        self.0 = [None; DEVICE_COUNT];
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;
    use crate::model::{Model, Source};
    use crate::protocol::message::{
        DeviceClear, DevicePower, Packet, SignedTenths, SwitchInputs, Tenths,
    };

    fn status(inputs_on: &[u8], warm_reset: bool) -> Packet {
        let mut switches = SwitchInputs::default();
        for &n in inputs_on {
            switches.switch[usize::from(n - 1)] = true;
        }
        let mut s = SystemStatus {
            system_current: Tenths(10),
            main_bus_volts: SignedTenths(126),
            internal_temp: 20,
            switches,
            ..Default::default()
        };
        s.faults.warm_reset = warm_reset;
        Packet::from_vpx(0, s)
    }

    fn spec(id: u8, switch_id: SwitchId) -> Packet {
        Packet::from_vpx(
            0,
            DeviceSpec {
                device_id: id,
                circuit_breaker: 5,
                switch_id,
                current_fault: true,
                switch_raw: None,
            },
        )
    }

    fn power(id: u8, on: bool) -> Packet {
        Packet::request(1, DevicePower { device_id: id, on })
    }

    /// Nav Lt (4) on switch 2, Strobe (5) on switch 3, EFIS (2) always on; input 2 on.
    fn model(t0: Instant) -> Model {
        let mut m = Model::new(Source::Simulated {
            scenario: "t".into(),
        });
        m.note_connected(t0, "test".into());
        m.apply_packet(t0, &spec(4, SwitchId::Input(2)));
        m.apply_packet(t0, &spec(5, SwitchId::Input(3)));
        m.apply_packet(t0, &spec(2, SwitchId::AlwaysOn));
        m.apply_packet(t0, &status(&[2], false));
        m
    }

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    /// Our reading of "until the switch is cycled" (ICD Appendix A): any change of the
    /// circuit's own input ends the hold, a single change, not a round trip; another
    /// input's change does not.
    #[test]
    fn a_hold_ends_at_the_first_change_of_the_circuits_own_input() {
        let t0 = Instant::now();
        let mut m = model(t0);
        m.note_sent(ms(t0, 100), &power(4, false));
        m.note_sent(ms(t0, 100), &power(5, true));
        assert_eq!(
            m.hold(4),
            Some(Hold {
                on: false,
                at: ms(t0, 100)
            })
        );
        m.apply_packet(ms(t0, 1000), &status(&[2], false));
        assert!(m.hold(4).is_some(), "nothing changed");
        // Input 3 closes: Strobe's hold ends, Nav Lt's (input 2) stays.
        m.apply_packet(ms(t0, 2000), &status(&[2, 3], false));
        assert_eq!(m.hold(5), None, "its input changed once: the hold is over");
        assert!(m.hold(4).is_some(), "another input changed");
        // Input 2 opens: one change, the hold is over.
        m.apply_packet(ms(t0, 3000), &status(&[3], false));
        assert_eq!(m.hold(4), None);
    }

    /// A hold sent between two broadcasts, the second showing its input changed: the
    /// change may have come first (the unit still holds it), so the page keeps it
    /// until the next change.
    #[test]
    fn a_hold_sent_between_two_broadcasts_outlives_the_change_the_second_shows() {
        let t0 = Instant::now();
        let mut m = model(t0);
        m.note_sent(ms(t0, 500), &power(4, true));
        m.apply_packet(ms(t0, 1000), &status(&[], false));
        assert!(m.hold(4).is_some(), "may have come after the change");
        m.apply_packet(ms(t0, 2000), &status(&[2], false));
        assert_eq!(m.hold(4), None, "the next change ends it");
    }

    #[test]
    fn the_starter_and_the_motors_are_never_held_and_device_clear_ends_a_hold() {
        let t0 = Instant::now();
        let mut m = model(t0);
        for id in [STARTER, FLAPS, TRIM_P, TRIM_R] {
            m.note_sent(t0, &power(id, true));
            assert_eq!(m.hold(id), None, "device {id}");
        }
        m.note_sent(t0, &power(4, true));
        m.note_sent(t0, &power(2, false));
        m.note_sent(t0, &power(5, false));
        // Clearing Nav Lt's fault sets it to its switch, and brings every switch-11
        // device back on (Table 33 note 2).
        m.note_sent(
            ms(t0, 10),
            &Packet::request(2, DeviceClear { device_id: 4 }),
        );
        assert_eq!(m.hold(4), None);
        assert_eq!(m.hold(2), None, "EFIS is always on: back on");
        assert!(m.hold(5).is_some());
    }

    #[test]
    fn a_reconnect_a_silence_or_a_warm_reset_forgets_every_hold() {
        let t0 = Instant::now();
        let mut m = model(t0);
        m.note_sent(t0, &power(4, false));
        m.note_connected(ms(t0, 500), "test".into());
        assert_eq!(m.hold(4), None, "reconnected");

        m.note_sent(ms(t0, 600), &power(4, false));
        m.apply_packet(ms(t0, 1000), &status(&[2], false));
        assert!(m.hold(4).is_some(), "1 s between broadcasts is no gap");
        m.apply_packet(ms(t0, 3600), &status(&[2], false));
        assert_eq!(
            m.hold(4),
            None,
            "2.6 s of silence: the unit may have restarted"
        );

        m.note_sent(ms(t0, 3700), &power(4, false));
        m.apply_packet(ms(t0, 4600), &status(&[2], true));
        assert_eq!(m.hold(4), None, "the warm-reset flag rose");
        m.note_sent(ms(t0, 4700), &power(4, false));
        m.apply_packet(ms(t0, 5600), &status(&[2], true));
        assert!(m.hold(4).is_some(), "a flag still set is no new reset");
    }

    #[test]
    fn a_circuit_whose_spec_is_unknown_keeps_its_hold() {
        let t0 = Instant::now();
        let mut m = model(t0);
        m.note_sent(t0, &power(6, true));
        m.apply_packet(ms(t0, 1000), &status(&[2, 3, 4], false));
        assert!(m.hold(6).is_some());
    }
}

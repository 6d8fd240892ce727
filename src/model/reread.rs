//! Data back after COMMUNICATION LOST: what the page knew of the unit's settings is
//! forgotten and read again at once.
//!
//! While the cable was out the unit may have been renamed, reconfigured from another
//! display, or swapped for another unit altogether: its old names, breakers, switches
//! and enable flags are no longer known to be its own. So when a status broadcast
//! comes after a loss ([`super::COMM_LOST_AFTER`] of silence), every name, spec, enable
//! flag and VERSION the model held is dropped (nothing can then show an old one as
//! current), screens say "re-reading settings" until the unit has answered, and the
//! app asks the whole connect set again at once (`app::queries`). A VERSION that
//! differs from the one before the loss is said to be another unit; a name that
//! differs is logged as a rename.
//!
//! Decision: the re-read ends when every setting has been answered, or
//! [`REREAD_GIVE_UP`] after the data's return (a unit older than software 2.0 never
//! answers names or enable flags): what is still unanswered is then shown as before
//! it was ever read (the pin's own name, a blank breaker), and the app's re-reader
//! keeps asking for it.

use std::time::{Duration, Instant};

use super::{LogLevel, Model, Setting};
use crate::protocol::device::{self, DEVICE_COUNT};
use crate::protocol::message::{DeviceName, Version};

/// Past this after the data's return, a re-read still unanswered stops being shown as
/// "re-reading". The whole set takes under half a second on a 57600-baud line; five
/// is what the page promises, and twice that covers requests lost on the way.
pub const REREAD_GIVE_UP: Duration = Duration::from_secs(10);

/// A re-read of every setting after the data came back.
#[derive(Debug, Clone)]
pub struct Reread {
    /// When the data came back.
    pub since: Instant,
    /// VERSION before the loss, until the unit says its VERSION again.
    version_before: Option<Version>,
    /// The names before the loss, to log a rename.
    names_before: [Option<DeviceName>; DEVICE_COUNT],
}

/// "HW sw 2.1", as the title bar shows a VERSION.
fn version_text(v: &Version) -> String {
    format!(
        "{} sw {}.{}",
        v.hardware_version.name(),
        v.software_major,
        v.software_minor
    )
}

impl Model {
    /// Since when the settings are being read again after a loss; `None` when they
    /// are not.
    pub fn rereading(&self) -> Option<Instant> {
        self.reread.as_ref().map(|r| r.since)
    }

    /// Whether `setting` is not known because it is being re-read after a loss.
    pub fn rereading_setting(&self, setting: Setting) -> bool {
        self.reread.is_some() && self.setting_heard(setting).is_none()
    }

    /// The status broadcast at `at` is the first after a loss: forget every setting
    /// and VERSION, and start the re-read.
    pub(super) fn begin_reread(&mut self, at: Instant) {
        let earlier = self.reread.take();
        let version_before = self
            .version
            .take()
            .map(|v| v.value)
            .or(earlier.as_ref().and_then(|r| r.version_before));
        let mut names_before = self.names.map(|n| n.map(|n| n.value));
        if let Some(e) = earlier {
            for (now, before) in names_before.iter_mut().zip(e.names_before) {
                if now.is_none() {
                    *now = before;
                }
            }
        }
        self.device_specs = [None; DEVICE_COUNT];
        self.names = [None; DEVICE_COUNT];
        self.enabled = [None; DEVICE_COUNT];
        self.system_spec = None;
        self.flap_spec = None;
        self.pitch_trim_spec = None;
        self.roll_trim_spec = None;
        self.wig_wag_spec = None;
        self.reread = Some(Reread {
            since: at,
            version_before,
            names_before,
        });
        self.log(
            at,
            LogLevel::Warning,
            "data back after a loss of communication: re-reading names and settings \
             (the unit may have been changed while the cable was out)"
                .into(),
        );
    }

    /// The unit said its VERSION during a re-read.
    pub(super) fn reread_version(&mut self, at: Instant, v: &Version) {
        let Some(before) = self.reread.as_mut().and_then(|r| r.version_before.take()) else {
            return;
        };
        if before != *v {
            self.log(
                at,
                LogLevel::Alert,
                format!(
                    "ANOTHER UNIT: VERSION is {} now, {} before the loss of communication; \
                     every setting is read again",
                    version_text(v),
                    version_text(&before)
                ),
            );
        }
    }

    /// The unit said a DEVICE_NAME during a re-read.
    pub(super) fn reread_name(&mut self, at: Instant, n: &DeviceName) {
        let Some(before) = self
            .reread
            .as_mut()
            .and_then(|r| r.names_before.get_mut(n.device_id as usize))
            .and_then(Option::take)
        else {
            return;
        };
        if before.name != n.name {
            let pin = device::device(n.device_id).map_or("?", |d| d.system_name);
            self.log(
                at,
                LogLevel::Warning,
                format!(
                    "{pin} renamed while the cable was out: {:?} is now {:?}",
                    before.text(),
                    n.text()
                ),
            );
        }
    }

    /// Ends the re-read once everything is answered, or at [`REREAD_GIVE_UP`].
    pub(super) fn settle_reread(&mut self, at: Instant) {
        let Some(since) = self.rereading() else {
            return;
        };
        let missing = Setting::all()
            .filter(|&s| self.setting_heard(s).is_none())
            .count()
            + usize::from(self.version.is_none());
        if missing == 0 {
            self.reread = None;
            self.log(
                at,
                LogLevel::Info,
                format!(
                    "settings re-read in {:.1} s after the data came back",
                    at.saturating_duration_since(since).as_secs_f64()
                ),
            );
        } else if at >= since + REREAD_GIVE_UP {
            self.reread = None;
            self.log(
                at,
                LogLevel::Warning,
                format!(
                    "{missing} settings still unanswered {} s after the data came back; \
                     asking again",
                    REREAD_GIVE_UP.as_secs()
                ),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Source;
    use crate::protocol::Packet;
    use crate::protocol::message::{DeviceStatus, HardwareVersion, Message, Tenths};

    fn model() -> Model {
        Model::new(Source::Simulated {
            scenario: "t".into(),
        })
    }

    fn status() -> Packet {
        Packet::from_vpx(
            0,
            DeviceStatus {
                on: [false; DEVICE_COUNT],
                current: [Tenths(0); DEVICE_COUNT],
            },
        )
    }

    fn version(major: u8) -> Message {
        Version {
            hardware_version: HardwareVersion::from_byte(1),
            software_major: major,
            software_minor: 1,
        }
        .into()
    }

    /// The unit's answer to `s`'s query, factory-fresh but for device 9's name.
    fn answer(s: Setting, name9: &str) -> Message {
        match s {
            Setting::Name(9) => DeviceName::new(9, name9).unwrap().into(),
            s => crate::model::factory_answer(s),
        }
    }

    /// A unit that answered everything at `t0`, device 9 named `name9`.
    fn heard_all(m: &mut Model, at: Instant, name9: &str, major: u8) {
        m.apply_packet(at, &status());
        m.apply_packet(at, &Packet::from_vpx(1, version(major)));
        for s in Setting::all() {
            m.apply_packet(at, &Packet::from_vpx(1, answer(s, name9)));
        }
    }

    /// A model that heard all of a unit ("Landing Lt", sw 2.1), then nothing until
    /// a status `silent` later: the data's return, and its time.
    fn back_after(silent: Duration) -> (Model, Instant) {
        let t0 = Instant::now();
        let mut m = model();
        heard_all(&mut m, t0, "Landing Lt", 2);
        let back = t0 + silent;
        m.apply_packet(back, &status());
        (m, back)
    }

    fn name9(m: &Model, now: Instant) -> String {
        m.circuits(now)
            .into_iter()
            .find(|c| c.id == 9)
            .map(|c| c.name)
            .unwrap()
    }

    #[test]
    fn data_back_after_a_loss_forgets_every_setting_until_the_unit_answers_again() {
        let t0 = Instant::now();
        let mut m = model();
        heard_all(&mut m, t0, "Landing Lt", 2);
        assert_eq!(m.rereading(), None, "a first connect is no re-read");
        assert_eq!(name9(&m, t0), "Landing Lt");
        // Status within COMM_LOST_AFTER: no loss, nothing forgotten.
        let t1 = t0 + Duration::from_secs(2);
        m.apply_packet(t1, &status());
        assert_eq!(m.rereading(), None);
        // Silent 3 s: the next status is the data's return.
        let back = t1 + Duration::from_secs(3);
        m.apply_packet(back, &status());
        assert_eq!(m.rereading(), Some(back));
        assert_eq!(name9(&m, back), "? (name re-reading…)");
        let c9 = m.circuits(back).into_iter().find(|c| c.id == 9).unwrap();
        assert!(
            c9.spec_unknown,
            "the breaker and switch are not the old ones"
        );
        assert!(m.version.is_none() && m.system_spec.is_none());
        assert!(m.events.iter().any(|e| e.text.contains("re-reading names")));
        // The answers come: the new name, a rename in the log, the re-read over.
        let t2 = back + Duration::from_millis(400);
        heard_all(&mut m, t2, "Taxi Lt", 2);
        assert_eq!(m.rereading(), None);
        assert_eq!(name9(&m, t2), "Taxi Lt");
        let texts: Vec<&str> = m.events.iter().map(|e| e.text.as_str()).collect();
        assert!(
            texts.iter().any(|t| t
                .contains("renamed while the cable was out: \"Landing Lt\" is now \"Taxi Lt\"")),
            "{texts:?}"
        );
        assert!(
            !texts.iter().any(|t| t.contains("ANOTHER UNIT")),
            "same VERSION"
        );
        assert!(
            texts
                .iter()
                .any(|t| t.contains("settings re-read in 0.4 s"))
        );
    }

    #[test]
    fn another_version_after_a_loss_is_another_unit() {
        let (mut m, back) = back_after(Duration::from_secs(4));
        m.apply_packet(back, &Packet::from_vpx(1, version(3)));
        let alert = m
            .events
            .iter()
            .find(|e| e.text.starts_with("ANOTHER UNIT"))
            .expect("said");
        assert_eq!(alert.level, LogLevel::Alert);
        assert!(alert.text.contains("sw 3.1 now") && alert.text.contains("sw 2.1 before"));
    }

    #[test]
    fn a_re_read_left_unanswered_stops_being_shown_after_the_give_up() {
        let (mut m, back) = back_after(Duration::from_secs(3));
        // Only the status comes (names never answered, as from a unit before 2.0).
        let mut t = back;
        while t < back + REREAD_GIVE_UP {
            t += Duration::from_secs(1);
            m.apply_packet(t, &status());
        }
        assert_eq!(m.rereading(), None);
        // Never the old name: the pin's own, as before a name was ever read.
        assert_eq!(name9(&m, t), device::device(9).unwrap().system_name);
        assert!(m.events.iter().any(|e| e.text.contains("still unanswered")));
    }
}

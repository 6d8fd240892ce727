//! The diagnostics page's timed requests: PING (answered at once or not at all),
//! VERSION (asked up to three times) and EEPROM_ERASE (one long wait). Each is a
//! [`Try`] judged against what the model heard after it was sent; the view's
//! [`Diagnostic`] says where it stands.

use std::time::{Duration, Instant};

use super::view::{Diagnostic, SetupView};
use crate::exchange::{ANSWER_TIMEOUT, ERASE_TIMEOUT, TRIES, Try, Verdict};
use crate::model::Model;
use crate::protocol::message::{EepromErase, Message, Ping, Version};

/// PING is answered at once or not at all.
pub const PING_TIMEOUT: Duration = Duration::from_secs(1);

/// How an EEPROM_ERASE ended, for the app to re-read the unit and say so.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EraseEnd {
    /// Answered with this response code (0: erased; ICD Table 12).
    Answered(u8),
    NoAnswer,
}

/// The requests in flight.
#[derive(Debug, Default)]
pub struct Diagnostics {
    ping: Option<Try>,
    version: Option<Try>,
    erase: Option<Try>,
}

fn waiting(t: &Try) -> Diagnostic {
    Diagnostic::Waiting {
        attempt: t.attempt,
        of: t.of(),
    }
}

impl Diagnostics {
    /// Starts a PING; returns what to send.
    pub fn ping(&mut self, view: &mut SetupView, now: Instant) -> Message {
        let t = Try::with(now, PING_TIMEOUT, 1);
        view.ping = waiting(&t);
        self.ping = Some(t);
        Ping { ack: false }.into()
    }

    /// Starts a VERSION request; returns what to send.
    pub fn version(&mut self, view: &mut SetupView, now: Instant) -> Message {
        let t = Try::with(now, ANSWER_TIMEOUT, TRIES);
        view.version = waiting(&t);
        self.version = Some(t);
        Version::REQUEST.into()
    }

    /// Starts an EEPROM_ERASE; returns what to send.
    pub fn erase(&mut self, view: &mut SetupView, now: Instant) -> Message {
        let t = Try::with(now, ERASE_TIMEOUT, 1);
        view.erase = waiting(&t);
        self.erase = Some(t);
        EepromErase { response_code: 0 }.into()
    }

    pub fn next_deadline(&self) -> Option<Instant> {
        [self.ping, self.version, self.erase]
            .iter()
            .flatten()
            .map(Try::deadline)
            .min()
    }

    /// Judges each request at `now`: the messages to send again, and how an erase
    /// ended if it just did.
    pub fn tick(
        &mut self,
        model: &Model,
        view: &mut SetupView,
        now: Instant,
    ) -> (Vec<Message>, Option<EraseEnd>) {
        let mut out = Vec::new();
        let mut erase_end = None;
        if let Some(t) = &mut self.ping {
            let reply = model.last_ping_reply.filter(|&r| r >= t.sent_at);
            match t.judge(reply.is_some(), now) {
                Verdict::Answered => {
                    view.ping = Diagnostic::Answered {
                        after: reply.unwrap_or(now) - t.sent_at,
                    };
                    self.ping = None;
                }
                Verdict::NoAnswer => {
                    view.ping = Diagnostic::NoAnswer;
                    self.ping = None;
                }
                Verdict::Resend | Verdict::Waiting => {}
            }
        }
        if let Some(t) = &mut self.version {
            let sent = t.sent_at;
            let reply = model.version.map(|v| v.at).filter(|&r| r >= sent);
            match t.judge(reply.is_some(), now) {
                Verdict::Answered => {
                    view.version = Diagnostic::Answered {
                        after: reply.unwrap_or(now) - sent,
                    };
                    self.version = None;
                }
                Verdict::Resend => {
                    view.version = waiting(t);
                    out.push(Version::REQUEST.into());
                }
                Verdict::NoAnswer => {
                    view.version = Diagnostic::NoAnswer;
                    self.version = None;
                }
                Verdict::Waiting => {}
            }
        }
        if let Some(t) = &mut self.erase {
            let reply = model
                .eeprom_erase
                .filter(|e| e.at >= t.sent_at)
                .map(|e| (e.at, e.value.response_code));
            match t.judge(reply.is_some(), now) {
                Verdict::Answered => {
                    let (at, code) = reply.unwrap_or((now, 0));
                    view.erase = Diagnostic::Answered {
                        after: at - t.sent_at,
                    };
                    self.erase = None;
                    erase_end = Some(EraseEnd::Answered(code));
                }
                Verdict::NoAnswer => {
                    view.erase = Diagnostic::NoAnswer;
                    self.erase = None;
                    erase_end = Some(EraseEnd::NoAnswer);
                }
                Verdict::Resend | Verdict::Waiting => {}
            }
        }
        (out, erase_end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::HardwareVersion;
    use crate::setup::tests::{hear, model, ms};

    #[test]
    fn version_is_asked_three_times_then_no_answer_and_ping_times_its_answer() {
        let t0 = Instant::now();
        let mut m = model();
        let mut v = SetupView::default();
        let mut p = Diagnostics::default();
        assert_eq!(p.version(&mut v, t0), Version::REQUEST.into());
        assert_eq!(v.version, Diagnostic::Waiting { attempt: 1, of: 3 });
        assert_eq!(p.tick(&m, &mut v, ms(t0, 999)).0, vec![]);
        assert_eq!(
            p.tick(&m, &mut v, ms(t0, 1000)).0,
            vec![Version::REQUEST.into()]
        );
        assert_eq!(v.version, Diagnostic::Waiting { attempt: 2, of: 3 });
        p.tick(&m, &mut v, ms(t0, 2000));
        p.tick(&m, &mut v, ms(t0, 3000));
        assert_eq!(v.version, Diagnostic::NoAnswer);
        assert_eq!(p.next_deadline(), None);

        p.ping(&mut v, ms(t0, 4000));
        hear(&mut m, ms(t0, 4012), Ping { ack: true });
        p.tick(&m, &mut v, ms(t0, 4020));
        assert_eq!(
            v.ping,
            Diagnostic::Answered {
                after: Duration::from_millis(12)
            }
        );
        p.version(&mut v, ms(t0, 5000));
        let answer = Version {
            hardware_version: HardwareVersion::VpxPro,
            software_major: 2,
            software_minor: 1,
        };
        hear(&mut m, ms(t0, 5030), answer);
        p.tick(&m, &mut v, ms(t0, 5040));
        assert_eq!(
            v.version,
            Diagnostic::Answered {
                after: Duration::from_millis(30)
            }
        );
    }

    /// A whole erase of the ATmega2560's 4 KiB EEPROM at 3.4 ms a byte takes ~14 s:
    /// an answer then is still the erase's, and the wait ends only at 20 s, once,
    /// never sent again.
    #[test]
    fn an_erase_ends_in_its_response_code_or_no_answer() {
        let t0 = Instant::now();
        let mut m = model();
        let mut v = SetupView::default();
        let mut p = Diagnostics::default();
        p.erase(&mut v, t0);
        assert_eq!(p.tick(&m, &mut v, ms(t0, 14_000)), (vec![], None));
        hear(&mut m, ms(t0, 14_100), EepromErase { response_code: 0 });
        assert_eq!(
            p.tick(&m, &mut v, ms(t0, 14_110)).1,
            Some(EraseEnd::Answered(0))
        );
        p.erase(&mut v, ms(t0, 30_000));
        assert_eq!(p.tick(&m, &mut v, ms(t0, 49_999)), (vec![], None));
        assert_eq!(
            p.tick(&m, &mut v, ms(t0, 50_000)).1,
            Some(EraseEnd::NoAnswer)
        );
        assert_eq!(v.erase, Diagnostic::NoAnswer);
        p.erase(&mut v, ms(t0, 60_000));
        hear(&mut m, ms(t0, 60_500), EepromErase { response_code: 2 });
        assert_eq!(
            p.tick(&m, &mut v, ms(t0, 60_510)).1,
            Some(EraseEnd::Answered(2))
        );
    }
}

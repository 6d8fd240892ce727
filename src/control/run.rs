//! The one permit for a motor run, from any origin (the device list's keys, setup's
//! endpoint capture, the installation check, the walk-around remote, the XFSp
//! gateway), and its refusal: a reason as a type, and words that fit where the run was
//! asked from.
//!
//! The chain, in this order and written only here ([`permit`]):
//! 1. the model's checks ([`super::motor_check`]: communication, a motor fault, the
//!    motor disabled, flap down inhibited, no live motor status);
//! 2. the room to the endpoint ahead (unless the run is setup's capture, which runs
//!    past endpoints on purpose), toward the endpoint the run will really reach: for
//!    a motor seen moving against its command, the other direction's. It comes
//!    first, so no confirmation is offered for a run that would be refused anyway;
//! 3. a motor seen moving against its command ([`super::against`]): refused unless
//!    the caller knows which way it really moves (a run the person confirmed at the
//!    keys, or the check running back what it saw).
//!
//! What belongs to the page alone (motors refused for the whole session, a page
//! nobody sees, a key's confirmation) is the controller's, before this chain
//! ([`super::Controller::start`]).

use std::fmt;
use std::time::Instant;

use super::against::{self, Against};
use super::endpoints::{self, Way};
use super::motor_check;
use super::streamer::{Direction, StopReason};
use crate::audit::Origin;
use crate::model::{Model, Motor};

/// Why a motor run was refused, as a type: a caller decides by this, never by the
/// words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refused {
    /// The page cannot stream a motor at all this session
    /// ([`super::Controller::refuse_motors`]).
    MotorsOff,
    /// Nobody can see the page (too small, unfocused): no run without a key behind it.
    Unseen(StopReason),
    /// The model's checks ([`super::motor_check`]): lost communication, a motor
    /// fault, the motor disabled, flap down inhibited, no live motor status.
    Model(StopReason),
    /// The motor was seen moving against its command, asked this way.
    Against(Direction),
    /// At (or within [`endpoints::START_ROOM`] of) the endpoint the run would reach,
    /// the one `toward` heads for.
    AtEndpoint {
        toward: Direction,
        position: u8,
        endpoint: u8,
    },
    /// Its position is too old to keep it off its endpoint.
    PositionStale,
    /// The remote's run ended without its own stop, for this reason: renewals are
    /// refused until it lets go.
    LeaseEnded(StopReason),
    /// The stream did not start (the direction does not apply to the motor).
    NotStarted,
    /// Another run is going on (a network request waits for it, [`super::How::Target`]).
    Busy,
}

/// A refused motor run: why, and the words for where it was asked from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MotorRefusal {
    pub motor: Motor,
    /// The direction asked.
    pub direction: Direction,
    pub reason: Refused,
    pub words: String,
}

impl fmt::Display for MotorRefusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.words)
    }
}

impl MotorRefusal {
    pub fn new(origin: Origin, motor: Motor, direction: Direction, reason: Refused) -> Self {
        MotorRefusal {
            motor,
            direction,
            reason,
            words: words(origin, motor, direction, reason),
        }
    }
}

/// Where the person confirms a run of a motor seen moving against its command, and
/// what to do there, in the words of the place asked from.
fn confirm_at(origin: Origin, direction: Direction) -> String {
    match origin {
        Origin::Key | Origin::Setup => format!(
            "let go, then press {} again within {} s to run it {} anyway, watching the motor",
            against::key_name(direction),
            against::CONFIRM_WITHIN.as_secs(),
            direction.name()
        ),
        Origin::Remote => {
            "not run from the phone: to run it anyway, confirm a run on the laptop's page, \
             watching the motor"
                .into()
        }
        Origin::Xfsp => {
            "not run on a network request: a run can only be confirmed on the page, by a \
             person watching the motor"
                .into()
        }
        Origin::Check | Origin::Page | Origin::Panic => {
            "not run: confirm a run on the page's device list, watching the motor".into()
        }
    }
}

/// A refusal's words for `origin`: the keys are named only to the keys.
pub fn words(origin: Origin, motor: Motor, direction: Direction, reason: Refused) -> String {
    let keys = matches!(origin, Origin::Key | Origin::Setup);
    match reason {
        Refused::MotorsOff => format!("{} cannot run from here this session", motor.name()),
        Refused::Unseen(why) => format!("not started: {}", why.describe()),
        Refused::Model(StopReason::CommLost) => super::commands::COMM_LOST.to_string(),
        Refused::Model(r @ StopReason::MotorFault(_)) if keys => format!(
            "{} is faulted ({}): reset it with r first",
            motor.name(),
            r.describe()
        ),
        Refused::Model(r @ StopReason::MotorFault(_)) => format!(
            "{} is faulted ({}): reset it first",
            motor.name(),
            r.describe()
        ),
        Refused::Model(r) => format!("{} cannot run: {}", motor.name(), r.describe()),
        Refused::Against(asked) => format!(
            "{}; {}",
            against::words(motor, asked),
            confirm_at(origin, direction)
        ),
        Refused::AtEndpoint {
            toward,
            position,
            endpoint,
        } => format!(
            "the {} is at its {} endpoint (position {position}, endpoint {endpoint}): it \
             does not run past it from here",
            motor.name(),
            toward.name()
        ),
        Refused::PositionStale => format!(
            "{} cannot run: {}",
            motor.name(),
            StopReason::PositionStale.describe()
        ),
        Refused::LeaseEnded(why) if keys => format!(
            "{} stopped: {}; let go and press again",
            motor.name(),
            why.describe()
        ),
        Refused::LeaseEnded(why) => format!(
            "{} stopped: {}; let go of the button and press it again",
            motor.name(),
            why.describe()
        ),
        Refused::NotStarted => format!("{} did not start", motor.name()),
        Refused::Busy => format!(
            "{} not started: another motor run is going on",
            motor.name()
        ),
    }
}

/// What the caller knows of a run before it starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Known {
    /// The way the caller saw the run move the position (the check's run back).
    pub way: Option<Way>,
    /// The person confirmed this run of a motor seen moving against its command (the
    /// same key again at the page, [`super::against`]).
    pub confirmed: bool,
    /// The run keeps to the endpoints (all but setup's capture).
    pub keep_ends: bool,
}

/// The permit chain (see the module docs). `Ok` carries the way the run is known to
/// move, if known, for its watch: the caller's, or, for a motor seen moving against
/// its command, the other way from its direction's.
pub fn permit(
    origin: Origin,
    model: &Model,
    against: &Against,
    motor: Motor,
    direction: Direction,
    known: Known,
    now: Instant,
) -> Result<Option<Way>, MotorRefusal> {
    let refuse = |reason| Err(MotorRefusal::new(origin, motor, direction, reason));
    if let Err(r) = motor_check(model, motor, direction, now) {
        return refuse(Refused::Model(r));
    }
    let way = known.way.or_else(|| {
        model
            .flap_trim
            .as_ref()
            .and_then(|st| against.known_way(motor, direction, &st.value))
    });
    if known.keep_ends {
        match endpoints::room_to_run(model, motor, direction, way, now) {
            Ok(()) => {}
            Err(endpoints::NoRoom::Stale) => return refuse(Refused::PositionStale),
            Err(endpoints::NoRoom::At {
                toward,
                position,
                endpoint,
            }) => {
                return refuse(Refused::AtEndpoint {
                    toward,
                    position,
                    endpoint,
                });
            }
        }
    }
    if known.way.is_none()
        && !known.confirmed
        && let Some(asked) = against.seen(motor)
    {
        return refuse(Refused::Against(asked));
    }
    Ok(way)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::TrimKind;
    use crate::protocol::fault::FaultCode;

    const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

    /// A refusal's words fit where it was asked from. Only the
    /// page's keys are told of keys; the phone of its buttons and the laptop's page;
    /// the network that it cannot confirm; the check where a person can.
    #[test]
    fn each_origin_is_told_in_its_own_words() {
        let against = Refused::Against(Direction::Up);
        let fault = Refused::Model(StopReason::MotorFault(FaultCode::TrimRunaway));
        let ended = Refused::LeaseEnded(StopReason::MaxRunTime);
        let said = |origin, reason| words(origin, PITCH, Direction::Up, reason);
        let moved = "pitch trim moved down when asked up: its leads or its sensor may be swapped";
        assert_eq!(
            said(Origin::Key, against),
            format!(
                "{moved}; let go, then press u again within 3 s to run it up anyway, \
                 watching the motor"
            )
        );
        assert_eq!(said(Origin::Setup, against), said(Origin::Key, against));
        assert_eq!(
            said(Origin::Remote, against),
            format!(
                "{moved}; not run from the phone: to run it anyway, confirm a run on the \
                 laptop's page, watching the motor"
            )
        );
        assert_eq!(
            said(Origin::Xfsp, against),
            format!(
                "{moved}; not run on a network request: a run can only be confirmed on the \
                 page, by a person watching the motor"
            )
        );
        assert_eq!(
            said(Origin::Check, against),
            format!(
                "{moved}; not run: confirm a run on the page's device list, watching the motor"
            )
        );
        assert!(said(Origin::Key, fault).ends_with("reset it with r first"));
        assert!(said(Origin::Key, ended).ends_with("let go and press again"));
        for origin in [Origin::Remote, Origin::Xfsp, Origin::Check] {
            for reason in [against, fault, ended] {
                let w = said(origin, reason);
                for keys in ["press u", "with r", "its key", "press its key twice"] {
                    assert!(!w.contains(keys), "{origin:?}: {w}");
                }
            }
        }
        assert_eq!(
            said(Origin::Remote, ended),
            "pitch trim stopped: maximum run time reached; let go of the button and press \
             it again"
        );
    }
}

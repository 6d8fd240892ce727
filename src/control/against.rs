//! A motor that moves against its command: one rule for every run, whoever starts it
//! (the device list's keys, the setup screens' endpoint capture, the installation
//! check, the XFSp gateway, the phone remote).
//!
//! An aircraft being checked is, by definition, not yet known to be wired right: a
//! motor's leads or its position sensor may be swapped. Such a motor, asked up, runs
//! down, and past the endpoint a run keeps to, since that endpoint is behind it.
//!
//! - Every run is watched ([`super::endpoints::Watch`]): once its position has gone
//!   [`MOVED`] counts the other way from the one its direction should move it (or,
//!   at the endpoint behind it, past that endpoint beyond [`NOISE`]), it is stopped,
//!   with its stop on the wire ([`StopReason::MovedAgainst`]), and the motor is
//!   recorded here.
//! - From then on, a run of that motor, in either direction (swapped leads or a
//!   swapped sensor turn both round), is refused for every origin until the person
//!   confirms it. The decision: the confirmation is the same motor key let go and
//!   pressed again (a fresh press, never a held key's repeat) within
//!   [`CONFIRM_WITHIN`] of the refusal, at the page, watching the motor
//!   ([`super::Controller`]). It holds for that one run. The installation check and
//!   the network cannot confirm: they are refused and say so.
//! - A confirmed run goes knowing the way the motor really moves: it is refused at
//!   the endpoint that way and stopped at both endpoints by position, as any run that
//!   keeps to them ([`super::run::permit`], `Watch::moving`).
//!
//! The record lasts as long as the page (or the headless gateway) runs: the person
//! who fixes the wiring starts the page again. It is shared ([`Against`] is a handle)
//! so a motor seen going the wrong way by one origin is refused to all of them.
//!
//! [`MOVED`]: super::endpoints::MOVED
//! [`NOISE`]: super::endpoints::NOISE

use std::sync::{Arc, Mutex};
use std::time::Duration;

use super::endpoints::{Way, expected_way, opposite};
use super::streamer::{Direction, StopReason};
use crate::model::Motor;
use crate::protocol::message::FlapTrimStatus;

/// How long after a refusal the same key confirms the run.
pub const CONFIRM_WITHIN: Duration = Duration::from_secs(3);

/// The motors seen moving against their command, shared by every origin that runs
/// them (a clone is the same record).
#[derive(Debug, Clone, Default)]
pub struct Against(Arc<Mutex<[Option<Direction>; 3]>>);

impl Against {
    fn lock(&self) -> std::sync::MutexGuard<'_, [Option<Direction>; 3]> {
        // A panic elsewhere while holding it leaves a plain array: still good.
        self.0.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// `motor` was asked `asked` and moved the other way.
    pub fn record(&self, motor: Motor, asked: Direction) {
        self.lock()[motor.index()] = Some(asked);
    }

    /// The direction `motor` was asked when it was seen moving against it, if it was.
    pub fn seen(&self, motor: Motor) -> Option<Direction> {
        self.lock()[motor.index()]
    }

    /// The way a run of `motor` `direction` is known to move the position: against
    /// the direction's own, for a motor seen moving against its command; `None` for
    /// one that was not.
    pub fn known_way(
        &self,
        motor: Motor,
        direction: Direction,
        ft: &FlapTrimStatus,
    ) -> Option<Way> {
        self.seen(motor)
            .map(|_| expected_way(motor, direction, ft).reversed())
    }
}

/// "pitch trim moved down when asked up: its leads or its sensor may be swapped".
pub fn words(motor: Motor, asked: Direction) -> String {
    format!(
        "{} moved {} when asked {}: its leads or its sensor may be swapped",
        motor.name(),
        opposite(asked).name(),
        asked.name()
    )
}

/// The page's words for a run stopped this way.
pub fn stopped(motor: Motor, asked: Direction) -> String {
    format!("{}; stopped", words(motor, asked))
}

/// The device list's key for `direction` (`control::keymap`).
pub fn key_name(direction: Direction) -> &'static str {
    match direction {
        Direction::Up => "u",
        Direction::Down => "d",
        Direction::Left => ",",
        Direction::Right => ".",
    }
}

/// Whether `reason` is this rule's stop, and for which asked direction.
pub fn asked(reason: StopReason) -> Option<Direction> {
    match reason {
        StopReason::MovedAgainst(d) => Some(d),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::TrimKind;

    const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

    #[test]
    fn the_words_name_the_motor_its_way_and_the_asked_one() {
        assert_eq!(
            stopped(PITCH, Direction::Up),
            "pitch trim moved down when asked up: its leads or its sensor may be swapped; \
             stopped"
        );
        assert_eq!(
            words(Motor::Trim(TrimKind::Roll), Direction::Right),
            "roll trim moved left when asked right: its leads or its sensor may be swapped"
        );
        assert_eq!(
            words(Motor::Flaps, Direction::Down),
            "flaps moved up when asked down: its leads or its sensor may be swapped"
        );
    }

    #[test]
    fn a_record_is_shared_by_every_clone_and_kept_per_motor() {
        let a = Against::default();
        let b = a.clone();
        b.record(PITCH, Direction::Up);
        assert_eq!(a.seen(PITCH), Some(Direction::Up));
        assert_eq!(a.seen(Motor::Flaps), None);
    }
}

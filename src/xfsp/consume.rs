//! Air and engine data taken from the network for the VP-X's EXTERNAL_DATA.
//!
//! The five inputs the VP-X wants (icd-reading X8) are IAS, GROUNDSPEED, P-ALT,
//! FUELPRES and ENGRPM. The draft gives them no scale, so each is taken as whole units
//! of what EXTERNAL_DATA carries: IAS and ground speed in the EFIS's speed unit (the
//! one FLAP_SPEC/TRIM_SPEC speeds use), pressure altitude in feet, fuel pressure in PSI,
//! RPM. Values outside an EXTERNAL_DATA field are clamped to it (a negative IAS is 0).
//!
//! A value is fresh while it is within its own Expire **and** at most [`MAX_AGE`] old;
//! its validity flag in EXTERNAL_DATA is set only then. Confidence USELESS is ignored.
//! When several sources send the same parameter, the most recent fresh one wins (no
//! voting: the VP-X uses these only for flap overspeed, trim power and the starter
//! lockout, and a second air-data computer is a cross-check for the pilot, not for us).

use std::time::{Duration, Instant};

use crate::protocol::message::{ExternalData, ExternalValidity};

use super::dict::Confidence;
use super::idents::{self, Ident};
use super::param::Parameter;

/// icd-reading R20: the VP-X itself gives up on EXTERNAL_DATA after 2 s.
pub const MAX_AGE: Duration = Duration::from_secs(2);
/// EXTERNAL_DATA is sent at 1 Hz (icd-reading R20).
pub const SEND_PERIOD: Duration = Duration::from_secs(1);

/// The five inputs, in EXTERNAL_DATA order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AirInput {
    Ias,
    GroundSpeed,
    PressureAltitude,
    FuelPressure,
    Rpm,
}

impl AirInput {
    pub const ALL: [AirInput; 5] = [
        AirInput::Ias,
        AirInput::GroundSpeed,
        AirInput::PressureAltitude,
        AirInput::FuelPressure,
        AirInput::Rpm,
    ];

    pub fn ident(self) -> Ident {
        match self {
            AirInput::Ias => idents::IAS,
            AirInput::GroundSpeed => idents::GROUNDSPEED,
            AirInput::PressureAltitude => idents::P_ALT,
            AirInput::FuelPressure => idents::FUELPRES,
            AirInput::Rpm => idents::ENGRPM,
        }
    }

    pub fn from_ident(ident: Ident) -> Option<AirInput> {
        AirInput::ALL.into_iter().find(|a| a.ident() == ident)
    }
}

/// One value heard on the network.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AirSample {
    pub value: i64,
    pub at: Instant,
    /// How long it counts as fresh: its Expire, capped at [`MAX_AGE`].
    pub life: Duration,
    pub src: u16,
    pub unit: u16,
}

impl AirSample {
    pub fn fresh(&self, now: Instant) -> bool {
        now.saturating_duration_since(self.at) <= self.life
    }
}

/// What is being forwarded, for the page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Forwarded {
    pub input: AirInput,
    /// The last value heard, fresh or not.
    pub last: Option<AirSample>,
    /// Whether its validity flag goes out set.
    pub fresh: bool,
}

/// The latest sample of each input and the 1 Hz EXTERNAL_DATA schedule.
#[derive(Debug, Clone, Default)]
pub struct AirData {
    /// In [`AirInput`]'s order, which is EXTERNAL_DATA's.
    samples: [Option<AirSample>; AirInput::ALL.len()],
    /// Set once anything has been heard: a gateway on a network with no air data
    /// never starts claiming to be the VP-X's air-data source.
    next_send: Option<Instant>,
}

impl AirData {
    /// The last sample of `input`, fresh or not.
    pub fn sample(&self, input: AirInput) -> Option<AirSample> {
        self.samples.get(input as usize).copied().flatten()
    }

    /// Takes a parameter if it is one of the five; returns which.
    pub fn offer(&mut self, src: u16, p: &Parameter, now: Instant) -> Option<AirInput> {
        let input = AirInput::from_ident(p.ident)?;
        if p.confidence == Confidence::Useless {
            return None;
        }
        let value = p.value.as_i64()?;
        let life = p.expire.duration().map_or(MAX_AGE, |d| d.min(MAX_AGE));
        let slot = self.samples.get_mut(input as usize)?;
        *slot = Some(AirSample {
            value,
            at: now,
            life,
            src,
            unit: p.unit,
        });
        self.next_send.get_or_insert(now);
        Some(input)
    }

    pub fn forwarded(&self, now: Instant) -> [Forwarded; 5] {
        AirInput::ALL.map(|input| {
            let last = self.sample(input);
            Forwarded {
                input,
                last,
                fresh: last.is_some_and(|s| s.fresh(now)),
            }
        })
    }

    /// EXTERNAL_DATA as it would be sent at `now`.
    pub fn external_data(&self, now: Instant) -> ExternalData {
        let get = |i: AirInput| self.sample(i).filter(|s| s.fresh(now)).map(|s| s.value);
        let u16_of = |v: Option<i64>| v.map_or(0, |v| v.clamp(0, i64::from(u16::MAX)) as u16);
        let ias = get(AirInput::Ias);
        let gs = get(AirInput::GroundSpeed);
        let alt = get(AirInput::PressureAltitude);
        let fuel = get(AirInput::FuelPressure);
        let rpm = get(AirInput::Rpm);
        ExternalData {
            indicated_airspeed: u16_of(ias),
            ground_speed: u16_of(gs),
            baro_altitude: alt.map_or(0, |v| {
                v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
            }),
            fuel_pressure: fuel.map_or(0, |v| {
                v.clamp(i64::from(i16::MIN), i64::from(i16::MAX)) as i16
            }),
            rpm: u16_of(rpm),
            valid: ExternalValidity {
                indicated_airspeed: ias.is_some(),
                ground_speed: gs.is_some(),
                baro_altitude: alt.is_some(),
                fuel_pressure: fuel.is_some(),
                rpm: rpm.is_some(),
            },
        }
    }

    /// EXTERNAL_DATA if one is due at `now`.
    pub fn due(&mut self, now: Instant) -> Option<ExternalData> {
        let next = self.next_send?;
        if now < next {
            return None;
        }
        // Keep the 1 Hz grid unless the caller fell behind by more than a period.
        let mut n = next + SEND_PERIOD;
        if n <= now {
            n = now + SEND_PERIOD;
        }
        self.next_send = Some(n);
        Some(self.external_data(now))
    }

    pub fn next_deadline(&self) -> Option<Instant> {
        self.next_send
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xfsp::expire::Expire;
    use crate::xfsp::format::Value;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn each_input_holds_its_own_slot_in_external_data_order() {
        for (i, input) in AirInput::ALL.into_iter().enumerate() {
            assert_eq!(input as usize, i, "{input:?}");
        }
    }

    #[test]
    fn validity_follows_the_shorter_of_expire_and_two_seconds() {
        let t0 = Instant::now();
        let mut a = AirData::default();
        assert_eq!(a.due(t0), None, "nothing heard, nothing sent");
        let ias = Parameter::new(idents::IAS, Value::Sint(95)).expire(Expire::at_least(ms(600)));
        let rpm = Parameter::new(idents::ENGRPM, Value::Uint(2400)); // never expires
        assert_eq!(a.offer(7, &ias, t0), Some(AirInput::Ias));
        assert_eq!(a.offer(7, &rpm, t0), Some(AirInput::Rpm));
        let d = a.due(t0).unwrap();
        assert_eq!((d.indicated_airspeed, d.rpm), (95, 2400));
        assert!(d.valid.indicated_airspeed && d.valid.rpm && !d.valid.ground_speed);
        assert_eq!(a.due(t0 + ms(999)), None);
        let d = a.due(t0 + ms(1000)).unwrap();
        assert!(!d.valid.indicated_airspeed, "600 ms expire has run out");
        assert_eq!(
            d.indicated_airspeed, 0,
            "an invalid field carries no stale value"
        );
        assert!(d.valid.rpm);
        let d = a.due(t0 + ms(2000)).unwrap();
        assert!(d.valid.rpm, "exactly 2 s old is still fresh");
        let d = a.due(t0 + ms(3000)).unwrap();
        assert!(
            !d.valid.rpm,
            "a never-expiring value is still at most 2 s old"
        );
    }

    #[test]
    fn out_of_range_values_clamp_and_useless_is_ignored() {
        let t0 = Instant::now();
        let mut a = AirData::default();
        a.offer(1, &Parameter::new(idents::IAS, Value::Sint(-5)), t0);
        a.offer(
            1,
            &Parameter::new(idents::FUELPRES, Value::Sint(1 << 20)),
            t0,
        );
        let useless =
            Parameter::new(idents::GROUNDSPEED, Value::Uint(100)).confidence(Confidence::Useless);
        assert_eq!(a.offer(1, &useless, t0), None);
        let wrong_format = Parameter::new(idents::P_ALT, Value::string("4500"));
        assert_eq!(a.offer(1, &wrong_format, t0), None);
        let d = a.external_data(t0);
        assert_eq!((d.indicated_airspeed, d.fuel_pressure), (0, i16::MAX));
        assert!(!d.valid.ground_speed && !d.valid.baro_altitude);
    }

    #[test]
    fn a_late_caller_does_not_get_a_burst() {
        let t0 = Instant::now();
        let mut a = AirData::default();
        a.offer(1, &Parameter::new(idents::IAS, Value::Sint(60)), t0);
        assert!(a.due(t0).is_some());
        assert!(a.due(t0 + ms(5500)).is_some());
        assert!(a.due(t0 + ms(5600)).is_none());
        assert_eq!(a.next_deadline(), Some(t0 + ms(6500)));
    }
}

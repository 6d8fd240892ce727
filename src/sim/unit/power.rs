//! Power physics: which pins are on (switches, overrides, alternators, wig-wag,
//! starter), the faults powering them trips, and what they draw.

use std::time::{Duration, Instant};

use super::{STARTER_CUTOUT_RPM, Unit, WIG_WAG_HALF_PERIOD, motor_index, motor_of_device};
use crate::protocol::FaultCode;
use crate::protocol::device::{self, DEVICE_COUNT, EFIS, FIELD_PRI, STARTER};
use crate::protocol::message::{OvervoltageLimit, SwitchId, WigWagModeSetting};
use crate::sim::scenario::MotorId;

/// Motor currents while running, amps (the ICD gives none).
const FLAP_MOTOR_AMPS: f32 = 3.5;
const TRIM_MOTOR_AMPS: f32 = 0.8;

impl Unit {
    fn switch_on(&self, s: SwitchId) -> bool {
        match s {
            SwitchId::Off => false,
            SwitchId::Input(n) => self.switches.get(n as usize - 1).copied().unwrap_or(false),
            SwitchId::AlwaysOn => true,
            SwitchId::Unknown(_) => false,
        }
    }

    /// What the pin would be without faults: its switch, or a DEVICE_POWER override.
    fn commanded(&self, id: usize) -> bool {
        self.overrides[id].unwrap_or_else(|| self.switch_on(self.config.devices[id].switch_id))
    }

    /// Recomputes every pin: switches, overrides, alternators, wig-wag, starter, and
    /// the faults that powering a pin can trip. A tripped alternator is replaced by
    /// the other one in the same instant.
    pub(super) fn update_power(&mut self, now: Instant) {
        for _ in 0..3 {
            if !self.compute_power(now) {
                break;
            }
        }
    }

    /// One pass of [`Unit::update_power`]; `true` when an alternator tripped.
    fn compute_power(&mut self, now: Instant) -> bool {
        if self.in_bootloader() {
            self.powered = [false; DEVICE_COUNT];
            return false;
        }
        // Starter: Appendix B note 1.
        if self.starter_pressed && self.rpm(now).is_some_and(|r| r > STARTER_CUTOUT_RPM) {
            self.starter_pressed = false;
            self.log("starter cut out: engine RPM above 500".into());
        }
        let mut want = [false; DEVICE_COUNT];
        for (id, w) in want.iter_mut().enumerate().skip(EFIS as usize) {
            if id <= 28 {
                *w = self.commanded(id);
            }
        }
        want[STARTER as usize] = self.starter_pressed;
        // "Only one alternator runs at a time." Decision: the primary wins; the
        // secondary runs only while the primary is off or faulted.
        let primary_on = want[FIELD_PRI as usize] && !self.faults[FIELD_PRI as usize].is_fault();
        if let Some(sec) = self.config.system.secondary_alternator
            && primary_on
            && let Some(w) = want.get_mut(sec as usize)
        {
            *w = false;
        }
        self.apply_wig_wag(&mut want, now);

        #[allow(clippy::needless_range_loop)] // `id` indexes five arrays and names the pin
        for id in 1..=28usize {
            if !want[id] || self.faults[id].is_fault() {
                continue;
            }
            let spec = self.config.devices[id];
            let load = self.load(id);
            let code = if self.shorts[id] {
                FaultCode::ShortCircuit
            } else if load > spec.circuit_breaker as f32 {
                FaultCode::OverCurrent
            } else if spec.current_fault
                && device::device(id as u8).is_some_and(|d| d.current_fault_support)
                && load <= 0.0
            {
                FaultCode::CurrentFault
            } else {
                continue;
            };
            self.faults[id] = code;
            self.log(format!(
                "device {id} ({}): {}",
                device::device(id as u8).map_or("?", |d| d.system_name),
                code.name()
            ));
        }
        for (id, p) in self.powered.iter_mut().enumerate() {
            *p = match motor_of_device(id as u8) {
                Some(m) => self.motors[motor_index(m)].running(now),
                None => want[id] && !self.faults[id].is_fault(),
            };
        }

        // Table 14 note 1: above the limit the active alternator is turned off.
        let limit = match self.config.system.overvoltage_limit {
            OvervoltageLimit::V32 => 32.0,
            _ => 16.0,
        };
        let mut tripped = false;
        if let Some(alt) = self.active_alternator()
            && self.bus_volts(0.0) > limit
        {
            self.faults[alt] = FaultCode::OverVoltage;
            self.powered[alt] = false;
            self.regulator_volts = None;
            tripped = true;
            self.log(format!("device {alt}: OVER_VOLTAGE, alternator off"));
        }

        // Table 24 notes 2, 3: 48 A follows the current; 60 A clears below 48 A.
        let total = self.total_amps();
        self.over_48 = total > 48.0;
        if total > 60.0 {
            self.over_60 = true;
        } else if total < 48.0 {
            self.over_60 = false;
        }
        tripped
    }

    fn apply_wig_wag(&mut self, want: &mut [bool; DEVICE_COUNT], now: Instant) {
        let ww = self.config.wig_wag;
        let devices: Vec<usize> = [ww.device_one, ww.device_two]
            .into_iter()
            .flatten()
            .map(|d| d as usize)
            .filter(|&d| d < DEVICE_COUNT)
            .collect();
        let lit = !devices.is_empty() && devices.iter().all(|&d| want[d]);
        if !lit {
            self.wig_wag_since = None;
            self.wig_wag_active = false;
            return;
        }
        let since = *self.wig_wag_since.get_or_insert(now);
        let warm =
            now.saturating_duration_since(since) >= Duration::from_secs(ww.warm_up_period as u64);
        // Table 17: "the speed at which the wig-wag function is engaged"; Table 44:
        // "speed to start wig-wag" (70). Decision: the lights flash at that speed and
        // above (in flight, where they make the aircraft seen) and burn steady below it
        // (taxiing, where they light the way). Note 4: no valid speed, no wig-wag.
        let fast_enough = self.speed(now).is_some_and(|s| s >= ww.speed as u16);
        self.wig_wag_active = self.wig_wag_mode == WigWagModeSetting::Auto && warm && fast_enough;
        if self.wig_wag_active {
            let phase = (now.saturating_duration_since(since).as_millis()
                / WIG_WAG_HALF_PERIOD.as_millis())
                % 2;
            for (i, &d) in devices.iter().enumerate() {
                want[d] = (i as u128 % 2) == phase;
            }
        }
    }

    fn active_alternator(&self) -> Option<usize> {
        if self.powered[FIELD_PRI as usize] {
            return Some(FIELD_PRI as usize);
        }
        self.config
            .system
            .secondary_alternator
            .map(|s| s as usize)
            .filter(|&s| self.powered.get(s).copied().unwrap_or(false))
    }

    pub(super) fn bus_volts(&self, noise: f32) -> f32 {
        match self.active_alternator() {
            Some(_) => self.regulator_volts.unwrap_or(self.nominal_volts) + noise,
            // On the battery alone the bus sags with the load.
            None => self.battery_volts - 0.02 * self.total_amps() + noise,
        }
    }

    pub(super) fn amps(&self, id: usize) -> f32 {
        if !self.powered[id] {
            return 0.0;
        }
        match motor_of_device(id as u8) {
            Some(MotorId::Flap) => FLAP_MOTOR_AMPS,
            Some(_) => TRIM_MOTOR_AMPS,
            None => self.load(id),
        }
    }

    /// What the pin's wiring draws while powered: nothing if the load is not connected.
    fn load(&self, id: usize) -> f32 {
        if self.open_circuits[id] {
            0.0
        } else {
            self.loads[id]
        }
    }

    pub(super) fn total_amps(&self) -> f32 {
        (0..DEVICE_COUNT).map(|i| self.amps(i)).sum()
    }
}

//! What is done to the unit from outside the wire: a person at the switches, a
//! test's injected fault, the scenario's timeline ([`SimCommand`]).

use std::time::{Duration, Instant};

use super::{Mode, Start, Unit, motor_index, motor_of_device};
use crate::protocol::FaultCode;
use crate::protocol::message::{DeviceName, DevicePower, SwitchId};
use crate::sim::scenario::{EventAction, MotorDirection, MotorId};

/// Something done to the unit from outside the wire: by a test, the page's demo, or a
/// scenario's timeline.
#[derive(Debug, Clone, PartialEq)]
pub enum SimCommand {
    /// Another display on the unit's serial bus sends DEVICE_POWER: the unit holds
    /// the device so until its switch changes, and the page never hears of it.
    OtherDisplayPower { device: u8, on: bool },
    /// Cockpit switch 1–10 is set on (closed) or off, as a person would. It drives
    /// the unit's input of the same number, unless the scenario's wiring says
    /// otherwise (`dead_switches`, `crossed_switches`).
    Switch { switch: u8, on: bool },
    /// A person flips cockpit switch 1–10 to its other position, and back after
    /// `hold`. Decision: the unit broadcasts its inputs at 1 Hz (SYSTEM_STATUS), so a
    /// hold under about a second may never be seen by a page, as on a real unit.
    FlipSwitch { switch: u8, hold: Duration },
    /// The device faults now with `code` (for 0, 29, 30: the motor's fault).
    Fault { device: u8, code: FaultCode },
    /// A short appears on (or leaves) a pin: SHORT_CIRCUIT whenever it is powered.
    Short { device: u8, on: bool },
    /// The pin's load changes, amps.
    Load { device: u8, amps: f32 },
    /// Nothing leaves the unit for this long; requests are still taken in.
    Silent(Duration),
    /// The unit's name for a device changes, as if set from another display (stored
    /// in its EEPROM, and nothing on the wire says so).
    Rename(DeviceName),
    /// This many pseudo-random bytes go out on the wire.
    GarbageRandom(usize),
    /// The running alternator's regulator now holds this many volts.
    BusVolts(f32),
    /// Engine RPM the unit sees (as if valid in EXTERNAL_DATA); `None` forgets it.
    Rpm(Option<u16>),
    /// The starter button is pressed or released.
    Starter(bool),
    /// The motor runs by itself until the unit trips a runaway fault.
    Runaway {
        motor: MotorId,
        direction: MotorDirection,
    },
    /// The flap or trim switch input is held in a direction, or released.
    MotorSwitch {
        motor: MotorId,
        direction: Option<MotorDirection>,
    },
    /// A person holds the flap or trim switch in `direction` and lets go after
    /// `hold` (the motor runs as the switch drives it, meanwhile).
    PressMotorSwitch {
        motor: MotorId,
        direction: MotorDirection,
        hold: Duration,
    },
    /// Sets the system fault bit of FAULT_STATUS.
    SystemFault,
    /// Power off and on: RAM state is lost, the EEPROM is read again.
    PowerCycle,
    /// A processor reset without a power cycle (CU Warm Reset, Table 24 note 4).
    WarmReset,
    /// The next FLASH_PROG in the bootloader writes one byte wrong.
    CorruptNextFlashProg,
    /// SPEC_ACKs are lost (or no longer lost) on the way out, as on a noisy line: the
    /// unit still applies and stores each spec and keeps broadcasting.
    DropSpecAcks(bool),
}

impl SimCommand {
    /// The command a scenario event stands for.
    pub fn from_event(a: &EventAction) -> SimCommand {
        match *a {
            EventAction::Switch { switch, on } => SimCommand::Switch { switch, on },
            EventAction::Fault { device, code } => SimCommand::Fault {
                device,
                code: code.code(),
            },
            EventAction::Short { device, on } => SimCommand::Short { device, on },
            EventAction::Load { device, amps } => SimCommand::Load { device, amps },
            EventAction::Silent { seconds } => {
                SimCommand::Silent(Duration::from_secs_f64(seconds.max(0.0)))
            }
            EventAction::Garbage { bytes } => SimCommand::GarbageRandom(bytes),
            EventAction::BusVolts { volts } => SimCommand::BusVolts(volts),
            EventAction::Rpm { rpm } => SimCommand::Rpm(rpm),
            EventAction::Starter { on } => SimCommand::Starter(on),
            EventAction::Runaway { motor, direction } => SimCommand::Runaway { motor, direction },
            EventAction::MotorSwitch { motor, direction } => {
                SimCommand::MotorSwitch { motor, direction }
            }
            EventAction::SystemFault => SimCommand::SystemFault,
            EventAction::PowerCycle => SimCommand::PowerCycle,
            EventAction::WarmReset => SimCommand::WarmReset,
            EventAction::DropSpecAcks { on } => SimCommand::DropSpecAcks(on),
        }
    }
}

impl Unit {
    /// Something done from outside the wire.
    pub fn apply(&mut self, c: SimCommand, now: Instant) {
        match c {
            SimCommand::Switch { switch, on } => self.set_cockpit_switch(switch, on),
            SimCommand::FlipSwitch { switch, hold } => {
                if let Some(&was) = self.cockpit.get((switch as usize).wrapping_sub(1)) {
                    self.set_cockpit_switch(switch, !was);
                    self.pending
                        .push((now + hold, SimCommand::Switch { switch, on: was }));
                }
            }
            SimCommand::Fault { device, code } => {
                if let Some(m) = motor_of_device(device) {
                    self.motors[motor_index(m)].set_fault(code, now);
                } else if let Some(f) = self.faults.get_mut(device as usize) {
                    *f = code;
                }
                self.log(format!("device {device}: {} injected", code.name()));
            }
            SimCommand::OtherDisplayPower { device, on } => {
                self.log(format!("another display: DEVICE_POWER {device} {on}"));
                self.device_power(
                    DevicePower {
                        device_id: device,
                        on,
                    },
                    now,
                );
            }
            SimCommand::Short { device, on } => {
                if let Some(s) = self.shorts.get_mut(device as usize) {
                    *s = on;
                }
            }
            SimCommand::Load { device, amps } => {
                if let Some(l) = self.loads.get_mut(device as usize) {
                    *l = amps.max(0.0);
                }
            }
            SimCommand::Silent(d) => {
                self.log(format!("going silent for {:.1} s", d.as_secs_f64()));
                self.silent_until = Some(now + d);
            }
            SimCommand::Rename(name) => {
                let mut cfg = self.config.clone();
                cfg.apply_device_name(&name);
                if self.commit(cfg) {
                    self.log(format!(
                        "device {} renamed {:?}",
                        name.device_id,
                        name.text()
                    ));
                }
            }
            SimCommand::DropSpecAcks(on) => {
                self.log(format!(
                    "{} SPEC_ACKs",
                    if on { "dropping" } else { "sending" }
                ));
                self.drop_spec_acks = on;
            }
            SimCommand::GarbageRandom(n) => {
                let bytes: Vec<u8> = (0..n).map(|_| self.rng.next() as u8).collect();
                self.emit_raw(&bytes, now);
            }
            SimCommand::BusVolts(v) => self.regulator_volts = Some(v),
            SimCommand::Rpm(r) => self.engine_rpm = r,
            SimCommand::Starter(on) => self.starter_pressed = on,
            SimCommand::Runaway { motor, direction } => {
                let g = self.geometry(motor, now);
                self.motors[motor_index(motor)].runaway(direction, &g, now);
                self.log(format!("{motor:?} motor runaway injected"));
            }
            SimCommand::MotorSwitch { motor, direction } => {
                let g = self.geometry(motor, now);
                let inhibited = motor == MotorId::Flap
                    && direction == Some(MotorDirection::Down)
                    && self.flap_down_inhibited(now);
                let held = if inhibited { None } else { direction };
                self.motors[motor_index(motor)].switch(held, &g, now);
            }
            SimCommand::PressMotorSwitch {
                motor,
                direction,
                hold,
            } => {
                self.apply(
                    SimCommand::MotorSwitch {
                        motor,
                        direction: Some(direction),
                    },
                    now,
                );
                let release = SimCommand::MotorSwitch {
                    motor,
                    direction: None,
                };
                self.pending.push((now + hold, release));
            }
            SimCommand::SystemFault => self.system_fault = true,
            SimCommand::PowerCycle => {
                self.log("power cycle".into());
                self.boot(now, Start::Cold);
            }
            SimCommand::WarmReset => {
                self.log("warm reset".into());
                self.boot(now, Start::Warm);
            }
            SimCommand::CorruptNextFlashProg => {
                if let Mode::Boot(b) = &mut self.mode {
                    b.corrupt_next_prog = true;
                } else {
                    self.log("CorruptNextFlashProg ignored: not in the bootloader".into());
                }
            }
        }
        self.update_power(now);
    }

    /// A cockpit switch moves; the inputs it reaches through the wiring follow.
    fn set_cockpit_switch(&mut self, switch: u8, on: bool) {
        let Some(s) = self.cockpit.get_mut((switch as usize).wrapping_sub(1)) else {
            return;
        };
        *s = on;
        let now_in = inputs(&self.cockpit, &self.switch_wiring);
        for (i, (&was, &is)) in self.switches.iter().zip(&now_in).enumerate() {
            if was != is {
                // ICD Appendix A: DEVICE_POWER overrides last "until the switch is
                // cycled". Our reading, the page's too (`model::hold`): ANY change of
                // the input ends the override, a single change, not a round trip.
                let input = SwitchId::Input(i as u8 + 1);
                for (d, spec) in self.config.devices.iter().enumerate() {
                    if spec.switch_id == input {
                        self.overrides[d] = None;
                    }
                }
            }
        }
        self.switches = now_in;
    }
}

/// The unit's inputs 1–10 as the wiring delivers the cockpit switches: an input is
/// closed when any switch wired to it is.
pub(super) fn inputs(cockpit: &[bool; 10], wiring: &[Option<usize>; 10]) -> [bool; 10] {
    let mut out = [false; 10];
    for (&on, to) in cockpit.iter().zip(wiring) {
        if let Some(i) = *to {
            out[i] |= on;
        }
    }
    out
}

//! The hands of the person in the cockpit, for a sim run by hand: one line of text
//! (`switch 3 on`, `flip 3`, `flap down`, …) becomes a [`SimCommand`]. `vpx-efis sim`
//! reads these lines from its standard input; [`HELP`] lists them.

use std::time::Duration;

use super::scenario::{MotorDirection, MotorId};
use super::unit::SimCommand;
use crate::protocol::FaultCode;
use crate::protocol::message::DeviceName;

/// How long `flip N` holds the switch in its other position when no time is given:
/// long enough for two of the unit's 1 Hz SYSTEM_STATUS broadcasts to show it.
pub const DEFAULT_FLIP_HOLD: Duration = Duration::from_secs(2);
/// The longest hold `flip` accepts; more is surely a typo.
pub const MAX_FLIP_HOLD_S: f64 = 3600.0;

/// What the console understands, for `help` and for a line it does not.
pub const HELP: &str = "\
commands (one per line):
  switch N on|off         set cockpit switch N (1-10), through the scenario's wiring
  flip N [SECONDS]        flip switch N to its other position and back after SECONDS (2)
  flap up|down|off        hold the flap switch, or let it go
  trim pitch|roll up|down|off
                          hold a trim switch, or let it go
  press flap|pitch|roll up|down [SECONDS]
                          hold that switch and let go after SECONDS (2)
  load DEVICE AMPS        the pin's load changes
  short DEVICE on|off     a short appears on the pin, or goes away
  power DEVICE on|off     another display sends DEVICE_POWER (held until the switch changes)
  fault DEVICE CODE       the device faults now (Appendix E code number)
  name DEVICE TEXT        the unit's name for the device changes (up to 16 characters),
                          as if set from another display: nothing on the wire says so
  silent SECONDS          nothing leaves the unit for SECONDS (a cable out): the page
                          shows COMMUNICATION LOST after 2.5 s
  help                    this list";

/// One line of the console, understood.
#[derive(Debug, Clone, PartialEq)]
pub enum ConsoleLine {
    /// Nothing to do (a blank line or a `#` comment).
    Nothing,
    Help,
    Command(SimCommand),
}

/// Reads one console line. The error says what was wrong, in words.
pub fn parse_line(line: &str) -> Result<ConsoleLine, String> {
    let line = line.split('#').next().unwrap_or("");
    // A name keeps its letters' case and its spaces.
    if let Some((first, rest)) = line.trim().split_once(char::is_whitespace)
        && first.eq_ignore_ascii_case("name")
    {
        return rename(rest.trim()).map(ConsoleLine::Command);
    }
    let words: Vec<String> = line.split_whitespace().map(str::to_lowercase).collect();
    let w: Vec<&str> = words.iter().map(String::as_str).collect();
    let cmd = match w.as_slice() {
        [] => return Ok(ConsoleLine::Nothing),
        ["help"] | ["?"] => return Ok(ConsoleLine::Help),
        ["switch", n, state] => SimCommand::Switch {
            switch: switch_number(n)?,
            on: on_off(state)?,
        },
        ["flip", n] => SimCommand::FlipSwitch {
            switch: switch_number(n)?,
            hold: DEFAULT_FLIP_HOLD,
        },
        ["flip", n, secs] => SimCommand::FlipSwitch {
            switch: switch_number(n)?,
            hold: seconds(secs)?,
        },
        ["flap", dir] => SimCommand::MotorSwitch {
            motor: MotorId::Flap,
            direction: direction(dir)?,
        },
        ["trim", axis, dir] => SimCommand::MotorSwitch {
            motor: match *axis {
                "pitch" => MotorId::Pitch,
                "roll" => MotorId::Roll,
                other => return Err(format!("trim {other:?}: say pitch or roll")),
            },
            direction: direction(dir)?,
        },
        ["press", motor, dir] => press(motor, dir, DEFAULT_FLIP_HOLD)?,
        ["press", motor, dir, secs] => press(motor, dir, seconds(secs)?)?,
        ["load", d, amps] => {
            let amps: f32 = amps
                .parse()
                .ok()
                .filter(|a: &f32| a.is_finite() && *a >= 0.0)
                .ok_or_else(|| format!("load {amps:?}: give amps, 0 or more"))?;
            SimCommand::Load {
                device: device(d)?,
                amps,
            }
        }
        ["short", d, state] => SimCommand::Short {
            device: device(d)?,
            on: on_off(state)?,
        },
        ["power", d, state] => SimCommand::OtherDisplayPower {
            device: device(d)?,
            on: on_off(state)?,
        },
        ["silent", secs] => SimCommand::Silent(seconds(secs)?),
        ["fault", d, code] => {
            let code: u8 = code
                .parse()
                .map_err(|_| format!("fault code {code:?}: give a number (Appendix E)"))?;
            SimCommand::Fault {
                device: device(d)?,
                code: FaultCode::from_byte(code),
            }
        }
        _ => {
            return Err(format!(
                "not understood: {:?} (type `help` for the list)",
                line.trim()
            ));
        }
    };
    Ok(ConsoleLine::Command(cmd))
}

/// `name DEVICE TEXT`: the text is the rest of the line, as DEVICE_NAME holds it.
fn rename(rest: &str) -> Result<SimCommand, String> {
    let (d, text) = rest
        .split_once(char::is_whitespace)
        .ok_or_else(|| "name: give a device and its new name".to_string())?;
    let text = text.trim();
    DeviceName::new(device(d)?, text)
        .map(SimCommand::Rename)
        .ok_or_else(|| format!("name {text:?}: up to 16 plain (ASCII) characters"))
}

fn press(motor: &str, dir: &str, hold: Duration) -> Result<SimCommand, String> {
    let motor = match motor {
        "flap" | "flaps" => MotorId::Flap,
        "pitch" => MotorId::Pitch,
        "roll" => MotorId::Roll,
        other => return Err(format!("press {other:?}: say flap, pitch or roll")),
    };
    let direction = direction(dir)?.ok_or_else(|| format!("press {dir:?}: say up or down"))?;
    Ok(SimCommand::PressMotorSwitch {
        motor,
        direction,
        hold,
    })
}

fn switch_number(n: &str) -> Result<u8, String> {
    n.parse()
        .ok()
        .filter(|s| (1..=10).contains(s))
        .ok_or_else(|| format!("switch {n:?}: give a switch from 1 to 10"))
}

fn device(n: &str) -> Result<u8, String> {
    n.parse()
        .ok()
        .filter(|d| crate::protocol::device::device(*d).is_some())
        .ok_or_else(|| format!("device {n:?}: give a device from 0 to 30"))
}

fn on_off(s: &str) -> Result<bool, String> {
    match s {
        "on" | "closed" | "1" => Ok(true),
        "off" | "open" | "0" => Ok(false),
        other => Err(format!("{other:?}: say on or off")),
    }
}

fn direction(s: &str) -> Result<Option<MotorDirection>, String> {
    match s {
        "up" | "left" => Ok(Some(MotorDirection::Up)),
        "down" | "right" => Ok(Some(MotorDirection::Down)),
        "off" | "release" => Ok(None),
        other => Err(format!("{other:?}: say up, down or off")),
    }
}

fn seconds(s: &str) -> Result<Duration, String> {
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && (0.0..=MAX_FLIP_HOLD_S).contains(v))
        .map(Duration::from_secs_f64)
        .ok_or_else(|| format!("{s:?}: give seconds from 0 to {MAX_FLIP_HOLD_S}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cmd(line: &str) -> SimCommand {
        match parse_line(line) {
            Ok(ConsoleLine::Command(c)) => c,
            other => panic!("{line:?}: {other:?}"),
        }
    }

    #[test]
    fn switch_lines_set_and_flip_cockpit_switches() {
        assert_eq!(
            cmd("switch 3 on"),
            SimCommand::Switch {
                switch: 3,
                on: true
            }
        );
        assert_eq!(
            cmd("  SWITCH 10 off  "),
            SimCommand::Switch {
                switch: 10,
                on: false
            }
        );
        assert_eq!(
            cmd("flip 7"),
            SimCommand::FlipSwitch {
                switch: 7,
                hold: Duration::from_secs(2)
            }
        );
        assert_eq!(
            cmd("flip 7 3.5"),
            SimCommand::FlipSwitch {
                switch: 7,
                hold: Duration::from_millis(3500)
            }
        );
    }

    #[test]
    fn motor_switch_load_short_and_fault_lines() {
        assert_eq!(
            cmd("flap down"),
            SimCommand::MotorSwitch {
                motor: MotorId::Flap,
                direction: Some(MotorDirection::Down)
            }
        );
        assert_eq!(
            cmd("trim roll off"),
            SimCommand::MotorSwitch {
                motor: MotorId::Roll,
                direction: None
            }
        );
        assert_eq!(
            cmd("press pitch up 1.5"),
            SimCommand::PressMotorSwitch {
                motor: MotorId::Pitch,
                direction: MotorDirection::Up,
                hold: Duration::from_millis(1500)
            }
        );
        assert_eq!(
            cmd("press flap down"),
            SimCommand::PressMotorSwitch {
                motor: MotorId::Flap,
                direction: MotorDirection::Down,
                hold: Duration::from_secs(2)
            }
        );
        assert_eq!(
            cmd("load 17 7.5"),
            SimCommand::Load {
                device: 17,
                amps: 7.5
            }
        );
        assert_eq!(
            cmd("short 5 on"),
            SimCommand::Short {
                device: 5,
                on: true
            }
        );
        assert_eq!(
            cmd("fault 9 3"),
            SimCommand::Fault {
                device: 9,
                code: FaultCode::from_byte(3)
            }
        );
    }

    #[test]
    fn name_keeps_its_case_and_spaces_and_silent_takes_seconds() {
        assert_eq!(
            cmd("name 9 Taxi Lt Left"),
            SimCommand::Rename(DeviceName::new(9, "Taxi Lt Left").unwrap())
        );
        assert_eq!(
            cmd("  NAME  4   Nav  # comment"),
            SimCommand::Rename(DeviceName::new(4, "Nav").unwrap())
        );
        assert_eq!(
            cmd("silent 4.5"),
            SimCommand::Silent(Duration::from_millis(4500))
        );
    }

    #[test]
    fn blank_lines_comments_and_help() {
        assert_eq!(parse_line(""), Ok(ConsoleLine::Nothing));
        assert_eq!(parse_line("   # a note"), Ok(ConsoleLine::Nothing));
        assert_eq!(parse_line("help"), Ok(ConsoleLine::Help));
        assert_eq!(
            cmd("switch 2 on # nav"),
            SimCommand::Switch {
                switch: 2,
                on: true
            }
        );
    }

    #[test]
    fn bad_lines_say_what_is_wrong() {
        for (line, words) in [
            ("switch 11 on", "1 to 10"),
            ("switch 0 on", "1 to 10"),
            ("switch 3 maybe", "on or off"),
            ("flip 3 -1", "seconds"),
            ("flip 3 nan", "seconds"),
            ("flip 3 1e9", "seconds"),
            ("trim yaw up", "pitch or roll"),
            ("flap sideways", "up, down or off"),
            ("press yaw up", "flap, pitch or roll"),
            ("press flap off", "up or down"),
            ("load 31 1.0", "0 to 30"),
            ("load 9 -2", "0 or more"),
            ("fault 9 short", "number"),
            ("dance", "help"),
            ("name 9", "device and its new name"),
            ("name 31 Foo", "0 to 30"),
            ("name 9 seventeen chars xx", "16"),
            ("silent forever", "seconds"),
        ] {
            let err = parse_line(line).expect_err(line);
            assert!(err.contains(words), "{line}: {err}");
        }
    }
}

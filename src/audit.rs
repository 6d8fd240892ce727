//! The audit log: every command sent to the unit, with who asked for it.
//!
//! Every command to the unit, whatever asked for it (a key, the installation check,
//! the setup screens, the XFSp network, the phone remote), is recorded where they all
//! pass: the page's [`crate::app::StopGate`], which is told each packet's
//! [`Origin`]. The record is kept in the aircraft's logbook ([`crate::logbook`], its
//! table `commands`): one record, not two. `vpx-efis log --jsonl` gives it back as
//! the JSON lines the audit files of earlier versions held, one object a line:
//!
//! ```json
//! {"time":"2026-12-04T18:20:01.123Z","origin":"key","command":"DEVICE_POWER: device 5 (5A-2), on","frame":"a5…","result":"sent"}
//! ```
//!
//! `result` is `sent` (queued on the link) or `refused: …` with the words (the
//! emergency stop closed the way to moves, or the link is closed).
//!
//! What a command is: a message that changes the unit (DEVICE_POWER, DEVICE_CLEAR,
//! TRIM_MOVE, FLAP_MOVE, WIG_WAG_MODE, the spec, name and enable writes,
//! EEPROM_ERASE, SOFTWARE_UPDATE). Queries, PING and EXTERNAL_DATA (air data
//! forwarded at 1 Hz) change nothing and are not recorded.
//!
//! Decision, motor runs: a run resends its move every 125 ms (control's
//! `RESEND_PERIOD`), and eight lines a second would bury everything else. So a run is two lines: its first move (`"run":"start"`)
//! and its stop, which carries `"moves"` (how many move messages the run sent, the
//! first included) and `"seconds"`. A move in another direction ends the open run's
//! record (a line `"run":"ended by a change of direction"`) and starts a new one. A
//! stop with no run open (the stops sent at quit, on a link error) is a line of its
//! own. A run still open when the log closes gets a line saying so.
//!
//! This module is the pure part: which messages are commands, and [`Lines`], the
//! commands into lines. The writing, off the page's loop, the link's reader and the
//! 4 Hz motor stream, is the logbook's writer thread ([`crate::logbook::Recorder`]).

use std::time::SystemTime;

use crate::protocol::describe::describe;
use crate::protocol::message::{EnableFlag, Message, Packet, TrimType};

/// Who asked for a command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// A key on the page (the device list, the motor keys).
    Key,
    /// The installation check.
    Check,
    /// The setup screens' writes.
    Setup,
    /// A node on the XFSp network (`--xfsp-control`).
    Xfsp,
    /// The walk-around remote on a phone (`--remote`).
    Remote,
    /// The page itself: the stops it sends at quit, on a link error or a reconnect.
    Page,
    /// The panic hook's emergency stop ([`crate::app::StopGate::emergency_stop`]),
    /// in whichever process panicked.
    Panic,
}

impl Origin {
    pub fn word(self) -> &'static str {
        match self {
            Origin::Key => "key",
            Origin::Check => "check",
            Origin::Setup => "setup",
            Origin::Xfsp => "xfsp",
            Origin::Remote => "remote",
            Origin::Page => "page",
            Origin::Panic => "panic",
        }
    }
}

/// Whether sending `m` changes the unit (see the module's notes).
pub fn is_command(m: &Message) -> bool {
    match m {
        Message::DevicePower(_)
        | Message::DeviceClear(_)
        | Message::TrimMove(_)
        | Message::FlapMove(_)
        | Message::WigWagMode(_)
        | Message::DeviceSpec(_)
        | Message::SystemSpec(_)
        | Message::TrimSpec(_)
        | Message::FlapSpec(_)
        | Message::WigWagSpec(_)
        | Message::DeviceName(_)
        | Message::EepromErase(_)
        | Message::SoftwareUpdate(_) => true,
        Message::DeviceEnable(e) => e.flag != EnableFlag::Query,
        _ => false,
    }
}

/// One line of the audit log: a command as it went, or a motor run's start or end.
/// The logbook keeps it in `commands` ([`crate::logbook::schema`]);
/// [`crate::logbook::jsonl`] gives it back as the JSON object the audit files had.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    pub at: SystemTime,
    pub origin: &'static str,
    /// "DEVICE_POWER: device 5 (5A-2), on", or "pitch trim run" for a run's summary.
    pub command: String,
    /// The frame as sent, in hex; `None` for a run's summary line.
    pub frame: Option<String>,
    /// `sent`, or `refused: ` and the words.
    pub result: String,
    /// `start`, `stop`, `ended by a change of direction`, `unfinished`.
    pub run: Option<String>,
    /// On a stop: whose run it was.
    pub run_origin: Option<&'static str>,
    pub moves: Option<u64>,
    pub seconds: Option<f64>,
}

/// A command as the stop gate saw it, before it becomes [`Line`]s.
#[derive(Debug, Clone)]
pub struct Item {
    pub at: SystemTime,
    pub origin: Origin,
    pub packet: Packet,
    pub result: Result<(), String>,
}

/// Which motor a move is for, and its direction, for the run's record.
fn motor_of(m: &Message) -> Option<(&'static str, u8, bool)> {
    match m {
        Message::TrimMove(t) => Some((
            match t.trim_type {
                TrimType::Pitch => "pitch trim",
                TrimType::Roll => "roll trim",
                TrimType::Unknown(_) => "trim (unknown type)",
            },
            t.direction.to_byte(),
            t.on,
        )),
        Message::FlapMove(f) => Some(("flaps", f.direction.to_byte(), f.on)),
        _ => None,
    }
}

struct Run {
    motor: &'static str,
    direction: u8,
    origin: Origin,
    started: SystemTime,
    moves: u64,
}

/// The commands into lines: pure, run by the logbook's writer thread. It holds the
/// motor runs open between their first move and their stop.
#[derive(Default)]
pub struct Lines {
    runs: Vec<Run>,
}

impl Lines {
    /// The lines `item` makes (none for a run's resend, two for a change of
    /// direction).
    pub fn take(&mut self, item: Item) -> Vec<Line> {
        let sent = item.result.is_ok();
        let mut line = Line {
            at: item.at,
            origin: item.origin.word(),
            command: format!(
                "{}: {}",
                item.packet.message.name(),
                describe(&item.packet.message)
            ),
            frame: Some(hex(&item.packet.to_bytes())),
            result: match &item.result {
                Ok(()) => "sent".to_string(),
                Err(why) => format!("refused: {why}"),
            },
            run: None,
            run_origin: None,
            moves: None,
            seconds: None,
        };
        let mut out = Vec::new();
        if let Some((motor, direction, on)) = motor_of(&item.packet.message)
            && sent
        {
            let open = self.runs.iter().position(|r| r.motor == motor);
            if on {
                match open {
                    Some(i) if self.runs[i].direction == direction => {
                        self.runs[i].moves += 1;
                        return out;
                    }
                    Some(i) => {
                        let old = self.runs.remove(i);
                        out.push(ended(
                            &old,
                            item.at,
                            "ended by a change of direction",
                            "sent",
                        ));
                    }
                    None => {}
                }
                self.runs.push(Run {
                    motor,
                    direction,
                    origin: item.origin,
                    started: item.at,
                    moves: 1,
                });
                line.run = Some("start".into());
            } else if let Some(i) = open {
                let run = self.runs.remove(i);
                line.run = Some("stop".into());
                line.run_origin = Some(run.origin.word());
                line.moves = Some(run.moves);
                line.seconds = Some(seconds(run.started, item.at));
            }
        }
        out.push(line);
        out
    }

    /// The runs still open when the log closes, each a line saying so.
    pub fn close(&mut self, now: SystemTime) -> Vec<Line> {
        std::mem::take(&mut self.runs)
            .iter()
            .map(|run| {
                ended(
                    run,
                    now,
                    "unfinished",
                    "no stop recorded before the log closed",
                )
            })
            .collect()
    }
}

fn ended(run: &Run, at: SystemTime, why: &str, result: &str) -> Line {
    Line {
        at,
        origin: run.origin.word(),
        command: format!("{} run", run.motor),
        frame: None,
        result: result.into(),
        run: Some(why.into()),
        run_origin: None,
        moves: Some(run.moves),
        seconds: Some(seconds(run.started, at)),
    }
}

fn seconds(from: SystemTime, to: SystemTime) -> f64 {
    let s = to.duration_since(from).unwrap_or_default().as_secs_f64();
    (s * 1000.0).round() / 1000.0
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::message::{DevicePower, FlapMove, TrimDirection, TrimMove};

    fn trim(on: bool, direction: TrimDirection) -> Packet {
        Packet::request(
            1,
            TrimMove {
                trim_type: TrimType::Pitch,
                on,
                direction,
            },
        )
    }

    fn item(origin: Origin, packet: Packet, result: Result<(), &str>) -> Item {
        Item {
            at: SystemTime::UNIX_EPOCH + std::time::Duration::from_secs(1_796_000_000),
            origin,
            packet,
            result: result.map_err(str::to_string),
        }
    }

    /// A run of 10 moves is two lines; a change of direction ends one run and
    /// starts another; a refusal says why; a run open at the close says so.
    #[test]
    fn a_run_is_two_lines() {
        let mut lines = Lines::default();
        let mut l: Vec<Line> = Vec::new();
        let mut take = |lines: &mut Lines, i| l.extend(lines.take(i));
        let power = Packet::request(
            7,
            DevicePower {
                device_id: 5,
                on: true,
            },
        );
        take(&mut lines, item(Origin::Key, power, Ok(())));
        for _ in 0..10 {
            take(
                &mut lines,
                item(Origin::Check, trim(true, TrimDirection::UpOrLeft), Ok(())),
            );
        }
        for _ in 0..3 {
            take(
                &mut lines,
                item(
                    Origin::Check,
                    trim(true, TrimDirection::DownOrRight),
                    Ok(()),
                ),
            );
        }
        take(
            &mut lines,
            item(
                Origin::Check,
                trim(false, TrimDirection::DownOrRight),
                Ok(()),
            ),
        );
        let flap = |on| {
            Packet::request(
                3,
                FlapMove {
                    on,
                    direction: crate::protocol::message::FlapDirection::Down,
                },
            )
        };
        take(
            &mut lines,
            item(
                Origin::Key,
                flap(true),
                Err("the emergency stop has gone out"),
            ),
        );
        take(&mut lines, item(Origin::Remote, flap(true), Ok(())));
        l.extend(
            lines.close(SystemTime::UNIX_EPOCH + std::time::Duration::from_secs(1_796_000_002)),
        );
        let runs: Vec<&str> = l.iter().map(|v| v.run.as_deref().unwrap_or("-")).collect();
        assert_eq!(
            runs,
            [
                "-",
                "start",
                "ended by a change of direction",
                "start",
                "stop",
                "-",
                "start",
                "unfinished"
            ],
            "{l:#?}"
        );
        assert_eq!(l[0].origin, "key");
        assert_eq!(l[0].result, "sent");
        assert_eq!(crate::utc::utc_text(l[0].at), "2026-11-30T00:53:20.000Z");
        assert!(l[0].command.starts_with("DEVICE_POWER: "), "{l:#?}");
        // The whole frame as sent: sync E7 7E, DEVICE_POWER's id 13 00, command number
        // 07, then (after the header's other bytes) the payload: device 5, 1 for on.
        let frame = l[0].frame.as_deref().unwrap();
        assert!(frame.starts_with("e77e130007"), "{frame}");
        assert_eq!(&frame[frame.len() - 6..frame.len() - 2], "0501", "{frame}");
        assert_eq!(l[2].moves, Some(10));
        assert!(l[2].frame.is_none(), "a run's summary has no frame");
        assert_eq!((l[4].moves, l[4].origin), (Some(3), "check"));
        assert_eq!(l[5].result, "refused: the emergency stop has gone out");
        assert_eq!(l[7].origin, "remote");
        assert_eq!(l[7].result, "no stop recorded before the log closed");
        assert_eq!(l[7].seconds, Some(2.0));
        // A run's stop carries every field: the frame, the run, whose run, moves, time.
        let stop = &l[4];
        assert!(
            stop.frame.is_some()
                && stop.run.is_some()
                && stop.run_origin.is_some()
                && stop.seconds.is_some(),
            "{stop:#?}"
        );
    }
}

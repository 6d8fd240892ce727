//! The audit log: the record of what was done to the aircraft that day.
//!
//! Every command to the unit, whatever asked for it (a key, the installation check,
//! the setup screens, the XFSp network, the phone remote), is recorded where they all
//! pass: the page's [`crate::app::StopGate`], which is told each packet's
//! [`Origin`]. One JSON object a line, in `vpx-audit-YYYY-MM-DD.jsonl` (the UTC day)
//! in the reports folder beside the check's reports:
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
//! The writing never blocks the page's loop, the link's reader or the 4 Hz motor
//! stream: [`Audit::record`] only puts the packet on a channel; a thread of its own
//! formats, appends and flushes (whenever the channel is empty, so each line is on
//! the disk within moments, and a burst costs one flush). A file that cannot be
//! written is reported once through [`Audit::take_problem`], and recording goes on
//! trying with the next line.

use std::fs::OpenOptions;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::SystemTime;

use crossbeam_channel::{Receiver, Sender, unbounded};
use serde_json::{Value, json};

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

/// The file for the UTC day of `at` in `dir`.
pub fn file_for(dir: &Path, at: SystemTime) -> PathBuf {
    let day = &crate::utc::utc_text(at)[..10];
    dir.join(format!("vpx-audit-{day}.jsonl"))
}

struct Item {
    at: SystemTime,
    origin: Origin,
    packet: Packet,
    result: Result<(), String>,
}

/// The way to the audit log: cheap to clone, never blocks.
#[derive(Clone)]
pub struct Audit {
    tx: Sender<Item>,
    problem: Arc<Mutex<Option<String>>>,
}

/// The writer thread; dropping every [`Audit`] ends it after the last line.
pub struct AuditThread(Option<JoinHandle<()>>);

impl AuditThread {
    /// Waits for the lines already recorded to be written (after the last `Audit`
    /// is dropped).
    pub fn join(mut self) {
        if let Some(t) = self.0.take() {
            let _ = t.join();
        }
    }
}

impl Audit {
    /// Starts the writer for files in `dir` (made if missing, at the first line).
    pub fn start(dir: PathBuf) -> std::io::Result<(Audit, AuditThread)> {
        let (tx, rx) = unbounded();
        let problem = Arc::new(Mutex::new(None));
        let p = problem.clone();
        let t = std::thread::Builder::new()
            .name("audit".into())
            .spawn(move || Writer::new(dir, p).run(&rx))?;
        Ok((Audit { tx, problem }, AuditThread(Some(t))))
    }

    /// Records `packet` if it is a command; `result` is `Err(words)` when it was not
    /// sent.
    pub fn record(&self, origin: Origin, packet: &Packet, result: Result<(), &str>) {
        if !is_command(&packet.message) {
            return;
        }
        let _ = self.tx.send(Item {
            at: SystemTime::now(),
            origin,
            packet: *packet,
            result: result.map_err(str::to_string),
        });
    }

    /// A failure to write the file, once, for the event log.
    pub fn take_problem(&self) -> Option<String> {
        self.problem.lock().ok()?.take()
    }
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

struct Writer {
    dir: PathBuf,
    out: Option<(PathBuf, BufWriter<std::fs::File>)>,
    runs: Vec<Run>,
    problem: Arc<Mutex<Option<String>>>,
    said_problem: bool,
}

impl Writer {
    fn new(dir: PathBuf, problem: Arc<Mutex<Option<String>>>) -> Writer {
        Writer {
            dir,
            out: None,
            runs: Vec::new(),
            problem,
            said_problem: false,
        }
    }

    fn run(mut self, rx: &Receiver<Item>) {
        while let Ok(item) = rx.recv() {
            self.take(item);
            while let Ok(item) = rx.try_recv() {
                self.take(item);
            }
            self.flush();
        }
        let now = SystemTime::now();
        for run in std::mem::take(&mut self.runs) {
            let line = json!({
                "time": crate::utc::utc_text(now),
                "origin": run.origin.word(),
                "command": format!("{} run", run.motor),
                "result": "no stop recorded before the log closed",
                "run": "unfinished",
                "moves": run.moves,
                "seconds": seconds(run.started, now),
            });
            self.write(now, &line);
        }
        self.flush();
    }

    fn take(&mut self, item: Item) {
        let sent = item.result.is_ok();
        let mut line = json!({
            "time": crate::utc::utc_text(item.at),
            "origin": item.origin.word(),
            "command": format!(
                "{}: {}",
                item.packet.message.name(),
                describe(&item.packet.message)
            ),
            "frame": hex(&item.packet.to_bytes()),
            "result": match &item.result {
                Ok(()) => "sent".to_string(),
                Err(why) => format!("refused: {why}"),
            },
        });
        if let Some((motor, direction, on)) = motor_of(&item.packet.message)
            && sent
        {
            let open = self.runs.iter().position(|r| r.motor == motor);
            if on {
                match open {
                    Some(i) if self.runs[i].direction == direction => {
                        self.runs[i].moves += 1;
                        return;
                    }
                    Some(i) => {
                        let old = self.runs.remove(i);
                        self.write(
                            item.at,
                            &ended(&old, item.at, "ended by a change of direction"),
                        );
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
                line["run"] = "start".into();
            } else if let Some(i) = open {
                let run = self.runs.remove(i);
                line["run"] = "stop".into();
                line["run_origin"] = run.origin.word().into();
                line["moves"] = run.moves.into();
                line["seconds"] = seconds(run.started, item.at).into();
            }
        }
        self.write(item.at, &line);
    }

    fn write(&mut self, at: SystemTime, line: &Value) {
        let path = file_for(&self.dir, at);
        if self.out.as_ref().is_none_or(|(p, _)| *p != path) {
            self.flush();
            let opened = std::fs::create_dir_all(&self.dir)
                .and_then(|()| OpenOptions::new().create(true).append(true).open(&path));
            match opened {
                Ok(f) => self.out = Some((path, BufWriter::new(f))),
                Err(e) => {
                    self.out = None;
                    return self.fail(format!("cannot open {}: {e}", path.display()));
                }
            }
        }
        if let Some((path, w)) = self.out.as_mut()
            && let Err(e) = writeln!(w, "{line}")
        {
            let msg = format!("cannot write {}: {e}", path.display());
            self.out = None;
            self.fail(msg);
        }
    }

    fn flush(&mut self) {
        if let Some((path, w)) = self.out.as_mut()
            && let Err(e) = w.flush()
        {
            let msg = format!("cannot write {}: {e}", path.display());
            self.out = None;
            self.fail(msg);
        }
    }

    fn fail(&mut self, msg: String) {
        if !self.said_problem {
            self.said_problem = true;
            if let Ok(mut p) = self.problem.lock() {
                *p = Some(format!("audit log: {msg}"));
            }
        }
    }
}

fn ended(run: &Run, at: SystemTime, why: &str) -> Value {
    json!({
        "time": crate::utc::utc_text(at),
        "origin": run.origin.word(),
        "command": format!("{} run", run.motor),
        "result": "sent",
        "run": why,
        "moves": run.moves,
        "seconds": seconds(run.started, at),
    })
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
    use crate::protocol::message::{
        DevicePower, DeviceSpecQuery, ExternalData, FlapMove, TrimDirection, TrimMove,
    };

    fn lines(dir: &Path) -> Vec<Value> {
        let mut out = Vec::new();
        for e in std::fs::read_dir(dir).unwrap() {
            let text = std::fs::read_to_string(e.unwrap().path()).unwrap();
            for l in text.lines() {
                out.push(serde_json::from_str(l).expect("each line is JSON"));
            }
        }
        out
    }

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

    /// A run of 10 moves is two lines; a change of direction ends one run and
    /// starts another; queries and air data are not commands; a refusal says why.
    #[test]
    fn a_run_is_two_lines_and_only_commands_are_recorded() {
        let dir = tempfile::tempdir().unwrap();
        let (audit, thread) = Audit::start(dir.path().join("reports")).unwrap();
        let power = Packet::request(
            7,
            DevicePower {
                device_id: 5,
                on: true,
            },
        );
        audit.record(Origin::Key, &power, Ok(()));
        audit.record(
            Origin::Page,
            &Packet::request(8, DeviceSpecQuery { device_id: 5 }),
            Ok(()),
        );
        audit.record(
            Origin::Xfsp,
            &Packet::request(9, ExternalData::default()),
            Ok(()),
        );
        for _ in 0..10 {
            audit.record(Origin::Check, &trim(true, TrimDirection::UpOrLeft), Ok(()));
        }
        for _ in 0..3 {
            audit.record(
                Origin::Check,
                &trim(true, TrimDirection::DownOrRight),
                Ok(()),
            );
        }
        audit.record(
            Origin::Check,
            &trim(false, TrimDirection::DownOrRight),
            Ok(()),
        );
        let flap = Packet::request(
            3,
            FlapMove {
                on: true,
                direction: crate::protocol::message::FlapDirection::Down,
            },
        );
        audit.record(Origin::Key, &flap, Err("the emergency stop has gone out"));
        drop(audit);
        thread.join();
        let l = lines(&dir.path().join("reports"));
        let runs: Vec<&str> = l.iter().map(|v| v["run"].as_str().unwrap_or("-")).collect();
        assert_eq!(
            runs,
            [
                "-",
                "start",
                "ended by a change of direction",
                "start",
                "stop",
                "-"
            ],
            "{l:#?}"
        );
        assert_eq!(l[0]["origin"], "key");
        assert_eq!(l[0]["result"], "sent");
        assert!(
            l[0]["command"]
                .as_str()
                .unwrap()
                .starts_with("DEVICE_POWER: "),
            "{l:#?}"
        );
        // The whole frame as sent: sync E7 7E, DEVICE_POWER's id 13 00, command number
        // 07, then (after the header's other bytes) the payload: device 5, 1 for on.
        let frame = l[0]["frame"].as_str().unwrap();
        assert!(frame.starts_with("e77e130007"), "{frame}");
        assert_eq!(&frame[frame.len() - 6..frame.len() - 2], "0501", "{frame}");
        assert_eq!(l[2]["moves"], 10);
        assert_eq!(
            (l[4]["moves"].as_u64(), l[4]["origin"].as_str()),
            (Some(3), Some("check"))
        );
        assert_eq!(l[5]["result"], "refused: the emergency stop has gone out");
        assert!(l.iter().all(|v| v["time"].as_str().unwrap().ends_with('Z')));
    }

    /// A folder that cannot be made is said once, and nothing panics.
    #[test]
    fn a_file_that_cannot_be_written_is_said_once() {
        let dir = tempfile::tempdir().unwrap();
        let blocked = dir.path().join("file");
        std::fs::write(&blocked, b"x").unwrap();
        let (audit, thread) = Audit::start(blocked.join("reports")).unwrap();
        let power = Packet::request(
            7,
            DevicePower {
                device_id: 5,
                on: true,
            },
        );
        audit.record(Origin::Key, &power, Ok(()));
        audit.record(Origin::Key, &power, Ok(()));
        let until = std::time::Instant::now() + std::time::Duration::from_secs(2);
        let mut said = None;
        while said.is_none() && std::time::Instant::now() < until {
            said = audit.take_problem();
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        let said = said.expect("the failure is said");
        assert!(said.starts_with("audit log: cannot open"), "{said}");
        drop(audit);
        thread.join();
    }
}

//! The XFSp gateway's part: a network run of a motor that moves against
//! its command is stopped within a few counts, and the record is shared with the
//! page's keys, both ways (`control::against`). On the fake clock, against the virtual
//! VP-X's pitch trim with its leads swapped (up 30, down 220). The check's own part
//! is in `src/check/tests/against.rs`; these live here because the check stands
//! beside the gateway, not above it. So does the check whose probe finds the
//! reversal, and the keys, the remote and the gateway that then refuse the motor.

use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use vpx_efis::check::state::{CheckView, MotorFinding, Outcome as Found, Step};
use vpx_efis::check::{CheckFlow, Command, Options};
use vpx_efis::control::run::Refused;
use vpx_efis::control::run_state::ReleaseMode;
use vpx_efis::control::{Controller, Direction, Handled, KeyContext, Selected, StreamerConfig};
use vpx_efis::model::{CircuitKind, CircuitState, Model, Motor, Setting, Source, TrimKind};
use vpx_efis::protocol::decoder::{Decoder, Event};
use vpx_efis::protocol::message::{Message, Packet};
use vpx_efis::sim::{Scenario, Unit, UnitOptions};
use vpx_efis::xfsp::drive::MotorDrive;

const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

/// The pitch trim alone, parked at `pos`, its leads swapped.
fn scenario(pos: u8) -> String {
    let mut s = format!(
        "description = \"gateway against\"\n[electrical]\nbattery_volts = 12.6\n\
         [flap]\nenabled = false\nup = 0\ndown = 0\nposition = 0\n\
         [pitch_trim]\nenabled = true\nup = 30\ndown = 220\nneutral = 125\npower = 100\n\
         position = {pos}\nreversed = true\n\
         [roll_trim]\nenabled = false\nup = 0\ndown = 0\nneutral = 0\n"
    );
    for id in 4..=28 {
        s.push_str(&format!("[[device]]\nid = {id}\nenabled = false\n"));
    }
    s
}

/// The page's loop without a screen: the unit, the model and the controller, 10 ms
/// at a time.
struct Rig {
    unit: Unit,
    rx: Decoder,
    model: Model,
    ctl: Controller,
    now: Instant,
    sent: Vec<Packet>,
}

fn rig(at: u8) -> Rig {
    let now = Instant::now();
    let s = Scenario::from_toml(&scenario(at)).unwrap();
    let mut model = Model::new(Source::Simulated {
        scenario: "gateway".into(),
    });
    model.note_connected(now, "test".into());
    let mut r = Rig {
        unit: Unit::with_memory_eeprom(&s, UnitOptions::default(), now),
        rx: Decoder::new(),
        model,
        ctl: Controller::new(StreamerConfig {
            release_mode: ReleaseMode::KeyRelease,
            ..StreamerConfig::default()
        }),
        now,
        sent: Vec::new(),
    };
    let queries: Vec<Packet> = Setting::all()
        .enumerate()
        .map(|(i, s)| Packet::request(i as u8, s.query()))
        .collect();
    r.send(queries);
    r.run_watching(1500, PITCH);
    r
}

impl Rig {
    fn send(&mut self, packets: Vec<Packet>) {
        for p in packets {
            self.model.note_sent(self.now, &p);
            self.unit.feed(&p.to_bytes(), self.now);
            self.sent.push(p);
        }
    }

    /// `ms` of the loop, with the unit's own pitch trim position every 10 ms.
    fn run_watching(&mut self, ms: u64, motor: Motor) -> Vec<u8> {
        assert_eq!(motor, PITCH);
        let mut seen = Vec::new();
        for _ in 0..ms / 10 {
            self.now += Duration::from_millis(10);
            self.unit.tick(self.now);
            let out = self.unit.take_output();
            let mut frames = Vec::new();
            self.rx.push(&out, |e| {
                if let Event::Frame(f) = e {
                    frames.push(Packet::parse(&f).unwrap());
                }
            });
            for p in frames {
                self.model.apply_packet(self.now, &p);
            }
            let p = self.ctl.tick(&self.model, self.now);
            self.send(p);
            seen.push(self.pitch_pos());
        }
        seen
    }

    fn pitch_pos(&self) -> u8 {
        self.unit.snapshot(self.now).pitch_trim_position
    }

    /// A key on the device list with the pitch trim's row selected.
    fn key(&mut self, c: char, kind: KeyEventKind, setup: bool) -> Handled {
        let ctx = KeyContext {
            selected: Some(Selected {
                id: PITCH.device_id(),
                kind: CircuitKind::Trim(TrimKind::Pitch),
                state: CircuitState::Off,
            }),
            overlay_open: false,
            past_endpoints: setup,
        };
        let key = KeyEvent::new_with_kind(KeyCode::Char(c), KeyModifiers::NONE, kind);
        let out = self.ctl.handle_key(key, &ctx, &self.model, self.now);
        self.send(out.packets.clone());
        out
    }

    /// `ticks` of 10 ms of a network run of the pitch trim nose up through `drive`:
    /// PTRIMREQ +50000 (toward 30) from 0x42, repeated at 4 Hz; the trim's positions
    /// meanwhile.
    fn network_run_up(&mut self, drive: &mut MotorDrive, ticks: u32) -> Vec<u8> {
        let mut seen = Vec::new();
        for i in 0..ticks {
            if i % 25 == 0 {
                let renewal = Some(Duration::from_millis(600));
                drive.request(PITCH, 50_000, 0x42, renewal, self.now);
            }
            let p = drive.tick(&mut self.ctl, &mut self.model, self.now);
            self.send(p);
            seen.extend(self.run_watching(10, PITCH));
        }
        seen
    }

    /// Fails unless one line of the event log holds every one of `words`.
    fn assert_said(&self, words: &[&str]) {
        let events = &self.model.events;
        assert!(
            events
                .iter()
                .any(|e| words.iter().all(|w| e.text.contains(w))),
            "no event with {words:?}: {events:#?}"
        );
    }

    fn trim_moves_since(&self, from: usize) -> Vec<bool> {
        self.sent[from..]
            .iter()
            .filter_map(|p| match p.message {
                Message::TrimMove(t) => Some(t.on),
                _ => None,
            })
            .collect()
    }
}

/// The XFSp gateway's drive, sharing the page's record: a network run nose-up is
/// stopped within a few counts as moving against its command (the words in the
/// event log), and the page's keys then refuse it; the network is refused what the
/// keys saw.
#[test]
fn the_gateway_stops_a_network_run_and_shares_what_it_saw() {
    let mut r = rig(128);
    let mut drive = MotorDrive::default();
    let seen = r.network_run_up(&mut drive, 200);
    let hi = *seen.iter().max().unwrap();
    assert!((131..=134).contains(&hi), "went down to {hi}");
    assert!(drive.running(&r.ctl).is_none());
    r.assert_said(&["it moved down when asked up: its leads or its sensor"]);
    let out = r.key('u', KeyEventKind::Press, false);
    assert!(out.packets.is_empty());
    assert!(out.notice.unwrap().contains("press u again"));

    // The other way round: the keys saw the flaps' record... here the pitch trim's,
    // so a fresh drive sharing it refuses a request for it, nothing sent.
    let mut other = MotorDrive::default();
    other.request(PITCH, -50_000, 0x43, None, r.now);
    let p = other.tick(&mut r.ctl, &mut r.model, r.now);
    assert!(p.is_empty(), "{p:?}");
    r.assert_said(&["0x0043", "not run on a network request"]);
}

/// The XFSp gateway's drive, the same reversed trim parked at 220: a network run
/// nose-up starts as probes and never takes it past 220 beyond the one count of
/// noise; stopped as moving against its command, said in the event log.
#[test]
fn the_gateway_probes_a_network_run_near_the_endpoint_behind_it() {
    let mut r = rig(220);
    let mut drive = MotorDrive::default();
    let from = r.sent.len();
    let mut seen = vec![r.pitch_pos()];
    seen.extend(r.network_run_up(&mut drive, 150));
    let most = *seen.iter().max().unwrap();
    assert!(most <= 221, "past 220 to {most}: {seen:?}");
    assert!(drive.running(&r.ctl).is_none());
    r.assert_said(&["pitch trim near its down endpoint: trying a short run first"]);
    r.assert_said(&["it moved down when asked up: its leads or its sensor"]);
    let moves = r.trim_moves_since(from);
    assert!(moves[0] && !moves.last().unwrap(), "{moves:?}");
    assert_eq!(r.ctl.against().seen(PITCH), Some(Direction::Up));
}

/// The check finds the reversed pitch trim, parked at its down
/// endpoint 220, by probing (its first run, up, goes down past nothing: the probe
/// shows its way). That finding is recorded as for any run: afterwards the first
/// press of `u` at the keys is refused with nothing on the wire, and so are the
/// remote's lease and a network request, each in the words of where it was asked.
#[test]
fn a_reversal_the_check_finds_by_probing_is_refused_to_keys_remote_and_network() {
    let mut r = rig(220);
    let opts = Options {
        skip: vec![Step::Switches, Step::Circuits, Step::Loads],
        ..Options::default()
    };
    let mut view = CheckView::default();
    let mut flow = CheckFlow::new(opts, &mut view, &r.model, r.now);
    let out = flow.command(Command::Enter, &mut view, &r.model, &mut r.ctl, r.now);
    r.send(out.packets);
    let mut seen = vec![r.pitch_pos()];
    let mut progress = Vec::new();
    for _ in 0..2000 {
        if view.step == Step::Done {
            break;
        }
        seen.extend(r.run_watching(10, PITCH));
        let out = flow.tick(&mut view, &r.model, &mut r.ctl, r.now);
        progress.extend(out.progress);
        r.send(out.packets);
    }
    assert_eq!(view.step, Step::Done, "{progress:?}");
    let pitch = view.motors.iter().find(|m| m.motor == PITCH).unwrap();
    assert_eq!(
        pitch.outcome,
        Found::Found(MotorFinding::Reversed),
        "{progress:?}"
    );
    let most = *seen.iter().max().unwrap();
    assert!(most <= 221, "past 220 to {most}: {progress:?}");
    assert_eq!(r.ctl.against().seen(PITCH), Some(Direction::Up));
    r.run_watching(4000, PITCH);

    // The keys: refused both ways, nothing sent, in the keys' words. `u` is known
    // now to run it down, and it is at its down endpoint: refused by that endpoint
    // before a confirmation is offered; `d` can be confirmed.
    let from = r.sent.len();
    for (key, words) in [
        ('u', "is at its down endpoint"),
        ('d', "let go, then press d again"),
    ] {
        let out = r.key(key, KeyEventKind::Press, false);
        assert!(out.packets.is_empty(), "{out:?}");
        let notice = out.notice.unwrap();
        assert!(notice.contains(words), "{notice}");
        r.key(key, KeyEventKind::Release, false);
        r.run_watching(3200, PITCH);
    }

    // The remote: refused both ways, with the reason as a type, and no key named to
    // the phone.
    let (p, got) = r.ctl.lease(&r.model, PITCH, Direction::Up, r.now);
    r.send(p);
    let why = got.unwrap_err();
    assert!(
        matches!(
            why.reason,
            Refused::AtEndpoint {
                toward: Direction::Down,
                ..
            }
        ),
        "{why:?}"
    );
    let (p, got) = r.ctl.lease(&r.model, PITCH, Direction::Down, r.now);
    r.send(p);
    let why = got.unwrap_err();
    assert_eq!(why.reason, Refused::Against(Direction::Up));
    assert!(why.words.contains("not run from the phone"), "{why}");
    assert!(!why.words.contains("press"), "{why}");

    // The network: a request refused, said in the event log.
    let mut drive = MotorDrive::default();
    drive.request(PITCH, 50_000, 0x44, None, r.now);
    let p = drive.tick(&mut r.ctl, &mut r.model, r.now);
    r.send(p);
    assert_eq!(drive.counts().refused, 1);
    assert!(drive.running(&r.ctl).is_none());
    r.run_watching(500, PITCH);
    assert!(r.trim_moves_since(from).is_empty(), "a refused run moved");
    r.assert_said(&["0x0044", "is at its down endpoint"]);
}

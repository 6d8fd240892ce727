//! End to end: a motor that moves against its command, run from the
//! device list's keys, is stopped within a few counts with the words, refused until
//! the person confirms, and never taken past its endpoint. The real page (`App`) on
//! the slave of a real pseudo-terminal opened by `vpx-efis sim --pty --scenario …`
//! running as its own process: `install` (the pitch trim's leads swapped) and
//! `reversed-flaps` (the flap motor's). What the page sent is read back from its own
//! traffic log; positions from the FLAP_TRIM_STATUS it heard.
// Needs a pseudo-terminal, which only Unix has.
#![cfg(unix)]

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use vpx_efis::app::{App, AppOptions};
use vpx_efis::check::Options;
use vpx_efis::check::state::{MotorFinding, Outcome, Step};
use vpx_efis::link;
use vpx_efis::model::{Motor, Source, TrimKind};
use vpx_efis::protocol::device::{FLAPS, TRIM_P};
use vpx_efis::protocol::message::Message;
use vpx_efis::protocol::{Crossing as Dir, Packet};
use vpx_efis::traffic::What;
use vpx_efis::ui::state::ReleaseMode;

mod common;
use common::process::{Kill, sim_pty};

/// One rig at a time: two pages and two sims at the real line rate on a loaded
/// machine can starve a status broadcast into COMMUNICATION LOST.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

struct Rig {
    app: App,
    _sim: Kill,
    _turn: std::sync::MutexGuard<'static, ()>,
}

impl Rig {
    /// The page, reporting key releases (as a kitty-protocol terminal does), against
    /// `vpx-efis sim --pty --scenario <scenario>`, its device list up.
    fn new(scenario: &str) -> Rig {
        let turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
        let (sim, path) = sim_pty(scenario);
        let app = App::new(
            Source::Serial { path: path.clone() },
            link::serial_connector(PathBuf::from(&path), 57_600),
            AppOptions {
                release_mode: ReleaseMode::KeyRelease,
                ..AppOptions::default()
            },
        );
        let mut r = Rig {
            app,
            _sim: sim,
            _turn: turn,
        };
        r.until("the device list and motor positions", 20_000, |app| {
            let m = app.model();
            let now = Instant::now();
            m.live_devices(now).is_some()
                && m.live_flap_trim(now).is_some()
                && m.names.iter().all(Option::is_some)
        });
        r
    }

    fn until(&mut self, what: &str, limit_ms: u64, f: impl Fn(&App) -> bool) {
        let limit = Duration::from_millis(limit_ms);
        common::app::until(&mut self.app, what, limit, |app, _| f(app));
    }

    fn wait(&mut self, ms: u64) {
        self.app
            .pump_until(Instant::now() + Duration::from_millis(ms));
    }

    fn key(&mut self, c: char, kind: KeyEventKind) {
        let k = KeyEvent::new_with_kind(KeyCode::Char(c), KeyModifiers::NONE, kind);
        self.app.handle_term_event(Event::Key(k), Instant::now());
    }

    fn select(&mut self, id: u8) {
        for _ in 0..40 {
            if self.app.view().selected == Some(id) {
                return;
            }
            let k = KeyEvent::new_with_kind(KeyCode::Down, KeyModifiers::NONE, KeyEventKind::Press);
            self.app.handle_term_event(Event::Key(k), Instant::now());
            self.wait(20);
        }
        panic!("could not select device {id}");
    }

    fn pos(&self, motor: Motor) -> u8 {
        let m = self.app.model();
        let ft = m.live_flap_trim(Instant::now()).expect("live positions");
        match motor {
            Motor::Flaps => ft.flap_position,
            Motor::Trim(TrimKind::Pitch) => ft.pitch_trim_position,
            Motor::Trim(TrimKind::Roll) => ft.roll_trim_position,
        }
    }

    /// Holds `c` for `ms` (a repeat every 40 ms, then the release), and 600 ms more:
    /// every position heard meanwhile.
    fn hold(&mut self, c: char, ms: u64, motor: Motor) -> Vec<u8> {
        let mut seen = vec![self.pos(motor)];
        self.key(c, KeyEventKind::Press);
        let end = Instant::now() + Duration::from_millis(ms);
        while Instant::now() < end {
            self.wait(40);
            seen.push(self.pos(motor));
            self.key(c, KeyEventKind::Repeat);
        }
        self.key(c, KeyEventKind::Release);
        for _ in 0..15 {
            self.wait(40);
            seen.push(self.pos(motor));
        }
        seen
    }

    /// A press and release of `c`: for a refusal, or the first of a confirmation.
    fn tap(&mut self, c: char) {
        self.key(c, KeyEventKind::Press);
        self.key(c, KeyEventKind::Release);
        self.wait(100);
    }

    /// The traffic log's length: a mark for [`Rig::moves_since`].
    fn mark(&self) -> u64 {
        self.app.model().traffic.total()
    }

    /// The move messages the page sent since `mark`, as on/off.
    fn moves_since(&self, mark: u64) -> Vec<bool> {
        let m = self.app.model();
        m.traffic
            .entries()
            .filter(|e| e.seq >= mark && e.dir == Dir::Tx)
            .filter_map(|e| match &e.what {
                What::Packet(Packet {
                    message: Message::TrimMove(t),
                    ..
                }) => Some(t.on),
                What::Packet(Packet {
                    message: Message::FlapMove(f),
                    ..
                }) => Some(f.on),
                _ => None,
            })
            .collect()
    }

    /// The runs since `mark` started and ended with a stop on the wire, and the page
    /// says the pitch trim was stopped moving against its command.
    fn stopped_moving_down_when_asked_up(&mut self, mark: u64) {
        let moves = self.moves_since(mark);
        assert!(
            moves.first() == Some(&true) && moves.last() == Some(&false),
            "{moves:?}"
        );
        let screen = self.screen();
        assert!(
            screen.contains(
                "pitch trim moved down when asked up: its leads or its sensor may be swapped; \
                 stopped"
            ),
            "{screen}"
        );
    }

    /// The page as drawn at 120×40, its rows trimmed and joined by spaces (a long
    /// notice wraps over rows).
    fn screen(&mut self) -> String {
        let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
        self.app.draw(&mut term, Instant::now()).unwrap();
        let drawn = common::screen::text(term.backend().buffer());
        drawn.lines().map(str::trim).collect::<Vec<_>>().join(" ")
    }
}

const PITCH: Motor = Motor::Trim(TrimKind::Pitch);

/// `install`: select Trim_P, hold `u` from neutral. The trim goes down, and is
/// stopped within a few counts with the words and its stop on the wire, not run on
/// to the down endpoint 220. `u` and `d` are then refused, nothing sent; `u` twice
/// runs it anyway, to 220 and never past, however often it is held there.
#[test]
fn install_a_reversed_pitch_trim_held_up_is_stopped_refused_and_kept_off_its_endpoint() {
    let mut r = Rig::new("install");
    r.select(TRIM_P);
    let p0 = r.pos(PITCH);
    let mark = r.mark();
    let seen = r.hold('u', 2000, PITCH);
    let most = *seen.iter().max().unwrap();
    eprintln!("install: u from {p0}: down to {most}");
    assert!(
        most > p0 && most <= p0 + 6,
        "from {p0} down to {most}: {seen:?}"
    );
    assert!(
        *seen.last().unwrap() == most || *seen.last().unwrap() + 1 >= most,
        "{seen:?}"
    );
    r.stopped_moving_down_when_asked_up(mark);

    // Refused both ways until confirmed: nothing on the wire.
    r.wait(3200);
    let mark = r.mark();
    let at = r.pos(PITCH);
    r.tap('d');
    let screen = r.screen();
    assert!(
        screen.contains("press d again within 3 s to run it down anyway, watching the motor"),
        "{screen}"
    );
    r.wait(3200);
    r.tap('u');
    assert!(r.screen().contains("press u again within 3 s"));
    r.wait(3200);
    assert!(r.moves_since(mark).is_empty(), "a refused key sent a move");
    assert!(r.pos(PITCH).abs_diff(at) <= 1);

    // Confirmed (u, then u held within 3 s): down to the endpoint, never past it, and
    // so for every further confirmed hold there.
    let mut most = 0;
    for _ in 0..4 {
        r.tap('u');
        let seen = r.hold('u', 6000, PITCH);
        most = most.max(*seen.iter().max().unwrap());
        assert!(
            most <= 220,
            "past the down endpoint 220 to {most}: {seen:?}"
        );
        r.wait(300);
    }
    eprintln!("install: confirmed holds of u: down to {most}");
    assert!(most >= 214, "the confirmed runs went down: {most}");
    r.tap('u');
    r.tap('u');
    let screen = r.screen();
    assert!(
        screen.contains("at its down endpoint"),
        "at 220 u is refused by the endpoint: {screen}"
    );
}

/// `reversed-flaps`: hold `d` on the Flaps row from 120; they go up, and are stopped
/// within a few counts with the words, the stop on the wire; then refused.
#[test]
fn reversed_flaps_held_down_are_stopped_and_refused() {
    let mut r = Rig::new("reversed-flaps");
    r.select(FLAPS);
    let p0 = r.pos(Motor::Flaps);
    let mark = r.mark();
    let seen = r.hold('d', 2000, Motor::Flaps);
    let least = *seen.iter().min().unwrap();
    eprintln!("reversed-flaps: d from {p0}: up to {least}");
    assert!(
        least < p0 && least + 6 >= p0,
        "from {p0} up to {least}: {seen:?}"
    );
    let moves = r.moves_since(mark);
    assert!(
        moves.first() == Some(&true) && moves.last() == Some(&false),
        "{moves:?}"
    );
    assert!(
        r.screen().contains(
            "flaps moved up when asked down: its leads or its sensor may be swapped; stopped"
        ),
        "{}",
        r.screen()
    );
    r.wait(3200);
    let mark = r.mark();
    r.tap('d');
    r.wait(500);
    assert!(r.moves_since(mark).is_empty());
    assert!(r.screen().contains("press d again within 3 s"));
}

/// `install`, its pitch trim parked at `at`, wired as given, in a scenario file the
/// sim reads, and the page's rig on it.
fn parked(at: u8, reversed: bool) -> (tempfile::TempDir, Rig) {
    let dir = tempfile::tempdir().unwrap();
    let toml = include_str!("../assets/scenarios/install.toml").replace(
        "position = 125\nreversed = true",
        &format!("position = {at}\nreversed = {reversed}"),
    );
    assert!(toml.contains(&format!("position = {at}\nreversed")));
    let path = dir.path().join("parked.toml");
    std::fs::write(&path, toml).unwrap();
    let r = Rig::new(path.to_str().unwrap());
    (dir, r)
}

/// The reversed pitch trim parked at its down endpoint
/// 220 with nothing known of its way. `u` (away from 220, as the page believes)
/// starts as short probes, and the trim never goes past 220 beyond the one count of
/// noise (before the probes: 223–224), stopped with the words and its stop on the
/// wire.
#[test]
fn install_a_reversed_pitch_trim_parked_at_its_endpoint_is_probed_not_driven_past_it() {
    let (_dir, mut r) = parked(220, true);
    r.select(TRIM_P);
    let p0 = r.pos(PITCH);
    assert_eq!(p0, 220);
    let mark = r.mark();
    let seen = r.hold('u', 1500, PITCH);
    let most = *seen.iter().max().unwrap();
    eprintln!("install parked at 220: u: down to {most}");
    assert!(most <= 221, "past 220 to {most}: {seen:?}");
    r.stopped_moving_down_when_asked_up(mark);
}

/// The same trim wired right, parked at 220: `u` probes, sees it go up, and runs on
/// smoothly while held (about 25 counts a second).
#[test]
fn install_a_pitch_trim_wired_right_parked_at_its_endpoint_runs_after_its_probe() {
    let (_dir, mut r) = parked(220, false);
    r.select(TRIM_P);
    let seen = r.hold('u', 3000, PITCH);
    let least = *seen.iter().min().unwrap();
    eprintln!("wired right, parked at 220: u for 3 s: up to {least}");
    assert!(seen.iter().all(|&p| p <= 220), "{seen:?}");
    assert!(least <= 170, "only to {least}: {seen:?}");
}

/// `scenario` (a file name or a built-in's) with `[section]`'s `position = from` made
/// `position = to`, in a scenario file the sim reads.
fn moved(scenario: &str, section: &str, from: u8, to: u8) -> (tempfile::TempDir, Rig) {
    let dir = tempfile::tempdir().unwrap();
    let text = match scenario {
        "install" => include_str!("../assets/scenarios/install.toml"),
        _ => include_str!("../assets/scenarios/reversed-flaps.toml"),
    };
    let head = format!("[{section}]");
    let at = text.find(&head).unwrap();
    let (before, after) = text.split_at(at);
    let old = format!("position = {from}\n");
    assert!(after.contains(&old), "{section}: {old}");
    let toml = format!(
        "{before}{}",
        after.replacen(&old, &format!("position = {to}\n"), 1)
    );
    let path = dir.path().join(format!("{scenario}-{to}.toml"));
    std::fs::write(&path, toml).unwrap();
    let r = Rig::new(path.to_str().unwrap());
    (dir, r)
}

impl Rig {
    /// The installation check, from the page, with only its motors step, to its end;
    /// then back on the device list.
    fn check_motors(&mut self, reports: &std::path::Path) {
        self.app.set_check_report_dir(Some(reports.to_path_buf()));
        self.until("the unit's settings", 20_000, |app| {
            vpx_efis::check::plan::ready(&app.model(), Instant::now()).is_ok()
        });
        let options = Options {
            skip: vec![Step::Switches, Step::Circuits, Step::Loads],
            ..Options::default()
        };
        self.app.open_check(options, Instant::now());
        let enter =
            KeyEvent::new_with_kind(KeyCode::Enter, KeyModifiers::NONE, KeyEventKind::Press);
        self.app
            .handle_term_event(Event::Key(enter), Instant::now());
        let end = Instant::now() + Duration::from_secs(60);
        while !self.app.check_finished() {
            assert!(
                Instant::now() < end,
                "the check did not end: {:?}, {:?}",
                self.app.check_view().prompt.clone(),
                self.app.take_check_progress()
            );
            self.wait(20);
        }
        let esc = KeyEvent::new_with_kind(KeyCode::Esc, KeyModifiers::NONE, KeyEventKind::Press);
        self.app.handle_term_event(Event::Key(esc), Instant::now());
        self.wait(100);
    }

    fn finding(&self, motor: Motor) -> Outcome<MotorFinding> {
        let v = self.app.check_view();
        v.motors
            .iter()
            .find(|m| m.motor == motor)
            .unwrap()
            .outcome
            .clone()
    }
}

/// The check, run from the page against `sim --pty` as its own
/// process, finds a reversed motor parked at the endpoint its first run backs away
/// from, by probing: the pitch trim of `install` at its down endpoint 220 (run up
/// first), and the flaps of `reversed-flaps` at their up endpoint 20 (run down
/// first). Afterwards the first press of that key on the device list is refused
/// with no move on the wire (it is now known to run the motor into the endpoint it
/// is at), and so is the other key, which says how to confirm. The other motor,
/// wired right (`install`'s flaps at their up endpoint 20, `reversed-flaps`' pitch
/// trim at 125), moves the commanded way: near an endpoint it shows its way in
/// probes, and the pauses between them do not eat its test run.
#[test]
fn a_reversal_the_check_finds_by_probing_is_refused_to_the_keys() {
    for (scenario, section, from, to, motor, id, keys, right) in [
        (
            "install",
            "pitch_trim",
            125,
            220,
            PITCH,
            TRIM_P,
            [
                ('u', "at its down endpoint"),
                ('d', "press d again within 3 s"),
            ],
            Motor::Flaps,
        ),
        (
            "reversed-flaps",
            "flap",
            120,
            20,
            Motor::Flaps,
            FLAPS,
            [
                ('d', "at its up endpoint"),
                ('u', "press u again within 3 s"),
            ],
            PITCH,
        ),
    ] {
        let (dir, mut r) = moved(scenario, section, from, to);
        assert_eq!(r.pos(motor), to, "{scenario}");
        r.check_motors(dir.path());
        assert_eq!(
            r.finding(motor),
            Outcome::Found(MotorFinding::Reversed),
            "{scenario}: {:?}",
            r.app.take_check_progress()
        );
        assert_eq!(
            r.finding(right),
            Outcome::Found(MotorFinding::Moves),
            "{scenario}: {:?}",
            r.app.take_check_progress()
        );
        r.select(id);
        for (key, words) in keys {
            r.wait(3200);
            let at = r.pos(motor);
            let mark = r.mark();
            r.key(key, KeyEventKind::Press);
            r.wait(500);
            let screen = r.screen();
            r.key(key, KeyEventKind::Release);
            r.wait(300);
            let moves = r.moves_since(mark);
            eprintln!("{scenario}: after the check, {key} at {at}: moves {moves:?}");
            assert!(
                moves.is_empty(),
                "{scenario}: {key} sent a move after the check found it reversed"
            );
            assert!(r.pos(motor).abs_diff(at) <= 1, "{scenario}");
            assert!(screen.contains(words), "{scenario}, {key}: {screen}");
        }
    }
}

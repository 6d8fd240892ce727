//! Snapshots of every step's screen of the installation check, drawn from hand-built
//! `CheckView`s and models into a `TestBackend`: the text at 80×24 and at 160×50, the
//! colours in every palette (dark, light, no colour), the WCAG contrast of every cell
//! in both colour palettes, and cell by cell the colours whose meaning matters
//! (pass green, fail red, warning amber, always beside their word).

use std::path::PathBuf;
use std::time::{Duration, Instant};

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier};

use vpx_efis::check::state::{
    CheckView, CircuitFinding, CircuitResult, Excluded, Input, Interruption, LeftBehind, LoadsView,
    MotorFinding, MotorResult, NotFollowed, Outcome, Planned, Prompt, Step, SwitchFinding,
    SwitchResult, Unasked,
};
use vpx_efis::loads;
use vpx_efis::model::{Model, Motor, Source, TrimKind};
use vpx_efis::protocol::FaultCode;
use vpx_efis::protocol::message::SwitchId;
use vpx_efis::ui::check;
use vpx_efis::ui::palette::{Palette, ThemeChoice, Why};
use vpx_efis::ui::state::{MotorRun, ViewState};

mod themes;

mod common;
use common::check_view::{motor_result, never_touched, suggested, the_starter};
use common::screen::{find, plain_text};

mod aircraft {
    use super::*;

    use vpx_efis::protocol::device::{EFIS, FIELD_PRI, STARTER};
    use vpx_efis::protocol::message::{
        DeviceStatus, SignedTenths, SwitchInputs, SystemStatus, Tenths,
    };

    /// A freshly wired aircraft: id, name, breaker, switch.
    pub const WIRED: &[(u8, &str, u8, SwitchId)] = &[
        (STARTER, "", 5, SwitchId::AlwaysOn),
        (EFIS, "EFIS", 5, SwitchId::AlwaysOn),
        (FIELD_PRI, "Alternator", 5, SwitchId::Input(1)),
        (4, "Nav Lt", 3, SwitchId::Input(2)),
        (5, "Strobe Lt", 3, SwitchId::Input(3)),
        (6, "Beacon", 2, SwitchId::Input(3)),
        (7, "Pitot Heat", 5, SwitchId::Input(5)),
        (0x11, "Landing Lt", 8, SwitchId::Input(6)),
        (0x12, "Taxi Lt", 6, SwitchId::Input(6)),
        (0x17, "Fuel Pump", 10, SwitchId::Input(7)),
    ];

    pub use crate::common::configured::Unit as Aircraft;

    impl Aircraft {
        /// One second of broadcasts at `ms`: switch inputs `word`, circuits `on`
        /// (id, tenths of an amp), the flaps and trims where `positions` puts them.
        pub fn broadcast(&mut self, ms: u64, word: u16, on: &[(u8, u16)], positions: (u8, u8, u8)) {
            let mut d = DeviceStatus::default();
            for &(id, a) in on {
                d.on[id as usize] = true;
                d.current[id as usize] = Tenths(a);
            }
            self.apply(
                ms,
                SystemStatus {
                    system_current: Tenths(152),
                    main_bus_volts: SignedTenths(138),
                    internal_temp: 24,
                    switches: SwitchInputs::from_word(word),
                    ..Default::default()
                },
            );
            self.apply(ms, d);
            let mut ft = crate::common::configured::flap_trim(positions);
            ft.roll_trim.motor_running = true;
            self.apply(ms + 20, ft);
        }
    }

    /// The unit configured at `t0`, on a real serial port.
    pub fn configured() -> Aircraft {
        let port = Source::Serial {
            path: "/dev/ttyUSB0".into(),
        };
        Aircraft::answered(port, WIRED)
    }

    /// Ten seconds of a live unit with `word` on the inputs and `on` powered; `now` is
    /// 300 ms after the last broadcast.
    pub fn live(word: u16, on: &[(u8, u16)], positions: (u8, u8, u8)) -> (Model, Instant) {
        let mut a = configured();
        for s in 1..=10 {
            a.broadcast(s * 1000, word, on, positions);
        }
        (a.model, a.t0 + Duration::from_millis(10_300))
    }

    /// Ten seconds of the unit with nothing on but the EFIS, flaps up, trims near
    /// neutral.
    pub fn idle() -> (Model, Instant) {
        live(0, &[EFIS_ON], (20, 128, 120))
    }

    /// The same unit, silent for the last 5.3 s: every live value stale.
    pub fn stale(word: u16, on: &[(u8, u16)]) -> (Model, Instant) {
        let (m, now) = live(word, on, (20, 128, 120));
        (m, now + Duration::from_secs(5))
    }
}

const EFIS_ON: (u8, u16) = (1, 24);

fn planned(id: u8, name: &str, pin: &'static str, breaker: u8, sw: u8) -> Planned {
    Planned {
        id,
        name: name.into(),
        pin,
        breaker: Some(breaker),
        switch: Some(SwitchId::Input(sw)),
        on_for: Duration::from_secs(3),
    }
}

fn plan() -> Vec<Planned> {
    vec![
        planned(4, "Nav Lt", "5A-1", 3, 2),
        planned(5, "Strobe Lt", "5A-2", 3, 3),
        planned(6, "Beacon", "5A-3", 2, 3),
        planned(0x11, "Landing Lt", "10A-1", 8, 6),
        planned(0x12, "Taxi Lt", "10A-2", 6, 6),
        planned(0x17, "Fuel Pump", "15A-1", 10, 7),
    ]
}

const MOTORS: [Motor; 3] = [
    Motor::Flaps,
    Motor::Trim(TrimKind::Pitch),
    Motor::Trim(TrimKind::Roll),
];

/// The ids are the ICD's (Table 40): the starter 0x01, the primary alternator field 0x03.
fn excluded() -> Vec<Excluded> {
    use vpx_efis::protocol::device::{FIELD_PRI, STARTER};
    vec![
        the_starter(STARTER),
        never_touched(
            (FIELD_PRI, "Alternator", "Field_Pri", 5, SwitchId::Input(1)),
            "an alternator field",
        ),
        suggested(
            (7, "Pitot Heat", "5A-4", 5, SwitchId::Input(7)),
            "the name has \"pitot\"",
        ),
    ]
}

fn base() -> CheckView {
    CheckView {
        plan: plan(),
        planned_motors: MOTORS
            .into_iter()
            .map(|m| (m, Duration::from_millis(1500)))
            .collect(),
        excluded: excluded(),
        unasked: vec![Unasked {
            input: Input::Switch(5),
            circuits: vec![7],
            why: "switch 5 powers only Pitot Heat (excluded): not asked".into(),
        }],
        ..Default::default()
    }
}

fn confirm() -> CheckView {
    CheckView {
        prompt: Some(Prompt {
            todo: "Make sure the aircraft is safe to power the circuits listed, then press Enter."
                .into(),
            watching: "nothing yet: nothing is switched on until you confirm.".into(),
            time_left: None,
            keys: vec![
                ("Enter", "safe: start"),
                ("↑↓", "select"),
                ("Space", "take back"),
                ("q", "quit"),
            ],
        }),
        // Pitot Heat: the selection runs down the plan, then the exclusions.
        current: Some(plan().len() + 2),
        ..base()
    }
}

fn sw(input: Input, circuits: &[u8], outcome: Outcome<SwitchFinding>) -> SwitchResult {
    SwitchResult {
        input,
        circuits: circuits.to_vec(),
        outcome,
    }
}

fn switch_results() -> Vec<SwitchResult> {
    vec![
        sw(
            Input::Switch(2),
            &[4],
            Outcome::Found(SwitchFinding::Passed),
        ),
        sw(
            Input::Switch(3),
            &[5, 6],
            Outcome::Found(SwitchFinding::OtherChanged(vec![Input::Switch(4)])),
        ),
        sw(
            Input::Switch(5),
            &[7],
            Outcome::Skipped("switch 5 powers only Pitot Heat (excluded): not asked".into()),
        ),
        sw(Input::Switch(6), &[0x11, 0x12], Outcome::NotRun),
        sw(Input::Switch(7), &[0x17], Outcome::NotRun),
        sw(Input::FlapUp, &[], Outcome::NotRun),
        sw(Input::FlapDown, &[], Outcome::NotRun),
    ]
}

fn switches() -> CheckView {
    CheckView {
        step: Step::Switches,
        switches: switch_results(),
        current: Some(3),
        prompt: Some(Prompt {
            todo: "Flip switch 6 on, then off.".into(),
            watching: "switch 6 and Landing Lt, Taxi Lt.".into(),
            time_left: Some(Duration::from_millis(13_200)),
            keys: vec![
                ("r", "retry"),
                ("s", "skip it"),
                ("S", "skip step"),
                ("q", "stop the check"),
            ],
        }),
        ..base()
    }
}

fn circ(
    id: u8,
    name: &str,
    pin: &'static str,
    cb: u8,
    o: Outcome<CircuitFinding>,
) -> CircuitResult {
    CircuitResult {
        id,
        name: name.into(),
        pin,
        breaker: Some(cb),
        switch: None,
        outcome: o,
    }
}

fn circuit_results() -> Vec<CircuitResult> {
    vec![
        circ(
            4,
            "Nav Lt",
            "5A-1",
            3,
            Outcome::Found(CircuitFinding::Within {
                amps: 1.2,
                breaker: 3,
            }),
        ),
        circ(
            5,
            "Strobe Lt",
            "5A-2",
            3,
            Outcome::Found(CircuitFinding::NoCurrent),
        ),
        circ(
            6,
            "Beacon",
            "5A-3",
            2,
            Outcome::Found(CircuitFinding::NearBreaker {
                amps: 1.8,
                breaker: 2,
            }),
        ),
        circ(0x11, "Landing Lt", "10A-1", 8, Outcome::NotRun),
        circ(0x12, "Taxi Lt", "10A-2", 6, Outcome::NotRun),
        circ(0x17, "Fuel Pump", "15A-1", 10, Outcome::NotRun),
    ]
}

fn circuits() -> CheckView {
    CheckView {
        step: Step::Circuits,
        switches: finished_switches(),
        circuits: circuit_results(),
        current: Some(3),
        prompt: Some(Prompt {
            todo: "Nothing: Landing Lt is on, the page reads its current.".into(),
            watching: "Landing Lt's current in two fresh DEVICE_STATUS.".into(),
            time_left: Some(Duration::from_secs(4)),
            keys: vec![
                ("s", "skip it"),
                ("S", "skip step"),
                ("q", "stop the check"),
            ],
        }),
        message: Some("Beacon: 1.8 A".into()),
        to_cycle: vec![(4, "Nav Lt".into(), SwitchId::Input(2))],
        ..base()
    }
}

fn finished_switches() -> Vec<SwitchResult> {
    let mut s = switch_results();
    s[3].outcome = Outcome::Found(SwitchFinding::CircuitsDidNotFollow(vec![(
        0x12,
        // Sent from the page's soft keys at 16:41:00 UTC, five minutes before.
        NotFollowed::HeldByPage {
            on: false,
            sent_at: Some(std::time::UNIX_EPOCH + Duration::from_secs(1_764_002_460)),
            ago: Duration::from_secs(300),
        },
    )]));
    s[4].outcome = Outcome::Found(SwitchFinding::NeverChanged);
    // The flap switch inputs have no circuit: all the check sees is the input.
    s[5].outcome = Outcome::Found(SwitchFinding::Changed);
    s[6].outcome = Outcome::Found(SwitchFinding::Changed);
    s
}

fn finished_circuits() -> Vec<CircuitResult> {
    let mut c = circuit_results();
    c[3].outcome = Outcome::Found(CircuitFinding::Within {
        amps: 6.9,
        breaker: 8,
    });
    c[4].outcome = Outcome::Found(CircuitFinding::Faulted(FaultCode::ShortCircuit));
    c[5].outcome = Outcome::Found(CircuitFinding::Within {
        amps: 4.5,
        breaker: 10,
    });
    c
}

fn motors() -> CheckView {
    let mut motors = finished_motors();
    // The roll trim under test, half way through its runs.
    motors[2].positions = vec![120, 131];
    motors[2].outcome = Outcome::NotRun;
    CheckView {
        step: Step::Motors,
        switches: finished_switches(),
        circuits: finished_circuits(),
        motors,
        current: Some(2),
        prompt: Some(Prompt {
            todo: "Keep clear of the ailerons: roll trim runs left, then right.".into(),
            watching: "roll trim's position in FLAP_TRIM_STATUS.".into(),
            time_left: None,
            keys: vec![("s", "skip it"), ("q", "stop the check")],
        }),
        ..base()
    }
}

fn finished_motors() -> Vec<MotorResult> {
    let found = |f| Outcome::Found(f);
    vec![
        motor_result(Motor::Flaps, &[20, 56, 20, 20], found(MotorFinding::Moves)),
        motor_result(
            Motor::Trim(TrimKind::Pitch),
            &[128, 118, 140, 128],
            found(MotorFinding::Reversed),
        ),
        motor_result(
            Motor::Trim(TrimKind::Roll),
            &[120, 120, 120, 120],
            found(MotorFinding::NoMovement),
        ),
    ]
}

fn to_cycle() -> Vec<(u8, String, SwitchId)> {
    vec![
        (4, "Nav Lt".into(), SwitchId::Input(2)),
        (0x11, "Landing Lt".into(), SwitchId::Input(6)),
        (0x12, "Taxi Lt".into(), SwitchId::Input(6)),
        // Switch 7 the check found dead (`finished_switches`): flipping it is no
        // release, and the words say so.
        (0x17, "Boost Pump".into(), SwitchId::Input(7)),
    ]
}

/// The builder's load file for the aircraft: a small alternator, so take-off and
/// landing are tight.
const LOAD_FILE: &str = include_str!("data/loads-18a-alternator.toml");

fn analysed() -> LoadsView {
    let file = loads::file::parse(LOAD_FILE).unwrap();
    let measured: Vec<(u8, f32)> = CheckView {
        circuits: finished_circuits(),
        ..Default::default()
    }
    .measured_amps();
    LoadsView::Analysed {
        path: PathBuf::from("/home/pilot/n123ab/loads.toml"),
        analysis: loads::analyse(&file, &measured),
    }
}

fn loads() -> CheckView {
    CheckView {
        step: Step::Loads,
        switches: finished_switches(),
        circuits: finished_circuits(),
        motors: finished_motors(),
        loads: Some(analysed()),
        ..base()
    }
}

fn done() -> CheckView {
    CheckView {
        step: Step::Done,
        switches: finished_switches(),
        circuits: finished_circuits(),
        motors: finished_motors(),
        to_cycle: to_cycle(),
        loads: Some(analysed()),
        report: Some(PathBuf::from(
            "/home/pilot/n123ab/vpx-check-2026-12-01-1834.md",
        )),
        message: Some("Report and CSV written.".into()),
        ..base()
    }
}

/// The aircraft's last check, 2026-11-03 18:30 UTC, for the trend: Landing Lt drew
/// 5.6 A (6.9 A now: +23 %, changed), Nav Lt 1.1 A (1.2 A now: +9 %), and the pump's
/// pin had another name then (not compared).
fn last_check() -> vpx_efis::check::trend::LastCheck {
    use vpx_efis::check::trend::{LastCheck, Reading};
    let r = |pin: &str, name: &str, tenths| Reading {
        pin: pin.into(),
        name: name.into(),
        tenths,
    };
    LastCheck {
        when: Some(std::time::UNIX_EPOCH + Duration::from_secs(1_793_730_600)),
        circuits: vec![
            r("5A-1", "Nav Lt", Some(11)),
            r("5A-2", "Strobe Lt", Some(9)),
            r("5A-3", "Beacon", Some(17)),
            r("10A-1", "Landing Lt", Some(56)),
            r("10A-2", "Taxi Lt", None),
            r("15A-1", "Boost Pump", Some(44)),
        ],
    }
}

fn circuits_trend() -> CheckView {
    CheckView {
        last_check: Some(last_check()),
        ..circuits()
    }
}

fn done_trend() -> CheckView {
    CheckView {
        last_check: Some(last_check()),
        ..done()
    }
}

fn all_passed() -> CheckView {
    let mut v = done();
    v.switches.truncate(1);
    v.circuits.truncate(1);
    v.motors.truncate(1);
    v.to_cycle.truncate(1);
    v.skipped_steps = vec![Step::Loads];
    v.loads = None;
    v
}

fn no_load_file() -> CheckView {
    CheckView {
        loads: Some(LoadsView::TemplateWritten(PathBuf::from(
            "/home/pilot/.config/vpx-efis/loads.toml",
        ))),
        skipped_steps: vec![],
        ..all_passed()
    }
}

fn interrupted() -> CheckView {
    CheckView {
        step: Step::Circuits,
        switches: finished_switches(),
        circuits: {
            let mut c = circuit_results();
            c[3].outcome = Outcome::NotRun;
            c
        },
        current: Some(3),
        to_cycle: vec![(4, "Nav Lt".into(), SwitchId::Input(2))],
        interrupted: Some(Interruption {
            cause: "COMMUNICATION LOST while Landing Lt was on".into(),
            left: vec![
                LeftBehind::new(
                    0x11,
                    "Landing Lt".into(),
                    "unknown: no answer, last seen ON".into(),
                ),
                LeftBehind::new(4, "Nav Lt".into(), "OFF, held by DEVICE_POWER".into()),
            ],
        }),
        report: Some(PathBuf::from(
            "/home/pilot/n123ab/vpx-check-2026-12-01-1834.md",
        )),
        // The flow's last prompt must not be shown once it stopped.
        prompt: circuits().prompt,
        ..base()
    }
}

fn quit_clean() -> CheckView {
    CheckView {
        step: Step::Switches,
        switches: switch_results(),
        current: Some(3),
        interrupted: Some(Interruption {
            cause: "quit".into(),
            left: vec![],
        }),
        ..base()
    }
}

/// The ended check scrolled past its end (kept at its last line by the screen).
fn done_scrolled_to_end() -> CheckView {
    CheckView {
        scroll: 1000,
        ..done()
    }
}

/// The report folder went read-only (a USB stick pulled): the results stay, `w`
/// writes them again.
fn done_report_not_written() -> CheckView {
    let why = "/media/usb/n123ab: Read-only file system (os error 30)";
    CheckView {
        report: None,
        report_error: Some(why.into()),
        message: Some(format!("✗ The report could not be written to {why}")),
        ..done()
    }
}

/// `l` after the check: the load analysis' table and bar chart.
fn done_load_analysis() -> CheckView {
    CheckView {
        show_loads: true,
        ..done()
    }
}

/// The circuits step with the circuits left alone among the results: pins as long as
/// "Field_Pri" and "Starter" are shown whole.
fn circuits_long_pins() -> CheckView {
    let mut v = circuits();
    let left_alone = excluded().into_iter().map(|e| CircuitResult {
        id: e.id,
        name: e.name,
        pin: e.pin,
        breaker: e.breaker,
        switch: e.switch,
        outcome: Outcome::Skipped(e.why),
    });
    v.circuits.splice(0..0, left_alone.take(2));
    v.current = Some(5);
    v
}

fn page(palette: Palette) -> ViewState {
    ViewState {
        theme: ThemeChoice {
            palette,
            why: Why::Asked,
        },
        ..Default::default()
    }
}

/// Switch 6 closed, Landing and Taxi on; flaps up, trims near neutral.
const SW6: u16 = 0b10_0010;

/// Every state a person can reach, with its model and the page's view.
/// The next circuit waits, not switched on: the terminal lost focus (the flow's
/// words, `check::circuits`).
fn circuits_paused_unseen() -> CheckView {
    CheckView {
        prompt: Some(Prompt {
            todo: "Paused before switching Landing Lt on: the terminal lost focus; nothing \
                   is switched on while the page cannot be seen. r: go on; s: skip it."
                .into(),
            watching: "Landing Lt's state (DEVICE_STATUS)".into(),
            time_left: None,
            keys: vec![("r", "go on"), ("s", "skip"), ("Esc", "stop")],
        }),
        message: None,
        ..circuits()
    }
}

/// A light under test asks "Is it lit?" while it is on (the flow's words,
/// `check::circuits`): y and n answer it, from the page's keys or the phone.
fn circuits_is_it_lit() -> CheckView {
    CheckView {
        prompt: Some(Prompt {
            todo: "Switching Landing Lt on to measure it, then back off. Is it lit? y: yes, \
                   n: no."
                .into(),
            watching: "Landing Lt's state and current (DEVICE_STATUS, once a second)".into(),
            time_left: Some(Duration::from_secs(4)),
            keys: vec![
                ("y", "lit"),
                ("n", "not lit"),
                ("s", "skip"),
                ("S", "skip step"),
                ("Esc", "stop"),
            ],
        }),
        message: None,
        ..circuits()
    }
}

/// Each state, with the motor run the page is streaming while it is drawn.
#[allow(clippy::type_complexity)]
fn every_state() -> Vec<(&'static str, CheckView, Model, Instant, Option<MotorRun>)> {
    let on6 = [EFIS_ON, (0x11, 61), (0x12, 38)];
    let (live6, t6) = aircraft::live(SW6, &on6, (20, 128, 120));
    let (stale6, ts) = aircraft::stale(SW6, &on6);
    let landing = [EFIS_ON, (0x11, 69)];
    let (lc, tc) = aircraft::live(0, &landing, (20, 128, 120));
    let (lm, tm) = aircraft::live(0, &[EFIS_ON], (20, 117, 133));
    let (idle, ti) = aircraft::idle();
    let roll_right = MotorRun {
        motor: Motor::Trim(TrimKind::Roll),
        direction: "right",
    };
    vec![
        ("confirm", confirm(), idle.clone(), ti),
        ("switches", switches(), live6, t6),
        ("switches_link_stale", switches(), stale6.clone(), ts),
        ("circuits", circuits(), lc.clone(), tc),
        ("circuits_trend", circuits_trend(), lc.clone(), tc),
        ("done_trend", done_trend(), idle.clone(), ti),
        ("circuits_is_it_lit", circuits_is_it_lit(), lc, tc),
        ("circuits_link_stale", circuits(), stale6.clone(), ts),
        ("motors", motors(), lm, tm),
        ("motors_link_stale", motors(), stale6.clone(), ts),
        ("loads", loads(), idle.clone(), ti),
        ("done", done(), idle.clone(), ti),
        (
            "done_scrolled_to_end",
            done_scrolled_to_end(),
            idle.clone(),
            ti,
        ),
        (
            "done_report_not_written",
            done_report_not_written(),
            idle.clone(),
            ti,
        ),
        ("done_load_analysis", done_load_analysis(), idle.clone(), ti),
        (
            "circuits_paused_unseen",
            circuits_paused_unseen(),
            idle.clone(),
            ti,
        ),
        ("circuits_long_pins", circuits_long_pins(), idle.clone(), ti),
        ("done_all_passed", all_passed(), idle.clone(), ti),
        ("done_no_load_file", no_load_file(), idle.clone(), ti),
        ("interrupted_comm_lost", interrupted(), stale6, ts),
        ("interrupted_quit_clean", quit_clean(), idle, ti),
    ]
    .into_iter()
    // The motors step is drawn while the page streams roll trim right.
    .map(|(name, v, m, now)| (name, v, m, now, (name == "motors").then_some(roll_right)))
    .collect()
}

/// `view` drawn at `w`×`h` on a page in the terminal's own palette.
fn render(view: &CheckView, m: &Model, now: Instant, w: u16, h: u16) -> Buffer {
    render_running(view, m, None, now, w, h)
}

/// [`render`]'s text.
fn screen(view: &CheckView, m: &Model, now: Instant, w: u16, h: u16) -> String {
    plain_text(&render(view, m, now, w, h))
}

/// [`render`] while the page streams the motor run `running`.
fn render_running(
    view: &CheckView,
    m: &Model,
    running: Option<MotorRun>,
    now: Instant,
    w: u16,
    h: u16,
) -> Buffer {
    let page = page(Palette::Terminal);
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    term.draw(|f| check::render(f, f.area(), view, m, &page, running, now))
        .unwrap();
    term.backend().buffer().clone()
}

#[test]
fn every_step_at_80x24() {
    for (name, v, m, now, run) in every_state() {
        let buf = render_running(&v, &m, run, now, 80, 24);
        insta::assert_snapshot!(format!("{name}_80x24"), plain_text(&buf));
    }
}

#[test]
fn every_step_at_160x50() {
    for (name, v, m, now, run) in every_state() {
        let buf = render_running(&v, &m, run, now, 160, 50);
        insta::assert_snapshot!(format!("{name}_160x50"), plain_text(&buf));
    }
}

/// Every step's colours in every palette, as a picture of them (the text is in the
/// snapshots above and the palette changes none of it).
#[test]
fn every_step_in_every_theme() {
    for (name, v, m, now, run) in every_state() {
        let buf = render_running(&v, &m, run, now, 80, 24);
        themes::assert_every_palette("check_snapshots", name, &buf);
    }
}

#[test]
fn every_step_meets_wcag_contrast_in_both_themes() {
    let mut failures = Vec::new();
    for (name, v, m, now, run) in every_state() {
        for (w, h) in [(80, 24), (120, 40), (160, 50)] {
            let buf = render_running(&v, &m, run, now, w, h);
            failures.extend(themes::contrast_in_both(&format!("{name} {w}x{h}"), &buf));
        }
    }
    themes::assert_contrast(failures);
}

/// The colour of the first cell of `needle` on the line holding `on_line`.
fn cell(buf: &Buffer, on_line: &str, needle: &str) -> ratatui::buffer::Cell {
    let (x, y) = find(buf, on_line, needle);
    buf[(x, y)].clone()
}

/// Pass green, fail red, warning amber, each as its palette paints it, and always with
/// its symbol and word, so without colour (mono) nothing is lost.
#[test]
fn marks_have_their_colour_and_always_their_word() {
    let (m, now) = aircraft::idle();
    let buf = render(&done(), &m, now, 160, 50);
    let t = plain_text(&buf);
    for (line, badge, word, dark, light) in [
        ("Nav Lt", "✓ PASS", Color::Green, 40, 22),
        ("Strobe Lt", "✗ FAIL", Color::Red, 203, 124),
        ("Beacon", "⚠ WARN", Color::Yellow, 220, 94),
    ] {
        assert!(t.contains(badge), "{badge} on screen:\n{t}");
        assert_eq!(cell(&buf, line, badge).fg, word, "{badge} on {line}");
        let d = themes::painted(&buf, Palette::Dark);
        assert_eq!(
            cell(&d, line, badge).fg,
            Color::Indexed(dark),
            "dark {badge}"
        );
        let l = themes::painted(&buf, Palette::Light);
        assert_eq!(
            cell(&l, line, badge).fg,
            Color::Indexed(light),
            "light {badge}"
        );
        let mono = themes::painted(&buf, Palette::Mono);
        let c = cell(&mono, line, badge);
        assert_eq!((c.fg, c.bg), (Color::Reset, Color::Reset));
        assert!(
            c.modifier.contains(Modifier::BOLD),
            "{badge} bold without colour"
        );
    }
    // The words after a failure are red too, not just its mark.
    assert_eq!(cell(&buf, "Strobe Lt", "no current").fg, Color::Red);
}

/// A current changed since the last check is said in words, and its row's words are
/// drawn as a caution; a steady one keeps the plain style.
#[test]
fn a_current_changed_since_the_last_check_says_so_in_words_and_caution() {
    let (m, now) = aircraft::idle();
    let buf = render(&done_trend(), &m, now, 160, 50);
    let t = plain_text(&buf);
    assert!(
        t.contains("last check 5.6 A, +23 %: changed since the last check"),
        "{t}"
    );
    assert!(t.contains("last check 1.1 A, +9 %"), "{t}");
    assert_eq!(
        cell(&buf, "Landing Lt", "changed since").fg,
        Color::Yellow,
        "a change is a caution"
    );
    assert_eq!(cell(&buf, "Nav Lt", "last check").fg, Color::Reset);
    let mono = themes::painted(&buf, Palette::Mono);
    assert_eq!(cell(&mono, "Landing Lt", "changed since").fg, Color::Reset);
}

#[test]
fn the_input_under_test_is_on_a_badge_reversed_without_colour() {
    let (m, now) = aircraft::live(SW6, &[EFIS_ON, (0x11, 61), (0x12, 38)], (20, 128, 120));
    let buf = render(&switches(), &m, now, 80, 24);
    let badge = cell(&buf, "▶ 6●◀", "▶ 6●◀");
    assert_eq!(badge.bg, Color::Gray, "{}", plain_text(&buf));
    let mono = themes::painted(&buf, Palette::Mono);
    assert!(
        cell(&mono, "▶ 6●◀", "▶")
            .modifier
            .contains(Modifier::REVERSED)
    );
    assert!(
        !cell(&mono, "▶ 6●◀", " 7○")
            .modifier
            .contains(Modifier::REVERSED)
    );
    // The live readings are there, and the circuits' live states are green ON.
    assert_eq!(cell(&buf, "Landing Lt", "ON").fg, Color::Green);
    assert!(plain_text(&buf).contains("6.1"));
}

/// With the link stale, nothing on any step's screen reads like a live value: no
/// input mark, no ON, no current, no position; the banner says why.
#[test]
fn a_stale_link_never_looks_current() {
    let on6 = [EFIS_ON, (0x11, 61), (0x12, 38)];
    let (m, now) = aircraft::stale(SW6, &on6);
    for (name, v) in [
        ("switches", switches()),
        ("circuits", circuits()),
        ("motors", motors()),
    ] {
        let t = screen(&v, &m, now, 80, 24);
        assert!(
            t.contains("C O M M U N I C A T I O N   L O S T"),
            "{name}:\n{t}"
        );
        for live in ["●", "○", " ON ", "6.1", "3.8", "6.9", "%  stopped"] {
            assert!(
                !t.contains(live),
                "{name} shows {live:?} with a stale link:\n{t}"
            );
        }
    }
    let t = screen(&switches(), &m, now, 80, 24);
    assert!(t.contains("inputs unknown: no live status"), "{t}");
    let t = screen(&circuits(), &m, now, 80, 24);
    assert!(t.contains("no live DEVICE_STATUS: current unknown"), "{t}");
    let t = screen(&motors(), &m, now, 80, 24);
    assert!(t.contains("position unknown"), "{t}");
}

#[test]
fn a_tight_breaker_is_amber_and_says_so() {
    // Landing Lt on its 8 A breaker: 6.9 A is tight; within it, the same bar is green
    // and says so.
    for (tenths, percent, words, colour) in [
        (69, "86 %", "86 % ≥ 80 %: tight", Color::Yellow),
        (30, "38 %", "38 % within", Color::Green),
    ] {
        let (m, now) = aircraft::live(0, &[EFIS_ON, (0x11, tenths)], (20, 128, 120));
        let buf = render(&circuits(), &m, now, 80, 24);
        let t = plain_text(&buf);
        assert!(t.contains(words), "no {words:?} in\n{t}");
        for mark in [percent, "█"] {
            assert_eq!(cell(&buf, "Now ON", mark).fg, colour, "{mark} of {words:?}");
        }
    }
}

#[test]
fn once_stopped_the_check_asks_nothing_more() {
    let (m, now) = aircraft::stale(SW6, &[EFIS_ON]);
    let buf = render(&interrupted(), &m, now, 80, 24);
    let t = plain_text(&buf);
    assert!(!t.contains("DO NOW"), "{t}");
    assert!(!t.contains("skip step"), "{t}");
    assert!(t.contains("Esc  back to the device list"), "{t}");
    assert!(
        t.contains("Landing Lt       unknown: no answer, last seen ON"),
        "{t}"
    );
    assert!(
        t.contains("Nav Lt           OFF, held by DEVICE_POWER"),
        "{t}"
    );
    assert_eq!(cell(&buf, "Stopped:", "STOP").bg, Color::Red);
}

#[test]
fn too_small_terminal_says_so() {
    let (m, now) = aircraft::idle();
    for (w, h) in [(79, 24), (80, 23)] {
        let t = screen(&switches(), &m, now, w, h);
        assert!(t.contains("Terminal too small"), "{t}");
        assert!(t.contains(&format!("{w}×{h} now, needs 80×24.")), "{t}");
    }
    let buf = render(&switches(), &m, now, 60, 20);
    insta::assert_snapshot!(plain_text(&buf));
}

/// `draw` paints in the page's palette, and only inside its area.
#[test]
fn draw_paints_in_the_pages_theme_inside_its_area_only() {
    let (m, now) = aircraft::idle();
    let mut term = Terminal::new(TestBackend::new(100, 30)).unwrap();
    let area = Rect::new(10, 3, 80, 24);
    term.draw(|f| check::draw(f, area, &done(), &m, &page(Palette::Dark), None, now))
        .unwrap();
    let buf = term.backend().buffer();
    assert_eq!(buf[(0, 0)].bg, Color::Reset, "outside the area");
    assert_eq!(buf[(99, 29)].bg, Color::Reset, "outside the area");
    assert_eq!(
        buf[(10, 3)].bg,
        Color::Indexed(16),
        "inside: dark's own black"
    );
    assert_eq!(
        buf[(89, 26)].bg,
        Color::Indexed(16),
        "inside: dark's own black"
    );
    assert_eq!(cell(buf, "Strobe Lt", "✗ FAIL").fg, Color::Indexed(203));
}

/// A long plan is packed into columns so every circuit that will be powered is seen
/// before the person confirms; one too long even for that says how many are hidden.
#[test]
fn a_long_plan_is_all_seen_or_says_what_is_hidden() {
    let (m, now) = aircraft::idle();
    let many = |n: u8| -> CheckView {
        let mut v = confirm();
        v.plan = (0..n)
            .map(|i| planned(4 + i, &format!("Circuit {i:02}"), "5A-1", 3, 2))
            .collect();
        v
    };
    let v = many(24);
    let t = screen(&v, &m, now, 80, 24);
    for i in 0..24 {
        assert!(t.contains(&format!("Circuit {i:02}")), "circuit {i}:\n{t}");
    }
    assert!(!t.contains("not shown"), "{t}");
    insta::assert_snapshot!(t);
    let t = screen(&many(40), &m, now, 80, 24);
    let shown = (0..40)
        .filter(|i| t.contains(&format!("Circuit {i:02}")))
        .count();
    assert!(
        t.contains(&format!(
            "{} more not shown: enlarge the window",
            40 - shown
        )),
        "{shown} shown:\n{t}"
    );
    // At 160×50 the same forty fit.
    let t = screen(&many(40), &m, now, 160, 50);
    assert!(
        (0..40).all(|i| t.contains(&format!("Circuit {i:02}"))),
        "{t}"
    );
}

/// A check stopped before most items ran, with nothing failed, must not read as a
/// clean installation: no green "nothing left to fix".
#[test]
fn a_stopped_check_with_nothing_failed_does_not_read_clean() {
    let (m, now) = aircraft::idle();
    let mut v = quit_clean();
    v.switches
        .retain(|s| !matches!(s.outcome, Outcome::Found(_)));
    let buf = render(&v, &m, now, 80, 24);
    let t = plain_text(&buf);
    assert!(!t.contains("Nothing left to fix"), "{t}");
    assert!(
        t.contains("Nothing failed so far, but 4 not run: check again."),
        "{t}"
    );
    assert_eq!(cell(&buf, "Nothing failed", "Nothing").fg, Color::Yellow);
    // Every item run and none failed: then it is green.
    let (m, now) = aircraft::idle();
    let buf = render(&all_passed(), &m, now, 80, 24);
    assert_eq!(cell(&buf, "Nothing left", "Nothing").fg, Color::Green);
}

/// The ended check's results scroll: at the top it says how much is below and which
/// keys scroll; at the end (and past it) the last result is on the screen under how
/// much is above; the app's limit is where the screen stops.
#[test]
fn the_ended_check_scrolls_to_every_result_and_says_its_keys() {
    let (m, now) = aircraft::idle();
    let p = page(Palette::Terminal);
    let top = screen(&done(), &m, now, 80, 24);
    assert!(top.contains("more lines below"), "{top}");
    assert!(!top.contains("more lines above"), "{top}");
    assert!(top.contains("↑↓ PgUp PgDn Home End  scroll"), "{top}");
    assert!(top.contains("l  load analysis"), "{top}");
    let max = check::results_scroll_max(&done(), &m, &p, now, Rect::new(0, 0, 80, 24));
    assert!(max > 20, "{max}");
    let at = |scroll| {
        let v = CheckView { scroll, ..done() };
        screen(&v, &m, now, 80, 24)
    };
    let end = at(max);
    assert_eq!(end, at(max + 50), "kept at the end");
    assert_ne!(
        end,
        at(max - 1),
        "one line short of the end is another screen"
    );
    assert!(end.contains(&format!("↑ {max} more lines above")), "{end}");
    assert!(!end.contains("more lines below"), "{end}");
    // The last result: the load analysis' last phase.
    assert!(end.contains("emergency"), "{end}");
    // Still running: nothing scrolls.
    assert_eq!(
        check::results_scroll_max(&circuits(), &m, &p, now, Rect::new(0, 0, 80, 24)),
        0
    );
}

/// A report that could not be written says why, in red with its mark and word, and
/// the key that writes it again; the results stay on the screen.
#[test]
fn a_report_not_written_says_why_and_the_key_to_write_it_again() {
    let (m, now) = aircraft::idle();
    for (w, h) in [(80, 24), (120, 40)] {
        let buf = render(&done_report_not_written(), &m, now, w, h);
        let t = plain_text(&buf);
        assert!(t.contains("✗ Report NOT written: "), "{t}");
        assert!(t.contains("w: write it again"), "{t}");
        assert!(t.contains(" w  write the report again"), "{t}");
        assert!(t.contains("Left to fix"), "{t}");
        assert_eq!(cell(&buf, "Report NOT written", "✗").fg, Color::Red);
    }
}

/// After the check, `l` shows the load analysis whole: the phases' table, the bar
/// chart against the alternator, and the circuits.
#[test]
fn the_load_analysis_is_seen_after_the_check() {
    let (m, now) = aircraft::idle();
    let t = screen(&done_load_analysis(), &m, now, 120, 40);
    for want in [
        "Load analysis",
        "Verdict",
        "│ alternator 18 A",
        "Circuit",
        "l  results",
    ] {
        assert!(t.contains(want), "no {want:?} in\n{t}");
    }
    // At 80×24 it scrolls: the chart and the last circuit are reached.
    let p = page(Palette::Terminal);
    let max =
        check::results_scroll_max(&done_load_analysis(), &m, &p, now, Rect::new(0, 0, 80, 24));
    assert!(max > 0);
    let seen: String = (0..=max)
        .map(|scroll| {
            let v = CheckView {
                scroll,
                ..done_load_analysis()
            };
            screen(&v, &m, now, 80, 24)
        })
        .collect();
    for want in ["│ alternator 18 A", "Fuel Pump      15A-1", "emergency"] {
        assert!(seen.contains(want), "no {want:?} at any scroll");
    }
}

/// The pin column holds the longest pin whole ("Field_Pri", "Starter"), at 80 and at
/// 120 columns, and the names beside it are not cut when there is room.
#[test]
fn circuit_rows_show_the_longest_pin_whole() {
    let (m, now) = aircraft::idle();
    for (w, h) in [(80, 24), (120, 40)] {
        let t = screen(&circuits_long_pins(), &m, now, w, h);
        for row in [
            " Field_Pri never touched",
            "Starter       Starter   never touched",
            "Alternator    Field_Pri never touched",
        ] {
            assert!(t.contains(row), "{w}×{h}: no {row:?} in\n{t}");
        }
        assert!(!t.contains("Field…") && !t.contains("Start…"), "{t}");
    }
}

/// The summary counts what the report and the headless run count: the items tested,
/// with the load analysis' warnings apart.
#[test]
fn the_summary_counts_as_the_report_does() {
    let (m, now) = aircraft::idle();
    for v in [done(), no_load_file()] {
        let t = screen(&v, &m, now, 160, 50);
        let about = vpx_efis::check::report::About {
            when: std::time::UNIX_EPOCH,
            port: "/dev/ttyUSB0".into(),
            unit: None,
            ours: "0".into(),
            travel: vec![],
        };
        let md = vpx_efis::check::report::markdown(&v, &about);
        let n = |m| v.marks().filter(|x| *x == m).count();
        use vpx_efis::check::state::Mark;
        let skipped = n(Mark::Skipped);
        if skipped > 0 {
            assert!(
                t.contains(&format!("– {skipped} skipped")),
                "{skipped} skipped:\n{t}"
            );
            assert!(md.contains(&format!("{skipped} skipped")), "{md}");
        } else {
            // The load file's row is skipped, but it is not an item: not counted.
            assert!(!t.contains(" skipped  "), "{t}");
            assert!(!md.contains(" skipped."), "{md}");
        }
        let passed = n(Mark::Pass);
        assert!(t.contains(&format!("✓ {passed} passed")), "{t}");
        assert!(md.contains(&format!("{passed} passed")), "{md}");
    }
}

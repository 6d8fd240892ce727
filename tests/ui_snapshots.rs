//! Snapshots of every state a person can reach on the electrical page, rendered into a
//! `TestBackend`. Text snapshots hide colour, so the states where colour carries the
//! meaning (Appendix A: green=on, white=off, red=faulted) are also snapshotted with the
//! buffer's Debug form, which lists styles, and asserted cell by cell.

use std::time::{Duration, Instant};

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};

use vpx_efis::model::{Connection, Model, Motor, Source, TrimKind};
use vpx_efis::protocol::FaultCode;
use vpx_efis::protocol::device::{EFIS, FIELD_PRI, FLAPS, STARTER, TRIM_P, TRIM_R};
use vpx_efis::ui::palette::Palette;
use vpx_efis::ui::state::{ControlState, MotorRun, Overlay, ReleaseMode, SortOrder, ViewState};
use vpx_efis::ui::{self, MIN_HEIGHT, MIN_WIDTH};

mod themes;

mod common;
use common::screen::{find, plain_text};

mod fixtures {
    use super::*;
    use vpx_efis::protocol::Packet;
    use vpx_efis::protocol::message::{
        DataIntegrityCode, DeviceEnable, DeviceName, DeviceSpec, DeviceStatus, EnableFlag,
        FaultStatus, FlapTrimStatus, MiscFlags, OvervoltageLimit, SignedTenths, SwitchId,
        SwitchInputs, SystemFaultFlags, SystemSpec, SystemStatus, Tenths, WigWagModeSetting,
    };

    /// The devices the demo aircraft has wired, with names, breakers and switches.
    pub const WIRED: &[(u8, &str, u8, SwitchId)] = &[
        (STARTER, "", 5, SwitchId::AlwaysOn),
        (EFIS, "EFIS", 5, SwitchId::AlwaysOn),
        (FIELD_PRI, "Alternator", 5, SwitchId::Input(1)),
        (4, "Nav Lt", 3, SwitchId::Input(2)),
        (5, "Strobe Lt", 3, SwitchId::Input(3)),
        (6, "Beacon", 2, SwitchId::Input(4)),
        (7, "Pitot Heat", 5, SwitchId::Input(5)),
        (8, "Radio", 3, SwitchId::AlwaysOn),
        (0x11, "Landing Lt", 8, SwitchId::Input(6)),
        (0x12, "Taxi Lt", 6, SwitchId::Input(6)),
        (0x17, "Fuel Pump", 10, SwitchId::Input(7)),
        (0x1A, "", 2, SwitchId::Off),
    ];

    /// Devices on in normal cruise, with their current in tenths of an amp.
    pub const ON: &[(u8, u16)] = &[
        (EFIS, 24),
        (FIELD_PRI, 31),
        (4, 12),
        (5, 18),
        (8, 21),
        (0x17, 45),
    ];

    pub use crate::common::configured::{Unit, faults};

    pub fn system(amps: u16, volts: i16) -> SystemStatus {
        SystemStatus {
            system_current: Tenths(amps),
            main_bus_volts: SignedTenths(volts),
            internal_temp: 31,
            switches: SwitchInputs::from_word(0b0000_0000_0111_1111),
            ..Default::default()
        }
    }

    pub fn devices(on: &[(u8, u16)]) -> DeviceStatus {
        let mut d = DeviceStatus::default();
        for &(id, amps) in on {
            d.on[id as usize] = true;
            d.current[id as usize] = Tenths(amps);
        }
        d
    }

    pub fn flap_trim() -> FlapTrimStatus {
        crate::common::configured::flap_trim((20, 128, 120))
    }

    impl Unit {
        /// A unit that answered every connect-time question at `t0`.
        pub fn configured(source: Source) -> Unit {
            Unit::answered(source, WIRED)
        }

        /// `secs` seconds of broadcasts starting at `from_ms`, one status pair per
        /// second, bus volts and amps wandering so the plot has a shape.
        pub fn run(
            &mut self,
            from_ms: u64,
            secs: u64,
            mut each: impl FnMut(
                u64,
                &mut SystemStatus,
                &mut DeviceStatus,
                &mut FlapTrimStatus,
            ) -> Option<FaultStatus>,
        ) {
            for i in 0..secs {
                let ms = from_ms + i * 1000;
                let wobble = ((i * 7) % 11) as i16 - 5;
                let mut s = system(145 + (i % 9) as u16 * 3, 138 + wobble);
                let mut d = devices(ON);
                let mut ft = flap_trim();
                let f = each(i, &mut s, &mut d, &mut ft);
                self.apply(ms, s);
                self.apply(ms, d);
                self.apply(ms + 50, ft);
                if let Some(f) = f {
                    self.apply(ms + 60, f);
                }
            }
        }
    }

    /// Two minutes of a healthy unit; `now` is 400 ms after the last broadcasts.
    pub fn normal() -> (Model, Instant) {
        let mut u = Unit::configured(Source::Simulated {
            scenario: "demo".into(),
        });
        u.run(1000, 120, |_, _, _, _| None);
        let now = u.at(1000 + 119 * 1000 + 400);
        (u.model, now)
    }

    /// `normal`, with `patch` applied to the last second.
    pub fn normal_with(
        mut patch: impl FnMut(
            &mut SystemStatus,
            &mut DeviceStatus,
            &mut FlapTrimStatus,
        ) -> Option<FaultStatus>,
    ) -> (Model, Instant) {
        let mut u = Unit::configured(Source::Simulated {
            scenario: "demo".into(),
        });
        u.run(1000, 119, |_, _, _, _| None);
        u.run(120_000, 1, |_, s, d, ft| patch(s, d, ft));
        let now = u.at(120_400);
        (u.model, now)
    }

    pub fn faulted_device() -> (Model, Instant) {
        normal_with(|_, d, _| {
            d.on[EFIS as usize] = false;
            d.current[EFIS as usize] = Tenths(0);
            Some(faults(&[(EFIS, FaultCode::ShortCircuit)], false))
        })
    }

    /// The EFIS shorted, and a reset sent 100 ms ago that the unit has not answered.
    pub fn reset_sent() -> (Model, Instant) {
        let (mut m, now) = faulted_device();
        let clear = vpx_efis::protocol::message::DeviceClear { device_id: EFIS };
        m.note_sent(now - Duration::from_millis(100), &Packet::request(7, clear));
        (m, now)
    }

    pub fn system_fault() -> (Model, Instant) {
        normal_with(|s, _, _| {
            s.system_current = Tenths(612);
            s.aux_battery_volts = Tenths(126);
            s.faults = SystemFaultFlags {
                current_over_48a: true,
                current_over_60a: true,
                warm_reset: true,
                data_integrity_failure: true,
                external_data_missing: true,
            };
            s.data_integrity_code = Some(DataIntegrityCode::FlapConfig);
            s.misc = MiscFlags {
                starter_annunciator: true,
                wig_wag_mode: WigWagModeSetting::Steady,
                software_update: true,
                wig_wag_active: true,
            };
            Some(faults(&[], true))
        })
    }

    /// Secondary alternator on 10A-3: the primary runs (green), the standby is off
    /// (white).
    pub fn dual_alternator() -> (Model, Instant) {
        let mut u = Unit::configured(Source::Simulated {
            scenario: "dual-alt".into(),
        });
        u.apply(
            10,
            SystemSpec {
                overvoltage_limit: OvervoltageLimit::V16,
                secondary_alternator: Some(0x13),
            },
        );
        u.apply(
            10,
            DeviceEnable {
                device_id: 0x13,
                flag: EnableFlag::Enabled,
            },
        );
        u.apply(10, DeviceName::new(0x13, "Alternator 2").unwrap());
        u.apply(
            10,
            DeviceSpec {
                device_id: 0x13,
                circuit_breaker: 5,
                switch_id: SwitchId::Input(8),
                current_fault: false,
                switch_raw: None,
            },
        );
        u.run(1000, 60, |_, _, _, _| None);
        {
            let now = u.at(60_400);
            (u.model, now)
        }
    }

    pub fn trim_running() -> (Model, Instant) {
        normal_with(|s, _, ft| {
            ft.pitch_trim.motor_running = true;
            ft.pitch_trim_position = 90;
            s.switches.pitch_trim_up = true;
            None
        })
    }

    pub fn flaps_midpoints() -> (Model, Instant) {
        normal_with(|s, _, ft| {
            ft.flap_position = 90;
            ft.flap.overspeed_alarm = true;
            ft.flap.down_switch_inhibited = true;
            ft.roll_trim.fault = true;
            ft.roll_trim_fault = FaultCode::TrimRunaway;
            s.switches.flap_down = true;
            None
        })
    }

    /// Data stopped 5.6 s before `now` on a real serial port.
    pub fn comm_lost() -> (Model, Instant) {
        let mut u = Unit::configured(Source::Serial {
            path: "/dev/ttyUSB0".into(),
        });
        u.run(1000, 90, |_, _, _, _| None);
        let now = u.at(1000 + 89 * 1000 + 5600);
        (u.model, now)
    }

    pub fn never_connected() -> (Model, Instant) {
        let t0 = Instant::now();
        (
            Model::new(Source::Serial {
                path: "/dev/ttyUSB0".into(),
            }),
            t0 + Duration::from_millis(300),
        )
    }

    /// The port opened 8 s ago and the unit has said nothing.
    pub fn connected_silent() -> (Model, Instant) {
        let t0 = Instant::now();
        let mut m = Model::new(Source::Serial {
            path: "/dev/ttyUSB0".into(),
        });
        m.note_connected(t0, "/dev/ttyUSB0".into());
        (m, t0 + Duration::from_secs(8))
    }

    pub fn port_lost() -> (Model, Instant) {
        let mut u = Unit::configured(Source::Serial {
            path: "/dev/ttyUSB0".into(),
        });
        u.run(1000, 30, |_, _, _, _| None);
        let at = u.at(30_500);
        u.model.note_link_lost(at, "device disconnected".into());
        {
            let now = u.at(33_000);
            (u.model, now)
        }
    }

    pub fn replay() -> (Model, Instant) {
        let mut u = Unit::configured(Source::Replay {
            file: "hangar-2024-05-01.vpxlog".into(),
        });
        u.run(1000, 10, |_, _, _, _| None);
        {
            let now = u.at(10_400);
            (u.model, now)
        }
    }
}

fn draw(model: &Model, view: &ViewState, now: Instant, w: u16, h: u16) -> Buffer {
    draw_with(model, view, &ControlState::default(), now, w, h)
}

/// [`draw`] with the controller in the state `control`.
fn draw_with(
    model: &Model,
    view: &ViewState,
    control: &ControlState,
    now: Instant,
    w: u16,
    h: u16,
) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal
        .draw(|f| ui::render(f, model, view, control, now))
        .unwrap();
    terminal.backend().buffer().clone()
}

/// The colour of the State column on the row of device `name`: `state` as a whole
/// word to the right of the name.
fn state_cell(buf: &Buffer, name: &str, state: &str) -> Color {
    let (nx, y) = find(buf, name, name);
    let cells: Vec<&str> = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
    let s: Vec<String> = state.chars().map(String::from).collect();
    let start = nx as usize + name.chars().count();
    for x in start..cells.len() - s.len() {
        if (0..s.len()).all(|k| cells[x + k] == s[k])
            && cells[x + s.len()] == " "
            && cells[x - 1] == " "
        {
            return buf[(x as u16, y)].fg;
        }
    }
    panic!(
        "state {state:?} not on the {name:?} row:\n{}",
        plain_text(buf)
    );
}

fn view_selecting(id: u8) -> ViewState {
    ViewState {
        selected: Some(id),
        ..Default::default()
    }
}

/// A state a person can reach on the page: its name, the unit's history with the
/// moment it is drawn at, the view, and the terminal's size.
struct State {
    name: &'static str,
    unit: fn() -> (Model, Instant),
    view: ViewState,
    size: (u16, u16),
}

impl State {
    /// Drawn with `view`, the controller as [`control_of`] gives it for this state.
    fn draw_in(&self, view: &ViewState) -> Buffer {
        let (m, now) = (self.unit)();
        let (w, h) = self.size;
        draw_with(&m, view, &control_of(self.name), now, w, h)
    }
}

/// Every state a person can reach, by name: what the snapshots, the themes and the
/// contrast check go over.
fn every_state() -> Vec<State> {
    let help = |v: ViewState| ViewState {
        overlay: Overlay::Help,
        ..v
    };
    let notice = |words: &str, v: ViewState| ViewState {
        notice: Some(words.into()),
        ..v
    };
    let s = |name, unit, view, size| State {
        name,
        unit,
        view,
        size,
    };
    let efis = || view_selecting(EFIS);
    let none = ViewState::default;
    vec![
        s("normal_80x24", fixtures::normal, efis(), (80, 24)),
        s("normal_120x40", fixtures::normal, efis(), (120, 40)),
        s(
            "normal_160x50",
            fixtures::normal,
            view_selecting(4),
            (160, 50),
        ),
        s(
            "wide_200x60",
            fixtures::normal,
            view_selecting(4),
            (200, 60),
        ),
        s(
            "faulted_device",
            fixtures::faulted_device,
            efis(),
            (120, 40),
        ),
        s("reset_sent", fixtures::reset_sent, efis(), (80, 24)),
        s("system_fault", fixtures::system_fault, efis(), (120, 40)),
        s(
            "dual_alternator",
            fixtures::dual_alternator,
            view_selecting(0x13),
            (120, 40),
        ),
        s(
            "trim_running",
            fixtures::trim_running,
            view_selecting(TRIM_P),
            (120, 40),
        ),
        s(
            "flaps_midpoints",
            fixtures::flaps_midpoints,
            view_selecting(FLAPS),
            (120, 40),
        ),
        s("comm_lost_80x24", fixtures::comm_lost, efis(), (80, 24)),
        s("comm_lost_160x50", fixtures::comm_lost, efis(), (160, 50)),
        s("help_100x30", fixtures::normal, help(efis()), (100, 30)),
        s("help_80x24", fixtures::normal, help(efis()), (80, 24)),
        s("help_replay", fixtures::replay, help(efis()), (120, 40)),
        s("too_small", fixtures::normal, none(), (60, 20)),
        s(
            "alphabetical",
            fixtures::normal,
            ViewState {
                sort: SortOrder::Alphabetical,
                ..efis()
            },
            (120, 40),
        ),
        s(
            "never_connected",
            fixtures::never_connected,
            none(),
            (80, 24),
        ),
        s(
            "connected_silent",
            fixtures::connected_silent,
            none(),
            (80, 24),
        ),
        s("port_lost", fixtures::port_lost, efis(), (120, 40)),
        s("replay", fixtures::replay, none(), (120, 40)),
        s(
            "notice",
            fixtures::normal,
            notice(REFUSED, efis()),
            (120, 40),
        ),
        s(
            "moved_against_80x24",
            fixtures::normal,
            notice(MOVED_AGAINST, view_selecting(TRIM_P)),
            (80, 24),
        ),
        s(
            "moved_against_refused_120x40",
            fixtures::normal,
            notice(MOVED_AGAINST_REFUSED, view_selecting(TRIM_P)),
            (120, 40),
        ),
        s(
            "short_terminal_scrolled",
            fixtures::normal,
            view_selecting(TRIM_P),
            (80, 24),
        ),
    ]
}

/// The state `name` of [`every_state`], drawn.
fn drawn(name: &str) -> Buffer {
    let state = every_state().into_iter().find(|s| s.name == name);
    let state = state.unwrap_or_else(|| panic!("no state {name:?}"));
    state.draw_in(&state.view)
}

/// How a snapshot holds a screen: its text, or the buffer's Debug form, which lists
/// every cell's style, for the screens whose meaning is in their colours (Appendix A).
#[derive(Clone, Copy, Debug)]
enum Form {
    Text,
    Styles,
}

/// The screens pinned whole: (the snapshot's name, the state, its form).
const PINNED: [(&str, &str, Form); 20] = [
    ("normal_80x24", "normal_80x24", Form::Text),
    ("normal_120x40_styles", "normal_120x40", Form::Styles),
    ("normal_160x50", "normal_160x50", Form::Text),
    (
        "wide_terminal_gives_its_width_to_the_right_hand_panels",
        "wide_200x60",
        Form::Text,
    ),
    (
        "faulted_device_names_the_fault_in_red_and_explains_it",
        "faulted_device",
        Form::Styles,
    ),
    (
        "a_reset_not_yet_answered_is_said_beside_the_fault_not_shown_as_current",
        "reset_sent",
        Form::Styles,
    ),
    (
        "system_fault_and_every_flag_in_words",
        "system_fault",
        Form::Text,
    ),
    (
        "dual_alternator_running_green_standby_white",
        "dual_alternator",
        Form::Styles,
    ),
    (
        "trim_running_shows_the_run_and_the_release_mode",
        "trim_running",
        Form::Text,
    ),
    (
        "flaps_with_midpoints_overspeed_and_inhibit",
        "flaps_midpoints",
        Form::Text,
    ),
    (
        "comm_lost_80x24_blanks_every_live_value",
        "comm_lost_80x24",
        Form::Styles,
    ),
    ("comm_lost_160x50", "comm_lost_160x50", Form::Text),
    ("help_overlay_lists_every_key", "help_100x30", Form::Text),
    ("help_overlay_80x24", "help_80x24", Form::Text),
    ("too_small_terminal_says_so", "too_small", Form::Text),
    (
        "alphabetical_sort_keeps_flaps_and_trim_apart",
        "alphabetical",
        Form::Text,
    ),
    ("never_connected", "never_connected", Form::Text),
    (
        "connected_but_silent_is_communication_lost",
        "connected_silent",
        Form::Text,
    ),
    ("port_lost_says_it_is_reopening", "port_lost", Form::Text),
    (
        "short_terminal_scrolls_the_list_to_the_selection_and_says_what_is_hidden",
        "short_terminal_scrolled",
        Form::Text,
    ),
];

#[test]
fn every_pinned_screen() {
    for (snapshot, state, form) in PINNED {
        let buf = drawn(state);
        match form {
            Form::Text => insta::assert_snapshot!(snapshot, plain_text(&buf)),
            Form::Styles => insta::assert_snapshot!(snapshot, format!("{buf:?}")),
        }
    }
}

/// The detail pane gives the selected circuit's current at the aircraft's last check
/// (from the logbook), with its date, in the label's style for the word and the
/// text's for the figure.
#[test]
fn the_detail_pane_shows_the_last_check() {
    use vpx_efis::check::trend::{LastCheck, Reading};
    let (m, now) = fixtures::normal();
    let view = ViewState {
        last_check: Some(LastCheck {
            // 2026-11-03T18:30:00Z.
            when: Some(std::time::UNIX_EPOCH + Duration::from_secs(1_793_730_600)),
            circuits: vec![Reading {
                pin: "5A-1".into(),
                name: "Nav Lt".into(),
                tenths: Some(11),
            }],
        }),
        ..view_selecting(4)
    };
    let buf = draw(&m, &view, now, 160, 50);
    let t = plain_text(&buf);
    assert!(
        t.contains("history last check 1.1 A, 2026-11-03 18:30 UTC"),
        "{t}"
    );
    insta::assert_snapshot!(t);
    let (x, y) = (0..buf.area.height)
        .find_map(|y| {
            let line: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
            line.find("history last check")
                .map(|i| (line[..i].chars().count() as u16, y))
        })
        .unwrap();
    assert_eq!(
        buf[(x, y)].fg,
        vpx_efis::ui::theme::label().fg.unwrap_or_default()
    );
    assert_eq!(buf[(x + 8, y)].fg, ratatui::style::Color::Reset);
}

#[test]
fn normal_120x40_styles() {
    let buf = drawn("normal_120x40");
    // Appendix A colours: green=on, white=off.
    assert_eq!(state_cell(&buf, "Nav Lt", "ON"), Color::Green);
    assert_eq!(state_cell(&buf, "Beacon", "OFF"), Color::White);
    assert_eq!(state_cell(&buf, "Starter", "OFF"), Color::White);
    // The Vertical Power mark, white on black.
    let (x, y) = find(&buf, "VERTICAL POWER", "VERTICAL POWER");
    assert_eq!(
        (buf[(x, y)].fg, buf[(x, y)].bg),
        (Color::White, Color::Black)
    );
    assert!(!plain_text(&buf).contains("COMMUNICATION LOST"));
}

#[test]
fn faulted_device_names_the_fault_in_red_and_explains_it() {
    let buf = drawn("faulted_device");
    assert_eq!(state_cell(&buf, "EFIS", "SHORT_CIRCUIT"), Color::Red);
    let t = plain_text(&buf);
    assert!(t.contains("Device short circuit."), "{t}");
    assert!(t.contains("remains off until cleared"), "{t}");
    // Reset is offered (not dimmed) for a faulted device.
    let (x, y) = find(&buf, "reset\u{a0}fault", "\u{a0}r\u{a0}");
    assert!(!buf[(x, y)].modifier.contains(Modifier::DIM));
}

/// After `r`, until the unit's next broadcast answers it, the row says the reset is
/// sent, in the caution colour, not as a current fault in red; the detail pane says
/// what it waits for, and `r` is dimmed.
#[test]
fn a_reset_not_yet_answered_is_said_beside_the_fault_not_shown_as_current() {
    let buf = drawn("reset_sent");
    assert_eq!(
        state_cell(&buf, "EFIS", "SHORT_CIRCUIT · reset sent"),
        Color::Yellow
    );
    let t = plain_text(&buf);
    assert!(t.contains("RESET SENT for SHORT_CIRCUIT (0x07)"), "{t}");
    let (x, y) = find(&buf, "waiting\u{a0}for", "\u{a0}r\u{a0}");
    assert!(buf[(x, y)].modifier.contains(Modifier::DIM));
}

#[test]
fn reset_is_dimmed_unless_faulted_and_starter_cannot_be_switched() {
    let (m, now) = fixtures::normal();
    let buf = draw(&m, &view_selecting(EFIS), now, 120, 40);
    let (x, y) = find(&buf, "reset\u{a0}fault", "\u{a0}r\u{a0}");
    assert!(buf[(x, y)].modifier.contains(Modifier::DIM));
    let buf = draw(&m, &view_selecting(STARTER), now, 120, 40);
    let t = plain_text(&buf);
    assert!(t.contains("starter is switched by the VP-X only"), "{t}");
    let (x, y) = find(&buf, "starter\u{a0}is", "\u{a0}o/f\u{a0}");
    assert!(buf[(x, y)].modifier.contains(Modifier::DIM));
}

#[test]
fn system_fault_and_every_flag_in_words() {
    let (m, now) = fixtures::system_fault();
    let buf = drawn("system_fault");
    // The flags wrap on screen, so their words are checked before wrapping.
    let flags: Vec<String> = ui::system_panel::flags(&m, now)
        .into_iter()
        .map(|(t, _)| t)
        .collect();
    let t = format!("{}\n{}", flags.join("\n"), plain_text(&buf));
    for words in [
        "SYSTEM FAULT",
        "OVER 60 A",
        "OVER 48 A",
        "DATA INTEGRITY FAILURE: Flap configuration error",
        "WARM RESET",
        "EXTERNAL DATA MISSING",
        "SOFTWARE UPDATED",
        "STARTER ENGAGED",
        "WIG-WAG ACTIVE (steady)",
        "aux 12.6 V",
        "61.2 A",
    ] {
        assert!(t.contains(words), "missing {words:?}:\n{t}");
    }
    let (x, y) = find(&buf, "SYSTEM FAULT", "SYSTEM FAULT");
    assert_eq!(buf[(x, y)].fg, Color::Red);
}

#[test]
fn dual_alternator_running_green_standby_white() {
    let buf = drawn("dual_alternator");
    assert_eq!(state_cell(&buf, "Alternator ", "ON"), Color::Green);
    assert_eq!(state_cell(&buf, "Alternator 2", "OFF"), Color::White);
    let t = plain_text(&buf);
    assert!(t.contains("A1") && t.contains("A2"), "{t}");
    assert!(t.contains("secondary alternator"), "{t}");
}

#[test]
fn trim_running_shows_the_run_and_the_release_mode() {
    let t = plain_text(&drawn("trim_running"));
    assert!(t.contains("▶ pitch trim up"), "{t}");
    assert!(t.contains("keys: release seen"), "{t}");
    assert!(
        t.contains("hold u / Shift+↑") && t.contains("pitch trim down"),
        "{t}"
    );
}

#[test]
fn roll_trim_row_shows_left_and_right() {
    let (m, now) = fixtures::normal();
    let buf = draw(&m, &view_selecting(TRIM_R), now, 120, 40);
    let t = plain_text(&buf);
    assert!(
        t.contains("roll trim left") && t.contains("roll trim right"),
        "{t}"
    );
    assert!(t.contains("keys: auto-repeat"), "{t}");
}

#[test]
fn flaps_with_midpoints_overspeed_and_inhibit() {
    let buf = drawn("flaps_midpoints");
    let t = plain_text(&buf);
    assert!(t.contains("FLAP OVERSPEED ALARM"), "{t}");
    assert!(t.contains("flap down inhibited"), "{t}");
    assert!(t.contains("roll trim TRIM_RUNAWAY (0x0e)"), "{t}");
    // Flaps sit on midpoint 1: the position mark replaces the "1" on the gauge.
    let (_, y) = find(&buf, "Flaps ", "Flaps UP├");
    let gauge: String = (0..buf.area.width)
        .map(|x| buf[(x, y)].symbol().to_string())
        .collect();
    assert!(
        gauge.contains('●') && gauge.contains('2') && !gauge.contains("─1─"),
        "{gauge}"
    );
}

#[test]
fn comm_lost_80x24_blanks_every_live_value() {
    let buf = drawn("comm_lost_80x24");
    let t = plain_text(&buf);
    assert!(t.contains("C O M M U N I C A T I O N   L O S T"), "{t}");
    let (x, y) = find(&buf, "C O M M", "C O M M");
    assert_eq!((buf[(x, y)].fg, buf[(x, y)].bg), (Color::White, Color::Red));
    // No live reading may survive: no amps, no volts, no ON/OFF.
    for stale in ["2.4", "13.", " ON ", " OFF ", "31 °C"] {
        assert!(!t.contains(stale), "stale {stale:?} still shown:\n{t}");
    }
    assert!(t.contains("-- A") && t.contains("-- V"), "{t}");
}

#[test]
fn comm_lost_recovers_by_itself_when_data_returns() {
    let (mut m, now) = fixtures::comm_lost();
    let back = now + Duration::from_millis(100);
    m.apply_packet(
        back,
        &vpx_efis::protocol::Packet::from_vpx(1, fixtures::system(150, 139)),
    );
    m.apply_packet(
        back,
        &vpx_efis::protocol::Packet::from_vpx(2, fixtures::devices(fixtures::ON)),
    );
    let buf = draw(&m, &view_selecting(EFIS), back, 80, 24);
    let t = plain_text(&buf);
    assert!(!t.contains("C O M M U N I C A T I O N"), "{t}");
    assert!(t.contains("13.9 V"), "{t}");
}

#[test]
fn help_overlay_lists_every_key() {
    let t = plain_text(&drawn("help_100x30"));
    for (key, _) in vpx_efis::control::keymap::HELP {
        assert!(t.contains(key), "help lacks {key:?}:\n{t}");
    }
    assert!(
        !t.contains("replay:"),
        "no replay keys on a live page:\n{t}"
    );
}

#[test]
fn help_overlay_in_replay_adds_the_replay_keys_and_says_read_only() {
    let t = plain_text(&drawn("help_replay"));
    for (key, what) in ui::help::REPLAY_KEYS {
        assert!(
            t.contains(key) && t.contains(what),
            "help lacks {key:?}:\n{t}"
        );
    }
    assert!(t.contains("read-only"), "{t}");
}

#[test]
fn too_small_terminal_says_so() {
    let (m, now) = fixtures::normal();
    assert!(plain_text(&drawn("too_small")).contains("needs 80×24"));
    // One column or row short is already too small: the layout is not tried.
    for (w, h) in [(MIN_WIDTH - 1, MIN_HEIGHT), (MIN_WIDTH, MIN_HEIGHT - 1)] {
        assert!(plain_text(&draw(&m, &ViewState::default(), now, w, h)).contains("too small"));
    }
    assert!(
        !plain_text(&draw(&m, &ViewState::default(), now, MIN_WIDTH, MIN_HEIGHT))
            .contains("too small")
    );
}

#[test]
fn alphabetical_sort_keeps_flaps_and_trim_apart() {
    let (m, now) = fixtures::normal();
    let view = ViewState {
        sort: SortOrder::Alphabetical,
        ..view_selecting(EFIS)
    };
    let names: Vec<String> = ui::ordered_circuits(&m, &view, now)
        .into_iter()
        .map(|c| c.name)
        .collect();
    assert_eq!(
        names,
        [
            "3A-1",
            "Alternator",
            "Beacon",
            "EFIS",
            "Fuel Pump",
            "Landing Lt",
            "Nav Lt",
            "Pitot Heat",
            "Radio",
            "Starter",
            "Strobe Lt",
            "Taxi Lt",
            "Flaps",
            "Trim_P",
            "Trim_R",
        ]
    );
}

#[test]
fn pin_order_keeps_flaps_and_trim_apart() {
    let (m, now) = fixtures::normal();
    let ids: Vec<u8> = ui::ordered_circuits(&m, &ViewState::default(), now)
        .into_iter()
        .map(|c| c.id)
        .collect();
    assert_eq!(
        ids,
        [
            1, 2, 3, 4, 5, 6, 7, 8, 0x11, 0x12, 0x17, 0x1A, FLAPS, TRIM_R, TRIM_P
        ]
    );
}

/// What the page says of the unit it has not heard, or no longer hears, or reads
/// from a file.
#[test]
fn the_link_state_is_said_in_words() {
    for (state, words) in [
        (
            "never_connected",
            &["N O   D A T A   Y E T", "connecting"][..],
        ),
        ("connected_silent", &["nothing heard"]),
        ("port_lost", &["device disconnected", "reopening"]),
    ] {
        let t = plain_text(&drawn(state));
        for w in words {
            assert!(t.contains(w), "{state}: no {w:?} in\n{t}");
        }
    }
}

#[test]
fn replay_is_labelled() {
    for (state, label) in [("replay", "REPLAY"), ("normal_120x40", "SIMULATED")] {
        let buf = drawn(state);
        let (x, y) = find(&buf, label, label);
        assert_eq!(buf[(x, y)].bg, Color::Magenta, "{state}");
    }
}

#[test]
fn notice_is_shown() {
    let t = plain_text(&drawn("notice"));
    assert!(t.contains(REFUSED), "{t}");
}

/// A reset refused, said on the key row.
const REFUSED: &str = "reset refused: EFIS is not faulted";

/// A motor that moved against its command, in the words (`control::against`) as the controller gives them.
const MOVED_AGAINST: &str =
    "pitch trim moved down when asked up: its leads or its sensor may be swapped; stopped";
const MOVED_AGAINST_REFUSED: &str = "pitch trim moved down when asked up: its leads or its \
     sensor may be swapped; let go, then press u again within 3 s to run it up anyway, watching \
     the motor";

/// A notice too long for the key row (a motor stopped for moving against its
/// command, and the refusal that says how to confirm a run) is word-wrapped on rows
/// of its own above the keys, read whole at 80 and 120 columns, never cut.
#[test]
fn a_motor_moving_against_its_command_is_said_whole_above_the_keys() {
    let (m, now) = fixtures::normal();
    for (name, notice, w, h) in [
        ("moved_against_80x24", MOVED_AGAINST, 80, 24),
        ("moved_against_refused_80x24", MOVED_AGAINST_REFUSED, 80, 24),
        (
            "moved_against_refused_120x40",
            MOVED_AGAINST_REFUSED,
            120,
            40,
        ),
    ] {
        let view = ViewState {
            notice: Some(notice.into()),
            ..view_selecting(TRIM_P)
        };
        let t = plain_text(&draw(&m, &view, now, w, h));
        let rows: Vec<&str> = t.lines().collect();
        let last = rows.len() - 1;
        assert!(
            rows[last].contains("select") && rows[last].contains("quit"),
            "{t}"
        );
        let said = rows[..last]
            .iter()
            .rev()
            .take(3)
            .rev()
            .map(|r| r.trim())
            .collect::<Vec<_>>()
            .join(" ");
        assert!(said.contains(notice), "{name}: not whole: {said}");
        insta::assert_snapshot!(name, t);
    }
}

#[test]
fn connection_state_kept_on_the_model() {
    // Guard for the fixtures themselves: the states above are the ones they claim.
    let (m, _) = fixtures::never_connected();
    assert_eq!(m.connection, Connection::Connecting);
    let (m, now) = fixtures::faulted_device();
    assert!(
        m.circuits(now)
            .iter()
            .any(|c| c.state == vpx_efis::model::CircuitState::Fault(FaultCode::ShortCircuit))
    );
}

#[test]
fn short_terminal_scrolls_the_list_to_the_selection_and_says_what_is_hidden() {
    let buf = drawn("short_terminal_scrolled");
    let t = plain_text(&buf);
    assert!(t.contains("▲"), "{t}");
    let (x, y) = find(&buf, "Trim_P", "▶");
    assert_eq!(x, 0);
    assert_eq!(
        Some(buf[(1, y)].bg),
        ui::theme::selected_row().bg,
        "selected row highlighted"
    );
    // Scrolled to the bottom: nothing below, so no ▼.
    assert!(!t.contains("▼"), "{t}");
}

/// The controller's state in the state `name` of [`every_state`]: streaming pitch trim
/// up on a terminal that reports key release in `trim_running`, idle elsewhere.
fn control_of(name: &str) -> ControlState {
    if name != "trim_running" {
        return ControlState::default();
    }
    ControlState {
        run: Some(MotorRun {
            motor: Motor::Trim(TrimKind::Pitch),
            direction: "up",
        }),
        release_mode: ReleaseMode::KeyRelease,
        repeat: None,
    }
}

/// `view`, with the help overlay saying `palette` was asked for.
fn in_theme(view: &ViewState, palette: Palette) -> ViewState {
    ViewState {
        theme: ui::palette::ThemeChoice {
            palette,
            why: ui::palette::Why::Asked,
        },
        ..view.clone()
    }
}

/// Every state in every palette, as a picture of its colours (the text is in the
/// snapshots above and does not change with the palette).
#[test]
fn every_state_in_every_theme() {
    for state in every_state() {
        for palette in themes::PALETTES {
            let buf = state.draw_in(&in_theme(&state.view, palette));
            themes::assert_painted("ui_snapshots", state.name, palette, &buf);
        }
    }
}

#[test]
fn every_state_meets_wcag_contrast_in_both_themes() {
    let mut failures = Vec::new();
    for state in every_state() {
        for palette in [Palette::Dark, Palette::Light] {
            let buf = state.draw_in(&in_theme(&state.view, palette));
            failures.extend(themes::contrast_in(state.name, palette, &buf));
        }
    }
    themes::assert_contrast(failures);
}

/// The colours people see for Appendix A's words in each theme.
#[test]
fn appendix_a_colours_in_each_theme() {
    let (m, now) = fixtures::faulted_device();
    let buf = draw(&m, &view_selecting(4), now, 120, 40);
    let cell = |b: &Buffer, name: &str, state: &str| {
        let (x, y) = find(b, name, name);
        let row: String = (x..b.area.width)
            .map(|x| b[(x, y)].symbol().to_string())
            .collect();
        let dx = row.find(&format!(" {state} ")).unwrap() as u16 + 1;
        b[(x + dx, y)].clone()
    };
    let dark = themes::painted(&buf, Palette::Dark);
    assert_eq!(cell(&dark, "Radio", "ON").fg, Color::Indexed(40), "green");
    assert_eq!(
        cell(&dark, "Beacon", "OFF").fg,
        Color::Indexed(231),
        "white"
    );
    assert_eq!(
        cell(&dark, "EFIS", "SHORT_CIRCUIT").fg,
        Color::Indexed(203),
        "red"
    );
    assert_eq!(
        cell(&dark, "Beacon", "OFF").bg,
        Color::Indexed(16),
        "own black"
    );
    let light = themes::painted(&buf, Palette::Light);
    assert_eq!(cell(&light, "Radio", "ON").fg, Color::Indexed(22));
    assert_eq!(
        cell(&light, "Beacon", "OFF").fg,
        Color::Indexed(234),
        "text colour"
    );
    assert_eq!(
        cell(&light, "EFIS", "SHORT_CIRCUIT").fg,
        Color::Indexed(124)
    );
    assert_eq!(
        cell(&light, "Beacon", "OFF").bg,
        Color::Reset,
        "terminal's own"
    );
    let mono = themes::painted(&buf, Palette::Mono);
    let fault = cell(&mono, "EFIS", "SHORT_CIRCUIT");
    assert_eq!((fault.fg, fault.bg), (Color::Reset, Color::Reset));
    assert!(
        fault.modifier.contains(Modifier::BOLD),
        "faults stand out without colour"
    );
    // The selection (Nav Lt) is in reverse video without colour.
    let (x, y) = find(&mono, "Nav Lt", "Nav Lt");
    assert!(mono[(x, y)].modifier.contains(Modifier::REVERSED));
    let (x, y) = find(&mono, "Beacon", "Beacon");
    assert!(!mono[(x, y)].modifier.contains(Modifier::REVERSED));
}

/// The check itself can fail, and says where: the old page's grey label on a light
/// terminal (1.26:1 in xterm's default colours) is caught and named.
#[test]
fn contrast_check_names_the_cell_the_state_and_both_colours() {
    let mut buf = Buffer::empty(ratatui::layout::Rect::new(0, 0, 6, 2));
    buf.set_string(
        1,
        1,
        "Pin",
        ratatui::style::Style::new().fg(Color::Indexed(250)),
    );
    let failures = themes::contrast_failures("made up", &buf, Palette::Light);
    assert_eq!(failures.len(), 3, "{failures:#?}");
    assert!(
        failures[0].contains("made up")
            && failures[0].contains("(1,1)")
            && failures[0].contains("#bcbcbc on bg #ffffff")
            && failures[0].contains("1.9"),
        "{}",
        failures[0]
    );
    // A colour whose value depends on the terminal's own theme cannot be checked.
    buf.set_string(1, 0, "x", ratatui::style::Style::new().fg(Color::White));
    let failures = themes::contrast_failures("made up", &buf, Palette::Light);
    assert!(failures[0].contains("unknown value"), "{failures:#?}");
}

/// At 200×60 the device list stops at its cap and the right-hand panels take the rest:
/// no name column of blank space, and the flap gauge and plot get the width.
#[test]
fn wide_terminal_gives_its_width_to_the_right_hand_panels() {
    let buf = drawn("wide_200x60");
    let (x, _) = find(&buf, "System", "System");
    assert!(x <= ui::LIST_MAX_WIDTH + 2, "right column starts at {x}");
    let (name_x, _) = find(&buf, "Nav Lt", "Nav Lt");
    let (pin_x, _) = find(&buf, "Nav Lt", "5A-1");
    assert!(pin_x - name_x <= 22, "name column {} wide", pin_x - name_x);
    let (gx, gy) = find(&buf, "Flaps UP", "Flaps UP");
    let track = (gx..200).filter(|&x| buf[(x, gy)].symbol() == "─").count();
    assert!(track > 100, "flap gauge uses the width: {track} cells");
}

/// `--theme terminal` keeps to the terminal's own 16 colours, whose values only the
/// terminal's theme knows. A colour of fixed value would stand on a palette it was not
/// chosen for: the dark band the selection had (index 236) gave about 1.6:1 under
/// xterm's default black on white. The selection is underlined on the terminal's own
/// background instead, each word in its usual colour, legible on any palette.
#[test]
fn terminal_theme_uses_only_the_terminals_own_colours_and_underlines_the_selection() {
    for state in every_state() {
        let (name, w) = (state.name, state.size.0);
        let buf = state.draw_in(&in_theme(&state.view, Palette::Terminal));
        let painted = themes::painted(&buf, Palette::Terminal);
        for (i, cell) in painted.content.iter().enumerate() {
            for c in [cell.fg, cell.bg] {
                assert!(
                    ui::palette::rgb(c).is_none(),
                    "{name}: cell ({},{}) {:?} has {c:?}, a colour of fixed value",
                    i as u16 % w,
                    i as u16 / w,
                    cell.symbol()
                );
            }
        }
    }
    let (m, now) = fixtures::normal();
    let buf = themes::painted(
        &draw(&m, &view_selecting(4), now, 120, 40),
        Palette::Terminal,
    );
    for (text, fg) in [("Nav Lt", Color::Reset), ("ON", Color::Green)] {
        let (x, y) = find(&buf, "Nav Lt", text);
        let cell = &buf[(x + 1, y)];
        assert_eq!((cell.fg, cell.bg), (fg, Color::Reset), "{text}");
        assert!(cell.modifier.contains(Modifier::UNDERLINED), "{text}");
    }
    let (x, y) = find(&buf, "Beacon", "OFF");
    assert_eq!(
        buf[(x, y)].fg,
        Color::White,
        "rows not selected keep their words"
    );
    assert!(!buf[(x, y)].modifier.contains(Modifier::UNDERLINED));
}

/// The overvoltage limit is told from the bus trace without colour: where its label
/// does not fit (80 columns), a red line among the trace's lines said "limit" by
/// colour alone, and under NO_COLOR not at all. It is dashed.
#[test]
fn the_limit_line_is_dashed_so_no_colour_still_tells_it_from_the_trace() {
    let (m, now) = fixtures::normal();
    let buf = themes::painted(&draw(&m, &view_selecting(EFIS), now, 80, 24), Palette::Mono);
    let (bx, by) = find(&buf, "bus V", "bus V");
    assert!(
        !plain_text(&buf).contains("limit"),
        "the label fits here; this test is about where it does not"
    );
    // The chart's first row: the y label, the axis, then the limit (16 V, above the
    // 13-14 V trace).
    let row: Vec<&str> = (bx..80).map(|x| buf[(x, by + 1)].symbol()).collect();
    let axis = row.iter().position(|s| *s == "│").expect("y axis") + 1;
    let line: String = row[axis..axis + 8].concat();
    assert_eq!(line, "⠉ ⠉ ⠉ ⠉ ", "{}", plain_text(&buf));
    // The trace itself stays solid: four dots side by side on a row below the limit
    // (its row depends on the chart's height).
    let (amps_x, _) = find(&buf, "bus V", "amps");
    let solid = |y: u16| {
        let cells: Vec<&str> = (bx..amps_x).map(|x| buf[(x, y)].symbol()).collect();
        cells.windows(4).any(|w| {
            w.iter()
                .all(|c| c.chars().all(|ch| ('\u{2801}'..='\u{28ff}').contains(&ch)))
        })
    };
    assert!(
        (by + 2..buf.area.height).any(solid),
        "no solid trace:\n{}",
        plain_text(&buf)
    );
}

/// The normal page with a link that has seen errors: decoder drops of every kind, many
/// frames sent and failed writes, so the link's words are at their longest.
fn link_with_errors() -> (Model, Instant) {
    let (mut m, now) = fixtures::normal();
    m.note_decoder(vpx_efis::protocol::decoder::DecoderStats {
        frames: 90_000,
        bytes_in: 2_000_000,
        skipped_bytes: 1234,
        bad_checksum: 123,
        bad_length: 45,
        unknown_message: 6,
        truncated_bytes: 0,
    });
    for _ in 0..12_345 {
        m.note_malformed();
    }
    for _ in 0..3 {
        m.note_write_error(now, "Input/output error (os error 5)".into());
    }
    m.link.tx_frames = 123_456;
    (m, now)
}

#[test]
fn normal_100x30() {
    let (m, now) = fixtures::normal();
    insta::assert_snapshot!(plain_text(&draw(&m, &view_selecting(EFIS), now, 100, 30)));
}

#[test]
fn link_errors_80x24_wrap_inside_the_left_column() {
    let (m, now) = link_with_errors();
    insta::assert_snapshot!(plain_text(&draw(&m, &view_selecting(EFIS), now, 80, 24)));
}

/// Every row of the left column (the list, the detail and, on short
/// terminals, the link's lines) ends at the column's edge, whatever the size and the
/// state: walking the drawn buffer, the cell on the edge is a border on every row from
/// the list's top line to the row above the keys.
#[test]
fn no_row_of_the_left_column_crosses_its_edge() {
    let mut states: Vec<State> = every_state()
        .into_iter()
        .filter(|s| s.view.overlay == Overlay::None)
        .collect();
    states.push(State {
        name: "link_with_errors",
        unit: link_with_errors,
        view: view_selecting(EFIS),
        size: (80, 24),
    });
    let sizes = [
        (80, 24),
        (100, 30),
        (81, 25),
        (90, 28),
        (120, 35),
        (120, 40),
        (160, 24),
        (200, 60),
    ];
    let mut walked = 0;
    for State {
        name, unit, view, ..
    } in &states
    {
        let (m, now) = unit();
        for (w, h) in sizes {
            let buf = draw_with(&m, view, &control_of(name), now, w, h);
            let rows: Vec<String> = (0..h)
                .map(|y| (0..w).map(|x| buf[(x, y)].symbol()).collect())
                .collect();
            let top = rows
                .iter()
                .position(|r| r.starts_with(" Devices"))
                .unwrap_or_else(|| panic!("{name} {w}x{h}: no device list\n{}", plain_text(&buf)));
            let edge = ui::left_column_width(w) - 1;
            // The key bar below the columns is one row, or more with a long notice.
            for y in top as u16..h - ui::key_bar::height(view, w) {
                let cell = buf[(edge, y)].symbol();
                assert!(
                    matches!(cell, "│" | "┐" | "┤" | "┘"),
                    "{name} {w}x{h}: row {y} crosses the left column's edge at x={edge} \
                     ({cell:?}):\n{}",
                    plain_text(&buf)
                );
                walked += 1;
            }
        }
    }
    assert!(walked > 1000, "{walked} rows walked");
}

/// The Events panel says what the person did, each line with its origin
/// ("key:", "check:", "setup:", and the network's own "XFSp 0x…"), in the words the
/// page writes (`control::commands::said`), a refusal among them.
#[test]
fn events_panel_lists_the_persons_own_actions_with_their_origin() {
    use vpx_efis::control::Action;
    use vpx_efis::control::commands::said;
    use vpx_efis::model::LogLevel;
    use vpx_efis::protocol::message::{DeviceClear, DevicePower, Message};

    let (mut m, now) = fixtures::normal();
    let at = now - Duration::from_secs(40);
    let off = Message::from(DevicePower {
        device_id: 4,
        on: false,
    });
    let line = said("key", &Action::PowerOff(4), &m, Ok(&off));
    m.log(at, LogLevel::Info, line);
    let line = said(
        "key",
        &Action::Reset(EFIS),
        &m,
        Err("EFIS is not faulted: a reset is for a tripped circuit"),
    );
    m.log(at + Duration::from_secs(5), LogLevel::Warning, line);
    let clear = Message::from(DeviceClear { device_id: 9 });
    let line = said("check", &Action::Reset(9), &m, Ok(&clear));
    m.log(at + Duration::from_secs(10), LogLevel::Info, line);
    m.log(
        at + Duration::from_secs(20),
        LogLevel::Info,
        "check: the installation check started".into(),
    );
    let t = plain_text(&draw(&m, &view_selecting(EFIS), now, 120, 40));
    let name = |id: u8| m.display_name(id).trim().to_string();
    for words in [
        format!("key: {} off (DEVICE_POWER sent)", name(4)),
        format!("key: {} reset refused: EFIS is not", name(EFIS)),
        format!("check: {} reset (DEVICE_CLEAR sent)", name(9)),
        "check: the installation check started".to_string(),
    ] {
        assert!(t.contains(&words), "{words:?} not on the page:\n{t}");
    }
    insta::assert_snapshot!(t);
}

/// A full frame of the page as the bytes crossterm's own writer sends a VT
/// console, the same on every OS: the snapshot is written on Linux and CI checks it
/// for x86_64-pc-windows-gnu under Wine too. The same escape sequences mean the same
/// screen on any VT console, which Windows 10 and later have. Each escape starts a
/// line; `\e` is ESC and `\\` a backslash, so the snapshot is the bytes, readable.
#[test]
fn normal_80x24_bytes_through_crossterm_are_the_same_on_every_os() {
    use ratatui::backend::CrosstermBackend;
    use ratatui::layout::Rect;
    use ratatui::{TerminalOptions, Viewport};
    // On Windows crossterm decides once per process whether the console takes VT
    // sequences (a Windows 10 console does, once crossterm turns its VT mode on), else
    // it calls the console API and writes nothing. Here the output is a Vec, not a
    // console: say it is a VT terminal, as a Windows 10 console is, before any
    // crossterm command runs in this process (only this test writes through it).
    #[cfg(windows)]
    // SAFETY: Windows' environment block is locked by the OS; no other test of this
    // binary reads TERM.
    unsafe {
        std::env::set_var("TERM", "xterm-256color");
    }
    let (m, now) = fixtures::normal();
    let mut bytes = Vec::new();
    {
        let mut terminal = Terminal::with_options(
            CrosstermBackend::new(&mut bytes),
            TerminalOptions {
                viewport: Viewport::Fixed(Rect::new(0, 0, 80, 24)),
            },
        )
        .unwrap();
        terminal
            .draw(|f| ui::render(f, &m, &view_selecting(EFIS), &ControlState::default(), now))
            .unwrap();
    }
    let text = String::from_utf8(bytes).expect("crossterm writes UTF-8");
    assert!(text.contains("EFIS"), "the frame was written: {text:?}");
    let escaped = text.replace('\\', "\\\\").replace('\u{1b}', "\n\\e");
    insta::assert_snapshot!(escaped);
}

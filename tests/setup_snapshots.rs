//! Snapshots of every setup screen, their error states and the confirmation dialogs,
//! rendered into a `TestBackend`; the states whose meaning is their colour (saved in
//! green, refused in red) are also checked cell by cell.

use std::time::{Duration, Instant};

use ratatui::buffer::Buffer;
use ratatui::style::Color;

use vpx_efis::model::{Model, Source};
use vpx_efis::protocol::Packet;
use vpx_efis::protocol::Payload;
use vpx_efis::protocol::device::{EFIS, FIELD_PRI, STARTER};
use vpx_efis::protocol::message::{
    DeviceEnable, DeviceName, DeviceSpec, EnableFlag, FlapTrimStatus, Message, OvervoltageLimit,
    SwitchId, WigWagSpec,
};
mod themes;

mod common;
use common::configured;
use common::screen::text;

use vpx_efis::setup::view::{
    Diagnostic, Dialog, Field, Forms, FromUnit, Held, Page, SetupView, Tone, WriteLine, WriteStatus,
};
use vpx_efis::ui::state::{Screen, ViewState};

fn apply(m: &mut Model, at: Instant, msg: impl Into<Message>) {
    m.apply_packet(at, &Packet::from_vpx(1, msg));
}

/// A unit that answered every connect-time question.
fn unit(t0: Instant) -> Model {
    let mut m = Model::new(Source::Serial {
        path: "/dev/ttyUSB0".into(),
    });
    m.note_connected(t0, "/dev/ttyUSB0".into());
    apply(&mut m, t0, configured::version());
    for id in 1..=28u8 {
        let (cb, sw) = match id {
            STARTER => (5, SwitchId::AlwaysOn),
            EFIS => (5, SwitchId::AlwaysOn),
            FIELD_PRI => (5, SwitchId::Input(1)),
            4 => (3, SwitchId::Input(2)),
            7 | 8 => (2, SwitchId::Input(4)),
            _ => (2, SwitchId::Off),
        };
        apply(
            &mut m,
            t0,
            DeviceSpec {
                device_id: id,
                circuit_breaker: cb,
                switch_id: sw,
                current_fault: id == 4,
                switch_raw: None,
            },
        );
        if (4..=28).contains(&id) {
            apply(
                &mut m,
                t0,
                DeviceEnable {
                    device_id: id,
                    flag: EnableFlag::Enabled,
                },
            );
        }
    }
    for id in 0..=30u8 {
        let name = match id {
            EFIS => "EFIS 1",
            FIELD_PRI => "Alternator",
            4 => "Nav Lt",
            7 => "Landing Lt",
            8 => "Taxi Light",
            _ => "",
        };
        apply(&mut m, t0, DeviceName::new(id, name).unwrap());
    }
    apply(&mut m, t0, configured::system_spec());
    apply(&mut m, t0, configured::flap_spec());
    for spec in configured::trim_specs() {
        apply(&mut m, t0, spec);
    }
    apply(
        &mut m,
        t0,
        WigWagSpec {
            device_one: Some(7),
            device_two: Some(8),
            warm_up_period: 5,
            speed: 70,
        },
    );
    let mut ft = FlapTrimStatus::default();
    ft.flap.enabled = true;
    ft.pitch_trim.enabled = true;
    ft.roll_trim.enabled = true;
    ft.flap_position = 57;
    ft.pitch_trim_position = 131;
    ft.roll_trim_position = 118;
    apply(&mut m, t0, ft);
    m
}

/// The unit of [`unit`] heard at `t0`, and the setup view on `page` for 5A-1 (pin 4).
fn on(page: Page) -> (Model, ViewState, Instant) {
    let t0 = Instant::now();
    let m = unit(t0);
    let v = view(&m, page, 4);
    (m, v, t0)
}

/// The setup view on `page` with every form showing what the unit holds.
fn view(m: &Model, page: Page, device: u8) -> ViewState {
    let held = Held::from_model(m, device);
    let forms = Forms {
        device: held.device.unwrap(),
        name: held.name.unwrap(),
        shown: held.shown.unwrap(),
        system: held.system.unwrap(),
        flap: held.flap.unwrap(),
        pitch: held.pitch.unwrap(),
        roll: held.roll.unwrap(),
        wig_wag: held.wig_wag.unwrap(),
        from_unit: FromUnit::ALL,
    };
    ViewState {
        screen: Screen::Setup,
        setup: SetupView {
            page,
            forms,
            file: "n123ab.toml".into(),
            ..Default::default()
        },
        ..Default::default()
    }
}

fn render(m: &Model, v: &ViewState, now: Instant, w: u16, h: u16) -> Buffer {
    let buf = common::screen::rendered(m, v, now, w, h);
    themes::check_themes("setup_snapshots", &buf);
    buf
}

/// The foreground colour of the first cell of `needle` on screen.
fn fg(buf: &Buffer, needle: &str) -> Color {
    for y in 0..buf.area.height {
        let line: Vec<String> = (0..buf.area.width)
            .map(|x| buf[(x, y)].symbol().to_string())
            .collect();
        let joined: String = line.concat();
        if let Some(byte) = joined.find(needle) {
            let x = joined[..byte].chars().count() as u16;
            return buf[(x, y)].fg;
        }
    }
    panic!("{needle:?} is not on screen:\n{}", text(buf));
}

/// `change` made to the forms of the view's page, not yet sent.
fn edit(v: &mut ViewState, change: impl FnOnce(&mut Forms)) {
    change(&mut v.setup.forms);
    v.setup.edited[v.setup.page.index()] = true;
}

fn select(v: &mut ViewState, field: Field) {
    v.setup.field = v
        .setup
        .page
        .fields()
        .iter()
        .position(|&f| f == field)
        .unwrap();
}

#[test]
fn device_page_80x24() {
    let (m, mut v, t0) = on(Page::Device);
    select(&mut v, Field::Name);
    insta::assert_snapshot!(text(&render(&m, &v, t0, 80, 24)));
}

#[test]
fn device_page_edited_and_refused_by_the_unit_in_red() {
    let (m, mut v, t0) = on(Page::Device);
    edit(&mut v, |f| f.device.circuit_breaker = 9);
    select(&mut v, Field::Breaker);
    v.setup.writes = vec![WriteLine {
        what: "DEVICE_SPEC for 5A-1".into(),
        status: WriteStatus::Refused {
            why: "Invalid circuit breaker value: 9 A is outside 1–5 A for 5A-1 (ICD Table 40); \
                  the unit holds 3 A, switch 2, current fault on"
                .into(),
            by_unit: true,
        },
    }];
    let buf = render(&m, &v, t0, 120, 30);
    insta::assert_snapshot!(text(&buf));
    assert_eq!(fg(&buf, "refused by the unit"), Color::Red);
    assert_eq!(fg(&buf, "9 A"), Color::Yellow, "an unsent edit stands out");
}

#[test]
fn device_page_saved_is_green_sending_is_yellow_no_answer_is_red() {
    let (m, mut v, t0) = on(Page::Device);
    v.setup.writes = vec![
        WriteLine {
            what: "DEVICE_SPEC for 5A-1".into(),
            status: WriteStatus::Saved {
                holds: "3 A, switch 2, current fault on".into(),
                matches: true,
            },
        },
        WriteLine {
            what: "DEVICE_NAME for 5A-1".into(),
            status: WriteStatus::Sending { attempt: 2, of: 3 },
        },
        WriteLine {
            what: "DEVICE_ENABLE for 5A-1".into(),
            status: WriteStatus::Queued,
        },
    ];
    let buf = render(&m, &v, t0, 100, 30);
    insta::assert_snapshot!(text(&buf));
    assert_eq!(fg(&buf, "saved ✓"), Color::Green);
    assert_eq!(fg(&buf, "sending (try 2/3)"), Color::Yellow);
    v.setup.writes[1].status = WriteStatus::NoAnswer;
    v.setup.writes[2].status = WriteStatus::NotSent;
    let buf = render(&m, &v, t0, 100, 30);
    assert_eq!(fg(&buf, "no answer after 3 tries"), Color::Red);
    assert_eq!(fg(&buf, "not sent"), Color::DarkGray);
}

#[test]
fn system_page() {
    let (m, mut v, t0) = on(Page::System);
    edit(&mut v, |f| f.system.secondary_alternator = Some(7));
    v.setup.writes = vec![WriteLine {
        what: "SYSTEM_SPEC".into(),
        status: WriteStatus::Refused {
            why: "Wig-Wag configuration error: 5A-4 (device 7) is a wig-wag device; remove it \
                  from the wig-wag before making it the secondary alternator (ICD Table 14 \
                  note 4)"
                .into(),
            by_unit: false,
        },
    }];
    let buf = render(&m, &v, t0, 100, 26);
    insta::assert_snapshot!(text(&buf));
    assert_eq!(fg(&buf, "refused, not sent"), Color::Red);
}

#[test]
fn flaps_page_with_the_live_position_and_a_capture() {
    let (m, mut v, t0) = on(Page::Flaps);
    edit(&mut v, |f| f.flap.midpoint_1 = 57);
    select(&mut v, Field::FlapMid1);
    v.setup.message = Some((
        Tone::Good,
        "midpoint 1 set to the flaps position 57; Enter sends it".into(),
    ));
    insta::assert_snapshot!(text(&render(
        &m,
        &v,
        t0 + Duration::from_millis(100),
        80,
        24
    )));
}

#[test]
fn pitch_and_roll_trim_pages() {
    let (m, mut v, t0) = on(Page::PitchTrim);
    select(&mut v, Field::TrimNeutral);
    insta::assert_snapshot!("pitch", text(&render(&m, &v, t0, 80, 24)));
    let mut v = view(&m, Page::RollTrim, 4);
    select(&mut v, Field::TrimPower);
    insta::assert_snapshot!("roll", text(&render(&m, &v, t0, 80, 24)));
}

#[test]
fn wig_wag_page() {
    let (m, v, t0) = on(Page::WigWag);
    insta::assert_snapshot!(text(&render(&m, &v, t0, 80, 24)));
}

#[test]
fn diagnostics_page_with_a_ping_time_and_a_silent_version() {
    let (m, mut v, t0) = on(Page::Diagnostics);
    v.setup.ping = Diagnostic::Answered {
        after: Duration::from_micros(12_400),
    };
    insta::assert_snapshot!("answered", text(&render(&m, &v, t0, 80, 24)));
    v.setup.ping = Diagnostic::NoAnswer;
    v.setup.version = Diagnostic::Waiting { attempt: 2, of: 3 };
    let buf = render(&m, &v, t0, 80, 24);
    insta::assert_snapshot!("silent", text(&buf));
    assert_eq!(fg(&buf, "no answer"), Color::Red);
}

#[test]
fn backup_page() {
    let (m, mut v, t0) = on(Page::Backup);
    select(&mut v, Field::File);
    v.setup.message = Some((Tone::Good, "backup written to n123ab.toml".into()));
    insta::assert_snapshot!(text(&render(&m, &v, t0, 80, 24)));
}

#[test]
fn erase_confirmation_names_what_is_lost_and_offers_a_backup() {
    let (m, mut v, t0) = on(Page::Backup);
    v.setup.field = 4;
    v.setup.dialog = Dialog::Erase {
        missing: vec![],
        backed_up: None,
    };
    insta::assert_snapshot!("complete", text(&render(&m, &v, t0, 100, 30)));
    v.setup.dialog = Dialog::Erase {
        missing: vec![
            "FLAP_SPEC".into(),
            "TRIM_SPEC (roll)".into(),
            "DEVICE_NAME 5A-3".into(),
            "DEVICE_NAME 5A-4".into(),
        ],
        backed_up: None,
    };
    insta::assert_snapshot!("incomplete", text(&render(&m, &v, t0, 80, 24)));
}

#[test]
fn load_confirmation_shows_the_differences() {
    let (m, mut v, t0) = on(Page::Backup);
    v.setup.field = 2;
    v.setup.dialog = Dialog::Load {
        file: "n123ab.toml".into(),
        changes: vec![
            "5A-1 (Nav Lt) breaker: 3 A → 4 A".into(),
            "5A-6 name: (no name) → \"GPS 1\"".into(),
            "flaps midpoint 1: 90 → 57".into(),
        ],
        notes: vec!["note: the backup was taken from software 1.3; the unit runs 1.4".into()],
        writes: 3,
    };
    insta::assert_snapshot!(text(&render(&m, &v, t0, 100, 30)));
}

#[test]
fn device_page_refused_by_the_unit_on_a_5a_pin_says_table_20_once_with_1_to_5_a() {
    use vpx_efis::protocol::message::{SpecAck, SpecAckError};
    use vpx_efis::setup::WriteQueue;
    let t0 = Instant::now();
    let mut m = unit(t0);
    let mut v = view(&m, Page::Device, 9);
    let held = m.device_specs[9].unwrap().value;
    // 5 A on 5A-6 (1–5 A): this program's checks accept it, this unit refuses it.
    let sent = DeviceSpec {
        circuit_breaker: 5,
        ..held
    };
    let mut q = WriteQueue::default();
    q.start(vec![sent.into()]);
    q.tick(&mut m, t0);
    let t1 = t0 + Duration::from_millis(20);
    apply(
        &mut m,
        t1,
        SpecAck {
            device_id: 9,
            error: Some(SpecAckError::InvalidBreaker),
        },
    );
    q.tick(&mut m, t1);
    let t2 = t0 + Duration::from_millis(40);
    apply(&mut m, t2, held);
    q.tick(&mut m, t2);
    edit(&mut v, |f| f.device = sent);
    select(&mut v, Field::Breaker);
    v.setup.writes = q.lines();
    let buf = render(&m, &v, t2, 120, 30);
    let screen = text(&buf);
    insta::assert_snapshot!(screen);
    assert_eq!(
        screen.matches("Invalid circuit breaker value").count(),
        1,
        "Table 20's words once:\n{screen}"
    );
    assert!(screen.contains("gives 1–5 A"), "{screen}");
    assert!(!screen.contains("1–10"), "not the flaps' range:\n{screen}");
    assert_eq!(fg(&buf, "refused by the unit"), Color::Red);
}

#[test]
fn a_breaker_left_unknown_shows_a_question_mark_on_the_setup_page_and_in_the_list() {
    use vpx_efis::model::Setting;
    let (mut m, mut v, t0) = on(Page::Device);
    edit(&mut v, |f| f.device.circuit_breaker = 4);
    m.mark_unknown(Setting::DeviceSpec(4), t0);
    v.setup.writes = vec![WriteLine {
        what: "DEVICE_SPEC for 5A-1".into(),
        status: WriteStatus::NoAnswer,
    }];
    let buf = render(&m, &v, t0, 120, 30);
    let screen = text(&buf);
    insta::assert_snapshot!(screen);
    let row = screen
        .lines()
        .find(|l| l.contains("Circuit breaker"))
        .unwrap();
    assert!(row.contains("? A re-reading…"), "{row}");
    assert!(
        !row.contains("3 A"),
        "the value from before the write is gone: {row}"
    );
    assert_eq!(fg(&buf, "? A re-reading…"), Color::Yellow);
    assert_eq!(fg(&buf, "no answer after 3 tries"), Color::Red);
    // The device list's CB column says the same.
    v.screen = Screen::Devices;
    let buf = render(&m, &v, t0, 120, 40);
    let list = text(&buf);
    let row = list.lines().find(|l| l.contains("Nav Lt")).unwrap();
    assert!(row.contains("?A"), "{row}");
    assert!(!row.contains("3A"), "{row}");
}

#[test]
fn a_setting_heard_long_ago_is_shown_with_its_age() {
    let (m, v, t0) = on(Page::System);
    let fresh = text(&render(&m, &v, t0 + Duration::from_secs(60), 120, 30));
    let row = fresh.lines().find(|l| l.contains("Overvoltage")).unwrap();
    assert!(
        !row.contains("ago"),
        "a minute old is the refresh, not old: {row}"
    );
    let later = render(&m, &v, t0 + Duration::from_secs(300), 120, 30);
    let screen = text(&later);
    let row = screen.lines().find(|l| l.contains("Overvoltage")).unwrap();
    assert!(row.contains("(heard 300 s ago)"), "{row}");
    assert_eq!(fg(&later, "(heard 300 s ago)"), Color::DarkGray);
}

/// Connected while the unit was silent: nothing of the pin was heard. No Appendix F
/// value stands in for the unit's: "set to" and "the unit holds" say it is not read,
/// and Enter's refusal says why nothing was sent.
#[test]
fn a_pin_never_heard_since_connect_shows_nothing_as_the_units() {
    let t0 = Instant::now();
    let mut m = Model::new(Source::Serial {
        path: "/dev/ttyUSB0".into(),
    });
    m.note_connected(t0, "/dev/ttyUSB0".into());
    let mut forms = Forms::default();
    vpx_efis::setup::form::select_device(&mut forms, 9, &m);
    let mut v = ViewState {
        screen: Screen::Setup,
        setup: SetupView {
            page: Page::Device,
            forms,
            message: Some((
                Tone::Bad,
                "nothing sent: DEVICE_SPEC for 5A-6 not yet read from the unit — re-reading; \
                 try again when it answers"
                    .into(),
            )),
            ..Default::default()
        },
        ..Default::default()
    };
    select(&mut v, Field::Breaker);
    let buf = render(&m, &v, t0, 120, 24);
    let screen = text(&buf);
    insta::assert_snapshot!(screen);
    assert!(screen.contains("try again when it answers"), "{screen}");
    // Every setting the unit holds for the pin, all but which pin it is.
    for field in &Page::Device.fields()[1..] {
        let row = screen.lines().find(|l| l.contains(field.label())).unwrap();
        assert!(row.contains("? not yet read from the unit"), "{row}");
    }
    let row = screen.lines().find(|l| l.contains("Switch")).unwrap();
    assert!(
        !row.contains("off"),
        "Appendix F's switch is not shown: {row}"
    );
    let row = screen
        .lines()
        .find(|l| l.contains("Circuit breaker"))
        .unwrap();
    assert!(!row.contains("2 A"), "nor its breaker: {row}");
    assert_eq!(fg(&buf, "? not yet read from the unit"), Color::DarkGray);
    assert_eq!(fg(&buf, "DEVICE_SPEC for 5A-6 not yet read"), Color::Red);
}

/// A write that turns a protection off asks first, naming what it turns off: the
/// System page's 32 V on a 14.2 V bus, and the Flaps page's "fitted: no".
#[test]
fn disarm_confirmations_name_the_consequence() {
    use vpx_efis::protocol::message::{SignedTenths, SystemStatus};
    use vpx_efis::setup::form;
    let t0 = Instant::now();
    let mut m = unit(t0);
    let mut st = SystemStatus::parse(&[0u8; 12]).unwrap();
    st.main_bus_volts = SignedTenths(142);
    apply(&mut m, t0, st);
    let mut v = view(&m, Page::System, 4);
    edit(&mut v, |f| {
        f.system.overvoltage_limit = OvervoltageLimit::V32
    });
    let consequences = form::disarms(&[v.setup.forms.system.into()], &m, t0);
    v.setup.dialog = Dialog::Disarm { consequences };
    insta::assert_snapshot!("overvoltage_100x30", text(&render(&m, &v, t0, 100, 30)));
    insta::assert_snapshot!("overvoltage_80x24", text(&render(&m, &v, t0, 80, 24)));
    let mut v = view(&m, Page::Flaps, 4);
    edit(&mut v, |f| f.flap.enabled = false);
    let consequences = form::disarms(&[v.setup.forms.flap.into()], &m, t0);
    v.setup.dialog = Dialog::Disarm { consequences };
    insta::assert_snapshot!("flaps_80x24", text(&render(&m, &v, t0, 80, 24)));
}

/// A digit on the Switch field is refused in words, and the footer offers no typing
/// there; a typed name that is too long says which character was not taken.
#[test]
fn typing_refused_in_words() {
    use std::time::SystemTime;
    use vpx_efis::setup::flow::{SetupFlow, SetupKey};
    let wall = SystemTime::UNIX_EPOCH;
    let (mut m, mut v, t0) = on(Page::Device);
    let mut flow = SetupFlow::default();
    flow.tick(&mut v.setup, true, Some(4), &mut m, t0);
    select(&mut v, Field::Switch);
    flow.key(SetupKey::Char('3'), &mut v.setup, &mut m, t0, wall);
    insta::assert_snapshot!("switch_digit", text(&render(&m, &v, t0, 80, 24)));
    select(&mut v, Field::Name);
    for c in " and Strobe!".chars() {
        flow.key(SetupKey::Char(c), &mut v.setup, &mut m, t0, wall);
    }
    insta::assert_snapshot!("name_too_long", text(&render(&m, &v, t0, 80, 24)));
}

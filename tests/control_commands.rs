//! Commands are refused, in words, where the ICD says the unit will not honour them or
//! the page could not show their effect; otherwise the exact message goes out.

use std::time::{Duration, Instant};

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
#[path = "common/events.rs"]
#[allow(dead_code)]
mod events;
#[path = "common/selection.rs"]
mod selection;
use selection::selected;

use vpx_efis::control::{Action, Controller, command};
use vpx_efis::model::{CircuitKind, CircuitState, Model, Source, TrimKind};
use vpx_efis::protocol::device::{EFIS, FLAPS, STARTER, TRIM_P, TRIM_R};
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::protocol::message::{
    DeviceClear, DevicePower, DeviceStatus, FaultStatus, FlapTrimStatus, Message, MiscFlags,
    Packet, Payload, SignedTenths, SystemStatus, Tenths, WigWagMode, WigWagModeSetting,
};

fn status(wig_wag: WigWagModeSetting) -> (Packet, Packet) {
    let s = SystemStatus {
        system_current: Tenths(100),
        main_bus_volts: SignedTenths(138),
        internal_temp: 30,
        misc: MiscFlags {
            wig_wag_mode: wig_wag,
            ..Default::default()
        },
        ..Default::default()
    };
    let mut d = DeviceStatus::default();
    d.on[EFIS as usize] = true;
    (Packet::from_vpx(0, s), Packet::from_vpx(0, d))
}

fn model(at: Instant, faults: &[(u8, FaultCode)], system_fault: bool) -> Model {
    let mut m = Model::new(Source::Simulated {
        scenario: "test".into(),
    });
    let (s, d) = status(WigWagModeSetting::Auto);
    m.apply_packet(at, &s);
    m.apply_packet(at, &d);
    if !faults.is_empty() || system_fault {
        m.apply_packet(at, &fault_status(faults, system_fault));
    }
    m
}

/// FAULT_STATUS with `faults` and the system fault flag.
fn fault_status(faults: &[(u8, FaultCode)], system_fault: bool) -> Packet {
    let f = FaultStatus {
        system_fault,
        ..FaultStatus::with_faults(faults)
    };
    Packet::from_vpx(0, f)
}

fn refused(action: Action, m: &Model, now: Instant) -> String {
    match command(&action, m, now) {
        Err(r) => r.words,
        Ok(msg) => panic!("{action:?} was sent as {msg:?}"),
    }
}

#[test]
fn the_starter_can_never_be_switched_only_reset() {
    let t0 = Instant::now();
    let m = model(t0, &[], false);
    for a in [Action::PowerOn(STARTER), Action::PowerOff(STARTER)] {
        assert!(refused(a, &m, t0).contains("only reset"));
    }
    let faulted = model(t0, &[(STARTER, FaultCode::OverCurrent)], false);
    assert_eq!(
        command(&Action::Reset(STARTER), &faulted, t0),
        Ok(Message::DeviceClear(DeviceClear { device_id: STARTER }))
    );
}

#[test]
fn power_commands_go_out_for_ordinary_devices() {
    let t0 = Instant::now();
    let m = model(t0, &[], false);
    assert_eq!(
        command(&Action::PowerOn(7), &m, t0),
        Ok(Message::DevicePower(DevicePower {
            device_id: 7,
            on: true
        }))
    );
    assert_eq!(
        command(&Action::PowerOff(EFIS), &m, t0),
        Ok(Message::DevicePower(DevicePower {
            device_id: EFIS,
            on: false
        }))
    );
}

/// `m` with FLAP_TRIM_STATUS saying every motor is enabled, which puts their rows on
/// the page.
fn with_motors(mut m: Model, at: Instant) -> Model {
    let mut payload = [0u8; 18];
    payload[0] = 0x80;
    payload[1] = 0x90;
    let ft = FlapTrimStatus::parse(&payload).unwrap();
    m.apply_packet(at, &Packet::from_vpx(0, ft));
    m
}

#[test]
fn flaps_and_trims_are_not_switched_with_device_power() {
    let t0 = Instant::now();
    let m = with_motors(model(t0, &[], false), t0);
    for id in [FLAPS, TRIM_P, TRIM_R] {
        assert!(
            m.is_shown(id, t0),
            "{id} must be on the page for this test to mean anything"
        );
        for a in [Action::PowerOn(id), Action::PowerOff(id)] {
            let why = refused(a, &m, t0);
            assert!(why.contains("is a motor: it is run up or down"), "{why}");
            assert!(!why.contains("key"), "it reaches the phone too: {why}");
        }
    }
}

/// What DEVICE_POWER never switches is one rule with one reason: switching it on or
/// off and the check putting it back are refused alike, in the same words, and the
/// phone offers no switch for it. A device that is no circuit says so with its own
/// reason, even while communication is lost (the remote answers it "no device").
#[test]
fn the_starter_and_the_motors_are_refused_by_one_rule_with_its_reason() {
    use vpx_efis::control::commands::{Reason, Unswitched};
    use vpx_efis::control::{put_back_off, switchable};
    let t0 = Instant::now();
    let m = with_motors(model(t0, &[], false), t0);
    for (id, what) in [
        (STARTER, Unswitched::Starter),
        (FLAPS, Unswitched::Motor),
        (TRIM_P, Unswitched::Motor),
        (TRIM_R, Unswitched::Motor),
    ] {
        let on = command(&Action::PowerOn(id), &m, t0).unwrap_err();
        assert_eq!(on.reason, Reason::NeverSwitched(what), "{id}: {on}");
        assert_eq!(command(&Action::PowerOff(id), &m, t0), Err(on.clone()));
        assert_eq!(put_back_off(&m, id), Err(on), "the check's put-back, {id}");
        assert!(!switchable(id));
    }
    assert!(switchable(EFIS) && switchable(7));
    let later = t0 + Duration::from_millis(2600);
    for (id, reason) in [(40, Reason::NoSuchDevice), (7, Reason::CommLost)] {
        for a in [Action::PowerOn(id), Action::Reset(id)] {
            let why = command(&a, &m, later).unwrap_err();
            assert_eq!(why.reason, reason, "{a:?}: {why}");
        }
    }
}

#[test]
fn reset_is_refused_unless_the_device_is_faulted() {
    let t0 = Instant::now();
    let m = model(t0, &[], false);
    assert!(refused(Action::Reset(7), &m, t0).contains("no fault"));
    let m = model(t0, &[(7, FaultCode::ShortCircuit)], false);
    assert_eq!(
        command(&Action::Reset(7), &m, t0),
        Ok(Message::DeviceClear(DeviceClear { device_id: 7 }))
    );
    // A faulted device is not switched on over its fault.
    assert!(refused(Action::PowerOn(7), &m, t0).contains("reset it"));
}

#[test]
fn the_system_fault_reset_is_refused_unless_it_is_set() {
    let t0 = Instant::now();
    let m = model(t0, &[], false);
    assert!(refused(Action::ResetSystemFault, &m, t0).contains("no system fault"));
    let m = model(t0, &[], true);
    assert_eq!(
        command(&Action::ResetSystemFault, &m, t0),
        Ok(Message::DeviceClear(DeviceClear { device_id: 255 }))
    );
}

#[test]
fn nothing_is_sent_while_communication_is_lost() {
    let t0 = Instant::now();
    let m = model(t0, &[(7, FaultCode::ShortCircuit)], true);
    let later = t0 + Duration::from_millis(2600);
    for a in [
        Action::PowerOn(EFIS),
        Action::PowerOff(EFIS),
        Action::Reset(7),
        Action::ResetSystemFault,
        Action::ToggleWigWag,
    ] {
        assert!(refused(a, &m, later).contains("COMMUNICATION LOST"));
    }
}

#[test]
fn wig_wag_toggles_from_the_live_mode() {
    let t0 = Instant::now();
    let mut m = model(t0, &[], false);
    assert_eq!(
        command(&Action::ToggleWigWag, &m, t0),
        Ok(Message::WigWagMode(WigWagMode {
            mode: WigWagModeSetting::Steady
        }))
    );
    let (s, _) = status(WigWagModeSetting::Steady);
    m.apply_packet(t0, &s);
    assert_eq!(
        command(&Action::ToggleWigWag, &m, t0),
        Ok(Message::WigWagMode(WigWagMode {
            mode: WigWagModeSetting::Auto
        }))
    );
}

#[test]
fn the_controller_sends_commands_and_shows_refusals() {
    let t0 = Instant::now();
    let m = model(t0, &[], false);
    let mut ctl = Controller::default();
    let ctx = |id, kind| selected(id, kind, CircuitState::Off);
    let o = ctl.handle_key(
        KeyEvent::new(KeyCode::Char('o'), KeyModifiers::NONE),
        &ctx(7, CircuitKind::Device),
        &m,
        t0,
    );
    assert_eq!(o.packets.len(), 1);
    assert_eq!(
        o.packets[0],
        Packet::request(
            o.packets[0].cnt,
            DevicePower {
                device_id: 7,
                on: true
            }
        )
    );
    let o = ctl.handle_key(
        KeyEvent::new(KeyCode::Char('f'), KeyModifiers::NONE),
        &ctx(STARTER, CircuitKind::Starter),
        &m,
        t0,
    );
    assert!(o.packets.is_empty());
    assert!(o.notice.unwrap().contains("starter"));
    let o = ctl.handle_key(
        KeyEvent::new(KeyCode::Char('u'), KeyModifiers::NONE),
        &ctx(7, CircuitKind::Device),
        &m,
        t0,
    );
    assert!(o.packets.is_empty());
    assert!(o.notice.unwrap().contains("flaps or trim row"));
    // Navigation on a trim row moves the selection and sends nothing.
    let o = ctl.handle_key(
        KeyEvent::new(KeyCode::Down, KeyModifiers::NONE),
        &ctx(TRIM_P, CircuitKind::Trim(TrimKind::Pitch)),
        &m,
        t0,
    );
    assert!(o.packets.is_empty());
    assert_eq!(o.action, Some(Action::SelectNext));
}

/// AC 43.13-1B's breaker practice on a fake clock: the first fault is reset with `r`;
/// when the circuit faults again after it, the second `r` sends nothing and says why,
/// and only `Y` right after sends the reset. The log holds both resets.
#[test]
fn a_circuit_that_faults_again_after_a_reset_needs_a_confirmed_second_reset() {
    const LANDING: u8 = 17;
    let t0 = Instant::now();
    let s = |n: u64| t0 + Duration::from_millis(n);
    let mut m = model(t0, &[], false);
    m.apply_packet(
        t0,
        &Packet::from_vpx(
            0,
            vpx_efis::protocol::message::DeviceName::new(LANDING, "Landing Lt").unwrap(),
        ),
    );
    let mut ctl = Controller::default();
    let short = CircuitState::Fault(FaultCode::ShortCircuit);
    let ctx = selected(LANDING, CircuitKind::Device, short);
    let key = |c| KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE);
    let shift_y = KeyEvent::new(KeyCode::Char('Y'), KeyModifiers::SHIFT);
    let clear = |o: &vpx_efis::control::Handled| {
        o.packets
            .iter()
            .filter(|p| p.message == Message::DeviceClear(DeviceClear { device_id: LANDING }))
            .count()
    };
    // A status every second, the fault with it.
    let heard = |m: &mut Model, at: Instant| {
        let (st, d) = status(WigWagModeSetting::Auto);
        m.apply_packet(at, &st);
        m.apply_packet(at, &d);
        m.apply_packet(
            at,
            &fault_status(&[(LANDING, FaultCode::ShortCircuit)], false),
        );
    };

    // The first fault: `r` resets it.
    heard(&mut m, s(1000));
    let o = ctl.handle_key(key('r'), &ctx, &m, s(1100));
    assert_eq!(clear(&o), 1, "the first reset goes out");
    for p in &o.packets {
        m.note_sent(s(1100), p);
    }
    // A FAULT_STATUS already on its way when the reset went out is not a second fault.
    heard(&mut m, s(1150));
    assert!(!m.faulted_again_after_reset(LANDING, s(1150)));
    // The next one shows it faulted again.
    heard(&mut m, s(2000));
    assert!(m.faulted_again_after_reset(LANDING, s(2000)));

    // The second `r` sends nothing and says why, naming the key that confirms.
    let o = ctl.handle_key(key('r'), &ctx, &m, s(2100));
    assert_eq!(o.packets, vec![]);
    assert_eq!(
        o.notice.as_deref(),
        Some(
            "Landing Lt faulted again after a reset: find the cause before resetting it \
             again (Y: reset it anyway)"
        )
    );
    // Another key in between: `Y` no longer confirms.
    let o = ctl.handle_key(key('w'), &ctx, &m, s(2200));
    assert_eq!(clear(&o), 0);
    let o = ctl.handle_key(shift_y, &ctx, &m, s(2300));
    assert_eq!(clear(&o), 0);
    assert_eq!(
        o.notice.as_deref(),
        Some(vpx_efis::control::NOTHING_TO_CONFIRM)
    );
    // Nor does a `Y` after the confirmation window.
    ctl.handle_key(key('r'), &ctx, &m, s(2400));
    let late = s(2400) + vpx_efis::control::CONFIRM_RESET_WITHIN + Duration::from_millis(1);
    // The unit talks all along (a silence would forget its names: a re-read).
    let mut at = s(3000);
    while at < late {
        heard(&mut m, at);
        at += Duration::from_secs(1);
    }
    assert_eq!(clear(&ctl.handle_key(shift_y, &ctx, &m, late)), 0);
    // `r` then `Y`: the deliberate second reset goes out.
    let t = late + Duration::from_millis(100);
    heard(&mut m, t);
    assert_eq!(clear(&ctl.handle_key(key('r'), &ctx, &m, t)), 0);
    let o = ctl.handle_key(shift_y, &ctx, &m, t + Duration::from_millis(500));
    assert_eq!(clear(&o), 1, "Y right after r sends the reset");
    for p in &o.packets {
        m.note_sent(t + Duration::from_millis(500), p);
    }
    // Both resets are in the event log.
    assert_eq!(
        events::containing(&m, "reset sent"),
        [
            "Landing Lt: reset sent (DEVICE_CLEAR), the 1st this session",
            "Landing Lt: reset sent after it faulted again (DEVICE_CLEAR), the 2nd this session"
        ]
    );
    // The same rule for anything else that resets (a remote) and for switching the
    // circuit on (the installation check): the words, never "reset it first".
    let t = t + Duration::from_secs(1);
    heard(&mut m, t);
    let why = refused(Action::Reset(LANDING), &m, t);
    assert_eq!(
        why,
        "Landing Lt faulted again after a reset: find the cause before resetting it again"
    );
    assert_eq!(refused(Action::PowerOn(LANDING), &m, t), why);
    assert_eq!(
        vpx_efis::control::device_power(&m, t, LANDING, true),
        Err(vpx_efis::control::Refusal {
            reason: vpx_efis::control::commands::Reason::FaultedAgain,
            words: why
        })
    );
}

/// A circuit's refusals reach the phone and the network as well as
/// the page, so they name no key: a faulted circuit is to be reset first (a motor's
/// words: `flaps_and_trims_are_not_switched_with_device_power`).
#[test]
fn a_circuit_refusal_names_no_key() {
    let t0 = Instant::now();
    let m = model(t0, &[(7, FaultCode::OverCurrent)], false);
    let faulted = refused(Action::PowerOn(7), &m, t0);
    assert!(faulted.ends_with("reset it first"), "{faulted}");
    assert!(
        !faulted.contains(" r ") && !faulted.contains("key"),
        "{faulted}"
    );
}

/// A reset the unit has not yet answered: a second `r` sends nothing and says why
/// (it would count as a reset of a circuit that may have no fault left), nor does
/// `o` switch it on. Once DEVICE_STATUS shows it on, the reset is answered.
#[test]
fn a_second_reset_before_the_unit_answers_the_first_sends_nothing_and_says_why() {
    const LANDING: u8 = 17;
    let t0 = Instant::now();
    let s = |n: u64| t0 + Duration::from_millis(n);
    let mut m = model(t0, &[(LANDING, FaultCode::ShortCircuit)], false);
    m.apply_packet(
        t0,
        &Packet::from_vpx(
            0,
            vpx_efis::protocol::message::DeviceName::new(LANDING, "Landing Lt").unwrap(),
        ),
    );
    let reset = Action::Reset(LANDING);
    let first = command(&reset, &m, s(100)).expect("the first reset goes out");
    assert_eq!(
        first,
        Message::DeviceClear(DeviceClear { device_id: LANDING })
    );
    m.note_sent(s(100), &Packet::request(1, first));
    assert_eq!(
        refused(reset.clone(), &m, s(600)),
        "Landing Lt: a reset was sent 0.5 s ago and the unit has not yet said whether \
         SHORT_CIRCUIT cleared; nothing more is sent until it does (its next broadcast)"
    );
    assert!(refused(Action::PowerOn(LANDING), &m, s(600)).contains("a reset was sent"));
    // Its switch is on: the unit's next DEVICE_STATUS shows it on. Answered.
    let (st, mut d) = status(WigWagModeSetting::Auto);
    if let Message::DeviceStatus(ds) = &mut d.message {
        ds.on[LANDING as usize] = true;
    }
    m.apply_packet(s(1000), &st);
    m.apply_packet(s(1000), &d);
    assert_eq!(
        refused(reset, &m, s(1000)),
        "Landing Lt has no fault to reset"
    );
}

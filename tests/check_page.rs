//! The installation check on the page itself. The page writes the check's report
//! when the page ends mid-check, as the headless check does: Ctrl-C on the check
//! screen, and a signal reaching the page's own loop (`App::run`). A page the person
//! cannot see (too small, unfocused) switches nothing on. The real `App` on the slave
//! of a real pseudo-terminal, the virtual VP-X (`install` scenario) on its master;
//! the report read back from disk.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crossbeam_channel::unbounded;
use crossterm::event::{Event, KeyCode, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use vpx_efis::app::{App, AppOptions, Flow, Terminated, Termination};
use vpx_efis::check::state::Step;
use vpx_efis::check::{Options, Timing};
use vpx_efis::sim::{self, SimOptions};

mod common;
use common::rig::{PtyUnit, Rig, one_at_a_time};

impl Rig {
    /// A page on the install scenario with a check running: switches skipped,
    /// confirmed, and the first circuit switched on under test.
    fn mid_circuit() -> Rig {
        Rig::at_circuit(false)
    }

    /// As [`Rig::mid_circuit`], its lights held on for "Is it lit?" (elsewhere here
    /// nobody looks at them, and none is held).
    fn mid_light() -> Rig {
        Rig::starting(false, Timing::default())
    }

    /// As [`Rig::mid_circuit`], on a circuit that was `on_already` (its switch on,
    /// measured as it is, nothing sent) or one the check itself switched on.
    fn at_circuit(on_already: bool) -> Rig {
        let timing = Timing {
            lit_for: Duration::ZERO,
            ..Timing::default()
        };
        Rig::starting(on_already, timing)
    }

    fn starting(on_already: bool, timing: Timing) -> Rig {
        let mut r = Rig::alone(
            SimOptions::new(sim::load_scenario("install").unwrap()),
            AppOptions::default(),
        );
        r.until("the unit's settings", Duration::from_secs(20), |app| {
            vpx_efis::check::plan::ready(&app.model(), Instant::now()).is_ok()
        });
        let options = Options {
            skip: vec![Step::Switches],
            loads_file: Some(r.dir.path().join("loads.toml")),
            timing,
            ..Options::default()
        };
        r.app
            .set_check_report_dir(Some(r.dir.path().join("reports")));
        // A circuit on already (its switch on) is measured as it is; the one wanted
        // here is one the check itself switches on.
        let on_before = r.app.model().live_devices(Instant::now()).unwrap().on;
        r.app.open_check(options, Instant::now());
        r.key_with(KeyCode::Enter, KeyModifiers::NONE);
        r.until(
            "a circuit switched on by the check, or one on already",
            Duration::from_secs(30),
            move |app| {
                let v = app.check_view();
                let on = app.model().live_devices(Instant::now()).map(|d| d.on);
                v.step == Step::Circuits
                    && v.current.and_then(|i| v.circuits.get(i)).is_some_and(|c| {
                        let id = usize::from(c.id);
                        on_before[id] == on_already && on.is_some_and(|on| on[id])
                    })
            },
        );
        r
    }

    fn reports(&self) -> PathBuf {
        self.dir.path().join("reports")
    }

    /// The circuit under test when the check stopped.
    fn under_test(&self) -> String {
        let v = self.app.check_view();
        v.circuits[v.current.expect("an item under test")]
            .name
            .clone()
    }
}

fn prompt(app: &App) -> String {
    app.check_view()
        .prompt
        .as_ref()
        .map_or(String::new(), |p| p.todo.clone())
}

/// The terminal made too small mid-circuit: the circuit on is put back, and the next
/// is not switched on, through the page hidden and then unfocused, until the page is
/// seen again and the person says to go on (r).
#[test]
fn a_page_that_cannot_be_seen_switches_no_further_circuit_on() {
    let mut r = Rig::mid_circuit();
    let first = r.app.check_view().current.unwrap();
    r.app
        .handle_term_event(Event::Resize(30, 8), Instant::now());
    r.until("the next circuit to wait", Duration::from_secs(20), |app| {
        prompt(app).starts_with("Paused before switching")
    });
    let v = r.app.check_view();
    let waiting = v.current.unwrap();
    assert_eq!(waiting, first + 1, "{:?}", v.prompt);
    let id = usize::from(v.circuits[waiting].id);
    let sent = r.sent("DEVICE_POWER");
    let quiet = |r: &mut Rig, what: &str| {
        let end = Instant::now() + Duration::from_millis(2500);
        r.until(what, Duration::from_secs(5), |_| Instant::now() >= end);
        assert_eq!(
            r.sent("DEVICE_POWER"),
            sent,
            "{what}: a DEVICE_POWER went out"
        );
        let on = r.app.model().live_devices(Instant::now()).unwrap().on;
        assert!(!on[id], "{what}: device {id} on");
    };
    quiet(&mut r, "hidden");
    // Seen again, but unfocused: an r (the terminal would not send it; here it does)
    // does not go on either.
    r.app
        .handle_term_event(Event::Resize(120, 40), Instant::now());
    r.app.handle_term_event(Event::FocusLost, Instant::now());
    r.key_with(KeyCode::Char('r'), KeyModifiers::NONE);
    quiet(&mut r, "unfocused");
    assert!(
        prompt(&r.app).contains("the terminal lost focus"),
        "{}",
        prompt(&r.app)
    );
    r.app.handle_term_event(Event::FocusGained, Instant::now());
    quiet(&mut r, "focused, not asked yet");
    r.key_with(KeyCode::Char('r'), KeyModifiers::NONE);
    r.until("the circuit switched on", Duration::from_secs(5), |app| {
        app.model()
            .live_devices(Instant::now())
            .is_some_and(|d| d.on[id])
    });
    assert_eq!(r.sent("DEVICE_POWER"), sent + 1);
    r.key_with(KeyCode::Esc, KeyModifiers::NONE);
    r.until("the check to end", Duration::from_secs(20), |app| {
        app.check_finished()
    });
    r.sim.stop();
}

/// The Markdown report in `dir`, the only one there, with its CSV beside it.
fn the_report(dir: &Path) -> String {
    let names = common::files::names_in(dir);
    assert_eq!(names.len(), 2, "{names:?}");
    assert!(
        names[0].starts_with("vpx-check-") && names[0].ends_with(".csv"),
        "{names:?}"
    );
    assert_eq!(names[1], names[0].replace(".csv", ".md"));
    std::fs::read_to_string(dir.join(&names[1])).unwrap()
}

/// What every report of a check stopped mid-circuit must say.
fn says_incomplete_and_what_was_left(md: &str, cause: &str, circuit: &str) {
    let after = common::report::interrupted(md, cause);
    // The page could not wait to see the circuit off: it says it sent the off and
    // that it was not confirmed, naming the circuit.
    assert!(
        after.contains(&format!("| {circuit} |"))
            && after.contains("DEVICE_POWER off sent, not confirmed"),
        "{after}"
    );
    assert!(
        md.contains("not run: the check stopped before it"),
        "the circuits after it are not run: {md}"
    );
    assert!(
        !md.contains("It left every circuit as it found it."),
        "{md}"
    );
}

#[test]
fn ctrl_c_on_the_check_screen_writes_an_incomplete_report_before_the_page_quits() {
    let mut r = Rig::mid_circuit();
    let circuit = r.under_test();
    assert!(!r.reports().exists(), "no report before the check ends");
    assert_eq!(
        r.key_with(KeyCode::Char('c'), KeyModifiers::CONTROL),
        Flow::Quit
    );
    let md = the_report(&r.reports());
    says_incomplete_and_what_was_left(&md, "stopped by you", &circuit);
    // The step bar stays where it stopped.
    assert_eq!(r.app.check_view().step, Step::Circuits);
    r.sim.stop();
}

/// Esc while the page is "measuring it as it is" (a circuit on already, nothing
/// sent): the check ends at once, and its report is written, marked INCOMPLETE.
#[test]
fn esc_while_a_circuit_is_measured_as_it_is_writes_an_incomplete_report() {
    let mut r = Rig::at_circuit(true);
    let circuit = r.under_test();
    assert!(!r.reports().exists(), "no report before the check ends");
    r.key_with(KeyCode::Esc, KeyModifiers::NONE);
    assert!(r.app.check_finished(), "nothing to put back: ended at once");
    let md = the_report(&r.reports());
    assert!(
        md.contains("**Result: INCOMPLETE.** The check was interrupted (stopped by you)"),
        "{md}"
    );
    assert!(md.contains(&format!("| {circuit} |")), "{md}");
    let v = r.app.check_view();
    assert!(v.report.is_some() && v.report_error.is_none());
    r.sim.stop();
}

#[test]
fn a_signal_to_the_page_writes_an_incomplete_report() {
    let mut r = Rig::mid_circuit();
    let circuit = r.under_test();
    let mut terminal = Terminal::new(TestBackend::new(100, 30)).unwrap();
    let (_keys_tx, keys) = unbounded();
    let (signal_tx, signals) = unbounded();
    signal_tx.send(Termination::Terminate).unwrap();
    let err = r
        .app
        .run(&mut terminal, &keys, &signals)
        .expect_err("a signal ends the page");
    assert!(
        matches!(
            err.downcast_ref::<Terminated>(),
            Some(Terminated(Termination::Terminate))
        ),
        "{err}"
    );
    let md = the_report(&r.reports());
    says_incomplete_and_what_was_left(&md, "ended by a signal (SIGTERM)", &circuit);
    r.sim.stop();
}

/// The report folder cannot be written when the check ends (here a file stands where
/// the folder must go; a USB stick pulled or a folder made read-only fail the same
/// way): the page says why and keeps the results; Esc once warns instead of leaving;
/// `w` writes it again once the folder is there, without leaving the screen.
#[test]
fn a_report_that_cannot_be_written_is_said_and_written_again_with_w() {
    let mut r = Rig::mid_circuit();
    let blocked = r.dir.path().join("usb");
    std::fs::write(&blocked, "a file where the folder must go").unwrap();
    let folder = blocked.join("reports");
    r.app.set_check_report_dir(Some(folder.clone()));
    r.key_with(KeyCode::Esc, KeyModifiers::NONE);
    r.until("the check to end", Duration::from_secs(20), |app| {
        app.check_finished()
    });
    let why = r
        .app
        .check_report_error()
        .expect("the write failed")
        .to_string();
    assert!(why.starts_with(&folder.display().to_string()), "{why}");
    let v = r.app.check_view();
    assert_eq!(v.report, None);
    assert!(
        v.message.as_deref().unwrap().contains("w writes it again"),
        "{:?}",
        v.message
    );
    assert!(
        vpx_efis::ui::check::keys::keys(v).contains(&("w", "write the report again")),
        "{:?}",
        vpx_efis::ui::check::keys::keys(v)
    );
    // Esc once: not left, the results would go with the screen.
    r.key_with(KeyCode::Esc, KeyModifiers::NONE);
    assert_eq!(r.app.view().screen, vpx_efis::ui::state::Screen::Check);
    assert!(
        r.app
            .check_view()
            .message
            .as_deref()
            .unwrap()
            .contains("Esc again leaves"),
        "{:?}",
        r.app.check_view().message
    );
    // The stick is back: `w` writes the same report, complete with what it left.
    std::fs::remove_file(&blocked).unwrap();
    r.key_with(KeyCode::Char('w'), KeyModifiers::NONE);
    assert_eq!(r.app.check_report_error(), None);
    let md = the_report(&folder);
    assert!(md.contains("**Result: INCOMPLETE.**"), "{md}");
    assert_eq!(
        r.app
            .check_view()
            .report
            .as_deref()
            .map(|p| p.parent().unwrap()),
        Some(folder.as_path())
    );
    // Written once: `w` again writes no second copy.
    r.key_with(KeyCode::Char('w'), KeyModifiers::NONE);
    assert_eq!(std::fs::read_dir(&folder).unwrap().count(), 2);
    r.sim.stop();
}

/// Headless, a report that cannot be written at the end is an error of the run: the
/// folder and the reason said, exit non-zero (1), after the summary was printed.
#[test]
fn headless_a_report_that_cannot_be_written_is_an_error_naming_the_folder() {
    let _turn = one_at_a_time();
    let unit = PtyUnit::start(SimOptions::new(sim::load_scenario("install").unwrap()));
    let blocked = unit.dir.path().join("usb");
    std::fs::write(&blocked, "a file where the folder must go").unwrap();
    let h = vpx_efis::app::HeadlessCheck {
        port: Some(unit.path.parse().unwrap()),
        baud: 57_600,
        scenario: "install".into(),
        options: Options {
            skip: vec![Step::Switches, Step::Circuits, Step::Motors, Step::Loads],
            yes: true,
            ..Options::default()
        },
        report: Some(blocked.join("reports")),
    };
    let (_tx, lines) = unbounded();
    let (_ttx, terminations) = unbounded();
    let mut out = Vec::new();
    let err = vpx_efis::app::run_headless_with(h, &lines, &terminations, &mut out)
        .expect_err("the report was not written");
    let text = String::from_utf8(out).unwrap();
    let e = format!("{err:#}");
    assert!(
        e.starts_with(&format!(
            "the report could not be written to {}: ",
            blocked.join("reports").display()
        )),
        "{e}"
    );
    assert!(err.downcast_ref::<vpx_efis::cmd::check::Ended>().is_none());
    assert!(
        text.contains("✗ The report could not be written to"),
        "{text}"
    );
    assert!(text.contains("Summary: "), "{text}");
    unit.sim.stop();
}

/// "Is it lit?" on the page: the light the check switched on stays on past its
/// measurement, the screen asking with the time left, until the person answers `y`;
/// then it goes back off, and the report says it went off at the answer.
#[test]
fn a_light_is_held_on_until_the_person_answers_on_the_page() {
    let mut r = Rig::mid_light();
    let name = r.under_test();
    assert_eq!(name, "Nav Lt", "the install scenario's first light");
    r.until("Nav Lt measured and held", Duration::from_secs(10), |app| {
        prompt(app).contains("is on and measured")
    });
    let held_from = Instant::now();
    // Past the 5 s a circuit was kept on before, it is still on, and still asked.
    while held_from.elapsed() < Duration::from_secs(6) {
        r.app.pump_until(Instant::now() + Duration::from_millis(50));
        assert!(r.sim.stats().powered[4], "Nav Lt switched off unanswered");
    }
    let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
    r.app.draw(&mut term, Instant::now()).unwrap();
    let screen = common::screen::text(term.backend().buffer());
    assert!(screen.contains("Is it lit?"), "{screen}");
    let left = r.app.check_view().prompt.as_ref().and_then(|p| p.time_left);
    assert!(
        left.is_some_and(|l| l > Duration::from_secs(45) && l < Duration::from_secs(55)),
        "{left:?}"
    );
    r.key_with(KeyCode::Char('y'), KeyModifiers::NONE);
    let end = Instant::now() + Duration::from_secs(4);
    while r.sim.stats().powered[4] {
        assert!(
            Instant::now() < end,
            "Nav Lt not switched off at the answer"
        );
        r.app.pump_until(Instant::now() + Duration::from_millis(20));
    }
    assert_eq!(
        r.app.check_view().lit_answer(4).map(|a| (a.lit, a.ended)),
        Some((Some(true), vpx_efis::check::state::LitEnd::Answer))
    );
}

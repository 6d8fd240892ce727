//! The installation check's report, from hand-built views: a check that ran to the end
//! with a fault of each kind, and one interrupted half-way. The Markdown and the CSV
//! are pinned as snapshots (the guide's sample is the first), and what a builder
//! and an inspector look for is asserted line by line.

use std::path::PathBuf;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use vpx_efis::check::report::{self, About};
use vpx_efis::check::state::{
    CheckView, CircuitFinding, CircuitResult, Input, Interruption, LeftBehind, LoadsView,
    MotorFinding, NotFollowed, Outcome, Planned, Step, SwitchFinding, SwitchResult,
};
use vpx_efis::loads;
use vpx_efis::model::{Motor, TrimKind};
use vpx_efis::protocol::fault::FaultCode;
use vpx_efis::protocol::message::{HardwareVersion, SwitchId, Version};

mod common;
use common::check_view::{Circuit, motor_result, suggested, the_starter};
use common::files::names_in;

/// 2026-12-01T18:30:12Z.
fn when() -> SystemTime {
    UNIX_EPOCH + Duration::from_secs(1_796_149_812)
}

fn about() -> About {
    About {
        when: when(),
        port: "/dev/ttyUSB0".into(),
        unit: Some(Version {
            hardware_version: HardwareVersion::VpxPro,
            software_major: 1,
            software_minor: 4,
        }),
        ours: "0.1.0".into(),
        // Flaps from 20 (up) to 220 (down); the pitch trim's ends never heard.
        travel: vec![(Motor::Flaps, (20, 220))],
    }
}

const CIRCUITS: [Circuit; 6] = [
    (0x02, "EFIS 1", "EFIS", 5, SwitchId::AlwaysOn),
    (0x04, "Nav Lt", "5A-1", 3, SwitchId::Input(2)),
    (0x05, "Strobe", "5A-2", 3, SwitchId::Input(2)),
    (0x0A, "Taxi Light", "5A-7", 5, SwitchId::Input(4)),
    (0x11, "Landing Lt", "10A-1", 8, SwitchId::Input(4)),
    (0x12, "Boost pump", "10A-2", 5, SwitchId::Input(5)),
];

fn result(i: usize, outcome: Outcome<CircuitFinding>) -> CircuitResult {
    let (id, name, pin, breaker, switch) = CIRCUITS[i];
    CircuitResult {
        id,
        name: name.into(),
        pin,
        breaker: Some(breaker),
        switch: Some(switch),
        outcome,
    }
}

const LOAD_FILE: &str = include_str!("data/loads-25a-alternator.toml");

/// A check that ran to the end and found one fault of each kind.
fn finished() -> CheckView {
    let plan = CIRCUITS
        .iter()
        .map(|&(id, name, pin, breaker, switch)| Planned {
            id,
            name: name.into(),
            pin,
            breaker: Some(breaker),
            switch: Some(switch),
            on_for: Duration::from_millis(1500),
        })
        .collect();
    let mut view = CheckView {
        step: Step::Done,
        plan,
        planned_motors: vec![
            (Motor::Flaps, Duration::from_secs(6)),
            (Motor::Trim(TrimKind::Pitch), Duration::from_secs(4)),
        ],
        excluded: vec![
            the_starter(0x01),
            suggested(
                (0x17, "Pitot heat", "15A-1", 10, SwitchId::Input(7)),
                "the name has \"pitot\"",
            ),
        ],
        switches: vec![
            SwitchResult {
                input: Input::Switch(2),
                circuits: vec![0x04, 0x05],
                outcome: Outcome::Found(SwitchFinding::Passed),
            },
            SwitchResult {
                input: Input::Switch(4),
                circuits: vec![0x0A, 0x11],
                outcome: Outcome::Found(SwitchFinding::OtherChanged(vec![Input::Switch(5)])),
            },
            SwitchResult {
                input: Input::Switch(5),
                circuits: vec![0x12],
                outcome: Outcome::Found(SwitchFinding::CircuitsDidNotFollow(vec![(
                    0x12,
                    // Sent from the page's soft keys at 16:41:00 UTC, five minutes before.
                    NotFollowed::HeldByPage {
                        on: false,
                        sent_at: Some(std::time::UNIX_EPOCH + Duration::from_secs(1_764_002_460)),
                        ago: Duration::from_secs(300),
                    },
                )])),
            },
            SwitchResult {
                input: Input::FlapUp,
                circuits: vec![],
                outcome: Outcome::Skipped("skipped by you".into()),
            },
        ],
        circuits: vec![
            result(
                0,
                Outcome::Found(CircuitFinding::Within {
                    amps: 2.1,
                    breaker: 5,
                }),
            ),
            result(
                1,
                Outcome::Found(CircuitFinding::Within {
                    amps: 1.2,
                    breaker: 3,
                }),
            ),
            result(2, Outcome::Found(CircuitFinding::NoCurrent)),
            result(
                3,
                Outcome::Found(CircuitFinding::NearBreaker {
                    amps: 4.3,
                    breaker: 5,
                }),
            ),
            result(
                4,
                Outcome::Found(CircuitFinding::Faulted(FaultCode::ShortCircuit)),
            ),
            result(5, Outcome::Skipped("skipped by you".into())),
        ],
        motors: vec![
            motor_result(
                Motor::Flaps,
                &[20, 60, 20, 20],
                Outcome::Found(MotorFinding::Moves),
            ),
            motor_result(
                Motor::Trim(TrimKind::Pitch),
                &[128, 110, 128, 128],
                Outcome::Found(MotorFinding::Reversed),
            ),
        ],
        to_cycle: vec![(0x12, "Boost pump".into(), SwitchId::Input(5))],
        ..CheckView::default()
    };
    let file = loads::file::parse(LOAD_FILE).unwrap();
    view.loads = Some(LoadsView::Analysed {
        path: PathBuf::from("/home/builder/.config/vpx-efis/loads.toml"),
        analysis: loads::analyse(&file, &view.measured_amps()),
    });
    view
}

/// Quit in the middle of the circuits: the landing light was on when the link went.
fn interrupted() -> CheckView {
    let mut view = finished();
    view.step = Step::Circuits;
    view.switches.truncate(1);
    view.circuits = vec![
        result(
            0,
            Outcome::Found(CircuitFinding::Within {
                amps: 2.1,
                breaker: 5,
            }),
        ),
        result(1, Outcome::NotRun),
        result(4, Outcome::NotRun),
    ];
    view.motors = vec![];
    view.to_cycle = vec![];
    view.loads = None;
    view.skipped_steps = vec![Step::Motors];
    view.interrupted = Some(Interruption {
        cause: "communication lost".into(),
        left: vec![LeftBehind::new(
            0x11,
            "Landing Lt".into(),
            "unknown: ON when the link went".into(),
        )],
    });
    view
}

#[test]
fn a_finished_check_reports_every_result_and_what_is_left_to_fix() {
    let md = report::markdown(&finished(), &about());
    insta::assert_snapshot!("finished_markdown", md);
    assert!(md.starts_with("# VP-X installation check, 2026-12-01 18:30 UTC\n\n**Result: FAILED.** 5 failed, 1 warning, 4 passed, 2 skipped.\n"), "{md}");
    for line in [
        "- When: 2026-12-01T18:30:12.000Z",
        "- Port: /dev/ttyUSB0",
        "- Unit: VP-X Pro, software 1.4",
        "- vpx-efis: 0.1.0",
        "| EFIS | EFIS 1 | 5 A | always on |",
        "| 10A-1 | Landing Lt | 8 A | switch 4 |",
        // Left alone, yet with its breaker and switch like every other.
        "| Starter | Starter | 5 A | always on |",
        "| 15A-1 | Pitot heat | 10 A | switch 7 |",
        "| Pitot heat | 15A-1 | suggested: the name has \"pitot\" |",
        "| switch 4 | Taxi Light, Landing Lt | ✗ FAIL | switch 5 changed instead: switches crossed |",
        "| flap switch UP | — | – SKIPPED | skipped by you |",
        "| Strobe | 5A-2 | 3 A | ✗ FAIL | 0 A | no current while on: an open circuit, a blown bulb, a load not connected |",
        "| Boost pump | 10A-2 | 5 A | – SKIPPED | — | skipped by you |",
        // Positions in counts, and on the travel where its ends are known (flaps
        // 20 up to 220 down: 60 is 20 % of the way).
        "| flaps | ✓ PASS | 20 → 60 → 20 → 20 counts (0 % → 20 % → 0 % → 0 % of travel) | it moves the commanded way |",
        "| pitch trim | ✗ FAIL | 128 → 110 → 128 → 128 counts | reversed: the motor's polarity is swapped, or the sensor is wired backwards |",
        "| switch 5 | Boost pump | ✗ FAIL | circuits did not follow: Boost pump is held off by DEVICE_POWER sent from this page at 16:41:00 UTC (ICD Appendix A): flip the switch to the other position and back to release it |",
        "- Boost pump: flip switch 5 to the other position and back",
    ] {
        assert!(md.lines().any(|l| l == line), "no line {line:?} in\n{md}");
    }
    // The list of what is left to fix: each failure and warning, once, in step order,
    // then the load analysis'.
    let fix: Vec<&str> = md
        .split("## Left to fix\n\n")
        .nth(1)
        .unwrap()
        .lines()
        .take_while(|l| !l.is_empty())
        .collect();
    assert_eq!(
        fix,
        [
            "1. switch 4: switch 5 changed instead: switches crossed",
            "2. switch 5: circuits did not follow: Boost pump is held off by DEVICE_POWER sent from this page at 16:41:00 UTC (ICD Appendix A): flip the switch to the other position and back to release it",
            "3. Strobe (5A-2): no current while on: an open circuit, a blown bulb, a load not connected",
            "4. Taxi Light (5A-7): draws 4.3 A of a 5 A breaker (≥ 80 %): the breaker is tight and will trip in flight",
            "5. Landing Lt (10A-1): faulted: SHORT_CIRCUIT (Device short circuit). Device faulted and disabled, FAULT_STATUS message broadcast. The faulted pin remains off until cleared by the external system.",
            "6. pitch trim: reversed: the motor's polarity is swapped, or the sensor is wired backwards",
            "7. Load analysis, landing: margin 15 % of 25 A: under 20 %",
            "8. Boost pump: flip switch 5 to the other position and back (the check left it held by DEVICE_POWER)",
        ]
    );
    // The load analysis, by hand. Measured: EFIS 2.1, Nav 1.2, Taxi Light 4.3 (typed
    // 3.5). Typed: Strobe 1.8 (its "no current" is a fault, not its load), Landing
    // Lt 7 (it faulted), Pitot heat 9 (excluded from the check). Alternator 25 A.
    // take-off  2.1 + 1.8 + 7 + 9       = 19.9 A, (25 − 19.9)·100/25 = 20.4 %
    // landing   2.1 + 1.2 + 1.8 + 7 + 9 = 21.1 A, (25 − 21.1)·100/25 = 15.6 %: warning
    // emergency 2.1 + 1.2               =  3.3 A, 17 × 0.8 × 60 / 3.3 = 247.3 min
    for line in [
        "| take-off | 19.9 A | ✓ PASS | margin 20 % of 25 A |",
        "| landing | 21.1 A | ⚠ WARN | margin 15 % of 25 A: under 20 % |",
        "| emergency (battery only) | 3.3 A | ✓ PASS | endurance 247 min |",
    ] {
        assert!(md.lines().any(|l| l == line), "no line {line:?} in\n{md}");
    }
    for said in [
        "| Taxi Light | 5A-7 | 4.3 A | measured (typed 3.5 A) |",
        "| Strobe | 5A-2 | 1.8 A | typed |",
        "- Battery: 17 Ah rated × 0.8 usable = 13.6 Ah",
    ] {
        assert!(md.contains(said), "no {said:?} in\n{md}");
    }
    assert!(!md.contains("INCOMPLETE"));
    assert!(!md.contains("## Interrupted"));
}

/// `S` in the middle of the switch step: the inputs tested before it keep their
/// results in the report (and the count), the rest say the step was skipped.
#[test]
fn a_step_skipped_part_way_keeps_what_it_found() {
    let mut view = finished();
    view.skipped_steps = vec![Step::Switches];
    view.switches[2].outcome = Outcome::Skipped("you skipped it".into());
    view.switches[3].outcome = Outcome::Skipped("step skipped".into());
    let md = report::markdown(&view, &about());
    assert!(
        md.contains(
            "- Steps skipped by the user: Switch inputs (the rest of it, after 2 results)\n"
        ),
        "{md}"
    );
    let section = md
        .split("## Switch inputs\n\n")
        .nth(1)
        .unwrap()
        .split("\n## ")
        .next()
        .unwrap();
    assert!(
        section.starts_with(
            "The user skipped the rest of this step; what it found before stands.\n\n"
        ),
        "{section}"
    );
    for line in [
        "| switch 2 | Nav Lt, Strobe | ✓ PASS | the input changed, and its circuits followed |",
        "| switch 4 | Taxi Light, Landing Lt | ✗ FAIL | switch 5 changed instead: switches crossed |",
        "| switch 5 | Boost pump | – SKIPPED | you skipped it |",
        "| flap switch UP | — | – SKIPPED | step skipped |",
    ] {
        assert!(
            section.lines().any(|l| l == line),
            "no {line:?} in\n{section}"
        );
    }
    assert!(md.contains("1. switch 4: switch 5 changed instead"), "{md}");
    // A step skipped before any result is still said in one line.
    view.switches.iter_mut().for_each(|s| {
        s.outcome = Outcome::Skipped("step skipped".into());
    });
    let md = report::markdown(&view, &about());
    assert!(
        md.contains("## Switch inputs\n\nSkipped by the user.\n\n"),
        "{md}"
    );
    assert!(
        md.contains("- Steps skipped by the user: Switch inputs\n"),
        "{md}"
    );
}

/// Paper: no colour codes, no box drawing that breaks when printed, only pipes and
/// dashes in the tables.
fn assert_prints_on_paper(md: &str) {
    assert!(!md.contains('\u{1b}'), "an escape code");
    let boxy: Vec<char> = md
        .chars()
        .filter(|c| matches!(*c as u32, 0x2500..=0x259F))
        .collect();
    assert!(boxy.is_empty(), "box drawing {boxy:?}");
    for l in md.lines().filter(|l| l.starts_with('|')) {
        assert!(l.ends_with('|'), "a table row cut short: {l:?}");
    }
}

#[test]
fn the_reports_print_on_paper() {
    assert_prints_on_paper(&report::markdown(&finished(), &about()));
    assert_prints_on_paper(&report::markdown(&interrupted(), &about()));
}

#[test]
fn an_interrupted_check_says_incomplete_and_what_it_left_in_which_state() {
    let md = report::markdown(&interrupted(), &about());
    insta::assert_snapshot!("interrupted_markdown", md);
    let after = common::report::interrupted(&md, "communication lost");
    assert!(
        after.contains("| Landing Lt | 10A-1 | unknown: ON when the link went |"),
        "{after}"
    );
    assert!(
        md.contains(
            "| Nav Lt | 5A-1 | 3 A | ? NOT RUN | — | not run: the check stopped before it |"
        ),
        "{md}"
    );
    // The motors were skipped by the person, the load analysis never reached.
    let section = |name: &str| {
        md.split(&format!("## {name}\n\n"))
            .nth(1)
            .unwrap()
            .lines()
            .next()
            .unwrap()
            .to_string()
    };
    assert_eq!(section("Motors"), "Skipped by the user.");
    assert_eq!(
        section("Load analysis"),
        "Not run: the check stopped before this step."
    );
    assert_eq!(
        section("Left to fix"),
        "1. Landing Lt (10A-1), left by the interrupted check: unknown: ON when the link went"
    );
    assert!(md.contains("- Steps skipped by the user: Motors"), "{md}");
    // Nothing put back by DEVICE_POWER: every other circuit truly is as it was.
    assert!(
        after.contains("\n\nIt could not put everything back. It left these circuits so:"),
        "{after}"
    );
    assert!(!after.contains("held there"), "{after}");
}

/// Interrupted after circuits were put back by DEVICE_POWER: they are as the check
/// found them, but held so by the unit, and the report says so rather than "as it
/// found it".
#[test]
fn an_interrupted_check_that_left_circuits_held_says_so() {
    let mut view = interrupted();
    view.to_cycle = vec![
        (0x04, "Nav Lt".into(), SwitchId::Input(2)),
        (0x05, "Strobe".into(), SwitchId::Input(2)),
    ];
    let md = report::markdown(&view, &about());
    assert!(
        md.contains(
            "Of the circuits it put back, Nav Lt and Strobe are held there by DEVICE_POWER \
             until their switch is cycled (see \"Switches to cycle\").\n"
        ),
        "{md}"
    );
    view.interrupted.as_mut().unwrap().left.clear();
    view.to_cycle.truncate(1);
    let md = report::markdown(&view, &about());
    assert!(
        !md.contains("It left every circuit as it found it."),
        "{md}"
    );
    assert!(
        md.contains(
            "Every circuit it switched is back as it found it, but Nav Lt is held there by \
             DEVICE_POWER until its switch is cycled (see \"Switches to cycle\").\n"
        ),
        "{md}"
    );
    assert!(
        md.contains("- Nav Lt: flip switch 2 to the other position and back\n"),
        "{md}"
    );
    // And only when nothing is held does it say it left everything as it was.
    view.to_cycle.clear();
    let md = report::markdown(&view, &about());
    assert!(
        md.contains("\nIt left every circuit as it found it.\n"),
        "{md}"
    );
}

#[test]
fn the_csv_has_a_row_for_each_measurement() {
    let csv = report::csv(&finished(), &about());
    insta::assert_snapshot!("finished_csv", csv);
    let rows: Vec<&str> = csv.split("\r\n").filter(|l| !l.is_empty()).collect();
    assert_eq!(
        rows[0],
        "when,step,item,pin,breaker_a,switch,result,amps,positions_counts,detail"
    );
    // 4 switch inputs, 6 circuits, 2 motors, 7 phases.
    assert_eq!(rows.len(), 1 + 4 + 6 + 2 + 7);
    assert!(rows.contains(
        &"2026-12-01T18:30:12.000Z,circuits,Taxi Light,5A-7,5,switch 4,WARN,4.3,,draws 4.3 A of a 5 A breaker (≥ 80 %): the breaker is tight and will trip in flight"
    ));
    assert!(rows.contains(
        &"2026-12-01T18:30:12.000Z,motors,flaps,Flaps,,,PASS,,20 60 20 20,it moves the commanded way"
    ));
    // A detail with a comma is quoted whole.
    assert!(
        rows.iter().any(|r| r.starts_with("2026-12-01T18:30:12.000Z,circuits,Strobe,5A-2,3,switch 2,FAIL,0,,\"no current while on: an open circuit, a blown bulb")),
        "{csv}"
    );
}

#[test]
fn the_files_are_named_with_the_time_and_never_replace_an_earlier_report() {
    let dir = tempfile::tempdir().unwrap();
    let view = finished();
    let w = vpx_efis::app::write_report(dir.path(), &view, &about()).unwrap();
    assert_eq!(w.markdown, dir.path().join("vpx-check-2026-12-01T1830Z.md"));
    assert_eq!(w.csv, dir.path().join("vpx-check-2026-12-01T1830Z.csv"));
    assert_eq!(
        std::fs::read_to_string(&w.markdown).unwrap(),
        report::markdown(&view, &about())
    );
    assert_eq!(
        std::fs::read_to_string(&w.csv).unwrap(),
        report::csv(&view, &about())
    );
    // A second check in the same minute.
    let again = vpx_efis::app::write_report(dir.path(), &interrupted(), &about()).unwrap();
    assert_eq!(
        again.markdown,
        dir.path().join("vpx-check-2026-12-01T1830Z-2.md")
    );
    assert_eq!(
        names_in(dir.path()),
        [
            "vpx-check-2026-12-01T1830Z-2.csv",
            "vpx-check-2026-12-01T1830Z-2.md",
            "vpx-check-2026-12-01T1830Z.csv",
            "vpx-check-2026-12-01T1830Z.md",
        ]
    );
    assert!(
        std::fs::read_to_string(&w.markdown)
            .unwrap()
            .contains("**Result: FAILED.**"),
        "the first report is untouched"
    );
}

#[test]
fn a_missing_folder_is_made_and_a_failed_write_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("logs").join("checks");
    let w = vpx_efis::app::write_report(&missing, &finished(), &about()).unwrap();
    assert_eq!(w.markdown, missing.join("vpx-check-2026-12-01T1830Z.md"));
    assert_eq!(
        names_in(&missing),
        [
            "vpx-check-2026-12-01T1830Z.csv",
            "vpx-check-2026-12-01T1830Z.md"
        ]
    );
    // A file where the folder must go: an error, and nothing written anywhere.
    let other = tempfile::tempdir().unwrap();
    let blocked = other.path().join("checks");
    std::fs::write(&blocked, "not a folder").unwrap();
    let e =
        vpx_efis::app::write_report(&blocked.join("reports"), &finished(), &about()).unwrap_err();
    assert!(
        e.to_string().starts_with("cannot make the report folder "),
        "{e}"
    );
    assert_eq!(names_in(other.path()), ["checks"]);
}

/// Every section a report may have, in the order the writer writes them.
const SECTIONS: [&str; 9] = [
    "## The circuits",
    "## Before power",
    "## Switch inputs",
    "## Circuits",
    "## Motors",
    "## Load analysis",
    "## Left to fix",
    "## Switches to cycle",
    "## Interrupted",
];

/// Whether `md`'s section headings are sections of a report, in the writer's order.
fn in_report_order(md: &str) -> Result<(), String> {
    let mut next = 0;
    for h in md.lines().filter(|l| l.starts_with("## ")) {
        match SECTIONS[next..].iter().position(|s| *s == h) {
            Some(i) => next += i + 1,
            None => return Err(format!("{h:?} is no section, or out of order")),
        }
    }
    Ok(())
}

/// The guide's sample report (docs/src/report.md) is a real one: the `install` scenario run headless. A
/// real run's times and readings vary, so it is not compared word for word; but it
/// must read as the writer writes today: a report's title and result, its sections in
/// order (the list of which is checked against the writer here too), printable, and
/// none of the words the writer no longer uses.
#[test]
fn the_guides_sample_is_a_report_as_the_writer_writes_it() {
    for md in [
        report::markdown(&finished(), &about()),
        report::markdown(&interrupted(), &about()),
    ] {
        in_report_order(&md).unwrap();
    }
    let all = report::markdown(&finished(), &about());
    assert!(all.contains("\n## Switches to cycle\n"));
    assert!(report::markdown(&interrupted(), &about()).contains("\n## Interrupted\n"));

    let guide = include_str!("../docs/src/report.md");
    let sample = guide
        .split("<summary>A sample report")
        .nth(1)
        .and_then(|s| s.split("````markdown\n").nth(1))
        .and_then(|s| s.split("\n````").next())
        .expect("the guide's report page has a sample report");
    assert!(
        sample.starts_with("# VP-X installation check, "),
        "{sample}"
    );
    assert!(
        sample
            .lines()
            .nth(2)
            .is_some_and(|l| l.starts_with("**Result: ")),
        "{sample}"
    );
    in_report_order(sample).unwrap();
    for h in [
        "## The circuits",
        "## Switch inputs",
        "## Circuits",
        "## Left to fix",
    ] {
        assert!(sample.lines().any(|l| l == h), "no {h} in the sample");
    }
    assert_prints_on_paper(sample);
    for stale in [
        "§6",
        "off and on again",
        "(circuits: ",
        "of a 8 A",
        "of a 11 A",
        "of a 18 A",
    ] {
        assert!(!sample.contains(stale), "{stale:?} in the guide's sample");
    }
}

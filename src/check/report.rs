//! The installation check's report for the builder's log: a Markdown file a person
//! reads (on screen or printed: plain tables, symbols with their words, nothing that
//! needs colour or a wide page of box art) and a CSV of every measurement for a
//! spreadsheet. Both are named with the check's time, `vpx-check-2026-12-01T1830Z.md`
//! and `.csv`. This builds their text; the app writes them (`app::check::report_files`),
//! each there whole or not at all, never over an earlier report.

use std::fmt::Write as _;
use std::path::Path;
use std::time::SystemTime;

use super::state::{
    CheckView, CircuitFinding, CircuitResult, LeftBehind, LoadsView, Mark, Outcome, Step,
    SwitchResult,
};
use super::words::{self, badge, switch_id as switch_text};
use crate::loads::analysis::amps_text;
use crate::loads::{Analysis, Figure, Phase};
use crate::model::Motor;
use crate::protocol::device;
use crate::protocol::message::{SwitchId, Version};

/// Where and when the check ran, beside what it found.
#[derive(Debug, Clone, PartialEq)]
pub struct About {
    pub when: SystemTime,
    /// The port as the person named it: `/dev/ttyUSB0`, `tcp://192.168.4.1:8880`.
    pub port: String,
    /// The unit's VERSION; `None` if it never answered.
    pub unit: Option<Version>,
    /// Ours: `env!("CARGO_PKG_VERSION")`.
    pub ours: String,
    /// Each motor's travel ends in sensor counts (up or left end, down or right end),
    /// as the unit gave them, so its positions read as percent of travel beside the
    /// raw counts, as on the screen. A motor missing here gets counts only.
    pub travel: Vec<(Motor, (u8, u8))>,
}

impl About {
    fn ends(&self, m: Motor) -> Option<(u8, u8)> {
        self.travel.iter().find(|(t, _)| *t == m).map(|(_, e)| *e)
    }
}

/// `vpx-check-2026-12-01T1830Z`: the check's time in UTC to the minute, sortable and
/// without the colons some file systems refuse.
pub fn stem(when: SystemTime) -> String {
    let t = crate::utc::utc_text(when); // 2026-12-01T18:30:12.345Z
    format!("vpx-check-{}T{}{}Z", &t[..10], &t[11..13], &t[14..16])
}

fn unit_text(v: Option<Version>) -> String {
    v.map_or_else(
        || "did not answer VERSION".into(),
        |v| {
            format!(
                "{}, software {}.{}",
                v.hardware_version.name(),
                v.software_major,
                v.software_minor
            )
        },
    )
}

/// A table cell: no `|` to split it, no line break to end the row.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace(['\n', '\r'], " ")
}

/// Whether the load analysis has anything to say (a warning or worse).
fn loads_level_warns(view: &CheckView) -> bool {
    match &view.loads {
        Some(LoadsView::Analysed { analysis, .. }) => analysis.level() != crate::loads::Level::Ok,
        Some(_) => true,
        None => false,
    }
}

fn switch_words(view: &CheckView, s: &SwitchResult) -> String {
    words::switch(s, |id| view.name_of(id))
}

/// The counts of the results, for the line at the top.
pub(crate) fn tally(view: &CheckView) -> String {
    let marks: Vec<Mark> = view.marks().collect();
    let n = |m: Mark| marks.iter().filter(|&&x| x == m).count();
    let mut parts = vec![];
    for (m, one, many) in [
        (Mark::Fail, "failed", "failed"),
        (Mark::Warn, "warning", "warnings"),
        (Mark::Pass, "passed", "passed"),
        (Mark::Skipped, "skipped", "skipped"),
        (Mark::NotRun, "not run", "not run"),
    ] {
        match n(m) {
            0 => {}
            1 => parts.push(format!("1 {one}")),
            k => parts.push(format!("{k} {many}")),
        }
    }
    if parts.is_empty() {
        "no results".into()
    } else {
        parts.join(", ")
    }
}

/// A circuit the check knows: id, name, pin, breaker, switch.
type Known = (u8, String, &'static str, Option<u8>, Option<SwitchId>);

/// One row per circuit the check knows, in pin order.
fn circuits_known(view: &CheckView) -> Vec<Known> {
    let mut out: Vec<Known> = Vec::new();
    let mut add = |id: u8, name: &str, pin: &'static str, breaker, switch| {
        if !out.iter().any(|c| c.0 == id) {
            out.push((id, name.to_string(), pin, breaker, switch));
        }
    };
    for c in &view.circuits {
        add(c.id, &c.name, c.pin, c.breaker, c.switch);
    }
    for p in &view.plan {
        add(p.id, &p.name, p.pin, p.breaker, p.switch);
    }
    for e in &view.excluded {
        add(e.id, &e.name, e.pin, e.breaker, e.switch);
    }
    out.sort_by_key(|c| c.0);
    out
}

fn or_dash<T>(v: Option<T>, f: impl Fn(T) -> String) -> String {
    v.map_or_else(|| "—".into(), f)
}

fn step_skipped(view: &CheckView, step: Step) -> bool {
    view.skipped_steps.contains(&step)
}

/// The report as Markdown.
pub fn markdown(view: &CheckView, about: &About) -> String {
    let mut o = String::new();
    let when = crate::utc::utc_text(about.when);
    let _ = writeln!(
        o,
        "# VP-X installation check, {} {} UTC\n",
        &when[..10],
        &when[11..16]
    );
    match &view.interrupted {
        Some(i) => {
            let _ = writeln!(
                o,
                "**Result: INCOMPLETE.** The check was interrupted ({}) and did not finish; \
                 see \"Interrupted\" below for what it left in which state. So far: {}.\n",
                i.cause,
                tally(view)
            );
        }
        None => {
            let marks: Vec<Mark> = view.marks().collect();
            let verdict = if marks.contains(&Mark::Fail) {
                "FAILED"
            } else if marks.contains(&Mark::Warn) || loads_level_warns(view) {
                "PASSED with warnings"
            } else {
                "PASSED"
            };
            let _ = writeln!(o, "**Result: {verdict}.** {}.\n", tally(view));
        }
    }
    let _ = writeln!(o, "- When: {when}");
    let _ = writeln!(o, "- Port: {}", about.port);
    let _ = writeln!(o, "- Unit: {}", unit_text(about.unit));
    let _ = writeln!(o, "- vpx-efis: {}", about.ours);
    if !view.skipped_steps.is_empty() {
        let steps: Vec<String> = view
            .skipped_steps
            .iter()
            .map(|&s| skipped_step_words(view, s))
            .collect();
        let _ = writeln!(o, "- Steps skipped by the user: {}", steps.join(", "));
    }
    o.push('\n');

    o.push_str("## The circuits\n\n");
    let known = circuits_known(view);
    if known.is_empty() {
        o.push_str("The check learned no circuit of the unit.\n\n");
    } else {
        o.push_str("| Pin | Circuit | Breaker | Switch |\n|---|---|---|---|\n");
        for (_, name, pin, breaker, switch) in &known {
            let _ = writeln!(
                o,
                "| {pin} | {} | {} | {} |",
                cell(name),
                or_dash(*breaker, |b| format!("{b} A")),
                or_dash(*switch, switch_text)
            );
        }
        o.push('\n');
    }

    before_power(&mut o, view);
    switches(&mut o, view);
    circuits(&mut o, view);
    motors(&mut o, view, about);
    loads(&mut o, view);
    wires(&mut o, view);

    o.push_str("## Left to fix\n\n");
    let fix = view.left_to_fix();
    if fix.is_empty() {
        if view.interrupted.is_some() {
            o.push_str("Nothing found so far; the check did not finish.\n\n");
        } else {
            o.push_str("Nothing: every result passed.\n\n");
        }
    } else {
        for (i, f) in fix.iter().enumerate() {
            let _ = writeln!(o, "{}. {f}", i + 1);
        }
        o.push('\n');
    }

    if !view.to_cycle.is_empty() {
        o.push_str("## Switches to cycle\n\n");
        let _ = writeln!(
            o,
            "The check put these circuits back as it found them, by DEVICE_POWER. The unit \
             now holds each so, whatever its switch says, until that switch is cycled \
             ({}). Flip each switch to the other position and back, so it ends where it \
             was (a switch the check found dead or crossed must be fixed first):\n",
            words::HOLD_RULE
        );
        for (_, name, switch) in &view.to_cycle {
            let _ = writeln!(o, "- {name}: {}", view.release(*switch));
        }
        o.push('\n');
    }

    if let Some(i) = &view.interrupted {
        o.push_str("## Interrupted\n\n");
        let _ = writeln!(o, "The check stopped: {}.\n", i.cause);
        let held = held_words(view);
        if i.left.is_empty() {
            match held {
                None => o.push_str("It left every circuit as it found it.\n\n"),
                Some(h) => {
                    let _ = writeln!(
                        o,
                        "Every circuit it switched is back as it found it, but {h}.\n"
                    );
                }
            }
        } else {
            o.push_str(
                "It could not put everything back. It left these circuits so:\n\n\
                 | Circuit | Pin | Left |\n|---|---|---|\n",
            );
            for LeftBehind { id, name, state } in &i.left {
                let pin = device::device(*id).map_or("?", |d| d.system_name);
                let _ = writeln!(o, "| {} | {pin} | {} |", cell(name), cell(state));
            }
            o.push('\n');
            if let Some(h) = held {
                let _ = writeln!(o, "Of the circuits it put back, {h}.\n");
            }
        }
    }
    let _ = writeln!(
        o,
        "The measurements are also in the CSV file of the same name."
    );
    o
}

/// "Nav Lt and Strobe are held there by DEVICE_POWER until their switch is cycled
/// (see "Switches to cycle")", or `None` when the check left nothing held.
fn held_words(view: &CheckView) -> Option<String> {
    let names: Vec<&str> = view.to_cycle.iter().map(|(_, n, _)| n.as_str()).collect();
    let (last, rest) = names.split_last()?;
    let (who, verb) = if rest.is_empty() {
        (last.to_string(), "is")
    } else {
        (format!("{} and {last}", rest.join(", ")), "are")
    };
    Some(format!(
        "{who} {verb} held there by DEVICE_POWER until {} switch is cycled (see \
         \"Switches to cycle\")",
        if rest.is_empty() { "its" } else { "their" }
    ))
}

fn before_power(o: &mut String, view: &CheckView) {
    o.push_str("## Before power\n\n");
    if view.plan.is_empty() && view.planned_motors.is_empty() {
        o.push_str("Nothing was to be switched on.\n\n");
    } else {
        o.push_str("What the check was to switch on, and for how long:\n\n");
        o.push_str("| Circuit | Pin | On for |\n|---|---|---|\n");
        for p in &view.plan {
            let _ = writeln!(
                o,
                "| {} | {} | {:.1} s |",
                cell(&p.name),
                p.pin,
                p.on_for.as_secs_f32()
            );
        }
        for (m, d) in &view.planned_motors {
            let _ = writeln!(
                o,
                "| {}, both ways and back | — | {:.1} s in all |",
                m.name(),
                d.as_secs_f32()
            );
        }
        o.push('\n');
    }
    if view.excluded.is_empty() {
        o.push_str("No circuit was excluded.\n\n");
    } else {
        o.push_str(
            "Left alone (never switched by the check):\n\n| Circuit | Pin | Why |\n|---|---|---|\n",
        );
        for e in &view.excluded {
            let _ = writeln!(o, "| {} | {} | {} |", cell(&e.name), e.pin, cell(&e.why));
        }
        o.push('\n');
    }
}

/// How many of `step`'s items got a result before the person skipped the rest of it
/// (`S` in the middle of a step keeps what was found).
fn found_in(view: &CheckView, step: Step) -> usize {
    let found = |o: bool| usize::from(o);
    match step {
        Step::Switches => view
            .switches
            .iter()
            .map(|s| found(matches!(s.outcome, Outcome::Found(_))))
            .sum(),
        Step::Circuits => view
            .circuits
            .iter()
            .map(|c| found(matches!(c.outcome, Outcome::Found(_))))
            .sum(),
        Step::Motors => view
            .motors
            .iter()
            .map(|m| found(matches!(m.outcome, Outcome::Found(_))))
            .sum(),
        _ => 0,
    }
}

/// "Switch inputs", or "Switch inputs (after 1 result)" for a step skipped part way.
fn skipped_step_words(view: &CheckView, step: Step) -> String {
    match found_in(view, step) {
        0 => step.title().to_string(),
        n => format!(
            "{} (the rest of it, after {})",
            step.title(),
            words::count(n, "result", "results")
        ),
    }
}

fn skipped_or_empty(o: &mut String, view: &CheckView, step: Step, empty: &str) -> bool {
    if step_skipped(view, step) && found_in(view, step) > 0 {
        // Skipped part way: the results found stand, the rest say "step skipped".
        o.push_str("The user skipped the rest of this step; what it found before stands.\n\n");
        false
    } else if step_skipped(view, step) {
        o.push_str("Skipped by the user.\n\n");
        true
    } else if match step {
        Step::Switches => view.switches.is_empty(),
        Step::Circuits => view.circuits.is_empty(),
        _ => view.motors.is_empty(),
    } {
        if view.interrupted.is_some() {
            o.push_str("Not run: the check stopped before this step.\n\n");
        } else {
            o.push_str(empty);
        }
        true
    } else {
        false
    }
}

fn switches(o: &mut String, view: &CheckView) {
    o.push_str("## Switch inputs\n\n");
    if skipped_or_empty(
        o,
        view,
        Step::Switches,
        "No switch input has a circuit assigned.\n\n",
    ) {
        return;
    }
    o.push_str("| Input | Circuits | Result | What happened |\n|---|---|---|---|\n");
    for s in &view.switches {
        let names: Vec<String> = s.circuits.iter().map(|&id| view.name_of(id)).collect();
        let _ = writeln!(
            o,
            "| {} | {} | {} | {} |",
            s.input.label(),
            cell(&if names.is_empty() {
                "—".to_string()
            } else {
                names.join(", ")
            }),
            badge(s.mark()),
            cell(&switch_words(view, s))
        );
    }
    o.push('\n');
}

fn measured(c: &CircuitResult) -> String {
    match &c.outcome {
        Outcome::Found(CircuitFinding::Within { amps, .. })
        | Outcome::Found(CircuitFinding::NearBreaker { amps, .. }) => format!("{amps:.1} A"),
        Outcome::Found(CircuitFinding::NoCurrent) => "0 A".into(),
        _ => "—".into(),
    }
}

fn circuits(o: &mut String, view: &CheckView) {
    o.push_str("## Circuits\n\n");
    if skipped_or_empty(o, view, Step::Circuits, "No circuit was to be tested.\n\n") {
        return;
    }
    o.push_str(
        "Each circuit switched on alone, its current read from two fresh DEVICE_STATUS \
         broadcasts, then put back as it was.",
    );
    // Beside each current, the last check's and the change (`super::trend`).
    let last = view.last_check.as_ref();
    if let Some(w) = last.and_then(|l| l.when) {
        let t = crate::utc::utc_text(w);
        let _ = write!(
            o,
            " Beside each current, this aircraft's last check's ({} {} UTC) and the \
             change; over {} % and at least {} is marked \"{}\".",
            &t[..10],
            &t[11..16],
            super::trend::CHANGED_PERCENT,
            super::trend::amps_text(super::trend::CHANGED_MIN_TENTHS as u16),
            super::trend::CHANGED_WORDS
        );
    }
    o.push_str("\n\n");
    if last.is_some() {
        o.push_str(
            "| Circuit | Pin | Breaker | Result | Current | Last check | What happened |\n\
             |---|---|---|---|---|---|---|\n",
        );
    } else {
        o.push_str(
            "| Circuit | Pin | Breaker | Result | Current | What happened |\n|---|---|---|---|---|---|\n",
        );
    }
    for c in &view.circuits {
        // What the person saw of a light, beside its current; a disagreement in words.
        let (mut current, mut what) = (measured(c), words::circuit(c));
        if let Some(lit) = view.lit_of(c.id) {
            let (seen, disagree) = words::lit_seen(c, lit);
            current = format!("{current}, {seen}");
            if let Some(d) = disagree {
                what = format!("{what}; {d}");
            }
        }
        // How the question ended, so when the light went off.
        if let Some(a) = view.lit_answer(c.id) {
            what = format!("{what}; {}", words::lit_ended(a.lit, a.ended, a.switched));
        }
        let trend = last.map(|_| {
            let t = view.trend(c);
            match t.words() {
                Some(w) if t.changed() => format!("⚠ {w}"),
                Some(w) => w,
                None => "—".into(),
            }
        });
        let _ = writeln!(
            o,
            "| {} | {} | {} | {} | {} |{} {} |",
            cell(&c.name),
            c.pin,
            or_dash(c.breaker, |b| format!("{b} A")),
            badge(c.mark()),
            cell(&current),
            trend.map_or_else(String::new, |t| format!(" {} |", cell(&t))),
            cell(&what)
        );
    }
    o.push('\n');
    let changed: Vec<String> = view
        .circuits
        .iter()
        .filter(|c| view.trend(c).changed())
        .map(|c| {
            let t = view.trend(c);
            format!(
                "- ⚠ {} ({}): {}, {}",
                c.name,
                c.pin,
                measured(c),
                t.words().unwrap_or_default()
            )
        })
        .collect();
    if !changed.is_empty() {
        let _ = writeln!(
            o,
            "Changed since the last check (a motor wearing or a connection corroding shows \
             as a current that creeps; look at each):\n\n{}\n",
            changed.join("\n")
        );
    }
}

/// "128 → 159 → 128 counts (50 % → 62 % → 50 % of travel)", or "—".
fn positions_cell(about: &About, m: Motor, raw: &[u8]) -> String {
    if raw.is_empty() {
        return "—".into();
    }
    match words::travel(raw, about.ends(m)) {
        Some(t) => format!("{} ({t})", words::counts(raw)),
        None => words::counts(raw),
    }
}

fn motors(o: &mut String, view: &CheckView, about: &About) {
    o.push_str("## Motors\n\n");
    if skipped_or_empty(o, view, Step::Motors, "No motor is enabled.\n\n") {
        return;
    }
    o.push_str(
        "Each run briefly each way on the page's safe motor stream; the positions are \
         FLAP_TRIM_STATUS's before, after each run, and after it was run back.\n\n\
         | Motor | Result | Positions | What happened |\n|---|---|---|---|\n",
    );
    for m in &view.motors {
        let _ = writeln!(
            o,
            "| {} | {} | {} | {} |",
            m.motor.name(),
            badge(m.mark()),
            positions_cell(about, m.motor, &m.positions),
            cell(&words::motor(m))
        );
    }
    o.push('\n');
}

/// The phases' short names for the circuit table's columns.
const PHASE_COLUMNS: [&str; 7] = [
    "Ground",
    "Taxi",
    "Take-off",
    "Day",
    "Night",
    "Landing",
    "Emergency",
];

fn duty_text(d: f64) -> String {
    if d >= 1.0 {
        "on".into()
    } else if d <= 0.0 {
        "–".into()
    } else {
        format!("{d}")
    }
}

fn loads(o: &mut String, view: &CheckView) {
    o.push_str("## Load analysis\n\n");
    if step_skipped(view, Step::Loads) {
        o.push_str("Skipped by the user.\n\n");
        return;
    }
    match &view.loads {
        None if view.interrupted.is_some() => {
            o.push_str("Not run: the check stopped before this step.\n\n")
        }
        None => o.push_str("Not run.\n\n"),
        Some(LoadsView::TemplateWritten(path)) => {
            let _ = writeln!(
                o,
                "No load file yet: a template listing every circuit was written to \
                 `{}`. Fill it in (the alternator's rating, the battery's capacity, \
                 which circuit is on in which phase, a current for each circuit the \
                 check cannot measure) and run the check again.\n",
                path.display()
            );
        }
        Some(LoadsView::Refused(why)) => {
            // One problem a line, each with its path, line and field.
            let _ = writeln!(o, "The load file could not be used:\n");
            for problem in why.lines() {
                let _ = writeln!(o, "- {problem}");
            }
            let _ = writeln!(o);
        }
        Some(LoadsView::Analysed { path, analysis }) => analysed(o, path, analysis),
    }
}

/// Each circuit's wire against its breaker (an unprotected wire fails) and the current
/// the check measured against the drop its run allows (over the limit warns).
fn wires(o: &mut String, view: &CheckView) {
    use crate::loads::{wire, wiring};
    // Without the load file (the Load analysis section says why) there is nothing
    // to hold the breakers against, and no section.
    let Some(w) = &view.wires else {
        return;
    };
    o.push_str("## Wires\n\n");
    if w.rows.iter().all(|r| r.wire.is_none()) {
        o.push_str(
            "No circuit's wire is entered in the load file (`wire`, `wire_length`, \
             `return_length` in each `[circuit.PIN]`): nothing to hold the breakers \
             against.\n\n",
        );
        return;
    }
    o.push_str(
        "Each breaker held against its wire (AC 43.13-1B ¶11-48, Table 11-3), and each \
         current the check measured against the voltage drop its run allows (Table 11-6).\n\n\
         | Pin | Circuit | Wire | Run | Breaker | Largest for the wire | Measured | Drop | Limit | Verdict |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in &w.rows {
        let verdict = match r.verdict {
            wiring::Verdict::Unprotected => words::badge(Mark::Fail),
            wiring::Verdict::Drop => words::badge(Mark::Warn),
            wiring::Verdict::Ok => words::badge(Mark::Pass),
            wiring::Verdict::NotEntered => "not entered".into(),
        };
        let _ = writeln!(
            o,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {verdict} |",
            r.pin,
            cell(&r.name),
            or_dash(r.wire, |w| w.to_string()),
            or_dash(r.run_feet, wire::feet_text),
            or_dash(r.breaker_amps, |b| format!("{b} A")),
            or_dash(r.max_breaker_amps, |m| format!(
                "{} A",
                wiring::amps_text(m)
            )),
            or_dash(r.amps, |a| format!("{a:.1} A")),
            or_dash(r.drop_volts, |d| format!("{d:.2} V")),
            or_dash(r.drop_limit_volts, |l| format!("{l} V")),
        );
    }
    o.push('\n');
    for r in &w.rows {
        if let Some(t) = r.unprotected_words() {
            let _ = writeln!(o, "- {} {t}.", words::badge(Mark::Fail));
        } else if let Some(t) = r.drop_words() {
            let _ = writeln!(o, "- {} {t}.", words::badge(Mark::Warn));
        }
    }
    for n in wiring::notes(&w.rows, w.system.as_ref()) {
        let _ = writeln!(o, "- Note: {n}.");
    }
    o.push('\n');
}

fn analysed(o: &mut String, path: &Path, a: &Analysis) {
    let _ = writeln!(o, "- Load file: `{}`", path.display());
    let _ = writeln!(o, "- Alternator: {} A rated", amps_text(a.alternator_amps));
    let _ = writeln!(
        o,
        "- Battery: {} Ah rated × {} usable = {} Ah\n",
        amps_text(a.battery_amp_hours),
        a.battery_usable,
        amps_text(a.usable_amp_hours())
    );
    o.push_str("| Phase | Total | Result | Margin or endurance |\n|---|---|---|---|\n");
    for p in &a.phases {
        let m = Mark::of(p.level);
        let _ = writeln!(
            o,
            "| {} | {} A | {} | {} |",
            p.phase.title(),
            amps_text(p.amps),
            badge(m),
            cell(&a.verdict(p.phase))
        );
    }
    o.push('\n');
    o.push_str(
        "Total of a phase = Σ current × share of the phase the circuit is on. Margin = \
         (alternator rating − total) × 100 / rating; under 20 % is a warning (a load over \
         80 % of the alternator's rating: FAA AC 43.13-1B par. 11-35a, which calls it a \
         rule of thumb, not a load analysis). Endurance \
         (emergency, battery only) = capacity × usable share × 60 / total, in minutes; \
         under 30 min is a warning.\n\n",
    );
    let _ = writeln!(
        o,
        "| Circuit | Pin | Current | From | {} |\n|---|---|---|---|{}",
        PHASE_COLUMNS.join(" | "),
        "---|".repeat(7)
    );
    for r in &a.rows {
        let from = match (r.figure, r.typed) {
            (Figure::Measured(m), Some(t)) if (m - t).abs() > 1e-9 => {
                format!("measured (typed {} A)", amps_text(t))
            }
            (f, _) => f.source().to_string(),
        };
        let current = match r.figure {
            Figure::Missing => "none".to_string(),
            f => format!("{} A", amps_text(f.amps())),
        };
        let duty: Vec<String> = Phase::ALL
            .iter()
            .map(|&p| duty_text(r.duty[p.index()]))
            .collect();
        let _ = writeln!(
            o,
            "| {} | {} | {current} | {from} | {} |",
            cell(&r.name),
            r.pin,
            duty.join(" | ")
        );
    }
    o.push('\n');
    if !a.unlisted.is_empty() {
        o.push_str("Measured but not in the load file (in no phase):\n\n");
        for &(id, amps) in &a.unlisted {
            let pin = device::device(id).map_or("?", |d| d.system_name);
            let _ = writeln!(o, "- {pin}: {} A", amps_text(amps));
        }
        o.push('\n');
    }
}

/// A CSV field, quoted when it must be (RFC 4180).
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// Every measurement and result, one row each, for a spreadsheet: the switch inputs,
/// the circuits with their current, the motors with their positions, and the load
/// analysis' phases with their totals.
pub fn csv(view: &CheckView, about: &About) -> String {
    let when = crate::utc::utc_text(about.when);
    let mut o =
        String::from("when,step,item,pin,breaker_a,switch,result,amps,positions_counts,detail\r\n");
    let mut row = |step: &str,
                   item: &str,
                   pin: &str,
                   breaker: String,
                   switch: String,
                   result: Mark,
                   amps: String,
                   positions: String,
                   detail: String| {
        let fields = [
            when.as_str(),
            step,
            item,
            pin,
            &breaker,
            &switch,
            result.word(),
            &amps,
            &positions,
            &detail,
        ];
        let line: Vec<String> = fields.iter().map(|f| field(f)).collect();
        o.push_str(&line.join(","));
        o.push_str("\r\n");
    };
    for s in &view.switches {
        let names: Vec<String> = s.circuits.iter().map(|&id| view.name_of(id)).collect();
        row(
            "switches",
            &s.input.label(),
            "",
            String::new(),
            String::new(),
            s.mark(),
            String::new(),
            String::new(),
            if names.is_empty() {
                switch_words(view, s)
            } else {
                format!("{}; circuits: {}", switch_words(view, s), names.join(", "))
            },
        );
    }
    for c in &view.circuits {
        let amps = match &c.outcome {
            Outcome::Found(CircuitFinding::Within { amps, .. })
            | Outcome::Found(CircuitFinding::NearBreaker { amps, .. }) => amps.to_string(),
            Outcome::Found(CircuitFinding::NoCurrent) => "0".into(),
            _ => String::new(),
        };
        row(
            "circuits",
            &c.name,
            c.pin,
            c.breaker.map(|b| b.to_string()).unwrap_or_default(),
            c.switch.map(switch_text).unwrap_or_default(),
            c.mark(),
            amps,
            String::new(),
            {
                let mut what = match view.lit_of(c.id).map(|lit| words::lit_seen(c, lit)) {
                    Some((seen, Some(d))) => format!("{}; {seen}; {d}", words::circuit(c)),
                    Some((seen, None)) => format!("{}; {seen}", words::circuit(c)),
                    None => words::circuit(c),
                };
                if let Some(a) = view.lit_answer(c.id) {
                    what = format!("{what}; {}", words::lit_ended(a.lit, a.ended, a.switched));
                }
                what
            },
        );
    }
    for m in &view.motors {
        let pos: Vec<String> = m.positions.iter().map(u8::to_string).collect();
        row(
            "motors",
            m.motor.name(),
            device::device(m.motor.device_id()).map_or("", |d| d.system_name),
            String::new(),
            String::new(),
            m.mark(),
            String::new(),
            pos.join(" "),
            words::motor(m),
        );
    }
    if let Some(LoadsView::Analysed { analysis, .. }) = &view.loads {
        for p in &analysis.phases {
            row(
                "loads",
                p.phase.title(),
                "",
                String::new(),
                String::new(),
                Mark::of(p.level),
                format!("{}", p.amps),
                String::new(),
                analysis.verdict(p.phase),
            );
        }
    }
    o
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A check at 2026-12-01T18:30:12Z on `/dev/ttyUSB0`, the unit silent.
    pub(crate) fn about() -> About {
        About {
            when: std::time::UNIX_EPOCH + std::time::Duration::from_secs(1_796_149_812),
            port: "/dev/ttyUSB0".into(),
            unit: None,
            ours: "0.1.0".into(),
            travel: vec![],
        }
    }

    #[test]
    fn a_name_is_the_minute_in_utc() {
        assert_eq!(stem(about().when), "vpx-check-2026-12-01T1830Z");
    }

    /// The second check's report: each current beside the last check's, with the
    /// change, and a change over the rule's line said in words and listed.
    #[test]
    fn each_current_is_beside_the_last_checks_with_the_change() {
        use crate::check::trend::{LastCheck, Reading};
        let c = |id, name: &str, pin, amps| CircuitResult {
            id,
            name: name.into(),
            pin,
            breaker: Some(10),
            switch: None,
            outcome: Outcome::Found(CircuitFinding::Within { amps, breaker: 10 }),
        };
        let mut view = CheckView {
            circuits: vec![
                c(4, "Nav Lt", "5A-1", 1.2),
                c(0x11, "Landing Lt", "10A-1", 7.5),
            ],
            ..CheckView::default()
        };
        let about = about();
        let first = markdown(&view, &about);
        assert!(!first.contains("Last check"), "{first}");
        view.last_check = Some(LastCheck {
            // 2026-11-03T18:30:00Z.
            when: Some(std::time::UNIX_EPOCH + std::time::Duration::from_secs(1_793_730_600)),
            circuits: vec![
                Reading {
                    pin: "5A-1".into(),
                    name: "Nav Lt".into(),
                    tenths: Some(11),
                },
                Reading {
                    pin: "10A-1".into(),
                    name: "Landing Lt".into(),
                    tenths: Some(61),
                },
            ],
        });
        let md = markdown(&view, &about);
        assert!(
            md.contains("this aircraft's last check's (2026-11-03 18:30 UTC)"),
            "{md}"
        );
        assert!(
            md.contains(
                "| Circuit | Pin | Breaker | Result | Current | Last check | What happened |"
            ),
            "{md}"
        );
        assert!(
            md.contains("| Nav Lt | 5A-1 | 10 A | ✓ PASS | 1.2 A | last check 1.1 A, +9 % |"),
            "{md}"
        );
        assert!(
            md.contains(
                "| Landing Lt | 10A-1 | 10 A | ✓ PASS | 7.5 A | ⚠ last check 6.1 A, +23 %: \
                 changed since the last check |"
            ),
            "{md}"
        );
        assert!(
            md.contains(
                "- ⚠ Landing Lt (10A-1): 7.5 A, last check 6.1 A, +23 %: changed since the \
                 last check"
            ),
            "{md}"
        );
        assert!(!md.contains("- ⚠ Nav Lt"), "{md}");
    }

    #[test]
    fn table_cells_keep_their_row_whole() {
        assert_eq!(cell("Nav | Strobe\nnew"), "Nav \\| Strobe new");
        assert_eq!(field("plain"), "plain");
        assert_eq!(field("a, \"b\""), "\"a, \"\"b\"\"\"");
    }
}

//! The logbook's records drawn for `vpx-efis log`: a circuit's history as the chart
//! ([`crate::ui::circuit_history`]) and the aircraft's records as the printable page
//! ([`crate::ui::aircraft_page`]), gathered from the store's reads
//! ([`crate::logbook::query`]). The app wires the store to the drawing, as it does for
//! the page; the subcommand only prints what comes back.

use crate::check::trend::Reading;
use crate::logbook::Logbook;
use crate::logbook::query::{self, CheckRow, CircuitRow, HistoryRow, time_of};
use crate::ui::aircraft_page::{self, AsBuilt, BuiltCircuit, CheckEntry};
pub use crate::ui::aircraft_page::{Page, html};
pub use crate::ui::circuit_history::minute;
use crate::ui::circuit_history::{self, Point};

/// The chart of circuit `name`'s readings (the logbook's, oldest first), `width`
/// columns wide, under the name as the latest check had it.
pub fn chart(name: &str, rows: &[HistoryRow], width: u16) -> String {
    let points: Vec<Point> = rows.iter().filter_map(point).collect();
    let title = rows.last().map_or(name, |r| r.name.as_str());
    circuit_history::chart(title, &points, width)
}

/// "faulted: OVER_CURRENT", of "faulted: OVER_CURRENT (Device over-current). …".
fn short(finding: &str) -> String {
    let first = finding.split(['(', ';', '.']).next().unwrap_or("").trim();
    if first.chars().count() > 40 {
        format!("{}…", first.chars().take(39).collect::<String>())
    } else {
        first.to_string()
    }
}

fn point(r: &HistoryRow) -> Option<Point> {
    Some(Point {
        when: time_of(&r.time)?,
        pin: r.pin.clone(),
        tenths: r.amps.map(|a| crate::check::trend::tenths(a as f32)),
        // The finding's first words: a chart line is no place for Appendix E.
        verdict: format!("{}: {}", r.verdict, short(&r.finding)),
    })
}

/// The page's records, gathered from the logbook.
pub fn page(book: &Logbook, aircraft: Option<&str>) -> anyhow::Result<Page> {
    let checks = query::checks(book, aircraft)?;
    let mut entries = Vec::with_capacity(checks.len());
    let mut latest: Option<(&CheckRow, Vec<CircuitRow>)> = None;
    for c in &checks {
        let circuits = query::check_circuits(book, c.entry)?;
        let Some(when) = time_of(&c.time) else {
            continue;
        };
        entries.push(CheckEntry {
            when,
            result: match &c.interrupted {
                Some(why) => format!("INCOMPLETE ({why}): {}", c.tally),
                None => c.tally.clone(),
            },
            by: c.origin.clone(),
            readings: circuits.iter().map(Reading::from).collect(),
        });
        latest = Some((c, circuits));
    }
    let settings = query::setting_changes(book, aircraft)?
        .into_iter()
        .filter_map(|s| {
            Some(aircraft_page::SettingChange {
                when: time_of(&s.time)?,
                setting: s.setting,
                old: s.old.unwrap_or_else(|| "not known".into()),
                new: s.new,
                confirmed: s.confirmed,
                by: s.origin,
            })
        })
        .collect();
    let firmware = query::firmware(book, aircraft)?
        .into_iter()
        .filter_map(|f| {
            Some(aircraft_page::FirmwareUpdate {
                when: time_of(&f.time)?,
                sha256: f.sha256,
                before: f.before.unwrap_or_else(|| "not known".into()),
                after: f.after.unwrap_or_else(|| "not known".into()),
                outcome: f.outcome,
            })
        })
        .collect();
    let (as_built, analysis, unit) = match &latest {
        Some((c, circuits)) => {
            let when = time_of(&c.time).unwrap_or(std::time::UNIX_EPOCH);
            let (built, analysis) = as_built(c, circuits, when);
            (Some(built), analysis, c.unit.clone())
        }
        None => (None, None, None),
    };
    Ok(Page {
        aircraft: aircraft.map_or_else(|| "Aircraft not named".into(), str::to_string),
        unit,
        written: Some(std::time::SystemTime::now()),
        ours: crate::program::VERSION.to_string(),
        as_built,
        analysis,
        checks: entries,
        settings,
        firmware,
    })
}

/// The wiring as the latest check found it, each circuit's wire from the load file
/// as it was at that check, and the load analysis made again from that file and the
/// check's currents (the same arithmetic as the check's, `loads::analyse`).
fn as_built(
    c: &CheckRow,
    circuits: &[CircuitRow],
    when: std::time::SystemTime,
) -> (
    AsBuilt,
    Option<(std::time::SystemTime, crate::loads::Analysis)>,
) {
    use crate::loads::{file, wiring};
    let file = c.load_file.as_deref().and_then(|t| file::parse(t).ok());
    let wires = file.as_ref().map(|f| f.circuits.as_slice()).unwrap_or(&[]);
    let built = circuits
        .iter()
        .map(|r| {
            let wire = wires
                .iter()
                .find(|w| w.id == r.device)
                .map(|w| wiring::row(r.device, r.name.clone(), w.wire, r.breaker, r.amps, None));
            BuiltCircuit {
                pin: r.pin.clone(),
                name: r.name.clone(),
                breaker: r.breaker,
                switch: r.switch.clone(),
                wire,
            }
        })
        .collect();
    let measured: Vec<(u8, f32)> = circuits
        .iter()
        .filter_map(|r| Some((r.device, r.amps? as f32)).filter(|(_, a)| *a > 0.0))
        .collect();
    let analysis = file.map(|f| (when, crate::loads::analyse(&f, &measured)));
    (
        AsBuilt {
            when,
            circuits: built,
        },
        analysis,
    )
}

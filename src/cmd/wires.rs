//! `vpx-efis wires [--port PATH|tcp://HOST:PORT] [--loads FILE] [--from-backup FILE]
//! [--json]`: each circuit's breaker held against the wire the load file gives it
//! (AC 43.13-1B Table 11-3), and its current now against the voltage drop its run
//! allows (Table 11-6), by the rules of [`crate::loads::wire`].
//!
//! Exit status: 1 when any breaker does not protect its wire or a measured drop is
//! over the limit, 0 otherwise (a circuit with no wire entered fails nothing), 2 for a
//! bad load file or backup (path, line and field).

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Context;
use clap::Args;
use serde::Serialize;

use crate::cmd::backup::{connect, read_with_progress};
use crate::cmd::common::PortArgs;
use crate::loads::wire::{self, SystemVoltage};
use crate::loads::wiring::{self, Row, Verdict};
use crate::loads::{LoadCircuit, disk};
use crate::program::UsageError;
use crate::protocol::config::UnitConfig;

#[derive(Debug, Args)]
pub struct WiresArgs {
    #[command(flatten)]
    pub port: PortArgs,
    /// The load file with each circuit's `wire`, `wire_length` and `return_length`
    /// (default: loads.toml beside the config file, as `check` reads it).
    #[arg(long, value_name = "FILE")]
    pub loads: Option<PathBuf>,
    /// Take the breakers from a backup file instead of a unit (a unit not powered
    /// yet): no current is measured, so only breaker against wire is judged.
    #[arg(long, value_name = "FILE")]
    pub from_backup: Option<PathBuf>,
    /// Print the rows as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Breakers over their wires, or drops over the limit: exit 1, after the rows.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct Found(pub String);

/// One row as `--json` prints it.
#[derive(Debug, Serialize)]
struct JsonRow<'a> {
    pin: &'a str,
    name: &'a str,
    wire: Option<String>,
    run_feet: Option<f64>,
    return_assumed: bool,
    breaker_amps: Option<u8>,
    max_breaker_amps: Option<f64>,
    amps: Option<f64>,
    drop_volts: Option<f64>,
    drop_at_breaker_volts: Option<f64>,
    drop_limit_volts: Option<f64>,
    longest_run_feet: Option<f64>,
    verdict: &'static str,
}

impl<'a> From<&'a Row> for JsonRow<'a> {
    fn from(r: &'a Row) -> Self {
        let round = |v: Option<f64>| v.map(|v| (v * 1000.0).round() / 1000.0);
        JsonRow {
            pin: r.pin,
            name: &r.name,
            wire: r.wire.map(|w| w.to_string()),
            run_feet: round(r.run_feet),
            return_assumed: r.return_assumed,
            breaker_amps: r.breaker_amps,
            max_breaker_amps: r.max_breaker_amps,
            amps: round(r.amps),
            drop_volts: round(r.drop_volts),
            drop_at_breaker_volts: round(r.drop_at_breaker_volts),
            drop_limit_volts: r.drop_limit_volts,
            longest_run_feet: round(r.longest_run_feet),
            verdict: r.verdict.word(),
        }
    }
}

/// The load file's circuits: `--loads` must be there; the default path may not be
/// yet (every circuit is then "not entered", and a note says where to write them).
fn file_circuits(explicit: Option<&Path>) -> anyhow::Result<(Vec<LoadCircuit>, Option<String>)> {
    let path = match explicit {
        Some(p) => p.to_path_buf(),
        None => match crate::places::loads_path() {
            Some(p) if p.exists() => p,
            Some(p) => {
                return Ok((
                    Vec::new(),
                    Some(format!(
                        "no load file at {}: every circuit is \"not entered\"; write each \
                         circuit's wire there (`vpx-efis check` writes its template)",
                        p.display()
                    )),
                ));
            }
            None => return Ok((Vec::new(), Some("no place for a load file is known".into()))),
        },
    };
    let circuits = disk::read_circuits(&path).map_err(|e| UsageError(e.to_string()))?;
    Ok((circuits, Some(format!("wires from {}", path.display()))))
}

/// What the unit (or the backup) gives: its configuration, its currents now (by
/// device id, while on) and its bus voltage.
struct UnitSide {
    config: UnitConfig,
    amps: [Option<f64>; crate::protocol::device::DEVICE_COUNT],
    bus_volts: Option<f32>,
    from: String,
}

fn from_unit(port: &PortArgs) -> anyhow::Result<UnitSide> {
    let mut unit = connect(port)?;
    let (_, config) =
        read_with_progress(&mut unit.client, "reading").context("reading the unit's breakers")?;
    let status = unit
        .client
        .device_status()
        .context("asking the unit's currents (DEVICE_STATUS_QUERY)")?;
    let mut amps = [None; crate::protocol::device::DEVICE_COUNT];
    for (id, a) in amps.iter_mut().enumerate() {
        if status.on[id] {
            *a = Some(f64::from(status.current[id].value()));
        }
    }
    // SYSTEM_STATUS is a 1 Hz broadcast: two and a half seconds see one or say none.
    let bus_volts = unit
        .client
        .next_system_status(Duration::from_millis(2500))
        .map(|s| s.main_bus_volts.value());
    Ok(UnitSide {
        config,
        amps,
        bus_volts,
        from: unit.from.clone(),
    })
}

fn from_backup(path: &Path) -> anyhow::Result<UnitSide> {
    let (b, _) = crate::backup::load_made(path).map_err(|e| UsageError(e.to_string()))?;
    Ok(UnitSide {
        config: b.config,
        amps: [None; crate::protocol::device::DEVICE_COUNT],
        bus_volts: None,
        from: format!("the backup {}", path.display()),
    })
}

/// The rows and the system for a unit side and the file's circuits.
fn assess(u: &UnitSide, file: &[LoadCircuit]) -> (Vec<Row>, Option<SystemVoltage>) {
    let system = wire::system(
        wire::limit_volts(u.config.system.overvoltage_limit),
        u.bus_volts,
    );
    let configured = wiring::configured(&u.config);
    let unit: Vec<wiring::Circuit<'_>> = configured
        .iter()
        .map(|(id, name, breaker)| wiring::Circuit {
            id: *id,
            name: Some(name),
            breaker_amps: Some(*breaker),
            amps: u.amps[*id as usize],
        })
        .collect();
    (wiring::assess(file, &unit, system.as_ref()), system)
}

fn opt(v: Option<String>) -> String {
    v.unwrap_or_else(|| "-".into())
}

/// The rows as a table, then the findings and the notes.
pub fn text(rows: &[Row], system: Option<&SystemVoltage>) -> String {
    let header = [
        "Pin",
        "Name",
        "Wire",
        "Run",
        "Breaker",
        "Max",
        "Now",
        "Drop",
        "At breaker",
        "Verdict",
    ];
    let cells: Vec<[String; 10]> = rows
        .iter()
        .map(|r| {
            [
                r.pin.to_string(),
                r.name.clone(),
                opt(r.wire.map(|w| w.to_string())),
                opt(r.run_feet.map(wire::feet_text)),
                opt(r.breaker_amps.map(|b| format!("{b} A"))),
                opt(r
                    .max_breaker_amps
                    .map(|m| format!("{} A", wiring::amps_text(m)))),
                opt(r.amps.map(|a| format!("{a:.1} A"))),
                opt(r.drop_volts.map(|d| format!("{d:.2} V"))),
                opt(r.drop_at_breaker_volts.map(|d| format!("{d:.2} V"))),
                match r.verdict {
                    Verdict::Unprotected => "UNPROTECTED".into(),
                    Verdict::Drop => "DROP".into(),
                    v => v.word().into(),
                },
            ]
        })
        .collect();
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for c in &cells {
        for (w, s) in widths.iter_mut().zip(c) {
            *w = (*w).max(s.chars().count());
        }
    }
    let line = |c: &[String]| {
        let mut l = String::new();
        for (i, (s, w)) in c.iter().zip(&widths).enumerate() {
            if i > 0 {
                l.push_str("  ");
            }
            l.push_str(s);
            if i + 1 < c.len() {
                l.push_str(&" ".repeat(w - s.chars().count()));
            }
        }
        l.push('\n');
        l
    };
    let mut out = line(&header.map(String::from));
    for c in &cells {
        out.push_str(&line(c));
    }
    let findings: Vec<String> = rows
        .iter()
        .filter_map(|r| {
            r.unprotected_words()
                .map(|w| format!("UNPROTECTED {}: {w}.", r.pin))
                .or_else(|| r.drop_words().map(|w| format!("DROP {}: {w}.", r.pin)))
        })
        .collect();
    if !findings.is_empty() {
        out.push('\n');
        for f in findings {
            out.push_str(&f);
            out.push('\n');
        }
    }
    out.push('\n');
    for n in wiring::notes(rows, system) {
        out.push_str(&format!("Note: {n}.\n"));
    }
    out
}

pub fn run(args: WiresArgs) -> anyhow::Result<()> {
    let (file, about_file) = file_circuits(args.loads.as_deref())?;
    let unit = match &args.from_backup {
        Some(p) => from_backup(p)?,
        None => from_unit(&args.port)?,
    };
    let (rows, system) = assess(&unit, &file);
    if args.json {
        let json: Vec<JsonRow<'_>> = rows.iter().map(JsonRow::from).collect();
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        println!("Breakers from {}; {}.", unit.from, opt(about_file));
        print!("{}", text(&rows, system.as_ref()));
    }
    let unprotected = rows
        .iter()
        .filter(|r| r.verdict == Verdict::Unprotected)
        .count();
    let drops = rows.iter().filter(|r| r.verdict == Verdict::Drop).count();
    if unprotected + drops > 0 {
        return Err(Found(format!(
            "{unprotected} breaker(s) do not protect their wire, {drops} measured drop(s) are \
             over the limit"
        ))
        .into());
    }
    Ok(())
}

//! `vpx-efis log [--circuit NAME | --export FILE.html | --jsonl] [--json] [--limit N]`:
//! the aircraft's logbook, read-only.
//!
//! - no option: the aircraft's latest entries, newest first;
//! - `--circuit NAME`: that circuit's current at every check, as a small chart;
//! - `--export FILE.html`: one self-contained, printable page of the aircraft's
//!   records ([`crate::ui::aircraft_page`]);
//! - `--jsonl`: the audit log's JSON lines, as its files had them;
//! - `--json`: the entries, or the circuit's history, as JSON.
//!
//! The aircraft and the file are the global `--aircraft` and `--logbook` (their
//! environment variables, their config keys); without `--aircraft`, the records kept
//! under no registration.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use serde::Serialize;

use crate::app::log_views;
use crate::logbook::query::{self, time_of};
use crate::logbook::{Logbook, Mode};
use crate::program::UsageError;

#[derive(Debug, Args)]
pub struct LogArgs {
    /// One circuit's current at every check (its name, as on the page; letter case
    /// does not matter), as a chart.
    #[arg(long, value_name = "NAME", conflicts_with_all = ["export", "jsonl"])]
    pub circuit: Option<String>,
    /// Write the aircraft's records as one printable HTML page.
    #[arg(long, value_name = "FILE.html", conflicts_with = "jsonl")]
    pub export: Option<PathBuf>,
    /// Print the audit log (every command sent to the unit) as JSON lines, oldest first.
    #[arg(long, conflicts_with = "json")]
    pub jsonl: bool,
    /// Print as JSON instead of words.
    #[arg(long)]
    pub json: bool,
    /// How many of the latest entries to list.
    #[arg(long, default_value_t = 30, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub limit: u32,
}

/// Where the logbook is and whose records to read: the global options' choice.
fn open() -> anyhow::Result<(Logbook, Option<String>)> {
    let Some(target) = crate::logbook::target() else {
        return Err(UsageError(
            "no logbook: there is no config folder on this system to keep it in; give \
             --logbook FILE"
                .into(),
        )
        .into());
    };
    let book = Logbook::open(&target.path, Mode::ReadOnly)?;
    Ok((book, target.aircraft))
}

fn whose(aircraft: Option<&str>) -> String {
    aircraft.map_or_else(
        || "the records kept under no registration (--aircraft not given)".into(),
        |a| a.to_string(),
    )
}

pub fn run(args: LogArgs) -> anyhow::Result<()> {
    let (book, aircraft) = open()?;
    let aircraft = aircraft.as_deref();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    if args.jsonl {
        let which = crate::logbook::jsonl::Which {
            aircraft,
            ..Default::default()
        };
        let sent =
            crate::logbook::jsonl::audit_lines(&book, &which, |line| writeln!(out, "{line}"))?;
        // A closed pipe (`| head`) ends the listing; it is no error.
        match sent {
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
            other => {
                other?;
            }
        }
        return Ok(());
    }
    if let Some(name) = &args.circuit {
        return circuit(&book, aircraft, name, args.json, &mut out);
    }
    if let Some(path) = &args.export {
        let page = log_views::page(&book, aircraft)?;
        write_export(path, &log_views::html(&page))?;
        writeln!(
            out,
            "Wrote {}: {} checks, {} settings changed, {} firmware updates.",
            path.display(),
            page.checks.len(),
            page.settings.len(),
            page.firmware.len()
        )?;
        return Ok(());
    }
    entries(&book, aircraft, args.limit as usize, args.json, &mut out)
}

#[derive(Debug, Serialize)]
struct JsonEntry<'a> {
    time: &'a str,
    aircraft: Option<&'a str>,
    origin: &'a str,
    kind: &'a str,
    summary: &'a str,
}

fn entries(
    book: &Logbook,
    aircraft: Option<&str>,
    limit: usize,
    json: bool,
    out: &mut impl std::io::Write,
) -> anyhow::Result<()> {
    let rows = query::latest_entries(book, aircraft, limit)?;
    if json {
        let list: Vec<JsonEntry> = rows
            .iter()
            .map(|r| JsonEntry {
                time: &r.time,
                aircraft: r.aircraft.as_deref(),
                origin: &r.origin,
                kind: &r.kind,
                summary: &r.summary,
            })
            .collect();
        writeln!(out, "{}", serde_json::to_string_pretty(&list)?)?;
        return Ok(());
    }
    if rows.is_empty() {
        writeln!(
            out,
            "No entry for {} in {}.",
            whose(aircraft),
            book.path().display()
        )?;
        let known = query::aircraft(book)?;
        if !known.is_empty() {
            writeln!(out, "Aircraft in it (--aircraft): {}.", known.join(", "))?;
        }
        return Ok(());
    }
    writeln!(
        out,
        "The latest {} entries of {}, newest first (UTC):",
        rows.len(),
        whose(aircraft)
    )?;
    let kind_w = rows.iter().map(|r| r.kind.len()).max().unwrap_or(4);
    let origin_w = rows.iter().map(|r| r.origin.len()).max().unwrap_or(3);
    for r in &rows {
        let when = time_of(&r.time).map_or_else(|| r.time.clone(), log_views::minute);
        writeln!(
            out,
            "{when}  {:<kind_w$}  {:<origin_w$}  {}",
            r.kind,
            r.origin,
            one_line(&r.summary)
        )?;
    }
    Ok(())
}

/// A summary from the logbook on one line of the terminal.
fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

#[derive(Debug, Serialize)]
struct JsonReading<'a> {
    time: &'a str,
    name: &'a str,
    pin: &'a str,
    amps: Option<f64>,
    verdict: &'a str,
    finding: &'a str,
}

fn circuit(
    book: &Logbook,
    aircraft: Option<&str>,
    name: &str,
    json: bool,
    out: &mut impl std::io::Write,
) -> anyhow::Result<()> {
    let rows = query::circuit_history(book, aircraft, name)?;
    if rows.is_empty() {
        let known = query::circuit_names(book, aircraft)?;
        let known = if known.is_empty() {
            format!("no check of {} is recorded", whose(aircraft))
        } else {
            format!("the circuits its checks know: {}", known.join(", "))
        };
        return Err(UsageError(format!("no circuit named {name:?}: {known}")).into());
    }
    if json {
        let list: Vec<JsonReading> = rows
            .iter()
            .map(|r| JsonReading {
                time: &r.time,
                name: &r.name,
                pin: &r.pin,
                amps: r.amps,
                verdict: &r.verdict,
                finding: &r.finding,
            })
            .collect();
        writeln!(out, "{}", serde_json::to_string_pretty(&list)?)?;
        return Ok(());
    }
    let width = crossterm::terminal::size().map_or(80, |(w, _)| w).min(120);
    write!(out, "{}", log_views::chart(name, &rows, width))?;
    Ok(())
}

/// Writes the page whole or not at all; a path that cannot be written is named.
fn write_export(path: &Path, html: &str) -> anyhow::Result<()> {
    if path.is_dir() {
        return Err(UsageError(format!(
            "{}: a folder; give the file to write, e.g. {}",
            path.display(),
            path.join("records.html").display()
        ))
        .into());
    }
    crate::files::write_atomically(path, html.as_bytes())
        .with_context(|| format!("cannot write the export to {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_export_path_that_cannot_be_written_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("x");
        std::fs::write(&file, "").unwrap();
        let e = write_export(&file.join("records.html"), "<p>").unwrap_err();
        let t = format!("{e:#}");
        assert!(
            t.starts_with(&format!(
                "cannot write the export to {}",
                file.join("records.html").display()
            )),
            "{t}"
        );
        let e = write_export(dir.path(), "<p>").unwrap_err().to_string();
        assert!(e.contains("a folder; give the file to write"), "{e}");
        // A good path gets the page whole.
        let good = dir.path().join("records.html");
        write_export(&good, "<p>page</p>").unwrap();
        assert_eq!(std::fs::read_to_string(good).unwrap(), "<p>page</p>");
    }
}

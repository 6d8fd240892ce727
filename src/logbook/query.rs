//! The logbook's reads, for `vpx-efis log`, its export and the trend: an aircraft's
//! latest entries, its checks with each circuit's reading, one circuit's history, the
//! last check's currents, the settings changed and the firmware updates.
//!
//! An aircraft is its registration; `None` reads the records kept under no
//! registration (`--aircraft` not given), as they were recorded. Every read is one
//! statement on the indexes of [`super::schema`]; the writer's rows are read as they
//! are, a time as its text (`2026-12-04T18:20:01.123Z`).

use std::time::{Duration, SystemTime, UNIX_EPOCH};

use rusqlite::{OptionalExtension, params};

use super::{Error, Logbook};

/// One entry as the list shows it.
#[derive(Debug, Clone, PartialEq)]
pub struct EntryRow {
    pub id: i64,
    pub time: String,
    pub aircraft: Option<String>,
    pub origin: String,
    pub kind: String,
    pub summary: String,
}

/// One check, with what the export and the list need of it.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckRow {
    pub entry: i64,
    pub time: String,
    pub origin: String,
    pub summary: String,
    pub tally: String,
    pub interrupted: Option<String>,
    pub load_file: Option<String>,
    /// The unit's VERSION as the logbook knows it: "VP-X Pro 1.4".
    pub unit: Option<String>,
}

/// One circuit at one check, read back as it was recorded.
pub use super::record::CheckCircuit as CircuitRow;

/// One circuit's reading at one check, for its history.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryRow {
    pub entry: i64,
    pub time: String,
    pub name: String,
    pub pin: String,
    pub amps: Option<f64>,
    pub verdict: String,
    pub finding: String,
}

/// A setting changed (a setup write, or one setting of a restore).
#[derive(Debug, Clone, PartialEq)]
pub struct SettingRow {
    pub time: String,
    pub origin: String,
    pub setting: String,
    pub old: Option<String>,
    pub new: String,
    pub confirmed: bool,
}

/// A firmware update.
#[derive(Debug, Clone, PartialEq)]
pub struct FirmwareRow {
    pub time: String,
    pub sha256: String,
    pub before: Option<String>,
    pub after: Option<String>,
    pub outcome: String,
}

/// The logbook's time text as a time: `None` for text it did not write.
pub fn time_of(text: &str) -> Option<SystemTime> {
    // 2026-12-04T18:20:01.123Z
    let b = text.as_bytes();
    if b.len() < 20 || b[4] != b'-' || b[10] != b'T' || !text.ends_with('Z') {
        return None;
    }
    let num = |r: std::ops::Range<usize>| text.get(r)?.parse::<i64>().ok();
    let (y, mo, d) = (num(0..4)?, num(5..7)?, num(8..10)?);
    let (h, mi, s) = (num(11..13)?, num(14..16)?, num(17..19)?);
    let ms = if b.get(19) == Some(&b'.') {
        num(20..23).unwrap_or(0)
    } else {
        0
    };
    // Days from the civil date (Howard Hinnant's algorithm).
    let y = if mo <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (mo + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146_097 + doe - 719_468;
    let secs = days * 86_400 + h * 3600 + mi * 60 + s;
    let secs = u64::try_from(secs).ok()?;
    Some(UNIX_EPOCH + Duration::from_secs(secs) + Duration::from_millis(ms as u64))
}

/// Reads a row into `$t`, its fields from the statement's columns in the order named.
macro_rules! row {
    ($t:ident { $($field:ident),+ $(,)? }) => {
        |r: &rusqlite::Row<'_>| {
            let mut column = 0..;
            Ok($t { $($field: r.get(column.next().unwrap_or_default())?),+ })
        }
    };
}

/// Every row `sql` gives for `params`, each read by `row`.
fn all<T, P: rusqlite::Params>(
    book: &Logbook,
    sql: &str,
    params: P,
    row: impl FnMut(&rusqlite::Row<'_>) -> rusqlite::Result<T>,
) -> Result<Vec<T>, Error> {
    let mut st = book.conn().prepare(sql).map_err(|e| book.error(e))?;
    st.query_map(params, row)
        .and_then(Iterator::collect)
        .map_err(|e| book.error(e))
}

/// The registrations the logbook knows, in order.
pub fn aircraft(book: &Logbook) -> Result<Vec<String>, Error> {
    all(
        book,
        "SELECT registration FROM aircraft ORDER BY registration",
        [],
        |r| r.get(0),
    )
}

/// The aircraft's `limit` latest entries, newest first.
pub fn latest_entries(
    book: &Logbook,
    aircraft: Option<&str>,
    limit: usize,
) -> Result<Vec<EntryRow>, Error> {
    all(
        book,
        "SELECT id, time, aircraft, origin, kind, summary FROM entries
         WHERE aircraft IS ?1 ORDER BY time DESC, id DESC LIMIT ?2",
        params![aircraft, i64::try_from(limit).unwrap_or(i64::MAX)],
        row!(EntryRow {
            id,
            time,
            aircraft,
            origin,
            kind,
            summary
        }),
    )
}

/// The aircraft's checks, oldest first.
pub fn checks(book: &Logbook, aircraft: Option<&str>) -> Result<Vec<CheckRow>, Error> {
    all(
        book,
        "SELECT e.id, e.time, e.origin, e.summary, c.tally, c.interrupted, c.load_file,
                u.hardware || ' ' || u.software
         FROM entries e JOIN checks c ON c.entry = e.id
         LEFT JOIN units u ON u.id = e.unit
         WHERE e.aircraft IS ?1 AND e.kind = 'check'
         ORDER BY e.time, e.id",
        params![aircraft],
        row!(CheckRow {
            entry,
            time,
            origin,
            summary,
            tally,
            interrupted,
            load_file,
            unit
        }),
    )
}

/// Every circuit of check `entry`, in device order.
pub fn check_circuits(book: &Logbook, entry: i64) -> Result<Vec<CircuitRow>, Error> {
    all(
        book,
        "SELECT device, name, pin, breaker, switch, amps, verdict, finding
         FROM check_circuits WHERE entry = ?1 ORDER BY device",
        params![entry],
        row!(CircuitRow {
            device,
            name,
            pin,
            breaker,
            switch,
            amps,
            verdict,
            finding
        }),
    )
}

/// The circuit named `name` (letter case and the blanks around it ignored, as the
/// trend matches names) at every check of the aircraft, oldest first.
pub fn circuit_history(
    book: &Logbook,
    aircraft: Option<&str>,
    name: &str,
) -> Result<Vec<HistoryRow>, Error> {
    all(
        book,
        "SELECT e.id, e.time, c.name, c.pin, c.amps, c.verdict, c.finding
         FROM check_circuits c JOIN entries e ON e.id = c.entry
         WHERE e.aircraft IS ?1 AND lower(trim(c.name)) = lower(trim(?2))
         ORDER BY e.time, e.id, c.device",
        params![aircraft, name],
        row!(HistoryRow {
            entry,
            time,
            name,
            pin,
            amps,
            verdict,
            finding
        }),
    )
}

/// The names of every circuit the aircraft's checks measured or listed, for the
/// error that names the known ones.
pub fn circuit_names(book: &Logbook, aircraft: Option<&str>) -> Result<Vec<String>, Error> {
    all(
        book,
        "SELECT DISTINCT c.name FROM check_circuits c JOIN entries e ON e.id = c.entry
         WHERE e.aircraft IS ?1 ORDER BY c.name COLLATE NOCASE",
        params![aircraft],
        |r| r.get(0),
    )
}

/// The last check's time and circuits, for the trend (`check::trend`).
#[derive(Debug, Clone, PartialEq)]
pub struct LastCheckRows {
    pub time: String,
    pub circuits: Vec<CircuitRow>,
}

/// The aircraft's last check that measured any circuit, as the trend reads it.
/// A check that measured nothing (stopped before its circuits, or with that step
/// skipped) is passed over: its "last current" would be none for every circuit.
pub fn last_check(book: &Logbook, aircraft: Option<&str>) -> Result<Option<LastCheckRows>, Error> {
    let found: Option<(i64, String)> = book
        .conn()
        .query_row(
            "SELECT e.id, e.time FROM entries e
             WHERE e.aircraft IS ?1 AND e.kind = 'check'
               AND EXISTS (SELECT 1 FROM check_circuits c
                           WHERE c.entry = e.id AND c.amps IS NOT NULL)
             ORDER BY e.time DESC, e.id DESC LIMIT 1",
            params![aircraft],
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
        .optional()
        .map_err(|e| book.error(e))?;
    let Some((entry, time)) = found else {
        return Ok(None);
    };
    Ok(Some(LastCheckRows {
        time,
        circuits: check_circuits(book, entry)?,
    }))
}

/// The settings changed on the aircraft's unit (setup writes and restores), oldest
/// first.
pub fn setting_changes(book: &Logbook, aircraft: Option<&str>) -> Result<Vec<SettingRow>, Error> {
    all(
        book,
        "SELECT e.time, e.origin, s.setting, s.old, s.new, s.confirmed
         FROM setting_changes s JOIN entries e ON e.id = s.entry
         WHERE e.aircraft IS ?1 ORDER BY e.time, e.id, s.rowid",
        params![aircraft],
        row!(SettingRow {
            time,
            origin,
            setting,
            old,
            new,
            confirmed
        }),
    )
}

/// The aircraft's firmware updates, oldest first.
pub fn firmware(book: &Logbook, aircraft: Option<&str>) -> Result<Vec<FirmwareRow>, Error> {
    all(
        book,
        "SELECT e.time, f.image_sha256, f.version_before, f.version_after, f.outcome
         FROM firmware f JOIN entries e ON e.id = f.entry
         WHERE e.aircraft IS ?1 ORDER BY e.time, e.id",
        params![aircraft],
        row!(FirmwareRow {
            time,
            sha256,
            before,
            after,
            outcome
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_logbooks_time_text_reads_back_as_the_time_it_was() {
        // 2026-12-01T18:30:12.345Z is 1_796_149_812.345 s (as report.rs's stem test).
        let t = time_of("2026-12-01T18:30:12.345Z").unwrap();
        assert_eq!(t, UNIX_EPOCH + Duration::from_millis(1_796_149_812_345));
        assert_eq!(crate::utc::utc_text(t), "2026-12-01T18:30:12.345Z");
        // A leap day and the turn of a year, against utc_text.
        for s in [951_782_400_000u64, 1_709_164_800_500, 1_798_761_599_999] {
            let t = UNIX_EPOCH + Duration::from_millis(s);
            assert_eq!(time_of(&crate::utc::utc_text(t)), Some(t));
        }
        assert_eq!(time_of("yesterday"), None);
        assert_eq!(time_of("2026-12-01 18:30:12Z"), None);
    }
}

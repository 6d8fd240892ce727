//! The audit log as the JSON lines its files had before it joined the logbook
//! ([`crate::audit`]): `vpx-efis log --jsonl` prints these, one object a line, oldest
//! first, for anyone whose tools read the files.

use rusqlite::params;

use super::{Error, Logbook};

/// Which audit lines: every one, or an aircraft's (by registration), or a time
/// window (text times as the logbook holds them, `2026-12-04T…Z`, either end open).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Which<'a> {
    pub aircraft: Option<&'a str>,
    pub since: Option<&'a str>,
    pub until: Option<&'a str>,
}

/// Calls `each` with every audit line chosen by `which`, oldest first, each one
/// JSON object without its line break, keys as the audit files had them. Stops at `each`'s first error (a closed pipe) and returns it. Gives
/// how many lines went.
pub fn audit_lines(
    book: &Logbook,
    which: &Which,
    mut each: impl FnMut(&str) -> std::io::Result<()>,
) -> Result<Result<usize, std::io::Error>, Error> {
    let mut st = book
        .conn()
        .prepare(
            "SELECT e.time, e.origin, c.command, c.frame, c.result, c.run, c.run_origin,
                    c.moves, c.seconds
             FROM commands c JOIN entries e ON e.id = c.entry
             WHERE (?1 IS NULL OR e.aircraft = ?1)
               AND (?2 IS NULL OR e.time >= ?2)
               AND (?3 IS NULL OR e.time < ?3)
             ORDER BY e.time, e.id",
        )
        .map_err(|e| book.error(e))?;
    let mut rows = st
        .query(params![which.aircraft, which.since, which.until])
        .map_err(|e| book.error(e))?;
    let mut n = 0;
    while let Some(r) = rows.next().map_err(|e| book.error(e))? {
        let line = (|| -> rusqlite::Result<String> {
            // Keys in the order serde_json gives them (sorted), as the files had.
            let mut v = serde_json::Map::new();
            v.insert("time".into(), r.get::<_, String>(0)?.into());
            v.insert("origin".into(), r.get::<_, String>(1)?.into());
            v.insert("command".into(), r.get::<_, String>(2)?.into());
            if let Some(f) = r.get::<_, Option<String>>(3)? {
                v.insert("frame".into(), f.into());
            }
            v.insert("result".into(), r.get::<_, String>(4)?.into());
            if let Some(x) = r.get::<_, Option<String>>(5)? {
                v.insert("run".into(), x.into());
            }
            if let Some(x) = r.get::<_, Option<String>>(6)? {
                v.insert("run_origin".into(), x.into());
            }
            if let Some(x) = r.get::<_, Option<i64>>(7)? {
                v.insert("moves".into(), x.into());
            }
            if let Some(x) = r.get::<_, Option<f64>>(8)? {
                v.insert("seconds".into(), x.into());
            }
            Ok(serde_json::Value::Object(v).to_string())
        })()
        .map_err(|e| book.error(e))?;
        if let Err(e) = each(&line) {
            return Ok(Err(e));
        }
        n += 1;
    }
    Ok(Ok(n))
}

/// Every audit line of the logbook at `path`, oldest first (tests, and tools that
/// want them all at once).
pub fn all_audit_lines(path: &std::path::Path) -> Result<Vec<String>, Error> {
    let book = Logbook::open(path, super::Mode::ReadOnly)?;
    let mut out = Vec::new();
    let _ = audit_lines(&book, &Which::default(), |l| {
        out.push(l.to_string());
        Ok(())
    })?;
    Ok(out)
}

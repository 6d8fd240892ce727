//! The aircraft's logbook: every check, change and update, kept in one SQLite file
//! for the life of the aircraft.
//!
//! - [`schema`]: the tables, their version and the migrations.
//! - [`record`]: what is recorded, as plain data; [`writer`]: the thread that writes
//!   it, off the hot path ([`Recorder`]).
//! - [`jsonl`]: the audit log as the JSON lines its files had.
//! - [`Logbook::open`]: the file, read-write or read-only, several processes at once
//!   (the page and a gateway): WAL, and a busy timeout before "locked" is said.
//!
//! Its own faults lose nothing already written: a file that is not a logbook (or is
//! damaged) is named and left as it is, never written over; one written by a newer
//! program is opened read-only, saying why; one locked by another process is waited
//! for ([`BUSY_TIMEOUT`]) and then said to be locked.

pub mod jsonl;
pub mod query;
pub mod record;
pub mod schema;
pub mod writer;

pub use record::{Entry, What};
pub use writer::{Recorder, record_now};

use std::path::{Path, PathBuf};
use std::time::Duration;

use rusqlite::{Connection, ErrorCode, OpenFlags};

/// How long a write waits for another process's write to finish before the logbook
/// is called locked. A check's record is a few hundred rows, written in
/// milliseconds; a gateway and a page share the file without ever waiting this long
/// unless something holds it open in a transaction (a person in `sqlite3`).
pub const BUSY_TIMEOUT: Duration = Duration::from_secs(5);

/// How long a program on its way out waits for its last records to be written.
pub const SHUTDOWN_WAIT: Duration = Duration::from_secs(2);

/// Where to record, and under which aircraft.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Target {
    pub path: PathBuf,
    /// A registration, checked ([`registration`]); `None`: the unit's records.
    pub aircraft: Option<String>,
}

static TARGET: std::sync::OnceLock<Option<Target>> = std::sync::OnceLock::new();

/// The command line's choice (`--logbook`, `--aircraft`, their environment variables
/// and config keys), set once by [`crate::cli`] before a command runs.
pub fn set_target(target: Option<Target>) {
    let _ = TARGET.set(target);
}

/// Where this process records: the command line's choice, else
/// [`Target::beside_config`] (a program that never went through the command line).
pub fn target() -> Option<Target> {
    match TARGET.get() {
        Some(t) => t.clone(),
        None => Target::beside_config(),
    }
}

impl Target {
    /// The logbook beside the config file ([`crate::places::logbook_path`]), under
    /// the unit alone.
    pub fn beside_config() -> Option<Target> {
        crate::places::logbook_path().map(|path| Target {
            path,
            aircraft: None,
        })
    }
}

/// An aircraft's registration as a person types it (`n123ab`, `G-ABCD`), upper case,
/// or a refusal in words. ICAO Annex 7's marks: a nationality mark and a registration
/// mark, letters and digits, with at most one hyphen between them; 2 to 10
/// characters, at least one a letter.
pub fn registration(text: &str) -> Result<String, String> {
    let t = text.trim().to_ascii_uppercase();
    let example = "write the registration as painted on the aircraft, e.g. N123AB or G-ABCD";
    if t.is_empty() {
        return Err(format!("an empty registration: {example}"));
    }
    if let Some(c) = t.chars().find(|c| !c.is_ascii_alphanumeric() && *c != '-') {
        return Err(format!(
            "{text:?} is not a registration: {c:?} is not a letter, digit or hyphen; {example}"
        ));
    }
    if !(2..=10).contains(&t.len()) {
        return Err(format!(
            "{text:?} is not a registration: {} characters, where a registration has 2 to 10; {example}",
            t.len()
        ));
    }
    if t.starts_with('-') || t.ends_with('-') || t.matches('-').count() > 1 {
        return Err(format!(
            "{text:?} is not a registration: a hyphen goes only between the nationality mark and the rest; {example}"
        ));
    }
    if !t.chars().any(|c| c.is_ascii_alphabetic()) {
        return Err(format!(
            "{text:?} is not a registration: it has no letter; {example}"
        ));
    }
    Ok(t)
}

/// What the caller wants to do with the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Record: made if missing, migrated to [`schema::VERSION`] if older.
    ReadWrite,
    /// Only read (`vpx-efis log`): never made, never migrated, never written.
    ReadOnly,
}

/// Why a logbook could not be opened, each with the file's path in its words.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Garbage, another kind of file, or a damaged logbook. Never written over.
    #[error(
        "{}: not a logbook, or a damaged one ({detail}); it is left as it is and nothing is recorded in it",
        path.display()
    )]
    Corrupt { path: PathBuf, detail: String },
    /// Another process held it for longer than the busy timeout.
    #[error(
        "{}: locked by another program (waited {} s); nothing is recorded in it until it is free",
        path.display(), waited.as_secs()
    )]
    Locked { path: PathBuf, waited: Duration },
    /// Read-only, and there is no file.
    #[error("{}: no logbook there (nothing has been recorded yet)", path.display())]
    Missing { path: PathBuf },
    /// Read-only, and its schema is older than this program's: it is brought up to
    /// date the next time a program records in it.
    #[error(
        "{}: a logbook of schema {found}, older than this program's {}; open it once with the page to bring it up to date",
        path.display(), schema::VERSION
    )]
    Older { path: PathBuf, found: u32 },
    /// Its folder could not be made.
    #[error("{}: cannot make its folder: {source}", path.display())]
    Folder {
        path: PathBuf,
        source: std::io::Error,
    },
    /// Anything else SQLite said (a full disk, no permission), with its words.
    #[error("{}: {source}", path.display())]
    Sqlite {
        path: PathBuf,
        source: rusqlite::Error,
    },
}

impl Error {
    /// The error SQLite gave for `path`, named for what it means to a person.
    pub fn of(path: &Path, e: rusqlite::Error, waited: Duration) -> Error {
        let path = path.to_path_buf();
        match e.sqlite_error_code() {
            Some(ErrorCode::NotADatabase | ErrorCode::DatabaseCorrupt) => Error::Corrupt {
                path,
                detail: e.to_string(),
            },
            Some(ErrorCode::DatabaseBusy | ErrorCode::DatabaseLocked) => {
                Error::Locked { path, waited }
            }
            _ => Error::Sqlite { path, source: e },
        }
    }
}

/// An open logbook.
pub struct Logbook {
    conn: Connection,
    path: PathBuf,
    /// Why it is read-only, when it is: asked for, or written by a newer program.
    read_only: Option<String>,
    busy: Duration,
}

impl std::fmt::Debug for Logbook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Logbook")
            .field("path", &self.path)
            .field("read_only", &self.read_only)
            .finish()
    }
}

impl Logbook {
    /// Opens the logbook at `path` with the usual busy timeout ([`BUSY_TIMEOUT`]).
    pub fn open(path: &Path, mode: Mode) -> Result<Logbook, Error> {
        Logbook::open_with(path, mode, BUSY_TIMEOUT)
    }

    /// As [`Logbook::open`], waiting at most `busy` for another process's lock.
    pub fn open_with(path: &Path, mode: Mode, busy: Duration) -> Result<Logbook, Error> {
        Logbook::open_migrating(path, mode, busy, schema::MIGRATIONS)
    }

    /// As [`Logbook::open_with`], with the migrations given (the tests' next schema).
    pub fn open_migrating(
        path: &Path,
        mode: Mode,
        busy: Duration,
        migrations: &[schema::Migration],
    ) -> Result<Logbook, Error> {
        let err = |e| Error::of(path, e, busy);
        let flags = match mode {
            Mode::ReadWrite => {
                if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                    std::fs::create_dir_all(dir).map_err(|source| Error::Folder {
                        path: path.to_path_buf(),
                        source,
                    })?;
                }
                OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_CREATE
            }
            Mode::ReadOnly => {
                if !path.exists() {
                    return Err(Error::Missing {
                        path: path.to_path_buf(),
                    });
                }
                OpenFlags::SQLITE_OPEN_READ_ONLY
            }
        } | OpenFlags::SQLITE_OPEN_NO_MUTEX;
        let conn = Connection::open_with_flags(path, flags).map_err(err)?;
        conn.busy_timeout(busy).map_err(err)?;
        // The first read of the file: garbage in its header is found here, before
        // anything could be written to it.
        let found = user_version(&conn).map_err(err)?;
        let latest = migrations.last().map_or(0, |m| m.to);
        let mut book = Logbook {
            conn,
            path: path.to_path_buf(),
            read_only: None,
            busy,
        };
        match mode {
            Mode::ReadOnly => {
                book.read_only = Some("opened to read".into());
                if found < latest {
                    return Err(Error::Older {
                        path: path.to_path_buf(),
                        found,
                    });
                }
            }
            Mode::ReadWrite if found > latest => {
                let by = book
                    .written_by()
                    .unwrap_or_else(|| "a newer program".into());
                book.read_only = Some(format!(
                    "written by {by} (logbook schema {found}; this program knows {latest}): opened read-only, nothing is recorded"
                ));
                book.conn
                    .pragma_update(None, "query_only", true)
                    .map_err(err)?;
            }
            Mode::ReadWrite => {
                // WAL: the page and a gateway write while `vpx-efis log` reads.
                // FULL: a committed record survives a pulled plug, not only a kill;
                // the records are few and batched, so the cost is not felt.
                book.conn
                    .pragma_update(None, "journal_mode", "WAL")
                    .map_err(err)?;
                book.conn
                    .pragma_update(None, "synchronous", "FULL")
                    .map_err(err)?;
                book.conn
                    .pragma_update(None, "foreign_keys", true)
                    .map_err(err)?;
                book.migrate(migrations).map_err(err)?;
            }
        }
        Ok(book)
    }

    /// Runs each migration past the file's version, each in its own transaction,
    /// reading the version again inside it (another process may have just done it).
    fn migrate(&mut self, migrations: &[schema::Migration]) -> rusqlite::Result<()> {
        for m in migrations {
            if user_version(&self.conn)? >= m.to {
                continue;
            }
            let tx = self
                .conn
                .transaction_with_behavior(rusqlite::TransactionBehavior::Immediate)?;
            if user_version(&tx)? < m.to {
                tx.execute_batch(m.sql)?;
                tx.execute(
                    "INSERT INTO about (key, value) VALUES ('written_by', ?1)
                     ON CONFLICT (key) DO UPDATE SET value = excluded.value",
                    [concat!("vpx-efis ", env!("CARGO_PKG_VERSION"))],
                )?;
                tx.pragma_update(None, "user_version", m.to)?;
            }
            tx.commit()?;
        }
        Ok(())
    }

    /// The program that last brought the schema up, as `about` names it.
    fn written_by(&self) -> Option<String> {
        self.conn
            .query_row(
                "SELECT value FROM about WHERE key = 'written_by'",
                [],
                |r| r.get(0),
            )
            .ok()
    }

    /// Why nothing can be recorded in it, if that is so.
    pub fn read_only(&self) -> Option<&str> {
        self.read_only.as_deref()
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The schema version of the file.
    pub fn version(&self) -> Result<u32, Error> {
        user_version(&self.conn).map_err(|e| self.error(e))
    }

    /// The connection, for the readers ([`query`](self)) and the writer.
    pub fn conn(&self) -> &Connection {
        &self.conn
    }

    pub(crate) fn conn_mut(&mut self) -> &mut Connection {
        &mut self.conn
    }

    /// What SQLite said, named for this file.
    pub fn error(&self, e: rusqlite::Error) -> Error {
        Error::of(&self.path, e, self.busy)
    }

    /// SQLite's own check of every page and index (`PRAGMA integrity_check`):
    /// `Ok(())`, or what is wrong as a [`Error::Corrupt`].
    pub fn integrity_check(&self) -> Result<(), Error> {
        let mut st = self
            .conn
            .prepare("PRAGMA integrity_check")
            .map_err(|e| self.error(e))?;
        let lines: Vec<String> = st
            .query_map([], |r| r.get(0))
            .and_then(Iterator::collect)
            .map_err(|e| self.error(e))?;
        if lines == ["ok"] {
            Ok(())
        } else {
            Err(Error::Corrupt {
                path: self.path.clone(),
                detail: lines.join("; "),
            })
        }
    }
}

fn user_version(conn: &Connection) -> rusqlite::Result<u32> {
    conn.query_row("PRAGMA user_version", [], |r| r.get(0))
}

#[cfg(test)]
mod tests;

//! The logbook's tables, and the migrations from one version of them to the next.
//!
//! The version is SQLite's own `PRAGMA user_version`: 0 is a new, empty file, and
//! [`MIGRATIONS`]`[i]` takes a logbook from version `i` to `i + 1`, each in one
//! transaction of its own (a kill half-way leaves the older version, whole). A file
//! whose version is above [`VERSION`] was written by a newer program: it is opened
//! read-only, never migrated down, and the table `about` names that program.
//!
//! Decisions, version 1:
//! - **One row per record in `entries`**, whatever it is (a check, a backup, a
//!   command sent, a fault seen): its time, the aircraft, the unit, who did it
//!   (`origin`), what it is (`kind`) and a line in words (`summary`). "An
//!   aircraft's latest entries" is then one index walk (`entries_aircraft_time`),
//!   whatever the mix of kinds. The details live in a table per kind, keyed by the
//!   entry's id (`checks`, `check_circuits`, `backups`, `setting_changes`,
//!   `firmware`, `commands`, `faults`).
//! - **Times** are text, UTC to the millisecond, `2026-12-04T18:20:01.123Z`
//!   ([`crate::utc::utc_text`]): they sort as text, and a person reading the file
//!   with `sqlite3` reads them as they are.
//! - **The aircraft** is its registration, upper case (`N123AB`, `G-ABCD`).
//!   `entries.aircraft` is NULL when none was named (`--aircraft`): the record then
//!   belongs to the unit alone, and "the aircraft's entries" are the unit's.
//! - **The unit** has no serial number on the wire, so it is known by what it tells:
//!   its VERSION (ICD Table 11: hardware, software major.minor) and the names its
//!   circuits hold, in device-id order. `units.identity` is those, as text, and is
//!   unique: the same unit seen again is the same row. Renaming a circuit makes a
//!   new identity; the `installs` rows keep the history readable either way.
//!   `entries.unit` is NULL while the unit has not answered VERSION.
//! - **Which unit was in which aircraft when**: `installs`, one row per pair, with
//!   the first and last time they were seen together. "This unit was in N123AB
//!   until 2026-11-03" is the row of the unit with another aircraft and the latest
//!   `last_seen`.
//! - **A check** keeps what its report shows: each circuit (`check_circuits`: name,
//!   pin, breaker, switch, measured amperes or NULL, verdict and the finding in
//!   words), each switch input and each motor (`check_switches`, `check_motors`),
//!   the load analysis's figures (`check_loads`, one row per phase, and the
//!   alternator and battery on `checks`) and the load file's text as it was. "A
//!   circuit's current at every check" is `check_circuits_name`: by name, since
//!   that is what the person asks for and what survives a circuit moving pins.
//! - **Verdicts** are the check's marks as its report prints them: `PASS`, `WARN`,
//!   `FAIL`, `SKIPPED`, `NOT RUN` (`check::state::Mark::word`).
//! - **A setup write and a restore** are both changes of settings: a setup write is
//!   one entry with one `setting_changes` row, a restore one entry with a row per
//!   setting it changed; `confirmed` is whether the unit's read-back matched.
//! - **The audit log** (every command sent through the stop gate, [`crate::audit`])
//!   is `commands`: the same fields as its JSON lines (`command`, `frame`, `result`,
//!   and for a motor run `run`, `run_origin`, `moves`, `seconds`), so `log --jsonl`
//!   gives back the lines the files had. A DEVICE_CLEAR is kind `reset`, a motor run's
//!   start and stop kind `run`, every other command kind `command`.
//! - Text a person wrote or a file held (a backup, a load file) is kept as it was,
//!   whole, never parsed into columns: the logbook must be able to show it as it was
//!   in ten years, whatever this program then reads.

/// The schema this program writes.
pub const VERSION: u32 = 1;

/// One step: the SQL taking a logbook from the version before to the next.
#[derive(Debug, Clone, Copy)]
pub struct Migration {
    /// The version it leaves the file at.
    pub to: u32,
    /// The statements, run in one transaction.
    pub sql: &'static str,
}

/// Every step from an empty file to [`VERSION`], in order.
pub const MIGRATIONS: &[Migration] = &[Migration { to: 1, sql: V1 }];

/// Kinds of entry (`entries.kind`).
pub mod kind {
    pub const CHECK: &str = "check";
    pub const BACKUP: &str = "backup";
    pub const RESTORE: &str = "restore";
    pub const SETTING: &str = "setting";
    pub const FIRMWARE: &str = "firmware";
    pub const COMMAND: &str = "command";
    pub const RESET: &str = "reset";
    pub const RUN: &str = "run";
    pub const FAULT: &str = "fault";
}

/// Version 1.
const V1: &str = r#"
-- What wrote this file, for a program too old to migrate it ('written_by').
CREATE TABLE about (
    key   TEXT PRIMARY KEY,
    value TEXT NOT NULL
);

CREATE TABLE aircraft (
    registration TEXT PRIMARY KEY,   -- 'N123AB', upper case
    first_seen   TEXT NOT NULL
);

CREATE TABLE units (
    id          INTEGER PRIMARY KEY,
    identity    TEXT NOT NULL UNIQUE,    -- hardware, software and names, as one text
    hardware    TEXT NOT NULL,           -- 'VP-X Pro'
    software    TEXT NOT NULL,           -- '1.4'
    names       TEXT NOT NULL,           -- JSON array of the circuits' names, by device id
    first_seen  TEXT NOT NULL
);

-- Which unit was in which aircraft, from when until when it was seen there.
CREATE TABLE installs (
    unit        INTEGER NOT NULL REFERENCES units(id),
    aircraft    TEXT NOT NULL REFERENCES aircraft(registration),
    first_seen  TEXT NOT NULL,
    last_seen   TEXT NOT NULL,
    PRIMARY KEY (unit, aircraft)
);

CREATE TABLE entries (
    id        INTEGER PRIMARY KEY,
    time      TEXT NOT NULL,                           -- UTC, '2026-12-04T18:20:01.123Z'
    aircraft  TEXT REFERENCES aircraft(registration),  -- NULL: not named
    unit      INTEGER REFERENCES units(id),            -- NULL: VERSION not known yet
    origin    TEXT NOT NULL,    -- key, check, setup, remote, xfsp, command line, page, panic, unit (a fault it showed)
    kind      TEXT NOT NULL,    -- check, backup, restore, setting, firmware, command, reset, run, fault
    summary   TEXT NOT NULL     -- one line in words
);
CREATE INDEX entries_aircraft_time ON entries (aircraft, time);
CREATE INDEX entries_unit_time ON entries (unit, time);
CREATE INDEX entries_kind_time ON entries (kind, time);

CREATE TABLE checks (
    entry              INTEGER PRIMARY KEY REFERENCES entries(id),
    port               TEXT NOT NULL,
    program            TEXT NOT NULL,     -- this program's version
    tally              TEXT NOT NULL,     -- '1 failed, 14 passed'
    interrupted        TEXT,              -- why it stopped early; NULL: it finished
    report             TEXT,              -- the report file's path, if written
    load_path          TEXT,
    load_file          TEXT,              -- the load file's text as it was
    alternator_amps    REAL,
    battery_amp_hours  REAL,
    battery_usable     REAL
);

CREATE TABLE check_circuits (
    entry      INTEGER NOT NULL REFERENCES checks(entry),
    device     INTEGER NOT NULL,   -- device id, 0-based as on the wire
    name       TEXT NOT NULL,
    pin        TEXT NOT NULL,
    breaker    INTEGER,            -- amperes
    switch     TEXT,               -- 'switch 3', 'dimmer', NULL: none
    amps       REAL,               -- measured; NULL: none
    verdict    TEXT NOT NULL,      -- PASS, WARN, FAIL, SKIPPED, NOT RUN
    finding    TEXT NOT NULL,      -- in words
    PRIMARY KEY (entry, device)
);
CREATE INDEX check_circuits_name ON check_circuits (name, entry);

CREATE TABLE check_switches (
    entry      INTEGER NOT NULL REFERENCES checks(entry),
    input      TEXT NOT NULL,      -- 'switch 3'
    circuits   TEXT NOT NULL,      -- the circuits on it, in words
    verdict    TEXT NOT NULL,
    finding    TEXT NOT NULL,
    PRIMARY KEY (entry, input)
);

CREATE TABLE check_motors (
    entry      INTEGER NOT NULL REFERENCES checks(entry),
    motor      TEXT NOT NULL,      -- 'pitch trim', 'roll trim', 'flaps'
    positions  TEXT NOT NULL,      -- the counts it went through, '20 200 20'
    verdict    TEXT NOT NULL,
    finding    TEXT NOT NULL,
    PRIMARY KEY (entry, motor)
);

-- The load analysis, one row per phase.
CREATE TABLE check_loads (
    entry              INTEGER NOT NULL REFERENCES checks(entry),
    phase              TEXT NOT NULL,  -- 'cruise', 'emergency'
    amps               REAL NOT NULL,
    margin_percent     REAL,           -- on the alternator; NULL for the emergency phase
    endurance_minutes  REAL,           -- on the battery
    level              TEXT NOT NULL,  -- ok, warning, failed
    PRIMARY KEY (entry, phase)
);

CREATE TABLE backups (
    entry  INTEGER PRIMARY KEY REFERENCES entries(id),
    path   TEXT,                 -- where the file went; NULL: not written
    text   TEXT NOT NULL         -- the backup file's text
);

-- A setup write (one row) or a restore (a row per setting it changed).
CREATE TABLE setting_changes (
    entry      INTEGER NOT NULL REFERENCES entries(id),
    setting    TEXT NOT NULL,      -- 'Landing Lt breaker', 'flaps: travel time'
    old        TEXT,               -- NULL: not known
    new        TEXT NOT NULL,
    confirmed  INTEGER NOT NULL    -- 1: the unit's read-back matched
);
CREATE INDEX setting_changes_entry ON setting_changes (entry);

CREATE TABLE firmware (
    entry           INTEGER PRIMARY KEY REFERENCES entries(id),
    image_sha256    TEXT NOT NULL,     -- hex, lower case
    image_path      TEXT NOT NULL,
    version_before  TEXT,              -- NULL: not known
    version_after   TEXT,
    outcome         TEXT NOT NULL      -- 'updated', 'failed: ...', 'interrupted: ...'
);

-- The audit log: every command sent to the unit, as its JSON lines had it.
CREATE TABLE commands (
    entry       INTEGER PRIMARY KEY REFERENCES entries(id),
    command     TEXT NOT NULL,     -- 'DEVICE_POWER: device 5 (5A-2), on'
    frame       TEXT,              -- the bytes sent, hex; NULL for a run's summary line
    result      TEXT NOT NULL,     -- 'sent', 'refused: ...'
    run         TEXT,              -- 'start', 'stop', 'ended by a change of direction', 'unfinished'
    run_origin  TEXT,
    moves       INTEGER,
    seconds     REAL
);

CREATE TABLE faults (
    entry   INTEGER PRIMARY KEY REFERENCES entries(id),
    device  INTEGER NOT NULL,      -- 255: the system fault flag
    name    TEXT NOT NULL,
    fault   TEXT NOT NULL          -- the fault in words, ICD Appendix E
);
"#;

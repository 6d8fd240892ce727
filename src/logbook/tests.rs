//! The logbook's file: made, migrated, shared, refused. Each test works on a real
//! SQLite file in a folder of its own.

use std::time::{Duration, Instant};

use rusqlite::Connection;

use super::schema::{MIGRATIONS, Migration, VERSION};
use super::*;

fn tables(conn: &Connection) -> Vec<String> {
    let mut st = conn
        .prepare("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name")
        .unwrap();
    st.query_map([], |r| r.get(0))
        .unwrap()
        .map(Result::unwrap)
        .collect()
}

/// A new file gets every table of the schema, its version, WAL, and the name of
/// the program that wrote it.
#[test]
fn a_new_logbook_has_the_schema_in_wal() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("folder made for it").join("logbook.sqlite");
    let book = Logbook::open(&path, Mode::ReadWrite).unwrap();
    assert_eq!(book.version().unwrap(), VERSION);
    assert_eq!(book.read_only(), None);
    let t = tables(book.conn());
    for want in [
        "about",
        "aircraft",
        "units",
        "installs",
        "entries",
        "checks",
        "check_circuits",
        "check_switches",
        "check_motors",
        "check_loads",
        "backups",
        "setting_changes",
        "firmware",
        "commands",
        "faults",
    ] {
        assert!(t.iter().any(|x| x == want), "{want} missing from {t:?}");
    }
    let mode: String = book
        .conn()
        .query_row("PRAGMA journal_mode", [], |r| r.get(0))
        .unwrap();
    assert_eq!(mode, "wal");
    assert_eq!(
        book.written_by().as_deref(),
        Some(concat!("vpx-efis ", env!("CARGO_PKG_VERSION")))
    );
    drop(book);
    // Opened again: nothing to migrate, the same file.
    let again = Logbook::open(&path, Mode::ReadWrite).unwrap();
    assert_eq!(again.version().unwrap(), VERSION);
}

/// Garbage where the logbook should be is named, and left byte for byte as it was.
#[test]
fn a_corrupt_file_is_named_and_never_written_over() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    let garbage: Vec<u8> = (0..8192u32).map(|i| (i * 7 + 3) as u8).collect();
    std::fs::write(&path, &garbage).unwrap();
    for mode in [Mode::ReadWrite, Mode::ReadOnly] {
        let e = Logbook::open(&path, mode).unwrap_err();
        assert!(matches!(e, Error::Corrupt { .. }), "{mode:?}: {e:?}");
        let words = e.to_string();
        assert!(words.contains(&path.display().to_string()), "{words}");
        assert!(words.contains("left as it is"), "{words}");
    }
    assert_eq!(std::fs::read(&path).unwrap(), garbage);
}

/// A logbook whose pages were damaged after it was written (here: its tables' pages
/// overwritten) opens, and SQLite's check names the damage.
#[test]
fn damage_inside_a_logbook_is_found_by_the_integrity_check() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    {
        let book = Logbook::open(&path, Mode::ReadWrite).unwrap();
        book.integrity_check().unwrap();
        book.conn()
            .execute_batch("PRAGMA wal_checkpoint(TRUNCATE)")
            .unwrap();
    }
    let mut bytes = std::fs::read(&path).unwrap();
    let page = 4096;
    assert!(bytes.len() > 3 * page, "{} bytes", bytes.len());
    for b in &mut bytes[page + 8..3 * page] {
        *b = 0x5a;
    }
    std::fs::write(&path, &bytes).unwrap();
    let e = match Logbook::open(&path, Mode::ReadWrite) {
        Err(e) => e,
        Ok(book) => book.integrity_check().unwrap_err(),
    };
    assert!(matches!(e, Error::Corrupt { .. }), "{e:?}");
}

/// A logbook of a later schema than ours is opened read-only, and says by whom it
/// was written; a write is refused by SQLite itself.
#[test]
fn a_logbook_from_a_newer_program_is_read_only_and_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    {
        let c = Connection::open(&path).unwrap();
        c.execute_batch(MIGRATIONS[0].sql).unwrap();
        c.execute(
            "INSERT INTO about VALUES ('written_by', 'vpx-efis 9.0.0')",
            [],
        )
        .unwrap();
        c.pragma_update(None, "user_version", VERSION + 1).unwrap();
    }
    let book = Logbook::open(&path, Mode::ReadWrite).unwrap();
    let why = book.read_only().expect("read-only");
    assert!(why.contains("vpx-efis 9.0.0"), "{why}");
    assert!(why.contains(&format!("schema {}", VERSION + 1)), "{why}");
    let write = book.conn().execute(
        "INSERT INTO aircraft VALUES ('N123AB', '2026-12-01T00:00:00.000Z')",
        [],
    );
    assert!(
        write.is_err(),
        "a write went into a newer program's logbook"
    );
    assert_eq!(book.version().unwrap(), VERSION + 1, "never migrated down");
}

/// Reading needs a file: none is made.
#[test]
fn reading_a_missing_logbook_says_so_and_makes_none() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    let e = Logbook::open(&path, Mode::ReadOnly).unwrap_err();
    assert!(matches!(e, Error::Missing { .. }), "{e:?}");
    assert!(!path.exists());
}

/// Another process holding a write transaction: opening waits the busy timeout,
/// then says the logbook is locked, naming it. A reader is never held up (WAL).
#[test]
fn a_locked_logbook_is_waited_for_then_said_to_be_locked() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    drop(Logbook::open(&path, Mode::ReadWrite).unwrap());
    let holder = Connection::open(&path).unwrap();
    holder
        .execute_batch(
            "BEGIN IMMEDIATE; INSERT INTO aircraft VALUES ('N1', '2026-12-01T00:00:00.000Z');",
        )
        .unwrap();
    // A new, empty file would need the lock to be made; an existing one at our
    // version needs none to open, so the wait shows at the first write.
    let mut book = Logbook::open_with(&path, Mode::ReadWrite, Duration::from_millis(300)).unwrap();
    let started = Instant::now();
    let e = book
        .conn_mut()
        .execute(
            "INSERT INTO aircraft VALUES ('N2', '2026-12-01T00:00:00.000Z')",
            [],
        )
        .map_err(|e| Error::of(&path, e, Duration::from_millis(300)))
        .unwrap_err();
    let waited = started.elapsed();
    assert!(matches!(e, Error::Locked { .. }), "{e:?}");
    assert!(
        waited >= Duration::from_millis(250),
        "waited only {waited:?}"
    );
    assert!(e.to_string().contains("locked by another program"), "{e}");
    let reader = Logbook::open(&path, Mode::ReadOnly).unwrap();
    let n: i64 = reader
        .conn()
        .query_row("SELECT count(*) FROM aircraft", [], |r| r.get(0))
        .unwrap();
    assert_eq!(n, 0, "the holder's write is not committed");
    holder.execute_batch("COMMIT").unwrap();
    book.conn_mut()
        .execute(
            "INSERT INTO aircraft VALUES ('N2', '2026-12-01T00:00:00.000Z')",
            [],
        )
        .expect("free again");
}

/// The migrations: a logbook of the first schema, with a record in it, opened by a
/// program with a next schema (a test-only step that adds a column), comes up to it
/// with the record kept; a reader of the older schema is told to open it first.
#[test]
fn a_logbook_of_the_first_schema_opens_with_the_next() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    {
        let book = Logbook::open_migrating(&path, Mode::ReadWrite, BUSY_TIMEOUT, &MIGRATIONS[..1])
            .unwrap();
        assert_eq!(book.version().unwrap(), 1);
        book.conn()
            .execute(
                "INSERT INTO aircraft VALUES ('N123AB', '2026-11-03T10:00:00.000Z')",
                [],
            )
            .unwrap();
    }
    let next: Vec<Migration> = MIGRATIONS[..1]
        .iter()
        .copied()
        .chain([Migration {
            to: 2,
            sql: "ALTER TABLE aircraft ADD COLUMN model TEXT;
                  UPDATE aircraft SET model = 'unknown';",
        }])
        .collect();
    let e = Logbook::open_migrating(&path, Mode::ReadOnly, BUSY_TIMEOUT, &next).unwrap_err();
    assert!(matches!(e, Error::Older { found: 1, .. }), "{e:?}");
    let book = Logbook::open_migrating(&path, Mode::ReadWrite, BUSY_TIMEOUT, &next).unwrap();
    assert_eq!(book.version().unwrap(), 2);
    let row: (String, String) = book
        .conn()
        .query_row("SELECT registration, model FROM aircraft", [], |r| {
            Ok((r.get(0)?, r.get(1)?))
        })
        .unwrap();
    assert_eq!(row, ("N123AB".into(), "unknown".into()));
    drop(book);
    // And the first program now finds a newer logbook.
    let old =
        Logbook::open_migrating(&path, Mode::ReadWrite, BUSY_TIMEOUT, &MIGRATIONS[..1]).unwrap();
    assert!(old.read_only().is_some());
}

/// A migration that fails half-way leaves the file at the version before, whole.
#[test]
fn a_failed_migration_leaves_the_version_before() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    drop(Logbook::open(&path, Mode::ReadWrite).unwrap());
    let bad: Vec<Migration> = MIGRATIONS
        .iter()
        .copied()
        .chain([Migration {
            to: VERSION + 1,
            sql: "CREATE TABLE half (x); SELECT * FROM no_such_table;",
        }])
        .collect();
    assert!(Logbook::open_migrating(&path, Mode::ReadWrite, BUSY_TIMEOUT, &bad).is_err());
    let book = Logbook::open(&path, Mode::ReadWrite).unwrap();
    assert_eq!(book.version().unwrap(), VERSION);
    assert!(!tables(book.conn()).iter().any(|t| t == "half"));
}

// ---- The writer thread: real files, real threads.

use super::record::{COMMAND_LINE, Check, CheckCircuit, Unit};
use crate::audit::Origin;
use crate::protocol::message::{DevicePower, Packet};

fn at(s: u64) -> std::time::SystemTime {
    // 2026-11-03T10:00:00Z and on.
    std::time::UNIX_EPOCH + Duration::from_secs(1_793_700_000 + s)
}

fn backup(s: u64, text: &str) -> Entry {
    Entry {
        at: at(s),
        origin: COMMAND_LINE,
        summary: format!("backup {s}"),
        what: What::Backup {
            path: None,
            text: text.into(),
        },
    }
}

fn unit(names: &[&str]) -> Unit {
    Unit {
        hardware: "VP-X Pro".into(),
        software: "2.1".into(),
        names: names.iter().map(|s| s.to_string()).collect(),
    }
}

fn count(path: &std::path::Path, sql: &str) -> i64 {
    let c = Connection::open(path).unwrap();
    c.query_row(sql, [], |r| r.get(0)).unwrap()
}

fn wait_problem(r: &Recorder, within: Duration) -> Option<String> {
    let until = Instant::now() + within;
    loop {
        if let Some(p) = r.take_problem() {
            return Some(p);
        }
        if Instant::now() > until {
            return None;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// A check, a backup and the commands of the stop gate go in under the aircraft and
/// the unit, the check with its circuits; the audit lines come back as the files had
/// them.
#[test]
fn records_go_in_under_the_aircraft_and_the_unit() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    let (r, thread) = Recorder::start(path.clone(), Some("N123AB".into())).unwrap();
    r.unit(unit(&["Landing Lt", "Taxi Lt"]));
    r.record(Entry {
        at: at(10),
        origin: Origin::Check.word(),
        summary: "check: 1 passed".into(),
        what: What::Check(Box::new(Check {
            tally: "1 passed".into(),
            circuits: vec![CheckCircuit {
                device: 5,
                name: "Landing Lt".into(),
                pin: "5A-2".into(),
                amps: Some(6.1),
                verdict: "passed".into(),
                finding: "6.1 A of a 10 A breaker".into(),
                ..CheckCircuit::default()
            }],
            ..Check::default()
        })),
    });
    r.record(backup(20, "[unit]\n"));
    let power = Packet::request(
        7,
        DevicePower {
            device_id: 5,
            on: true,
        },
    );
    r.command(Origin::Key, &power, Ok(()));
    assert!(r.flush(Duration::from_secs(5)));
    drop(r);
    thread.join();
    assert_eq!(
        count(
            &path,
            "SELECT count(*) FROM entries WHERE aircraft = 'N123AB' AND unit IS NOT NULL"
        ),
        3
    );
    assert_eq!(
        count(
            &path,
            "SELECT count(*) FROM check_circuits WHERE name = 'Landing Lt' AND amps = 6.1"
        ),
        1
    );
    assert_eq!(count(&path, "SELECT count(*) FROM installs"), 1);
    let lines = jsonl::all_audit_lines(&path).unwrap();
    assert_eq!(lines.len(), 1, "{lines:?}");
    let v: serde_json::Value = serde_json::from_str(&lines[0]).unwrap();
    assert_eq!(v["origin"], "key");
    assert_eq!(v["result"], "sent");
    assert!(v["command"].as_str().unwrap().starts_with("DEVICE_POWER: "));
}

/// A unit seen before in another aircraft: the writer finds it, with the day.
#[test]
fn a_unit_seen_in_another_aircraft_is_said_with_the_day() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    let before = Target {
        path: path.clone(),
        aircraft: Some("N123AB".into()),
    };
    assert_eq!(
        writer::record_now_in(before, backup(0, "a"), Some(unit(&["Nav Lt"]))),
        None
    );
    let (r, thread) = Recorder::start(path.clone(), Some("N456CD".into())).unwrap();
    r.unit(unit(&["Nav Lt"]));
    r.record(backup(86_400, "b"));
    assert!(r.flush(Duration::from_secs(5)));
    assert_eq!(
        r.was_in(),
        Some(("N123AB".to_string(), "2026-11-03".to_string()))
    );
    drop(r);
    thread.join();
    // The same unit, not a second one; two installs.
    assert_eq!(count(&path, "SELECT count(*) FROM units"), 1);
    assert_eq!(count(&path, "SELECT count(*) FROM installs"), 2);
}

/// Garbage where the logbook should be: the writer says so, names it, writes
/// nothing, and the garbage is left as it was.
#[test]
fn the_writer_goes_on_without_a_corrupt_logbook_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    let garbage = vec![0x42u8; 5000];
    std::fs::write(&path, &garbage).unwrap();
    let (r, thread) = Recorder::start(path.clone(), None).unwrap();
    r.record(backup(0, "x"));
    assert!(r.flush(Duration::from_secs(5)));
    let said = wait_problem(&r, Duration::from_secs(2)).expect("said");
    assert!(said.contains("not a logbook"), "{said}");
    assert!(said.contains(&path.display().to_string()), "{said}");
    assert!(r.status().problem.is_some());
    assert_eq!(r.status().written, 0);
    drop(r);
    thread.join();
    assert_eq!(std::fs::read(&path).unwrap(), garbage);
}

/// Another process holds the logbook: the writer waits the busy timeout, says it is
/// locked, keeps the records, and writes them all with the next one once it is
/// free. Nothing already there is lost.
#[test]
fn a_locked_logbook_keeps_the_records_until_it_is_free() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("logbook.sqlite");
    assert_eq!(
        writer::record_now_in(
            Target {
                path: path.clone(),
                aircraft: None
            },
            backup(0, "first"),
            None
        ),
        None
    );
    let holder = Connection::open(&path).unwrap();
    holder.busy_timeout(Duration::from_secs(5)).unwrap();
    holder
        .execute_batch("BEGIN IMMEDIATE; INSERT INTO about VALUES ('held', 'yes');")
        .unwrap();
    let (r, thread) = Recorder::start_with(path.clone(), None, Duration::from_millis(300)).unwrap();
    let started = Instant::now();
    r.record(backup(1, "second"));
    assert!(r.flush(Duration::from_secs(5)));
    assert!(started.elapsed() >= Duration::from_millis(250));
    let said = wait_problem(&r, Duration::from_secs(2)).expect("said");
    assert!(said.contains("locked by another program"), "{said}");
    assert!(said.contains("1 records wait"), "{said}");
    holder.execute_batch("COMMIT").unwrap();
    r.record(backup(2, "third"));
    assert!(r.flush(Duration::from_secs(5)));
    assert_eq!(r.status().problem, None);
    drop(r);
    thread.join();
    assert_eq!(count(&path, "SELECT count(*) FROM backups"), 3);
}

/// A full disk (a real one: a 256 KiB tmpfs, mounted for the test, which needs
/// root): the action's record fails, is said with SQLite's words, and every record
/// written before is still there and the file whole.
#[cfg(target_os = "linux")]
#[test]
fn a_full_disk_is_said_and_loses_nothing_written_before() {
    let dir = tempfile::tempdir().unwrap();
    let mnt = dir.path().join("small");
    std::fs::create_dir(&mnt).unwrap();
    let mounted = std::process::Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=256k", "tmpfs"])
        .arg(&mnt)
        .output()
        .is_ok_and(|o| o.status.success());
    if !mounted {
        eprintln!("SKIPPED: mounting a tmpfs needs root; the full disk is not tried here");
        return;
    }
    struct Unmount(std::path::PathBuf);
    impl Drop for Unmount {
        fn drop(&mut self) {
            let _ = std::process::Command::new("umount").arg(&self.0).status();
        }
    }
    let _u = Unmount(mnt.clone());
    let path = mnt.join("logbook.sqlite");
    let (r, thread) = Recorder::start_with(path.clone(), None, Duration::from_millis(300)).unwrap();
    r.record(backup(0, "small"));
    assert!(r.flush(Duration::from_secs(5)));
    assert_eq!(r.status().written, 1);
    // A backup's text larger than the disk.
    r.record(backup(1, &"x".repeat(600 * 1024)));
    assert!(r.flush(Duration::from_secs(5)));
    let said = wait_problem(&r, Duration::from_secs(2)).expect("said");
    assert!(said.contains("full"), "{said}");
    assert!(said.contains("wait in memory"), "{said}");
    drop(r);
    thread.join();
    let book = Logbook::open(&path, Mode::ReadOnly).unwrap();
    book.integrity_check().unwrap();
    let n: i64 = book
        .conn()
        .query_row("SELECT count(*) FROM backups", [], |r| r.get(0))
        .unwrap();
    assert_eq!(n, 1, "the record before the disk filled is there");
}

/// Registrations as painted are taken (upper case); anything else is refused with
/// the reason and an example.
#[test]
fn a_registration_is_checked_in_words() {
    for (typed, want) in [
        ("n123ab", "N123AB"),
        (" G-ABCD ", "G-ABCD"),
        ("VH-XYZ", "VH-XYZ"),
        ("JA123A", "JA123A"),
    ] {
        assert_eq!(registration(typed).as_deref(), Ok(want), "{typed:?}");
    }
    for (typed, why) in [
        ("", "an empty registration"),
        ("N 123", "' ' is not a letter, digit or hyphen"),
        ("N123ABCDEFGH", "12 characters"),
        ("-ABC", "a hyphen goes only between"),
        ("G--ABC", "a hyphen goes only between"),
        ("12345", "it has no letter"),
    ] {
        let e = registration(typed).unwrap_err();
        assert!(e.contains(why), "{typed:?}: {e}");
        assert!(e.contains("N123AB"), "{typed:?}: no example in {e}");
    }
}

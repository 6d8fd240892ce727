//! `kill -9` of the page in the middle of a check: the real `vpx-efis` binary in a
//! real terminal (a pty it has as its controlling terminal), against the virtual
//! VP-X as a process of its own (`vpx-efis sim --pty`), recording into a logbook in
//! a temporary folder. The test reads the logbook while the check switches circuits
//! on; once it has seen the check's commands there, it kills the page with SIGKILL
//! (no handler, no flush, no clean-up). Then SQLite's `PRAGMA integrity_check` must
//! say ok, and every entry the test had seen before the kill must still be there,
//! unchanged.
// Needs pseudo-terminals and POSIX signals, which only Unix has.
#![cfg(unix)]

mod common;
mod page_rig;

use std::time::{Duration, Instant};

use common::process::{Kill, sim_pty};
use page_rig::terminal::{Term, page};
use rusqlite::{Connection, OpenFlags};

type Row = (i64, String, String, String, String);

/// Every entry in the logbook now, read as another program reads it (read-only,
/// beside the page's writes).
fn entries(path: &std::path::Path) -> Vec<Row> {
    let Ok(c) = Connection::open_with_flags(path, OpenFlags::SQLITE_OPEN_READ_ONLY) else {
        return Vec::new();
    };
    let _ = c.busy_timeout(Duration::from_secs(2));
    let Ok(mut st) = c.prepare("SELECT id, time, origin, kind, summary FROM entries ORDER BY id")
    else {
        return Vec::new();
    };
    st.query_map([], |r| {
        Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?, r.get(4)?))
    })
    .map(|rows| rows.filter_map(Result::ok).collect())
    .unwrap_or_default()
}

#[test]
fn a_kill_in_the_middle_of_a_check_leaves_the_logbook_whole() {
    let dir = tempfile::tempdir().unwrap();
    let book = dir.path().join("logbook.sqlite");
    let (_sim, port) = sim_pty("demo");
    let (mut term, slave) = Term::open();
    let book_arg = book.to_str().unwrap().to_string();
    let args = [
        "--port",
        &port,
        "--logbook",
        &book_arg,
        "--aircraft",
        "n123ab",
    ];
    let child = page(&args, slave);
    let pid = child.id();
    let child = Kill(child);
    let wait_for = |term: &Term, what: &[u8], from: usize| {
        let words = String::from_utf8_lossy(what);
        term.wait_for(&words, &[what], from, Duration::from_secs(20));
    };
    // The unit's names read: the check can plan.
    wait_for(&term, b"Nav Lt", 0);
    std::thread::sleep(Duration::from_millis(500));
    // i: the check; Enter: the aircraft is safe to power; S, S: skip the switch
    // inputs and the circuits, so the motors step runs a motor at once.
    let mark = term.written();
    term.typed(b"i");
    wait_for(&term, b"INSTALLATION CHECK", mark);
    // The screen is drawn in differences from here on, so the steps are waited for
    // by time; the logbook says whether the motors step ran.
    for key in [b"\r", b"S", b"S"] {
        std::thread::sleep(Duration::from_millis(1500));
        term.typed(key);
    }
    let seen;
    let until = Instant::now() + Duration::from_secs(30);
    loop {
        let now = entries(&book);
        if now.iter().any(|e| e.2 == "check" && e.3 == "run") {
            seen = now;
            break;
        }
        assert!(Instant::now() < until, "the check ran no motor: {now:#?}");
        std::thread::sleep(Duration::from_millis(10));
    }
    // SIGKILL: nothing of the page runs after this.
    // SAFETY: kill(2) on our own child's pid.
    assert_eq!(unsafe { libc::kill(pid as i32, libc::SIGKILL) }, 0);
    let mut child = child;
    let status = child.0.wait().unwrap();
    assert!(
        !status.success(),
        "the page was killed, not ended: {status:?}"
    );

    let c = Connection::open(&book).unwrap();
    let check: Vec<String> = c
        .prepare("PRAGMA integrity_check")
        .unwrap()
        .query_map([], |r| r.get(0))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    assert_eq!(check, ["ok"]);
    let after = entries(&book);
    for e in &seen {
        assert!(after.contains(e), "{e:?} was lost by the kill: {after:#?}");
    }
    assert!(
        after.iter().all(|e| e.1.ends_with('Z') && !e.4.is_empty()),
        "{after:#?}"
    );
    // Recorded under the aircraft named (upper case), with the unit.
    let named: i64 = c
        .query_row(
            "SELECT count(*) FROM entries WHERE aircraft = 'N123AB'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(named as usize, after.len());
    println!(
        "{} entries seen before the kill, {} in the logbook after it",
        seen.len(),
        after.len()
    );
}

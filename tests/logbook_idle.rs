//! The logbook's writer thread sleeps in its channel: an idle recorder never wakes
//! (the page's idle tests measure the whole page; this is the thread alone, counted
//! by the kernel's tally of its wake-ups). A binary of its own, so the only thread
//! named "logbook" is this test's.
#![cfg(target_os = "linux")]

use std::time::{Duration, SystemTime};

use vpx_efis::logbook::{Entry, Recorder, What};

#[test]
fn an_idle_writer_does_not_wake() {
    let dir = tempfile::tempdir().unwrap();
    let (r, thread) = Recorder::start(dir.path().join("logbook.sqlite"), None).unwrap();
    r.record(Entry {
        at: SystemTime::now(),
        origin: "command line",
        summary: "backup".into(),
        what: What::Backup {
            path: None,
            text: "x".into(),
        },
    });
    assert!(r.flush(Duration::from_secs(5)));
    let task = std::fs::read_dir("/proc/self/task")
        .unwrap()
        .filter_map(|e| e.ok())
        .find(|e| {
            std::fs::read_to_string(e.path().join("comm")).is_ok_and(|c| c.trim() == "logbook")
        })
        .expect("the logbook thread");
    let wakes = || {
        let s = std::fs::read_to_string(task.path().join("status")).unwrap();
        let n = |key: &str| -> u64 {
            s.lines()
                .find_map(|l| l.strip_prefix(key))
                .unwrap()
                .trim()
                .parse()
                .unwrap()
        };
        n("voluntary_ctxt_switches:") + n("nonvoluntary_ctxt_switches:")
    };
    // The flush is answered just before the thread goes back to its wait.
    std::thread::sleep(Duration::from_millis(200));
    let before = wakes();
    std::thread::sleep(Duration::from_millis(2000));
    assert_eq!(wakes(), before, "the writer woke while nothing came");
    drop(r);
    thread.join();
}

//! Idle means idle with a phone connected: the real page (`vpx-efis --port …
//! --remote 127.0.0.1:PORT`) in a pseudo-terminal of its own, against `vpx-efis sim
//! --pty` in another process, with a paired phone holding `/api/events` open and
//! nothing changing, uses at most 1 % of a core (its own CPU time, as
//! `page_idle_cpu` measures it). The phone keeps hearing the state at least every
//! second meanwhile.
//!
//! `IDLE_CPU_SECS=30 cargo test --release --test remote_idle_cpu -- --nocapture`
//! measures longer.
// Needs pseudo-terminals, which only Unix has.
#![cfg(unix)]

use std::io::{BufRead, BufReader};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

mod common;
mod page_rig;

use common::cpu::process_cpu_time;
use common::phone::Phone;
use common::process::{Kill, sim_pty};
use page_rig::terminal::{Term, find, page};

/// A port nobody listens on now.
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// The pairing URL in the page's output (the overlay's, with its key: 22 base64url
/// characters).
fn url_in(out: &[u8], base: &str) -> Option<String> {
    let at = find(out, format!("{base}/#k=").as_bytes())?;
    let url: String = out[at..]
        .iter()
        .map(|&b| b as char)
        .take_while(|c| c.is_ascii_alphanumeric() || ":/.#=_-".contains(*c))
        .collect();
    (url.len() == base.len() + 4 + 22).then_some(url)
}

#[test]
fn the_page_is_idle_with_a_phone_listening_to_its_events() {
    let (_sim, port) = sim_pty("hangar");
    let listen = format!("127.0.0.1:{}", free_port());
    let base = format!("http://{listen}");
    let (mut term, slave) = Term::open();
    let mut child = page(&["--port", &port, "--remote", &listen], slave);
    let pid = child.id();
    if let Err(why) = process_cpu_time(pid) {
        let _ = child.kill();
        let _ = child.wait();
        eprintln!("remote_idle_cpu: skipped, not measurable here: {why}");
        return;
    }
    let child = Kill(child);
    let start = Instant::now();
    let url = loop {
        if let Some(u) = url_in(&term.output(), &base) {
            break u;
        }
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "the page never showed its pairing URL: {}",
            String::from_utf8_lossy(&term.output())
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    let phone = Phone::scan(&url).expect("pairing");
    // The phone: the events stream, signed, counting the states it hears.
    let heard = Arc::new(AtomicUsize::new(0));
    let h = heard.clone();
    let events = phone.events();
    std::thread::spawn(move || {
        let mut lines = BufReader::new(events.into_body().into_reader()).lines();
        while let Some(Ok(line)) = lines.next() {
            if line.starts_with("data: ") {
                h.fetch_add(1, Ordering::SeqCst);
            }
        }
    });
    // Paired: the person hides the overlay (Esc) and goes to the wingtip.
    if std::env::var("REMOTE_IDLE_OVERLAY").is_err() {
        term.typed(b"\x1b");
    }
    // Past the connect requests and the first redraws.
    std::thread::sleep(Duration::from_millis(2500));
    let cpu0 = process_cpu_time(pid).unwrap();
    let heard0 = heard.load(Ordering::SeqCst);
    let wall0 = Instant::now();
    let secs = common::cpu::idle_secs(10);
    std::thread::sleep(Duration::from_secs(secs));
    let cpu = process_cpu_time(pid).unwrap() - cpu0;
    let wall = wall0.elapsed();
    let states = heard.load(Ordering::SeqCst) - heard0;
    let mut child = child;
    assert!(
        child.0.try_wait().unwrap().is_none(),
        "the page ended while idle"
    );
    term.typed(b"q");
    let end = Instant::now() + Duration::from_secs(5);
    while child.0.try_wait().unwrap().is_none() {
        assert!(Instant::now() < end, "the page did not quit on q");
        std::thread::sleep(Duration::from_millis(20));
    }
    let share = cpu.as_secs_f64() / wall.as_secs_f64();
    eprintln!(
        "page with a phone on /api/events: {cpu:?} CPU in {wall:.1?} = {:.2} % of a core, \
         {states} states sent",
        share * 100.0
    );
    assert!(
        states as u64 >= secs - 1,
        "the phone heard {states} states in {secs} s: the heartbeat is missing"
    );
    assert!(
        share <= 0.01,
        "the page used {:.2} % of a core",
        share * 100.0
    );
}

/// The page's threads, by name (Linux's /proc).
#[cfg(target_os = "linux")]
fn threads(pid: u32) -> Vec<String> {
    std::fs::read_dir(format!("/proc/{pid}/task"))
        .map(|d| {
            d.filter_map(|t| {
                std::fs::read_to_string(t.ok()?.path().join("comm"))
                    .ok()
                    .map(|s| s.trim().to_string())
            })
            .collect()
        })
        .unwrap_or_default()
}

/// How many listening TCP sockets the page holds (its fds' socket inodes among the
/// LISTEN rows of /proc/net/tcp and tcp6).
#[cfg(target_os = "linux")]
fn listening(pid: u32) -> usize {
    let inodes: Vec<String> = std::fs::read_dir(format!("/proc/{pid}/fd"))
        .map(|d| {
            d.filter_map(|f| {
                let link = std::fs::read_link(f.ok()?.path()).ok()?;
                let l = link.to_string_lossy().to_string();
                Some(l.strip_prefix("socket:[")?.strip_suffix(']')?.to_string())
            })
            .collect()
        })
        .unwrap_or_default();
    ["/proc/net/tcp", "/proc/net/tcp6"]
        .iter()
        .flat_map(|f| {
            std::fs::read_to_string(f)
                .unwrap_or_default()
                .lines()
                .skip(1)
                .filter_map(|l| {
                    let cols: Vec<&str> = l.split_whitespace().collect();
                    (cols.get(3) == Some(&"0A")).then(|| cols.get(9).map(|s| s.to_string()))?
                })
                .collect::<Vec<_>>()
        })
        .filter(|inode| inodes.contains(inode))
        .count()
}

/// Off costs nothing: without `--remote` the page has no remote thread and no
/// listening socket; `p` starts both, `p` again (the code shown) ends both.
#[cfg(target_os = "linux")]
#[test]
fn off_the_remote_has_no_thread_and_no_socket() {
    let (_sim, port) = sim_pty("hangar");
    let (mut term, slave) = Term::open();
    let child = Kill(page(&["--port", &port], slave));
    let pid = child.0.id();
    let wait = |what: &str, f: &dyn Fn() -> bool| {
        let end = Instant::now() + Duration::from_secs(10);
        while !f() {
            assert!(Instant::now() < end, "{what}");
            std::thread::sleep(Duration::from_millis(20));
        }
    };
    let remote_thread = || threads(pid).iter().any(|t| t == "remote");
    term.wait_for("the device list", &[b"EFIS"], 0, Duration::from_secs(10));
    std::thread::sleep(Duration::from_millis(500));
    assert!(!remote_thread(), "{:?}", threads(pid));
    assert_eq!(listening(pid), 0, "the page listens with the remote off");
    term.typed(b"p");
    wait("no remote thread after p", &remote_thread);
    term.wait_for("the pairing URL", &[b"/#k="], 0, Duration::from_secs(10));
    assert_eq!(listening(pid), 1, "the remote listens on one socket");
    term.typed(b"p");
    wait("the remote thread stayed after p", &|| !remote_thread());
    assert_eq!(listening(pid), 0, "the socket stayed open after p");
    drop(child);
}

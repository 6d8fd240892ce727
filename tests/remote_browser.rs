//! The walk-around remote's phone page in a real browser: headless Chromium
//! at a phone's 390×844, driven through WebDriver (`webdriver`), against the real page
//! binary (`vpx-efis --port … --remote 127.0.0.1:PORT` in a real terminal) wired to the
//! virtual VP-X as its own process (`vpx-efis sim --pty`), through a tap that records
//! every byte the page puts on the wire.
//!
//! Without chromedriver these skip with a message; with `CI` set they fail instead.
//! They measure real time, so they take turns (a lock) rather than compete for a
//! loaded machine's cores. The page in a terminal needs a pseudo-terminal: Unix only.
#![cfg(unix)]

use std::io::Write;
use std::process::ChildStdin;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use serde_json::json;
use vpx_efis::protocol::message::{DevicePower, Message, TrimMove};

mod common;
use common::process::{Kill, Sim, sim};

mod webdriver;
use webdriver::{Browser, free_port};

// The page in a real terminal, as the keys' end-to-end tests run it.
mod page_rig;
use page_rig::terminal::{self, Term};

static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// A small aircraft, quiet (nothing on its timeline), with lights to switch and a
/// pitch trim wired right.
const SCENARIO: &str = r#"
description = "remote_browser: lights, a pump, flaps and pitch trim, nothing scheduled"
[electrical]
battery_volts = 12.6
temperature_c = 20
[[device]]
id = 2
name = "EFIS"
breaker = 5
switch = 11
load = 2.8
[[device]]
id = 4
name = "Nav Lt"
breaker = 3
switch = 2
load = 1.4
[[device]]
id = 5
name = "Strobe Lt"
breaker = 5
switch = 2
load = 2.1
[[device]]
id = 17
name = "Landing Lt"
breaker = 10
switch = 5
load = 6.5
[[device]]
id = 19
name = "Boost Pump"
breaker = 7
switch = 7
load = 4.2
[flap]
mode = "momentary"
up = 20
down = 220
midpoint_1 = 90
midpoint_2 = 160
breaker = 7
position = 120
[pitch_trim]
up = 30
down = 220
neutral = 125
position = 125
"#;

/// Wall-clock milliseconds, the clock the browser's `Date.now()` reads.
fn wall_ms(t: SystemTime) -> f64 {
    t.duration_since(UNIX_EPOCH).unwrap().as_secs_f64() * 1000.0
}

type Wire = page_rig::Recorded<SystemTime>;

/// The sim's pty on one side, a fresh pty whose slave the page opens on the other, and
/// a record of what the page sends, timed by the wall clock the browser reads.
struct Tap {
    wire: Wire,
    joined: page_rig::Tap,
}

impl Tap {
    fn start(sim_path: &str) -> Tap {
        let sim_in = serialport::new(sim_path, 57_600)
            .timeout(Duration::from_millis(20))
            .open_native()
            .expect("open the sim's pty");
        let sim_out = sim_in.try_clone_native().expect("clone the sim's pty");
        let wire: Wire = Arc::default();
        let joined = page_rig::Tap::between(sim_out, sim_in, wire.clone(), SystemTime::now);
        Tap { wire, joined }
    }

    /// Every message the page sent, with when it reached the wire.
    fn sent(&self) -> Vec<(SystemTime, Message)> {
        (page_rig::packets(&self.wire.lock().unwrap()).into_iter())
            .map(|(at, p)| (at, p.message))
            .collect()
    }

    fn trim_moves(&self) -> Vec<(SystemTime, TrimMove)> {
        (self.sent().into_iter())
            .filter_map(|(at, m)| match m {
                Message::TrimMove(t) => Some((at, t)),
                _ => None,
            })
            .collect()
    }
}

/// The virtual VP-X, the tap, the page with the remote on, and the browser.
struct Hangar {
    browser: Browser,
    tap: Tap,
    term: Term,
    sim_console: ChildStdin,
    base: String,
    // Dropped last: the page before the sim, as a mechanic quits.
    _page: Kill,
    _sim: Kill,
    _dir: tempfile::TempDir,
    // These tests measure real time, so they take turns.
    _turn: MutexGuard<'static, ()>,
}

impl Hangar {
    /// `None` (skipped, with a message) when there is no chromedriver and CI is unset.
    fn open() -> Option<Hangar> {
        Hangar::open_with(None)
    }

    /// As [`Hangar::open`], with the browser paired.
    fn paired() -> Option<Hangar> {
        let h = Hangar::open()?;
        h.pair();
        Some(h)
    }

    /// As [`Hangar::open`], the sim on a built-in scenario (`demo`, `install`) when
    /// one is named, else on [`SCENARIO`].
    fn open_with(built_in: Option<&str>) -> Option<Hangar> {
        let turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
        let browser = Browser::start()?;
        let dir = tempfile::tempdir().unwrap();
        let scenario = dir.path().join("remote.toml");
        std::fs::write(&scenario, SCENARIO).unwrap();
        let scenario = built_in.unwrap_or_else(|| scenario.to_str().unwrap());
        let Sim {
            process: sim,
            console: sim_console,
            line: path,
        } = sim(&["--pty", "--scenario", scenario]);
        let tap = Tap::start(&path);
        let link = dir.path().join("vpx-serial");
        std::os::unix::fs::symlink(&tap.joined.slave_path, &link).unwrap();
        let port = free_port();
        let remote = format!("127.0.0.1:{port}");
        let (term, slave) = Term::open();
        let page = Kill(terminal::page(
            &["--port", link.to_str().unwrap(), "--remote", &remote],
            slave,
        ));
        Some(Hangar {
            browser,
            tap,
            term,
            sim_console,
            base: format!("http://{remote}"),
            _page: page,
            _sim: sim,
            _dir: dir,
            _turn: turn,
        })
    }

    /// The pairing URL the page shows now, read from the terminal: the key (128
    /// bits, 22 base64url characters) in its fragment.
    fn pairing_url(&self) -> String {
        let start = Instant::now();
        let needle = format!("{}/#k=", self.base);
        loop {
            let screen = String::from_utf8_lossy(&self.term.output()).into_owned();
            if let Some(at) = screen.rfind(&needle) {
                let key: String = screen[at + needle.len()..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '-' || *c == '_')
                    .collect();
                if key.len() == 22 {
                    return format!("{needle}{key}");
                }
            }
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "the page showed no pairing URL {needle}KEY"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// The five words the overlay shows now, read from the terminal: the last run of
    /// five BIP-39 words after "and type the words".
    fn pairing_words(&self) -> String {
        let list = bip39::Language::English.word_list();
        let start = Instant::now();
        loop {
            let screen = String::from_utf8_lossy(&self.term.output()).into_owned();
            if let Some(at) = screen.rfind("and type the words") {
                let plain = strip_csi(&screen[at..]);
                let tokens: Vec<&str> = plain
                    .split(|c: char| !c.is_ascii_lowercase())
                    .filter(|t| !t.is_empty())
                    .collect();
                if let Some(w) = tokens
                    .windows(5)
                    .find(|w| w.iter().all(|t| list.contains(t)))
                {
                    return w.join(" ");
                }
            }
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "the page showed no words to type: {:?}",
                screen
                    .rfind("and type the words")
                    .map(|at| &screen[at..(at + 600).min(screen.len())])
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn console(&mut self, line: &str) {
        writeln!(self.sim_console, "{line}").unwrap();
        self.sim_console.flush().unwrap();
    }

    /// Opens the pairing URL as a phone that scanned the QR code does, and waits until
    /// the list is live.
    fn pair(&self) {
        let url = self.pairing_url();
        self.browser.goto(&url);
        self.wait_live();
    }

    fn wait_live(&self) {
        self.browser.wait_for(
            "the device list, live",
            "return document.getElementById('conn').textContent === 'live' \
             && document.querySelectorAll('#devices .device').length > 0",
            Duration::from_secs(15),
        );
    }

    /// The state word a device's row shows (ON, OFF, FAULT: …, UNKNOWN, —).
    fn row_state(&self, name: &str) -> String {
        self.browser
            .exec(
                "for (const r of document.querySelectorAll('#devices .device')) \
                 if (r.querySelector('.name').textContent === arguments[0]) \
                 return r.querySelector('.state').textContent; return null;",
                json!([name]),
            )
            .as_str()
            .unwrap_or("<no such row>")
            .to_string()
    }

    fn wait_row_state(&self, name: &str, want: &str, limit: Duration) -> Instant {
        let start = Instant::now();
        loop {
            let got = self.row_state(name);
            if got == want {
                return Instant::now();
            }
            assert!(
                start.elapsed() < limit,
                "{name} shows {got:?}, not {want:?}, after {limit:?}; the phone shows:\n{}",
                self.browser.text("body")
            );
            std::thread::sleep(Duration::from_millis(25));
        }
    }

    /// Records, in the page, when the next pointer events happen (`Date.now()`).
    fn watch_pointer(&self) {
        self.browser.exec(
            "window.__seen = []; for (const t of ['pointerdown', 'pointerup', \
             'visibilitychange', 'blur']) { (t === 'blur' ? window : document)\
             .addEventListener(t, () => window.__seen.push([t, Date.now(), \
             document.visibilityState]), true); }",
            json!([]),
        );
    }

    /// Waits until the trim has run a while (three moves on the wire).
    fn wait_for_the_trim_to_run(&self) {
        let start = Instant::now();
        while trim_on(&self.tap.trim_moves()).len() < 3 {
            assert!(
                start.elapsed() < Duration::from_secs(3),
                "the trim never ran: {:?}",
                self.tap.trim_moves()
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn seen(&self, what: &str) -> Option<f64> {
        let v = self.browser.exec(
            "const e = (window.__seen || []).find((e) => e[0] === arguments[0]); \
             return e ? e[1] : null;",
            json!([what]),
        );
        v.as_f64()
    }
}

/// `s` without its terminal control sequences (ESC [ … final byte), each one a space.
fn strip_csi(s: &str) -> String {
    let mut out = String::new();
    let mut chars = s.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' && chars.peek() == Some(&'[') {
            chars.next();
            for c in chars.by_ref() {
                if ('@'..='~').contains(&c) {
                    break;
                }
            }
            out.push(' ');
        } else {
            out.push(c);
        }
    }
    out
}

fn trim_on(moves: &[(SystemTime, TrimMove)]) -> Vec<SystemTime> {
    moves
        .iter()
        .filter(|(_, m)| m.on)
        .map(|(t, _)| *t)
        .collect()
}

/// The first stop after the run began, checked to be its end: nothing ran after it.
fn the_stop(moves: &[(SystemTime, TrimMove)]) -> SystemTime {
    let stop = *trim_off(moves)
        .first()
        .unwrap_or_else(|| panic!("no stop on the wire: {moves:?}"));
    assert!(
        trim_on(moves).iter().all(|t| *t < stop),
        "the trim ran again after its stop: {moves:?}"
    );
    stop
}

/// The stops after the run began (the page also sends one when it connects).
fn trim_off(moves: &[(SystemTime, TrimMove)]) -> Vec<SystemTime> {
    let Some(began) = trim_on(moves).first().copied() else {
        return Vec::new();
    };
    (moves.iter())
        .filter(|(t, m)| !m.on && *t > began)
        .map(|(t, _)| *t)
        .collect()
}

/// Opening the URL (as a phone does from the QR code) pairs, takes the code out of the
/// address bar, and shows the list; a switch worked in the cockpit (the sim's console)
/// shows on the phone within a second or two.
#[test]
fn opening_the_url_pairs_and_the_list_is_live() {
    let Some(mut h) = Hangar::paired() else {
        return;
    };
    let url = h.browser.url();
    assert!(
        !url.contains("#k="),
        "the key left in the address bar: {url}"
    );
    assert!(
        h.browser.text("#typed").is_empty(),
        "a scanned phone is not marked as typed"
    );
    h.wait_row_state("Nav Lt", "OFF", Duration::from_secs(5));
    h.wait_row_state("EFIS", "ON", Duration::from_secs(1));
    let volts = h.browser.text("#bus-volts");
    assert!(
        volts.ends_with(" V") && volts != "— V",
        "bus volts {volts:?}"
    );
    h.console("switch 2 on");
    h.wait_row_state("Nav Lt", "ON", Duration::from_secs(4));
    h.wait_row_state("Strobe Lt", "ON", Duration::from_secs(1));
    h.console("switch 2 off");
    h.wait_row_state("Nav Lt", "OFF", Duration::from_secs(4));
}

/// Without a key in the URL the phone asks for the words: wrong ones are refused in
/// words, the right ones (typed as a person might, capitals and commas) pair, and the
/// phone says it was paired the weaker way.
#[test]
fn typing_the_words_pairs_and_the_phone_says_it_is_weaker() {
    let Some(h) = Hangar::open() else { return };
    let words = h.pairing_words();
    h.browser.goto(&h.base);
    h.browser.wait_for(
        "the pairing form",
        "return !document.getElementById('pairing').classList.contains('hidden')",
        Duration::from_secs(5),
    );
    h.browser.type_into("#pair-code", "zoo zoo zoo zoo zoo");
    h.browser.click("#pair-button");
    h.browser.wait_for(
        "the refusal",
        "return document.getElementById('pair-msg').textContent.startsWith('Wrong code')",
        Duration::from_secs(5),
    );
    assert!(
        !h.browser.text("#pairing").is_empty(),
        "still asks for the words"
    );
    h.browser
        .exec("document.getElementById('pair-code').value = ''", json!([]));
    h.browser
        .type_into("#pair-code", &words.to_uppercase().replace(' ', ", "));
    h.browser.click("#pair-button");
    h.wait_live();
    h.wait_row_state("EFIS", "ON", Duration::from_secs(5));
    let marked = h.browser.text("#typed");
    assert!(
        marked.starts_with("Paired by typed words: weaker than the QR code."),
        "{marked:?}"
    );
}

/// Five wrong attempts in a row lock pairing: the right words after them are
/// refused, and the phone says so, with the seconds left.
#[test]
fn five_wrong_codes_lock_pairing_in_words() {
    let Some(h) = Hangar::open() else { return };
    let words = h.pairing_words();
    let wrong = "zoo zoo zoo zoo zoo";
    h.browser.goto(&h.base);
    h.browser.wait_for(
        "the pairing form",
        "return !document.getElementById('pairing').classList.contains('hidden')",
        Duration::from_secs(5),
    );
    let mut said = Vec::new();
    for attempt in [wrong, wrong, wrong, wrong, wrong, words.as_str()] {
        h.browser.exec(
            "document.getElementById('pair-msg').textContent = ''",
            json!([]),
        );
        h.browser
            .exec("document.getElementById('pair-code').value = ''", json!([]));
        h.browser.type_into("#pair-code", attempt);
        h.browser.click("#pair-button");
        let msg = h.browser.wait_for(
            "an answer",
            "return document.getElementById('pair-msg').textContent",
            Duration::from_secs(5),
        );
        said.push(msg.as_str().unwrap().to_string());
    }
    assert!(
        said[..5].iter().all(|m| m.starts_with("Wrong code")),
        "{said:#?}"
    );
    let locked = |m: &str| {
        m.starts_with("Too many wrong codes: pairing is locked for ") && m.ends_with(" s more.")
    };
    assert!(
        locked(&said[5]),
        "the right words, after five wrong: {said:#?}"
    );
    assert!(
        h.browser.text("#live").is_empty(),
        "paired while locked: {said:#?}"
    );
}

/// A tap on "Turn ON" puts DEVICE_POWER on the wire and the phone shows the circuit on.
#[test]
fn a_tap_switches_a_circuit() {
    let Some(h) = Hangar::paired() else { return };
    h.wait_row_state("Landing Lt", "OFF", Duration::from_secs(5));
    h.browser.click("#devices .device[data-id='17'] button.act");
    h.wait_row_state("Landing Lt", "ON", Duration::from_secs(4));
    let powers: Vec<DevicePower> = (h.tap.sent().into_iter())
        .filter_map(|(_, m)| match m {
            Message::DevicePower(p) => Some(p),
            _ => None,
        })
        .collect();
    assert_eq!(
        powers,
        [DevicePower {
            device_id: 17,
            on: true
        }],
        "one DEVICE_POWER, for the Landing Lt, on"
    );
    h.browser.click("#devices .device[data-id='17'] button.act");
    h.wait_row_state("Landing Lt", "OFF", Duration::from_secs(4));
    // The starter is only reset (control's rule): no switch is offered, and a tap on
    // its button sends nothing.
    let sent_before = h.tap.sent().len();
    let button = h.browser.wait_for(
        "the starter's button",
        "const b = document.querySelector(\"#devices .device[data-id='1'] button.act\"); \
         return b.disabled && b.textContent",
        Duration::from_secs(4),
    );
    assert_eq!(button.as_str(), Some("Reset only"), "{button}");
    h.browser.click("#devices .device[data-id='1'] button.act");
    std::thread::sleep(Duration::from_millis(300));
    let starter: Vec<_> = (h.tap.sent().into_iter().skip(sent_before))
        .filter(|(_, m)| matches!(m, Message::DevicePower(p) if p.device_id == 1))
        .collect();
    assert!(starter.is_empty(), "sent for the starter: {starter:?}");
}

/// The page's own SHA-256 and HMAC (a page on http:// has no `crypto.subtle`) give
/// RFC 4231's HMAC-SHA-256 test cases 1, 2, 3, 4, 6 and 7 (6 and 7: a key longer
/// than the block) and FIPS 180-4's SHA-256 examples, written here from the RFC and
/// the standard; and signing a request takes well under 1 ms on the phone.
#[test]
fn the_pages_sha256_and_hmac_match_rfc_4231_and_signing_is_fast() {
    let Some(h) = Hangar::open() else { return };
    h.browser.goto(&h.base);
    h.browser.wait_for(
        "the page",
        "return !!window.vpxCrypto",
        Duration::from_secs(5),
    );
    let key131 = "aa".repeat(131);
    let cases = json!([
        ["0b".repeat(20), hexs(b"Hi There"),
         "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7"],
        [hexs(b"Jefe"), hexs(b"what do ya want for nothing?"),
         "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"],
        ["aa".repeat(20), "dd".repeat(50),
         "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe"],
        ["0102030405060708090a0b0c0d0e0f10111213141516171819", "cd".repeat(50),
         "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b"],
        [key131, hexs(b"Test Using Larger Than Block-Size Key - Hash Key First"),
         "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54"],
        ["aa".repeat(131), hexs(b"This is a test using a larger than block-size key and a larger than block-size data. The key needs to be hashed before being used by the HMAC algorithm."),
         "9b09ffa71b942fcb27635fbcd5b0e944bfdc63644f0713938a7f51535c3a35e2"],
    ]);
    let got = h.browser.exec(
        "const c = window.vpxCrypto; \
         const un = (s) => new Uint8Array((s.match(/../g) || []).map((x) => parseInt(x, 16))); \
         return arguments[0].map(([k, m, want]) => [c.hex(c.hmacSha256(un(k), un(m))), want]) \
           .concat([[c.hex(c.sha256(c.utf8('abc'))), \
             'ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad'], \
             [c.hex(c.sha256(c.utf8(''))), \
             'e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855'], \
             [c.hex(c.sha256(c.utf8('abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq'))), \
             '248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1']]);",
        json!([cases]),
    );
    for pair in got.as_array().unwrap() {
        assert_eq!(pair[0], pair[1], "the page's digest against the reference");
    }
    // Signing as the page does for a tap: a thousand of them, timed by the page.
    let per = h.browser.exec(
        "const c = window.vpxCrypto; const key = new Uint8Array(16).fill(7); \
         const msg = 'vpx-efis/1\\n00112233445566778899aabbccddeeff\\n12345\\n987654\\nPOST\\n\
/api/device/17/power\\n{\"on\":true}'; \
         const t0 = performance.now(); \
         for (let i = 0; i < 1000; i++) c.hmacSha256(key, c.utf8(msg + i)); \
         return (performance.now() - t0) / 1000;",
        json!([]),
    );
    let per = per.as_f64().unwrap();
    eprintln!("signing a request on the page: {:.1} µs", per * 1000.0);
    assert!(per < 1.0, "signing took {per:.3} ms a request");
}

fn hexs(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}

/// Wraps `fetch` in every page before its own script runs (DevTools'
/// `Page.addScriptToEvaluateOnNewDocument`): each request the page makes is kept, as
/// a listener on the WiFi would see it, in `window.__captured` (the events stream's
/// too) and in localStorage, which outlives a page left.
const CAPTURE: &str = "
    (() => {
      const real = window.fetch;
      window.__captured = [];
      window.fetch = function (input, init) {
        init = init || {};
        window.__captured.push({ method: init.method || 'GET', path: String(input),
          headers: Object.assign({}, init.headers || {}), body: init.body || '' });
        return real.apply(this, arguments);
      };
    })();";

/// A captured request, sent again from a plain HTTP client with the Origin the
/// browser added: status and the error's words.
fn replay(base: &str, req: &serde_json::Value, body: Option<&str>) -> (u16, String) {
    let url = format!("{base}{}", req["path"].as_str().unwrap());
    let agent: ureq::Agent = ureq::Agent::config_builder()
        .http_status_as_error(false)
        .timeout_global(Some(Duration::from_secs(5)))
        .build()
        .into();
    let headers = req["headers"].as_object().unwrap();
    let body = body.unwrap_or(req["body"].as_str().unwrap_or(""));
    let resp = match req["method"].as_str().unwrap() {
        "GET" => {
            let mut r = agent.get(&url).header("Origin", base);
            for (k, v) in headers {
                r = r.header(k, v.as_str().unwrap());
            }
            r.call()
        }
        _ => {
            let mut r = agent.post(&url).header("Origin", base);
            for (k, v) in headers {
                r = r.header(k, v.as_str().unwrap());
            }
            r.send(body)
        }
    };
    let mut resp = resp.expect("an answer");
    let status = resp.status().as_u16();
    let text = resp.body_mut().read_to_string().unwrap_or_default();
    let words = serde_json::from_str::<serde_json::Value>(&text)
        .ok()
        .and_then(|v| v["error"].as_str().map(str::to_string))
        .unwrap_or(text);
    (status, words)
}

/// A listener on the WiFi: Chromium at phone size pairs by the QR code's URL and
/// switches a circuit; every request it made, captured whole (method, path, headers,
/// body), is sent again from a plain HTTP client: refused, and nothing reaches the
/// unit; altered (another state, another device), refused. The phone still works
/// afterwards. The same for a held trim's lease renewals: sent again, they run
/// nothing.
#[test]
fn a_listener_replaying_what_the_phone_sent_is_refused_and_nothing_reaches_the_unit() {
    let Some(h) = Hangar::open() else { return };
    h.browser.cdp(
        "Page.addScriptToEvaluateOnNewDocument",
        json!({ "source": CAPTURE }),
    );
    h.pair();
    h.wait_row_state("Landing Lt", "OFF", Duration::from_secs(5));
    h.browser.click("#devices .device[data-id='17'] button.act");
    h.wait_row_state("Landing Lt", "ON", Duration::from_secs(4));
    let captured = h.browser.exec("return window.__captured", json!([]));
    let find = |method: &str, path: &str| {
        captured
            .as_array()
            .unwrap()
            .iter()
            .rev()
            .find(|r| r["method"] == method && r["path"] == path)
            .cloned()
            .unwrap_or_else(|| panic!("no {method} {path} captured: {captured}"))
    };
    let pair = find("POST", "/api/pair");
    let power = find("POST", "/api/device/17/power");
    let events = find("GET", "/api/events");
    assert_eq!(power["body"], r#"{"on":true}"#);
    let headers = power["headers"].as_object().unwrap();
    assert!(
        headers.contains_key("X-Vpx-Mac") && !headers.contains_key("Cookie"),
        "signed, with no cookie to steal: {power}"
    );
    let powers = |h: &Hangar| {
        (h.tap.sent().into_iter())
            .filter(|(_, m)| matches!(m, Message::DevicePower(_)))
            .count()
    };
    let before = powers(&h);
    assert_eq!(before, 1, "the phone's tap sent one DEVICE_POWER");
    // The replays and the forgeries.
    assert_eq!(replay(&h.base, &pair, None), (401, "wrong code".into()));
    assert_eq!(
        replay(&h.base, &power, None),
        (401, "replayed counter".into())
    );
    assert_eq!(
        replay(&h.base, &power, Some(r#"{"on":false}"#)),
        (401, "bad signature".into())
    );
    let mut other = power.clone();
    other["path"] = json!("/api/device/2/power");
    assert_eq!(
        replay(&h.base, &other, Some(r#"{"on":false}"#)),
        (401, "bad signature".into())
    );
    assert_eq!(
        replay(&h.base, &events, None),
        (401, "replayed counter".into())
    );
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(powers(&h), before, "a replay reached the unit");
    // The phone goes on: the light off from the phone.
    h.browser.click("#devices .device[data-id='17'] button.act");
    h.wait_row_state("Landing Lt", "OFF", Duration::from_secs(4));
    assert_eq!(powers(&h), before + 1);

    // A held trim: its renewals captured, the run over, then sent again.
    h.browser.exec("window.__captured = []", json!([]));
    h.browser
        .touch_hold("#motor-pitch-up", Duration::from_millis(600));
    std::thread::sleep(Duration::from_millis(600));
    let captured = h.browser.exec("return window.__captured", json!([]));
    let renewals: Vec<serde_json::Value> = (captured.as_array().unwrap().iter())
        .filter(|r| r["path"] == "/api/motor/pitch" && r["body"] == r#"{"direction":"up"}"#)
        .cloned()
        .collect();
    assert!(renewals.len() >= 3, "{captured}");
    let ran = trim_on(&h.tap.trim_moves()).len();
    assert!(ran > 0, "the trim never ran for the phone");
    for r in &renewals {
        assert_eq!(replay(&h.base, r, None), (401, "replayed counter".into()));
    }
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        trim_on(&h.tap.trim_moves()).len(),
        ran,
        "a replayed renewal ran the trim"
    );
}

/// On the phone, against the `demo` and `install` scenarios the
/// list holds the enabled devices by name (every name the scenario file gives, no pin
/// it disables) and no flap or trim row; the motors fitted show under MOTORS only.
#[test]
fn the_phone_lists_the_enabled_devices_by_name_and_motors_only_under_motors() {
    for name in ["demo", "install"] {
        let Some(h) = Hangar::open_with(Some(name)) else {
            return;
        };
        h.pair();
        let file = page_rig::ScenarioDevices::read(name);
        // Wait until the enable flags are read (no disabled pin left on the list) and
        // the names: the page's connect reads both (until then it shows a pin's own
        // name, as the page does).
        let disabled = &file.disabled;
        let names_js = serde_json::to_string(&file.names).unwrap();
        h.browser.wait_for(
            "the disabled pins gone from the list and the names read",
            &format!(
                "const rows = [...document.querySelectorAll('#devices .device')]; \
                 const ids = rows.map((r) => Number(r.dataset.id)); \
                 const name = (id) => {{ const r = rows.find((r) => Number(r.dataset.id) === id); \
                   return r ? r.querySelector('.name').textContent : null; }}; \
                 return ids.length > 0 && {disabled:?}.every((d) => !ids.includes(d)) \
                   && {names_js}.every(([id, n]) => name(id) === n)"
            ),
            Duration::from_secs(10),
        );
        let rows = h.browser.exec(
            "return [...document.querySelectorAll('#devices .device')].map((r) => \
             [Number(r.dataset.id), r.querySelector('.name').textContent, \
              r.querySelector('button.act').textContent])",
            json!([]),
        );
        let rows: Vec<(u64, String, String)> = (rows.as_array().unwrap().iter())
            .map(|r| {
                (
                    r[0].as_u64().unwrap(),
                    r[1].as_str().unwrap().to_string(),
                    r[2].as_str().unwrap().to_string(),
                )
            })
            .collect();
        let listed: Vec<(u64, String)> = rows.iter().map(|r| (r.0, r.1.clone())).collect();
        file.assert_listed(name, &listed);
        let cards = h.browser.exec(
            "return [...document.querySelectorAll('#motors .motor:not(.hidden)')].map((m) => \
             m.dataset.motor)",
            json!([]),
        );
        let fitted: Vec<&str> = ["flap", "pitch_trim", "roll_trim"]
            .into_iter()
            .zip(["flaps", "pitch", "roll"])
            .filter(|(t, _)| {
                (file.toml.get(*t))
                    .and_then(|s| s.as_table())
                    .is_some_and(|s| s.get("enabled").and_then(|e| e.as_bool()) != Some(false))
            })
            .map(|(_, m)| m)
            .collect();
        assert_eq!(cards, json!(fitted), "{name}: the motors under MOTORS");
        eprintln!("{name}: {} rows on the phone", rows.len());
    }
}

/// The installation check started at the laptop: the phone shows its DO NOW prompt
/// and the answers it offers, and an answer from the phone moves the check on.
#[test]
fn the_check_prompts_on_the_phone_and_takes_its_answers() {
    let Some(mut h) = Hangar::paired() else {
        return;
    };
    assert!(h.browser.text("#check").is_empty(), "no check yet");
    // At the laptop: hide the remote's overlay, open the check, and confirm that
    // the aircraft is safe to power (given where the list of circuits is shown).
    h.term.typed(b"\x1b");
    std::thread::sleep(Duration::from_millis(300));
    h.term.typed(b"i");
    std::thread::sleep(Duration::from_millis(500));
    h.term.typed(b"\r");
    let first = h.browser.wait_for(
        "the check's prompt",
        "const c = document.getElementById('check'); \
         return !c.classList.contains('hidden') && c.innerText",
        Duration::from_secs(6),
    );
    let first = first.as_str().unwrap().to_string();
    assert!(first.contains("DO NOW"), "{first}");
    assert!(first.contains("Flip switch 2 on"), "{first}");
    let answers = h.browser.exec(
        "return [...document.querySelectorAll('#check-answers button')].map((b) => \
         b.dataset.answer)",
        json!([]),
    );
    assert!(
        answers.as_array().unwrap().contains(&json!("skip")),
        "{answers}"
    );
    h.browser.click("#check-answers button[data-answer='skip']");
    let next = h.browser.wait_for(
        "the next prompt",
        "const p = document.getElementById('check-prompt').textContent; \
         return p.startsWith('Flip switch 2') ? null : p",
        Duration::from_secs(4),
    );
    assert!(
        next.as_str().unwrap().contains("switch 5"),
        "after skipping switch 2: {next}"
    );
}

/// A finger held on NOSE UP for 800 ms, then lifted: the trim runs while it is held,
/// and its stop is on the wire within 150 ms of `pointerup` (the page's own clock of
/// the event against the tap's clock of the byte: the same wall clock).
#[test]
fn a_held_trim_button_stops_within_150_ms_of_pointerup() {
    let Some(h) = Hangar::paired() else { return };
    h.watch_pointer();
    h.browser
        .touch_hold("#motor-pitch-up", Duration::from_millis(800));
    std::thread::sleep(Duration::from_millis(700));
    let up = h.seen("pointerup").expect("the page saw pointerup");
    let down = h.seen("pointerdown").expect("the page saw pointerdown");
    let moves = h.tap.trim_moves();
    let on = trim_on(&moves);
    assert!(!on.is_empty(), "the trim never ran: {moves:?}");
    assert!(
        wall_ms(on[0]) - down < 400.0,
        "the run began {:.0} ms after the touch",
        wall_ms(on[0]) - down
    );
    let stop = the_stop(&moves);
    let after = wall_ms(stop) - up;
    assert!(
        (0.0..=150.0).contains(&after),
        "the stop reached the wire {after:.0} ms after pointerup; TRIM_MOVEs (ms after \
         pointerdown, on): {:?}",
        moves
            .iter()
            .map(|(t, m)| ((wall_ms(*t) - down).round(), m.on))
            .collect::<Vec<_>>()
    );
    eprintln!("stop on the wire {after:.0} ms after pointerup");
}

/// A finger held on NOSE UP, and a second finger put down anywhere else on the page:
/// the run stops at once (the keys' "another key"), before either finger lifts.
#[test]
fn another_touch_stops_a_run() {
    let Some(h) = Hangar::paired() else { return };
    h.watch_pointer();
    let hold = h.browser.origin("#motor-pitch-up");
    let other = h.browser.origin("#bus-volts");
    // Two fingers, tick by tick: the first down and held; after 500 ms the second
    // comes down; both stay down another 500 ms, then lift.
    let finger = |id: &str, actions: Vec<serde_json::Value>| {
        json!({"type": "pointer", "id": id, "parameters": {"pointerType": "touch"},
               "actions": actions})
    };
    h.browser.cmd(
        "POST",
        "/actions",
        Some(json!({"actions": [
            finger("first", vec![
                json!({"type": "pointerMove", "duration": 0, "origin": hold, "x": 0, "y": 0}),
                json!({"type": "pointerDown", "button": 0}),
                json!({"type": "pause", "duration": 500}),
                json!({"type": "pause", "duration": 0}),
                json!({"type": "pause", "duration": 500}),
                json!({"type": "pointerUp", "button": 0}),
            ]),
            finger("second", vec![
                json!({"type": "pause", "duration": 0}),
                json!({"type": "pause", "duration": 0}),
                json!({"type": "pause", "duration": 500}),
                json!({"type": "pointerMove", "duration": 0, "origin": other, "x": 0, "y": 0}),
                json!({"type": "pointerDown", "button": 0}),
                json!({"type": "pointerUp", "button": 0}),
            ]),
        ]})),
    );
    h.browser.cmd("DELETE", "/actions", None);
    std::thread::sleep(Duration::from_millis(500));
    let downs = h.browser.exec(
        "return (window.__seen || []).filter((e) => e[0] === 'pointerdown').map((e) => e[1])",
        json!([]),
    );
    let downs: Vec<f64> = (downs.as_array().unwrap().iter())
        .filter_map(|v| v.as_f64())
        .collect();
    assert_eq!(downs.len(), 2, "two fingers down: {downs:?}");
    let up = h.seen("pointerup").expect("a finger lifted");
    let moves = h.tap.trim_moves();
    let stop = the_stop(&moves);
    let why = h
        .browser
        .exec("return document.body.dataset.lastStop || null", json!([]));
    let after = wall_ms(stop) - downs[1];
    assert!(
        (0.0..=150.0).contains(&after) && wall_ms(stop) <= up && why == "another touch",
        "stop {after:.0} ms after the second finger, {:.0} ms before the first lift \
         (the page's reason: {why})",
        up - wall_ms(stop)
    );
    eprintln!("stop on the wire {after:.0} ms after the second finger");
}

/// A finger on NOSE UP, not lifted, and the page left (the phone opens another
/// address): the page's own stop (on the hidden page, then `pagehide`, kept alive
/// past the page's end) is on the wire within 150 ms, well before the lease would
/// end the run (219 ms after pagehide with the page's stops taken out).
#[test]
fn leaving_the_page_mid_run_stops_it() {
    let Some(h) = Hangar::paired() else { return };
    h.browser.touch_down("#motor-pitch-up");
    h.wait_for_the_trim_to_run();
    h.browser.exec(
        "window.addEventListener('pagehide', () => \
         localStorage.setItem('pagehide', String(Date.now())))",
        json!([]),
    );
    let left = SystemTime::now();
    h.browser.goto("about:blank");
    std::thread::sleep(Duration::from_millis(800));
    let moves = h.tap.trim_moves();
    let stop = the_stop(&moves);
    // Back on the page's origin to read when it saw pagehide.
    h.browser.goto(&h.base);
    let hidden = h
        .browser
        .exec("return Number(localStorage.getItem('pagehide'))", json!([]))
        .as_f64()
        .filter(|t| *t > 0.0)
        .expect("the page saw pagehide");
    assert!(stop >= left, "stopped before the page was left: {moves:?}");
    // The page also stops on `visibilitychange` to hidden, which a browser fires just
    // before `pagehide`: the stop may lead pagehide's own timestamp by a few ms. That
    // it follows the leaving is asserted above; here, that it is not late.
    let after = wall_ms(stop) - hidden;
    assert!(after <= 150.0, "stop {after:.0} ms after pagehide");
    eprintln!("stop on the wire {after:.0} ms after pagehide");
    let _ = h.browser.cmd("DELETE", "/actions", None);
}

/// A finger on NOSE DOWN, not lifted; then the phone shows another tab (the first is
/// hidden for real: a visibility change, not a synthetic event). The run stops at
/// once, by the page's stop, well before the server's 300 ms lease would end it.
#[test]
fn hiding_the_tab_mid_run_stops_the_run() {
    let Some(h) = Hangar::paired() else { return };
    h.watch_pointer();
    h.browser.touch_down("#motor-pitch-down");
    h.wait_for_the_trim_to_run();
    let hidden_from = SystemTime::now();
    let first = h.browser.open_other_tab();
    let hidden_by = SystemTime::now();
    std::thread::sleep(Duration::from_millis(800));
    let moves = h.tap.trim_moves();
    let stop = the_stop(&moves);
    assert!(
        stop >= hidden_from,
        "stopped {:.0} ms before the tab was hidden (the page's reason: {}); TRIM_MOVEs \
         (ms after the hide, on): {:?}",
        wall_ms(hidden_from) - wall_ms(stop),
        h.browser
            .exec("return document.body.dataset.lastStop || null", json!([])),
        moves
            .iter()
            .map(|(t, m)| ((wall_ms(*t) - wall_ms(hidden_from)).round(), m.on))
            .collect::<Vec<_>>()
    );
    h.browser.switch_to(&first);
    h.browser.wait_for(
        "the first tab, visible again",
        "return document.visibilityState === 'visible' && !!window.__seen",
        Duration::from_secs(3),
    );
    let visibility = h.seen("visibilitychange");
    let why = h
        .browser
        .exec("return document.body.dataset.lastStop || null", json!([]));
    // The tab lost focus, then was hidden: the page stops at the first of the two.
    // Within 150 ms of it, so the page sent the stop (the server's lease would have
    // taken 300 ms and more).
    let blur = h.seen("blur");
    let hide = [blur, visibility]
        .into_iter()
        .flatten()
        .fold(f64::MAX, f64::min);
    assert!(
        visibility.is_some(),
        "the tab was never hidden; the page saw {}",
        h.browser.exec("return window.__seen", json!([]))
    );
    // The renderer hears of it a little after WebDriver answers, but not much.
    assert!(
        hide >= wall_ms(hidden_from) && hide <= wall_ms(hidden_by) + 500.0,
        "the hide came {:.0} ms after the new tab opened",
        hide - wall_ms(hidden_by)
    );
    let after = wall_ms(stop) - hide;
    assert!(
        (0.0..=150.0).contains(&after) && (why == "page hidden" || why == "focus lost"),
        "stop {after:.0} ms after the hide (blur {blur:?}, visibilitychange \
         {visibility:?}; the page's reason: {why})"
    );
    eprintln!(
        "stop on the wire {after:.0} ms after the tab was hidden ({why}); the page saw {}",
        h.browser.exec("return window.__seen", json!([]))
    );
    let _ = h.browser.cmd("DELETE", "/actions", None);
}

/// The laptop's page frozen (SIGSTOP: its connection stays open but says nothing):
/// after 2.5 s without an event the phone blanks every value and says so, and never
/// shows the last numbers as current.
#[test]
fn a_silent_laptop_blanks_the_phone_after_2_5_s() {
    let Some(h) = Hangar::paired() else { return };
    h.wait_row_state("EFIS", "ON", Duration::from_secs(5));
    let pid = h._page.0.id() as libc::pid_t;
    // SAFETY: signals our own child.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGSTOP) }, 0);
    let frozen = Instant::now();
    let blank = h.browser.wait_for(
        "the values blanked",
        "return !document.getElementById('stale').classList.contains('hidden') \
         && document.getElementById('bus-volts').textContent === '—' \
         && [...document.querySelectorAll('#devices .state')].every((s) => s.textContent === '—') \
         && [...document.querySelectorAll('#motors .pos')].every((p) => p.textContent === '—')",
        Duration::from_secs(6),
    );
    let took = frozen.elapsed();
    let said = h.browser.text("#stale");
    // SAFETY: as above. (After reading the banner: heard again, the phone hides it.)
    unsafe { libc::kill(pid, libc::SIGCONT) };
    assert_eq!(blank, json!(true));
    assert!(said.contains("NO DATA FROM THE LAPTOP"), "{said:?}");
    // The heartbeat comes at least every second, so the last event was at most 1 s
    // before the freeze: blanked 1.5–3.0 s after it (plus the 200 ms watch).
    assert!(
        took >= Duration::from_millis(1400) && took <= Duration::from_millis(3400),
        "blanked {took:?} after the page froze"
    );
    // Heard again: live again.
    h.wait_row_state("EFIS", "ON", Duration::from_secs(5));
}

/// The unit goes quiet (the sim's `silent`: a cable out): the phone says
/// COMMUNICATION LOST and blanks the values, then shows them again when it is back.
#[test]
fn a_quiet_unit_shows_communication_lost() {
    let Some(mut h) = Hangar::paired() else {
        return;
    };
    h.wait_row_state("EFIS", "ON", Duration::from_secs(5));
    h.console("silent 6");
    h.browser.wait_for(
        "COMMUNICATION LOST",
        "return !document.getElementById('commlost').classList.contains('hidden') \
         && document.getElementById('bus-volts').textContent === '—' \
         && [...document.querySelectorAll('#devices .state')].every((s) => s.textContent === '—')",
        Duration::from_secs(6),
    );
    assert!(h.browser.text("#commlost").contains("COMMUNICATION LOST"));
    // The motors fitted stay on screen, blank and disabled: a lost unit is not a
    // unit without flaps.
    let motors = h.browser.exec(
        "return [...document.querySelectorAll('#motors .motor:not(.hidden)')].map((m) => \
         [m.querySelector('.pos').textContent, m.querySelector('button').disabled])",
        json!([]),
    );
    assert_eq!(
        motors,
        json!([["—", true], ["—", true]]),
        "flaps and pitch trim"
    );
    h.wait_row_state("EFIS", "ON", Duration::from_secs(10));
    assert!(h.browser.text("#commlost").is_empty(), "still says lost");
}

/// Every text the page draws meets WCAG's 4.5:1 against what is behind it, in the
/// phone's light and dark settings alike (sunlight at the wingtip): the state words
/// ON, OFF and FAULT, the values, the buttons, the banners, the notice.
#[test]
fn every_text_meets_wcag_contrast_light_and_dark() {
    let Some(mut h) = Hangar::paired() else {
        return;
    };
    h.console("switch 2 on");
    h.console("fault 5 8");
    h.browser.wait_for(
        "ON, OFF and FAULT on the list",
        "const s = [...document.querySelectorAll('#devices .state')].map((e) => e.className); \
         return ['on', 'off', 'fault'].every((c) => s.includes('state ' + c))",
        Duration::from_secs(5),
    );
    // The fault in words (ICD Table 43's 0x08 OVER_CURRENT), not only in red.
    let fault = h.browser.exec(
        "return [...document.querySelectorAll('#devices .state.fault')].map((e) => e.textContent)",
        json!([]),
    );
    assert_eq!(fault, json!(["FAULT: OVER CURRENT"]));
    // The banners and the notice as they show when they do.
    h.browser.exec(
        "for (const id of ['stale', 'commlost', 'notice']) \
         document.getElementById(id).classList.remove('hidden'); \
         document.getElementById('notice').classList.add('refused');",
        json!([]),
    );
    const RATIOS: &str = "
        const lin = (c) => { c /= 255; return c <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4; };
        const rgb = (s) => s.match(/[\\d.]+/g).map(Number);
        const lum = ([r, g, b]) => 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
        const bg = (e) => { for (; e; e = e.parentElement) { const c = rgb(getComputedStyle(e).backgroundColor);
            if (c.length < 4 || c[3] > 0) return c.slice(0, 3); } return [255, 255, 255]; };
        const out = [];
        for (const e of document.querySelectorAll('#live *, #notice, header *')) {
            if (![...e.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim())) continue;
            if (e.closest('.hidden') && !e.closest('#stale, #commlost, #notice')) continue;
            const a = lum(rgb(getComputedStyle(e).color)), b = lum(bg(e));
            const ratio = (Math.max(a, b) + 0.05) / (Math.min(a, b) + 0.05);
            out.push([e.tagName + '.' + e.className + ' ' + e.textContent.trim().slice(0, 24), ratio]);
        }
        return [getComputedStyle(document.body).backgroundColor, out];";
    let mut backgrounds = Vec::new();
    for scheme in ["light", "dark"] {
        h.browser.color_scheme(scheme);
        std::thread::sleep(Duration::from_millis(200));
        let v = h.browser.exec(RATIOS, json!([]));
        backgrounds.push(v[0].clone());
        let all = v[1].as_array().unwrap();
        assert!(all.len() > 20, "{scheme}: only {} texts", all.len());
        let poor: Vec<_> = all
            .iter()
            .filter(|r| r[1].as_f64().unwrap() < 4.5)
            .collect();
        assert!(poor.is_empty(), "{scheme}: under 4.5:1: {poor:?}");
        let least = (all.iter())
            .min_by(|a, b| a[1].as_f64().unwrap().total_cmp(&b[1].as_f64().unwrap()))
            .unwrap();
        eprintln!("{scheme}: {} texts, the least contrast {least}", all.len());
    }
    assert_eq!(
        backgrounds,
        [json!("rgb(255, 255, 255)"), json!("rgb(0, 0, 0)")],
        "the phone's setting picks the page's colours"
    );
}

/// The guide's screenshots of the phone page, light and dark, at 390×844: run by
/// `scripts/screenshots` (or by hand, `cargo test --test remote_browser -- --ignored
/// readme_screenshots`) when the page's look changes, then commit
/// `docs/src/images/remote-*.png`.
#[test]
#[ignore = "writes the guide's screenshots; run by scripts/screenshots"]
fn readme_screenshots() {
    let Some(mut h) = Hangar::paired() else {
        return;
    };
    // The lights on, one of them faulted: the three states a row can show.
    h.console("switch 2 on");
    h.console("switch 7 on");
    h.console("fault 5 8");
    h.wait_row_state("Nav Lt", "ON", Duration::from_secs(4));
    h.browser.wait_for(
        "the strobe's fault",
        "return [...document.querySelectorAll('#devices .state')].some((s) => \
         s.textContent.startsWith('FAULT'))",
        Duration::from_secs(4),
    );
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/src/images");
    std::fs::create_dir_all(&docs).unwrap();
    // Light at the top (totals, motors), dark at the lights.
    for scheme in ["light", "dark"] {
        if scheme == "dark" {
            h.browser.exec(
                "document.querySelector('#devices .device[data-id=\"2\"]').scrollIntoView()",
                json!([]),
            );
        }
        h.browser.color_scheme(scheme);
        std::thread::sleep(Duration::from_millis(300));
        let png = h.browser.screenshot();
        assert_eq!(&png[1..4], b"PNG");
        std::fs::write(docs.join(format!("remote-{scheme}.png")), png).unwrap();
    }
}

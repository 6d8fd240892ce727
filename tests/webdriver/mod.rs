//! A headless Chromium driven through W3C WebDriver (Debian's `chromium` and
//! `chromium-driver`), spoken as JSON over HTTP with ureq: only the few commands the
//! browser tests need. Shared by the tests that include it (`mod webdriver;`).
//!
//! When chromedriver (`CHROMEDRIVER`, or on the PATH) or chromium is missing,
//! [`Browser::start`] prints why and returns `None` so that a developer's `cargo test`
//! skips; with `CI` set it panics instead, so CI (whose `.ci/run` installs both) never
//! passes by skipping.
#![allow(dead_code)]

use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine;
use serde_json::{Value, json};

/// The W3C name of an element reference in a command's JSON.
const ELEMENT: &str = "element-6066-11e4-a52e-4f735466cecf";

/// The phone's screen: an iPhone 12–15's CSS viewport.
pub const WIDTH: u32 = 390;
pub const HEIGHT: u32 = 844;

/// One chromedriver process and one browser session in it, both ended when dropped.
pub struct Browser {
    driver: Child,
    base: String,
    agent: ureq::Agent,
    profile: tempfile::TempDir,
}

fn find_program(names: &[&str]) -> Option<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    for name in names {
        for dir in std::env::split_paths(&path).chain([PathBuf::from("/usr/bin")]) {
            let candidate = dir.join(name);
            if candidate.is_file() {
                return Some(candidate);
            }
        }
    }
    None
}

/// Skips (returns `None`, with a message) or, under CI, fails.
fn missing(what: &str) -> Option<Browser> {
    let msg = format!(
        "{what} not found: the browser tests need Debian's `chromium` and `chromium-driver` \
         (apt-get install chromium chromium-driver; .ci/run installs them)"
    );
    if std::env::var_os("CI").is_some() {
        panic!("{msg}; CI is set, so this is a failure, not a skip");
    }
    // Straight to stderr, past the test harness's capture: a skip is seen.
    let _ = writeln!(std::io::stderr(), "SKIPPED: {msg}");
    None
}

pub fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port on 127.0.0.1")
}

impl Browser {
    /// chromedriver on a free port and a fresh headless Chromium at 390×844 with a
    /// profile of its own; `dark` asks for `prefers-color-scheme: dark`.
    pub fn start() -> Option<Browser> {
        // CHROMEDRIVER names another driver (or none: a path that is not there).
        let driver_path = match std::env::var_os("CHROMEDRIVER") {
            Some(p) => Some(PathBuf::from(p)).filter(|p| p.is_file()),
            None => find_program(&["chromedriver"]),
        };
        let Some(driver_path) = driver_path else {
            return missing("chromedriver");
        };
        let Some(chromium) = find_program(&["chromium", "chromium-browser"]) else {
            return missing("chromium");
        };
        let port = free_port();
        let mut driver = Command::new(&driver_path)
            .arg(format!("--port={port}"))
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromedriver");
        // It prints "ChromeDriver was started successfully on port N." when it listens.
        let stdout = driver.stdout.take().expect("chromedriver's stdout");
        let mut lines = BufReader::new(stdout).lines();
        let started = lines.by_ref().take(20).any(|l| {
            l.map(|l| l.contains("started successfully"))
                .unwrap_or(false)
        });
        // Keep draining its output so that it never blocks on a full pipe.
        std::thread::spawn(move || for _ in lines {});
        let profile = tempfile::tempdir().expect("a fresh profile directory");
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .timeout_global(Some(Duration::from_secs(60)))
            .build()
            .into();
        let mut browser = Browser {
            driver,
            base: format!("http://127.0.0.1:{port}"),
            agent,
            profile,
        };
        assert!(
            started,
            "chromedriver ({}) did not start",
            driver_path.display()
        );
        browser.new_session(&chromium);
        Some(browser)
    }

    fn new_session(&mut self, chromium: &Path) {
        let args = [
            "--headless".to_string(),
            "--no-sandbox".into(),
            "--disable-gpu".into(),
            "--disable-quic".into(),
            "--no-first-run".into(),
            "--disable-background-networking".into(),
            "--disable-component-update".into(),
            "--disable-sync".into(),
            format!("--window-size={WIDTH},{HEIGHT}"),
            format!("--user-data-dir={}", self.profile.path().display()),
        ];
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            // A desktop window cannot be narrower than 500 px: the phone's viewport
            // comes from Chromium's mobile emulation (touch, a phone's metrics).
            "goog:chromeOptions": {"binary": chromium, "args": args, "mobileEmulation": {
                "deviceMetrics": {"width": WIDTH, "height": HEIGHT, "pixelRatio": 1.0,
                                  "touch": true, "mobile": true},
            }},
        }}});
        let value = self
            .raw("POST", "/session", Some(caps))
            .expect("a browser session");
        let id = value["sessionId"]
            .as_str()
            .expect("a session id")
            .to_string();
        self.base = format!("{}/session/{id}", self.base);
    }

    /// One command; `Err` with WebDriver's error and message when it failed.
    fn raw(&self, method: &str, path: &str, body: Option<Value>) -> Result<Value, String> {
        let url = format!("{}{path}", self.base);
        let response = match method {
            "GET" => self.agent.get(&url).call(),
            "DELETE" => self.agent.delete(&url).call(),
            _ => self
                .agent
                .post(&url)
                .send_json(body.unwrap_or_else(|| json!({}))),
        };
        let mut response = response.map_err(|e| format!("{method} {path}: {e}"))?;
        let status = response.status().as_u16();
        let reply: Value = response
            .body_mut()
            .with_config()
            .limit(64 << 20)
            .read_json()
            .map_err(|e| format!("{method} {path}: {e}"))?;
        let value = reply["value"].clone();
        if status != 200 {
            return Err(format!(
                "{method} {path}: {} ({status}): {}",
                value["error"], value["message"]
            ));
        }
        Ok(value)
    }

    /// A command in this session that must succeed.
    pub fn cmd(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        self.raw(method, path, body)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    pub fn goto(&self, url: &str) {
        self.cmd("POST", "/url", Some(json!({ "url": url })));
    }

    pub fn url(&self) -> String {
        self.cmd("GET", "/url", None)
            .as_str()
            .unwrap_or("")
            .to_string()
    }

    /// A script's value; `arguments[i]` are `args`.
    pub fn exec(&self, script: &str, args: Value) -> Value {
        self.cmd(
            "POST",
            "/execute/sync",
            Some(json!({ "script": script, "args": args })),
        )
    }

    /// Polls `script` (an expression's `return`) until it returns something truthy, and
    /// returns that; panics after `timeout` with `what` and the last value.
    pub fn wait_for(&self, what: &str, script: &str, timeout: Duration) -> Value {
        let start = Instant::now();
        loop {
            let v = self.exec(script, json!([]));
            let truthy =
                !(v.is_null() || v == Value::Bool(false) || v == json!("") || v == json!(0));
            if truthy {
                return v;
            }
            assert!(
                start.elapsed() < timeout,
                "waited {timeout:?} for {what}; last: {v}\npage: {}",
                self.text("body")
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// The element a CSS selector finds first.
    pub fn find(&self, css: &str) -> String {
        let v = self.cmd(
            "POST",
            "/element",
            Some(json!({"using": "css selector", "value": css})),
        );
        v[ELEMENT]
            .as_str()
            .expect("an element reference")
            .to_string()
    }

    pub fn click(&self, css: &str) {
        let e = self.find(css);
        self.cmd("POST", &format!("/element/{e}/click"), Some(json!({})));
    }

    pub fn type_into(&self, css: &str, text: &str) {
        let e = self.find(css);
        self.cmd(
            "POST",
            &format!("/element/{e}/value"),
            Some(json!({ "text": text })),
        );
    }

    /// The rendered text of the first element `css` finds.
    pub fn text(&self, css: &str) -> String {
        match self.raw(
            "POST",
            "/element",
            Some(json!({"using": "css selector", "value": css})),
        ) {
            Ok(v) => {
                let e = v[ELEMENT].as_str().unwrap_or_default().to_string();
                self.cmd("GET", &format!("/element/{e}/text"), None)
                    .as_str()
                    .unwrap_or("")
                    .to_string()
            }
            Err(e) => format!("<{e}>"),
        }
    }

    /// A touch on the element `css` finds: down, held for `hold`, up — WebDriver
    /// Actions with a pointer of type touch, as a finger on a phone.
    pub fn touch_hold(&self, css: &str, hold: Duration) {
        self.touch(
            css,
            &[
                json!({"type": "pause", "duration": hold.as_millis() as u64}),
                json!({"type": "pointerUp", "button": 0}),
            ],
        );
        self.cmd("DELETE", "/actions", None);
    }

    /// A touch put down on the element `css` finds and left there: the run goes on
    /// until something else stops it.
    pub fn touch_down(&self, css: &str) {
        self.touch(css, &[]);
    }

    /// The element `css` finds, as an Actions origin.
    pub fn origin(&self, css: &str) -> Value {
        json!({ ELEMENT: self.find(css) })
    }

    /// A finger onto the element, down, then `then`.
    fn touch(&self, css: &str, then: &[Value]) {
        let e = self.find(css);
        let mut actions = vec![
            json!({"type": "pointerMove", "duration": 0, "origin": { ELEMENT: e }, "x": 0, "y": 0}),
            json!({"type": "pointerDown", "button": 0}),
        ];
        actions.extend_from_slice(then);
        self.cmd(
            "POST",
            "/actions",
            Some(json!({"actions": [{
                "type": "pointer",
                "id": "finger",
                "parameters": {"pointerType": "touch"},
                "actions": actions,
            }]})),
        );
    }

    /// Opens a new tab and switches to it, so that the first is hidden; returns the
    /// first tab's handle.
    pub fn open_other_tab(&self) -> String {
        let first = self
            .cmd("GET", "/window", None)
            .as_str()
            .unwrap()
            .to_string();
        let new = self.cmd("POST", "/window/new", Some(json!({"type": "tab"})));
        let handle = new["handle"].as_str().expect("a new tab").to_string();
        self.cmd("POST", "/window", Some(json!({ "handle": handle })));
        first
    }

    pub fn switch_to(&self, handle: &str) {
        self.cmd("POST", "/window", Some(json!({ "handle": handle })));
    }

    /// A Chrome DevTools command, through chromedriver's `goog/cdp/execute`.
    pub fn cdp(&self, cmd: &str, params: Value) -> Value {
        self.cmd(
            "POST",
            "/goog/cdp/execute",
            Some(json!({ "cmd": cmd, "params": params })),
        )
    }

    /// Emulates the phone's light or dark setting (`prefers-color-scheme`).
    pub fn color_scheme(&self, scheme: &str) {
        self.cdp(
            "Emulation.setEmulatedMedia",
            json!({"features": [{"name": "prefers-color-scheme", "value": scheme}]}),
        );
    }

    /// The viewport as a PNG.
    pub fn screenshot(&self) -> Vec<u8> {
        let b64 = self.cmd("GET", "/screenshot", None);
        base64::engine::general_purpose::STANDARD
            .decode(b64.as_str().expect("base64 text"))
            .expect("a PNG in base64")
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        // End the session (it closes Chromium), then chromedriver.
        if self.base.contains("/session/") {
            let _ = self.raw("DELETE", "", None);
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

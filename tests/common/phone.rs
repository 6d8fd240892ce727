//! A phone in Rust, for the remote's tests: it pairs by the QR code's URL (the key in
//! its fragment) or by typed words, and signs every request as the phone's page does
//! (`vpx_efis::remote::signing`): the session, a counter that only grows, the
//! laptop's time as reckoned from its `X-Vpx-Now`, the method, the path and the body.
//! A request can also be made without sending it ([`Phone::request`]) and sent later
//! as it is ([`send`]): a listener's replay.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use base64::Engine;
use serde_json::Value;
use vpx_efis::remote::pairing::typed_key;
use vpx_efis::remote::signing::{self, H_COUNTER, H_MAC, H_NOW, H_SESSION, H_TIME};

pub fn agent() -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .timeout_global(Some(Duration::from_secs(5)))
        .build()
        .into()
}

/// An HTTP answer: status, the headers we look at, the body as JSON (or Null).
#[derive(Debug, Clone)]
pub struct Answer {
    pub status: u16,
    pub retry_after: Option<String>,
    pub now_ms: Option<u64>,
    pub body: Value,
}

pub fn answer(r: Result<ureq::http::Response<ureq::Body>, ureq::Error>) -> Answer {
    let mut r = r.expect("an HTTP answer");
    let header = |n: &str| {
        r.headers()
            .get(n)
            .and_then(|v| v.to_str().ok())
            .map(str::to_string)
    };
    let (retry_after, now_ms) = (header("retry-after"), header(H_NOW));
    let status = r.status().as_u16();
    let text = r.body_mut().read_to_string().unwrap_or_default();
    Answer {
        status,
        retry_after,
        now_ms: now_ms.and_then(|n| n.parse().ok()),
        body: serde_json::from_str(&text).unwrap_or(Value::Null),
    }
}

/// A request as it goes on the network: what a listener sees, whole.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sent {
    pub method: String,
    pub path: String,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

/// Sends `req` to `base` exactly as it is.
pub fn send(base: &str, req: &Sent) -> Answer {
    let url = format!("{base}{}", req.path);
    let a = agent();
    answer(match req.method.as_str() {
        "GET" => {
            let mut r = a.get(&url);
            for (k, v) in &req.headers {
                r = r.header(k, v);
            }
            r.call()
        }
        _ => {
            let mut r = a.post(&url);
            for (k, v) in &req.headers {
                r = r.header(k, v);
            }
            r.send(&req.body[..])
        }
    })
}

/// `http://host:port/#k=KEY` → (`http://host:port`, the key).
pub fn split_pairing_url(url: &str) -> (String, Vec<u8>) {
    let (base, key) = url.split_once("/#k=").expect("a pairing URL, /#k=KEY");
    let key = base64::engine::general_purpose::URL_SAFE_NO_PAD
        .decode(key)
        .expect("the key in base64url");
    (base.to_string(), key)
}

/// `http://host:port/some/path` → `http://host:port`.
fn base_of(url: &str) -> Option<String> {
    let rest = url.strip_prefix("http://")?;
    Some(format!(
        "http://{}",
        &rest[..rest.find('/').unwrap_or(rest.len())]
    ))
}

/// `http://host:port/some/path` or `/some/path` → the path.
fn path_of(url: &str) -> String {
    match url.strip_prefix("http://") {
        Some(rest) => rest[rest.find('/').unwrap_or(rest.len())..].to_string(),
        None => url.to_string(),
    }
}

struct Inner {
    session: String,
    key: Vec<u8>,
    counter: u64,
    /// The laptop's clock at `at`.
    laptop_ms: u64,
    at: Instant,
}

/// A paired phone. Clones share the session and its counter, as the page's requests
/// do.
#[derive(Clone)]
pub struct Phone {
    pub base: String,
    inner: Arc<Mutex<Inner>>,
    /// Sent as `Origin` when set.
    pub origin: Option<String>,
    pub typed: bool,
}

/// Signs `POST /api/pair` with `key` and sends it: a phone, or the refusal.
pub fn pair_with(base: &str, key: &[u8], origin: Option<&str>) -> Result<Phone, Answer> {
    let mac = signing::sign(
        key,
        "",
        0,
        0,
        signing::Request::new("POST", "/api/pair", b""),
    );
    let mut req = agent()
        .post(format!("{base}/api/pair"))
        .header(H_COUNTER, "0")
        .header(H_TIME, "0")
        .header(H_MAC, &mac);
    if let Some(o) = origin {
        req = req.header("Origin", o);
    }
    let a = answer(req.send_empty());
    if a.status != 200 {
        return Err(a);
    }
    Ok(Phone {
        base: base.to_string(),
        inner: Arc::new(Mutex::new(Inner {
            session: a.body["session"].as_str().expect("a session").to_string(),
            key: key.to_vec(),
            counter: 0,
            laptop_ms: a.body["now_ms"].as_u64().expect("the laptop's clock"),
            at: Instant::now(),
        })),
        origin: None,
        typed: a.body["typed"] == true,
    })
}

impl Phone {
    /// Pairs as a phone that scanned the QR code: `http://host:port/#k=KEY`.
    pub fn scan(url: &str) -> Result<Phone, Answer> {
        let (base, key) = split_pairing_url(url);
        pair_with(&base, &key, None)
    }

    /// Pairs by typed words.
    pub fn type_words(base: &str, words: &str) -> Result<Phone, Answer> {
        pair_with(base, &typed_key(words), None)
    }

    /// The same phone, its requests sent with `Origin: origin`.
    pub fn with_origin(&self, origin: &str) -> Phone {
        Phone {
            origin: Some(origin.to_string()),
            ..self.clone()
        }
    }

    pub fn session(&self) -> String {
        self.inner.lock().unwrap().session.clone()
    }

    /// The request signed, not sent.
    pub fn request(&self, method: &str, url: &str, body: Option<&Value>) -> Sent {
        let path = path_of(url);
        let body = body
            .map(|b| serde_json::to_vec(b).unwrap())
            .unwrap_or_default();
        let mut i = self.inner.lock().unwrap();
        i.counter += 1;
        let time = i.laptop_ms + i.at.elapsed().as_millis() as u64;
        let asked = signing::Request::new(method, &path, &body);
        let mac = signing::sign(&i.key, &i.session, i.counter, time, asked);
        let mut headers = vec![
            (H_SESSION.to_string(), i.session.clone()),
            (H_COUNTER.to_string(), i.counter.to_string()),
            (H_TIME.to_string(), time.to_string()),
            (H_MAC.to_string(), mac),
        ];
        if !body.is_empty() {
            headers.push(("Content-Type".into(), "application/json".into()));
        }
        if let Some(o) = &self.origin {
            headers.push(("Origin".into(), o.clone()));
        }
        Sent {
            method: method.to_string(),
            path,
            headers,
            body,
        }
    }

    fn heard(&self, a: &Answer) {
        if let Some(now) = a.now_ms {
            let mut i = self.inner.lock().unwrap();
            i.laptop_ms = now;
            i.at = Instant::now();
        }
    }

    /// `url`: a path, or a whole URL (another address than the one paired with).
    pub fn get(&self, url: &str) -> Answer {
        let base = base_of(url).unwrap_or_else(|| self.base.clone());
        let a = send(&base, &self.request("GET", url, None));
        self.heard(&a);
        a
    }

    pub fn post(&self, url: &str, body: Option<Value>) -> Answer {
        let base = base_of(url).unwrap_or_else(|| self.base.clone());
        let a = send(&base, &self.request("POST", url, body.as_ref()));
        self.heard(&a);
        a
    }

    /// `GET /api/events`, signed: the open stream.
    pub fn events(&self) -> ureq::http::Response<ureq::Body> {
        let req = self.request("GET", "/api/events", None);
        let mut r = agent()
            .get(format!("{}{}", self.base, req.path))
            .config()
            .timeout_global(None)
            .build();
        for (k, v) in &req.headers {
            r = r.header(k, v);
        }
        r.call().expect("the events stream")
    }
}

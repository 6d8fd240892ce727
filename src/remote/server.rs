//! The HTTP side: axum routes on a current-thread tokio runtime, on a thread of its
//! own. It reads the model for the state and hands every command to the page as a
//! [`Request`], whose answer it waits for: the page carries it out through `control`
//! (nothing here sends anything to the unit).
//!
//! Before any route: a foreign `Origin` gets 403; then every `/api/*` route but
//! `/api/pair` needs a paired session (401 "not paired") and a request signed with
//! its key ([`super::signing`]: 401 with the refusal's words), so nothing reaches a
//! handler, let alone the page, that a listener could have sent. `/api/pair` checks
//! its own signature against the offer ([`super::pairing`]).

use std::convert::Infallible;
use std::net::SocketAddr;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use axum::Json;
use axum::Router;
use axum::body::{Body, Bytes};
use axum::extract::{Path, Request as HttpRequest, State as Ctx};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::sse::{Event, Sse};
use axum::response::{Html, IntoResponse, Response};
use axum::routing::{get, post};
use crossbeam_channel::Sender;
use serde::Deserialize;
use serde_json::json;
use tokio::sync::{Notify, oneshot};

use super::pairing::{Denied, How, PairResult, Pairing};
use super::signing::{self, Claim};
use super::state::{self, PageSide};
use super::{Command, Reply, Request};
use crate::control::Direction;
use crate::model::{Model, Motor, TrimKind};

/// The phone page, compiled in.
const INDEX: &str = include_str!("../../assets/remote/index.html");
/// The largest request body taken: every one the phone sends is a few bytes.
const MAX_BODY: usize = 4096;
/// The longest the events stream goes without sending the state: the phone's sign
/// that the page is alive.
pub const HEARTBEAT: Duration = Duration::from_millis(1000);
/// The least time between two looks at the state on an events stream: changes
/// closer together go as one. The unit's 10 Hz motor status changes the model ten
/// times a second, mostly to the same values; building the state that often cost an
/// idle page with a phone connected about 0.3 % of a core (debug build), over the
/// idle budget. Half a second is still live to a person watching a phone.
pub const EVENTS_GAP: Duration = Duration::from_millis(500);
/// How long a command waits for the page to answer before the phone hears 503.
const PAGE_ANSWER: Duration = Duration::from_secs(2);

/// What the server and the page share.
pub struct Shared {
    pub(super) pairing: Mutex<Pairing>,
    pub(super) page: Mutex<PageSide>,
    /// The state last served and its number: `seq` counts changes.
    published: Mutex<(u64, Option<String>)>,
    /// Poked by the page when the model or its side changed.
    pub(super) changed: Notify,
    /// The laptop's clock for signed requests starts here.
    epoch: Instant,
}

impl Shared {
    pub(super) fn new(pairing: Pairing) -> Shared {
        Shared {
            pairing: Mutex::new(pairing),
            page: Mutex::new(PageSide::default()),
            published: Mutex::new((0, None)),
            changed: Notify::new(),
            epoch: Instant::now(),
        }
    }

    /// The laptop's clock as signed requests carry it: ms since the remote started.
    pub(super) fn now_ms(&self) -> u64 {
        self.epoch.elapsed().as_millis() as u64
    }

    pub(super) fn pairing(&self) -> MutexGuard<'_, Pairing> {
        self.pairing.lock().unwrap_or_else(|p| p.into_inner())
    }
}

#[derive(Clone)]
struct Server {
    shared: Arc<Shared>,
    model: Arc<Mutex<Model>>,
    requests: Sender<Request>,
    /// `http://ADDR:PORT`, the only Origin taken.
    origin: String,
    /// Bound to every address (`--remote 0.0.0.0:PORT`): the page's own origin is
    /// the address the phone used, `http://` + its Host header, taken only as an IP
    /// address (a name could be a rebinding attacker's).
    any_address: bool,
}

impl Server {
    fn origin_ok(&self, origin: &[u8], host: Option<&[u8]>) -> bool {
        if origin == self.origin.as_bytes() {
            return true;
        }
        let Some(host) = host.and_then(|h| std::str::from_utf8(h).ok()) else {
            return false;
        };
        self.any_address
            && host.parse::<SocketAddr>().is_ok()
            && origin.strip_prefix(b"http://") == Some(host.as_bytes())
    }
}

pub(super) fn router(
    shared: Arc<Shared>,
    model: Arc<Mutex<Model>>,
    requests: Sender<Request>,
    bound: SocketAddr,
) -> Router {
    let server = Server {
        shared,
        model,
        requests,
        origin: format!("http://{bound}"),
        any_address: bound.ip().is_unspecified(),
    };
    Router::new()
        .route("/", get(index))
        .route("/api/pair", post(pair))
        .route("/api/state", get(state_now))
        .route("/api/events", get(events))
        .route("/api/device/{id}/power", post(power))
        .route("/api/device/{id}/clear", post(clear))
        .route("/api/motor/{motor}", post(motor))
        .route("/api/check/answer", post(check_answer))
        .route("/api/logout", post(logout))
        .fallback(not_found)
        .layer(middleware::from_fn_with_state(server.clone(), gate))
        .with_state(server)
}

fn error(status: StatusCode, words: &str) -> Response {
    (status, Json(json!({ "error": words }))).into_response()
}

fn refused(words: String) -> Response {
    (StatusCode::CONFLICT, Json(json!({ "refused": words }))).into_response()
}

/// The session a request names (`X-Vpx-Session`), if any.
fn session_of(headers: &HeaderMap) -> Option<String> {
    headers
        .get(signing::H_SESSION)
        .and_then(|v| v.to_str().ok())
        .map(str::to_string)
}

/// The signature's headers, if all four are there and readable.
fn claim_of(headers: &HeaderMap) -> Option<Claim> {
    let text = |name: &str| headers.get(name).and_then(|v| v.to_str().ok());
    Some(Claim {
        session: text(signing::H_SESSION).unwrap_or_default().to_string(),
        counter: text(signing::H_COUNTER)?.parse().ok()?,
        time_ms: text(signing::H_TIME)?.parse().ok()?,
        mac: text(signing::H_MAC)?.to_string(),
    })
}

/// 401 in the words of a signature's refusal, with the laptop's clock in the body
/// too, so that a phone whose reckoning drifted can set it right and sign again.
fn unsigned(s: &Server, words: &str) -> Response {
    (
        StatusCode::UNAUTHORIZED,
        Json(json!({ "error": words, "now_ms": s.shared.now_ms() })),
    )
        .into_response()
}

/// Origin first (403), then the session and its signature (401) for every `/api/*`
/// but the pairing, which checks its own. The body is read here (at most
/// [`MAX_BODY`]), as the signature covers it, and handed on as it came.
async fn gate(Ctx(s): Ctx<Server>, req: HttpRequest, next: Next) -> Response {
    let host = req.headers().get(header::HOST).map(HeaderValue::as_bytes);
    if let Some(origin) = req.headers().get(header::ORIGIN)
        && !s.origin_ok(origin.as_bytes(), host)
    {
        return error(StatusCode::FORBIDDEN, "origin");
    }
    let path = req.uri().path().to_string();
    let req = if path.starts_with("/api/") && path != "/api/pair" {
        let paired = session_of(req.headers()).is_some_and(|t| s.shared.pairing().is_session(&t));
        if !paired {
            return error(StatusCode::UNAUTHORIZED, "not paired");
        }
        let Some(claim) = claim_of(req.headers()) else {
            return unsigned(&s, &signing::BadSignature::Malformed.to_string());
        };
        let (parts, body) = req.into_parts();
        let Ok(body) = axum::body::to_bytes(body, MAX_BODY).await else {
            return error(StatusCode::PAYLOAD_TOO_LARGE, "body too large");
        };
        let target = parts
            .uri
            .path_and_query()
            .map_or(path.as_str(), |p| p.as_str());
        let asked = signing::Request::new(parts.method.as_str(), target, &body);
        let verdict = s.shared.pairing().verify(&claim, asked, s.shared.now_ms());
        match verdict {
            Ok(_) => {}
            Err(Denied::NotPaired) => return error(StatusCode::UNAUTHORIZED, "not paired"),
            Err(Denied::Signature(why)) => return unsigned(&s, &why.to_string()),
        }
        HttpRequest::from_parts(parts, Body::from(body))
    } else {
        req
    };
    let mut resp = next.run(req).await;
    // Nothing here may be cached: a state is only true when it is fetched.
    resp.headers_mut()
        .insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    if let Ok(v) = HeaderValue::from_str(&s.shared.now_ms().to_string()) {
        resp.headers_mut().insert(signing::H_NOW, v);
    }
    resp
}

async fn not_found() -> Response {
    error(StatusCode::NOT_FOUND, "no such route")
}

async fn index() -> Html<&'static str> {
    Html(INDEX)
}

/// `POST /api/pair`, signed with the QR code's key or the typed words' key (session
/// "", counter 0). Its body is not read: the signature alone says which offer.
async fn pair(Ctx(s): Ctx<Server>, headers: HeaderMap, body: Bytes) -> Response {
    let Some(claim) = claim_of(&headers) else {
        return error(
            StatusCode::BAD_REQUEST,
            "sign the pairing with the QR code's key or the typed words",
        );
    };
    let result = s.shared.pairing().pair(&claim, &body, Instant::now());
    // The title's count and the overlay's code changed.
    s.shared.changed.notify_waiters();
    match result {
        PairResult::Paired { session, how } => Json(json!({
            "paired": true,
            "session": session,
            "typed": how == How::Typed,
            "now_ms": s.shared.now_ms(),
        }))
        .into_response(),
        PairResult::Wrong => error(StatusCode::UNAUTHORIZED, "wrong code"),
        PairResult::Locked(secs) => (
            StatusCode::TOO_MANY_REQUESTS,
            [(header::RETRY_AFTER, secs.to_string())],
            Json(json!({ "error": "locked", "retry_after_s": secs })),
        )
            .into_response(),
    }
}

impl Server {
    /// The state now, as JSON, numbered: `seq` moves on when anything else changed.
    fn state_json(&self) -> String {
        let page = self
            .shared
            .page
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .clone();
        let st = {
            let model = self.model.lock().unwrap_or_else(|p| p.into_inner());
            state::build(&model, &page, Instant::now())
        };
        // Serialized once, with seq 0 first, then numbered in place.
        let body = serde_json::to_string(&st).unwrap_or_default();
        let mut published = self
            .shared
            .published
            .lock()
            .unwrap_or_else(|p| p.into_inner());
        let numbered = match body.strip_prefix("{\"seq\":0,") {
            Some(rest) => {
                if published.1.as_deref() != Some(body.as_str()) {
                    published.0 += 1;
                }
                format!("{{\"seq\":{},{rest}", published.0)
            }
            None => body.clone(),
        };
        published.1 = Some(body);
        numbered
    }

    /// Hands `command` to the page and waits for its answer.
    async fn ask(&self, command: Command) -> Result<Reply, Response> {
        let (tx, rx) = oneshot::channel();
        if self.requests.send(Request { command, reply: tx }).is_err() {
            return Err(error(
                StatusCode::SERVICE_UNAVAILABLE,
                "the page is closing",
            ));
        }
        match tokio::time::timeout(PAGE_ANSWER, rx).await {
            Ok(Ok(r)) => Ok(r),
            _ => Err(error(
                StatusCode::SERVICE_UNAVAILABLE,
                "the page did not answer",
            )),
        }
    }

    async fn command(&self, command: Command) -> Response {
        match self.ask(command).await {
            Ok(reply) => reply.into_response(),
            Err(resp) => resp,
        }
    }
}

impl IntoResponse for Reply {
    fn into_response(self) -> Response {
        match self {
            Reply::Sent(words) => Json(json!({ "sent": words })).into_response(),
            Reply::Refused(words) => refused(words),
            Reply::NoDevice(id) => error(StatusCode::NOT_FOUND, &format!("no device {id}")),
            Reply::Leased(ms) => Json(json!({ "lease_ms": ms })).into_response(),
            Reply::Stopped => Json(json!({ "stopped": true })).into_response(),
            Reply::Answered => Json(json!({ "answered": true })).into_response(),
        }
    }
}

async fn state_now(Ctx(s): Ctx<Server>) -> Response {
    ([(header::CONTENT_TYPE, "application/json")], s.state_json()).into_response()
}

/// The state at once, then on every change and at least every [`HEARTBEAT`]; ends
/// when the session does (logout, revoke).
async fn events(Ctx(s): Ctx<Server>, headers: HeaderMap) -> Response {
    let token = session_of(&headers).unwrap_or_default();
    let stream = futures_util::stream::unfold(
        (s, token, None::<String>, None::<tokio::time::Instant>),
        |(s, token, last, sent_at)| async move {
            // When the state was last built: at most one build per EVENTS_GAP.
            let mut looked: Option<tokio::time::Instant> = None;
            loop {
                if !s.shared.pairing().is_session(&token) {
                    return None;
                }
                if let Some(at) = sent_at {
                    let changed = s.shared.changed.notified();
                    // Woken by a change, or the heartbeat falls due.
                    let _ = tokio::time::timeout_at(at + HEARTBEAT, changed).await;
                    let gap = looked.unwrap_or(at) + EVENTS_GAP;
                    tokio::time::sleep_until(gap.min(at + HEARTBEAT)).await;
                }
                looked = Some(tokio::time::Instant::now());
                let json = s.state_json();
                let due = sent_at.is_none_or(|at| at.elapsed() >= HEARTBEAT);
                if due || last.as_deref() != Some(json.as_str()) {
                    let event: Result<Event, Infallible> =
                        Ok(Event::default().event("state").data(json.clone()));
                    return Some((
                        event,
                        (s, token, Some(json), Some(tokio::time::Instant::now())),
                    ));
                }
            }
        },
    );
    Sse::new(stream).into_response()
}

#[derive(Deserialize)]
struct PowerBody {
    on: bool,
}

async fn power(
    Ctx(s): Ctx<Server>,
    Path(id): Path<String>,
    body: Option<Json<PowerBody>>,
) -> Response {
    let Ok(id) = id.parse::<u8>() else {
        return error(StatusCode::NOT_FOUND, &format!("no device {id}"));
    };
    let Some(Json(body)) = body else {
        return error(
            StatusCode::BAD_REQUEST,
            "send {\"on\":true} or {\"on\":false}",
        );
    };
    s.command(Command::Power { id, on: body.on }).await
}

async fn clear(Ctx(s): Ctx<Server>, Path(id): Path<String>) -> Response {
    let Ok(id) = id.parse::<u8>() else {
        return error(StatusCode::NOT_FOUND, &format!("no device {id}"));
    };
    s.command(Command::Clear { id }).await
}

#[derive(Deserialize)]
struct MotorBody {
    direction: Option<String>,
    #[serde(default)]
    stop: bool,
}

async fn motor(
    Ctx(s): Ctx<Server>,
    Path(name): Path<String>,
    body: Option<Json<MotorBody>>,
) -> Response {
    let motor = match name.as_str() {
        "flaps" => Motor::Flaps,
        "pitch" => Motor::Trim(TrimKind::Pitch),
        "roll" => Motor::Trim(TrimKind::Roll),
        _ => return error(StatusCode::NOT_FOUND, &format!("no motor {name}")),
    };
    let Some(Json(body)) = body else {
        return error(
            StatusCode::BAD_REQUEST,
            "send {\"direction\":\"up\"} (down, left, right) or {\"stop\":true}",
        );
    };
    if body.stop {
        return s.command(Command::MotorStop).await;
    }
    let direction = match body.direction.as_deref() {
        Some("up") => Direction::Up,
        Some("down") => Direction::Down,
        Some("left") => Direction::Left,
        Some("right") => Direction::Right,
        _ => {
            return error(
                StatusCode::BAD_REQUEST,
                "direction is one of up, down, left, right",
            );
        }
    };
    s.command(Command::Motor { motor, direction }).await
}

#[derive(Deserialize)]
struct AnswerBody {
    answer: String,
}

async fn check_answer(Ctx(s): Ctx<Server>, body: Option<Json<AnswerBody>>) -> Response {
    let Some(Json(body)) = body else {
        return error(StatusCode::BAD_REQUEST, "send {\"answer\":\"go_on\"}");
    };
    s.command(Command::CheckAnswer(body.answer)).await
}

async fn logout(Ctx(s): Ctx<Server>, headers: HeaderMap) -> Response {
    if let Some(t) = session_of(&headers) {
        s.shared.pairing().end(&t);
    }
    s.shared.changed.notify_waiters();
    Json(json!({ "paired": false })).into_response()
}

//! Every route of the remote's HTTP server, in words: the guide's HTTP API page is
//! generated from this table (`cargo run -- reference`), and the test below holds it
//! to the routes [`super::server`] really serves, so the page cannot drift from them.

/// One route: its method, its path as axum writes it, what it takes and what it answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Route {
    pub method: &'static str,
    pub path: &'static str,
    /// The request's JSON body, or "" when it takes none.
    pub body: &'static str,
    pub answers: &'static str,
}

/// What every `/api/*` route but `/api/pair` answers without a paired session, and
/// what any route answers to a foreign `Origin`, before its own handler runs.
pub const GATE: &str = "Every `/api/*` route but `/api/pair` answers 401 \
    `{\"error\":\"not paired\"}` without a valid session, and 401 with the refusal's words \
    (`\"bad signature\"`, `\"replayed counter\"`, `\"stale request\"`, `\"unsigned or \
    malformed signature\"`) without a valid signature, and changes nothing. A request is signed \
    by four headers: `X-Vpx-Session`, `X-Vpx-Counter` (only grows), `X-Vpx-Time` (the laptop's \
    clock in ms, which every answer carries as `X-Vpx-Now`) and `X-Vpx-Mac`, the HMAC-SHA-256 \
    in hex of `vpx-efis/1\\n{session}\\n{counter}\\n{time}\\n{METHOD}\\n{path}\\n{body}` \
    (`src/remote/signing.rs`). A request whose \
    `Origin` header is not the page's own (`http://ADDR:PORT`) gets 403 \
    `{\"error\":\"origin\"}` before anything else; a request without `Origin` (a script) is \
    judged by its session alone. A path that is no route gets 404 \
    `{\"error\":\"no such route\"}`.";

pub const ROUTES: &[Route] = &[
    Route {
        method: "GET",
        path: "/",
        body: "",
        answers: "the phone page (compiled in); no session needed, no data in it. \
                  `#k=KEY` pairs (the fragment never reaches the laptop)",
    },
    Route {
        method: "POST",
        path: "/api/pair",
        body: "signed with the QR code's key, or with SHA-256 of `vpx-efis typed pairing\\n` \
               and the typed words (session empty, counter and time 0)",
        answers: "200 `{\"paired\":true,\"session\":\"…\",\"typed\":false,\"now_ms\":N}`; 401 `{\"error\":\"wrong code\"}`; 429 \
                  `{\"error\":\"locked\",\"retry_after_s\":N}` with `Retry-After: N`",
    },
    Route {
        method: "GET",
        path: "/api/state",
        body: "",
        answers: "the state as JSON: a value that is not live is `null`, never an old number",
    },
    Route {
        method: "GET",
        path: "/api/events",
        body: "",
        answers: "`text/event-stream`: `event: state`, `data: <state>`, at once, on a change \
                  (changes within 0.5 s go as one), and at least every second as a heartbeat",
    },
    Route {
        method: "POST",
        path: "/api/device/{id}/power",
        body: "`{\"on\":true}`",
        answers: "200 `{\"sent\":\"Nav Lt on (DEVICE_POWER sent)\"}`; 409 \
                  `{\"refused\":\"<control's words>\"}`; 404 `{\"error\":\"no device N\"}`",
    },
    Route {
        method: "POST",
        path: "/api/device/{id}/clear",
        body: "",
        answers: "as power: DEVICE_CLEAR",
    },
    Route {
        method: "POST",
        path: "/api/motor/{motor}",
        body: "`{\"direction\":\"up\"|\"down\"|\"left\"|\"right\"}` or `{\"stop\":true}`; \
               `{motor}` is `flaps`, `pitch` or `roll`",
        answers: "a direction starts or renews the run's 300 ms lease: 200 \
                  `{\"lease_ms\":300}`; 409 `{\"refused\":\"…\"}`. A stop ends the run: 200 \
                  `{\"stopped\":true}` once its stop is queued for the wire",
    },
    Route {
        method: "POST",
        path: "/api/check/answer",
        body: "`{\"answer\":\"go_on\"|\"skip\"|\"retry\"|\"lit_yes\"|\"lit_no\"}`",
        answers: "answers the installation check running on the page: 200 \
                  `{\"answered\":true}`, or 409 when that answer is not offered now",
    },
    Route {
        method: "POST",
        path: "/api/logout",
        body: "",
        answers: "ends this session",
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    /// The `(method, path)` of every `.route("PATH", METHOD(handler))` in the server's
    /// source, read as text: axum's `Router` does not list its routes.
    fn served() -> Vec<(String, String)> {
        let source = include_str!("server.rs");
        let mut found = Vec::new();
        for chunk in source.split(".route(\"").skip(1) {
            let (path, rest) = chunk
                .split_once('"')
                .expect("a route's path ends with a quote");
            let rest = rest.trim_start_matches([',', ' ', '\n']);
            // `get(h)`, `post(h)`, or `get(h).post(h2)`: every method named before `)`.
            let call = rest.split(')').next().unwrap_or("");
            let mut methods: Vec<String> = rest
                .split(')')
                .take_while(|s| !s.trim().is_empty())
                .filter_map(|s| s.trim_start_matches('.').split('(').next())
                .map(|m| m.trim().to_ascii_uppercase())
                .filter(|m| ["GET", "POST", "PUT", "DELETE", "PATCH"].contains(&m.as_str()))
                .collect();
            if methods.is_empty() {
                panic!("cannot read the method of route {path:?}: {call:?}");
            }
            methods.dedup();
            for m in methods {
                found.push((m, path.to_string()));
            }
        }
        found
    }

    #[test]
    fn the_table_lists_exactly_the_routes_the_server_serves() {
        let mut served = served();
        served.sort();
        let mut listed: Vec<(String, String)> = ROUTES
            .iter()
            .map(|r| (r.method.to_string(), r.path.to_string()))
            .collect();
        listed.sort();
        assert!(!served.is_empty());
        assert_eq!(
            listed, served,
            "remote::routes::ROUTES must list every route of remote/server.rs's router, \
             each once; then run `cargo run -- reference` to regenerate the guide's HTTP API page"
        );
    }
}

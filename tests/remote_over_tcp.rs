//! The walk-around remote where most of our users are, on Windows.
//! The page (the App, pumped here as its own loop does) against `vpx-efis sim --tcp`
//! as a second process, `--remote` on 127.0.0.1, a phone in Rust (`common::phone`,
//! signing every request as the phone's page does): paired by the QR code's key, a
//! circuit switched and seen switched in the state, a motor leased, renewed and let
//! go. No pseudo-terminal, so it runs under Wine too (`.ci/windows`), where the
//! laptop that serves the phone at the wingtip most often is a Windows one.

use std::time::{Duration, Instant};

use serde_json::{Value, json};
use vpx_efis::app::{App, AppOptions};
use vpx_efis::link::{self, PortAddr};
use vpx_efis::model::Source;

mod common;
use common::app::until;
use common::phone::{Answer, Phone};
use common::process::sim_tcp;

/// Runs `f` (the phone's HTTP calls) on a thread of its own while the page's loop
/// runs here, as it would in its own process.
fn during<T: Send + 'static>(app: &mut App, f: impl FnOnce() -> T + Send + 'static) -> T {
    let h = std::thread::spawn(f);
    let end = Instant::now() + Duration::from_secs(10);
    while !h.is_finished() {
        assert!(Instant::now() < end, "the call never ended");
        app.pump_until(Instant::now() + Duration::from_millis(2));
    }
    h.join().expect("the phone's thread")
}

fn device(st: &Value, id: u64) -> Value {
    st["devices"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["id"] == id)
        .cloned()
        .unwrap_or(Value::Null)
}

#[test]
fn a_phone_pairs_switches_a_circuit_and_runs_a_trim_against_sim_tcp() {
    let (_sim, addr) = sim_tcp("demo");
    let port: PortAddr = addr.parse().expect("tcp://HOST:PORT");
    let mut app = App::new(
        Source::Serial {
            path: port.to_string(),
        },
        link::port_connector(&port, 57_600),
        AppOptions::default(),
    );
    app.start_remote(Some("127.0.0.1:0".parse().unwrap()), Instant::now())
        .expect("the remote starts on 127.0.0.1");
    until(
        &mut app,
        "the device list",
        Duration::from_secs(15),
        |app, now| {
            let m = app.model();
            m.live_devices(now).is_some() && m.names.iter().all(Option::is_some)
        },
    );
    let url = app.remote_url().unwrap();
    assert!(
        url.starts_with("http://127.0.0.1:") && url.contains("/#k="),
        "{url}"
    );
    let phone = during(&mut app, move || Phone::scan(&url)).expect("paired by the key");
    assert_eq!(app.view().remote.as_ref().unwrap().paired, 1);

    // Nav Lt (4) is on by its switch in `demo`; the phone turns GPS 1 (9) off and on.
    let p = phone.clone();
    let st = during(&mut app, move || p.get("/api/state")).body;
    assert_eq!(device(&st, 9)["name"], "GPS 1", "{st}");
    let before = device(&st, 9)["state"].clone();
    let want = if before == "ON" { "OFF" } else { "ON" };
    let p = phone.clone();
    let on = want == "ON";
    let a: Answer = during(&mut app, move || {
        p.post("/api/device/9/power", Some(json!({ "on": on })))
    });
    assert_eq!(a.status, 200, "{a:?}");
    let end = Instant::now() + Duration::from_secs(4);
    loop {
        app.pump_until(Instant::now() + Duration::from_millis(100));
        let p = phone.clone();
        let st = during(&mut app, move || p.get("/api/state")).body;
        if device(&st, 9)["state"] == want {
            break;
        }
        assert!(Instant::now() < end, "GPS 1 never showed {want}: {st}");
    }

    // The pitch trim held for 600 ms (a renewal every 100 ms), then let go.
    let p = phone.clone();
    let renewals = during(&mut app, move || {
        let t0 = Instant::now();
        let mut statuses = Vec::new();
        while t0.elapsed() < Duration::from_millis(600) {
            statuses.push(
                p.post("/api/motor/pitch", Some(json!({"direction": "up"})))
                    .status,
            );
            std::thread::sleep(Duration::from_millis(100));
        }
        statuses
    });
    assert!(renewals.iter().all(|s| *s == 200), "{renewals:?}");
    assert!(app.motor_run().is_some(), "the lease runs the trim");
    let p = phone.clone();
    let a = during(&mut app, move || {
        p.post("/api/motor/pitch", Some(json!({"stop": true})))
    });
    assert_eq!((a.status, a.body), (200, json!({"stopped": true})));
    app.pump_until(Instant::now() + Duration::from_millis(100));
    assert!(app.motor_run().is_none(), "let go, the trim stopped");
    common::events::assert_a_line_starts(&app.model(), "remote: pitch trim up running");
    common::events::assert_a_line_starts(&app.model(), "remote: pitch trim up stopped");
}

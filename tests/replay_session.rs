//! Record a session of the real page against the virtual VP-X, replay it, and the page
//! draws the same frames at the same instants; a capture cut at any byte replays up to
//! the cut and says so; a corrupt one is refused in words.

use std::time::{Duration, Instant};

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;

use vpx_efis::app::{self, App, AppOptions, Capture, Recorder};
use vpx_efis::model::Source;
use vpx_efis::protocol::message::{Payload, SystemStatus};
use vpx_efis::ui::{self, state::ViewState};

mod common;
use common::process;
use common::screen::text;

#[test]
fn a_recorded_session_replays_to_the_same_frames_at_the_same_instants() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("session.vpxcap");
    let (source, connector, sim) = app::builtin_sim("short-circuit").unwrap();
    let mut live = App::recording(
        source,
        connector,
        AppOptions::default(),
        Recorder::create(&path).unwrap(),
    );
    let end = Instant::now() + Duration::from_secs(3);
    let start = loop {
        if let Some(s) = live.recording_started() {
            break s;
        }
        assert!(Instant::now() < end, "the page never connected");
        live.pump_until(Instant::now() + Duration::from_millis(10));
    };
    // Before the strobe shorts (3 s), as it shorts, and after; odd offsets so the
    // instants fall anywhere in the broadcast cycle.
    let replay_source = Source::Replay {
        file: "session.vpxcap".into(),
    };
    let mut frames: Vec<(Duration, Buffer)> = Vec::new();
    for ms in [730u64, 1910, 3370, 4120] {
        live.pump_until(start + Duration::from_millis(ms));
        // Copy the model under its lock with `now` read there, so nothing the link
        // stamps later is in the copy. A frame the link thread stamped before `now`
        // but had not yet applied (it stamps before it takes the lock) would be
        // missing from the copy while the replay has it: on a loaded machine that
        // happens, so such a copy is taken again a moment later.
        let newest = |m: &vpx_efis::model::Model, now: Instant| {
            m.traffic
                .entries()
                .filter(|e| e.at <= now)
                .map(|e| e.seq)
                .max()
        };
        let (mut model, now) = loop {
            let (copy, now) = {
                let m = live.model();
                (m.clone(), Instant::now())
            };
            live.pump_until(Instant::now() + Duration::from_millis(30));
            if newest(&live.model(), now) == newest(&copy, now) {
                break (copy, now);
            }
        };
        // The frame of the same data, as a replay labels it: the source label and the
        // port name in the event log are the only things that say where bytes came from.
        model.source = replay_source.clone();
        for e in model.events.iter_mut() {
            e.text = e
                .text
                .replace("built-in virtual VP-X", "replay of session.vpxcap");
        }
        let mut view = ViewState::default();
        view.selected = ui::ordered_circuits(&model, &view, now)
            .first()
            .map(|c| c.id);
        // As `ui::draw` draws it: rendered, then painted in the view's palette.
        let mut buf = common::screen::rendered(&model, &view, now, 120, 40);
        view.theme.palette.paint(&mut buf);
        frames.push((now - start, buf));
    }
    live.shutdown();
    sim.stop();

    let cap = Capture::load(&path).unwrap();
    assert_eq!(cap.problem, None);
    let mut replay = App::replay(cap, AppOptions::default(), 1.0, true);
    let mut differing = Vec::new();
    for (at, want) in &frames {
        let now = replay.replay_seek(*at).unwrap();
        let mut term = Terminal::new(TestBackend::new(120, 40)).unwrap();
        replay.draw(&mut term, now).unwrap();
        let got = term.backend().buffer().clone();
        if &got != want {
            differing.push(format!(
                "at {at:?}\n--- live\n{}--- replay\n{}",
                text(want),
                text(&got)
            ));
        }
    }
    assert!(differing.is_empty(), "{}", differing.join("\n"));
    // The fault is in the last frames, so they were not all the same picture.
    assert!(text(&frames[3].1).contains("SHORT_CIRCUIT"));
    assert!(!text(&frames[0].1).contains("SHORT_CIRCUIT"));
}

fn shipped() -> Vec<u8> {
    std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/captures/normal.vpxcap"
    ))
    .unwrap()
}

#[test]
fn a_capture_cut_at_any_byte_loads_up_to_the_cut_and_says_so() {
    let data = shipped();
    let full = Capture::from_bytes("normal.vpxcap", &data).unwrap();
    let mut cuts_with_problem = 0;
    for cut in 0..data.len() {
        let c = Capture::from_bytes("cut.vpxcap", &data[..cut])
            .unwrap_or_else(|e| panic!("cut at {cut}: {e}"));
        assert!(c.records.len() <= full.records.len());
        assert_eq!(
            c.records[..],
            full.records[..c.records.len()],
            "cut at {cut}"
        );
        if let Some(p) = &c.problem {
            assert!(p.contains("cut short at byte"), "{p}");
            cuts_with_problem += 1;
        }
    }
    // Every cut but those on a record boundary (and the header's end) is reported.
    assert!(cuts_with_problem > data.len() * 9 / 10);
}

#[test]
fn a_cut_capture_replays_up_to_the_cut_with_its_message_on_screen() {
    let data = shipped();
    let full = Capture::from_bytes("normal.vpxcap", &data).unwrap();
    for cut in [16 + 5, data.len() / 3, data.len() / 2 + 7, data.len() - 1] {
        let c = Capture::from_bytes("cut.vpxcap", &data[..cut]).unwrap();
        let problem = c.problem.clone().expect("a cut mid-record");
        let received: usize = c
            .records
            .iter()
            .filter(|r| r.dir == vpx_efis::link::Crossing::Rx)
            .map(|r| r.bytes.len())
            .sum();
        let mut app = App::replay(c, AppOptions::default(), 1.0, true);
        let now = app.replay_seek(full.length()).unwrap();
        assert_eq!(
            app.model().link.decoder.bytes_in as usize,
            received,
            "cut at {cut}: every byte before the cut, none after"
        );
        app.handle_term_event(
            crossterm::event::Event::Key(crossterm::event::KeyEvent::new(
                crossterm::event::KeyCode::Char('t'),
                crossterm::event::KeyModifiers::NONE,
            )),
            now,
        );
        let mut term = Terminal::new(TestBackend::new(160, 40)).unwrap();
        app.draw(&mut term, now).unwrap();
        let screen = text(term.backend().buffer());
        assert!(screen.contains(&problem[..40]), "{screen}");
    }
}

#[test]
fn a_corrupt_capture_is_refused_in_words_never_a_panic() {
    let data = shipped();
    let bad_dir = {
        let mut d = shipped();
        d[16] = b'Q';
        d
    };
    let e = Capture::from_bytes("bad.vpxcap", &bad_dir)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("corrupt at byte 16") && e.contains("unknown direction"),
        "{e}"
    );
    let e = Capture::from_bytes("raw.bin", b"\xE7\x7E\x10 not a capture at all")
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a vpx-efis capture"), "{e}");
    // Every single-byte corruption of the record headers: an error or a clean load,
    // never a panic.
    for i in 16..data.len().min(400) {
        for b in [0x00, 0xFF, b'R', b'T'] {
            let mut d = shipped();
            d[i] = b;
            let _ = Capture::from_bytes("x", &d);
        }
    }
    // The binary says so before touching the terminal, and fails.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.vpxcap");
    std::fs::write(&path, &bad_dir).unwrap();
    let out = process::vpx(&["--replay"], process::NO_CONFIG)
        .arg(&path)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("corrupt at byte 16"), "{err}");
}

#[test]
fn decode_reads_a_capture_with_times_and_directions() {
    let out = process::vpx(&["decode"], process::NO_CONFIG)
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/captures/normal.vpxcap"
        ))
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let sys = text
        .lines()
        .find(|l| l.contains(SystemStatus::NAME))
        .expect("a SYSTEM_STATUS line");
    assert!(sys.trim_start().split(' ').nth(1) == Some("rx"), "{sys}");
    assert!(text.lines().any(|l| l.contains(" tx VERSION")), "{text}");
    assert!(text.contains("0 bad checksum"), "{text}");
}

#[test]
fn at_the_end_of_a_replay_the_bytes_held_back_are_scanned_again() {
    use vpx_efis::link::{Crossing, Record};
    // PING response, cnt 1, ack 1 (E7^7E^10^00^01^00^01^01^01 = 0x89, inverted 0x76).
    let ping_ack = vec![0xE7, 0x7E, 0x10, 0x00, 0x01, 0x00, 0x01, 0x01, 0x01, 0x76];
    // The capture ends on a DEVICE_STATUS header claiming its own 66 bytes, inside
    // which are an intact message of an id the ICD does not define (0x16/0x00, no
    // payload: E7^7E^16^00^01^00^01^00 = 0x8F, inverted 0x70) and the first 4 bytes of
    // a PING. Live, the header would still be waiting for its 75 bytes; the capture is
    // over, so the link scans them again.
    let tail = vec![
        0xE7, 0x7E, 0x12, 0x01, 0x00, 0x00, 0x00, 0x42, // the false header
        0xE7, 0x7E, 0x16, 0x00, 0x01, 0x00, 0x01, 0x00, 0x70, // unknown, intact
        0xE7, 0x7E, 0x10, 0x00, // cut off
    ];
    let cap = Capture {
        name: "tail.vpxcap".into(),
        records: vec![
            Record {
                dir: Crossing::Rx,
                offset: Duration::ZERO,
                bytes: ping_ack,
            },
            Record {
                dir: Crossing::Rx,
                offset: Duration::from_millis(100),
                bytes: tail,
            },
        ],
        problem: None,
    };
    let mut app = App::replay(cap, AppOptions::default(), 1.0, true);
    app.replay_seek(Duration::from_millis(100)).unwrap();
    let end = Instant::now() + Duration::from_secs(5);
    while app.model().link.decoder.unknown_message == 0 && Instant::now() < end {
        std::thread::sleep(Duration::from_millis(10));
    }
    let d = app.model().link.decoder;
    assert_eq!(
        (d.bytes_in, d.frames, d.unknown_message),
        (31, 1, 1),
        "{d:?}"
    );
    // The false header is skipped, the cut-off PING reported as such: every byte.
    assert_eq!((d.skipped_bytes, d.truncated_bytes), (8, 4), "{d:?}");
}

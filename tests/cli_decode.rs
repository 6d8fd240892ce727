//! `vpx-efis decode` run as a program on a hand-written raw capture: good frames of
//! several kinds, garbage, a corrupted frame, an unknown message, a frame whose field is
//! out of range, an impossible length, and a frame cut off at the end.
//!
//! The frames are the hand-worked vectors of `protocol_vectors.rs` (checksum working
//! there); the expected lines and counts below are worked out by hand from the bytes.

use std::io::Write;
use std::process::Stdio;

use serde_json::Value;

#[path = "common/process.rs"]
#[allow(dead_code)]
mod process;

/// 00 55 AA: noise before anything (3 bytes).
const NOISE: &[u8] = &[0x00, 0x55, 0xAA];
/// PING request, cnt 0x21, EFIS → VP-X (10 bytes).
const PING: &[u8] = &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x01, 0x00, 0x01, 0x00, 0x57];
/// SYSTEM_STATUS, cnt 0x42 (21 bytes; its checksum is 0xE7).
const SYSTEM_STATUS: &[u8] = &[
    0xE7, 0x7E, 0x12, 0x00, 0x42, 0x00, 0x01, 0x0C, 0x00, 0x7B, 0xFF, 0xF1, 0x00, 0x7D, 0x1F, 0x80,
    0x01, 0x40, 0x09, 0x03, 0xE7,
];
/// The PING above with checksum 0x58 instead of 0x57 (10 bytes).
const PING_CORRUPT: &[u8] = &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x01, 0x00, 0x01, 0x00, 0x58];
/// FAULT_STATUS, cnt 0x45: device 9 SHORT_CIRCUIT, device 29 TRIM_RUNAWAY, system
/// fault (44 bytes).
const FAULT_STATUS: &[u8] = &[
    0xE7, 0x7E, 0x12, 0x03, 0x45, 0x00, 0x01, 0x23, 0x00, 0x02, 0x00, 0xA0, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0E, 0x00, 0xBB,
];
/// 0x16/0x00, defined nowhere, checksum good (9 bytes).
const UNKNOWN: &[u8] = &[0xE7, 0x7E, 0x16, 0x00, 0x01, 0x00, 0x01, 0x00, 0x70];
/// PING response with ack 2, outside Table 10's 0–1, checksum good (10 bytes).
const PING_ACK_2: &[u8] = &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x00, 0x01, 0x01, 0x02, 0x55];
/// DEVICE_STATUS header claiming 2 payload bytes, checksum good (11 bytes).
const DEVICE_STATUS_LEN_2: &[u8] = &[
    0xE7, 0x7E, 0x12, 0x01, 0x43, 0x00, 0x01, 0x02, 0x06, 0x02, 0x31,
];
/// FLAP_TRIM_STATUS, cnt 0x44, broadcast to 0xFF (27 bytes).
const FLAP_TRIM_STATUS: &[u8] = &[
    0xE7, 0x7E, 0x12, 0x02, 0x44, 0x00, 0xFF, 0x12, 0x90, 0xD4, 0x64, 0x80, 0x7F, 0x00, 0x00, 0x0E,
    0x14, 0xDC, 0x50, 0xA0, 0xF0, 0x0A, 0x80, 0xE6, 0x19, 0x7F, 0xCC,
];
/// The start of a frame the capture stopped in (3 bytes).
const CUT_OFF: &[u8] = &[0xE7, 0x7E, 0x12];

/// DEVICE_STATUS, cnt 0x43: devices 1, 2, 9, 30 on at 0.5, 2.3, 25.8, 1.7 A (75 bytes).
fn device_status() -> Vec<u8> {
    let mut b = vec![
        0xE7, 0x7E, 0x12, 0x01, 0x43, 0x00, 0x01, 0x42, 0x06, 0x02, 0x00, 0x40,
    ];
    let mut currents = [0u8; 62];
    for (id, hi, lo) in [
        (1, 0x00, 0x05),
        (2, 0x00, 0x17),
        (9, 0x01, 0x02),
        (30, 0x00, 0x11),
    ] {
        currents[2 * id] = hi;
        currents[2 * id + 1] = lo;
    }
    b.extend_from_slice(&currents);
    b.push(0x31);
    b
}

fn capture() -> Vec<u8> {
    let mut c = Vec::new();
    for part in [NOISE, PING, SYSTEM_STATUS, PING_CORRUPT] {
        c.extend_from_slice(part);
    }
    c.extend_from_slice(&device_status());
    for part in [
        FAULT_STATUS,
        UNKNOWN,
        PING_ACK_2,
        DEVICE_STATUS_LEN_2,
        FLAP_TRIM_STATUS,
        CUT_OFF,
    ] {
        c.extend_from_slice(part);
    }
    // 3 + 10 + 21 + 10 + 75 + 44 + 9 + 10 + 11 + 27 + 3
    assert_eq!(c.len(), 223);
    c
}

fn run(args: &[&str], stdin: &[u8]) -> (bool, String, String) {
    let mut child = process::vpx(&[&["decode"], args].concat(), process::NO_CONFIG)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start vpx-efis");
    child.stdin.take().unwrap().write_all(stdin).unwrap();
    let out = child.wait_with_output().unwrap();
    (
        out.status.success(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn capture_file() -> tempfile::NamedTempFile {
    let mut f = tempfile::NamedTempFile::new().unwrap();
    f.write_all(&capture()).unwrap();
    f
}

#[test]
fn text_output_has_one_line_per_frame_and_per_dropped_thing() {
    let f = capture_file();
    let (ok, out, err) = run(&[f.path().to_str().unwrap()], b"");
    assert!(ok, "{err}");
    let expected = [
        "skipped 3 bytes: 00 55 AA",
        "PING cnt 33 EFIS→VP-X: ack flag 0 (request)",
        "SYSTEM_STATUS cnt 66 VP-X→EFIS: system current 12.3 A, main bus -1.5 V, \
         aux battery 12.5 V, internal temp 31 °C, switches on: switch 1, roll trim down; \
         misc: starter annunciator no, wig-wag mode steady, software update no, \
         wig-wag active no; system faults: data integrity failure, external data missing; \
         data integrity code 0x03 (Device configuration error)",
        "bad checksum (computed 0x57, frame carries 0x58), resyncing one byte on: \
         E7 7E 10 00 21 01 00 01 00 58",
        // Only the corrupt candidate's first byte went with it; the rest is plain noise.
        "skipped 9 bytes: 7E 10 00 21 01 00 01 00 58",
        "DEVICE_STATUS cnt 67 VP-X→EFIS: on: 1 Starter 0.5 A, 2 EFIS 2.3 A, 9 5A-6 25.8 A, \
         30 Trim_P 1.7 A",
        "FAULT_STATUS cnt 69 VP-X→EFIS: faulted: 9 5A-6 0x07 SHORT_CIRCUIT, \
         29 Trim_R 0x0e TRIM_RUNAWAY; system fault yes; 31 codes carried",
        "unknown message 0x16/0x00: E7 7E 16 00 01 00 01 00 70",
        "undecodable PING cnt 33 VP-X→EFIS: PING: field ACK flag is 2, outside its range: \
         E7 7E 10 00 21 00 01 01 02 55",
        "bad length: DEVICE_STATUS header claims 2 bytes, the ICD gives 66: \
         E7 7E 12 01 43 00 01 02",
        "skipped 10 bytes: 7E 12 01 43 00 01 02 06 02 31",
        "FLAP_TRIM_STATUS cnt 68 VP-X→broadcast: flap: position 100 [enabled, overspeed alarm], \
         fault code 0x00 NO FAULT, up 20, down 220, midpoint 1 80, midpoint 2 160; \
         pitch trim: position 128 [enabled, motor running], fault code 0x00 NO FAULT, \
         up 240, down 10, neutral 128; roll trim: position 127 [enabled, fault], \
         fault code 0x0e TRIM_RUNAWAY, up 230, down 25, neutral 127",
        "incomplete frame at end: 3 bytes: E7 7E 12",
        // Frames: PING, SYSTEM_STATUS, DEVICE_STATUS, FAULT_STATUS, PING ack 2,
        // FLAP_TRIM_STATUS = 6 (187 bytes). Skipped: 3 + (1 + 9) + (1 + 10) = 24.
        // 187 + 24 + 9 unknown + 3 incomplete = 223.
        "summary: 223 bytes in, 6 frames (1 undecodable), 24 bytes skipped, 1 bad checksum, \
         1 bad length, 1 unknown message, 3 bytes incomplete at end",
    ];
    let got: Vec<&str> = out.lines().collect();
    assert_eq!(got, expected);
}

#[test]
fn json_output_is_one_object_per_line_with_a_summary() {
    let f = capture_file();
    let (ok, out, err) = run(&["--json", f.path().to_str().unwrap()], b"");
    assert!(ok, "{err}");
    let lines: Vec<Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect();
    let names: Vec<&str> = lines.iter().map(|v| v["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "SKIPPED",
            "PING",
            "SYSTEM_STATUS",
            "BAD_CHECKSUM",
            "SKIPPED",
            "DEVICE_STATUS",
            "FAULT_STATUS",
            "UNKNOWN_MESSAGE",
            "UNDECODABLE",
            "BAD_LENGTH",
            "SKIPPED",
            "FLAP_TRIM_STATUS",
            "INCOMPLETE",
            "SUMMARY",
        ]
    );
    // A raw capture has no times or directions, so there are no such keys.
    assert!(
        lines
            .iter()
            .all(|v| v.get("time").is_none() && v.get("dir").is_none())
    );

    assert_eq!(lines[0]["bytes"], 3);
    assert_eq!(lines[0]["hex"], "00 55 AA");

    let ping = &lines[1];
    assert_eq!(
        (&ping["cnt"], &ping["src"], &ping["dst"]),
        (&33.into(), &1.into(), &0.into())
    );
    assert_eq!(ping["ack"], false);

    let sys = &lines[2];
    assert_eq!(sys["main_bus_v"], -1.5);
    assert_eq!(sys["system_current_a"], 12.3);
    assert_eq!(sys["switches_on"], serde_json::json!([1]));
    assert_eq!(sys["roll_trim_down"], true);
    assert_eq!(sys["data_integrity_code"], 3);

    assert_eq!(lines[3]["computed"], 0x57);
    assert_eq!(lines[3]["found"], 0x58);

    let ds = &lines[5];
    assert_eq!(
        (&ds["cnt"], &ds["src"], &ds["dst"]),
        (&67.into(), &0.into(), &1.into())
    );
    let devices = ds["devices"].as_array().unwrap();
    assert_eq!(devices.len(), 31);
    let on: Vec<(u64, f64)> = devices
        .iter()
        .filter(|d| d["on"] == true)
        .map(|d| (d["id"].as_u64().unwrap(), d["current_a"].as_f64().unwrap()))
        .collect();
    assert_eq!(on, [(1, 0.5), (2, 2.3), (9, 25.8), (30, 1.7)]);
    assert_eq!(devices[9]["name"], "5A-6");

    let fs = &lines[6];
    assert_eq!(fs["system_fault"], true);
    let faulted: Vec<(u64, u64)> = fs["faulted"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["id"].as_u64().unwrap(),
                d["fault_code"]["code"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(faulted, [(9, 0x07), (29, 0x0E)]);

    assert_eq!(
        (&lines[7]["major"], &lines[7]["minor"]),
        (&0x16.into(), &0.into())
    );
    assert_eq!(lines[8]["message"], "PING");
    assert_eq!(
        (&lines[9]["message"], &lines[9]["len"]),
        (&"DEVICE_STATUS".into(), &2.into())
    );
    assert_eq!(lines[11]["dst"], 0xFF);
    assert_eq!(lines[11]["roll_trim"]["fault_code"]["name"], "TRIM_RUNAWAY");
    assert_eq!(lines[12]["bytes"], 3);
    assert_eq!(lines[12]["hex"], "E7 7E 12");

    let s = &lines[13];
    for (k, v) in [
        ("bytes_in", 223),
        ("frames", 6),
        ("undecodable", 1),
        ("skipped_bytes", 24),
        ("bad_checksum", 1),
        ("bad_length", 1),
        ("unknown_message", 1),
        ("incomplete_bytes", 3),
    ] {
        assert_eq!(s[k], v, "{k}");
    }
}

#[test]
fn reads_standard_input_by_default() {
    let (ok, out, err) = run(&[], PING);
    assert!(ok, "{err}");
    assert_eq!(
        out,
        "PING cnt 33 EFIS→VP-X: ack flag 0 (request)\n\
         summary: 10 bytes in, 1 frames (0 undecodable), 0 bytes skipped, 0 bad checksum, \
         0 bad length, 0 unknown message, 0 bytes incomplete at end\n"
    );
    let (ok, out, _) = run(&["-", "--json"], PING);
    assert!(ok);
    assert_eq!(out.lines().count(), 2);
}

#[test]
fn a_missing_file_is_an_error_that_names_it() {
    let (ok, out, err) = run(&["/nonexistent/capture.bin"], b"");
    assert!(!ok);
    assert!(out.is_empty());
    assert!(err.contains("/nonexistent/capture.bin"), "{err}");
}

/// DEVICE_POWER device 5 on, cnt 2, EFIS → VP-X (ICD Table 31):
/// E7^7E^13^00^02^01^00^02^05^01 = 0x8F, inverted 0x70 (11 bytes).
const DEVICE_POWER: &[u8] = &[
    0xE7, 0x7E, 0x13, 0x00, 0x02, 0x01, 0x00, 0x02, 0x05, 0x01, 0x70,
];
/// SPEC_ACK device 5 no error, cnt 3, VP-X → EFIS: E7^7E^11^06^03^00^01^02^05^00 =
/// 0x8B, inverted 0x74 (11 bytes).
const SPEC_ACK: &[u8] = &[
    0xE7, 0x7E, 0x11, 0x06, 0x03, 0x00, 0x01, 0x02, 0x05, 0x00, 0x74,
];
/// DEVICE_SPEC, cnt 1, VP-X → EFIS: device 4, 5 A, switch 255, current fault off:
/// E7^7E^11^00^01^00^01^04^04^05^FF^00 = 0x72, inverted 0x8D (13 bytes).
const DEVICE_SPEC_255: &[u8] = &[
    0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0xFF, 0x00, 0x8D,
];

/// The same with switch 11: ...^0B = 0x86, inverted 0x79.
const DEVICE_SPEC_11: &[u8] = &[
    0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0x0B, 0x00, 0x79,
];
/// With switch 3: ...^03 = 0x8E, inverted 0x71.
const DEVICE_SPEC_3: &[u8] = &[
    0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0x03, 0x00, 0x71,
];
/// With switch 0: ...^00 = 0x8D, inverted 0x72.
const DEVICE_SPEC_0: &[u8] = &[
    0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0x00, 0x00, 0x72,
];
/// With switch 12, no switch id (ICD Table 13: 0–11): ...^0C = 0x81, inverted 0x7E.
const DEVICE_SPEC_12: &[u8] = &[
    0xE7, 0x7E, 0x11, 0x00, 0x01, 0x00, 0x01, 0x04, 0x04, 0x05, 0x0C, 0x00, 0x7E,
];

#[test]
fn a_false_header_hides_no_frame_in_a_capture() {
    // A capture with a false header: a PING, an unknown id claiming 250 bytes, then three
    // intact frames and the end. Then the same with a DEVICE_STATUS header claiming
    // its own 66 bytes (possible, so held), and with one at the very end.
    let false_250: &[u8] = &[0xE7, 0x7E, 0x20, 0x00, 0x00, 0x00, 0x00, 0xFA];
    let status_66: &[u8] = &[0xE7, 0x7E, 0x12, 0x01, 0x00, 0x00, 0x00, 0x42];
    let (ok, out, err) = run(
        &[],
        &[PING, false_250, DEVICE_POWER, PING, SPEC_ACK].concat(),
    );
    assert!(ok, "{err}");
    let ping = "PING cnt 33 EFIS→VP-X: ack flag 0 (request)";
    let power = "DEVICE_POWER cnt 2 EFIS→VP-X: device 5 5A-2, power state on";
    let ack = "SPEC_ACK cnt 3 VP-X→EFIS: device 5 5A-2, error code 0 (none)";
    assert_eq!(
        out.lines().collect::<Vec<_>>(),
        [
            ping,
            "bad length: 0x20/0x00 header claims 250 bytes, no message of the ICD is longer \
             than 66: E7 7E 20 00 00 00 00 FA",
            "skipped 7 bytes: 7E 20 00 00 00 00 FA",
            power,
            ping,
            ack,
            "summary: 50 bytes in, 4 frames (0 undecodable), 8 bytes skipped, 0 bad checksum, \
             1 bad length, 0 unknown message, 0 bytes incomplete at end",
        ]
    );
    let (ok, out, _) = run(
        &[],
        &[PING, status_66, DEVICE_POWER, PING, SPEC_ACK, status_66].concat(),
    );
    assert!(ok);
    assert_eq!(
        out.lines().collect::<Vec<_>>(),
        [
            ping,
            "skipped 8 bytes: E7 7E 12 01 00 00 00 42",
            power,
            ping,
            ack,
            "incomplete frame at end: 8 bytes: E7 7E 12 01 00 00 00 42",
            "summary: 58 bytes in, 4 frames (0 undecodable), 8 bytes skipped, 0 bad checksum, \
             0 bad length, 0 unknown message, 8 bytes incomplete at end",
        ]
    );
}

/// The switch said once, plainly, by the byte that was sent, and
/// what the page reads it as only where that differs (icd-reading R10).
#[test]
fn a_switch_read_as_always_on_shows_the_byte_that_was_sent() {
    for (frame, switch) in [
        (DEVICE_SPEC_255, "switch 255 (always on; read as 11)"),
        (DEVICE_SPEC_11, "switch 11 (always on)"),
        (DEVICE_SPEC_3, "switch 3 (input 3)"),
        (DEVICE_SPEC_0, "switch 0 (always off)"),
        (DEVICE_SPEC_12, "switch 12 (not a switch id: 0-11)"),
    ] {
        let (ok, out, err) = run(&[], frame);
        assert!(ok, "{err}");
        assert_eq!(
            out.lines().next().unwrap(),
            format!(
                "DEVICE_SPEC cnt 1 VP-X→EFIS: device 4 5A-1, circuit breaker 5 A, \
                 {switch}, current fault disabled"
            )
        );
    }
    let (ok, out, _) = run(&["--json"], DEVICE_SPEC_255);
    assert!(ok);
    let spec: Value = serde_json::from_str(out.lines().next().unwrap()).unwrap();
    assert_eq!(
        (&spec["switch_id"], &spec["switch_raw"], &spec["switch"]),
        (&11.into(), &255.into(), &"always on (255)".into())
    );
}

//! `vpx-efis sim` paces its line at the real 57600 8N1 rate (5760 bytes a second) by
//! default, and `--no-pace` turns that off. Judged with lower bounds only (a loaded
//! machine can make a line slower, never faster), except that unpaced the same
//! replies must come faster than a real line could carry them.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

mod common;
mod sim_common;

use vpx_efis::protocol::message::*;
use vpx_efis::sim::line_rate::BYTES_PER_SECOND;

/// Names asked for in one burst: 93 DEVICE_NAME replies of 26 bytes (8 + 17 + 1) are
/// 2418 bytes, 420 ms on a real line.
const ASKS: usize = 93;
const REPLY_BYTES: usize = 8 + 17 + 1;

/// Starts `vpx-efis sim --pty` with `extra` arguments, asks for [`ASKS`] names at
/// once and returns how long the last reply took to arrive after the burst was sent.
fn burst_of_names(extra: &[&str]) -> Duration {
    let sim = common::process::sim(&[&["--pty", "--scenario", "install"], extra].concat());
    let mut c = sim_common::Client::open(&sim.line, Duration::from_millis(20));
    // Past the first broadcasts, so the line is quiet but for the 1 Hz and 10 Hz ones.
    assert_eq!(
        c.request(Ping { ack: false }),
        Message::Ping(Ping { ack: true })
    );
    let mut burst = Vec::new();
    let mut cnts = Vec::new();
    for i in 0..ASKS {
        let cnt = (i % 250) as u8 + 1;
        cnts.push(cnt);
        burst.extend(
            Packet::request(
                cnt,
                DeviceNameQuery {
                    device_id: (i % 31) as u8,
                },
            )
            .to_bytes(),
        );
    }
    let from = c.log.len();
    let sent = Instant::now();
    c.send_raw(&burst);
    let end = sent + Duration::from_secs(10);
    loop {
        let replies: Vec<Instant> = c.log[from..]
            .iter()
            .filter(|(_, p)| matches!(p.message, Message::DeviceName(_)))
            .map(|(at, _)| *at)
            .collect();
        if replies.len() == ASKS {
            return *replies.last().unwrap() - sent;
        }
        assert!(
            Instant::now() < end,
            "only {} of {ASKS} names",
            replies.len()
        );
        c.poll();
    }
}

fn line_time(bytes: usize) -> Duration {
    Duration::from_secs_f64(bytes as f64 / BYTES_PER_SECOND as f64)
}

#[test]
fn sim_is_paced_at_5760_bytes_a_second_by_default_and_not_with_no_pace() {
    let replies = line_time(ASKS * REPLY_BYTES);
    let paced = burst_of_names(&[]);
    let unpaced = burst_of_names(&["--no-pace"]);
    eprintln!(
        "{ASKS} names ({} bytes, {replies:?} on a real line): paced {paced:?}, --no-pace {unpaced:?}",
        ASKS * REPLY_BYTES
    );
    assert!(
        paced >= replies,
        "paced: the replies alone need {replies:?} on the line, came in {paced:?}"
    );
    assert!(
        unpaced < replies,
        "--no-pace: {unpaced:?}, no faster than a real line ({replies:?})"
    );
}

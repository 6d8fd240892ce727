//! Arbitrary bytes, cut into arbitrary reads, through the streaming decoder; every frame
//! it passes on goes through the typed parser and the describer.
//!
//! Beyond "never panics" it checks what the rest of the program relies on: the decoder
//! holds at most one candidate (never more than the longest message), every input byte
//! is accounted for, a frame that parses re-emits to bytes that parse to the same
//! packet, and nothing pending can hide a complete frame: after every read the held
//! bytes hold no intact known frame, and at the end of the input `finish` leaves
//! nothing held, with every byte reported.

#![no_main]

use std::cell::Cell;

use libfuzzer_sys::fuzz_target;
use vpx_protocol::describe::{describe, to_json};
use vpx_protocol::message::MAX_MESSAGE_LEN;
use vpx_protocol::{Decoder, Event, Packet};

/// Bytes an event accounts for: only the first byte of a rejected candidate is consumed.
fn accounted(e: &Event<'_>) -> u64 {
    match e {
        Event::Frame(f) => f.as_bytes().len() as u64,
        Event::Skipped(b) | Event::UnknownMessage(b) | Event::Truncated(b) => b.len() as u64,
        Event::BadChecksum(_) | Event::BadLength(_) => 1,
    }
}

fn check_frame(e: &Event<'_>) {
    if let Event::Frame(f) = e
        && let Ok(p) = Packet::parse(f)
    {
        let _ = describe(&p.message);
        let _ = to_json(&p.message);
        assert_eq!(Packet::parse_bytes(&p.to_bytes()), Ok(p));
    }
}

/// Whether a fresh decoder finds a known frame in `held` minus its first byte (the
/// held candidate itself), reading it to its end.
fn hides_a_frame(held: &[u8]) -> bool {
    let mut probe = Decoder::new();
    let mut found = false;
    let mut on = |e: Event<'_>| found |= matches!(e, Event::Frame(_));
    if held.len() > 1 {
        probe.push(&held[1..], &mut on);
    }
    probe.finish(&mut on);
    found
}

fuzz_target!(|input: (Vec<u8>, Vec<u8>)| {
    let (cuts, stream) = input;
    let mut dec = Decoder::new();
    let accounted_bytes = Cell::new(0u64);
    let truncated = Cell::new(0u32);
    let mut on_event = |e: Event<'_>| {
        check_frame(&e);
        accounted_bytes.set(accounted_bytes.get() + accounted(&e));
        truncated.set(truncated.get() + matches!(e, Event::Truncated(_)) as u32);
    };
    let mut rest = &stream[..];
    let mut fed = 0;
    let mut i = 0;
    while !rest.is_empty() {
        let cut = if cuts.is_empty() {
            rest.len()
        } else {
            cuts[i % cuts.len()] as usize
        };
        i += 1;
        if cut == 0 {
            // A read that timed out with nothing: must change nothing.
            dec.push(&[], &mut on_event);
        }
        let (chunk, tail) = rest.split_at(cut.clamp(1, rest.len()));
        rest = tail;
        dec.push(chunk, &mut on_event);
        fed += chunk.len();
        assert!(dec.pending() <= 8 + MAX_MESSAGE_LEN + 1);
        // Nothing pending hides a complete frame, at any read and so at the last.
        let held = &stream[fed - dec.pending()..fed];
        assert!(!hides_a_frame(held), "held {held:02X?}");
    }
    assert_eq!(truncated.get(), 0, "only finish reports a truncated frame");
    let s = dec.stats();
    assert_eq!(s.bytes_in, stream.len() as u64);
    assert_eq!(accounted_bytes.get() + dec.pending() as u64, s.bytes_in);
    // The end of the input: the held bytes are rescanned and all reported.
    dec.finish(&mut on_event);
    assert_eq!(dec.pending(), 0);
    assert_eq!(accounted_bytes.get(), stream.len() as u64);
    assert!(truncated.get() <= 1);
});

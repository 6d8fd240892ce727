//! Arbitrary bytes, cut into arbitrary reads, through the streaming decoder; every frame
//! it passes on goes through the typed parser and the describer.
//!
//! Beyond "never panics" it checks what the rest of the program relies on: the decoder
//! holds at most one frame, every input byte is accounted for, and a frame that parses
//! re-emits to bytes that parse to the same packet.

#![no_main]

use libfuzzer_sys::fuzz_target;
use vpx_efis::protocol::describe::{describe, to_json};
use vpx_efis::protocol::frame::MAX_FRAME;
use vpx_efis::protocol::{Decoder, Event, Packet};

fuzz_target!(|input: (Vec<u8>, Vec<u8>)| {
    let (cuts, stream) = input;
    let mut dec = Decoder::new();
    let mut accounted = 0u64;
    let mut on_event = |e: Event<'_>| match e {
        Event::Frame(f) => {
            accounted += f.as_bytes().len() as u64;
            if let Ok(p) = Packet::parse(&f) {
                let _ = describe(&p.message);
                let _ = to_json(&p.message);
                assert_eq!(Packet::parse_bytes(&p.to_bytes()), Ok(p));
            }
        }
        Event::Skipped(b) | Event::UnknownMessage(b) => accounted += b.len() as u64,
        // Only the first byte of a rejected candidate is consumed.
        Event::BadChecksum(_) | Event::BadLength(_) => accounted += 1,
    };
    let mut rest = &stream[..];
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
        assert!(dec.pending() <= MAX_FRAME);
    }
    let s = dec.stats();
    assert_eq!(s.bytes_in, stream.len() as u64);
    assert_eq!(accounted + dec.pending() as u64, s.bytes_in);
});

//! The link sink: the link's callback, which applies what the link reports to the
//! shared model (and the capture file), then wakes the page's loop.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use crossbeam_channel::Sender;

use super::{Recorder, Wake, lock, record};
use crate::link::{self, LinkEvent, RxItem};
use crate::model::Model;

pub(super) type SharedSink = Arc<dyn Fn(LinkEvent) + Send + Sync>;

/// The link's callback: applies what it sees to the model, then wakes the loop.
pub(super) fn link_sink(
    model: Arc<Mutex<Model>>,
    wake: Sender<Wake>,
    recorder: Option<Recorder>,
) -> impl Fn(LinkEvent) + Send + Sync + 'static {
    move |ev| {
        let w = {
            let mut m = lock(&model);
            match ev {
                LinkEvent::Connected { port } => {
                    let at = Instant::now();
                    record::on_connected(&recorder, &mut m, at);
                    m.traffic.note_connected(at);
                    m.note_connected(at, port);
                    Some(Wake::Connected)
                }
                LinkEvent::Disconnected { reason } | LinkEvent::OpenFailed { reason } => {
                    m.note_link_lost(Instant::now(), reason);
                    Some(Wake::LinkDown)
                }
                // A write is recorded with its Tx event, under the same lock, so the
                // model never lags the capture by one frame (a replay sought to any
                // instant then shows what the live page showed).
                LinkEvent::Bytes {
                    dir: link::Crossing::Tx,
                    ..
                } => None,
                LinkEvent::Bytes { at, dir, bytes } => {
                    record::on_bytes(&recorder, &mut m, at, dir, &bytes);
                    None
                }
                LinkEvent::Rx {
                    at,
                    item,
                    stats,
                    raw,
                } => {
                    m.traffic.note_rx(at, &item, &raw);
                    m.note_decoder(stats);
                    match item {
                        RxItem::Packet(p) => m.apply_packet(at, &p),
                        RxItem::Malformed(_) => m.note_malformed(),
                        _ => {}
                    }
                    Some(Wake::Data)
                }
                LinkEvent::Tx { at, packet, raw } => {
                    record::on_bytes(&recorder, &mut m, at, link::Crossing::Tx, &raw);
                    m.traffic.note_tx(at, packet.as_ref(), &raw);
                    if let Some(p) = packet {
                        m.note_sent(at, &p);
                    }
                    None
                }
                LinkEvent::WriteError { at, reason } => {
                    m.note_write_error(at, reason);
                    Some(Wake::WriteError)
                }
            }
        };
        if let Some(w) = w {
            let _ = wake.send(w);
        }
    }
}

//! `vpx-efis gateway` after a loss of communication, every part a process of its own
//! as a user starts them: the virtual VP-X (`vpx-efis sim --pty`, commanded from its
//! console), the gateway on its pty, and an XFSp receiver on real UDP on 127.0.0.1.
//!
//! When the unit's data returns, the gateway forgets the circuits' names (the unit
//! may have been renamed meanwhile) and must read them again, as the page does. Until
//! it has, a receiver that tells circuits apart by their "System/Item" label (as the
//! XFSp draft has it) must still be able to: no two circuits under one label.
#![cfg(unix)]

use std::collections::BTreeMap;
use std::io::Write;
use std::net::UdpSocket;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use vpx_efis::xfsp::format::latin1;
use vpx_efis::xfsp::{Body, EcbState, Message, Value, idents};

mod common;
use common::process::{Sim, gateway, sim};

/// One ECBSTAT as heard: circuit (unit), label, state.
type Ecb = (u16, String, EcbState);

/// Every datagram the receiver heard, with when, as its ECBSTATs.
type Heard = Arc<Mutex<Vec<(Instant, Vec<Ecb>)>>>;

fn listen(peer: UdpSocket) -> Heard {
    let heard: Heard = Arc::default();
    let h = heard.clone();
    std::thread::spawn(move || {
        let mut buf = [0u8; 4096];
        loop {
            let Ok(n) = peer.recv(&mut buf) else { continue };
            let at = Instant::now();
            let Ok(Message {
                body: Body::Params(ps),
                ..
            }) = Message::parse(&buf[..n])
            else {
                continue;
            };
            let ecbs: Vec<Ecb> = ps
                .iter()
                .filter(|p| p.ident == idents::ECBSTAT)
                .filter_map(|p| match &p.value {
                    Value::Bus(b) => Some((p.unit, latin1(&b.label), b.state)),
                    _ => None,
                })
                .collect();
            if !ecbs.is_empty() {
                h.lock().unwrap().push((at, ecbs));
            }
        }
    });
    heard
}

/// The label each circuit was last published under, from what was heard in `window`.
fn labels_in(heard: &Heard, from: Instant, to: Instant) -> BTreeMap<u16, String> {
    let mut out = BTreeMap::new();
    for (at, ecbs) in heard.lock().unwrap().iter() {
        if *at >= from && *at < to {
            for (unit, label, _) in ecbs {
                out.insert(*unit, label.clone());
            }
        }
    }
    out
}

#[test]
fn after_a_loss_every_circuit_is_published_under_its_own_name_within_2_s_and_never_shares_one() {
    let Sim {
        process: _sim,
        mut console,
        line: path,
    } = sim(&["--pty", "--scenario", "demo"]);

    let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
    peer.set_read_timeout(Some(Duration::from_millis(50)))
        .unwrap();
    let to = peer.local_addr().unwrap().to_string();
    let heard = listen(peer);
    // Its config file and audit log in a folder of the test's own.
    let home = tempfile::tempdir().unwrap();
    let (_gateway, said) = gateway(&path, &to, home.path());

    // Before the loss: the labels settle once every name has been read (two refresh
    // rounds alike, with names the demo scenario gives, written here by hand).
    let end = Instant::now() + Duration::from_secs(20);
    let names = loop {
        std::thread::sleep(Duration::from_millis(1300));
        let now = Instant::now();
        let last = labels_in(&heard, now - Duration::from_millis(1300), now);
        let before = labels_in(
            &heard,
            now - Duration::from_millis(2600),
            now - Duration::from_millis(1300),
        );
        if last.get(&2).map(String::as_str) == Some("VP-X/EFIS 1") && last == before {
            break last;
        }
        assert!(
            Instant::now() < end,
            "the names never settled: {last:?}; the gateway said {:?}",
            said.lock().unwrap()
        );
    };
    assert_eq!(names[&17], "VP-X/Landing Lt");
    assert_eq!(names[&27], "VP-X/Map Lt");
    assert!(names.len() >= 10, "{names:?}");

    // The unit goes silent for 4 s, from its console, as a cable pulled and put back.
    let silenced = Instant::now();
    writeln!(console, "silent 4").unwrap();
    console.flush().unwrap();
    let back = silenced + Duration::from_secs(4);
    std::thread::sleep(Duration::from_secs(4) + Duration::from_secs(4));
    let heard_now = heard.lock().unwrap().clone();

    // The loss was seen: every circuit published UNKNOWN before the data returned.
    assert!(
        heard_now
            .iter()
            .filter(|(at, _)| *at > silenced && *at < back)
            .flat_map(|(_, e)| e)
            .any(|(_, _, s)| *s == EcbState::Unknown0),
        "the loss was never published"
    );

    // From the silence on, no datagram and no moment has two circuits under one
    // label: the label each circuit was last published under is its own.
    let mut current = names.clone();
    for (at, ecbs) in heard_now.iter().filter(|(at, _)| *at > silenced) {
        let mut in_one = BTreeMap::new();
        for (unit, label, _) in ecbs {
            if let Some(other) = in_one.insert(label.clone(), *unit) {
                panic!(
                    "circuits {other} and {unit} both published as {label:?}, {:?} after \
                     the data returned",
                    at.saturating_duration_since(back)
                );
            }
            current.insert(*unit, label.clone());
        }
        let mut seen = BTreeMap::new();
        for (unit, label) in &current {
            if let Some(other) = seen.insert(label, unit) {
                panic!(
                    "circuits {other} and {unit} stand under one label {label:?}, {:?} \
                     after the data returned",
                    at.saturating_duration_since(back)
                );
            }
        }
    }

    // Within 2 s of the data's return, every circuit is published again under its own
    // name with a known state.
    let mut again: BTreeMap<u16, Instant> = BTreeMap::new();
    for (at, ecbs) in heard_now.iter().filter(|(at, _)| *at > back) {
        for (unit, label, state) in ecbs {
            if *state != EcbState::Unknown0 && names.get(unit) == Some(label) {
                again.entry(*unit).or_insert(*at);
            }
        }
    }
    for (unit, name) in &names {
        let at = again.get(unit).unwrap_or_else(|| {
            panic!(
                "circuit {unit} never published as {name:?} again; after the data returned \
                 it was {:?}",
                heard_now
                    .iter()
                    .filter(|(at, _)| *at > back)
                    .flat_map(|(_, e)| e)
                    .filter(|(u, _, _)| u == unit)
                    .map(|(_, l, _)| l)
                    .collect::<std::collections::BTreeSet<_>>()
            )
        });
        let after = at.saturating_duration_since(back);
        assert!(
            after <= Duration::from_secs(2),
            "circuit {unit} published as {name:?} {after:?} after the data returned"
        );
    }
    let last = again
        .values()
        .max()
        .unwrap()
        .saturating_duration_since(back);
    eprintln!(
        "every circuit under its own name again {last:?} after the data returned ({} circuits)",
        names.len()
    );
}

//! Ask the unit something and wait for its answer: a synchronous request/response
//! client over a [`Link`], for the commands (backup, restore, flash) and the setup
//! screens. It knows the wire, not the model: it returns messages and a
//! [`UnitConfig`], and keeps no state about the unit between calls.
//!
//! **Matching a reply.** ICD Table 2 note 1 and icd-reading R14: the EFIS chooses the
//! command number of each request and the VP-X echoes it in the response, while
//! broadcasts carry the unit's own count. A reply is therefore a packet from the unit
//! whose command number is one this request used *and* that the caller's `matches`
//! accepts (its message type and device id). The count alone is not enough, because a
//! broadcast can carry the same number by chance; the type alone is not enough, because
//! a late answer to an earlier request would be taken for this one.
//!
//! **Retries.** When to send again and when to give up is [`crate::exchange`]'s, as for
//! every request. Each try is sent with a fresh command number. An answer carrying the
//! number of an *earlier* try of the same request is still accepted: a unit that was
//! merely slow has answered the same question, and waiting for a second answer would
//! only make it slower.

use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, unbounded};

use super::connection::{Connector, Link, LinkEvent, RxItem};
use crate::exchange::{ANSWER_TIMEOUT, ERASE_TIMEOUT, TRIES, Try, Verdict};
use crate::protocol::config::UnitConfig;
use crate::protocol::device::{
    self, DEVICE_COUNT, FLAPS, SYSTEM_SPEC_ID, TRIM_P, TRIM_R, WIG_WAG_SPEC_ID, enable_flag_allowed,
};
use crate::protocol::message::{
    DeviceEnable, DeviceNameQuery, DeviceSpecQuery, DeviceStatus, DeviceStatusQuery, EepromErase,
    EnableFlag, Message, SpecAckError, SystemStatus, TrimType, Version,
};
use crate::protocol::{Error as WireError, Packet};

/// How long [`UnitClient::new`] waits for the port to open.
pub const CONNECT_TIMEOUT: Duration = Duration::from_secs(3);

/// Why a request got no usable answer.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RequestError {
    #[error("the unit did not answer {what} after {tries} {}", if *tries == 1 { "try" } else { "tries" })]
    Timeout { what: String, tries: u8 },
    #[error("the link to the unit was lost while asking {what}: {reason}")]
    LinkLost { what: String, reason: String },
    #[error("could not open the link to the unit: {reason}")]
    NotConnected { reason: String },
    #[error("the unit answered {what} with a frame that does not decode: {error}")]
    Malformed { what: String, error: WireError },
}

/// Why a setting was not stored.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SpecError {
    /// The unit answered with a non-zero SPEC_ACK code (ICD Table 20).
    #[error("the unit refused {what}: {} (SPEC_ACK code {:#04x})", .error.description(), .error.to_byte())]
    Refused { what: String, error: SpecAckError },
    #[error(transparent)]
    Request(#[from] RequestError),
}

/// What the link reports that a waiting request cares about.
enum Inbound {
    Packet(Packet),
    /// A frame of a known message that does not decode, with the command number from
    /// its header (byte 5), so that a garbled answer is reported rather than waited out.
    Malformed {
        cnt: u8,
        error: WireError,
    },
    Up,
    Down(String),
}

/// A synchronous request/response client over one [`Link`].
pub struct UnitClient {
    link: Link,
    rx: Receiver<Inbound>,
    next_cnt: u8,
    /// Why the link is down, or `None` while it is up.
    down: Option<String>,
    port: String,
}

impl UnitClient {
    /// Starts a link on `connector` and waits (up to [`CONNECT_TIMEOUT`]) for the port to
    /// open, so that a wrong path is reported at once with its reason.
    pub fn new(connector: Connector) -> Result<UnitClient, RequestError> {
        let (tx, rx) = unbounded();
        let port = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
        let link = {
            let port = port.clone();
            Link::start(connector, move |e| forward(&tx, &port, e))
        };
        let mut client = UnitClient {
            link,
            rx,
            // Any start will do (the unit only echoes it); 1 makes captures easy to read.
            next_cnt: 1,
            down: Some("the port has not opened yet".into()),
            port: String::new(),
        };
        let end = Instant::now() + CONNECT_TIMEOUT;
        while client.down.is_some() {
            let left = end.saturating_duration_since(Instant::now());
            match client.rx.recv_timeout(left) {
                Ok(Inbound::Up) => client.down = None,
                Ok(Inbound::Down(reason)) => {
                    return Err(RequestError::NotConnected { reason });
                }
                Ok(_) => {}
                Err(_) => {
                    return Err(RequestError::NotConnected {
                        reason: format!(
                            "the port did not open within {} s",
                            CONNECT_TIMEOUT.as_secs()
                        ),
                    });
                }
            }
        }
        client.port = port.lock().map(|p| p.clone()).unwrap_or_default();
        Ok(client)
    }

    /// The port's name as the link reported it when it opened.
    pub fn port(&self) -> &str {
        &self.port
    }

    /// Sends `message` and returns the first reply that carries one of this request's
    /// command numbers and that `matches` accepts. `tries` counts every attempt, the
    /// first included (0 is taken as 1); each waits up to `timeout`.
    pub fn request(
        &mut self,
        message: impl Into<Message>,
        matches: impl Fn(&Message) -> bool,
        timeout: Duration,
        tries: u8,
    ) -> Result<Message, RequestError> {
        self.ask(message, |m| matches(m).then_some(*m), timeout, tries)
    }

    /// [`Self::request`], answered with what `pick` takes from the first reply it
    /// takes anything from.
    fn ask<T>(
        &mut self,
        message: impl Into<Message>,
        pick: impl Fn(&Message) -> Option<T>,
        timeout: Duration,
        tries: u8,
    ) -> Result<T, RequestError> {
        let message = message.into();
        let what = request_name(&message);
        let mut try_ = Try::with(Instant::now(), timeout, tries);
        let mut sent: Vec<u8> = Vec::with_capacity(usize::from(try_.of()));
        // Whatever is queued from before this request (broadcasts, stale answers) cannot
        // be its answer; draining keeps the wait loop short and link state current.
        self.drain();
        loop {
            if let Some(reason) = self.down.clone() {
                // Give a reopening port (a pulled and replugged cable) one timeout to
                // come back before this try is spent.
                if !self.wait_until_up(timeout) {
                    return Err(RequestError::LinkLost { what, reason });
                }
            }
            let cnt = self.take_cnt();
            sent.push(cnt);
            if self
                .link
                .handle()
                .send(Packet::request(cnt, message))
                .is_err()
            {
                return Err(RequestError::LinkLost {
                    what,
                    reason: "the link has shut down".into(),
                });
            }
            let end = Instant::now() + timeout;
            loop {
                let left = end.saturating_duration_since(Instant::now());
                match self.rx.recv_timeout(left) {
                    Ok(Inbound::Packet(p)) => {
                        if p.src == crate::protocol::Node::Vpx
                            && sent.contains(&p.cnt)
                            && let Some(answer) = pick(&p.message)
                        {
                            return Ok(answer);
                        }
                    }
                    Ok(Inbound::Malformed { cnt, error }) if sent.contains(&cnt) => {
                        return Err(RequestError::Malformed { what, error });
                    }
                    Ok(Inbound::Malformed { .. }) => {}
                    Ok(Inbound::Up) => self.down = None,
                    Ok(Inbound::Down(reason)) => {
                        self.down = Some(reason);
                        // What was sent may never have left; try again once it is back.
                        break;
                    }
                    Err(RecvTimeoutError::Timeout) => break,
                    Err(RecvTimeoutError::Disconnected) => {
                        return Err(RequestError::LinkLost {
                            what,
                            reason: "the link has shut down".into(),
                        });
                    }
                }
            }
            if try_.spent(Instant::now()) == Verdict::NoAnswer {
                break;
            }
        }
        match self.down.clone() {
            Some(reason) => Err(RequestError::LinkLost { what, reason }),
            None => Err(RequestError::Timeout {
                what,
                tries: try_.of(),
            }),
        }
    }

    /// Sends a setting (DEVICE_SPEC, SYSTEM_SPEC, TRIM_SPEC, FLAP_SPEC, WIG_WAG_SPEC or
    /// DEVICE_NAME) and waits for its SPEC_ACK (ICD §6.2.7). `Ok` only when the unit
    /// answered code 0: nothing counts as stored that the unit did not acknowledge.
    pub fn send_spec(
        &mut self,
        spec: impl Into<Message>,
        timeout: Duration,
        tries: u8,
    ) -> Result<(), SpecError> {
        let spec = spec.into();
        let want = spec_ack_id(&spec);
        let refused = self.ask(
            spec,
            |m| match m {
                Message::SpecAck(a) if want.is_none_or(|id| a.device_id == id) => Some(a.error),
                _ => None,
            },
            timeout,
            tries,
        )?;
        match refused {
            None => Ok(()),
            Some(error) => Err(SpecError::Refused {
                what: setting_name(&spec),
                error,
            }),
        }
    }

    /// Asks VERSION (ICD §6.1.2).
    pub fn version(&mut self) -> Result<Version, RequestError> {
        // The unit answers with the hardware field set; our own request (hardware 0)
        // can never be mistaken for it because only packets from the unit count.
        self.ask(
            Version::REQUEST,
            |m| match m {
                Message::Version(v) => Some(*v),
                _ => None,
            },
            ANSWER_TIMEOUT,
            TRIES,
        )
    }

    /// EEPROM_ERASE (ICD §6.1.4): returns the unit's result code, 0 meaning success.
    /// Sent once: the unit takes long to answer (see [`ERASE_TIMEOUT`]) and a second
    /// erase while the first runs would gain nothing.
    pub fn erase_eeprom(&mut self) -> Result<u8, RequestError> {
        self.ask(
            EepromErase { response_code: 0 },
            |m| match m {
                Message::EepromErase(e) => Some(e.response_code),
                _ => None,
            },
            ERASE_TIMEOUT,
            1,
        )
    }

    /// DEVICE_SPEC_QUERY for `id` (ICD §6.2.6). The answer's type depends on the id
    /// (icd-reading R13): 0 FLAP_SPEC, 29/30 TRIM_SPEC roll/pitch, 253 SYSTEM_SPEC,
    /// 254 WIG_WAG_SPEC, others DEVICE_SPEC for that id.
    pub fn query_spec(&mut self, id: u8) -> Result<Message, RequestError> {
        self.request(
            DeviceSpecQuery { device_id: id },
            move |m| query_answers(id, m),
            ANSWER_TIMEOUT,
            TRIES,
        )
    }

    /// DEVICE_NAME_QUERY for `id` (ICD §6.2.9): the stored 16 bytes.
    pub fn query_name(&mut self, id: u8) -> Result<[u8; 16], RequestError> {
        self.ask(
            DeviceNameQuery { device_id: id },
            move |m| match m {
                Message::DeviceName(n) if n.device_id == id => Some(n.name),
                _ => None,
            },
            ANSWER_TIMEOUT,
            TRIES,
        )
    }

    /// DEVICE_ENABLE with flag 2 for `id` (ICD §6.2.10): whether the page shows it.
    pub fn query_enable(&mut self, id: u8) -> Result<bool, RequestError> {
        self.ask(
            DeviceEnable {
                device_id: id,
                flag: EnableFlag::Query,
            },
            move |m| match m {
                Message::DeviceEnable(e) if e.device_id == id => match e.flag {
                    EnableFlag::Enabled => Some(true),
                    EnableFlag::Disabled => Some(false),
                    _ => None,
                },
                _ => None,
            },
            ANSWER_TIMEOUT,
            TRIES,
        )
    }

    /// DEVICE_STATUS_QUERY (ICD Table 2): every circuit's on/off and current now.
    pub fn device_status(&mut self) -> Result<DeviceStatus, RequestError> {
        self.ask(
            DeviceStatusQuery,
            |m| match m {
                Message::DeviceStatus(s) => Some(*s),
                _ => None,
            },
            ANSWER_TIMEOUT,
            TRIES,
        )
    }

    /// The next SYSTEM_STATUS the unit broadcasts (1 Hz, ICD Table 24), waiting up to
    /// `timeout`; `None` when none came.
    pub fn next_system_status(&mut self, timeout: Duration) -> Option<SystemStatus> {
        self.drain();
        let end = Instant::now() + timeout;
        loop {
            let left = end.saturating_duration_since(Instant::now());
            match self.rx.recv_timeout(left) {
                Ok(Inbound::Packet(p)) => {
                    if let (crate::protocol::Node::Vpx, Message::SystemStatus(s)) =
                        (p.src, p.message)
                    {
                        return Some(s);
                    }
                }
                Ok(Inbound::Up) => self.down = None,
                Ok(Inbound::Down(r)) => self.down = Some(r),
                Ok(Inbound::Malformed { .. }) => {}
                Err(_) => return None,
            }
        }
    }

    /// Sets whether the page shows `id` (DEVICE_ENABLE flag 0/1), then reads it back.
    ///
    /// Table 23 gives the unit no answer to a set (only to the query, flag 2), so the
    /// query that follows is the only way to know the setting was stored. `Ok(false)`
    /// means the unit answered but holds the other value.
    pub fn set_enable(&mut self, id: u8, shown: bool) -> Result<bool, RequestError> {
        let set = DeviceEnable {
            device_id: id,
            flag: if shown {
                EnableFlag::Enabled
            } else {
                EnableFlag::Disabled
            },
        };
        let cnt = self.take_cnt();
        if self.link.handle().send(Packet::request(cnt, set)).is_err() {
            return Err(RequestError::LinkLost {
                what: request_name(&set.into()),
                reason: "the link has shut down".into(),
            });
        }
        Ok(self.query_enable(id)? == shown)
    }

    /// Reads the whole configuration: VERSION, then every DEVICE_SPEC (1–28), FLAP_SPEC
    /// (query 0), both TRIM_SPECs (29, 30), SYSTEM_SPEC (253), WIG_WAG_SPEC (254), every
    /// DEVICE_NAME (0–30) and every DEVICE_ENABLE (4–28). `progress(done, total)` is
    /// called before the first request and after each answer.
    ///
    /// Entries the ICD gives no query for (the breaker of the two trims, the enable flag
    /// of ids outside 4–28) keep their [`UnitConfig::default`] values.
    pub fn query_config(
        &mut self,
        mut progress: impl FnMut(usize, usize),
    ) -> Result<(Version, UnitConfig), RequestError> {
        let spec_ids: Vec<u8> = (1..TRIM_R)
            .chain([FLAPS, TRIM_R, TRIM_P, SYSTEM_SPEC_ID, WIG_WAG_SPEC_ID])
            .collect();
        let enable_ids: Vec<u8> = (0..DEVICE_COUNT as u8)
            .filter(|&i| enable_flag_allowed(i))
            .collect();
        let total = 1 + spec_ids.len() + DEVICE_COUNT + enable_ids.len();
        let mut done = 0;
        progress(done, total);
        let mut step = |done: &mut usize| {
            *done += 1;
            progress(*done, total);
        };

        let version = self.version()?;
        step(&mut done);
        let mut cfg = UnitConfig::default();
        for id in spec_ids {
            match self.query_spec(id)? {
                Message::DeviceSpec(s) => cfg.apply_device_spec(&s),
                Message::FlapSpec(s) => cfg.apply_flap_spec(&s),
                Message::TrimSpec(s) => cfg.apply_trim_spec(&s),
                Message::SystemSpec(s) => cfg.apply_system_spec(&s),
                Message::WigWagSpec(s) => cfg.apply_wig_wag_spec(&s),
                _ => unreachable!("query_answers accepts only spec messages"),
            }
            step(&mut done);
        }
        for id in 0..DEVICE_COUNT as u8 {
            cfg.names[id as usize] = self.query_name(id)?;
            step(&mut done);
        }
        for id in enable_ids {
            cfg.enabled[id as usize] = self.query_enable(id)?;
            step(&mut done);
        }
        Ok((version, cfg))
    }

    /// Stops the link's threads. Dropping the client does the same.
    pub fn close(self) {
        self.link.shutdown();
    }

    fn take_cnt(&mut self) -> u8 {
        let c = self.next_cnt;
        self.next_cnt = self.next_cnt.wrapping_add(1);
        c
    }

    fn drain(&mut self) {
        while let Ok(i) = self.rx.try_recv() {
            match i {
                Inbound::Up => self.down = None,
                Inbound::Down(r) => self.down = Some(r),
                _ => {}
            }
        }
    }

    fn wait_until_up(&mut self, timeout: Duration) -> bool {
        let end = Instant::now() + timeout;
        while self.down.is_some() {
            match self
                .rx
                .recv_timeout(end.saturating_duration_since(Instant::now()))
            {
                Ok(Inbound::Up) => self.down = None,
                Ok(Inbound::Down(r)) => self.down = Some(r),
                Ok(_) => {}
                Err(_) => return false,
            }
        }
        true
    }
}

fn forward(tx: &Sender<Inbound>, port: &std::sync::Mutex<String>, e: LinkEvent) {
    let i = match e {
        LinkEvent::Connected { port: p } => {
            if let Ok(mut slot) = port.lock() {
                *slot = p;
            }
            Inbound::Up
        }
        LinkEvent::Disconnected { reason } | LinkEvent::OpenFailed { reason } => {
            Inbound::Down(reason)
        }
        LinkEvent::WriteError { reason, .. } => Inbound::Down(reason),
        LinkEvent::Rx {
            item: RxItem::Packet(p),
            ..
        } => Inbound::Packet(p),
        LinkEvent::Rx {
            item: RxItem::Malformed(error),
            raw,
            ..
        } => Inbound::Malformed {
            cnt: raw.get(4).copied().unwrap_or(0),
            error,
        },
        _ => return,
    };
    // The client may be gone while the link winds down; nothing is left to tell.
    let _ = tx.send(i);
}

/// Whether `m` is the answer to DEVICE_SPEC_QUERY `id` (icd-reading R13).
pub fn query_answers(id: u8, m: &Message) -> bool {
    match (id, m) {
        (FLAPS, Message::FlapSpec(_)) => true,
        (TRIM_R, Message::TrimSpec(t)) => t.trim_type == TrimType::Roll,
        (TRIM_P, Message::TrimSpec(t)) => t.trim_type == TrimType::Pitch,
        (SYSTEM_SPEC_ID, Message::SystemSpec(_)) => true,
        (WIG_WAG_SPEC_ID, Message::WigWagSpec(_)) => true,
        (id, Message::DeviceSpec(s)) => s.device_id == id && !matches!(id, FLAPS | TRIM_R | TRIM_P),
        _ => false,
    }
}

/// The device id the SPEC_ACK to `spec` carries (ICD Table 19 and its note 1), or `None`
/// when any id is accepted.
///
/// Table 19's byte 1 is "the device identifier used when sending the specification
/// request", and note 1 names only 253 (SYSTEM_SPEC) and 254 (WIG_WAG_SPEC).
/// TRIM_SPEC and FLAP_SPEC carry no device id, so the ICD names none for their
/// SPEC_ACK (0, 29 and 30 are only the query's mapping, icd-reading R13): for them
/// the echoed command number alone identifies the answer, whatever id it carries.
/// (The virtual VP-X answers FLAP_SPEC with 0 and TRIM_SPEC with 29/30.)
pub fn spec_ack_id(spec: &Message) -> Option<u8> {
    match spec {
        Message::DeviceSpec(s) => Some(s.device_id),
        Message::SystemSpec(_) => Some(SYSTEM_SPEC_ID),
        Message::WigWagSpec(_) => Some(WIG_WAG_SPEC_ID),
        Message::DeviceName(n) => Some(n.device_id),
        _ => None,
    }
}

fn pin(id: u8) -> String {
    match device::device(id) {
        Some(d) => d.system_name.to_string(),
        None => format!("device {id}"),
    }
}

/// "DEVICE_SPEC_QUERY for 5A-3", for error messages.
pub fn request_name(m: &Message) -> String {
    let subject = match m {
        Message::DeviceSpecQuery(q) => Some(match q.device_id {
            SYSTEM_SPEC_ID => "the system settings".to_string(),
            WIG_WAG_SPEC_ID => "the wig-wag".to_string(),
            id => pin(id),
        }),
        Message::DeviceNameQuery(q) => Some(pin(q.device_id)),
        Message::DeviceEnable(e) => Some(pin(e.device_id)),
        _ => return setting_name(m),
    };
    match subject {
        Some(s) => format!("{} for {s}", m.name()),
        None => m.name().to_string(),
    }
}

/// "DEVICE_SPEC for 5A-3", "TRIM_SPEC (pitch)", "SYSTEM_SPEC", for messages that set.
pub fn setting_name(m: &Message) -> String {
    match m {
        Message::DeviceSpec(s) => format!("DEVICE_SPEC for {}", pin(s.device_id)),
        Message::DeviceName(n) => format!("DEVICE_NAME for {}", pin(n.device_id)),
        Message::DeviceEnable(e) => format!("DEVICE_ENABLE for {}", pin(e.device_id)),
        Message::TrimSpec(t) => match t.trim_type {
            TrimType::Roll => "TRIM_SPEC (roll)".into(),
            TrimType::Pitch => "TRIM_SPEC (pitch)".into(),
            TrimType::Unknown(n) => format!("TRIM_SPEC (type {n})"),
        },
        m => m.name().to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::{PipeEnd, duplex_pipe, pipe_connector};
    use crate::protocol::message::{DeviceSpec, Ping, SpecAck, SwitchId};
    use crate::protocol::{Decoder, Event};
    use std::io::{Read, Write};

    /// A hand-written unit on the far end of a pipe: `answer` turns each request into
    /// the packets to send back (or none).
    fn fake_unit(
        end: PipeEnd,
        answer: impl Fn(&Packet) -> Vec<Packet> + Send + 'static,
    ) -> std::thread::JoinHandle<Vec<Packet>> {
        std::thread::spawn(move || {
            let PipeEnd {
                mut reader,
                mut writer,
            } = end;
            let mut dec = Decoder::new();
            let mut seen = Vec::new();
            let mut buf = [0u8; 256];
            loop {
                let n = match reader.read(&mut buf) {
                    Ok(0) => return seen,
                    Ok(n) => n,
                    Err(e) if e.kind() == std::io::ErrorKind::TimedOut => continue,
                    Err(_) => return seen,
                };
                let mut got = Vec::new();
                dec.push(&buf[..n], |e| {
                    if let Event::Frame(f) = e
                        && let Ok(p) = Packet::parse(&f)
                    {
                        got.push(p);
                    }
                });
                for p in got {
                    for r in answer(&p) {
                        if writer.write_all(&r.to_bytes()).is_err() {
                            return seen;
                        }
                    }
                    seen.push(p);
                }
            }
        })
    }

    fn client_with(
        answer: impl Fn(&Packet) -> Vec<Packet> + Send + 'static,
    ) -> (UnitClient, std::thread::JoinHandle<Vec<Packet>>) {
        let (ours, theirs) = duplex_pipe(Duration::from_millis(20));
        let unit = fake_unit(theirs, answer);
        (UnitClient::new(pipe_connector(ours, "pipe")).unwrap(), unit)
    }

    /// The unit's SPEC_ACK (ICD Table 19) to command `cnt`, for `device_id`.
    fn ack(cnt: u8, device_id: u8, error: Option<SpecAckError>) -> Packet {
        Packet::from_vpx(cnt, SpecAck { device_id, error })
    }

    fn spec(id: u8) -> DeviceSpec {
        DeviceSpec {
            device_id: id,
            circuit_breaker: 3,
            switch_id: SwitchId::Input(2),
            current_fault: true,
            switch_raw: None,
        }
    }

    #[test]
    fn a_reply_is_matched_by_echoed_number_and_type_not_by_type_alone() {
        let (mut c, unit) = client_with(|p| match p.message {
            Message::DeviceSpecQuery(q) => vec![
                // A broadcast-looking DEVICE_SPEC with another number comes first and
                // must not be taken for the answer.
                Packet::from_vpx(p.cnt.wrapping_add(100), spec(q.device_id)),
                // The echoed number on the wrong type must not be taken either.
                Packet::from_vpx(p.cnt, Ping { ack: true }),
                Packet::from_vpx(
                    p.cnt,
                    DeviceSpec {
                        circuit_breaker: 5,
                        ..spec(q.device_id)
                    },
                ),
            ],
            _ => vec![],
        });
        let got = c.query_spec(6).unwrap();
        assert_eq!(
            got,
            Message::DeviceSpec(DeviceSpec {
                circuit_breaker: 5,
                ..spec(6)
            })
        );
        c.close();
        let seen = unit.join().unwrap();
        assert_eq!(seen.len(), 1, "answered at the first try");
    }

    #[test]
    fn silence_is_a_timeout_that_names_the_request_and_counts_tries() {
        let (mut c, unit) = client_with(|_| vec![]);
        let start = Instant::now();
        let err = c
            .request(
                DeviceSpecQuery { device_id: 6 },
                |m| query_answers(6, m),
                Duration::from_millis(100),
                3,
            )
            .unwrap_err();
        assert!(start.elapsed() < Duration::from_secs(2), "no hang");
        assert_eq!(
            err.to_string(),
            "the unit did not answer DEVICE_SPEC_QUERY for 5A-3 after 3 tries"
        );
        c.close();
        let seen = unit.join().unwrap();
        let cnts: Vec<u8> = seen.iter().map(|p| p.cnt).collect();
        assert_eq!(cnts.len(), 3);
        assert!(
            cnts[0] != cnts[1] && cnts[1] != cnts[2],
            "each try has its own number: {cnts:?}"
        );
    }

    #[test]
    fn a_late_answer_to_an_earlier_try_is_accepted() {
        // The unit answers only the first try, and only when the second arrives: a slow
        // unit, not a deaf one.
        let first = std::sync::Mutex::new(None::<u8>);
        let (mut c, unit) = client_with(move |p| {
            let mut f = first.lock().unwrap();
            match *f {
                None => {
                    *f = Some(p.cnt);
                    vec![]
                }
                Some(cnt) => vec![ack(cnt, 6, None)],
            }
        });
        c.send_spec(spec(6), Duration::from_millis(150), 3).unwrap();
        c.close();
        assert_eq!(unit.join().unwrap().len(), 2);
    }

    #[test]
    fn a_refusal_is_reported_in_the_words_of_table_20() {
        let (mut c, _unit) =
            client_with(|p| vec![ack(p.cnt, 6, Some(SpecAckError::InvalidBreaker))]);
        let err = c.send_spec(spec(6), ANSWER_TIMEOUT, 1).unwrap_err();
        assert_eq!(
            err.to_string(),
            "the unit refused DEVICE_SPEC for 5A-3: Invalid circuit breaker value (SPEC_ACK code 0x03)"
        );
    }

    #[test]
    fn a_spec_ack_for_another_device_is_not_this_ones() {
        let (mut c, _unit) = client_with(|p| vec![ack(p.cnt, 7, None)]);
        assert!(matches!(
            c.send_spec(spec(6), Duration::from_millis(100), 1),
            Err(SpecError::Request(RequestError::Timeout { .. }))
        ));
    }

    #[test]
    fn flap_and_trim_spec_acks_are_matched_by_command_number_whatever_their_id() {
        // Table 19 names no id for the SPEC_ACK of FLAP_SPEC or TRIM_SPEC: an
        // independent unit may answer with any (here 0xFF and 7), and the echoed
        // command number is what makes it the answer. A DEVICE_SPEC's ack still
        // needs its id (see `a_spec_ack_for_another_device_is_not_this_ones`).
        let (mut c, _unit) = client_with(|p| {
            let id = match p.message {
                Message::FlapSpec(_) => 0xFF,
                _ => 7,
            };
            vec![ack(p.cnt, id, None)]
        });
        c.send_spec(
            crate::protocol::defaults::flap_spec(),
            Duration::from_millis(300),
            1,
        )
        .unwrap();
        c.send_spec(
            crate::protocol::defaults::trim_spec(TrimType::Pitch),
            Duration::from_millis(300),
            1,
        )
        .unwrap();
        assert_eq!(
            spec_ack_id(&crate::protocol::defaults::flap_spec().into()),
            None
        );
    }

    #[test]
    fn a_lost_link_is_not_reported_as_a_silent_unit() {
        let (ours, theirs) = duplex_pipe(Duration::from_millis(20));
        let mut c = UnitClient::new(pipe_connector(ours, "pipe")).unwrap();
        drop(theirs);
        let err = c.query_spec(6).unwrap_err();
        assert!(
            matches!(err, RequestError::LinkLost { .. }),
            "{err:?}: a pipe cannot be reopened, so the link is lost"
        );
        assert!(
            err.to_string().contains("DEVICE_SPEC_QUERY for 5A-3"),
            "{err}"
        );
    }

    #[test]
    fn a_port_that_cannot_open_is_reported_at_once() {
        let Err(err) = UnitClient::new(crate::link::serial_connector(
            "/dev/does-not-exist-vpx".into(),
            57_600,
        )) else {
            panic!("a missing port must not connect");
        };
        assert!(err.to_string().contains("vpx-efis ports"), "{err}");
    }

    #[test]
    fn query_answers_follows_icd_reading_r13() {
        use crate::protocol::defaults;
        let pitch = Message::TrimSpec(defaults::trim_spec(TrimType::Pitch));
        let roll = Message::TrimSpec(defaults::trim_spec(TrimType::Roll));
        assert!(query_answers(TRIM_P, &pitch) && !query_answers(TRIM_P, &roll));
        assert!(query_answers(TRIM_R, &roll) && !query_answers(TRIM_R, &pitch));
        assert!(query_answers(0, &Message::FlapSpec(defaults::flap_spec())));
        assert!(!query_answers(
            0,
            &Message::DeviceSpec(defaults::device_spec(0))
        ));
        assert!(query_answers(
            253,
            &Message::SystemSpec(defaults::system_spec())
        ));
        assert!(query_answers(
            254,
            &Message::WigWagSpec(defaults::wig_wag_spec())
        ));
        assert!(query_answers(
            9,
            &Message::DeviceSpec(defaults::device_spec(9))
        ));
        assert!(!query_answers(
            9,
            &Message::DeviceSpec(defaults::device_spec(8))
        ));
    }
}

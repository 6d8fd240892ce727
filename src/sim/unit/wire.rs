//! The wire side: a received byte stream decoded into requests, each request
//! answered as ICD §6 says, and every byte the unit sends (held back while it is
//! silent).

use std::time::Instant;

use super::{Mode, Start, Unit, motor_index, motor_of_device};
use crate::protocol::config::UnitConfig;
use crate::protocol::decoder::Event;
use crate::protocol::device::{
    FLAPS, STARTER, SYSTEM_FAULT_ID, SYSTEM_SPEC_ID, TRIM_P, TRIM_R, WIG_WAG_SPEC_ID,
};
use crate::protocol::message::{
    DataIntegrityCode, DeviceEnable, DeviceName, DevicePower, DeviceSpec, EepromErase, EnableFlag,
    FlapDirection, FlapSpec, HardwareVersion, Payload, Ping, SpecAck, SpecAckError, SwitchId,
    SystemSpec, TrimDirection, TrimSpec, TrimType, Version, WigWagModeSetting, WigWagSpec,
};
use crate::protocol::{FaultCode, Message, Node, Packet, validate};
use crate::sim::bootloader::Bootloader;
use crate::sim::scenario::{MotorDirection, MotorId};

impl Unit {
    /// Bytes received at `now`.
    pub fn feed(&mut self, bytes: &[u8], now: Instant) {
        self.wire.rx_bytes += bytes.len() as u64;
        if self.in_bootloader() {
            self.feed_bootloader(bytes, now);
            return;
        }
        // One byte at a time (5760 bytes/s at most): a SOFTWARE_UPDATE hands every
        // byte after its last one to the bootloader, even those in the same read.
        for (i, b) in bytes.iter().enumerate() {
            let mut frames: Vec<Vec<u8>> = Vec::new();
            let wire = &mut self.wire;
            self.decoder.push(std::slice::from_ref(b), |e| match e {
                Event::Frame(f) => frames.push(f.as_bytes().to_vec()),
                Event::Skipped(b) | Event::Truncated(b) => wire.garbage_bytes += b.len() as u64,
                Event::BadChecksum(_) | Event::BadLength(_) => {
                    wire.garbage_bytes += 1;
                    wire.bad_frames += 1;
                }
                Event::UnknownMessage(_) => wire.bad_frames += 1,
            });
            for f in &frames {
                self.wire.rx_frames += 1;
                let frame = crate::protocol::FrameRef::parse(f).expect("the decoder checked it");
                let h = frame.header();
                match Packet::parse(&frame) {
                    Ok(p) => self.handle(p, now),
                    // §6.1.2: the VP-X ignores a VERSION request's payload, so one of
                    // any length (too short to decode as Table 11) is still answered;
                    // so is an EEPROM_ERASE request without its byte (§6.1.4).
                    Err(_) if h.id == Version::ID && self.for_us(h.src, h.dst) => {
                        self.version(h.cnt, now)
                    }
                    Err(_) if h.id == EepromErase::ID && self.for_us(h.src, h.dst) => {
                        self.eeprom_erase(h.cnt, now);
                        self.update_power(now);
                    }
                    Err(_) => self.malformed(h, frame.payload(), now),
                }
            }
            if self.in_bootloader() {
                self.feed_bootloader(&bytes[i + 1..], now);
                return;
            }
        }
    }

    fn feed_bootloader(&mut self, bytes: &[u8], now: Instant) {
        let Mode::Boot(b) = &mut self.mode else {
            return;
        };
        let mut out = Vec::new();
        let exit = b.feed(bytes, &mut self.flash, &mut out);
        self.boot_stats = b.stats();
        self.emit_raw(&out, now);
        if exit {
            let programmed = self.boot_stats.pages_programmed > 0;
            self.log(if programmed {
                "bootloader EXIT: rebooting with the Software Update flag set".into()
            } else {
                "bootloader EXIT: nothing was programmed, rebooting".into()
            });
            self.boot(now, Start::BootloaderExit { programmed });
        }
    }

    /// An intact frame whose payload did not decode. A spec still gets its SPEC_ACK
    /// (OutOfRange), so the EFIS learns the unit refused it rather than waiting.
    fn malformed(&mut self, h: crate::protocol::FrameHeader, payload: &[u8], now: Instant) {
        self.wire.malformed += 1;
        let first = payload.first().copied().unwrap_or(0);
        let id = match h.id {
            DeviceSpec::ID | DeviceName::ID => Some(first),
            SystemSpec::ID => Some(SYSTEM_SPEC_ID),
            WigWagSpec::ID => Some(WIG_WAG_SPEC_ID),
            FlapSpec::ID => Some(FLAPS),
            TrimSpec::ID => Some(if first & 0x80 != 0 { TRIM_R } else { TRIM_P }),
            _ => None,
        };
        if let Some(device_id) = id {
            self.reply(
                h.cnt,
                SpecAck {
                    device_id,
                    error: Some(SpecAckError::OutOfRange),
                },
                now,
            );
        }
    }

    /// Whether a frame from `src` to `dst` is a request for this unit.
    fn for_us(&self, src: Node, dst: Node) -> bool {
        matches!(dst, Node::Vpx | Node::Broadcast) && src != Node::Vpx
    }

    /// The VERSION reply (ICD Table 11).
    fn version(&mut self, cnt: u8, now: Instant) {
        let v = Version {
            hardware_version: HardwareVersion::from_byte(self.opts.hardware_version),
            software_major: self.opts.software_version.0,
            software_minor: self.opts.software_version.1,
        };
        self.reply(cnt, v, now)
    }

    /// EEPROM_ERASE, ICD §6.1.4: defaults back, DATA_INTEGRITY until the next reset or
    /// power cycle.
    fn eeprom_erase(&mut self, cnt: u8, now: Instant) {
        let defaults = UnitConfig::default();
        let code = match self.eeprom.store(&defaults) {
            Ok(()) => 0,
            Err(e) => {
                self.log(format!("EEPROM_ERASE: cannot write the EEPROM: {e}"));
                1
            }
        };
        self.config = defaults;
        self.integrity = Some(DataIntegrityCode::GeneralEeprom);
        self.log("EEPROM_ERASE: configuration back to the ICD Appendix F defaults".into());
        self.reply(
            cnt,
            EepromErase {
                response_code: code,
            },
            now,
        );
    }

    fn handle(&mut self, p: Packet, now: Instant) {
        if !self.for_us(p.src, p.dst) {
            self.wire.ignored += 1;
            return;
        }
        let cnt = p.cnt;
        match p.message {
            Message::Ping(Ping { ack: false }) => self.reply(cnt, Ping { ack: true }, now),
            Message::Version(_) => self.version(cnt, now),
            Message::SoftwareUpdate(_) => {
                // §6.1.3: no reply; the unit goes quiet and listens for §7 frames.
                self.log("SOFTWARE_UPDATE: entering the bootloader".into());
                for m in &mut self.motors {
                    m.halt(now);
                }
                self.mode = Mode::Boot(Bootloader::default());
            }
            Message::EepromErase(_) => self.eeprom_erase(cnt, now),
            Message::DeviceSpecQuery(q) => self.spec_query(cnt, q.device_id, now),
            m @ (Message::DeviceSpec(_)
            | Message::SystemSpec(_)
            | Message::TrimSpec(_)
            | Message::FlapSpec(_)
            | Message::WigWagSpec(_)
            | Message::DeviceName(_)) => self.spec(cnt, &m, now),
            Message::DeviceNameQuery(q) => match self.config.names.get(q.device_id as usize) {
                Some(&name) => self.reply(
                    cnt,
                    DeviceName {
                        device_id: q.device_id,
                        name,
                    },
                    now,
                ),
                // Table 22: ids 0–30 only.
                None => self.wire.ignored += 1,
            },
            // Decision (Table 23 notes 1 and 2): a query for a device whose display
            // cannot be set is still answered with what holds: Starter, EFIS and
            // Field_Pri (1–3) are always enabled; the flaps (0) and trims (29, 30)
            // are as their FLAP_SPEC / TRIM_SPEC enable flag says. Setting them is
            // ignored, as the table's range 4–28 says.
            Message::DeviceEnable(DeviceEnable {
                device_id: id @ (0..=3 | TRIM_R | TRIM_P),
                flag: EnableFlag::Query,
            }) => {
                let on = match id {
                    FLAPS => self.config.flap.enabled,
                    TRIM_R => self.config.roll_trim.enabled,
                    TRIM_P => self.config.pitch_trim.enabled,
                    _ => true,
                };
                self.reply_enable(cnt, id, on, now);
            }
            Message::DeviceEnable(e) => {
                if validate::device_enable(&self.config, &e).is_err() {
                    self.wire.ignored += 1;
                } else if e.flag == EnableFlag::Query {
                    let on = self.config.enabled[e.device_id as usize];
                    self.reply_enable(cnt, e.device_id, on, now);
                } else {
                    // Table 23: a set has no answer.
                    let mut cfg = self.config.clone();
                    cfg.apply_device_enable(&e);
                    self.commit(cfg);
                }
            }
            Message::DeviceStatusQuery(_) => {
                let s = self.device_status();
                self.reply(cnt, s, now);
            }
            Message::DevicePower(d) => self.device_power(d, now),
            // Decision: a stop (power 0) is honoured whatever its other bytes hold, so
            // a motor never runs on to the stream timeout because the stop message
            // carried a direction (or, for TRIM_MOVE, a trim type) outside Tables 30
            // and 31. A stop of an unknown trim type stops both trims. A run ("on")
            // with such a byte is refused: the unit cannot know which way to go.
            Message::TrimMove(t) => {
                let motors: &[MotorId] = match t.trim_type {
                    TrimType::Pitch => &[MotorId::Pitch],
                    TrimType::Roll => &[MotorId::Roll],
                    TrimType::Unknown(_) if !t.on => &[MotorId::Pitch, MotorId::Roll],
                    TrimType::Unknown(_) => {
                        self.wire.malformed += 1;
                        return;
                    }
                };
                let dir = match t.direction {
                    TrimDirection::DownOrRight => MotorDirection::Down,
                    TrimDirection::UpOrLeft => MotorDirection::Up,
                    // Not looked at by a stop.
                    TrimDirection::Unknown(_) if !t.on => MotorDirection::Up,
                    TrimDirection::Unknown(_) => {
                        self.wire.malformed += 1;
                        return;
                    }
                };
                if matches!(t.trim_type, TrimType::Unknown(_))
                    || matches!(t.direction, TrimDirection::Unknown(_))
                {
                    self.wire.malformed += 1;
                }
                for &motor in motors {
                    self.stream(motor, t.on, dir, now);
                }
            }
            Message::FlapMove(f) => {
                let dir = match f.direction {
                    FlapDirection::Up => MotorDirection::Up,
                    FlapDirection::Down => MotorDirection::Down,
                    FlapDirection::Unknown(_) if !f.on => {
                        // A stop all the same (see TRIM_MOVE above), counted as odd.
                        self.wire.malformed += 1;
                        MotorDirection::Up
                    }
                    FlapDirection::Unknown(_) => {
                        self.wire.malformed += 1;
                        return;
                    }
                };
                // Decision: the overspeed inhibit (Table 16 "Max Speed") also refuses
                // FLAP_MOVE down, so the page's "inhibited" is never contradicted.
                if f.on && dir == MotorDirection::Down && self.flap_down_inhibited(now) {
                    self.wire.ignored += 1;
                    return;
                }
                self.stream(MotorId::Flap, f.on, dir, now);
            }
            Message::WigWagMode(w) => match w.mode {
                WigWagModeSetting::Unknown(_) => self.wire.malformed += 1,
                m => self.wig_wag_mode = m,
            },
            Message::DeviceClear(c) => self.clear(c.device_id, now),
            Message::ExternalData(d) => self.external = Some((now, d)),
            // Messages only a VP-X sends.
            _ => self.wire.ignored += 1,
        }
        self.update_power(now);
    }

    fn stream(&mut self, motor: MotorId, on: bool, dir: MotorDirection, now: Instant) {
        let g = self.geometry(motor, now);
        if !self.motors[motor_index(motor)].stream(on, dir, &g, now) {
            self.wire.ignored += 1;
        }
    }

    fn spec_query(&mut self, cnt: u8, id: u8, now: Instant) {
        let c = &self.config;
        // icd-reading R13.
        let m: Message = match id {
            FLAPS => c.flap.into(),
            TRIM_R => c.roll_trim.into(),
            TRIM_P => c.pitch_trim.into(),
            1..=28 => c.devices[id as usize].into(),
            SYSTEM_SPEC_ID => c.system.into(),
            WIG_WAG_SPEC_ID => c.wig_wag.into(),
            // Table 18 note 1: invalid ids are ignored.
            _ => {
                self.wire.ignored += 1;
                return;
            }
        };
        self.reply(cnt, m, now);
    }

    /// A *_SPEC or DEVICE_NAME: judged by the shared §6.2 rules, stored if accepted.
    fn spec(&mut self, cnt: u8, m: &Message, now: Instant) {
        let device_id = match m {
            Message::DeviceSpec(s) => s.device_id,
            Message::DeviceName(n) => n.device_id,
            Message::SystemSpec(_) => SYSTEM_SPEC_ID,
            Message::WigWagSpec(_) => WIG_WAG_SPEC_ID,
            Message::FlapSpec(_) => FLAPS,
            // Table 19 gives no id for TRIM_SPEC; the axis's own device id is used.
            Message::TrimSpec(t) if t.trim_type == TrimType::Roll => TRIM_R,
            _ => TRIM_P,
        };
        let mut cfg = self.config.clone();
        let verdict = validate::accept(&mut cfg, m).unwrap_or(Err(SpecAckError::BadConfig));
        let error = match verdict {
            Ok(()) => {
                if self.commit(cfg) {
                    None
                } else {
                    Some(SpecAckError::EepromWrite)
                }
            }
            Err(e) => Some(e),
        };
        if self.drop_spec_acks {
            // The spec above is applied and stored; only its answer is lost.
            self.wire.spec_acks_dropped += 1;
            return;
        }
        self.reply(cnt, SpecAck { device_id, error }, now);
    }

    /// Stores a changed configuration; `false` (and nothing changed) if the EEPROM
    /// could not be written.
    pub(super) fn commit(&mut self, cfg: UnitConfig) -> bool {
        match self.eeprom.store(&cfg) {
            Ok(()) => {
                self.config = cfg;
                true
            }
            Err(e) => {
                self.log(format!("EEPROM write failed: {e}"));
                false
            }
        }
    }

    pub(super) fn device_power(&mut self, d: DevicePower, now: Instant) {
        match d.device_id {
            // Appendix B note 1: the starter cannot be switched from outside; the
            // motors run only by TRIM_MOVE / FLAP_MOVE.
            STARTER | FLAPS | TRIM_R | TRIM_P => self.wire.ignored += 1,
            id @ 2..=28 => {
                if self.faults[id as usize].is_fault() {
                    // Appendix E: a faulted pin stays off until DEVICE_CLEAR.
                    self.wire.ignored += 1;
                } else {
                    self.overrides[id as usize] = Some(d.on);
                }
            }
            _ => self.wire.ignored += 1,
        }
        self.update_power(now);
    }

    /// DEVICE_CLEAR, ICD §6.5.1.
    fn clear(&mut self, id: u8, now: Instant) {
        if id == SYSTEM_FAULT_ID {
            self.system_fault = false;
            return;
        }
        if let Some(m) = motor_of_device(id) {
            let g = self.geometry(m, now);
            let motor = &mut self.motors[motor_index(m)];
            motor.advance(&g, now);
            motor.clear();
            return;
        }
        let Some(slot) = self.faults.get_mut(id as usize) else {
            self.wire.ignored += 1;
            return;
        };
        if !slot.is_fault() {
            return;
        }
        *slot = FaultCode::NoFault;
        // Note 2: the device returns to its switch's state, and every switch-11 device
        // comes back on. Decision: that means their DEVICE_POWER overrides are dropped.
        self.overrides[id as usize] = None;
        for (i, d) in self.config.devices.iter().enumerate() {
            if d.switch_id == SwitchId::AlwaysOn {
                self.overrides[i] = None;
            }
        }
        self.log(format!("device {id} fault cleared by DEVICE_CLEAR"));
        self.update_power(now);
    }

    fn silent(&mut self, now: Instant) -> bool {
        match self.silent_until {
            Some(t) if now < t => true,
            Some(_) => {
                self.silent_until = None;
                self.log("talking again".into());
                false
            }
            None => false,
        }
    }

    pub(super) fn emit_raw(&mut self, bytes: &[u8], now: Instant) {
        if self.silent(now) {
            self.wire.silenced_bytes += bytes.len() as u64;
        } else {
            self.wire.tx_bytes += bytes.len() as u64;
            self.out.extend_from_slice(bytes);
        }
    }

    fn reply(&mut self, cnt: u8, m: impl Into<Message>, now: Instant) {
        self.wire.replies += 1;
        let bytes = Packet::from_vpx(cnt, m).to_bytes();
        self.emit_raw(&bytes, now);
    }

    /// DEVICE_ENABLE's answer to a query (Table 23, flag 2 asked, 0 or 1 told).
    fn reply_enable(&mut self, cnt: u8, device_id: u8, on: bool, now: Instant) {
        let flag = if on {
            EnableFlag::Enabled
        } else {
            EnableFlag::Disabled
        };
        self.reply(cnt, DeviceEnable { device_id, flag }, now);
    }
}

//! Test vectors for every message of ICD Appendix D (plus DEVICE_NAME,
//! DEVICE_NAME_QUERY and DEVICE_ENABLE of §6.2.8–6.2.10), written byte by byte from
//! the ICD tables and checked both ways: the bytes parse to the typed value written
//! out field by field, and the typed value emits exactly those bytes.
//!
//! Every checksum was worked by hand (ICD §4.1.3, icd-reading R2: XOR of every byte
//! before it, both sync bytes included, then NOT) and the working is in the comment
//! above it as `header … = h; payload … = p; h^p = x; !x = checksum`. Nothing here is
//! produced by our encoder, so an encoder and decoder that agree on a wrong reading
//! still fail.
//!
//! Field values are chosen so that a swapped bit, byte or field shows: asymmetric bit
//! patterns, 16-bit values with both bytes non-zero, negative signed values.

// The codec's no-panic lints (Cargo.toml) are for the library. clippy.toml lifts them
// inside #[test] functions, not in the helpers beside them, which index their own
// fixtures here.
#![allow(clippy::indexing_slicing)]

use vpx_protocol::device::DEVICE_COUNT;
use vpx_protocol::message::*;
use vpx_protocol::{Decoder, Error, Event, FaultCode, FrameRef, LenRule, MessageId, Node, Packet};

fn to_vpx(cnt: u8, m: impl Into<Message>) -> Packet {
    Packet {
        cnt,
        src: Node::External,
        dst: Node::Vpx,
        message: m.into(),
    }
}

fn from_vpx(cnt: u8, m: impl Into<Message>) -> Packet {
    Packet {
        cnt,
        src: Node::Vpx,
        dst: Node::External,
        message: m.into(),
    }
}

/// One frame written by hand from its ICD table, and the packet it is.
struct Vector {
    /// Where the bytes come from, e.g. "ICD Table 26".
    table: &'static str,
    /// What the row shows.
    what: &'static str,
    bytes: &'static [u8],
    packet: Packet,
    /// Whether our encoder must give back these very bytes (false where the ICD
    /// allows another spelling on receipt than the one we send).
    emitted: bool,
}

/// A frame that parses to `packet` and that `packet` emits.
fn both(table: &'static str, what: &'static str, bytes: &'static [u8], packet: Packet) -> Vector {
    Vector {
        table,
        what,
        bytes,
        packet,
        emitted: true,
    }
}

/// A frame that parses to `packet`, which we send otherwise.
fn parsed(table: &'static str, what: &'static str, bytes: &'static [u8], packet: Packet) -> Vector {
    Vector {
        emitted: false,
        ..both(table, what, bytes, packet)
    }
}

/// DEVICE_STATUS with devices 1, 2, 9 and 30 on, each with its own current.
fn device_status_value() -> DeviceStatus {
    let mut on = [false; DEVICE_COUNT];
    let mut current = [Tenths(0); DEVICE_COUNT];
    for (id, tenths) in [(1, 5), (2, 23), (9, 258), (30, 17)] {
        on[id] = true;
        current[id] = Tenths(tenths);
    }
    DeviceStatus { on, current }
}

/// DEVICE_NAME's 16 bytes for "Landing Lt" (Table 41), NUL-padded.
fn landing_light() -> [u8; 16] {
    let mut name = [0u8; 16];
    name[..10].copy_from_slice(b"Landing Lt");
    name
}

/// FLAP_TRIM_STATUS of the Table 27 row below.
fn flap_trim_status_value() -> FlapTrimStatus {
    FlapTrimStatus {
        flap: FlapFlags {
            enabled: true,
            motor_running: false,
            fault: false,
            overspeed_alarm: true,
            down_switch_inhibited: false,
        },
        pitch_trim: TrimFlags {
            enabled: true,
            motor_running: true,
            fault: false,
        },
        roll_trim: TrimFlags {
            enabled: true,
            motor_running: false,
            fault: true,
        },
        flap_position: 100,
        pitch_trim_position: 128,
        roll_trim_position: 127,
        flap_fault: FaultCode::NoFault,
        pitch_trim_fault: FaultCode::NoFault,
        roll_trim_fault: FaultCode::TrimRunaway,
        flap_up: 0x14,
        flap_down: 0xDC,
        flap_midpoint_1: 0x50,
        flap_midpoint_2: 0xA0,
        pitch_trim_up: 0xF0,
        pitch_trim_down: 0x0A,
        pitch_trim_neutral: 0x80,
        roll_trim_up: 0xE6,
        roll_trim_down: 0x19,
        roll_trim_neutral: 0x7F,
    }
}

/// FAULT_STATUS with `faulted` devices and their `codes`; the others' codes are
/// `rest`.
fn fault_status_value(
    faulted: &[usize],
    system_fault: bool,
    codes: &[(usize, FaultCode)],
    rest: Option<FaultCode>,
) -> FaultStatus {
    let mut status = FaultStatus {
        faulted: [false; DEVICE_COUNT],
        system_fault,
        codes: [rest; DEVICE_COUNT],
    };
    for &id in faulted {
        status.faulted[id] = true;
    }
    for &(id, code) in codes {
        status.codes[id] = Some(code);
    }
    status
}

/// Every vector, one row each. The comment above a row works its checksum.
fn vectors() -> Vec<Vector> {
    let mut switch_1 = [false; 10];
    switch_1[0] = true;
    vec![
        // ------------------------------------------------------------ §6.1 system
        // header E7^7E^10^00^21^01^00^01 = A8; payload 00; A8^00 = A8; !A8 = 57
        both(
            "ICD Table 10",
            "PING request",
            &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x01, 0x00, 0x01, 0x00, 0x57],
            to_vpx(0x21, Ping { ack: false }),
        ),
        // The reply echoes cnt 0x21 (Table 2 note 1).
        // header E7^7E^10^00^21^00^01^01 = A8; payload 01; A8^01 = A9; !A9 = 56
        both(
            "ICD Table 10",
            "PING response",
            &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x00, 0x01, 0x01, 0x01, 0x56],
            from_vpx(0x21, Ping { ack: true }),
        ),
        // Hardware 2 = VP-X Pro, software 1.3.
        // header E7^7E^10^01^05^00^01^03 = 8F; payload 02^01^03 = 00; 8F^00 = 8F; !8F = 70
        both(
            "ICD Table 11",
            "VERSION response",
            &[
                0xE7, 0x7E, 0x10, 0x01, 0x05, 0x00, 0x01, 0x03, 0x02, 0x01, 0x03, 0x70,
            ],
            from_vpx(
                0x05,
                Version {
                    hardware_version: HardwareVersion::VpxPro,
                    software_major: 1,
                    software_minor: 3,
                },
            ),
        ),
        // header E7^7E^10^02^07^01^00^00 = 8D; no payload; !8D = 72
        both(
            "ICD §6.1.3",
            "SOFTWARE_UPDATE, no payload",
            &[0xE7, 0x7E, 0x10, 0x02, 0x07, 0x01, 0x00, 0x00, 0x72],
            to_vpx(0x07, SoftwareUpdate),
        ),
        // Response code 1 = failure.
        // header E7^7E^10^03^08^00^01^01 = 82; payload 01; 82^01 = 83; !83 = 7C
        both(
            "ICD Table 12",
            "EEPROM_ERASE failure response",
            &[0xE7, 0x7E, 0x10, 0x03, 0x08, 0x00, 0x01, 0x01, 0x01, 0x7C],
            from_vpx(0x08, EepromErase { response_code: 1 }),
        ),
        // ------------------------------------------------------------ §6.2 device
        // Device 9 (5A-6), breaker 5 A, switch 3, current fault checking on.
        // header E7^7E^11^00^30^01^00^04 = BD; payload 09^05^03^01 = 0E; BD^0E = B3; !B3 = 4C
        both(
            "ICD Table 13",
            "DEVICE_SPEC",
            &[
                0xE7, 0x7E, 0x11, 0x00, 0x30, 0x01, 0x00, 0x04, 0x09, 0x05, 0x03, 0x01, 0x4C,
            ],
            to_vpx(
                0x30,
                DeviceSpec {
                    device_id: 9,
                    circuit_breaker: 5,
                    switch_id: SwitchId::Input(3),
                    current_fault: true,
                    switch_raw: None,
                },
            ),
        ),
        // icd-reading R10: note 3 says 255, most of the ICD says 11. Both decode as
        // always-on; we send 11.
        // header E7^7E^11^00^31^01^00^04 = BC; payload 0C^0A^FF^00 = F9; BC^F9 = 45; !45 = BA
        parsed(
            "ICD Table 13 note 3",
            "DEVICE_SPEC switch 255 is always on",
            &[
                0xE7, 0x7E, 0x11, 0x00, 0x31, 0x01, 0x00, 0x04, 0x0C, 0x0A, 0xFF, 0x00, 0xBA,
            ],
            to_vpx(0x31, always_on_spec()),
        ),
        // header as above = BC; payload 0C^0A^0B^00 = 0D; BC^0D = B1; !B1 = 4E
        both(
            "ICD Table 13 note 3",
            "DEVICE_SPEC always on is sent as 11",
            &[
                0xE7, 0x7E, 0x11, 0x00, 0x31, 0x01, 0x00, 0x04, 0x0C, 0x0A, 0x0B, 0x00, 0x4E,
            ],
            to_vpx(0x31, always_on_spec()),
        ),
        // Overvoltage limit 1 = 32 V, secondary alternator on device 12.
        // header E7^7E^11^01^32^01^00^02 = B8; payload 01^0C = 0D; B8^0D = B5; !B5 = 4A
        both(
            "ICD Table 14",
            "SYSTEM_SPEC",
            &[
                0xE7, 0x7E, 0x11, 0x01, 0x32, 0x01, 0x00, 0x02, 0x01, 0x0C, 0x4A,
            ],
            to_vpx(
                0x32,
                SystemSpec {
                    overvoltage_limit: OvervoltageLimit::V32,
                    secondary_alternator: Some(12),
                },
            ),
        ),
        // icd-reading R15, MSB first: type, enable, polarity. Flags 0x60 =
        // 0b0110_0000: pitch, enabled, inverted. Up 200, down 30, neutral 128, power
        // 60 %, speed 300 = 0x012C (both bytes non-zero, so byte order shows).
        // header E7^7E^11^02^33^01^00^07 = BF;
        // payload 60^C8^1E^80^3C^01^2C = 27; BF^27 = 98; !98 = 67
        both(
            "ICD Table 15",
            "TRIM_SPEC",
            &[
                0xE7, 0x7E, 0x11, 0x02, 0x33, 0x01, 0x00, 0x07, 0x60, 0xC8, 0x1E, 0x80, 0x3C, 0x01,
                0x2C, 0x67,
            ],
            to_vpx(
                0x33,
                TrimSpec {
                    trim_type: TrimType::Pitch,
                    enabled: true,
                    polarity: Polarity::Inverted,
                    up: 200,
                    down: 30,
                    neutral: 128,
                    power: 60,
                    speed: 300,
                },
            ),
        ),
        // Flags 0xA0 = 0b1010_0000: position-based, NOT enabled, inverted (the enable
        // bit clear between two set bits pins the order). Up 20, down 220, midpoints
        // 80/160, breaker 7 A, overspeed position 70, max speed 150 = 0x0096, endpoint
        // duration 5 tenths = 0.5 s (icd-reading R23).
        // header E7^7E^11^03^34^01^00^0B = B5;
        // payload A0^14^DC^50^A0^07^46^00^96^00^05 = 4A; B5^4A = FF; !FF = 00
        both(
            "ICD Table 16",
            "FLAP_SPEC",
            &[
                0xE7, 0x7E, 0x11, 0x03, 0x34, 0x01, 0x00, 0x0B, 0xA0, 0x14, 0xDC, 0x50, 0xA0, 0x07,
                0x46, 0x00, 0x96, 0x00, 0x05, 0x00,
            ],
            to_vpx(
                0x34,
                FlapSpec {
                    mode: FlapMode::PositionBased,
                    enabled: false,
                    polarity: Polarity::Inverted,
                    up: 20,
                    down: 220,
                    midpoint_1: 80,
                    midpoint_2: 160,
                    circuit_breaker: 7,
                    overspeed_position: 70,
                    max_speed: 150,
                    endpoint_duration: Tenths(5),
                },
            ),
        ),
        // Device one 20 (10A-4), device two 255 = disabled, warm-up 10 s, speed 80.
        // header E7^7E^11^04^35^01^00^04 = BC; payload 14^FF^0A^50 = B1; BC^B1 = 0D; !0D = F2
        both(
            "ICD Table 17",
            "WIG_WAG_SPEC",
            &[
                0xE7, 0x7E, 0x11, 0x04, 0x35, 0x01, 0x00, 0x04, 0x14, 0xFF, 0x0A, 0x50, 0xF2,
            ],
            to_vpx(
                0x35,
                WigWagSpec {
                    device_one: Some(20),
                    device_two: None,
                    warm_up_period: 10,
                    speed: 80,
                },
            ),
        ),
        // 253 asks for SYSTEM_SPEC.
        // header E7^7E^11^05^36^01^00^01 = BB; payload FD; BB^FD = 46; !46 = B9
        both(
            "ICD Table 18 note 1",
            "DEVICE_SPEC_QUERY for SYSTEM_SPEC",
            &[0xE7, 0x7E, 0x11, 0x05, 0x36, 0x01, 0x00, 0x01, 0xFD, 0xB9],
            to_vpx(0x36, DeviceSpecQuery { device_id: 253 }),
        ),
        // 0x11/0x06 (icd-reading R4): device 9, error 0x04 invalid switch id.
        // header E7^7E^11^06^36^00^01^02 = BB; payload 09^04 = 0D; BB^0D = B6; !B6 = 49
        both(
            "ICD Tables 19, 20",
            "SPEC_ACK with an error",
            &[
                0xE7, 0x7E, 0x11, 0x06, 0x36, 0x00, 0x01, 0x02, 0x09, 0x04, 0x49,
            ],
            from_vpx(
                0x36,
                SpecAck {
                    device_id: 9,
                    error: Some(SpecAckError::InvalidSwitch),
                },
            ),
        ),
        // 0x42 is in no table; it must survive a round trip rather than be guessed at.
        // header E7^7E^11^06^37^00^01^02 = BA; payload 09^42 = 4B; BA^4B = F1; !F1 = 0E
        both(
            "ICD Table 20",
            "SPEC_ACK keeps an unknown error code",
            &[
                0xE7, 0x7E, 0x11, 0x06, 0x37, 0x00, 0x01, 0x02, 0x09, 0x42, 0x0E,
            ],
            from_vpx(
                0x37,
                SpecAck {
                    device_id: 9,
                    error: Some(SpecAckError::Unknown(0x42)),
                },
            ),
        ),
        // Device 12, "Landing Lt" (Table 41) NUL-padded to 16 bytes.
        // "Landing Lt" = 4C 61 6E 64 69 6E 67 20 4C 74.
        // header E7^7E^11^07^38^01^00^11 = A7;
        // payload 0C ^ 4C^61^6E^64^69^6E^67^20^4C^74 ^ 00×6 = 53; A7^53 = F4; !F4 = 0B
        both(
            "ICD Table 21",
            "DEVICE_NAME",
            &[
                0xE7, 0x7E, 0x11, 0x07, 0x38, 0x01, 0x00, 0x11, 0x0C, 0x4C, 0x61, 0x6E, 0x64, 0x69,
                0x6E, 0x67, 0x20, 0x4C, 0x74, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0B,
            ],
            to_vpx(
                0x38,
                DeviceName {
                    device_id: 12,
                    name: landing_light(),
                },
            ),
        ),
        // header E7^7E^11^08^39^01^00^01 = B9; payload 0C; B9^0C = B5; !B5 = 4A
        both(
            "ICD Table 22",
            "DEVICE_NAME_QUERY",
            &[0xE7, 0x7E, 0x11, 0x08, 0x39, 0x01, 0x00, 0x01, 0x0C, 0x4A],
            to_vpx(0x39, DeviceNameQuery { device_id: 12 }),
        ),
        // Flag 2 asks for the current state.
        // header E7^7E^11^09^3A^01^00^02 = B8; payload 0C^02 = 0E; B8^0E = B6; !B6 = 49
        both(
            "ICD Table 23",
            "DEVICE_ENABLE query",
            &[
                0xE7, 0x7E, 0x11, 0x09, 0x3A, 0x01, 0x00, 0x02, 0x0C, 0x02, 0x49,
            ],
            to_vpx(
                0x3A,
                DeviceEnable {
                    device_id: 12,
                    flag: EnableFlag::Query,
                },
            ),
        ),
        // ------------------------------------------------------------ §6.3 status
        // As icd-reading R8 lays it out (12 bytes):
        //   system current 12.3 A      = 123  = 00 7B
        //   main bus volts -1.5 V      = -15  = FF F1 (signed: a sign bug shows as 6552.1 V)
        //   aux battery 12.5 V         = 125  = 00 7D
        //   internal temp 31 °C        =        1F
        //   switches: roll trim down (first byte MSB) + switch 1 (second byte LSB) = 80 01
        //   misc: wig-wag mode steady (bit 6)                                      = 40
        //   faults: data integrity failure (bit 3) + external data missing (bit 0) = 09
        //   data integrity code 3 (device configuration, Table 25)                 = 03
        // header E7^7E^12^00^42^00^01^0C = C4;
        // payload 00^7B^FF^F1^00^7D^1F^80^01^40^09^03 = DC; C4^DC = 18; !18 = E7
        // (the checksum is the sync byte, which a decoder must not trip over).
        both(
            "ICD Table 24",
            "SYSTEM_STATUS",
            &[
                0xE7, 0x7E, 0x12, 0x00, 0x42, 0x00, 0x01, 0x0C, 0x00, 0x7B, 0xFF, 0xF1, 0x00, 0x7D,
                0x1F, 0x80, 0x01, 0x40, 0x09, 0x03, 0xE7,
            ],
            from_vpx(
                0x42,
                SystemStatus {
                    system_current: Tenths(123),
                    main_bus_volts: SignedTenths(-15),
                    aux_battery_volts: Tenths(125),
                    internal_temp: 31,
                    switches: SwitchInputs {
                        roll_trim_down: true,
                        roll_trim_up: false,
                        pitch_trim_down: false,
                        pitch_trim_up: false,
                        flap_down: false,
                        flap_up: false,
                        switch: switch_1,
                    },
                    misc: MiscFlags {
                        starter_annunciator: false,
                        wig_wag_mode: WigWagModeSetting::Steady,
                        software_update: false,
                        wig_wag_active: false,
                    },
                    faults: SystemFaultFlags {
                        current_over_48a: false,
                        current_over_60a: false,
                        warm_reset: false,
                        data_integrity_failure: true,
                        external_data_missing: true,
                    },
                    data_integrity_code: Some(DataIntegrityCode::DeviceConfig),
                },
            ),
        ),
        // With icd-reading R7 (bit i of byte k is device 8k+i):
        //   byte 0: devices 1, 2 → bits 1, 2 = 06;  byte 1: device 9 → bit 1 = 02
        //   byte 2: none = 00;                      byte 3: device 30 → bit 6 = 40
        // Currents, u16 at offset 4 + 2·id:
        //   device 1 = 0.5 A = 00 05, device 2 = 2.3 A = 00 17,
        //   device 9 = 25.8 A = 01 02, device 30 = 1.7 A = 00 11, all others 00 00.
        // header E7^7E^12^01^43^00^01^42 = 8A;
        // payload 06^02^00^40 ^ 05^17^01^02^11 (zeros drop out) = 44; 8A^44 = CE; !CE = 31
        both(
            "ICD Table 26",
            "DEVICE_STATUS",
            &DEVICE_STATUS,
            from_vpx(0x43, device_status_value()),
        ),
        // Addressed to 0xFF (icd-reading R22: broadcasts may use 0x01 or 0xFF).
        //   flap flags: enabled (bit 7) + overspeed alarm (bit 4) = 90
        //   trim flags: pitch enabled (7) + pitch motor running (6) + roll enabled (4) +
        //               roll fault (2) = D4
        //   positions flap 100 = 64, pitch 128 = 80, roll 127 = 7F
        //   faults: flap 00, pitch 00, roll 0E (TRIM_RUNAWAY)
        //   flap up 14, down DC, midpoints 50 A0; pitch up F0 down 0A neutral 80;
        //   roll up E6 down 19 neutral 7F
        // header E7^7E^12^02^44^00^FF^12 = 20;
        // payload 90^D4^64^80^7F^00^00^0E^14^DC^50^A0^F0^0A^80^E6^19^7F = 13; 20^13 = 33;
        // !33 = CC
        both(
            "ICD Table 27",
            "FLAP_TRIM_STATUS broadcast to FF",
            &FLAP_TRIM_STATUS_TO_FF,
            Packet {
                cnt: 0x44,
                src: Node::Vpx,
                dst: Node::Broadcast,
                message: flap_trim_status_value().into(),
            },
        ),
        // With icd-reading R7: device 9 (byte 1 bit 1 = 02) and device 29 (byte 3 bit 5
        // = 20) faulted, plus the system fault in byte 3's MSB: 20|80 = A0.
        // Codes at offset 4 + id: device 9 = 07 SHORT_CIRCUIT, device 29 = 0E TRIM_RUNAWAY.
        // header E7^7E^12^03^45^00^01^23 = EF; payload 00^02^00^A0^07^0E = AB; EF^AB = 44;
        // !44 = BB
        both(
            "ICD Table 28",
            "FAULT_STATUS, all 35 bytes",
            &FAULT_STATUS,
            from_vpx(
                0x45,
                fault_status_value(
                    &[9, 29],
                    true,
                    &[(9, FaultCode::ShortCircuit), (29, FaultCode::TrimRunaway)],
                    Some(FaultCode::NoFault),
                ),
            ),
        ),
        // icd-reading R9: a shorter payload (≥ 4) is accepted; codes it lacks are
        // unknown. 6 bytes: device 0 faulted (byte 0 bit 0), codes for devices 0
        // (0A FLAP_RUNAWAY) and 1 (00) only.
        // header E7^7E^12^03^46^00^01^06 = C9; payload 01^00^00^00^0A^00 = 0B; C9^0B = C2;
        // !C2 = 3D
        both(
            "ICD Table 28",
            "FAULT_STATUS cut short",
            &[
                0xE7, 0x7E, 0x12, 0x03, 0x46, 0x00, 0x01, 0x06, 0x01, 0x00, 0x00, 0x00, 0x0A, 0x00,
                0x3D,
            ],
            from_vpx(
                0x46,
                fault_status_value(
                    &[0],
                    false,
                    &[(0, FaultCode::FlapRunaway), (1, FaultCode::NoFault)],
                    None,
                ),
            ),
        ),
        // icd-reading R6: no payload.
        // header E7^7E^12^04^47^01^00^00 = C9; no payload; !C9 = 36
        both(
            "ICD Appendix D 0x12/0x04",
            "DEVICE_STATUS_QUERY",
            &[0xE7, 0x7E, 0x12, 0x04, 0x47, 0x01, 0x00, 0x00, 0x36],
            to_vpx(0x47, DeviceStatusQuery),
        ),
        // ------------------------------------------------------------ §6.4 power
        // Device 9 on.
        // header E7^7E^13^00^50^01^00^02 = D9; payload 09^01 = 08; D9^08 = D1; !D1 = 2E
        both(
            "ICD Table 29",
            "DEVICE_POWER",
            &[
                0xE7, 0x7E, 0x13, 0x00, 0x50, 0x01, 0x00, 0x02, 0x09, 0x01, 0x2E,
            ],
            to_vpx(
                0x50,
                DevicePower {
                    device_id: 9,
                    on: true,
                },
            ),
        ),
        // Roll (1), on (1), left (1 for roll, note 2).
        // header E7^7E^13^01^51^01^00^03 = D8; payload 01^01^01 = 01; D8^01 = D9; !D9 = 26
        both(
            "ICD Table 30",
            "TRIM_MOVE",
            &[
                0xE7, 0x7E, 0x13, 0x01, 0x51, 0x01, 0x00, 0x03, 0x01, 0x01, 0x01, 0x26,
            ],
            to_vpx(
                0x51,
                TrimMove {
                    trim_type: TrimType::Roll,
                    on: true,
                    direction: TrimDirection::UpOrLeft,
                },
            ),
        ),
        // On (1), down (1).
        // header E7^7E^13^02^52^01^00^02 = D9; payload 01^01 = 00; D9^00 = D9; !D9 = 26
        both(
            "ICD Table 31",
            "FLAP_MOVE",
            &[
                0xE7, 0x7E, 0x13, 0x02, 0x52, 0x01, 0x00, 0x02, 0x01, 0x01, 0x26,
            ],
            to_vpx(
                0x52,
                FlapMove {
                    on: true,
                    direction: FlapDirection::Down,
                },
            ),
        ),
        // 1 = steady.
        // header E7^7E^13^03^53^01^00^01 = DA; payload 01; DA^01 = DB; !DB = 24
        both(
            "ICD Table 32",
            "WIG_WAG_MODE",
            &[0xE7, 0x7E, 0x13, 0x03, 0x53, 0x01, 0x00, 0x01, 0x01, 0x24],
            to_vpx(
                0x53,
                WigWagMode {
                    mode: WigWagModeSetting::Steady,
                },
            ),
        ),
        // ------------------------------------------------------------ §6.5, §6.6
        // Note 1: 255 clears the system fault.
        // header E7^7E^14^00^54^01^00^01 = D9; payload FF; D9^FF = 26; !26 = D9
        both(
            "ICD Table 33 note 1",
            "DEVICE_CLEAR of the system fault",
            &[0xE7, 0x7E, 0x14, 0x00, 0x54, 0x01, 0x00, 0x01, 0xFF, 0xD9],
            to_vpx(0x54, DeviceClear { device_id: 255 }),
        ),
        // IAS 120 = 00 78, GS 115 = 00 73, baro altitude -500 ft = FF FF FE 0C (signed
        // 32-bit), fuel pressure 28 psi = 00 1C, RPM 2400 = 09 60, validity IAS, GS,
        // baro, RPM valid and fuel pressure not: 80|40|20|08 = E8.
        // header E7^7E^15^00^55^01^00^0D = D5;
        // payload 00^78^00^73^FF^FF^FE^0C^00^1C^09^60^E8 = 64; D5^64 = B1; !B1 = 4E
        both(
            "ICD Table 34",
            "EXTERNAL_DATA",
            &[
                0xE7, 0x7E, 0x15, 0x00, 0x55, 0x01, 0x00, 0x0D, 0x00, 0x78, 0x00, 0x73, 0xFF, 0xFF,
                0xFE, 0x0C, 0x00, 0x1C, 0x09, 0x60, 0xE8, 0x4E,
            ],
            to_vpx(
                0x55,
                ExternalData {
                    indicated_airspeed: 120,
                    ground_speed: 115,
                    baro_altitude: -500,
                    fuel_pressure: 28,
                    rpm: 2400,
                    valid: ExternalValidity {
                        indicated_airspeed: true,
                        ground_speed: true,
                        baro_altitude: true,
                        fuel_pressure: false,
                        rpm: true,
                    },
                },
            ),
        ),
    ]
}

/// The DEVICE_SPEC both Table 13 note 3 rows decode to.
fn always_on_spec() -> DeviceSpec {
    DeviceSpec {
        device_id: 12,
        circuit_breaker: 10,
        switch_id: SwitchId::AlwaysOn,
        current_fault: false,
        switch_raw: None,
    }
}

/// The Table 26 row: devices 1, 2, 9 and 30 on. The length is header, payload and
/// checksum, so a slip that would shift every field after it does not compile.
#[rustfmt::skip]
const DEVICE_STATUS: [u8; 8 + 66 + 1] = [
    0xE7, 0x7E, 0x12, 0x01, 0x43, 0x00, 0x01, 0x42,
    0x06, 0x02, 0x00, 0x40,
    0x00, 0x00, // device 0
    0x00, 0x05, // device 1
    0x00, 0x17, // device 2
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 3–8
    0x01, 0x02, // device 9
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 10–14
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 15–19
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 20–24
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 25–29
    0x00, 0x11, // device 30
    0x31,
];

/// The first Table 28 row: devices 9 and 29 and the system faulted.
#[rustfmt::skip]
const FAULT_STATUS: [u8; 8 + 35 + 1] = [
    0xE7, 0x7E, 0x12, 0x03, 0x45, 0x00, 0x01, 0x23,
    0x00, 0x02, 0x00, 0xA0,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // codes 0–8
    0x07, // device 9
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 10–19
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, // 20–28
    0x0E, // device 29
    0x00, // device 30
    0xBB,
];

/// The Table 27 row, kept by name because the decoder test below streams it too.
const FLAP_TRIM_STATUS_TO_FF: [u8; 8 + 18 + 1] = [
    0xE7, 0x7E, 0x12, 0x02, 0x44, 0x00, 0xFF, 0x12, 0x90, 0xD4, 0x64, 0x80, 0x7F, 0x00, 0x00, 0x0E,
    0x14, 0xDC, 0x50, 0xA0, 0xF0, 0x0A, 0x80, 0xE6, 0x19, 0x7F, 0xCC,
];

/// Each row's bytes parse to its packet and, where we send them so, its packet emits
/// them. Every row is tried; the failure lists each broken row by its table.
#[test]
fn every_vector_parses_and_emits_as_its_icd_table_says() {
    let mut broken = Vec::new();
    for v in vectors() {
        let parsed = Packet::parse_bytes(v.bytes);
        if parsed.as_ref() != Ok(&v.packet) {
            broken.push(format!(
                "{} ({}): parsed {parsed:?}, the table says {:?}",
                v.table, v.what, v.packet
            ));
        }
        let emitted = v.packet.to_bytes();
        if v.emitted && emitted != v.bytes {
            broken.push(format!(
                "{} ({}): emitted {emitted:02X?}, the table says {:02X?}",
                v.table, v.what, v.bytes
            ));
        }
    }
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

#[test]
fn device_name_new_pads_the_name_with_nuls() {
    assert_eq!(
        DeviceName::new(12, "Landing Lt"),
        Some(DeviceName {
            device_id: 12,
            name: landing_light(),
        })
    );
}

/// The streaming decoder delivers the Table 27 frame, addressed to 0xFF, as a frame,
/// not as an error.
#[test]
fn the_decoder_delivers_the_flap_trim_status_frame() {
    let mut frames = Vec::new();
    Decoder::new().push(&FLAP_TRIM_STATUS_TO_FF, |e| {
        if let Event::Frame(f) = e {
            frames.push(f.as_bytes().to_vec());
        }
    });
    assert_eq!(frames, vec![FLAP_TRIM_STATUS_TO_FF.to_vec()]);
}

/// What the tests start from: every field 0, every flag clear, no fault or error
/// code; the payloads' lengths from Tables 24, 26 and 27.
#[test]
fn the_status_defaults_are_the_all_zero_payloads() {
    #[track_caller]
    fn zeros<P: Payload + Default + PartialEq + core::fmt::Debug>(len: usize) {
        let zeros = vec![0u8; len];
        assert_eq!(P::parse(&zeros), Ok(P::default()), "{}", P::NAME);
        assert_eq!(P::default().emit().as_slice(), zeros, "{}", P::NAME);
    }
    zeros::<SystemStatus>(12);
    zeros::<DeviceStatus>(66);
    zeros::<FlapTrimStatus>(18);
}

// ---------------------------------------------------------------- errors

/// Appendix D (plus §6.2.8–6.2.10) by hand: id, name, payload length rule. The table
/// sizes are maxima (§6 intro): VERSION's and DEVICE_STATUS_QUERY's request payload is
/// ignored (up to 66 bytes, DEVICE_STATUS's length), EEPROM_ERASE's request may come
/// without its byte, DEVICE_NAME's name may be cut short after its NUL.
const TABLE: &[(u8, u8, &str, LenRule)] = &[
    (0x10, 0x00, "PING", LenRule::Exact(1)),
    (0x10, 0x01, "VERSION", LenRule::Between(0, 66)),
    (0x10, 0x02, "SOFTWARE_UPDATE", LenRule::Exact(0)),
    (0x10, 0x03, "EEPROM_ERASE", LenRule::Between(0, 1)),
    (0x11, 0x00, "DEVICE_SPEC", LenRule::Exact(4)),
    (0x11, 0x01, "SYSTEM_SPEC", LenRule::Exact(2)),
    (0x11, 0x02, "TRIM_SPEC", LenRule::Exact(7)),
    (0x11, 0x03, "FLAP_SPEC", LenRule::Exact(11)),
    (0x11, 0x04, "WIG_WAG_SPEC", LenRule::Exact(4)),
    (0x11, 0x05, "DEVICE_SPEC_QUERY", LenRule::Exact(1)),
    (0x11, 0x06, "SPEC_ACK", LenRule::Exact(2)),
    (0x11, 0x07, "DEVICE_NAME", LenRule::Between(2, 17)),
    (0x11, 0x08, "DEVICE_NAME_QUERY", LenRule::Exact(1)),
    (0x11, 0x09, "DEVICE_ENABLE", LenRule::Exact(2)),
    (0x12, 0x00, "SYSTEM_STATUS", LenRule::Exact(12)),
    (0x12, 0x01, "DEVICE_STATUS", LenRule::Exact(66)),
    (0x12, 0x02, "FLAP_TRIM_STATUS", LenRule::Exact(18)),
    (0x12, 0x03, "FAULT_STATUS", LenRule::Between(4, 35)),
    (0x12, 0x04, "DEVICE_STATUS_QUERY", LenRule::Between(0, 66)),
    (0x13, 0x00, "DEVICE_POWER", LenRule::Exact(2)),
    (0x13, 0x01, "TRIM_MOVE", LenRule::Exact(3)),
    (0x13, 0x02, "FLAP_MOVE", LenRule::Exact(2)),
    (0x13, 0x03, "WIG_WAG_MODE", LenRule::Exact(1)),
    (0x14, 0x00, "DEVICE_CLEAR", LenRule::Exact(1)),
    (0x15, 0x00, "EXTERNAL_DATA", LenRule::Exact(13)),
];

#[test]
fn the_message_table_matches_the_icd() {
    assert_eq!(ALL_IDS.len(), TABLE.len());
    for &(major, minor, name, rule) in TABLE {
        assert_eq!(
            lookup(MessageId::new(major, minor)),
            Some((name, rule)),
            "{name}"
        );
    }
}

#[test]
fn wrong_payload_length_names_the_message() {
    for &(major, minor, name, rule) in TABLE {
        let (too_short, too_long) = match rule {
            LenRule::Exact(n) => (n.checked_sub(1), n + 1),
            LenRule::Between(lo, hi) => (lo.checked_sub(1), hi + 1),
        };
        for got in too_short.into_iter().chain([too_long]) {
            // Non-zero filler, so a parser that read past a short payload would not
            // happen to see valid flags.
            let payload = vec![0x5A; got];
            assert_eq!(
                Message::parse(MessageId::new(major, minor), &payload),
                Err(Error::BadLength {
                    message: name,
                    expected: rule,
                    got
                }),
                "{name} with {got} bytes"
            );
        }
    }
}

/// Whole frames, each written by hand, and the error each must give: the table they
/// break, what is wrong, the bytes, the error.
#[test]
fn broken_frames_are_refused_with_the_error_that_names_the_fault() {
    let rows: [(&str, &str, &[u8], Error); 5] = [
        // A good checksum on a payload that cannot be DEVICE_STATUS.
        // header E7^7E^12^01^43^00^01^02 = CA; payload 06^02 = 04; CA^04 = CE; !CE = 31
        (
            "ICD Table 26",
            "DEVICE_STATUS with a 2-byte payload",
            &[
                0xE7, 0x7E, 0x12, 0x01, 0x43, 0x00, 0x01, 0x02, 0x06, 0x02, 0x31,
            ],
            Error::BadLength {
                message: "DEVICE_STATUS",
                expected: LenRule::Exact(66),
                got: 2,
            },
        ),
        // The PING request of Table 10 with its checksum 57 changed to 58.
        (
            "ICD §4.1.3",
            "PING with a wrong checksum",
            &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x01, 0x00, 0x01, 0x00, 0x58],
            Error::BadChecksum {
                computed: 0x57,
                found: 0x58,
            },
        ),
        // The same with one payload bit flipped: payload 01 instead of 00.
        (
            "ICD §4.1.3",
            "PING with a flipped payload bit",
            &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x01, 0x00, 0x01, 0x01, 0x57],
            Error::BadChecksum {
                computed: 0x56,
                found: 0x57,
            },
        ),
        // Ack 2, outside the range 0–1: a field error, not a guess.
        // header E7^7E^10^00^21^00^01^01 = A8; payload 02; A8^02 = AA; !AA = 55
        (
            "ICD Table 10",
            "PING with ack 2",
            &[0xE7, 0x7E, 0x10, 0x00, 0x21, 0x00, 0x01, 0x01, 0x02, 0x55],
            Error::FieldRange {
                message: "PING",
                field: "ACK flag",
                value: 2,
            },
        ),
        // 0x16/0x00 is in no table.
        // E7^7E = 99; ^16 = 8F; ^00 = 8F; ^01 = 8E; ^00 = 8E; ^01 = 8F; ^00 = 8F; !8F = 70
        (
            "ICD Appendix D",
            "unknown message 0x16/0x00",
            &[0xE7, 0x7E, 0x16, 0x00, 0x01, 0x00, 0x01, 0x00, 0x70],
            Error::UnknownMessage(MessageId::new(0x16, 0x00)),
        ),
    ];
    for (table, what, bytes, error) in rows {
        assert_eq!(Packet::parse_bytes(bytes), Err(error), "{table} ({what})");
    }
}

// ---------------------------------------------------------------- leniency on receipt

/// A frame written by hand from ICD Table 1 and §4.1.3 (XOR of every byte, inverted).
fn hand_frame(major: u8, minor: u8, cnt: u8, src: u8, dst: u8, payload: &[u8]) -> Vec<u8> {
    let mut f = vec![0xE7, 0x7E, major, minor, cnt, src, dst, payload.len() as u8];
    f.extend_from_slice(payload);
    let x = f.iter().fold(0u8, |a, b| a ^ b);
    f.push(!x);
    f
}

#[test]
fn short_device_names_and_odd_request_payloads_are_taken() {
    // DEVICE_NAME for device 9, "Taxi" and its NUL: 6 bytes, not Table 21's 17.
    let f = hand_frame(
        0x11,
        0x07,
        4,
        0x00,
        0x01,
        &[0x09, b'T', b'a', b'x', b'i', 0x00],
    );
    // E7^7E^11^07^04^00^01^06 = 8C; ^09^54^61^78^69^00 = A1; !A1 = 5E.
    assert_eq!(*f.last().unwrap(), 0x5E, "checksum worked by hand");
    let p = Packet::parse(&FrameRef::parse(&f).unwrap()).unwrap();
    let Message::DeviceName(n) = p.message else {
        panic!("{p:?}")
    };
    assert_eq!((n.device_id, n.text()), (9, "Taxi".to_string()));
    // An id alone is not a name.
    assert!(Message::parse(MessageId::new(0x11, 0x07), &[0x09]).is_err());
    // DEVICE_STATUS_QUERY with a stray byte is still the query.
    assert_eq!(
        Message::parse(MessageId::new(0x12, 0x04), &[0x00]),
        Ok(Message::DeviceStatusQuery(DeviceStatusQuery))
    );
    // VERSION with 4 bytes: the first three are Table 11's.
    assert_eq!(
        Message::parse(MessageId::new(0x10, 0x01), &[2, 2, 1, 9]),
        Ok(Message::Version(Version {
            hardware_version: HardwareVersion::from_byte(2),
            software_major: 2,
            software_minor: 1
        }))
    );
    // VERSION and EEPROM_ERASE with no payload are frames (the unit answers them),
    // but carry no version and no result code: neither is made up.
    for (minor, name) in [(0x01, "VERSION"), (0x03, "EEPROM_ERASE")] {
        let f = hand_frame(0x10, minor, 7, 0x01, 0x00, &[]);
        let frame = FrameRef::parse(&f).expect("a frame the decoder passes");
        assert!(
            matches!(Packet::parse(&frame), Err(Error::BadLength { message, .. }) if message == name),
            "{name}"
        );
    }
}

#[test]
fn ignored_payloads_stay_within_the_longest_message() {
    assert_eq!(vpx_protocol::message::IGNORED_PAYLOAD_MAX, MAX_MESSAGE_LEN);
}

//! How long each of the unit's broadcasts stays current: the ICD's rates and our
//! reading of them. The model judges its facts by these ([`crate::model`] decides what
//! is stale), and the traffic log judges each message's rate by the same numbers, so
//! both stand on this leaf without one standing on the other.

use std::time::Duration;

/// SYSTEM_STATUS and DEVICE_STATUS silent this long means communication is lost
/// (more than 2.5 s: both are 1 Hz broadcasts, so two missed in a row).
pub const COMM_LOST_AFTER: Duration = Duration::from_millis(2500);
/// A 1 Hz broadcast older than this is no longer shown.
pub const STATUS_STALE_AFTER: Duration = COMM_LOST_AFTER;
/// FLAP_TRIM_STATUS is 10 Hz; a second without it means positions are no longer live.
pub const FLAP_TRIM_STALE_AFTER: Duration = Duration::from_millis(1000);
/// icd-reading R9: FAULT_STATUS is sent only while a fault exists, so status arriving
/// without it for this long means "no faults", not lost communication.
pub const FAULT_STATUS_QUIET_AFTER: Duration = Duration::from_millis(2500);
/// FAULT_STATUS's period while a fault exists (ICD Table 6 and §6.3.4: 1 Hz).
pub const FAULT_STATUS_PERIOD: Duration = Duration::from_secs(1);
/// How late a FAULT_STATUS may come after its period before it counts as not coming
/// (after a reset, the sign that the fault is gone: §6.3.4 sends it only while a fault
/// exists). Decision, the ICD being silent on jitter: half a period. A whole second of
/// the unit's broadcasts (SYSTEM_STATUS 21 bytes, DEVICE_STATUS 75, FAULT_STATUS 44,
/// ten FLAP_TRIM_STATUS of 27) is 410 bytes, about 70 ms of a 57600-baud line; a
/// USB-serial adapter's latency timer (16 ms by default) and a serial-to-network
/// bridge add tens of milliseconds more. A broadcast 500 ms late is missing, not late;
/// a wait much longer would keep a cleared fault on screen with the reset unanswered.
pub const FAULT_STATUS_MARGIN: Duration = Duration::from_millis(500);

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

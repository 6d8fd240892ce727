//! Which way a frame crossed the wire. Plain data, here at the floor, because the
//! link that moves bytes, the capture file, the traffic log and the traffic view
//! all speak of it and none of them should have to import another for it.

/// Which way a frame crossed the serial line, as the EFIS sees it (ICD Table 1, bytes 6 and
/// 7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Crossing {
    /// From the unit to us.
    Rx,
    /// From us to the unit.
    Tx,
}

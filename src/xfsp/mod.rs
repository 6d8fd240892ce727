//! The VP-X on the XFSp avionics network: what the page publishes, what it takes in,
//! and the sockets that carry it. The wire codec itself is the `xfsp` crate
//! (`crates/xfsp`), re-exported here so the rest of the program names one `xfsp`.
//!
//! - [`net`]: the multicast and unicast sockets;
//! - [`publish`]: the model as XFSp parameters; [`scale`]: our units on the wire;
//! - [`consume`]: air data in, as EXTERNAL_DATA; [`drive`]: requests that run motors;
//! - [`gateway`]: the loop that ties them together.

pub mod consume;
pub mod drive;
pub mod gateway;
pub mod net;
pub mod publish;
pub mod scale;

pub use ::xfsp::{
    BUS_SCALE, Body, Boolean, Bus, CasFlags, CasLevel, CasMsg, CertLevel, Confidence, EcbFlags,
    EcbState, Error, Expire, FormatId, HEADER_LEN, Header, Ident, IdentInfo, LengthRule,
    MAX_PARAM_BYTES_V4, MAX_PARAM_BYTES_V6, Message, MessageView, MsgClass, MsgKind, MsgOp,
    ParamHeader, ParamView, Parameter, Received, Receiver, RxStats, Sender, Tcid, Units, Value,
    Verdict, dict, error, expire, format, header, idents, message, param, receiver, sender,
    serial_newer,
};

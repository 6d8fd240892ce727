#![doc = include_str!("../README.md")]

mod cursor;
pub mod dict;
pub mod error;
pub mod expire;
pub mod format;
pub mod header;
pub mod idents;
pub mod message;
pub mod param;
pub mod receiver;
pub mod sender;

pub use dict::{
    Boolean, CasFlags, CasLevel, CertLevel, Confidence, EcbFlags, EcbState, MsgClass, MsgOp, Tcid,
    Units,
};
pub use error::{Error, LengthRule};
pub use expire::Expire;
pub use format::{BUS_SCALE, Bus, CasMsg, FormatId, Value};
pub use header::{HEADER_LEN, Header};
pub use idents::{Ident, IdentInfo};
pub use message::{Body, Message, MessageView};
pub use param::{ParamHeader, ParamView, Parameter};
pub use receiver::{Received, Receiver, RxStats, Verdict, serial_newer};
pub use sender::{MAX_PARAM_BYTES_V4, MAX_PARAM_BYTES_V6, MsgKind, Sender};

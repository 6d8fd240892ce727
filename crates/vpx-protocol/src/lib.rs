#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

pub mod bootloader;
pub mod config;
pub mod decoder;
pub mod defaults;
pub mod describe;
pub mod device;
pub mod direction;
/// Errors of frames and payloads.
pub mod error;
pub mod fault;
pub mod frame;
pub mod message;
pub mod names;
pub mod validate;

pub use decoder::{Decoder, DecoderStats, Event};
pub use direction::Direction;
pub use error::{Error, LenRule, Result};
pub use fault::FaultCode;
pub use frame::{FrameHeader, FrameRef, MessageId, Node, checksum};
pub use message::{Message, Packet, Payload};

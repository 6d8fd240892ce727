//! The VP-X wire format (ICD v2.1) and nothing else: frames, checksum, the streaming
//! decoder, typed messages, the device table, fault codes, defaults and the §6.2
//! configuration rules. Pure and free of I/O, so everything else can trust it.
//!
//! Modelled on smoltcp's `wire` module: one typed representation per message with a
//! `parse` that never panics and an [`Error`] that says what was wrong.
//!
//! Where the ICD contradicts itself we follow `READING-NOTES.md`; each place says so.

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

#![doc = include_str!("../README.md")]
#![cfg_attr(not(any(feature = "std", test)), no_std)]

// The crate uses only `core` and `alloc` (strings, vectors), with or without `std`.
extern crate alloc;

pub mod bootloader;
pub mod config;
pub mod crossing;
pub mod decoder;
pub mod defaults;
pub mod describe;
pub mod device;
/// Errors of frames and payloads.
pub mod error;
pub mod fault;
pub mod frame;
pub mod message;
pub mod names;
pub mod validate;

pub use crossing::Crossing;
pub use decoder::{Decoder, DecoderStats, Event};
pub use error::{Error, LenRule, Result};
pub use fault::FaultCode;
pub use frame::{FrameHeader, FrameRef, MessageId, Node, checksum};
pub use message::{Message, Packet, Payload};

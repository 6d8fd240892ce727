//! Shared by the integration tests that include it (`mod common;`): each test crate
//! uses some of it.
#![allow(dead_code)]

pub mod app;
pub mod configured;
pub mod cpu;
pub mod live_unit;
pub mod phone;
pub mod process;
#[cfg(unix)]
pub mod rig;
pub mod screen;
pub mod xfsp_peer;

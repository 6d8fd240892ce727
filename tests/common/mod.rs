//! Shared by the integration tests that include it (`mod common;`): each test crate
//! uses some of it.
#![allow(dead_code)]

pub mod cpu;
pub mod live_unit;
pub mod phone;
pub mod process;
pub mod sim_process;
pub mod xfsp_peer;

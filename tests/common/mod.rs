//! Shared by the integration tests that include it (`mod common;`): each test crate
//! uses some of it.
#![allow(dead_code)]

pub mod app;
pub mod check_view;
pub mod configured;
pub mod cpu;
pub mod events;
pub mod files;
pub mod live_unit;
pub mod phone;
pub mod process;
pub mod report;
#[cfg(unix)]
pub mod rig;
pub mod screen;
pub mod xfsp_peer;

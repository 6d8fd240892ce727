//! Firmware update through the VP-X bootloader (ICD §6.1.3, §7): the Intel HEX image
//! ([`hex`]), the §7.2 hardware check ([`hardware`]) and the update itself
//! ([`updater`]), after the check that the image can be a whole program ([`whole`]).
//! The command line and its log live in `cmd::flash`.

pub mod hardware;
pub mod hex;
pub mod updater;
pub mod whole;

pub use hardware::{check_hardware, file_hardware};
pub use hex::{Image, load_hex, parse_hex};
pub use updater::{
    Event, Found, Left, Options, Port, Progress, UpdateError, UpdateReport, detect, update,
};
pub use whole::Coverage;

//! The unit's side for the tests that run motors on a fake clock: the broadcasts that
//! keep the model live (nothing on, nothing faulted, 13.8 V).

use vpx_efis::protocol::device::DEVICE_COUNT;
use vpx_efis::protocol::message::{
    DeviceStatus, MiscFlags, Packet, SignedTenths, SystemStatus, Tenths, WigWagModeSetting,
};

pub fn system_status() -> Packet {
    Packet::from_vpx(
        0,
        SystemStatus {
            system_current: Tenths(100),
            main_bus_volts: SignedTenths(138),
            aux_battery_volts: Tenths(0),
            internal_temp: 30,
            switches: Default::default(),
            misc: MiscFlags {
                starter_annunciator: false,
                wig_wag_mode: WigWagModeSetting::Auto,
                software_update: false,
                wig_wag_active: false,
            },
            faults: Default::default(),
            data_integrity_code: None,
        },
    )
}

pub fn device_status() -> Packet {
    Packet::from_vpx(
        0,
        DeviceStatus {
            on: [false; DEVICE_COUNT],
            current: [Tenths(0); DEVICE_COUNT],
        },
    )
}

//! Fault messages, ICD §6.5 (major 0x14).

device_id_message! {
    /// DEVICE_CLEAR — ICD Table 33. Device 255 clears the system fault.
    DeviceClear = 0x14 / 0x00 "DEVICE_CLEAR" {
        /// Table 33 byte 1: the faulted device, 0–30, or 255 for the system fault.
        device_id
    }
}

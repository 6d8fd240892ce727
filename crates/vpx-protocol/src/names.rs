//! Pre-defined pin names, ICD Appendix C (Table 41), read down each column.

/// ICD Table 41, the pre-defined pin names an EFIS may offer, read down each column.
pub const PIN_NAMES: &[&str] = &[
    "EFIS 1",
    "EFIS 2",
    "EFIS 3",
    "PFD",
    "PFD 1",
    "PFD 2",
    "MFD",
    "Backup AI",
    "HSI",
    "CDI",
    "CO Detect",
    "Autopilot",
    "Audio",
    "Audio Panel",
    "Comm 1",
    "Comm 2",
    "Nav 1",
    "Nav 2",
    "Comm/Nav 1",
    "Comm/Nav 2",
    "GPS 1",
    "GPS 2",
    "Transponder",
    "AHRS",
    "Weather",
    "ADC",
    "429 Conv",
    "EIS",
    "Eng Mon",
    "AOA",
    "Intercom",
    "Ethernet",
    "Annunciator",
    "Strobe Lt",
    "Nav Lt",
    "Beacon",
    "Landing Lt",
    "Taxi Light",
    "Cabin Lt",
    "Baggage Lt",
    "Map Lt",
    "Wing Tim R",
    "Wing Tip R",
    "Headset",
    "Headset 2",
    "Glow Strip",
    "Panel Lt",
    "Alternator",
    "Alternator 1",
    "Alternator 2",
    "Main Alt",
    "Standby Alt",
    "De-Ice",
    "Brake",
    "Canopy",
    "Ignition L",
    "Ignition R",
    "Warning",
    "Gear",
    "Flaps",
    "Trim",
    "Seat Heat 1",
    "Seat Heat 2",
    "Defrost",
    "Fan",
    "Fan 1",
    "Fan 2",
    "Fan 3",
    "Misc 1",
    "Misc 2",
    "Misc 3",
    "Aux 1",
    "Aux 2",
    "Aux 3",
    "Smoke",
    "Starter",
    "Boost",
    "Boost L",
    "Boost H",
    "Boost Pump",
    "Pitot",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_41_has_every_name_and_each_fits_device_name() {
        // 33 + 25 + 23 entries in the three columns of Table 41.
        assert_eq!(PIN_NAMES.len(), 81);
        assert!(PIN_NAMES.iter().all(|n| n.is_ascii() && n.len() <= 16));
        assert!(
            PIN_NAMES.contains(&"Wing Tim R"),
            "the ICD's own spelling is kept"
        );
    }
}

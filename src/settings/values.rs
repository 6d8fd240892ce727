//! Every value a person sets (a flag, an environment variable, a line of the config
//! file) is read here, the same way whatever it came from, and refused in words before
//! anything is opened.

use std::net::Ipv4Addr;

use crate::link::PortAddr;

/// The rates a USB-serial adapter and the VP-X side of a bridge can be set to. Anything
/// else is a typo: `--baud 0` would leave a real adapter at B0, which hangs the line up
/// (drops DTR), and an odd rate is at best rounded by the driver.
pub const STANDARD_BAUD_RATES: [u32; 11] = [
    1200, 2400, 4800, 9600, 19_200, 38_400, 57_600, 115_200, 230_400, 460_800, 921_600,
];

/// The rate the VP-X talks (ICD §3.2.1).
pub const VPX_BAUD: u32 = 57_600;

/// A baud rate: a standard one, or a refusal that names them.
pub fn baud(text: &str) -> Result<u32, String> {
    let list = STANDARD_BAUD_RATES.map(|b| b.to_string()).join(", ");
    match text.trim().parse::<u32>() {
        Ok(b) if STANDARD_BAUD_RATES.contains(&b) => Ok(b),
        Ok(0) => Err(format!(
            "0 is not a baud rate (it would hang up a real adapter); the VP-X talks {VPX_BAUD}. \
             Standard rates: {list}"
        )),
        Ok(b) => Err(format!(
            "{b} is not a standard baud rate; the VP-X talks {VPX_BAUD}. Standard rates: {list}"
        )),
        Err(_) => Err(format!(
            "{text:?} is not a number; the VP-X talks {VPX_BAUD}. Standard rates: {list}"
        )),
    }
}

/// A port: a serial path, or `tcp://HOST:PORT`.
pub fn port(text: &str) -> Result<PortAddr, String> {
    text.parse()
}

/// An XFSp source id, decimal (22096) or hex (0x5650), 16 bits.
pub fn source_id(text: &str) -> Result<u16, String> {
    let t = text.trim();
    let parsed = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
        Some(hex) => u16::from_str_radix(hex, 16),
        None => t.parse::<u16>(),
    };
    parsed.map_err(|_| {
        format!("{text:?} is not a 16-bit source id: write it in hex (0x5650) or decimal (0–65535)")
    })
}

/// A list of XFSp source ids, comma-separated ("0x1234,0x5678" or "4660"), for
/// `--xfsp-control-from`. An empty list or an empty item is refused: a list that
/// allows nobody is a typo, not a setting.
pub fn source_ids(text: &str) -> Result<SourceIds, String> {
    if text.trim().is_empty() {
        return Err("an empty list of source ids: name at least one (0x1234,0x5678)".into());
    }
    let mut ids = Vec::new();
    for (i, item) in text.split(',').enumerate() {
        if item.trim().is_empty() {
            return Err(format!(
                "{text:?}: item {} is empty; write source ids separated by commas (0x1234,0x5678)",
                i + 1
            ));
        }
        let id = source_id(item).map_err(|why| format!("in {text:?}: {why}"))?;
        if !ids.contains(&id) {
            ids.push(id);
        }
    }
    Ok(SourceIds(ids))
}

/// Source ids as `--xfsp-control-from` takes them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceIds(pub Vec<u16>);

impl std::fmt::Display for SourceIds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&crate::xfsp::gateway::source_list(&self.0))
    }
}

/// Yes or no, as the config file and the environment write it.
pub fn yes_no(text: &str) -> Result<bool, String> {
    match text.trim().to_ascii_lowercase().as_str() {
        "true" | "yes" | "on" | "1" => Ok(true),
        "false" | "no" | "off" | "0" => Ok(false),
        _ => Err(format!("{text:?} is neither true nor false")),
    }
}

/// The interface address to join the XFSp group on.
pub fn iface(text: &str) -> Result<Ipv4Addr, String> {
    text.trim().parse().map_err(|_| {
        format!(
            "{text:?} is not an IPv4 address: give the address of this machine's interface on \
             the avionics network (e.g. 192.168.1.20), or 0.0.0.0 for the system's choice"
        )
    })
}

/// An XFSp `GROUP:PORT`.
pub fn xfsp_target(text: &str) -> Result<String, String> {
    crate::xfsp::net::Target::parse(text)?;
    Ok(text.trim().to_string())
}

/// The page's colours, as `--theme` asks for them; [`crate::ui::palette`] decides the
/// palette from this and the terminal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Theme {
    /// Light or dark, from the terminal's background (mono under NO_COLOR).
    #[default]
    Auto,
    Dark,
    Light,
    /// No colour: meaning in words and marks alone.
    Mono,
    /// The terminal's own sixteen colours.
    Terminal,
}

/// Each theme and its word, as `--theme` spells it.
pub const THEMES: [(&str, Theme); 5] = [
    ("auto", Theme::Auto),
    ("dark", Theme::Dark),
    ("light", Theme::Light),
    ("mono", Theme::Mono),
    ("terminal", Theme::Terminal),
];

pub fn theme_word(t: Theme) -> &'static str {
    THEMES
        .iter()
        .find(|(_, th)| *th == t)
        .map_or("auto", |(w, _)| w)
}

pub fn theme(text: &str) -> Result<Theme, String> {
    THEMES
        .iter()
        .find(|(w, _)| *w == text.trim())
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            format!(
                "{text:?} is not a theme: {}",
                THEMES.map(|(w, _)| w).join(", ")
            )
        })
}

/// The range `--repeat-delay` accepts, in milliseconds. Below 300 ms no desktop
/// repeats (and a real first repeat would be taken for a fresh press); above 1.5 s a
/// tap would run a motor for longer than anyone means to nudge it.
pub const REPEAT_DELAY_MS: (u64, u64) = (300, 1500);

/// A key repeat delay in milliseconds.
pub fn repeat_delay_ms(text: &str) -> Result<u64, String> {
    let (lo, hi) = REPEAT_DELAY_MS;
    match text.trim().parse::<u64>() {
        Ok(ms) if (lo..=hi).contains(&ms) => Ok(ms),
        _ => Err(format!(
            "{text:?} is not a repeat delay: milliseconds, {lo}–{hi}"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_standard_baud_rates_pass_and_zero_says_why() {
        assert_eq!(baud("57600"), Ok(57_600));
        assert_eq!(baud("115200"), Ok(115_200));
        assert_eq!(baud("9600"), Ok(9600));
        let zero = baud("0").unwrap_err();
        assert!(zero.contains("hang up"), "{zero}");
        assert!(zero.contains("57600"), "{zero}");
        let odd = baud("57601").unwrap_err();
        assert!(odd.contains("not a standard baud rate"), "{odd}");
        assert!(odd.contains("1200, 2400"), "{odd}");
        assert!(baud("fast").unwrap_err().contains("not a number"));
        assert!(baud("-9600").is_err());
    }

    #[test]
    fn source_ids_read_hex_and_decimal_within_16_bits() {
        assert_eq!(source_id("0x5651"), Ok(0x5651));
        assert_eq!(source_id("0X5651"), Ok(0x5651));
        assert_eq!(source_id("22096"), Ok(22096));
        assert_eq!(source_id("0xFFFF"), Ok(0xFFFF));
        assert!(source_id("0x10000").unwrap_err().contains("16-bit"));
        assert!(source_id("65536").is_err());
        assert!(source_id("0x").is_err());
        assert!(source_id("5651h").is_err());
    }

    #[test]
    fn source_id_lists_are_read_whole_or_refused_in_words() {
        assert_eq!(source_ids("0x1234"), Ok(SourceIds(vec![0x1234])));
        assert_eq!(
            source_ids(" 0x1234, 22096 ,0x1234"),
            Ok(SourceIds(vec![0x1234, 22096])),
            "spaces are trimmed and a repeat is kept once"
        );
        assert_eq!(SourceIds(vec![0x1234, 7]).to_string(), "0x1234, 0x0007");
        assert!(source_ids("").unwrap_err().contains("empty list"));
        assert!(source_ids("  ").unwrap_err().contains("empty list"));
        let gap = source_ids("0x1234,,0x5678").unwrap_err();
        assert!(gap.contains("item 2 is empty"), "{gap}");
        assert!(
            source_ids("0x1234,")
                .unwrap_err()
                .contains("item 2 is empty")
        );
        let bad = source_ids("0x1234,zz").unwrap_err();
        assert!(bad.contains("\"zz\" is not a 16-bit source id"), "{bad}");
        assert!(
            source_ids("0x1234;0x5678").is_err(),
            "semicolons are no separator"
        );
        assert!(source_ids("0x10000").unwrap_err().contains("16-bit"));
    }

    #[test]
    fn yes_and_no() {
        for t in ["true", "TRUE", "yes", "on", "1"] {
            assert_eq!(yes_no(t), Ok(true), "{t}");
        }
        for t in ["false", "no", "off", "0"] {
            assert_eq!(yes_no(t), Ok(false), "{t}");
        }
        assert!(
            yes_no("maybe")
                .unwrap_err()
                .contains("neither true nor false")
        );
        assert!(yes_no("").is_err());
    }

    #[test]
    fn interfaces_are_ipv4_addresses() {
        assert_eq!(iface("192.168.1.20"), Ok(Ipv4Addr::new(192, 168, 1, 20)));
        assert_eq!(iface("0.0.0.0"), Ok(Ipv4Addr::UNSPECIFIED));
        assert!(iface("eth0").unwrap_err().contains("not an IPv4 address"));
        assert!(iface("192.168.1.256").is_err());
    }

    #[test]
    fn themes_and_repeat_delays() {
        assert_eq!(theme("light"), Ok(Theme::Light));
        assert_eq!(theme("terminal"), Ok(Theme::Terminal));
        assert_eq!(theme_word(Theme::Mono), "mono");
        assert!(
            theme("blue")
                .unwrap_err()
                .contains("auto, dark, light, mono, terminal")
        );
        assert_eq!(repeat_delay_ms("500"), Ok(500));
        assert_eq!(repeat_delay_ms("300"), Ok(300));
        assert_eq!(repeat_delay_ms("1500"), Ok(1500));
        assert!(repeat_delay_ms("299").is_err());
        assert!(repeat_delay_ms("1501").unwrap_err().contains("300–1500"));
    }
}

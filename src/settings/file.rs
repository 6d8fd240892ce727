//! The config file: TOML, one `key = value` a line, every key optional.
//!
//! ```toml
//! port = "/dev/ttyUSB0"          # or "tcp://192.168.4.1:8880"
//! baud = 57600
//! theme = "auto"                 # auto, dark, light, mono or terminal
//! repeat_delay = 500             # ms, the terminal's first key auto-repeat
//! xfsp = "224.0.2.69:20234"      # the XFSp group for --xfsp and `gateway`
//! xfsp_iface = "192.168.1.20"
//! xfsp_source_id = 0x5651        # hex or decimal
//! xfsp_cert = 0
//! xfsp_control = false           # true: take commands from the network
//! xfsp_control_from = "0x1234,0x5678"  # only from these sources (needs xfsp_control)
//! ```
//!
//! Every problem is reported with its line, so a person can go straight to it. Values
//! are read by the same functions as the flags ([`super::values`]).

use std::net::Ipv4Addr;

use crate::toml_lines::{self, Value};
use serde::Deserialize;

use super::values::{self, Theme};
use crate::link::PortAddr;

/// A value from the file and the line it is on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Setting<T> {
    pub value: T,
    pub line: usize,
}

/// What the file sets; a key it does not mention is `None`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SettingsFile {
    pub port: Option<Setting<PortAddr>>,
    pub baud: Option<Setting<u32>>,
    pub theme: Option<Setting<Theme>>,
    pub repeat_delay_ms: Option<Setting<u64>>,
    pub xfsp: Option<Setting<String>>,
    pub xfsp_iface: Option<Setting<Ipv4Addr>>,
    pub xfsp_source_id: Option<Setting<u16>>,
    pub xfsp_cert: Option<Setting<u8>>,
    pub xfsp_control: Option<Setting<bool>>,
    pub xfsp_control_from: Option<Setting<values::SourceIds>>,
}

/// The keys the file may hold, for the message that refuses any other.
pub const KEYS: [&str; 10] = [
    "port",
    "baud",
    "theme",
    "repeat_delay",
    "xfsp",
    "xfsp_iface",
    "xfsp_source_id",
    "xfsp_cert",
    "xfsp_control",
    "xfsp_control_from",
];

/// A problem in the file: the line it is on (when known) and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileProblem {
    pub line: Option<usize>,
    pub message: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    port: Option<Value>,
    baud: Option<Value>,
    theme: Option<Value>,
    repeat_delay: Option<Value>,
    xfsp: Option<Value>,
    xfsp_iface: Option<Value>,
    xfsp_source_id: Option<Value>,
    xfsp_cert: Option<Value>,
    xfsp_control: Option<Value>,
    xfsp_control_from: Option<Value>,
}

/// Reads the file's text. The first problem stops the reading: one wrong line is
/// enough to refuse the file, and it is named.
pub fn parse(text: &str) -> Result<SettingsFile, FileProblem> {
    let raw: Raw = toml_lines::parse(text).map_err(|r| FileProblem {
        line: r.line,
        message: match r.unknown_key {
            Some(key) => format!("unknown key {key:?}; the keys are {}", KEYS.join(", ")),
            None => r.message,
        },
    })?;
    let read = |key: &str, v: Option<Value>| -> Result<Option<(String, usize)>, FileProblem> {
        let Some(v) = v else { return Ok(None) };
        let line = toml_lines::line(text, &v);
        match v.into_inner() {
            toml::Value::String(s) => Ok(Some((s, line))),
            toml::Value::Integer(i) => Ok(Some((i.to_string(), line))),
            toml::Value::Boolean(b) => Ok(Some((b.to_string(), line))),
            other => Err(FileProblem {
                line: Some(line),
                message: format!(
                    "{key}: {} where text or a whole number was expected",
                    match other.type_str() {
                        "array" => "a list",
                        "table" => "a section",
                        "float" => "a decimal number",
                        _ => "a date",
                    }
                ),
            }),
        }
    };
    fn check<T>(
        key: &str,
        got: Option<(String, usize)>,
        f: impl Fn(&str) -> Result<T, String>,
    ) -> Result<Option<Setting<T>>, FileProblem> {
        got.map(|(text, line)| {
            f(&text)
                .map(|value| Setting { value, line })
                .map_err(|why| FileProblem {
                    line: Some(line),
                    message: format!("{key}: {why}"),
                })
        })
        .transpose()
    }
    Ok(SettingsFile {
        port: check("port", read("port", raw.port)?, values::port)?,
        baud: check("baud", read("baud", raw.baud)?, values::baud)?,
        theme: check("theme", read("theme", raw.theme)?, values::theme)?,
        repeat_delay_ms: check(
            "repeat_delay",
            read("repeat_delay", raw.repeat_delay)?,
            values::repeat_delay_ms,
        )?,
        xfsp: check("xfsp", read("xfsp", raw.xfsp)?, values::xfsp_target)?,
        xfsp_iface: check(
            "xfsp_iface",
            read("xfsp_iface", raw.xfsp_iface)?,
            values::iface,
        )?,
        xfsp_source_id: check(
            "xfsp_source_id",
            read("xfsp_source_id", raw.xfsp_source_id)?,
            values::source_id,
        )?,
        xfsp_cert: check("xfsp_cert", read("xfsp_cert", raw.xfsp_cert)?, |t| {
            t.parse::<u8>()
                .map_err(|_| format!("{t:?} is not a certification level (0–255)"))
        })?,
        xfsp_control: check(
            "xfsp_control",
            read("xfsp_control", raw.xfsp_control)?,
            values::yes_no,
        )?,
        xfsp_control_from: check(
            "xfsp_control_from",
            read("xfsp_control_from", raw.xfsp_control_from)?,
            values::source_ids,
        )?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_is_read_with_its_line() {
        let f = parse(
            "# mine\nport = \"tcp://192.168.4.1:8880\"\nbaud = 115200\ntheme = \"light\"\n\
             repeat_delay = 450\nxfsp = \"239.1.2.3:5000\"\nxfsp_iface = \"10.0.0.2\"\n\
             xfsp_source_id = 0x5651\nxfsp_cert = 2\n",
        )
        .unwrap();
        assert_eq!(
            f.port,
            Some(Setting {
                value: PortAddr::Tcp {
                    host: "192.168.4.1".into(),
                    port: 8880
                },
                line: 2
            })
        );
        assert_eq!(f.baud.map(|s| (s.value, s.line)), Some((115_200, 3)));
        assert_eq!(f.theme.map(|s| s.value), Some(Theme::Light));
        assert_eq!(f.repeat_delay_ms.map(|s| s.value), Some(450));
        assert_eq!(f.xfsp.map(|s| s.value), Some("239.1.2.3:5000".into()));
        assert_eq!(
            f.xfsp_iface.map(|s| s.value),
            Some(Ipv4Addr::new(10, 0, 0, 2))
        );
        assert_eq!(
            f.xfsp_source_id.map(|s| (s.value, s.line)),
            Some((0x5651, 8))
        );
        assert_eq!(f.xfsp_cert.map(|s| s.value), Some(2));
    }

    #[test]
    fn network_control_is_read_as_yes_no_and_a_list() {
        let f = parse("xfsp_control = true\nxfsp_control_from = \"0x1234, 0x5678\"\n").unwrap();
        assert_eq!(f.xfsp_control.map(|s| (s.value, s.line)), Some((true, 1)));
        assert_eq!(
            f.xfsp_control_from.map(|s| s.value.0),
            Some(vec![0x1234, 0x5678])
        );
        let f = parse("xfsp_control = false\nxfsp_control_from = 4660\n").unwrap();
        assert_eq!(f.xfsp_control.map(|s| s.value), Some(false));
        assert_eq!(f.xfsp_control_from.map(|s| s.value.0), Some(vec![0x1234]));
    }

    #[test]
    fn an_empty_file_sets_nothing_and_a_hex_string_id_is_read_too() {
        assert_eq!(parse(""), Ok(SettingsFile::default()));
        let f = parse("xfsp_source_id = \"0x5651\"").unwrap();
        assert_eq!(f.xfsp_source_id.map(|s| s.value), Some(0x5651));
    }

    #[test]
    fn each_kind_of_mistake_names_its_line() {
        for (text, line, words) in [
            (
                "port = \"/dev/ttyUSB0\"\nbaud = 0\n",
                2,
                "baud: 0 is not a baud rate",
            ),
            ("\n\nbaud = 57600\nspeed = 3\n", 4, "unknown key \"speed\""),
            ("port = \"tcp://h\"\n", 1, "no port number"),
            ("theme = \"blue\"", 1, "auto, dark, light, mono, terminal"),
            ("baud = 57600\nbaud = 9600\n", 2, "duplicate key"),
            ("port = [1, 2]\n", 1, "port: a list where text"),
            ("xfsp_iface = \"eth0\"\n", 1, "not an IPv4 address"),
            (
                "xfsp_control = true\nxfsp_control_from = \"0x1234,zz\"\n",
                2,
                "xfsp_control_from: in \"0x1234,zz\": \"zz\" is not a 16-bit source id",
            ),
            ("xfsp_control_from = \"\"\n", 1, "empty list"),
            ("xfsp_control = \"maybe\"\n", 1, "neither true nor false"),
            ("\nport = \"/dev/ttyUSB0\n", 2, ""),
        ] {
            let p = parse(text).unwrap_err();
            assert_eq!(p.line, Some(line), "{text:?}: {p:?}");
            assert!(p.message.contains(words), "{text:?}: {p:?}");
        }
    }
}

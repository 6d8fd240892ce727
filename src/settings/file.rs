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
//! Every problem is reported, each with its line, so a person can go straight to them. Values
//! are read by the same functions as the flags ([`super::values`]).

use std::net::Ipv4Addr;

use std::collections::BTreeMap;

use crate::toml_lines::{self, Problem, Value};

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
    /// The logbook's file, as written (relative: from the config file's folder).
    pub logbook: Option<Setting<std::path::PathBuf>>,
    /// The aircraft's registration, checked and in upper case.
    pub aircraft: Option<Setting<String>>,
}

/// The keys the file may hold, for the message that refuses any other.
pub const KEYS: [&str; 12] = [
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
    "logbook",
    "aircraft",
];

/// Reads the file's text and lists every problem, each with its line and key
/// ([`toml_lines`]).
pub fn parse(text: &str) -> Result<SettingsFile, Vec<Problem>> {
    let raw: BTreeMap<String, Value> = toml_lines::parse(text).map_err(|p| vec![p])?;
    let mut problems = Vec::new();
    for (key, v) in &raw {
        if !KEYS.contains(&key.as_str()) {
            problems.push(Problem::new(
                Some(toml_lines::line(text, v)),
                key,
                format!("unknown key; the keys are {}", KEYS.join(", ")),
            ));
        }
    }
    let mut r = Reader {
        text,
        raw: &raw,
        problems: &mut problems,
    };
    let file = SettingsFile {
        port: r.get("port", values::port),
        baud: r.get("baud", values::baud),
        theme: r.get("theme", values::theme),
        repeat_delay_ms: r.get("repeat_delay", values::repeat_delay_ms),
        xfsp: r.get("xfsp", values::xfsp_target),
        xfsp_iface: r.get("xfsp_iface", values::iface),
        xfsp_source_id: r.get("xfsp_source_id", values::source_id),
        xfsp_cert: r.get("xfsp_cert", |t| {
            t.parse::<u8>()
                .map_err(|_| format!("{t:?} is not a certification level (0–255)"))
        }),
        xfsp_control: r.get("xfsp_control", values::yes_no),
        xfsp_control_from: r.get("xfsp_control_from", values::source_ids),
        logbook: r.get("logbook", |t| {
            if t.trim().is_empty() {
                Err("an empty path: name the logbook's file, or leave the key out".into())
            } else {
                Ok(std::path::PathBuf::from(t))
            }
        }),
        aircraft: r.get("aircraft", crate::logbook::registration),
    };
    if problems.is_empty() {
        Ok(file)
    } else {
        problems.sort_by_key(|p| p.line);
        Err(problems)
    }
}

/// The file's keys, each read as its flag is.
struct Reader<'a> {
    text: &'a str,
    raw: &'a BTreeMap<String, Value>,
    problems: &'a mut Vec<Problem>,
}

impl Reader<'_> {
    /// `key`'s value as `read` takes its text; `None` where the file lacks it, or
    /// where it is wrong (then a problem).
    fn get<T>(
        &mut self,
        key: &str,
        read: impl Fn(&str) -> Result<T, String>,
    ) -> Option<Setting<T>> {
        let v = self.raw.get(key)?;
        let line = toml_lines::line(self.text, v);
        let text = match v.get_ref() {
            toml::Value::String(s) => Ok(s.clone()),
            toml::Value::Integer(i) => Ok(i.to_string()),
            toml::Value::Boolean(b) => Ok(b.to_string()),
            other => Err(format!(
                "{} where text or a whole number was expected",
                toml_lines::kind(other)
            )),
        };
        match text.and_then(|t| read(&t)) {
            Ok(value) => Some(Setting { value, line }),
            Err(why) => {
                self.problems.push(Problem::new(Some(line), key, why));
                None
            }
        }
    }
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
            (
                "\n\nbaud = 57600\nspeed = 3\n",
                4,
                "speed: unknown key; the keys are port,",
            ),
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
            assert_eq!(p.len(), 1, "{text:?}: {p:?}");
            let p = &p[0];
            assert_eq!(p.line, Some(line), "{text:?}: {p:?}");
            assert!(p.to_string().contains(words), "{text:?}: {p}");
        }
    }

    /// Several mistakes are all listed, in line order, in one run.
    #[test]
    fn every_mistake_is_listed_at_once() {
        let p =
            parse("baud = 0\ntheme = \"blue\"\nspeed = 3\nxfsp_iface = \"eth0\"\n").unwrap_err();
        let got: Vec<(Option<usize>, &str, &str)> = p
            .iter()
            .map(|p| (p.line, p.field.as_str(), &p.message[..8]))
            .collect();
        assert_eq!(
            got,
            vec![
                (Some(1), "baud", "0 is not"),
                (Some(2), "theme", "\"blue\" i"),
                (Some(3), "speed", "unknown "),
                (Some(4), "xfsp_iface", "\"eth0\" i"),
            ]
        );
    }
}

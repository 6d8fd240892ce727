//! What `--port` names: a serial path (`/dev/ttyUSB0`, `COM3`, `/dev/cu.usbserial-…`),
//! or `tcp://HOST:PORT`, a serial-to-network bridge (ser2net, the WiFi bridges mounted
//! behind a panel) or `vpx-efis sim --tcp`.

use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PortAddr {
    Serial(PathBuf),
    /// `host` as written: a name, an IPv4 address, or an IPv6 address without brackets.
    Tcp {
        host: String,
        port: u16,
    },
}

impl PortAddr {
    pub fn is_tcp(&self) -> bool {
        matches!(self, PortAddr::Tcp { .. })
    }

    /// `HOST:PORT` as `ToSocketAddrs` takes it (IPv6 in brackets).
    pub fn tcp_authority(host: &str, port: u16) -> String {
        if host.contains(':') {
            format!("[{host}]:{port}")
        } else {
            format!("{host}:{port}")
        }
    }
}

/// A serial path, taken as is (tests and the pty's path; `--port` text goes through
/// [`str::parse`], which also reads `tcp://`).
impl From<PathBuf> for PortAddr {
    fn from(path: PathBuf) -> PortAddr {
        PortAddr::Serial(path)
    }
}

impl From<String> for PortAddr {
    fn from(path: String) -> PortAddr {
        PortAddr::Serial(path.into())
    }
}

impl fmt::Display for PortAddr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PortAddr::Serial(p) => write!(f, "{}", p.display()),
            PortAddr::Tcp { host, port } => {
                write!(f, "tcp://{}", PortAddr::tcp_authority(host, *port))
            }
        }
    }
}

impl FromStr for PortAddr {
    type Err = String;

    fn from_str(text: &str) -> Result<PortAddr, String> {
        let t = text.trim();
        if t.is_empty() {
            return Err("an empty port: give a serial path or tcp://HOST:PORT".into());
        }
        let Some((scheme, rest)) = t.split_once("://") else {
            return Ok(PortAddr::Serial(PathBuf::from(text)));
        };
        if !scheme.eq_ignore_ascii_case("tcp") {
            return Err(format!(
                "{t:?}: {scheme}:// is not a transport vpx-efis speaks; give a serial path or \
                 tcp://HOST:PORT (a raw TCP bridge such as ser2net or a WiFi serial bridge)"
            ));
        }
        let bad =
            |why: &str| format!("{t:?}: {why}; write tcp://HOST:PORT, e.g. tcp://192.168.4.1:8880");
        let rest = rest.strip_suffix('/').unwrap_or(rest);
        let (host, port) = if let Some(v6) = rest.strip_prefix('[') {
            let (host, after) = v6
                .split_once(']')
                .ok_or_else(|| bad("an IPv6 address needs its closing ]"))?;
            let port = after
                .strip_prefix(':')
                .ok_or_else(|| bad("no port number"))?;
            (host, port)
        } else {
            rest.rsplit_once(':').ok_or_else(|| bad("no port number"))?
        };
        if host.is_empty() {
            return Err(bad("no host"));
        }
        if host.contains(['/', ' ']) {
            return Err(bad("the host has a / or a space in it"));
        }
        let port: u16 = match port.parse() {
            Ok(0) | Err(_) => return Err(bad(&format!("{port:?} is not a port number (1–65535)"))),
            Ok(p) => p,
        };
        Ok(PortAddr::Tcp {
            host: host.to_string(),
            port,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tcp(host: &str, port: u16) -> PortAddr {
        PortAddr::Tcp {
            host: host.into(),
            port,
        }
    }

    #[test]
    fn paths_stay_paths_and_tcp_urls_become_host_and_port() {
        assert_eq!(
            "/dev/ttyUSB0".parse(),
            Ok(PortAddr::Serial("/dev/ttyUSB0".into()))
        );
        assert_eq!("COM3".parse(), Ok(PortAddr::Serial("COM3".into())));
        assert_eq!(
            "tcp://192.168.4.1:8880".parse(),
            Ok(tcp("192.168.4.1", 8880))
        );
        assert_eq!(
            "TCP://bridge.local:2000/".parse(),
            Ok(tcp("bridge.local", 2000))
        );
        assert_eq!("tcp://[::1]:7000".parse(), Ok(tcp("::1", 7000)));
    }

    #[test]
    fn a_tcp_url_without_a_usable_port_or_host_is_refused_in_words() {
        for (text, why) in [
            ("tcp://192.168.4.1", "no port number"),
            ("tcp://192.168.4.1:0", "not a port number"),
            ("tcp://192.168.4.1:70000", "not a port number"),
            ("tcp://:8880", "no host"),
            ("tcp://[::1:7000", "closing ]"),
            ("rfc2217://host:1", "not a transport"),
            ("", "empty port"),
        ] {
            let err = text.parse::<PortAddr>().unwrap_err();
            assert!(err.contains(why), "{text}: {err}");
        }
    }

    #[test]
    fn shown_as_written() {
        assert_eq!(tcp("10.0.0.5", 4001).to_string(), "tcp://10.0.0.5:4001");
        assert_eq!(tcp("::1", 4001).to_string(), "tcp://[::1]:4001");
        assert_eq!(
            PortAddr::Serial("/dev/ttyUSB0".into()).to_string(),
            "/dev/ttyUSB0"
        );
    }
}

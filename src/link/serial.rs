//! Real serial ports: opening one with words a mechanic can act on, and listing them.

use std::io;
use std::path::{Path, PathBuf};
use std::time::Duration;

use serialport::{SerialPort, SerialPortType};

use super::connection::Connector;
use crate::platform::Os;

/// Why a port could not be opened, with the likely fix for this OS.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    #[error("{path}: no such port. {hint}")]
    NotFound { path: PathBuf, hint: &'static str },
    #[error("{path}: permission denied. {hint}")]
    PermissionDenied { path: PathBuf, hint: &'static str },
    #[error("{path}: the port is busy. {hint}")]
    Busy { path: PathBuf, hint: &'static str },
    #[error("{path}: cannot open the port: {detail}. {hint}")]
    Other {
        path: PathBuf,
        detail: String,
        hint: &'static str,
    },
}

/// Opens a port at `baud`, 8N1 (ICD §3.2.1), with a short read timeout so reader
/// threads can notice a shutdown.
pub fn open_serial(path: &Path, baud: u32) -> Result<Box<dyn SerialPort>, OpenError> {
    serialport::new(path.to_string_lossy(), baud)
        .data_bits(serialport::DataBits::Eight)
        .parity(serialport::Parity::None)
        .stop_bits(serialport::StopBits::One)
        .flow_control(serialport::FlowControl::None)
        .timeout(Duration::from_millis(50))
        .open()
        .map_err(|e| {
            // Read at once, before anything else can overwrite it: on Windows the
            // error's kind alone cannot tell a missing port from a busy one.
            let code = io::Error::last_os_error().raw_os_error();
            open_error(path, &e, code, Os::current())
        })
}

/// What kind of failure an open was, from the error's kind and the OS's error code,
/// never from its message: Windows words its messages in the user's language.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Problem {
    NotFound,
    PermissionDenied,
    Busy,
    Other,
}

/// Error codes, as numbers so every OS's branch is tested everywhere. errno values are
/// the same on Linux and macOS for these; Windows' come from winerror.h.
mod code {
    pub const EPERM: i32 = 1;
    pub const ENOENT: i32 = 2;
    pub const ENXIO: i32 = 6;
    pub const EACCES: i32 = 13;
    pub const EBUSY: i32 = 16;
    pub const ENODEV: i32 = 19;
    pub const ERROR_FILE_NOT_FOUND: i32 = 2;
    pub const ERROR_PATH_NOT_FOUND: i32 = 3;
    pub const ERROR_ACCESS_DENIED: i32 = 5;
    pub const ERROR_SHARING_VIOLATION: i32 = 32;
    pub const ERROR_INVALID_NAME: i32 = 123;
}

fn classify(kind: serialport::ErrorKind, code: Option<i32>, os: Os) -> Problem {
    use serialport::ErrorKind as K;
    match os {
        // serialport maps every failed CreateFileW to NoDevice or Io(Other) and keeps
        // only the localised text, so the code decides. There are no per-user
        // permissions on COM ports: "access denied" means another program holds it.
        Os::Windows => match code {
            Some(code::ERROR_FILE_NOT_FOUND | code::ERROR_PATH_NOT_FOUND)
            | Some(code::ERROR_INVALID_NAME) => Problem::NotFound,
            Some(code::ERROR_ACCESS_DENIED | code::ERROR_SHARING_VIOLATION) => Problem::Busy,
            _ => match kind {
                K::Io(io::ErrorKind::NotFound) => Problem::NotFound,
                K::Io(io::ErrorKind::PermissionDenied) => Problem::Busy,
                _ => Problem::Other,
            },
        },
        // serialport maps errno to kinds on Unix; TIOCEXCL's EBUSY and a held flock
        // both come as NoDevice.
        Os::Linux | Os::MacOs | Os::OtherUnix => match kind {
            K::Io(io::ErrorKind::NotFound) => Problem::NotFound,
            K::Io(io::ErrorKind::PermissionDenied) => Problem::PermissionDenied,
            K::NoDevice | K::Io(io::ErrorKind::WouldBlock) => Problem::Busy,
            _ => match code {
                Some(code::ENOENT | code::ENXIO | code::ENODEV) => Problem::NotFound,
                Some(code::EACCES | code::EPERM) => Problem::PermissionDenied,
                Some(code::EBUSY) => Problem::Busy,
                _ => Problem::Other,
            },
        },
    }
}

/// What to do about `problem` on `os`, in words a mechanic can act on.
fn hint(problem: Problem, os: Os) -> &'static str {
    match (problem, os) {
        (Problem::NotFound, Os::Windows) => {
            "Serial ports are named COM3, COM4, …: `vpx-efis ports` lists them, as does Device Manager under \
             Ports (COM & LPT). If the adapter is not there, install its driver (FTDI, Prolific, CH340) and plug \
             it in again."
        }
        (Problem::NotFound, Os::MacOs) => {
            "Check the path (`vpx-efis ports` lists them; on a Mac use the /dev/cu.* name) and that the \
             USB-serial cable is plugged in; some adapters need their driver installed first."
        }
        (Problem::NotFound, Os::Linux | Os::OtherUnix) => {
            "Check the path (`vpx-efis ports` lists them) and that the USB-serial cable is plugged in."
        }
        (Problem::PermissionDenied, Os::Linux) => {
            "Add yourself to the port's group (usually `dialout`: `sudo usermod -aG dialout $USER`, then log \
             in again)."
        }
        (Problem::PermissionDenied, Os::MacOs) => {
            "Open the /dev/cu.* name of the port (`vpx-efis ports`), not /dev/tty.*; if it is still refused, \
             allow the adapter's driver in System Settings > Privacy & Security."
        }
        (Problem::PermissionDenied, Os::OtherUnix) => {
            "Add yourself to the group that owns the port (`ls -l` on it shows which; often `dialer` or \
             `uucp`), then log in again."
        }
        (Problem::PermissionDenied | Problem::Busy, Os::Windows) => {
            "Windows lets one program at a time open a COM port: close the other one (a terminal program, \
             another vpx-efis, the EFIS or GPS software) and retry. If nothing else has it, unplug the \
             adapter and plug it in again, or reinstall its driver."
        }
        (Problem::Busy, Os::Linux) => {
            "Another program has it open (a terminal program, another vpx-efis, or ModemManager probing a \
             newly plugged adapter: wait a few seconds, or `sudo systemctl stop ModemManager`); close it and \
             retry."
        }
        (Problem::Busy, Os::MacOs | Os::OtherUnix) => {
            "Another program has it open (a terminal program, `screen`, another vpx-efis); close it and retry."
        }
        (Problem::Other, Os::Windows) => {
            "Check the COM port's name (`vpx-efis ports`), that no other program holds it, and that the \
             adapter's driver is installed (Device Manager, Ports (COM & LPT))."
        }
        (Problem::Other, Os::MacOs) => {
            "Check the path (`vpx-efis ports`; use /dev/cu.*, not /dev/tty.*) and the cable."
        }
        (Problem::Other, Os::Linux | Os::OtherUnix) => {
            "Check the path (`vpx-efis ports`) and the cable."
        }
    }
}

fn open_error(path: &Path, e: &serialport::Error, code: Option<i32>, os: Os) -> OpenError {
    let problem = classify(e.kind(), code, os);
    let path = path.to_path_buf();
    let hint = hint(problem, os);
    match problem {
        Problem::NotFound => OpenError::NotFound { path, hint },
        Problem::PermissionDenied => OpenError::PermissionDenied { path, hint },
        Problem::Busy => OpenError::Busy { path, hint },
        Problem::Other => OpenError::Other {
            path,
            detail: e.to_string(),
            hint,
        },
    }
}

/// A [`Connector`] that (re)opens the same serial path each time it is called.
pub fn serial_connector(path: PathBuf, baud: u32) -> Connector {
    Box::new(move || {
        let port = open_serial(&path, baud).map_err(|e| io::Error::other(e.to_string()))?;
        let writer = port
            .try_clone()
            .map_err(|e| io::Error::other(e.to_string()))?;
        Ok((
            Box::new(port) as _,
            Box::new(writer) as _,
            path.display().to_string(),
        ))
    })
}

/// A serial port as `vpx-efis ports` shows it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PortInfo {
    pub path: String,
    pub description: String,
}

/// The serial ports this machine has, in the order `vpx-efis ports` shows them.
pub fn list_ports() -> anyhow::Result<Vec<PortInfo>> {
    let ports = serialport::available_ports()?;
    let ports = ports
        .into_iter()
        .map(|p| PortInfo {
            description: match p.port_type {
                SerialPortType::UsbPort(u) => {
                    let mut d = format!("USB {:04x}:{:04x}", u.vid, u.pid);
                    for s in [u.manufacturer, u.product, u.serial_number]
                        .into_iter()
                        .flatten()
                    {
                        d.push(' ');
                        d.push_str(&s);
                    }
                    d
                }
                SerialPortType::PciPort => "PCI".into(),
                SerialPortType::BluetoothPort => "Bluetooth".into(),
                SerialPortType::Unknown => "unknown".into(),
            },
            path: p.port_name,
        })
        .collect();
    Ok(arrange_ports(ports, Os::current()))
}

/// macOS shows each port twice: /dev/cu.X, which opens at once, and /dev/tty.X, which
/// waits for a carrier signal a VP-X cable never gives. There the cu.* names come
/// first and each tty.* twin says which name to use. Elsewhere, sorted by path.
fn arrange_ports(mut ports: Vec<PortInfo>, os: Os) -> Vec<PortInfo> {
    ports.sort_by(|a, b| a.path.cmp(&b.path));
    if os != Os::MacOs {
        return ports;
    }
    let twin_of = |path: &str| {
        path.strip_prefix("/dev/tty.")
            .map(|name| format!("/dev/cu.{name}"))
    };
    let cu: Vec<String> = ports
        .iter()
        .filter(|p| p.path.starts_with("/dev/cu."))
        .map(|p| p.path.clone())
        .collect();
    for p in &mut ports {
        if let Some(twin) = twin_of(&p.path)
            && cu.contains(&twin)
        {
            p.description = format!("{} (same port as {twin}: use that)", p.description);
        }
    }
    // Stable: cu.* first, then everything else, each in path order.
    ports.sort_by_key(|p| !p.path.starts_with("/dev/cu."));
    ports
}

#[cfg(test)]
mod tests {
    use super::*;
    use serialport::ErrorKind as K;

    #[test]
    fn a_missing_port_says_so_and_how_to_find_the_right_one() {
        let Err(err) = open_serial(Path::new("/dev/does-not-exist-vpx"), 57_600) else {
            panic!("opening a missing port must fail");
        };
        assert!(matches!(err, OpenError::NotFound { .. }), "{err:?}");
        assert!(err.to_string().contains("vpx-efis ports"), "{err}");
    }

    /// A port held by another opener (serialport takes it exclusively: TIOCEXCL and
    /// flock) is busy, not missing.
    #[cfg(unix)]
    #[test]
    fn a_port_another_program_holds_is_busy() {
        let pty = crate::link::open_pty_pair().unwrap();
        let _held = open_serial(Path::new(&pty.path), 57_600).expect("the first open");
        let Err(err) = open_serial(Path::new(&pty.path), 57_600) else {
            panic!("a second open of a held port must fail");
        };
        assert!(matches!(err, OpenError::Busy { .. }), "{err:?}");
    }

    #[test]
    fn unix_errors_are_sorted_by_kind_and_errno() {
        use io::ErrorKind as Io;
        for os in [Os::Linux, Os::MacOs, Os::OtherUnix] {
            for (kind, code, want, what) in [
                (K::Io(Io::NotFound), None, Problem::NotFound, "NotFound"),
                (
                    K::Io(Io::PermissionDenied),
                    None,
                    Problem::PermissionDenied,
                    "denied",
                ),
                // TIOCEXCL's EBUSY and a held flock.
                (K::NoDevice, None, Problem::Busy, "NoDevice"),
                (K::Io(Io::WouldBlock), None, Problem::Busy, "WouldBlock"),
                // Kinds serialport leaves Unknown: the errno decides.
                (K::Unknown, Some(6), Problem::NotFound, "ENXIO"),
                (K::Unknown, Some(19), Problem::NotFound, "ENODEV"),
                (K::Unknown, Some(13), Problem::PermissionDenied, "EACCES"),
                (K::Unknown, Some(1), Problem::PermissionDenied, "EPERM"),
                (K::Unknown, Some(16), Problem::Busy, "EBUSY"),
                (K::Unknown, Some(5), Problem::Other, "EIO"),
                (K::InvalidInput, None, Problem::Other, "InvalidInput"),
            ] {
                assert_eq!(classify(kind, code, os), want, "{what} on {os:?}");
            }
        }
    }

    /// What serialport gives on Windows: NoDevice (file or path not found, access
    /// denied) or Io(Other), with a message in the user's language. The code decides.
    #[test]
    fn windows_errors_are_sorted_by_their_code_not_their_words() {
        use io::ErrorKind as Io;
        for (kind, code, want, what) in [
            (
                K::NoDevice,
                Some(2),
                Problem::NotFound,
                "ERROR_FILE_NOT_FOUND",
            ),
            (
                K::NoDevice,
                Some(3),
                Problem::NotFound,
                "ERROR_PATH_NOT_FOUND",
            ),
            (
                K::Io(Io::Other),
                Some(123),
                Problem::NotFound,
                "ERROR_INVALID_NAME",
            ),
            // Another program holds the port.
            (K::NoDevice, Some(5), Problem::Busy, "ERROR_ACCESS_DENIED"),
            (
                K::Io(Io::Other),
                Some(32),
                Problem::Busy,
                "ERROR_SHARING_VIOLATION",
            ),
            // A driver that fails, or no code at all: not guessed.
            (
                K::Io(Io::Other),
                Some(31),
                Problem::Other,
                "ERROR_GEN_FAILURE",
            ),
            (K::NoDevice, None, Problem::Other, "NoDevice, no code"),
            (K::Io(Io::NotFound), None, Problem::NotFound, "NotFound"),
            (
                K::Io(Io::PermissionDenied),
                None,
                Problem::Busy,
                "PermissionDenied",
            ),
        ] {
            assert_eq!(classify(kind, code, Os::Windows), want, "{what}");
        }
    }

    #[test]
    fn hints_speak_of_each_os_own_fixes() {
        let has = |p, os, words: &[&str]| {
            let h = hint(p, os);
            for w in words {
                assert!(h.contains(w), "{p:?} on {os:?}: {h:?} lacks {w:?}");
            }
        };
        has(Problem::PermissionDenied, Os::Linux, &["dialout"]);
        has(Problem::Busy, Os::Linux, &["ModemManager"]);
        has(Problem::NotFound, Os::MacOs, &["/dev/cu."]);
        has(
            Problem::PermissionDenied,
            Os::MacOs,
            &["/dev/cu.", "not /dev/tty."],
        );
        has(Problem::Other, Os::MacOs, &["not /dev/tty."]);
        has(Problem::NotFound, Os::Windows, &["COM3", "driver"]);
        has(
            Problem::Busy,
            Os::Windows,
            &["one program at a time", "driver"],
        );
        has(
            Problem::Other,
            Os::Windows,
            &["COM port", "driver", "other program"],
        );
        // No advice that does not apply: no dialout or ModemManager off Linux, no COM
        // ports off Windows.
        for p in [
            Problem::NotFound,
            Problem::PermissionDenied,
            Problem::Busy,
            Problem::Other,
        ] {
            for os in Os::ALL {
                let h = hint(p, os);
                assert_eq!(
                    h.contains("dialout"),
                    os == Os::Linux && p == Problem::PermissionDenied,
                    "{p:?} {os:?}"
                );
                assert!(
                    os == Os::Linux || !h.contains("ModemManager"),
                    "{p:?} {os:?}"
                );
                assert!(os == Os::Windows || !h.contains("COM"), "{p:?} {os:?}");
            }
        }
    }

    #[test]
    fn the_message_carries_the_path_and_the_hint() {
        let e = serialport::Error::new(K::NoDevice, "Zugriff verweigert");
        let err = open_error(Path::new("COM4"), &e, Some(5), Os::Windows);
        assert_eq!(
            err.to_string(),
            format!(
                "COM4: the port is busy. {}",
                hint(Problem::Busy, Os::Windows)
            )
        );
        let e = serialport::Error::new(K::Io(io::ErrorKind::Other), "Fehler");
        let err = open_error(Path::new("COM4"), &e, Some(31), Os::Windows);
        assert!(
            err.to_string()
                .starts_with("COM4: cannot open the port: Fehler. "),
            "{err}"
        );
    }

    fn port(path: &str, description: &str) -> PortInfo {
        PortInfo {
            path: path.into(),
            description: description.into(),
        }
    }

    #[test]
    fn on_a_mac_cu_names_come_first_and_tty_twins_point_to_them() {
        let listed = vec![
            port("/dev/tty.usbserial-A1", "USB 0403:6001"),
            port("/dev/tty.Bluetooth-Incoming-Port", "unknown"),
            port("/dev/cu.usbserial-A1", "USB 0403:6001"),
            port("/dev/cu.Bluetooth-Incoming-Port", "unknown"),
        ];
        let shown = arrange_ports(listed.clone(), Os::MacOs);
        assert_eq!(
            shown,
            vec![
                port("/dev/cu.Bluetooth-Incoming-Port", "unknown"),
                port("/dev/cu.usbserial-A1", "USB 0403:6001"),
                port(
                    "/dev/tty.Bluetooth-Incoming-Port",
                    "unknown (same port as /dev/cu.Bluetooth-Incoming-Port: use that)"
                ),
                port(
                    "/dev/tty.usbserial-A1",
                    "USB 0403:6001 (same port as /dev/cu.usbserial-A1: use that)"
                ),
            ]
        );
        // Elsewhere nothing is renamed, only sorted.
        let linux = arrange_ports(
            vec![port("/dev/ttyUSB0", "USB"), port("/dev/ttyS0", "unknown")],
            Os::Linux,
        );
        assert_eq!(
            linux,
            vec![port("/dev/ttyS0", "unknown"), port("/dev/ttyUSB0", "USB")]
        );
    }
}

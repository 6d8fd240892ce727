//! Real serial ports: opening one with words a mechanic can act on, and listing them.

use std::io;
use std::path::{Path, PathBuf};
use std::time::Duration;

use serialport::{SerialPort, SerialPortType};

use super::connection::Connector;

/// Why a port could not be opened, with the likely fix.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    #[error(
        "{path}: no such port. Check the path (`vpx-efis ports` lists them) and that the USB-serial cable is plugged in."
    )]
    NotFound { path: PathBuf },
    #[error(
        "{path}: permission denied. Add yourself to the port's group (usually `dialout`: `sudo usermod -aG dialout $USER`, then log in again)."
    )]
    PermissionDenied { path: PathBuf },
    #[error(
        "{path}: the port is busy. Another program (a terminal, another vpx-efis, ModemManager) has it open; close it and retry."
    )]
    Busy { path: PathBuf },
    #[error("{path}: cannot open the port: {detail}")]
    Other { path: PathBuf, detail: String },
}

/// Opens a port at `baud`, 8N1 (ICD §3.2.1), with a short read timeout so reader
/// threads can notice a shutdown.
pub fn open_serial(path: &Path, baud: u32) -> Result<Box<dyn SerialPort>, OpenError> {
    let p = path.to_path_buf();
    serialport::new(path.to_string_lossy(), baud)
        .data_bits(serialport::DataBits::Eight)
        .parity(serialport::Parity::None)
        .stop_bits(serialport::StopBits::One)
        .flow_control(serialport::FlowControl::None)
        .timeout(Duration::from_millis(50))
        .open()
        .map_err(|e| classify(p, e))
}

fn classify(path: PathBuf, e: serialport::Error) -> OpenError {
    let detail = e.to_string();
    let lower = detail.to_lowercase();
    match e.kind() {
        serialport::ErrorKind::Io(io::ErrorKind::NotFound) => OpenError::NotFound { path },
        serialport::ErrorKind::Io(io::ErrorKind::PermissionDenied) => {
            OpenError::PermissionDenied { path }
        }
        _ if lower.contains("no such file") || lower.contains("not found") => {
            OpenError::NotFound { path }
        }
        _ if lower.contains("permission") => OpenError::PermissionDenied { path },
        _ if lower.contains("busy") || lower.contains("resource temporarily unavailable") => {
            OpenError::Busy { path }
        }
        _ if !path.exists() => OpenError::NotFound { path },
        _ => OpenError::Other { path, detail },
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

pub fn list_ports() -> anyhow::Result<Vec<PortInfo>> {
    let ports = serialport::available_ports()?;
    Ok(ports
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
                SerialPortType::Unknown => {
                    usb_from_sysfs(&p.port_name).unwrap_or_else(|| "unknown".into())
                }
            },
            path: p.port_name,
        })
        .collect())
}

/// USB vendor/product from sysfs. `serialport` is built without libudev (a fresh
/// machine lacks its headers), so it cannot say which ports are USB adapters; the
/// kernel's sysfs tree can: the tty's device links into the USB device that carries
/// `idVendor` and `idProduct`.
fn usb_from_sysfs(port: &str) -> Option<String> {
    usb_from_sysfs_in(Path::new("/sys"), port)
}

fn usb_from_sysfs_in(sys: &Path, port: &str) -> Option<String> {
    let name = Path::new(port).file_name()?.to_str()?;
    let device = std::fs::canonicalize(sys.join("class/tty").join(name).join("device")).ok()?;
    let read = |dir: &Path, f: &str| {
        std::fs::read_to_string(dir.join(f))
            .ok()
            .map(|s| s.trim().to_string())
    };
    let mut dir = device.as_path();
    for _ in 0..6 {
        if let (Some(vid), Some(pid)) = (read(dir, "idVendor"), read(dir, "idProduct")) {
            let mut d = format!("USB {vid}:{pid}");
            for f in ["manufacturer", "product", "serial"] {
                if let Some(v) = read(dir, f) {
                    d.push(' ');
                    d.push_str(&v);
                }
            }
            return Some(d);
        }
        dir = dir.parent()?;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usb_ids_come_from_the_usb_device_above_the_tty_in_sysfs() {
        let root = tempfile::tempdir().unwrap();
        let usb = root.path().join("devices/pci0/usb1/1-2");
        let iface = usb.join("1-2:1.0/ttyUSB0");
        std::fs::create_dir_all(&iface).unwrap();
        std::fs::write(usb.join("idVendor"), "0403\n").unwrap();
        std::fs::write(usb.join("idProduct"), "6001\n").unwrap();
        std::fs::write(usb.join("product"), "FT232R USB UART\n").unwrap();
        std::fs::create_dir_all(root.path().join("class/tty/ttyUSB0")).unwrap();
        std::os::unix::fs::symlink(&iface, root.path().join("class/tty/ttyUSB0/device")).unwrap();
        assert_eq!(
            usb_from_sysfs_in(root.path(), "/dev/ttyUSB0").as_deref(),
            Some("USB 0403:6001 FT232R USB UART")
        );
        assert_eq!(usb_from_sysfs_in(root.path(), "/dev/ttyS0"), None);
    }

    #[test]
    fn a_missing_port_says_so_and_how_to_find_the_right_one() {
        let Err(err) = open_serial(Path::new("/dev/does-not-exist-vpx"), 57_600) else {
            panic!("opening a missing port must fail");
        };
        assert!(matches!(err, OpenError::NotFound { .. }), "{err:?}");
        assert!(err.to_string().contains("vpx-efis ports"), "{err}");
    }
}

//! The thin socket layer: one UDP socket, a receiving thread, and sending.
//!
//! A target `GROUP:PORT` with a multicast group (224.0.0.0/4) is the normal XFSp case:
//! the socket binds `GROUP:PORT` (`0.0.0.0:PORT` on Windows) with SO_REUSEADDR (so the page, a gateway and
//! `xfsp-dump` can all listen on one host), joins the group on the configured
//! interface, sends with that interface as the multicast interface, TTL 1 (the
//! aircraft network is one segment) and multicast loop on (a display on the same host,
//! and the tests, hear us; our own datagrams are then ignored by source id).
//!
//! Any other address is **unicast**, for tests and point-to-point bench setups:
//! - [`XfspNet::open`] (the gateway) binds an ephemeral port on the interface
//!   address and sends everything to the target; a peer answers to the address our
//!   datagrams come from.
//! - [`XfspNet::listen`] (`xfsp-dump`) binds the target address itself and only
//!   listens.
//!
//! Received datagrams go through a bounded channel; when the consumer falls behind,
//! the newest are dropped (a flood cannot exhaust memory).

use std::io;
use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, TrySendError, bounded};
use socket2::{Domain, Protocol, Socket, Type};

use crate::platform::Os;
use crate::transient::is_transient;

/// The draft's default group and port (icd-reading X9).
pub const DEFAULT_TARGET: &str = "224.0.2.69:20234";
/// Datagrams queued between the receiving thread and the main loop.
pub const QUEUE: usize = 4096;
/// The receiving thread checks for shutdown this often.
const READ_TIMEOUT: Duration = Duration::from_millis(100);
/// Larger than any UDP payload, so nothing is silently truncated.
const MAX_DATAGRAM: usize = 65_536;

/// Where XFSp traffic goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    Multicast { group: Ipv4Addr, port: u16 },
    Unicast(SocketAddrV4),
}

impl Target {
    /// `GROUP:PORT` or `HOST:PORT` (IPv4 literals).
    pub fn parse(s: &str) -> Result<Target, String> {
        let addr: SocketAddrV4 = s
            .trim()
            .parse()
            .map_err(|_| format!("`{s}` is not an IPv4 address and port like 224.0.2.69:20234"))?;
        Ok(if addr.ip().is_multicast() {
            Target::Multicast {
                group: *addr.ip(),
                port: addr.port(),
            }
        } else {
            Target::Unicast(addr)
        })
    }

    pub fn addr(&self) -> SocketAddrV4 {
        match *self {
            Target::Multicast { group, port } => SocketAddrV4::new(group, port),
            Target::Unicast(a) => a,
        }
    }
}

impl std::fmt::Display for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Target::Multicast { .. } => write!(f, "multicast {}", self.addr()),
            Target::Unicast(a) => write!(f, "unicast {a}"),
        }
    }
}

/// One received datagram.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Datagram {
    pub at: Instant,
    pub from: SocketAddr,
    pub bytes: Vec<u8>,
}

/// A socket with its receiving thread. Dropping it stops the thread.
pub struct XfspNet {
    socket: UdpSocket,
    dest: Option<SocketAddr>,
    incoming: Receiver<Datagram>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl XfspNet {
    /// For the gateway: listen and send (see the module docs for unicast).
    pub fn open(target: &Target, iface: Ipv4Addr) -> io::Result<XfspNet> {
        match *target {
            Target::Multicast { group, port } => {
                let s = multicast_socket(group, port, iface)?;
                XfspNet::start(s, Some(target.addr().into()))
            }
            Target::Unicast(dest) => {
                let s = UdpSocket::bind(SocketAddrV4::new(iface, 0))?;
                XfspNet::start(s, Some(dest.into()))
            }
        }
    }

    /// For `xfsp-dump`: listen only.
    pub fn listen(target: &Target, iface: Ipv4Addr) -> io::Result<XfspNet> {
        let s = match *target {
            Target::Multicast { group, port } => multicast_socket(group, port, iface)?,
            Target::Unicast(a) => UdpSocket::bind(a)?,
        };
        XfspNet::start(s, None)
    }

    fn start(socket: UdpSocket, dest: Option<SocketAddr>) -> io::Result<XfspNet> {
        socket.set_read_timeout(Some(READ_TIMEOUT))?;
        let reader = socket.try_clone()?;
        let (tx, incoming) = bounded(QUEUE);
        let stop = Arc::new(AtomicBool::new(false));
        let thread = {
            let stop = stop.clone();
            std::thread::Builder::new()
                .name("xfsp-rx".into())
                .spawn(move || {
                    let mut buf = vec![0u8; MAX_DATAGRAM];
                    while !stop.load(Ordering::SeqCst) {
                        match reader.recv_from(&mut buf) {
                            Ok((n, from)) => {
                                let d = Datagram {
                                    at: Instant::now(),
                                    from,
                                    bytes: buf.get(..n).unwrap_or_default().to_vec(),
                                };
                                match tx.try_send(d) {
                                    Ok(()) | Err(TrySendError::Full(_)) => {}
                                    // Nobody is listening any more.
                                    Err(TrySendError::Disconnected(_)) => return,
                                }
                            }
                            Err(e) if is_transient(&e) => {}
                            // An ICMP error from an earlier unicast send, or a transient
                            // failure: keep listening, gently.
                            Err(_) => std::thread::sleep(Duration::from_millis(10)),
                        }
                    }
                })?
        };
        Ok(XfspNet {
            socket,
            dest,
            incoming,
            stop,
            thread: Some(thread),
        })
    }

    /// Received datagrams, in arrival order.
    pub fn incoming(&self) -> &Receiver<Datagram> {
        &self.incoming
    }

    pub fn local_addr(&self) -> io::Result<SocketAddr> {
        self.socket.local_addr()
    }

    /// Sends each datagram to the target; returns the first error.
    pub fn send_all(&self, datagrams: &[Vec<u8>]) -> io::Result<()> {
        let Some(dest) = self.dest else {
            return Err(io::Error::other("this socket only listens"));
        };
        let mut first = Ok(());
        for d in datagrams {
            if let Err(e) = self.socket.send_to(d, dest)
                && first.is_ok()
            {
                first = Err(e);
            }
        }
        first
    }
}

impl Drop for XfspNet {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// A socket bound for `group:port` with SO_REUSEADDR, joined on `iface`, sending
/// through `iface`. socket2 does what std cannot (SO_REUSEADDR before bind, the
/// multicast interface) the same way on every OS, close-on-exec included.
fn multicast_socket(group: Ipv4Addr, port: u16, iface: Ipv4Addr) -> io::Result<UdpSocket> {
    let socket = Socket::new(Domain::IPV4, Type::DGRAM, Some(Protocol::UDP))?;
    socket.set_reuse_address(true)?;
    let bind = multicast_bind_addr(Os::current(), group, port);
    socket.bind(&SocketAddr::V4(bind).into())?;
    socket.join_multicast_v4(&group, &iface)?;
    socket.set_multicast_if_v4(&iface)?;
    socket.set_multicast_loop_v4(true)?;
    socket.set_multicast_ttl_v4(1)?;
    Ok(socket.into())
}

/// The address a multicast listener binds. On Unix it is the group itself, which keeps
/// other groups' traffic on the same port out of this socket (Linux hands a socket
/// bound to 0.0.0.0 every group any socket on the host joined). Windows refuses to
/// bind a multicast address (WSAEADDRNOTAVAIL) and only delivers a group's datagrams
/// to sockets that joined it, so there it is 0.0.0.0.
fn multicast_bind_addr(os: Os, group: Ipv4Addr, port: u16) -> SocketAddrV4 {
    match os {
        Os::Windows => SocketAddrV4::new(Ipv4Addr::UNSPECIFIED, port),
        Os::Linux | Os::MacOs | Os::OtherUnix => SocketAddrV4::new(group, port),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_tell_multicast_from_unicast() {
        assert_eq!(
            Target::parse(DEFAULT_TARGET),
            Ok(Target::Multicast {
                group: Ipv4Addr::new(224, 0, 2, 69),
                port: 20234
            })
        );
        assert_eq!(
            Target::parse("127.0.0.1:9000"),
            Ok(Target::Unicast(SocketAddrV4::new(
                Ipv4Addr::LOCALHOST,
                9000
            )))
        );
        assert!(Target::parse("224.0.2.69").is_err());
        assert!(Target::parse("[::1]:5").is_err());
    }

    #[test]
    fn a_multicast_listener_binds_the_group_on_unix_and_any_address_on_windows() {
        let group = Ipv4Addr::new(224, 0, 2, 69);
        for os in [Os::Linux, Os::MacOs, Os::OtherUnix] {
            assert_eq!(
                multicast_bind_addr(os, group, 20234),
                "224.0.2.69:20234".parse().unwrap(),
                "{os:?}"
            );
        }
        assert_eq!(
            multicast_bind_addr(Os::Windows, group, 20234),
            "0.0.0.0:20234".parse().unwrap()
        );
    }

    /// Two listeners on one host share the group's port (SO_REUSEADDR before bind),
    /// and a datagram sent on the loopback interface reaches both.
    #[test]
    fn two_listeners_share_a_group_on_loopback() {
        let port = {
            let probe = UdpSocket::bind("127.0.0.1:0").unwrap();
            probe.local_addr().unwrap().port()
        };
        let target = Target::Multicast {
            group: Ipv4Addr::new(239, 255, 73, 13),
            port,
        };
        let a = XfspNet::listen(&target, Ipv4Addr::LOCALHOST).expect("a listener on the group");
        let b = XfspNet::open(&target, Ipv4Addr::LOCALHOST).expect("a second socket on the port");
        b.send_all(&[b"hello".to_vec()]).unwrap();
        let got = a
            .incoming()
            .recv_timeout(Duration::from_secs(2))
            .expect("the listener hears the sender");
        assert_eq!(got.bytes, b"hello");
        let echo = b
            .incoming()
            .recv_timeout(Duration::from_secs(2))
            .expect("multicast loop is on");
        assert_eq!(echo.bytes, b"hello");
    }
}

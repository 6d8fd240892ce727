//! Serial over the network: the VP-X's RS-232 line carried raw over TCP by a
//! serial-to-network bridge (ser2net in raw mode, the WiFi serial bridges mounted behind
//! a panel), and `vpx-efis sim --tcp`, which offers the virtual VP-X the same way.
//!
//! A TCP link is a serial link to everything above it: the same [`Connector`] shape,
//! reopened by the same supervisor when the peer goes away. Three things differ and are
//! decided here:
//! - Nagle is off (`TCP_NODELAY`): a motor stream's 11-byte frames must leave now, not
//!   when a 200 ms delayed ACK comes back.
//! - The baud rate belongs to the bridge's serial side, which is set up on the bridge.
//! - A bridge that loses power or WiFi never closes the connection, so a silent TCP
//!   link is closed and reopened after [`SILENCE_LIMIT`]; a unit broadcasts at 10 Hz,
//!   so seconds of silence on a connection that is still up mean nothing arrives.

use std::io::{self, Read, Write};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream, ToSocketAddrs};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use super::PortAddr;
use super::connection::Connector;
use super::pipe::{PipeReader, PipeWriter, pipe_pair};

/// How long a connection attempt waits for the bridge to answer.
pub const CONNECT_TIMEOUT: Duration = Duration::from_secs(3);
/// The read timeout: short, so the link's threads notice a shutdown, as on a serial port.
pub const READ_TIMEOUT: Duration = Duration::from_millis(50);
/// A write that cannot go out for this long fails instead of hanging the writer.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(2);
/// A connection silent this long is taken as dead and reopened.
pub const SILENCE_LIMIT: Duration = Duration::from_secs(10);
/// How long an accepted client may be silent before the OS probes whether it is there.
const CLIENT_KEEPALIVE: Duration = Duration::from_secs(15);

/// Why a bridge could not be reached, with what to check. Sorted by `io::ErrorKind`,
/// never by the (localised) text of the message.
#[derive(Debug, thiserror::Error)]
pub enum TcpOpenError {
    #[error(
        "{addr}: cannot find the host: {detail}. Check the name, or use the bridge's IP address."
    )]
    Resolve { addr: String, detail: String },
    #[error(
        "{addr}: connection refused: nothing listens on that port. Check the port number \
         (ser2net's configuration, or the WiFi bridge's settings page) and that the bridge \
         is running."
    )]
    Refused { addr: String },
    #[error(
        "{addr}: no answer within {secs} s. Check the address, that the bridge is powered, and \
         that this machine is on the bridge's network (its WiFi)."
    )]
    TimedOut { addr: String, secs: u64 },
    #[error(
        "{addr}: the network cannot reach that host. Check that this machine is on the \
         bridge's network (its WiFi) and the address is right."
    )]
    Unreachable { addr: String },
    #[error("{addr}: cannot connect: {detail}")]
    Other { addr: String, detail: String },
}

impl TcpOpenError {
    fn from_io(addr: &str, e: &io::Error) -> TcpOpenError {
        let addr = addr.to_string();
        match e.kind() {
            io::ErrorKind::ConnectionRefused => TcpOpenError::Refused { addr },
            io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock => TcpOpenError::TimedOut {
                addr,
                secs: CONNECT_TIMEOUT.as_secs(),
            },
            io::ErrorKind::HostUnreachable
            | io::ErrorKind::NetworkUnreachable
            | io::ErrorKind::AddrNotAvailable
            | io::ErrorKind::NetworkDown => TcpOpenError::Unreachable { addr },
            _ => TcpOpenError::Other {
                addr,
                detail: e.to_string(),
            },
        }
    }
}

/// Connects to `host:port` with Nagle off and the link's timeouts; tries each address
/// the name resolves to, and reports the first failure.
pub fn open_tcp(host: &str, port: u16) -> Result<TcpStream, TcpOpenError> {
    let shown = PortAddr::Tcp {
        host: host.to_string(),
        port,
    }
    .to_string();
    let addrs: Vec<SocketAddr> = PortAddr::tcp_authority(host, port)
        .to_socket_addrs()
        .map_err(|e| TcpOpenError::Resolve {
            addr: shown.clone(),
            detail: e.to_string(),
        })?
        .collect();
    let mut first_error = None;
    for a in &addrs {
        match TcpStream::connect_timeout(a, CONNECT_TIMEOUT) {
            Ok(s) => {
                let set = |r: io::Result<()>| r.map_err(|e| TcpOpenError::from_io(&shown, &e));
                set(s.set_nodelay(true))?;
                set(s.set_read_timeout(Some(READ_TIMEOUT)))?;
                set(s.set_write_timeout(Some(WRITE_TIMEOUT)))?;
                return Ok(s);
            }
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    Err(match first_error {
        Some(e) => TcpOpenError::from_io(&shown, &e),
        None => TcpOpenError::Resolve {
            addr: shown,
            detail: "the name has no address".into(),
        },
    })
}

/// A [`Connector`] that connects to the same bridge each time it is called.
pub fn tcp_connector(host: String, port: u16) -> Connector {
    Box::new(move || {
        let stream = open_tcp(&host, port).map_err(|e| io::Error::other(e.to_string()))?;
        let writer = stream.try_clone()?;
        let name = PortAddr::Tcp {
            host: host.clone(),
            port,
        }
        .to_string();
        Ok((
            Box::new(SilenceLimited::new(stream, SILENCE_LIMIT)) as _,
            Box::new(writer) as _,
            name,
        ))
    })
}

/// The read half of a TCP link: a read timeout is "nothing yet", as on a serial port,
/// until nothing at all has come for `limit`; then the connection is declared dead so
/// the supervisor reopens it.
pub struct SilenceLimited {
    stream: TcpStream,
    limit: Duration,
    last_byte: Instant,
}

impl SilenceLimited {
    pub fn new(stream: TcpStream, limit: Duration) -> SilenceLimited {
        SilenceLimited {
            stream,
            limit,
            last_byte: Instant::now(),
        }
    }
}

impl Read for SilenceLimited {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        match self.stream.read(buf) {
            Ok(0) => Err(io::Error::new(
                io::ErrorKind::ConnectionAborted,
                "the bridge closed the connection",
            )),
            Ok(n) => {
                self.last_byte = Instant::now();
                Ok(n)
            }
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
                ) && self.last_byte.elapsed() >= self.limit =>
            {
                // Closing both directions also frees the writer's clone of the socket.
                let _ = self.stream.shutdown(Shutdown::Both);
                Err(io::Error::new(
                    io::ErrorKind::TimedOut,
                    format!(
                        "nothing received for {} s; reconnecting",
                        self.limit.as_secs()
                    ),
                ))
            }
            Err(e) => Err(e),
        }
    }
}

// ------------------------------------------------------------------ the device side

/// The device side of a TCP "serial line", for `vpx-efis sim --tcp`: one client at a
/// time, and a new one accepted after it leaves. The unit behind it keeps running
/// between clients, as a real unit does while its cable is unplugged: what it sends
/// with nobody connected is lost, and its state is the same for the next client.
pub struct TcpLine {
    /// What clients send, for the unit to read.
    pub reader: PipeReader,
    /// What the unit sends, for the current client.
    pub writer: LineWriter,
    pub local_addr: SocketAddr,
}

/// Writes to whichever client is connected; with none, the bytes go nowhere.
pub struct LineWriter {
    client: Arc<Mutex<Option<TcpStream>>>,
}

impl Write for LineWriter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let mut client = lock(&self.client);
        if let Some(s) = client.as_mut()
            && s.write_all(buf).is_err()
        {
            // The client has gone; its reader thread will see it too and say so.
            *client = None;
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// Starts accepting on `listener`. `say` gets one line per client that comes, goes or
/// is turned away (a second client while one is connected is closed at once).
pub fn serve_line(
    listener: TcpListener,
    say: impl Fn(String) + Send + Sync + 'static,
) -> io::Result<TcpLine> {
    let local_addr = listener.local_addr()?;
    let (to_unit, reader) = pipe_pair(READ_TIMEOUT);
    let client: Arc<Mutex<Option<TcpStream>>> = Arc::default();
    let busy = Arc::new(Mutex::new(None::<SocketAddr>));
    let say = Arc::new(say);
    let (c, b) = (client.clone(), busy.clone());
    std::thread::Builder::new()
        .name("tcp-accept".into())
        .spawn(move || {
            for stream in listener.incoming() {
                let Ok(stream) = stream else {
                    // A lasting accept error (no file descriptors left) must not spin.
                    std::thread::sleep(Duration::from_millis(100));
                    continue;
                };
                let peer = stream
                    .peer_addr()
                    .unwrap_or_else(|_| SocketAddr::from(([0, 0, 0, 0], 0)));
                let mut current = lock(&b);
                if let Some(other) = *current {
                    say(format!(
                        "turned away {peer}: {other} is connected (one client at a time)"
                    ));
                    let _ = stream.shutdown(Shutdown::Both);
                    continue;
                }
                let _ = stream.set_nodelay(true);
                // A client whose bridge lost power never closes: keepalive probes end
                // it, so the one client slot is freed for the next.
                let _ = socket2::SockRef::from(&stream)
                    .set_tcp_keepalive(&socket2::TcpKeepalive::new().with_time(CLIENT_KEEPALIVE));
                let Ok(write_half) = stream.try_clone() else {
                    continue;
                };
                let _ = write_half.set_write_timeout(Some(WRITE_TIMEOUT));
                *lock(&c) = Some(write_half);
                *current = Some(peer);
                drop(current);
                say(format!("client {peer} connected"));
                let (c, b, say, to_unit) = (c.clone(), b.clone(), say.clone(), to_unit.clone());
                let _ = std::thread::Builder::new()
                    .name("tcp-client".into())
                    .spawn(move || {
                        pump_client(stream, to_unit);
                        *lock(&c) = None;
                        *lock(&b) = None;
                        say(format!("client {peer} left; waiting for the next"));
                    });
            }
        })?;
    Ok(TcpLine {
        reader,
        writer: LineWriter { client },
        local_addr,
    })
}

/// Copies what the client sends to the unit until the client goes.
fn pump_client(mut stream: TcpStream, mut to_unit: PipeWriter) {
    let mut buf = [0u8; 1024];
    loop {
        match stream.read(&mut buf) {
            Ok(0) => return,
            Ok(n) => {
                if to_unit.write_all(&buf[..n]).is_err() {
                    return;
                }
            }
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(_) => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_closed_port_is_refused_in_words() {
        // Bind, note the port, close: nothing listens there now.
        let port = TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let err = open_tcp("127.0.0.1", port).unwrap_err();
        assert!(matches!(err, TcpOpenError::Refused { .. }), "{err:?}");
        let text = err.to_string();
        assert!(text.starts_with(&format!("tcp://127.0.0.1:{port}: connection refused")));
        assert!(text.contains("ser2net"), "{text}");
    }

    #[test]
    fn error_kinds_not_words_decide_the_advice() {
        let of = |k: io::ErrorKind| TcpOpenError::from_io("tcp://h:1", &io::Error::from(k));
        assert!(matches!(
            of(io::ErrorKind::ConnectionRefused),
            TcpOpenError::Refused { .. }
        ));
        assert!(matches!(
            of(io::ErrorKind::TimedOut),
            TcpOpenError::TimedOut { secs: 3, .. }
        ));
        assert!(matches!(
            of(io::ErrorKind::HostUnreachable),
            TcpOpenError::Unreachable { .. }
        ));
        assert!(matches!(
            of(io::ErrorKind::NetworkUnreachable),
            TcpOpenError::Unreachable { .. }
        ));
        assert!(matches!(
            of(io::ErrorKind::PermissionDenied),
            TcpOpenError::Other { .. }
        ));
    }

    #[test]
    fn an_unknown_host_is_a_resolve_error() {
        let err = open_tcp("no-such-host.invalid", 2000).unwrap_err();
        assert!(matches!(err, TcpOpenError::Resolve { .. }), "{err:?}");
        assert!(err.to_string().contains("cannot find the host"), "{err}");
    }

    #[test]
    fn the_line_serves_one_client_at_a_time_and_the_next_after_it_leaves() {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let line = serve_line(listener, |_| {}).unwrap();
        let TcpLine {
            mut reader,
            mut writer,
            local_addr,
        } = line;
        let port = local_addr.port();

        let mut first = open_tcp("127.0.0.1", port).unwrap();
        first.write_all(b"hello").unwrap();
        let mut got = [0u8; 5];
        read_exactly(&mut reader, &mut got);
        assert_eq!(&got, b"hello");
        writer.write_all(b"back").unwrap();
        let mut back = [0u8; 4];
        read_exactly(&mut first, &mut back);
        assert_eq!(&back, b"back");

        // A second client while the first is connected is closed at once.
        let mut second = open_tcp("127.0.0.1", port).unwrap();
        second
            .set_read_timeout(Some(Duration::from_secs(2)))
            .unwrap();
        let mut buf = [0u8; 4];
        assert!(matches!(second.read(&mut buf), Ok(0) | Err(_)));

        // After the first leaves, a new client is served.
        drop(first);
        let end = Instant::now() + Duration::from_secs(3);
        let mut third = loop {
            let mut c = open_tcp("127.0.0.1", port).unwrap();
            c.write_all(b"again").unwrap();
            let mut got = [0u8; 5];
            if try_read_exactly(&mut reader, &mut got, Duration::from_millis(300)) {
                assert_eq!(&got, b"again");
                break c;
            }
            assert!(Instant::now() < end, "the third client was never served");
        };
        writer.write_all(b"ok").unwrap();
        let mut ok = [0u8; 2];
        read_exactly(&mut third, &mut ok);
        assert_eq!(&ok, b"ok");
    }

    #[test]
    fn a_silent_connection_is_declared_dead_after_the_limit() {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = listener.local_addr().unwrap().port();
        let stream = open_tcp("127.0.0.1", port).unwrap();
        let _peer = listener.accept().unwrap();
        let mut r = SilenceLimited::new(stream, Duration::from_millis(200));
        let mut buf = [0u8; 8];
        let started = Instant::now();
        let err = loop {
            match r.read(&mut buf) {
                Err(e) if e.kind() == io::ErrorKind::WouldBlock => continue,
                Err(e) if e.to_string().contains("reconnecting") => break e,
                Err(e) if e.kind() == io::ErrorKind::TimedOut => continue,
                other => panic!("unexpected {other:?}"),
            }
        };
        assert!(started.elapsed() >= Duration::from_millis(200), "{err}");
        assert!(err.to_string().contains("nothing received"), "{err}");
    }

    fn read_exactly(r: &mut impl Read, buf: &mut [u8]) {
        assert!(
            try_read_exactly(r, buf, Duration::from_secs(3)),
            "timed out reading"
        );
    }

    fn try_read_exactly(r: &mut impl Read, buf: &mut [u8], limit: Duration) -> bool {
        let end = Instant::now() + limit;
        let mut at = 0;
        while at < buf.len() {
            if Instant::now() > end {
                return false;
            }
            match r.read(&mut buf[at..]) {
                Ok(0) => std::thread::sleep(Duration::from_millis(5)),
                Ok(n) => at += n,
                Err(_) => {}
            }
        }
        true
    }
}

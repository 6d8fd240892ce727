//! The walk-around remote: the page on a phone at the wingtip, over HTTP.
//!
//! Off until asked for (`--remote`, or the page's key): then an axum server on a
//! current-thread tokio runtime, on a thread of its own, bound only to the address
//! given (or the laptop's LAN address, [`lan_address`]). When off there is no thread
//! and no socket.
//!
//! It stands on the model (the state it serves) and hands every command to the page
//! as a [`Request`] on a channel: the page carries it out through `control` and the
//! stop gate with the origin "remote", and answers. Nothing here sends to the unit.
//!
//! The API is the contract of the guide (`docs/src/remote.md`, and the routes in
//! [`routes`], from which its HTTP API page is generated):
//! [`server`] holds the routes, [`pairing`] the offer and the sessions, [`signing`]
//! the signed requests, [`state`] the JSON state with the model's staleness.
//!
//! What is protected, in one sentence (the overlay and the guide say it too):
//! [`PROTECTED`].

pub mod pairing;
pub mod routes;
pub mod server;
pub mod signing;
pub mod state;

use std::net::{IpAddr, Ipv4Addr, SocketAddr, TcpListener, UdpSocket};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use crossbeam_channel::{Receiver, unbounded};
use tokio::sync::oneshot;

use crate::control::Direction;
use crate::model::{Model, Motor};

pub use state::{Answer, CheckPrompt, PageSide};

/// What a listener on the network can and cannot do, as the overlay and the README
/// say it.
pub const PROTECTED: &str = "Anyone on this WiFi can see the circuits' states, but only a paired phone can act: its key never crosses the network.";

/// The port the remote listens on unless told otherwise.
pub const DEFAULT_PORT: u16 = 8750;

/// What a phone asked the page to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Command {
    Power {
        id: u8,
        on: bool,
    },
    Clear {
        id: u8,
    },
    /// Start or renew the hold-to-run lease.
    Motor {
        motor: Motor,
        direction: Direction,
    },
    /// The finger let go: end the leased run.
    MotorStop,
    /// An answer to the installation check: `go_on`, `skip`, `retry`, `lit_yes`,
    /// `lit_no`.
    CheckAnswer(String),
}

/// The page's answer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reply {
    /// Sent, in words.
    Sent(String),
    /// Refused, in control's words.
    Refused(String),
    NoDevice(u8),
    /// The lease, started or renewed, in milliseconds.
    Leased(u64),
    /// The stop is queued on the link.
    Stopped,
    Answered,
}

/// A command waiting for the page.
#[derive(Debug)]
pub struct Request {
    pub command: Command,
    reply: oneshot::Sender<Reply>,
}

impl Request {
    /// Answers the phone (which may have gone: nothing to do then).
    pub fn answer(self, reply: Reply) {
        let _ = self.reply.send(reply);
    }
}

/// Where the remote listens when given no address: the address of the interface a
/// packet to the LAN would leave by (a UDP socket "connected" to a private address
/// sends nothing), or 127.0.0.1 when there is none. `true` when it fell back.
pub fn lan_address() -> (IpAddr, bool) {
    let probe = || -> std::io::Result<IpAddr> {
        let s = UdpSocket::bind((Ipv4Addr::UNSPECIFIED, 0))?;
        s.connect((Ipv4Addr::new(192, 168, 0, 1), 9))?;
        Ok(s.local_addr()?.ip())
    };
    match probe() {
        Ok(ip) if !ip.is_unspecified() && !ip.is_loopback() => (ip, false),
        _ => (IpAddr::V4(Ipv4Addr::LOCALHOST), true),
    }
}

/// The running remote: the server's thread and what the page shares with it.
pub struct Remote {
    addr: SocketAddr,
    /// The address the page shows: the bound one, or for every address
    /// (`0.0.0.0`) the LAN address, on the bound port.
    shown: SocketAddr,
    shared: Arc<server::Shared>,
    requests: Receiver<Request>,
    stop: Option<oneshot::Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl Remote {
    /// Binds `addr` (port 0 picks a free one) and starts the server's thread.
    pub fn start(addr: SocketAddr, model: Arc<Mutex<Model>>) -> anyhow::Result<Remote> {
        let pairing = pairing::Pairing::new()
            .map_err(|e| anyhow::anyhow!("the remote needs the OS's random source: {e}"))?;
        let listener = TcpListener::bind(addr)
            .map_err(|e| anyhow::anyhow!("the remote could not listen on {addr}: {e}"))?;
        listener.set_nonblocking(true)?;
        let bound = listener.local_addr()?;
        let shared = Arc::new(server::Shared::new(pairing));
        let (tx, requests) = unbounded();
        let (stop, stopped) = oneshot::channel::<()>();
        let router = server::router(shared.clone(), model, tx, bound);
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_io()
            .enable_time()
            .build()?;
        let thread = std::thread::Builder::new()
            .name("remote".into())
            .spawn(move || {
                runtime.block_on(async move {
                    let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                        return;
                    };
                    let serve = std::future::IntoFuture::into_future(axum::serve(listener, router));
                    // The stop ends everything at once, open event streams included.
                    tokio::select! {
                        _ = serve => {}
                        _ = stopped => {}
                    }
                });
            })?;
        let shown = if bound.ip().is_unspecified() {
            SocketAddr::new(lan_address().0, bound.port())
        } else {
            bound
        };
        Ok(Remote {
            addr: bound,
            shown,
            shared,
            requests,
            stop: Some(stop),
            thread: Some(thread),
        })
    }

    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The URL with the pairing key in its fragment, as the QR code holds it.
    pub fn pairing_url(&self) -> String {
        format!("http://{}/#k={}", self.shown, self.shared.pairing().key())
    }

    /// The page's address without the key: what a person types.
    pub fn base_url(&self) -> String {
        format!("http://{}/", self.shown)
    }

    /// The words a phone without a camera types now.
    pub fn words(&self) -> String {
        self.shared.pairing().words().to_string()
    }

    /// How many phones are paired.
    pub fn paired(&self) -> usize {
        self.shared.pairing().paired()
    }

    /// How many of them by typed words.
    pub fn typed(&self) -> usize {
        self.shared.pairing().typed()
    }

    /// Ends every phone's session.
    pub fn revoke_all(&self) {
        self.shared.pairing().revoke_all();
        self.shared.changed.notify_waiters();
    }

    /// The phones' commands, for the page's loop.
    pub fn requests(&self) -> &Receiver<Request> {
        &self.requests
    }

    /// What only the page knows; wakes the event streams if it changed.
    pub fn set_page(&self, page: PageSide) {
        let mut p = self.shared.page.lock().unwrap_or_else(|p| p.into_inner());
        if *p != page {
            *p = page;
            self.shared.changed.notify_waiters();
        }
    }

    /// The model changed: the event streams look again.
    pub fn poke(&self) {
        self.shared.changed.notify_waiters();
    }

    /// Stops the server; every session ends with it.
    pub fn stop(mut self) {
        self.shutdown();
    }

    fn shutdown(&mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Remote {
    fn drop(&mut self) {
        self.shutdown();
    }
}

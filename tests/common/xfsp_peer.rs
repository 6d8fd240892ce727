//! A node on the XFSp network beside the page (`--xfsp` to 127.0.0.1): it hears what
//! the page publishes, learns the page's address from it, and sends it requests.

use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use vpx_efis::xfsp::net::Target;
use vpx_efis::xfsp::{
    Body, Bus, CertLevel, Confidence, EcbState, Message, MsgKind, Parameter, Sender, Value, idents,
};

pub struct PagePeer {
    pub sock: UdpSocket,
    page: Option<SocketAddr>,
}

impl PagePeer {
    pub fn new() -> PagePeer {
        let sock = UdpSocket::bind("127.0.0.1:0").unwrap();
        sock.set_read_timeout(Some(Duration::from_millis(20)))
            .unwrap();
        PagePeer { sock, page: None }
    }

    /// Where the page is to publish: this peer.
    pub fn target(&self) -> Target {
        Target::parse(&self.sock.local_addr().unwrap().to_string()).unwrap()
    }

    /// Runs `pump` (the page's loop) until the page has published parameters that
    /// satisfy `want`, and notes its address; fails after `limit`.
    pub fn wait_for_page(
        &mut self,
        limit: Duration,
        mut pump: impl FnMut(),
        want: impl Fn(&Parameter) -> bool,
    ) {
        let end = Instant::now() + limit;
        let mut buf = [0u8; 2048];
        loop {
            assert!(
                Instant::now() < end,
                "nothing the peer wanted was published"
            );
            pump();
            if let Ok((n, from)) = self.sock.recv_from(&mut buf)
                && let Ok(m) = Message::parse(&buf[..n])
                && let Body::Params(ps) = m.body
                && ps.iter().any(&want)
            {
                self.page = Some(from);
                return;
            }
        }
    }

    /// An ECBSTAT request (USERSEL) for circuit `unit` from source `src`, message 1.
    pub fn ecbstat(&self, src: u16, unit: u16, state: EcbState) {
        let p = Parameter::new(
            idents::ECBSTAT,
            Value::Bus(Bus {
                state,
                ..Bus::default()
            }),
        )
        .unit(unit)
        .confidence(Confidence::UserSel);
        let d = Sender::new(src, 1)
            .pack(MsgKind::flight_data(CertLevel::Experimental), &[p])
            .unwrap()
            .remove(0);
        let page = self.page.expect("heard the page first");
        self.sock.send_to(&d, page).unwrap();
    }
}

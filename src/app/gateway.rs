//! The XFSp gateway on the app's loop: inside the page (`--xfsp`), so circuits,
//! faults and positions go out on the network while the person watches, and network
//! commands show in the event log; and in `vpx-efis gateway`, the same app with no
//! screen.

use std::net::Ipv4Addr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::serve::Wait;
use super::{App, XfspOptions, lock, terminal};
use crate::audit::Origin;
use crate::xfsp::dict::CertLevel;
use crate::xfsp::gateway::{Control, Gateway, GatewayConfig, source_list};
use crate::xfsp::net::{Datagram, Target, XfspNet};

/// A running gateway and its sockets.
pub(super) struct PageGateway {
    pub(super) gateway: Gateway,
    pub(super) net: XfspNet,
    net_error_said: bool,
}

/// Reads `--xfsp`, `--xfsp-iface`, `--xfsp-source-id`, `--xfsp-cert`,
/// `--xfsp-control` and `--xfsp-control-from`. A list without `--xfsp-control` is
/// refused rather than guessed at: naming who may command does not turn commands on.
pub fn xfsp_setup(args: &XfspOptions) -> anyhow::Result<Option<(Target, Ipv4Addr, GatewayConfig)>> {
    let Some(target) = &args.xfsp else {
        return Ok(None);
    };
    let target = Target::parse(target).map_err(anyhow::Error::msg)?;
    let iface = args.xfsp_iface;
    let control = match (args.xfsp_control, &args.xfsp_control_from) {
        (false, None) => Control::Off,
        (true, None) => Control::Any,
        (true, Some(ids)) => Control::From(ids.clone()),
        (false, Some(ids)) => {
            return Err(crate::program::UsageError(format!(
                "--xfsp-control-from ({}) says who may command, but network commands are off: \
                 add --xfsp-control (or xfsp_control = true in the config file)",
                source_list(ids)
            ))
            .into());
        }
    };
    let config = GatewayConfig {
        source_id: args.xfsp_source_id,
        cert: CertLevel::from(args.xfsp_cert),
        control,
        ..GatewayConfig::default()
    };
    Ok(Some((target, iface, config)))
}

impl App {
    /// Opens the XFSp sockets and starts publishing.
    pub fn enable_xfsp(
        &mut self,
        target: &Target,
        iface: Ipv4Addr,
        config: GatewayConfig,
    ) -> anyhow::Result<()> {
        let net = XfspNet::open(target, iface)
            .map_err(|e| anyhow::anyhow!("cannot open XFSp {target} on {iface}: {e}"))?;
        let now = Instant::now();
        lock(&self.model).log(
            now,
            crate::model::LogLevel::Info,
            // Who may command comes first: the panel cuts a long line at its edge.
            format!(
                "XFSp: {}; publishing on {target}",
                config.control.describe()
            ),
        );
        let gateway = Gateway::new(config, now);
        self.gateway = Some(PageGateway {
            gateway,
            net,
            net_error_said: false,
        });
        Ok(())
    }

    /// `vpx-efis gateway`'s front on the app's loop ([`App::serve`]): no screen and no
    /// input; `each_pass` after every tick (the gateway says its new event-log lines).
    /// Returns once `stop` is raised (looked at every `poll` at the latest) or a
    /// thread has panicked.
    pub fn serve_until(
        &mut self,
        stop: &AtomicBool,
        poll: Duration,
        mut each_pass: impl FnMut(&App),
    ) {
        let never = crossbeam_channel::never::<()>();
        let wait = Wait {
            input: &never,
            terminations: &crossbeam_channel::never(),
            until: None,
            poll: Some(poll),
        };
        self.serve(
            wait,
            |app, now| {
                app.no_screen(now);
                each_pass(app);
                (stop.load(Ordering::SeqCst) || terminal::panicked()).then_some(())
            },
            |_, _| None,
        );
    }

    /// The gateway's counters, while XFSp is on (the headless gateway's closing line).
    pub fn xfsp_stats(&self) -> Option<crate::xfsp::gateway::GatewayStats> {
        self.gateway.as_ref().map(|g| g.gateway.stats())
    }

    /// The address the XFSp sockets send from, while XFSp is on.
    pub fn xfsp_local_addr(&self) -> Option<std::net::SocketAddr> {
        self.gateway.as_ref().and_then(|g| g.net.local_addr().ok())
    }

    /// Datagrams from the network, or a channel that never delivers.
    pub(super) fn xfsp_incoming(&self) -> Receiver<Datagram> {
        self.gateway
            .as_ref()
            .map_or_else(crossbeam_channel::never, |g| g.net.incoming().clone())
    }

    pub(super) fn xfsp_receive(&mut self, d: Datagram) {
        let Some(g) = self.gateway.as_mut() else {
            return;
        };
        // Motor requests run through the page's controller, the one way every run
        // goes (`control::How::Target`): the page's keys come first.
        let mut model = lock(&self.model);
        self.controller
            .act_xfsp(|c| (g.gateway.receive(&d.bytes, &mut model, c, d.at), ()));
        // No redraw of its own: what the network changes on screen (a command in the
        // event log, what is forwarded) goes through the model, whose revision `tick`
        // watches. Marking every datagram dirty redrew the page for each of our own,
        // heard back through the multicast loop several times a second.
    }

    pub(super) fn xfsp_tick(&mut self, now: Instant) {
        let Some(g) = self.gateway.as_mut() else {
            return;
        };
        let datagrams = {
            let mut model = lock(&self.model);
            self.controller.act_xfsp(|c| {
                let step = g.gateway.tick(&mut model, c, now);
                (step.to_unit, step.datagrams)
            })
        };
        match g.net.send_all(&datagrams) {
            Err(e) if !g.net_error_said => {
                lock(&self.model).log(
                    now,
                    crate::model::LogLevel::Warning,
                    format!("cannot send on XFSp: {e}"),
                );
                g.net_error_said = true;
            }
            Ok(()) if !datagrams.is_empty() => g.net_error_said = false,
            _ => {}
        }
    }

    pub(super) fn xfsp_deadline(&self) -> Option<Instant> {
        self.gateway.as_ref().map(|g| g.gateway.next_deadline())
    }

    pub(super) fn xfsp_shutdown(&mut self, now: Instant) {
        let Some(g) = self.gateway.as_mut() else {
            return;
        };
        // Leaving is the process's own stop, not the network's.
        let mut model = lock(&self.model);
        self.controller.act_with(Origin::Page, |c| {
            (g.gateway.shutdown(&mut model, c, now), ())
        });
    }
}

//! The page's side of the walk-around remote ([`crate::remote`]): the key that starts
//! and stops it, what the overlay and the title show, the revoke key, and carrying out
//! the phones' commands.
//!
//! Every command from a phone goes the way a key's does: through `control` (the same
//! rules and refusals, in the same words), queued under the controller's lock through
//! the stop gate with the origin "remote" (so the audit log has it), and into the
//! event log as "remote: …". A motor runs by lease ([`crate::control::LEASE`]); any
//! other command from the remote ends the leased run first, and the run also ends on
//! every stop cause a key's run has, since it is the controller's one run.

use std::net::SocketAddr;
use std::time::Instant;

use crossbeam_channel::Receiver;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use super::{App, lock};
use crate::audit::Origin;
use crate::check::state::Step;
use crate::control::commands::{self, Reason};
use crate::control::{Action, LEASE, StopReason};
use crate::model::LogLevel;
use crate::remote::{
    self, Answer, CheckPrompt, Command, DEFAULT_PORT, PageSide, Remote, Reply, Request,
};
use crate::ui::state::{Overlay, RemoteView, Screen};

/// The remote as the page holds it.
#[derive(Default)]
pub(super) struct RemoteSide {
    server: Option<Remote>,
    /// `--remote ADDR:PORT`, for the key to start it on again.
    addr: Option<SocketAddr>,
    /// No LAN address was found: it listens on 127.0.0.1, and the overlay says so.
    loopback_only: bool,
    /// The model's revision the event streams were last told of.
    seen_revision: u64,
    /// The last motor refusal logged: a held button renews ten times a second, and
    /// one line says it.
    refused: Option<String>,
    /// The remote's run at the last look, to log its start and its end.
    run: Option<(crate::model::Motor, crate::control::Direction)>,
}

impl App {
    /// Starts the remote on `addr` (`None`: the LAN address, [`DEFAULT_PORT`]) and
    /// shows its overlay.
    pub fn start_remote(&mut self, addr: Option<SocketAddr>, now: Instant) -> anyhow::Result<()> {
        if self.replay.is_some() {
            anyhow::bail!("the remote is not served while replaying a capture");
        }
        if addr.is_some() {
            self.remote.addr = addr;
        }
        let (addr, fell_back) = match self.remote.addr {
            Some(a) => (a, false),
            None => {
                let (ip, fell_back) = remote::lan_address();
                (SocketAddr::new(ip, DEFAULT_PORT), fell_back)
            }
        };
        let server = Remote::start(addr, self.model.clone())?;
        lock(&self.model).log(
            now,
            LogLevel::Info,
            format!("remote: listening on http://{}", server.addr()),
        );
        self.remote.loopback_only = fell_back;
        self.remote.server = Some(server);
        self.view.overlay = Overlay::Remote;
        self.remote_view();
        Ok(())
    }

    /// Stops the remote: every session ends, a leased run stops.
    pub(super) fn stop_remote(&mut self, now: Instant) {
        if let Some(server) = self.remote.server.take() {
            self.controller.act_with(Origin::Remote, |c| {
                (c.lease_stop(now, StopReason::Quit), ())
            });
            server.stop();
            lock(&self.model).log(now, LogLevel::Info, "remote: stopped".into());
        }
        if self.view.overlay == Overlay::Remote {
            self.view.overlay = Overlay::None;
        }
        self.view.remote = None;
        self.dirty = true;
    }

    /// The remote's URL with its pairing key, while it is on.
    pub fn remote_url(&self) -> Option<String> {
        self.remote.server.as_ref().map(Remote::pairing_url)
    }

    /// The phones' commands (a channel that never delivers while the remote is off).
    pub(super) fn remote_requests(&self) -> Receiver<Request> {
        match &self.remote.server {
            Some(s) => s.requests().clone(),
            None => crossbeam_channel::never(),
        }
    }

    /// `p`: off → on with its overlay; on, overlay hidden → the overlay again; on,
    /// overlay shown → off. `P`: every phone unpaired.
    pub(super) fn remote_key(&mut self, action: Option<&Action>, now: Instant) {
        match action {
            Some(Action::Remote) => match (&self.remote.server, self.view.overlay) {
                (None, _) => {
                    let addr = self.remote.addr;
                    if let Err(e) = self.start_remote(addr, now) {
                        self.set_notice(now, Some(format!("{e:#}")));
                    }
                }
                (Some(_), Overlay::Remote) => self.stop_remote(now),
                (Some(_), _) => self.view.overlay = Overlay::Remote,
            },
            Some(Action::RevokePhones) => {
                let notice = match &self.remote.server {
                    Some(s) => {
                        s.revoke_all();
                        self.controller.act_with(Origin::Remote, |c| {
                            (c.lease_stop(now, StopReason::OtherKey), ())
                        });
                        lock(&self.model).log(
                            now,
                            LogLevel::Info,
                            "remote: every phone unpaired".into(),
                        );
                        "every phone is unpaired: pair again by the QR code".to_string()
                    }
                    None => "the remote is off (p starts it)".to_string(),
                };
                self.set_notice(now, Some(notice));
            }
            _ => return,
        }
        self.remote_view();
        self.dirty = true;
    }

    /// Keeps the overlay, the title and the server's view of the page up to date.
    pub(super) fn remote_tick(&mut self, now: Instant) {
        let Some(server) = &self.remote.server else {
            return;
        };
        let (running, remote_run, stop) = self.controller.with(|c| {
            (
                c.streamer().running_key(),
                c.remote_running(),
                c.last_stop().copied(),
            )
        });
        if remote_run != self.remote.run {
            let mut model = lock(&self.model);
            if let Some((m, d)) = self.remote.run {
                let why = stop.map_or("stopped".into(), |s| s.reason.describe());
                model.log(
                    now,
                    LogLevel::Info,
                    format!("remote: {} {} stopped: {why}", m.name(), d.name()),
                );
            }
            if let Some((m, d)) = remote_run {
                model.log(
                    now,
                    LogLevel::Info,
                    format!("remote: {} {} running", m.name(), d.name()),
                );
            }
            self.remote.run = remote_run;
        }
        server.set_page(PageSide {
            running,
            check: self.check_prompt(),
        });
        let revision = lock(&self.model).revision();
        if revision != self.remote.seen_revision {
            self.remote.seen_revision = revision;
            server.poke();
        }
        self.remote_view();
    }

    fn remote_view(&mut self) {
        let old = self.view.remote.as_ref();
        if let (Some(s), Some(v)) = (&self.remote.server, old)
            && v.paired == s.paired()
            && v.typed == s.typed()
            && v.words == s.words()
        {
            return;
        }
        let view = self.remote.server.as_ref().map(|s| {
            let url = s.pairing_url();
            // The QR code is made again only for a new key.
            let qr = match old {
                Some(v) if v.url == url => v.qr.clone(),
                _ => [4, 2].map(|zone| crate::ui::remote::qr_rows(&url, zone)),
            };
            RemoteView {
                url,
                address: s.base_url(),
                words: s.words(),
                paired: s.paired(),
                typed: s.typed(),
                loopback_only: self.remote.loopback_only,
                qr,
            }
        });
        if view != self.view.remote {
            self.view.remote = view;
            self.dirty = true;
        }
    }

    /// A phone's command: carried out through control, answered, logged.
    pub(super) fn remote_request(&mut self, req: Request, now: Instant) {
        self.dirty = true;
        let reply = match &req.command {
            Command::MotorStop => {
                self.remote.refused = None;
                self.controller.act_with(Origin::Remote, |c| {
                    (c.lease_stop(now, StopReason::RemoteStop), ())
                });
                Reply::Stopped
            }
            Command::Motor { motor, direction } => {
                let (motor, direction) = (*motor, *direction);
                let shared = self.model.clone();
                let result = {
                    let model = lock(&shared);
                    self.controller
                        .act_with(Origin::Remote, |c| c.lease(&model, motor, direction, now))
                };
                match result {
                    Ok(()) => {
                        self.remote.refused = None;
                        Reply::Leased(LEASE.as_millis() as u64)
                    }
                    Err(why) => {
                        let line = format!(
                            "remote: {} {} refused: {}",
                            motor.name(),
                            direction.name(),
                            why.words
                        );
                        if self.remote.refused.as_ref() != Some(&line) {
                            lock(&self.model).log(now, LogLevel::Warning, line.clone());
                            self.remote.refused = Some(line);
                        }
                        Reply::Refused(why.words)
                    }
                }
            }
            Command::Power { id, on } => {
                self.end_lease(now);
                let action = if *on {
                    Action::PowerOn(*id)
                } else {
                    Action::PowerOff(*id)
                };
                self.remote_command(*id, action, now)
            }
            Command::Clear { id } => {
                self.end_lease(now);
                self.remote_command(*id, Action::Reset(*id), now)
            }
            Command::CheckAnswer(answer) => {
                self.end_lease(now);
                self.remote_check_answer(answer, now)
            }
        };
        self.remote_tick(now);
        req.answer(reply);
    }

    /// Any command from the remote but its motor's ends its leased run first, as any
    /// other key does.
    fn end_lease(&mut self, now: Instant) {
        self.controller.act_with(Origin::Remote, |c| {
            (c.lease_stop(now, StopReason::OtherKey), ())
        });
    }

    /// A power or reset command: control's rule, sent through the gate, logged.
    fn remote_command(&mut self, id: u8, action: Action, now: Instant) -> Reply {
        let shared = self.model.clone();
        let model = lock(&shared);
        let result = commands::command(&action, &model, now);
        if result
            .as_ref()
            .is_err_and(|why| matches!(why.reason, Reason::NoSuchDevice | Reason::NotListed))
        {
            return Reply::NoDevice(id);
        }
        let result = self.controller.act_with(Origin::Remote, |c| match result {
            Ok(message) => {
                let cnt = c.next_cnt();
                let p = crate::protocol::message::Packet::request(cnt, message);
                (vec![p], Ok(message))
            }
            Err(why) => (Vec::new(), Err(why.words)),
        });
        drop(model);
        let mut model = lock(&shared);
        let line = commands::said(
            "remote",
            &action,
            &model,
            result.as_ref().map_err(String::as_str),
        );
        let level = if result.is_ok() {
            LogLevel::Info
        } else {
            LogLevel::Warning
        };
        model.log(now, level, line.clone());
        match result {
            Ok(_) => Reply::Sent(line.trim_start_matches("remote: ").to_string()),
            Err(why) => Reply::Refused(why),
        }
    }

    /// The check's DO NOW for the phone, while the check runs on the page: its prompt
    /// and the answers it offers now ([`crate::check::state::CheckView::prompt_answers`]).
    /// "Is it lit?" is its own question on the phone (`lit_question`), answered
    /// `lit_yes` / `lit_no`.
    /// Decision: the confirmation before power is not offered on the phone: what will
    /// be powered is listed on the laptop, and confirmed there.
    fn check_prompt(&self) -> Option<CheckPrompt> {
        if self.view.screen != Screen::Check || self.check_finished() {
            return None;
        }
        let v = self.check_view();
        if v.step == Step::Confirm {
            return None;
        }
        let p = v.prompt.as_ref()?;
        let offered = v.prompt_answers();
        let lit = offered.iter().any(|a| a.id.starts_with("lit_"));
        let answers = offered
            .iter()
            .filter(|a| !a.id.starts_with("lit_"))
            .map(|a| Answer {
                id: a.id,
                label: label_of(a.id),
            })
            .collect();
        Some(CheckPrompt {
            step: v.step.title().to_string(),
            prompt: p.todo.clone(),
            answers,
            lit_question: lit.then(|| "Is it lit?".to_string()),
        })
    }

    /// An answer from the phone, as the key the check takes for it, if offered now.
    fn remote_check_answer(&mut self, answer: &str, now: Instant) -> Reply {
        let offered = if self.check_prompt().is_some() {
            self.check_view().prompt_answers()
        } else {
            Vec::new()
        };
        let key = offered
            .into_iter()
            .find(|a| a.id == answer)
            .and_then(|a| key_code(a.key));
        let Some(key) = key else {
            return Reply::Refused(format!("{answer} is not offered now"));
        };
        lock(&self.model).log(now, LogLevel::Info, format!("remote: check: {answer}"));
        self.check_key(KeyEvent::new(key, KeyModifiers::NONE), now);
        Reply::Answered
    }
}

/// The phone's button words for an answer the check offers.
fn label_of(id: &str) -> &'static str {
    match id {
        "go_on" => "Go on",
        "skip" => "Skip",
        "retry" => "Retry",
        "lit_yes" => "Yes, lit",
        _ => "No, dark",
    }
}

/// The key the check's prompt names, as the page's key event carries it.
fn key_code(key: &str) -> Option<KeyCode> {
    match key {
        "Enter" => Some(KeyCode::Enter),
        k if k.chars().count() == 1 => k.chars().next().map(KeyCode::Char),
        _ => None,
    }
}

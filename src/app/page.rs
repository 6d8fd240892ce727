//! The page: its state (the model, the view, the motor path, the flows), what it does
//! with a key, a link wake-up or a tick, and when it redraws. Everything but the
//! terminal and the input thread (`runner`), so tests can drive it with
//! synthetic keys and a `TestBackend`.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, unbounded};
use crossterm::event::Event as TermEvent;
use ratatui::Terminal;
use ratatui::backend::Backend;

use crate::audit::Origin;
use crate::control::run_state::{ControlState, MotorRun};
use crate::control::{
    Action, Controller, KeyContext, MotorStreamer, RESEND_PERIOD, StopReason, StreamerConfig,
};
use crate::link::{Connector, Link};
use crate::model::Rereader;
use crate::model::{Model, Source};
use crate::protocol::message::Packet;
use crate::ui::palette::ThemeChoice;
use crate::ui::{
    self, state::Overlay, state::ReleaseMode, state::Screen, state::SortOrder, state::ViewState,
};

use super::link_sink::{SharedSink, link_sink};
use super::motor_stream::MotorPath;
use super::serve::{Outside, Wait};
use super::{
    QueryPacer, Recorder, StopGate, Terminated, Termination, check, gateway, lock, replay, terminal,
};

/// The screen is redrawn at most this often (coalescing the 10 Hz FLAP_TRIM_STATUS
/// with everything else) …
pub(super) const MIN_FRAME_GAP: Duration = Duration::from_millis(33);
/// … and at least this often, so ages tick and COMMUNICATION LOST appears on time
/// even when nothing arrives.
pub(super) const IDLE_REDRAW: Duration = Duration::from_millis(1000);
/// A change from the link is drawn this long after it arrived, not at once: the unit
/// sends its 1 Hz SYSTEM_STATUS, DEVICE_STATUS and FAULT_STATUS back to back (140
/// bytes, 24 ms at 5760 bytes a second), and drawn at the first frame they cost two
/// redraws a second instead of one, about half of an idle page's CPU.
const LINK_SETTLE: Duration = MIN_FRAME_GAP;
/// How long a notice stays on screen.
const NOTICE_FOR: Duration = Duration::from_secs(5);

/// Why the link woke the main loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wake {
    Data,
    Connected,
    LinkDown,
    WriteError,
    /// The motor-stream thread ended a run (dead man, run cap): show it.
    Motor,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    Continue,
    Quit,
}

#[derive(Debug, Clone)]
pub struct AppOptions {
    /// Longest continuous motor run before the key must be pressed again.
    pub max_run: Duration,
    pub release_mode: ReleaseMode,
    /// The palette, chosen before the terminal was taken.
    pub theme: ThemeChoice,
    /// `--repeat-delay`: how long the first hold waits for the first key repeat, set
    /// by hand instead of learned.
    pub repeat_delay: Option<Duration>,
    /// The logbook ([`crate::logbook`]) and the aircraft to record under: every
    /// command sent (the audit log), with its origin, every check, setup write and
    /// fault. `None` records nothing (tests that do not look at it).
    pub logbook: Option<crate::logbook::Target>,
}

impl Default for AppOptions {
    fn default() -> Self {
        AppOptions {
            max_run: Duration::from_secs(10),
            release_mode: ReleaseMode::AutoRepeat,
            theme: ThemeChoice::default(),
            repeat_delay: None,
            logbook: None,
        }
    }
}

/// The page: everything but the terminal and the input thread, so tests can drive it
/// with synthetic keys and a `TestBackend`.
pub struct App {
    pub(super) model: Arc<Mutex<Model>>,
    pub(super) view: ViewState,
    /// The motor controller, shared with the motor-stream thread.
    pub(super) controller: Arc<MotorPath>,
    pub(super) motor_thread: Option<std::thread::JoinHandle<()>>,
    pub(super) link: Option<Link>,
    /// The app's one way to the wire: every packet the page sends goes through here;
    /// `None` in replay.
    pub(super) gate: Option<Arc<StopGate>>,
    /// The logbook's way in: records, and its problems for the event log.
    pub(super) logbook: Option<crate::logbook::Recorder>,
    /// What the logbook was last told of the unit.
    pub(super) told: super::logbook::Told,
    pub(super) wake_rx: Receiver<Wake>,
    pub(super) pacer: QueryPacer,
    pub(super) notice_until: Option<Instant>,
    pub(super) dirty: bool,
    /// When the link made the screen dirty (and nothing else had): drawn
    /// [`LINK_SETTLE`] later, with whatever else came meanwhile.
    pub(super) news_at: Option<Instant>,
    pub(super) last_draw: Option<Instant>,
    pub(super) drawn_revision: u64,
    /// The controller's state the last frame showed (read from it when drawing).
    pub(super) drawn_control: ControlState,
    pub(super) gateway: Option<gateway::PageGateway>,
    /// `--record`: the link sink writes every byte here.
    pub(super) recorder: Option<Recorder>,
    /// `--replay`: the page is read-only and runs on the capture's clock.
    pub(super) replay: Option<replay::Replay>,
    /// Traffic entries at the last draw, so the traffic screen redraws as frames come.
    pub(super) traffic_drawn: u64,
    /// The setup screens' writes waiting for the unit, and their timed requests.
    pub(super) setup: crate::setup::flow::SetupFlow,
    /// Asks again for any setting a write left unknown, until the unit answers.
    pub(super) rereader: Rereader,
    /// The re-read after a loss the app last started asking for (`model::reread`).
    pub(super) reread_asked: Option<Instant>,
    /// The installation check (`i`), its view and its results in words.
    pub(super) check: check::CheckState,
    /// The walk-around remote, while it is on.
    pub(super) remote: super::remote::RemoteSide,
}

impl App {
    pub fn new(source: Source, connector: Connector, options: AppOptions) -> App {
        App::build(source, options, None, |sink, _| {
            (Link::start(connector, move |e| sink(e)), None)
        })
    }

    /// Starts the link through `start`, which gets the sink that feeds the model (a
    /// replay wraps it); `recorder` gets every byte.
    pub(super) fn build(
        source: Source,
        options: AppOptions,
        recorder: Option<Recorder>,
        start: impl FnOnce(SharedSink, Arc<Mutex<Model>>) -> (Link, Option<replay::Replay>),
    ) -> App {
        let model = Arc::new(Mutex::new(Model::new(source)));
        let (wake_tx, wake_rx) = unbounded();
        let sink: SharedSink =
            Arc::new(link_sink(model.clone(), wake_tx.clone(), recorder.clone()));
        let (link, replay) = start(sink, model.clone());
        let mut config = StreamerConfig {
            max_run: options.max_run,
            release_mode: options.release_mode,
            ..Default::default()
        };
        if let Some(d) = options.repeat_delay {
            config.first_repeat_timeout = d;
            config.first_repeat_fixed = true;
        }
        let controller = Controller::new(config);
        let view = ViewState {
            theme: options.theme,
            ..Default::default()
        };
        // A replay is read-only: no link for motors, and no thread to send on it.
        let (logbook, logbook_failed) = match options.logbook.clone().filter(|_| replay.is_none()) {
            // The thread runs on its own; `shutdown` waits for its last records.
            Some(t) => match crate::logbook::Recorder::start(t.path, t.aircraft) {
                Ok((r, _thread)) => (Some(r), None),
                Err(e) => (
                    None,
                    Some(format!("logbook: its thread could not start ({e})")),
                ),
            },
            None => (None, None),
        };
        if let Some(why) = logbook_failed {
            lock(&model).log(Instant::now(), crate::model::LogLevel::Warning, why);
        }
        if let Some(book) = &logbook {
            lock(&model).aircraft = Some(crate::model::Aircraft {
                registration: book.aircraft().map(str::to_string),
                was_in: None,
            });
        }
        let gate = replay
            .is_none()
            .then(|| Arc::new(StopGate::with_logbook(link.handle(), logbook.clone())));
        let controller = MotorPath::new(controller, gate.clone());
        let motor_thread = if replay.is_none() {
            controller.spawn(wake_tx)
        } else {
            None
        };
        App {
            model,
            view,
            controller,
            motor_thread,
            link: Some(link),
            gate,
            logbook,
            told: Default::default(),
            wake_rx,
            pacer: QueryPacer::default(),
            notice_until: None,
            dirty: true,
            news_at: None,
            last_draw: None,
            drawn_revision: 0,
            drawn_control: ControlState::default(),
            gateway: None,
            recorder,
            replay,
            traffic_drawn: 0,
            setup: Default::default(),
            rereader: Rereader::default(),
            reread_asked: None,
            check: Default::default(),
            remote: Default::default(),
        }
    }

    pub fn model(&self) -> MutexGuard<'_, Model> {
        lock(&self.model)
    }

    pub fn view(&self) -> &ViewState {
        &self.view
    }

    /// The motor run the controller is streaming now, as the screen draws it.
    pub fn motor_run(&self) -> Option<MotorRun> {
        self.controller.running()
    }

    /// The controller's state as the screens draw it, read from it now.
    pub fn control_state(&self) -> ControlState {
        self.controller.with(|c| ControlState {
            run: c.running(),
            release_mode: c.release_mode(),
            // A replay runs no motors: nothing to say about key repeats.
            repeat: self.replay.is_none().then(|| c.repeat_timing()),
        })
    }

    /// Queues `packets` for `origin` (the audit log records the commands among them).
    pub(super) fn send(&self, origin: Origin, packets: Vec<Packet>) {
        // A replay (no gate) is read-only: it never puts anything on a wire.
        if let Some(gate) = &self.gate {
            gate.send(origin, packets);
        }
    }

    /// Makes the panic hook's first act the stop of every motor, queued through the
    /// page's own way to the wire so that nothing queued after it moves a motor.
    pub fn arm_emergency_stop(&self) {
        if let Some(gate) = self.gate.clone() {
            terminal::set_emergency_stop(move || {
                gate.emergency_stop();
                // Give the writer thread a moment to put the stops on the wire.
                std::thread::sleep(Duration::from_millis(50));
            });
        }
    }

    pub(super) fn set_notice(&mut self, now: Instant, notice: Option<String>) {
        if let Some(n) = notice {
            self.view.notice = Some(n);
            self.notice_until = Some(now + NOTICE_FOR);
            self.dirty = true;
        }
    }

    /// A terminal event: keys, focus, resize.
    pub fn handle_term_event(&mut self, event: TermEvent, now: Instant) -> Flow {
        self.dirty = true;
        if terminal::panicked() {
            // The hook has sent the emergency stop and the loop is on its way out; a
            // key (a repeat late enough to count as a new press) must not restart a
            // motor in between.
            return Flow::Continue;
        }
        if let TermEvent::Resize(w, h) = event {
            self.set_page_size(w, h, now);
        }
        if let TermEvent::Key(key) = event
            && self.page_hidden()
        {
            return self.hidden_key(key, now);
        }
        if let Some(flow) = self.replay_key(&event, now) {
            return flow;
        }
        match event {
            TermEvent::Key(key) if self.view.screen == Screen::Traffic => {
                return self.traffic_key(key, now);
            }
            TermEvent::Key(key) if self.view.screen == Screen::Setup => {
                return self.setup_key(key, now);
            }
            TermEvent::Key(key) if self.view.screen == Screen::Check => {
                return self.check_key(key, now);
            }
            TermEvent::Key(key) => {
                let shared = self.model.clone();
                let outcome = {
                    let model = lock(&shared);
                    let rows = ui::ordered_circuits(&model, &self.view, now);
                    let ctx = self.view.key_context(&rows);
                    let outcome = self.controller.handle_key(key, &ctx, &model, now);
                    if let Some(action) = &outcome.action {
                        self.apply_view_action(action, &rows);
                    }
                    outcome
                };
                // The person's own commands go in the event log, sent or refused.
                if let Some(a) = outcome.action.as_ref().filter(|a| a.is_command()) {
                    let mut model = lock(&self.model);
                    let (level, line) = match (&outcome.sent, &outcome.notice) {
                        (Some(m), _) => (
                            crate::model::LogLevel::Info,
                            crate::control::commands::said("key", a, &model, Ok(m)),
                        ),
                        (None, why) => (
                            crate::model::LogLevel::Warning,
                            crate::control::commands::said(
                                "key",
                                a,
                                &model,
                                Err(why.as_deref().unwrap_or("nothing sent")),
                            ),
                        ),
                    };
                    model.log(now, level, line);
                }
                self.set_notice(now, outcome.notice);
                if outcome.action == Some(Action::Quit) {
                    return Flow::Quit;
                }
                if outcome.action == Some(Action::InstallCheck) {
                    self.open_check_from_list(now);
                }
                self.remote_key(outcome.action.as_ref(), now);
            }
            TermEvent::FocusGained => {
                self.controller.with(|c| c.on_focus_gained(now));
            }
            TermEvent::FocusLost => {
                self.controller.act_on_run(|c| c.on_focus_lost(now));
                let n = self.controller.take_notice();
                self.set_notice(now, n);
            }
            _ => {}
        }
        Flow::Continue
    }

    /// The terminal's size, from a resize or a draw. The moment the page no longer
    /// fits, a running motor stops with its stop message: nothing the person cannot
    /// see may keep moving. The selection stays where it was.
    fn set_page_size(&mut self, width: u16, height: u16, now: Instant) {
        let hidden = width < ui::MIN_WIDTH || height < ui::MIN_HEIGHT;
        if hidden != self.page_hidden() {
            self.controller
                .act_on_run(|c| c.set_page_hidden(now, hidden));
            let n = self.controller.take_notice();
            self.set_notice(now, n);
            self.dirty = true;
        }
    }

    /// The terminal is too small to show the page: keys do nothing but quit.
    /// The controller's, which refuses the check's runs meanwhile: one place knows.
    pub(super) fn page_hidden(&self) -> bool {
        self.controller.with(|c| c.page_hidden())
    }

    /// A key while the page is too small to be seen: only quit acts (on the device
    /// list; elsewhere only Ctrl-C quits, since `q` may be text there). Decision: `?`
    /// does nothing, as help opened unseen would be there, unasked, once the page
    /// fits; the too-small screen says which keys act. Esc still closes a help left
    /// open.
    fn hidden_key(&mut self, key: crossterm::event::KeyEvent, now: Instant) -> Flow {
        let on_devices = self.view.screen == Screen::Devices;
        let shared = self.model.clone();
        let (handled, rows) = {
            let model = lock(&shared);
            let rows = ui::ordered_circuits(&model, &self.view, now);
            let ctx = if on_devices {
                self.view.key_context(&rows)
            } else {
                KeyContext::default()
            };
            (self.controller.handle_key_hidden(key, &ctx, now), rows)
        };
        self.set_notice(now, handled.notice);
        let ctrl_c = key
            .modifiers
            .contains(crossterm::event::KeyModifiers::CONTROL)
            && matches!(key.code, crossterm::event::KeyCode::Char('c' | 'C'));
        match handled.action {
            Some(Action::Quit) if on_devices || ctrl_c => Flow::Quit,
            Some(a @ Action::CloseOverlay) if on_devices => {
                self.apply_view_action(&a, &rows);
                Flow::Continue
            }
            _ => Flow::Continue,
        }
    }

    pub(super) fn apply_view_action(&mut self, action: &Action, rows: &[crate::model::Circuit]) {
        let pos = self
            .view
            .selected
            .and_then(|id| rows.iter().position(|c| c.id == id));
        match action {
            Action::SelectNext => {
                let next = pos.map_or(0, |p| (p + 1).min(rows.len().saturating_sub(1)));
                self.view.selected = rows.get(next).map(|c| c.id);
            }
            Action::SelectPrev => {
                let prev = pos.map_or(0, |p| p.saturating_sub(1));
                self.view.selected = rows.get(prev).map(|c| c.id);
            }
            Action::ToggleSort => {
                self.view.sort = match self.view.sort {
                    SortOrder::Pin => SortOrder::Alphabetical,
                    SortOrder::Alphabetical => SortOrder::Pin,
                }
            }
            Action::ToggleHelp => {
                self.view.overlay = if self.view.overlay == Overlay::Help {
                    Overlay::None
                } else {
                    Overlay::Help
                }
            }
            Action::CloseOverlay => self.view.overlay = Overlay::None,
            Action::TrafficView => self.view.screen = Screen::Traffic,
            Action::Setup => {
                self.view.screen = Screen::Setup;
                self.reload_wires();
            }
            _ => {}
        }
    }

    /// Something arrived from the link. Call [`App::tick`] once the wake-ups waiting
    /// have been drained.
    pub fn on_wake(&mut self, wake: Wake, now: Instant) {
        match wake {
            Wake::Connected => {
                // Whatever ran before the port came back (a pulled cable mid-run) is
                // told to stop on the new connection before anything else.
                self.send(
                    Origin::Page,
                    MotorStreamer::emergency_stop_packets().to_vec(),
                );
                self.pacer.start(now);
                self.rereader.connected(now);
            }
            Wake::LinkDown => {
                self.pacer.stop();
                self.rereader.link_down();
            }
            Wake::WriteError => {
                self.controller.stop(now, StopReason::LinkError);
                let n = self.controller.take_notice();
                self.set_notice(now, n);
            }
            Wake::Data | Wake::Motor => {}
        }
        // No tick here: both loops tick right after draining the wake-ups, so a
        // motor fault in the packets just applied is seen at once, and a burst of N
        // frames costs one tick, not N + 1.
    }

    /// Everything time-driven: motor resends and dead-man timeouts, query batches,
    /// notice expiry, and whether the screen needs a redraw.
    pub fn tick(&mut self, now: Instant) {
        if terminal::panicked() {
            // The hook has sent the emergency stop; make sure nothing here resends a
            // move after it. The run loop then leaves.
            self.controller.stop(now, StopReason::Panic);
            self.check_interrupt(crate::check::Cause::Panic, false, now);
            self.xfsp_shutdown(now);
            return;
        }
        let (ticked, queries) = {
            let model = lock(&self.model);
            // A reset's answer can change with no packet (its FAULT_STATUS overdue).
            let timed = self
                .last_draw
                .and_then(|t| model.next_change(t))
                .is_some_and(|t| now >= t);
            if (model.revision() != self.drawn_revision || timed) && !self.dirty {
                self.dirty = true;
                self.news_at = Some(now);
            }
            let ticked = self.controller.tick(&model, now);
            // Data back after a loss: the whole connect set at once, answer-paced,
            // not at the next minute's refresh; what it misses is asked again.
            let reread = model.rereading();
            if reread.is_some() && reread != self.reread_asked {
                self.pacer.start(now);
                self.rereader.connected(now);
            }
            self.reread_asked = reread;
            let controller = &self.controller;
            (
                ticked,
                self.pacer.due(now, &model, || controller.next_cnt()),
            )
        };
        self.send(Origin::Page, queries);
        {
            let shared = self.model.clone();
            let mut model = lock(&shared);
            self.tell_logbook(&mut model);
        }
        if let Some(why) = self
            .logbook
            .as_ref()
            .and_then(crate::logbook::Recorder::take_problem)
        {
            lock(&self.model).log(now, crate::model::LogLevel::Warning, why);
        }
        self.set_notice(now, ticked.notice);
        // A run started or ended since the last frame (whoever started or ended it),
        // or the repeat timing was learned.
        let control = ControlState {
            run: ticked.running,
            release_mode: ticked.release_mode,
            repeat: self.replay.is_none().then_some(ticked.repeat),
        };
        if control != self.drawn_control {
            self.dirty = true;
        }
        self.setup_tick(now);
        self.check_tick(now);
        self.reread_tick(now);
        self.traffic_tick();
        self.xfsp_tick(now);
        self.remote_tick(now);
        if self.notice_until.is_some_and(|t| now >= t) {
            self.view.notice = None;
            self.notice_until = None;
            self.dirty = true;
        }
        if self
            .last_draw
            .is_none_or(|t| now.saturating_duration_since(t) >= IDLE_REDRAW)
        {
            self.dirty = true;
        }
    }

    /// Settings left unknown by an unanswered write are asked for again, paced, until
    /// the unit answers (whichever flow wrote them).
    fn reread_tick(&mut self, now: Instant) {
        let queries = self.rereader.due(&lock(&self.model), now);
        for q in queries {
            let cnt = self.controller.next_cnt();
            self.send(Origin::Page, vec![Packet::request(cnt, q)]);
        }
    }

    /// The earliest moment the main loop must call [`App::tick`] again.
    pub fn next_deadline(&self, now: Instant) -> Instant {
        let redraw = match self.last_draw {
            Some(t) if self.dirty => self.redraw_from(t),
            Some(t) => t + IDLE_REDRAW,
            None => now,
        };
        // The motor-stream thread keeps the resend deadline and wakes this loop
        // (Wake::Motor) when a run ends; but while a run is on, this loop still ticks
        // every resend period, so COMMUNICATION LOST or a motor fault stops it on time
        // and the thread sees the loop alive.
        let motor = self.controller.running().map(|_| now + RESEND_PERIOD);
        let (reread, reset_answer) = {
            let model = lock(&self.model);
            (
                self.rereader.next_deadline(&model, now),
                model.next_change(now),
            )
        };
        [
            motor,
            self.pacer.next_deadline(),
            self.notice_until,
            self.xfsp_deadline(),
            self.setup.next_deadline(),
            self.check_deadline(),
            reread,
            reset_answer,
            Some(redraw),
        ]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(now + IDLE_REDRAW)
    }

    /// Draws if something changed and the last frame is old enough.
    pub fn draw_if_needed<B: Backend>(
        &mut self,
        terminal: &mut Terminal<B>,
        now: Instant,
    ) -> std::io::Result<bool> {
        if !self.dirty || self.last_draw.is_some_and(|t| now < self.redraw_from(t)) {
            return Ok(false);
        }
        self.draw(terminal, now)?;
        Ok(true)
    }

    /// Draws now.
    pub fn draw<B: Backend>(
        &mut self,
        terminal: &mut Terminal<B>,
        now: Instant,
    ) -> std::io::Result<()> {
        let err = |e: B::Error| std::io::Error::other(e.to_string());
        terminal.autoresize().map_err(err)?;
        let area = terminal.get_frame().area();
        self.set_page_size(area.width, area.height, now);
        {
            let model = lock(&self.model);
            if self.view.selected.is_none() {
                self.view.selected = ui::ordered_circuits(&model, &self.view, now)
                    .first()
                    .map(|c| c.id);
            }
            let control = self.control_state();
            if self.view.screen == Screen::Check {
                let mut frame = terminal.get_frame();
                let area = frame.area();
                let check = self.check_view();
                ui::check::draw(
                    &mut frame,
                    area,
                    check,
                    &model,
                    &self.view,
                    control.run,
                    now,
                );
            } else {
                ui::draw(&mut terminal.get_frame(), &model, &self.view, &control, now);
            }
            self.drawn_revision = model.revision();
            self.drawn_control = control;
        }
        // The terminal write happens without the model lock: a slow terminal must not
        // hold up the link's reader and writer, which take the lock for every frame.
        terminal.apply_buffer().map_err(err)?;
        self.dirty = false;
        self.news_at = None;
        self.last_draw = Some(now);
        Ok(())
    }

    /// When a dirty screen may be drawn, the last frame drawn at `last`.
    pub(super) fn redraw_from(&self, last: Instant) -> Instant {
        let settled = self.news_at.map(|t| t + LINK_SETTLE);
        (last + MIN_FRAME_GAP).max(settled.unwrap_or(last))
    }

    /// Runs the link, the XFSp network and timers (no input) until `until`: for tests
    /// and for replay.
    pub fn pump_until(&mut self, until: Instant) {
        let never = crossbeam_channel::never::<()>();
        self.serve(
            Wait {
                input: &never,
                terminations: &crossbeam_channel::never(),
                until: Some(until),
                poll: None,
            },
            |app, _| {
                // Keep the draw bookkeeping moving as the page would.
                let now = Instant::now();
                if app.dirty && app.last_draw.is_none_or(|t| now >= app.redraw_from(t)) {
                    app.last_draw = Some(now);
                    app.dirty = false;
                    app.news_at = None;
                    app.drawn_revision = lock(&app.model).revision();
                    app.drawn_control = app.control_state();
                }
                None::<()>
            },
            |_, _| None,
        );
    }

    /// Stops any motor, lets the writer flush, and closes the link.
    pub fn shutdown(mut self) {
        self.stop_everything();
    }

    fn stop_everything(&mut self) {
        let now = Instant::now();
        self.controller.stop(now, StopReason::Quit);
        // A check still running switches its circuit back off before the link closes.
        self.check_interrupt(crate::check::Cause::Quit, false, now);
        self.controller.stop_thread();
        if let Some(t) = self.motor_thread.take() {
            let _ = t.join();
        }
        self.xfsp_shutdown(now);
        self.stop_remote(now);
        if let Some(link) = self.link.take() {
            // Queued packets (the stop above) are written before the link closes.
            link.shutdown();
        }
        // The last records (the stops just sent) are in the file before we leave; a
        // logbook locked by another program is not waited for past this.
        if let Some(book) = &self.logbook {
            book.flush(crate::logbook::SHUTDOWN_WAIT);
        }
    }

    /// The page's front on the app's loop ([`App::serve`]): terminal input, drawing.
    /// A [`Termination`] (SIGTERM, SIGHUP, SIGINT, a closed console) leaves it as `q`
    /// does, returning [`Terminated`]; the caller's shutdown then puts the motor stop
    /// on the wire.
    pub fn run<B: Backend>(
        &mut self,
        terminal: &mut Terminal<B>,
        input: &Receiver<TermEvent>,
        terminations: &Receiver<Termination>,
    ) -> anyhow::Result<()> {
        let wait = Wait {
            input,
            terminations,
            until: None,
            poll: None,
        };
        let ended = self.serve(
            wait,
            |app, now| {
                if terminal::panicked() {
                    return Some(Err(anyhow::anyhow!(
                        "a thread of the page panicked; motors were sent their stop"
                    )));
                }
                app.draw_if_needed(terminal, now)
                    .err()
                    .map(|e| Err(e.into()))
            },
            |app, outside| match outside {
                Outside::Input(ev) => {
                    (app.handle_term_event(ev, Instant::now()) == Flow::Quit).then_some(Ok(()))
                }
                Outside::InputEnded => {
                    // No release can arrive any more: stop before waiting for a signal.
                    app.controller.stop(Instant::now(), StopReason::Quit);
                    app.check_interrupt(crate::check::Cause::Quit, false, Instant::now());
                    Some(Err(input_closed(terminations)))
                }
                Outside::Signal(t) => {
                    app.check_interrupt(
                        crate::check::Cause::Signal(t.name().into()),
                        false,
                        Instant::now(),
                    );
                    Some(Err(Terminated(t).into()))
                }
            },
        );
        ended.unwrap_or(Ok(()))
    }
}

/// Why the page ends when its terminal input closes. A closed terminal window ends
/// the input and sends SIGHUP; whichever comes first, the signal names the exit.
pub(super) fn input_closed(terminations: &Receiver<Termination>) -> anyhow::Error {
    match terminations.recv_timeout(Duration::from_millis(200)) {
        Ok(t) => Terminated(t).into(),
        Err(_) => anyhow::anyhow!("the terminal input stopped"),
    }
}

impl Drop for App {
    /// The drop guard: whatever path leaves the page, a running motor gets its stop.
    fn drop(&mut self) {
        self.stop_everything();
    }
}

//! Owning the terminal: raw mode, the alternate screen, focus reports and keyboard
//! enhancement, and giving all of it back on every exit path, panic included.

use std::io::{self, Stdout, Write};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use crossterm::event::{
    DisableFocusChange, EnableFocusChange, KeyboardEnhancementFlags, PopKeyboardEnhancementFlags,
    PushKeyboardEnhancementFlags,
};
use crossterm::execute;
use crossterm::terminal::{
    EnterAlternateScreen, LeaveAlternateScreen, disable_raw_mode, enable_raw_mode,
};
use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;

/// Whether we pushed keyboard-enhancement flags, so restore pops exactly what we pushed.
static ENHANCED: AtomicBool = AtomicBool::new(false);
static ACTIVE: AtomicBool = AtomicBool::new(false);
/// Set by the panic hook. A panic on another thread (the link's reader, say) leaves
/// the main loop running, and its next resend would undo the emergency stop; the loop
/// checks this and stops for good.
static PANICKED: AtomicBool = AtomicBool::new(false);
/// Run first by the panic hook: stops any motor before anything else happens.
static EMERGENCY_STOP: Mutex<Option<Box<dyn Fn() + Send>>> = Mutex::new(None);

pub type Tui = Terminal<CrosstermBackend<Stdout>>;

/// Restores the terminal when dropped.
pub struct TerminalGuard {
    pub terminal: Tui,
    /// The terminal reports key release (kitty keyboard protocol).
    pub key_release: bool,
}

impl TerminalGuard {
    pub fn enter() -> anyhow::Result<Self> {
        install_panic_hook();
        enable_raw_mode()
            .map_err(|e| anyhow::anyhow!("cannot put the terminal in raw mode: {e}"))?;
        ACTIVE.store(true, Ordering::SeqCst);
        let mut out = io::stdout();
        execute!(out, EnterAlternateScreen, EnableFocusChange)?;
        let key_release = matches!(
            crossterm::terminal::supports_keyboard_enhancement(),
            Ok(true)
        );
        if key_release {
            execute!(
                out,
                PushKeyboardEnhancementFlags(
                    KeyboardEnhancementFlags::DISAMBIGUATE_ESCAPE_CODES
                        | KeyboardEnhancementFlags::REPORT_EVENT_TYPES
                )
            )?;
            ENHANCED.store(true, Ordering::SeqCst);
        }
        let terminal = Terminal::new(CrosstermBackend::new(out))?;
        Ok(TerminalGuard {
            terminal,
            key_release,
        })
    }
}

impl Drop for TerminalGuard {
    fn drop(&mut self) {
        restore();
        let _ = self.terminal.show_cursor();
    }
}

/// Gives the terminal back. Safe to call more than once and from the panic hook.
pub fn restore() {
    if !ACTIVE.swap(false, Ordering::SeqCst) {
        return;
    }
    let mut out = io::stdout();
    if ENHANCED.swap(false, Ordering::SeqCst) {
        let _ = execute!(out, PopKeyboardEnhancementFlags);
    }
    let _ = execute!(
        out,
        DisableFocusChange,
        LeaveAlternateScreen,
        crossterm::cursor::Show
    );
    let _ = disable_raw_mode();
    let _ = out.flush();
}

/// Whether any thread has panicked since the hook was installed.
pub fn panicked() -> bool {
    PANICKED.load(Ordering::SeqCst)
}

/// Registers what the panic hook must do first: the process's emergency stop (every
/// motor's stop through the app's [`super::StopGate`]; for `flash`, its stop at the
/// next safe point).
pub fn set_emergency_stop(f: impl Fn() + Send + 'static) {
    if let Ok(mut slot) = EMERGENCY_STOP.lock() {
        *slot = Some(Box::new(f));
    }
}

pub fn clear_emergency_stop() {
    if let Ok(mut slot) = EMERGENCY_STOP.lock() {
        *slot = None;
    }
}

/// Installs (once) the hook that, on any panic, first runs the emergency stop, then
/// gives the terminal back, then prints the panic as usual.
pub fn install_panic_hook() {
    static INSTALLED: AtomicBool = AtomicBool::new(false);
    if INSTALLED.swap(true, Ordering::SeqCst) {
        return;
    }
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        PANICKED.store(true, Ordering::SeqCst);
        // try_lock: a panic while the slot is held must not deadlock the hook.
        if let Ok(slot) = EMERGENCY_STOP.try_lock()
            && let Some(stop) = slot.as_ref()
        {
            stop();
        }
        restore();
        previous(info);
    }));
}

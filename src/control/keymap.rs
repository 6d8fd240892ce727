//! Keys to actions. Pure: a crossterm [`KeyEvent`] and what is selected give an
//! [`Action`]; nothing is sent from here.
//!
//! The rule for motors: **navigation keys never run a motor.** ↑/↓ and j/k move the
//! selection on every row, flaps and trim included, so scrolling through the list can
//! never start a motor. A motor runs only on its own keys, and only while its row is
//! selected:
//!
//! | row                    | up / left           | down / right          |
//! |------------------------|---------------------|-----------------------|
//! | flaps, pitch trim      | `Shift+↑` or `u`    | `Shift+↓` or `d`      |
//! | roll trim              | `Shift+←` or `,`/`<`| `Shift+→` or `.`/`>`  |
//!
//! On any other row these keys do nothing but say where they work.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use crate::model::{Circuit, CircuitKind, CircuitState, Motor, TrimKind};
use crate::ui::state::{Overlay, ViewState};

use super::streamer::Direction;

/// The selected row, as far as the keys care.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Selected {
    pub id: u8,
    pub kind: CircuitKind,
    pub state: CircuitState,
}

impl Selected {
    /// The motor this row runs, if it is a flaps or trim row.
    pub fn motor(&self) -> Option<Motor> {
        match self.kind {
            CircuitKind::Flaps => Some(Motor::Flaps),
            CircuitKind::Trim(k) => Some(Motor::Trim(k)),
            _ => None,
        }
    }
}

/// What the keymap needs to know about the screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct KeyContext {
    pub selected: Option<Selected>,
    pub overlay_open: bool,
    /// Motor keys here may run past the configured endpoints: the setup screens,
    /// where they are how a person finds new ones (`control::endpoints`).
    pub past_endpoints: bool,
}

impl KeyContext {
    /// The context for the view's selection among `circuits` (the rows on screen).
    pub fn from_view(view: &ViewState, circuits: &[Circuit]) -> Self {
        KeyContext {
            selected: view.selected.and_then(|id| {
                circuits.iter().find(|c| c.id == id).map(|c| Selected {
                    id: c.id,
                    kind: c.kind,
                    state: c.state,
                })
            }),
            overlay_open: view.overlay != Overlay::None,
            past_endpoints: false,
        }
    }

    pub fn motor_selected(&self) -> Option<Motor> {
        self.selected.and_then(|s| s.motor())
    }
}

/// Whether a motor key event is a press or a repeat the terminal marked as such.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyPhase {
    Press,
    Repeat,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Action {
    SelectPrev,
    SelectNext,
    /// A motor key on its motor's row.
    Motor {
        motor: Motor,
        direction: Direction,
        phase: KeyPhase,
    },
    /// Some key was released (only terminals with release reports send these).
    KeyReleased,
    /// DEVICE_POWER for a device id.
    PowerOn(u8),
    PowerOff(u8),
    /// DEVICE_CLEAR for a device id.
    Reset(u8),
    /// DEVICE_CLEAR for a device id that faulted again after a reset, confirmed: only
    /// right after `r` was refused for it (`Controller`, `commands::reset`).
    ResetAgain(u8),
    /// DEVICE_CLEAR 255.
    ResetSystemFault,
    /// WIG_WAG_MODE, the opposite of the live mode.
    ToggleWigWag,
    ToggleSort,
    ToggleHelp,
    CloseOverlay,
    Quit,
    TrafficView,
    Setup,
    /// The installation check (`i`).
    InstallCheck,
    /// `p`: the walk-around remote on, its overlay shown, or off.
    Remote,
    /// `P`: every phone paired with the remote unpaired.
    RevokePhones,
    /// A bound key that does nothing here; the words say where it works.
    Unavailable(&'static str),
}

impl Action {
    /// Whether the action sends a command (handled by `commands`).
    pub fn is_command(&self) -> bool {
        matches!(
            self,
            Action::PowerOn(_)
                | Action::PowerOff(_)
                | Action::Reset(_)
                | Action::ResetSystemFault
                | Action::ToggleWigWag
        )
    }
}

pub const NO_MOTOR_HERE: &str = "motor keys work on a flaps or trim row: select it with ↑/↓ or j/k";
pub const ROLL_KEYS: &str = "roll trim runs left/right: Shift+←/→ or ,/.";
pub const PITCH_KEYS: &str = "this motor runs up/down: Shift+↑/↓ or u/d";
pub const NOTHING_SELECTED: &str = "select a device first (↑/↓ or j/k)";

/// Every key, in words, for the help overlay. The table lives with the widget that
/// shows it; the keymap tests check every binding in it against [`map`], so the two
/// cannot drift apart.
pub const HELP: &[(&str, &str)] = crate::ui::help::KEYS;

/// The action for a key, or `None` for a key that is not bound.
pub fn map(key: &KeyEvent, ctx: &KeyContext) -> Option<Action> {
    if key.kind == KeyEventKind::Release {
        return Some(Action::KeyReleased);
    }
    let phase = match key.kind {
        KeyEventKind::Repeat => KeyPhase::Repeat,
        _ => KeyPhase::Press,
    };
    let mods = key.modifiers;
    let ctrl_alt = mods.intersects(KeyModifiers::CONTROL | KeyModifiers::ALT);
    let shift = mods.contains(KeyModifiers::SHIFT);
    let code = normalize(key.code, shift);

    if ctrl_alt {
        return (mods.contains(KeyModifiers::CONTROL) && matches!(code, KeyCode::Char('c' | 'C')))
            .then_some(Action::Quit);
    }
    if ctx.overlay_open {
        return match code {
            KeyCode::Char('q') => Some(Action::Quit),
            KeyCode::Char('p') if phase == KeyPhase::Press => Some(Action::Remote),
            KeyCode::Char('P') if phase == KeyPhase::Press => Some(Action::RevokePhones),
            KeyCode::Char('?') | KeyCode::Esc => {
                (phase == KeyPhase::Press).then_some(Action::CloseOverlay)
            }
            _ => None,
        };
    }

    if let Some(dir) = motor_direction(code, shift) {
        return Some(motor_action(ctx, dir, phase));
    }

    let nav = match code {
        KeyCode::Up | KeyCode::Char('k') => Some(Action::SelectPrev),
        KeyCode::Down | KeyCode::Char('j') => Some(Action::SelectNext),
        _ => None,
    };
    if nav.is_some() {
        // Holding a navigation key scrolls, like everywhere else.
        return nav;
    }
    if phase == KeyPhase::Repeat {
        // A held 'o' must not send DEVICE_POWER thirty times a second.
        return None;
    }
    let selected = |f: fn(u8) -> Action| {
        Some(
            ctx.selected
                .map_or(Action::Unavailable(NOTHING_SELECTED), |s| f(s.id)),
        )
    };
    match code {
        KeyCode::Char('o') | KeyCode::Enter => selected(Action::PowerOn),
        KeyCode::Char('f') => selected(Action::PowerOff),
        KeyCode::Char('r') => selected(Action::Reset),
        KeyCode::Char('R') => Some(Action::ResetSystemFault),
        KeyCode::Char('Y') => selected(Action::ResetAgain),
        KeyCode::Char('w') => Some(Action::ToggleWigWag),
        KeyCode::Char('s') => Some(Action::ToggleSort),
        KeyCode::Char('?') => Some(Action::ToggleHelp),
        KeyCode::Char('q') => Some(Action::Quit),
        KeyCode::Char('t') => Some(Action::TrafficView),
        KeyCode::Char('c') => Some(Action::Setup),
        KeyCode::Char('i') => Some(Action::InstallCheck),
        KeyCode::Char('p') => Some(Action::Remote),
        KeyCode::Char('P') => Some(Action::RevokePhones),
        _ => None,
    }
}

/// With the kitty protocol a shifted letter may arrive as the base key plus SHIFT;
/// legacy terminals send the shifted character. Both mean the same key here.
fn normalize(code: KeyCode, shift: bool) -> KeyCode {
    match code {
        KeyCode::Char(c) if shift && c.is_ascii_lowercase() => {
            KeyCode::Char(c.to_ascii_uppercase())
        }
        KeyCode::Char(',') if shift => KeyCode::Char('<'),
        KeyCode::Char('.') if shift => KeyCode::Char('>'),
        other => other,
    }
}

/// The direction a motor key asks for, whatever row is selected.
fn motor_direction(code: KeyCode, shift: bool) -> Option<Direction> {
    match code {
        KeyCode::Up if shift => Some(Direction::Up),
        KeyCode::Down if shift => Some(Direction::Down),
        KeyCode::Left if shift => Some(Direction::Left),
        KeyCode::Right if shift => Some(Direction::Right),
        KeyCode::Char('u') => Some(Direction::Up),
        KeyCode::Char('d') => Some(Direction::Down),
        KeyCode::Char(',' | '<') => Some(Direction::Left),
        KeyCode::Char('.' | '>') => Some(Direction::Right),
        _ => None,
    }
}

fn motor_action(ctx: &KeyContext, direction: Direction, phase: KeyPhase) -> Action {
    match ctx.motor_selected() {
        Some(motor) if direction.applies_to(motor) => Action::Motor {
            motor,
            direction,
            phase,
        },
        Some(Motor::Trim(TrimKind::Roll)) => Action::Unavailable(ROLL_KEYS),
        Some(_) => Action::Unavailable(PITCH_KEYS),
        None => Action::Unavailable(NO_MOTOR_HERE),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::device::{FLAPS, STARTER, TRIM_P, TRIM_R};

    fn ctx(id: u8, kind: CircuitKind) -> KeyContext {
        KeyContext {
            selected: Some(Selected {
                id,
                kind,
                state: CircuitState::Off,
            }),
            overlay_open: false,
            past_endpoints: false,
        }
    }

    fn key(code: KeyCode, mods: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, mods)
    }

    fn plain(code: KeyCode) -> KeyEvent {
        key(code, KeyModifiers::NONE)
    }

    /// Every key the help overlay names does something on the row it names.
    #[test]
    fn every_key_in_the_help_is_bound() {
        let token = |t: &str| -> KeyEvent {
            let (mods, rest) = match t.strip_prefix("Shift+") {
                Some(r) => (KeyModifiers::SHIFT, r),
                None => match t.strip_prefix("Ctrl-") {
                    Some(r) => (KeyModifiers::CONTROL, r),
                    None => (KeyModifiers::NONE, t),
                },
            };
            let code = match rest {
                "↑" => KeyCode::Up,
                "↓" => KeyCode::Down,
                "←" => KeyCode::Left,
                "→" => KeyCode::Right,
                "Enter" => KeyCode::Enter,
                "Esc" => KeyCode::Esc,
                "C" => KeyCode::Char('c'),
                c if c.chars().count() == 1 => KeyCode::Char(c.chars().next().unwrap()),
                other => panic!("help names a key the test cannot type: {other}"),
            };
            key(code, mods)
        };
        for (keys, what) in HELP {
            if *keys == "any key" {
                continue;
            }
            let row = if what.contains("roll trim") {
                ctx(TRIM_R, CircuitKind::Trim(TrimKind::Roll))
            } else if what.contains("flaps") {
                ctx(FLAPS, CircuitKind::Flaps)
            } else {
                ctx(9, CircuitKind::Device)
            };
            let row = if keys.contains("Esc") {
                KeyContext {
                    overlay_open: true,
                    ..row
                }
            } else {
                row
            };
            for t in keys
                .split(|c: char| c.is_whitespace() || c == '/')
                .filter(|t| !t.is_empty())
            {
                let action = map(&token(t), &row);
                assert!(
                    action.is_some() && !matches!(action, Some(Action::Unavailable(_))),
                    "help says {t:?} does {what:?}, the keymap gives {action:?}"
                );
            }
        }
    }

    #[test]
    fn arrows_and_jk_navigate_on_motor_rows_too() {
        for c in [
            ctx(FLAPS, CircuitKind::Flaps),
            ctx(TRIM_P, CircuitKind::Trim(TrimKind::Pitch)),
            ctx(TRIM_R, CircuitKind::Trim(TrimKind::Roll)),
            ctx(5, CircuitKind::Device),
        ] {
            assert_eq!(map(&plain(KeyCode::Up), &c), Some(Action::SelectPrev));
            assert_eq!(map(&plain(KeyCode::Down), &c), Some(Action::SelectNext));
            assert_eq!(
                map(&plain(KeyCode::Char('k')), &c),
                Some(Action::SelectPrev)
            );
            assert_eq!(
                map(&plain(KeyCode::Char('j')), &c),
                Some(Action::SelectNext)
            );
        }
    }

    #[test]
    fn motor_keys_run_only_the_selected_motor() {
        let flaps = ctx(FLAPS, CircuitKind::Flaps);
        assert_eq!(
            map(&key(KeyCode::Down, KeyModifiers::SHIFT), &flaps),
            Some(Action::Motor {
                motor: Motor::Flaps,
                direction: Direction::Down,
                phase: KeyPhase::Press
            })
        );
        let pitch = ctx(TRIM_P, CircuitKind::Trim(TrimKind::Pitch));
        assert_eq!(
            map(&plain(KeyCode::Char('u')), &pitch),
            Some(Action::Motor {
                motor: Motor::Trim(TrimKind::Pitch),
                direction: Direction::Up,
                phase: KeyPhase::Press
            })
        );
        let roll = ctx(TRIM_R, CircuitKind::Trim(TrimKind::Roll));
        assert_eq!(
            map(&key(KeyCode::Left, KeyModifiers::SHIFT), &roll),
            Some(Action::Motor {
                motor: Motor::Trim(TrimKind::Roll),
                direction: Direction::Left,
                phase: KeyPhase::Press
            })
        );
        // Kitty reports Shift+. as '.' with SHIFT; legacy terminals as '>'.
        for k in [
            key(KeyCode::Char('.'), KeyModifiers::SHIFT),
            plain(KeyCode::Char('>')),
            plain(KeyCode::Char('.')),
        ] {
            assert!(matches!(
                map(&k, &roll),
                Some(Action::Motor {
                    direction: Direction::Right,
                    ..
                })
            ));
        }
        assert_eq!(
            map(&plain(KeyCode::Char('u')), &roll),
            Some(Action::Unavailable(ROLL_KEYS))
        );
        assert_eq!(
            map(&plain(KeyCode::Char(',')), &pitch),
            Some(Action::Unavailable(PITCH_KEYS))
        );
        assert_eq!(
            map(
                &key(KeyCode::Up, KeyModifiers::SHIFT),
                &ctx(5, CircuitKind::Device)
            ),
            Some(Action::Unavailable(NO_MOTOR_HERE))
        );
    }

    #[test]
    fn repeats_and_releases_keep_their_kind() {
        let pitch = ctx(TRIM_P, CircuitKind::Trim(TrimKind::Pitch));
        let rep =
            KeyEvent::new_with_kind(KeyCode::Char('d'), KeyModifiers::NONE, KeyEventKind::Repeat);
        assert!(matches!(
            map(&rep, &pitch),
            Some(Action::Motor {
                phase: KeyPhase::Repeat,
                ..
            })
        ));
        let rel = KeyEvent::new_with_kind(
            KeyCode::Char('d'),
            KeyModifiers::NONE,
            KeyEventKind::Release,
        );
        assert_eq!(map(&rel, &pitch), Some(Action::KeyReleased));
        let held_o =
            KeyEvent::new_with_kind(KeyCode::Char('o'), KeyModifiers::NONE, KeyEventKind::Repeat);
        assert_eq!(map(&held_o, &ctx(5, CircuitKind::Device)), None);
    }

    #[test]
    fn command_keys() {
        let c = ctx(7, CircuitKind::Device);
        assert_eq!(
            map(&plain(KeyCode::Char('o')), &c),
            Some(Action::PowerOn(7))
        );
        assert_eq!(map(&plain(KeyCode::Enter), &c), Some(Action::PowerOn(7)));
        assert_eq!(
            map(&plain(KeyCode::Char('f')), &c),
            Some(Action::PowerOff(7))
        );
        assert_eq!(map(&plain(KeyCode::Char('r')), &c), Some(Action::Reset(7)));
        assert_eq!(
            map(&key(KeyCode::Char('R'), KeyModifiers::SHIFT), &c),
            Some(Action::ResetSystemFault)
        );
        assert_eq!(
            map(&key(KeyCode::Char('r'), KeyModifiers::SHIFT), &c),
            Some(Action::ResetSystemFault),
            "kitty's base key plus SHIFT"
        );
        assert_eq!(
            map(&plain(KeyCode::Char('w')), &c),
            Some(Action::ToggleWigWag)
        );
        assert_eq!(
            map(&plain(KeyCode::Char('s')), &c),
            Some(Action::ToggleSort)
        );
        assert_eq!(
            map(&plain(KeyCode::Char('?')), &c),
            Some(Action::ToggleHelp)
        );
        assert_eq!(map(&plain(KeyCode::Char('q')), &c), Some(Action::Quit));
        assert_eq!(
            map(&key(KeyCode::Char('c'), KeyModifiers::CONTROL), &c),
            Some(Action::Quit)
        );
        assert_eq!(
            map(&plain(KeyCode::Char('t')), &c),
            Some(Action::TrafficView)
        );
        assert_eq!(map(&plain(KeyCode::Char('c')), &c), Some(Action::Setup));
        assert_eq!(
            map(&plain(KeyCode::Char('i')), &c),
            Some(Action::InstallCheck)
        );
        assert_eq!(map(&plain(KeyCode::Char('x')), &c), None);
        assert_eq!(
            map(&plain(KeyCode::Char('o')), &KeyContext::default()),
            Some(Action::Unavailable(NOTHING_SELECTED))
        );
        let starter = ctx(STARTER, CircuitKind::Starter);
        assert_eq!(
            map(&plain(KeyCode::Char('o')), &starter),
            Some(Action::PowerOn(STARTER)),
            "the keymap maps; commands refuses"
        );
    }

    #[test]
    fn the_help_overlay_takes_the_keys() {
        let mut c = ctx(TRIM_P, CircuitKind::Trim(TrimKind::Pitch));
        c.overlay_open = true;
        assert_eq!(map(&plain(KeyCode::Char('u')), &c), None);
        assert_eq!(map(&plain(KeyCode::Char('j')), &c), None);
        assert_eq!(map(&plain(KeyCode::Esc), &c), Some(Action::CloseOverlay));
        assert_eq!(
            map(&plain(KeyCode::Char('?')), &c),
            Some(Action::CloseOverlay)
        );
        assert_eq!(map(&plain(KeyCode::Char('q')), &c), Some(Action::Quit));
    }
}

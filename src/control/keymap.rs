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
    /// The context for the selected device id among `circuits` (the rows on screen),
    /// with or without an overlay over them.
    pub fn for_selection(selected: Option<u8>, overlay_open: bool, circuits: &[Circuit]) -> Self {
        KeyContext {
            selected: selected.and_then(|id| {
                circuits.iter().find(|c| c.id == id).map(|c| Selected {
                    id: c.id,
                    kind: c.kind,
                    state: c.state,
                })
            }),
            overlay_open,
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

/// Every key, in words: the help overlay (`ui::help`) draws this table. It lives
/// here, beside [`map`], and the keymap tests type every binding it names and check
/// what [`map`] does with it, so the words and the keys cannot drift apart.
pub const HELP: &[(&str, &str)] = &[
    ("↑/↓  j/k", "move the selection (never runs a motor)"),
    ("Shift+↑  u", "flaps / pitch trim row: run up while held"),
    ("Shift+↓  d", "flaps / pitch trim row: run down while held"),
    ("Shift+←  ,", "roll trim row: run left while held"),
    ("Shift+→  .", "roll trim row: run right while held"),
    ("any key", "stops a running motor (and does nothing else)"),
    ("o  Enter", "switch the selected device on (DEVICE_POWER)"),
    ("f", "switch the selected device off (DEVICE_POWER)"),
    // One line for both, so the list still fits 80×24.
    ("r  Y", "reset the fault (DEVICE_CLEAR); Y: confirm a 2nd"),
    ("R", "reset the system fault (DEVICE_CLEAR 255)"),
    ("w", "wig-wag steady / auto (WIG_WAG_MODE)"),
    ("s", "sort by pin / by name"),
    // t and c share a line so the phone remote's fits 80×24 too.
    ("t  c", "traffic view; c: setup screens"),
    ("i", "installation check"),
    ("p  P", "phone remote: on / show / off; P: unpair phones"),
    ("?  Esc", "this help"),
    ("q  Ctrl-C", "quit"),
];

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
        let (none, shift, ctrl) = (
            KeyModifiers::NONE,
            KeyModifiers::SHIFT,
            KeyModifiers::CONTROL,
        );
        let starter = ctx(STARTER, CircuitKind::Starter);
        let nothing = KeyContext::default();
        for (code, mods, at, want, why) in [
            (KeyCode::Char('o'), none, &c, Some(Action::PowerOn(7)), ""),
            (KeyCode::Enter, none, &c, Some(Action::PowerOn(7)), ""),
            (KeyCode::Char('f'), none, &c, Some(Action::PowerOff(7)), ""),
            (KeyCode::Char('r'), none, &c, Some(Action::Reset(7)), ""),
            (
                KeyCode::Char('R'),
                shift,
                &c,
                Some(Action::ResetSystemFault),
                "",
            ),
            (
                KeyCode::Char('r'),
                shift,
                &c,
                Some(Action::ResetSystemFault),
                "kitty's base key plus SHIFT",
            ),
            (KeyCode::Char('w'), none, &c, Some(Action::ToggleWigWag), ""),
            (KeyCode::Char('s'), none, &c, Some(Action::ToggleSort), ""),
            (KeyCode::Char('?'), none, &c, Some(Action::ToggleHelp), ""),
            (KeyCode::Char('q'), none, &c, Some(Action::Quit), ""),
            (KeyCode::Char('c'), ctrl, &c, Some(Action::Quit), ""),
            (KeyCode::Char('t'), none, &c, Some(Action::TrafficView), ""),
            (KeyCode::Char('c'), none, &c, Some(Action::Setup), ""),
            (KeyCode::Char('i'), none, &c, Some(Action::InstallCheck), ""),
            (KeyCode::Char('x'), none, &c, None, "unbound"),
            (
                KeyCode::Char('o'),
                none,
                &nothing,
                Some(Action::Unavailable(NOTHING_SELECTED)),
                "nothing selected",
            ),
            (
                KeyCode::Char('o'),
                none,
                &starter,
                Some(Action::PowerOn(STARTER)),
                "the keymap maps; commands refuses",
            ),
        ] {
            assert_eq!(map(&key(code, mods), at), want, "{code:?} {mods:?} {why}");
        }
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

//! Keys of the traffic view (`t` from the device list).
//!
//! The view's state (pause, filters, search, cursor) lives in `model.traffic.view`,
//! next to the ring it points into.

use std::time::Instant;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind};

use super::{App, Flow, lock};
use crate::control::StopReason;
use crate::protocol::Crossing;
use crate::traffic::{KindFilter, TrafficLog};
use crate::ui::state::Screen;

const PAGE: usize = 20;

impl App {
    pub(super) fn traffic_key(&mut self, key: KeyEvent, now: Instant) -> Flow {
        // Any key stops a running motor before it does anything else here.
        self.controller.stop(now, StopReason::OtherKey);
        if key.kind == KeyEventKind::Release {
            return Flow::Continue;
        }
        let model = self.model.clone();
        let mut m = lock(&model);
        let log = &mut m.traffic;
        if log.view.typing {
            match key.code {
                KeyCode::Enter => {
                    log.view.typing = false;
                    jump(log, Toward::Older);
                }
                KeyCode::Esc => {
                    log.view.typing = false;
                    log.view.search.clear();
                }
                KeyCode::Backspace => {
                    log.view.search.pop();
                }
                KeyCode::Char(c) => log.view.search.push(c),
                _ => {}
            }
            return Flow::Continue;
        }
        match key.code {
            KeyCode::Char('q') => return Flow::Quit,
            KeyCode::Esc | KeyCode::Char('t') => self.view.screen = Screen::Devices,
            KeyCode::Char(' ') => {
                log.view.frozen_at = match log.view.frozen_at {
                    Some(_) => None,
                    None => Some(log.total()),
                }
            }
            KeyCode::Char('d') => {
                log.view.dir = match log.view.dir {
                    None => Some(Crossing::Rx),
                    Some(Crossing::Rx) => Some(Crossing::Tx),
                    Some(Crossing::Tx) => None,
                }
            }
            KeyCode::Char('m') => cycle_kind(log, 1),
            KeyCode::Char('M') => cycle_kind(log, -1),
            KeyCode::Char('e') => {
                log.view.kind = if log.view.kind == KindFilter::Errors {
                    KindFilter::All
                } else {
                    KindFilter::Errors
                }
            }
            KeyCode::Char('/') => {
                log.view.typing = true;
                log.view.search.clear();
            }
            KeyCode::Char('n') => jump(log, Toward::Older),
            KeyCode::Char('N') => jump(log, Toward::Newer),
            KeyCode::Char('x') => {
                log.view.dir = None;
                log.view.kind = KindFilter::All;
                log.view.search.clear();
                log.view.cursor = None;
            }
            KeyCode::Up | KeyCode::Char('k') => move_cursor(log, -1),
            KeyCode::Down | KeyCode::Char('j') => move_cursor(log, 1),
            KeyCode::PageUp => move_cursor(log, -(PAGE as isize)),
            KeyCode::PageDown => move_cursor(log, PAGE as isize),
            KeyCode::Home | KeyCode::Char('g') => {
                log.view.cursor = log.visible().first().map(|e| e.seq)
            }
            KeyCode::End | KeyCode::Char('G') => log.view.cursor = None,
            _ => {}
        }
        Flow::Continue
    }

    /// The traffic screen redraws as entries arrive, even those that change nothing
    /// else on the page (the 10 Hz FLAP_TRIM_STATUS mostly repeats itself).
    pub(super) fn traffic_tick(&mut self) {
        if self.view.screen != Screen::Traffic {
            return;
        }
        let total = lock(&self.model).traffic.total();
        if total != self.traffic_drawn {
            self.traffic_drawn = total;
            self.dirty = true;
        }
    }
}

fn cycle_kind(log: &mut TrafficLog, by: isize) {
    let choices = log.filter_choices();
    let at = choices
        .iter()
        .position(|k| *k == log.view.kind)
        .unwrap_or(0) as isize;
    let n = choices.len() as isize;
    log.view.kind = choices[((at + by).rem_euclid(n)) as usize];
    log.view.cursor = None;
}

/// Moves the cursor by `by` visible entries; from "following", up starts at the newest.
fn move_cursor(log: &mut TrafficLog, by: isize) {
    let seqs: Vec<u64> = log.visible().iter().map(|e| e.seq).collect();
    let Some(last) = seqs.len().checked_sub(1) else {
        return;
    };
    let at = match log.view.cursor {
        Some(c) => seqs.iter().position(|&s| s >= c).unwrap_or(last),
        None if by < 0 => last + 1,
        None => return,
    };
    let to = (at as isize + by).clamp(0, last as isize) as usize;
    log.view.cursor = if by > 0 && at + by as usize > last {
        // Moving down past the newest goes back to following it.
        None
    } else {
        Some(seqs[to])
    };
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Toward {
    Older,
    Newer,
}

/// Moves the cursor to the next search hit; older first, because the newest is where
/// the list starts.
fn jump(log: &mut TrafficLog, toward: Toward) {
    let hits: Vec<u64> = log
        .visible()
        .iter()
        .filter(|e| log.matches(e))
        .map(|e| e.seq)
        .collect();
    let from = log.view.cursor.unwrap_or(u64::MAX);
    let next = match toward {
        Toward::Older => hits.iter().rev().find(|&&s| s < from),
        Toward::Newer => hits.iter().find(|&&s| s > from),
    };
    if let Some(&s) = next.or(match toward {
        // Wrap around, as in a pager.
        Toward::Older => hits.last(),
        Toward::Newer => hits.first(),
    }) {
        log.view.cursor = Some(s);
    }
}

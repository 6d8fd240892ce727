//! The traffic view (`t`): every frame both ways with its bytes, and a table of message
//! rates against the ICD so a missing or slow broadcast stands out.
//!
//! Pure rendering of `model.traffic` at `now`, like every other widget.

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Row, Table};

use super::state::ViewState;
use super::{MIN_HEIGHT, MIN_WIDTH, theme, title_bar, too_small, values};
use crate::model::Model;
use crate::protocol::Crossing;
use crate::traffic::{EXPECTED, Entry, ExpectKind, Health, KindFilter, TrafficLog, What, hex};

/// The longest the rate table grows, so the list keeps most of the screen.
const MAX_TABLE_ROWS: usize = 12;

pub fn render(frame: &mut Frame, model: &Model, view: &ViewState, now: Instant) {
    let area = frame.area();
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        too_small::render(frame, MIN_WIDTH, MIN_HEIGHT);
        return;
    }
    let log = &model.traffic;
    let rates = rate_rows(log, now);
    let table_h = (rates.len().min(MAX_TABLE_ROWS) as u16 + 3).min(area.height / 3);
    let replay_h = u16::from(log.replay.is_some());
    let [title, table, list, replay, status, keys] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(table_h),
        Constraint::Fill(1),
        Constraint::Length(replay_h),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    title_bar::render(frame, title, model, now);
    render_rates(frame, table, log, rates, now);
    render_list(frame, list, log);
    if replay_h > 0 {
        render_replay(frame, replay, log);
    }
    render_status(frame, status, log, view);
    render_keys(frame, keys, log);
}

/// Style of an entry's name: errors red, dropped bytes yellow, what we sent cyan.
pub fn entry_style(e: &Entry) -> Style {
    match e.what {
        What::Packet(_) | What::RawTx if e.dir == Crossing::Tx => theme::info(),
        What::Packet(_) | What::RawTx => Style::new(),
        What::Dropped => theme::caution(),
        _ => theme::alert(),
    }
}

/// A search hit: black on yellow, so it shows in any row colour.
pub fn match_style() -> Style {
    Style::new().fg(Color::Black).bg(Color::Yellow)
}

pub fn health_style(h: Health) -> Style {
    match h {
        Health::Ok => theme::on_off(true),
        Health::Slow => theme::caution(),
        Health::Missing => theme::alert(),
        Health::Quiet | Health::Starting | Health::NoRate => theme::label(),
    }
}

fn health_word(h: Health, kind: Option<ExpectKind>) -> &'static str {
    match (h, kind) {
        (Health::Ok, _) => "ok",
        (Health::Slow, _) => "SLOW",
        (Health::Missing, _) => "MISSING",
        (Health::Quiet, Some(ExpectKind::WhileFault)) => "quiet = no faults",
        (Health::Quiet, _) => "not sent (no air data)",
        (Health::Starting, _) => "…",
        (Health::NoRate, _) => "",
    }
}

fn dir_label(d: Crossing) -> &'static str {
    match d {
        Crossing::Rx => "rx",
        Crossing::Tx => "tx",
    }
}

struct RateRow {
    dir: Crossing,
    name: &'static str,
    icd: String,
    health: Health,
    kind: Option<ExpectKind>,
}

/// The ICD's broadcasts first (seen or not: a broadcast never heard is the point), then
/// every other type seen.
fn rate_rows(log: &TrafficLog, now: Instant) -> Vec<RateRow> {
    let mut rows: Vec<RateRow> = EXPECTED
        .iter()
        .map(|e| RateRow {
            dir: e.dir,
            name: e.name,
            icd: match e.kind {
                ExpectKind::Always => format!("{} Hz", e.hz),
                ExpectKind::WhileFault => format!("{} Hz while faulted", e.hz),
                ExpectKind::WhenWeHaveData => format!("{} Hz from us", e.hz),
            },
            health: log.health(e.dir, e.name, now),
            kind: Some(e.kind),
        })
        .collect();
    for (dir, name, _) in log.seen() {
        if !EXPECTED.iter().any(|e| e.dir == dir && e.name == name) {
            rows.push(RateRow {
                dir,
                name,
                icd: "on request".into(),
                health: Health::NoRate,
                kind: None,
            });
        }
    }
    rows
}

fn render_rates(frame: &mut Frame, area: Rect, log: &TrafficLog, rows: Vec<RateRow>, now: Instant) {
    let origin = log.origin.unwrap_or(now);
    let body: Vec<Row> = rows
        .iter()
        .take(MAX_TABLE_ROWS)
        .map(|r| {
            let stat = log.stat(r.dir, r.name);
            let (count, rate, last) = match stat {
                Some(s) => (
                    s.count.to_string(),
                    s.rate_hz(now, origin)
                        .map_or_else(|| values::BLANK.into(), |hz| format!("{hz:.1} Hz")),
                    values::age(now, s.last),
                ),
                None => ("0".into(), values::BLANK.into(), "never".into()),
            };
            let style = health_style(r.health);
            Row::new(vec![
                Span::styled(dir_label(r.dir), theme::label()),
                Span::styled(r.name, style),
                Span::raw(count),
                Span::raw(rate),
                Span::raw(last),
                Span::styled(r.icd.clone(), theme::label()),
                Span::styled(health_word(r.health, r.kind), style),
            ])
        })
        .collect();
    let errors: Vec<String> = log
        .errors
        .iter()
        .map(|(k, n)| format!("{} {n}", k.to_lowercase()))
        .collect();
    let errors_line = if errors.is_empty() {
        Line::styled(" decoder: no errors", theme::label())
    } else {
        Line::styled(format!(" decoder: {}", errors.join("  ")), theme::caution())
    };
    let block = Block::new()
        .borders(Borders::TOP)
        .border_style(theme::border())
        .title(Span::styled(" Rates ", theme::panel_title()))
        .title_bottom(errors_line);
    let table = Table::new(
        body,
        [
            Constraint::Length(3),
            Constraint::Length(18),
            Constraint::Length(7),
            Constraint::Length(9),
            Constraint::Length(8),
            Constraint::Length(19),
            Constraint::Fill(1),
        ],
    )
    .header(Row::new(["", "message", "count", "rate", "last", "ICD", ""]).style(theme::label()))
    .block(block);
    frame.render_widget(table, area);
}

/// The first visible row so that the cursor (or the newest entry) is in view.
fn window_start(list: &[&Entry], height: usize, cursor: Option<u64>) -> (usize, Option<usize>) {
    let len = list.len();
    match cursor.and_then(|c| list.iter().position(|e| e.seq >= c).or(len.checked_sub(1))) {
        Some(i) => (
            i.saturating_sub(height / 2).min(len.saturating_sub(height)),
            Some(i),
        ),
        None => (len.saturating_sub(height), None),
    }
}

fn render_list(frame: &mut Frame, area: Rect, log: &TrafficLog) {
    let visible = log.visible();
    let block = Block::new()
        .borders(Borders::TOP)
        .border_style(theme::border())
        .title(Span::styled(
            format!(" Traffic {} of {} ", visible.len(), log.total()),
            theme::panel_title(),
        ));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let height = inner.height.saturating_sub(1) as usize;
    let (start, cursor) = window_start(&visible, height, log.view.cursor);
    let origin = log.origin;
    let rows: Vec<Row> = visible
        .iter()
        .enumerate()
        .skip(start)
        .take(height)
        .map(|(i, e)| {
            let t = origin.map_or(0.0, |o| e.at.saturating_duration_since(o).as_secs_f64());
            let name_style = entry_style(e);
            let row = Row::new(vec![
                Span::raw(format!("{t:>9.3}")),
                Span::styled(
                    dir_label(e.dir),
                    if e.dir == Crossing::Tx {
                        theme::info()
                    } else {
                        theme::label()
                    },
                ),
                Span::styled(e.name(), name_style),
                Span::raw(e.text()),
                Span::styled(hex(&e.raw), theme::label()),
            ]);
            if Some(i) == cursor {
                row.style(theme::selected_row().add_modifier(Modifier::REVERSED))
            } else if log.matches(e) {
                row.style(match_style())
            } else {
                row
            }
        })
        .collect();
    let table = Table::new(
        rows,
        [
            Constraint::Length(9),
            Constraint::Length(2),
            Constraint::Length(17),
            Constraint::Fill(3),
            Constraint::Fill(2),
        ],
    )
    .header(Row::new(["time s", "", "message", "fields", "bytes"]).style(theme::label()));
    frame.render_widget(table, inner);
}

fn render_replay(frame: &mut Frame, area: Rect, log: &TrafficLog) {
    let Some(r) = &log.replay else { return };
    let state = if r.finished {
        Span::styled(" END ", theme::banner_waiting())
    } else if r.paused {
        Span::styled(" PAUSED ", theme::banner_waiting())
    } else {
        Span::styled(" PLAYING ", theme::source_not_live())
    };
    let mut spans = vec![
        Span::styled(format!("REPLAY {} ", r.file), theme::panel_title()),
        state,
        Span::raw(format!(
            " {} of {}  ×{}  read-only ",
            values::secs(r.position),
            values::secs(r.length),
            r.speed
        )),
    ];
    if let Some(p) = &r.problem {
        spans.push(Span::styled(format!(" {p}"), theme::caution()));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

fn render_status(frame: &mut Frame, area: Rect, log: &TrafficLog, view: &ViewState) {
    let v = &log.view;
    let mut spans = Vec::new();
    if let Some(n) = &view.notice {
        spans.push(Span::styled(format!("{n} "), theme::caution()));
        spans.push(Span::styled("│ ", theme::border()));
    }
    if v.frozen_at.is_some() {
        spans.push(Span::styled(
            format!(" PAUSED, {} new ", log.held_back()),
            theme::banner_waiting(),
        ));
        spans.push(Span::raw(" "));
    }
    let dir = match v.dir {
        None => "both ways",
        Some(Crossing::Rx) => "rx only",
        Some(Crossing::Tx) => "tx only",
    };
    let kind = match v.kind {
        KindFilter::All => "all messages".to_string(),
        KindFilter::Errors => "decoder errors".to_string(),
        KindFilter::Message(n) => n.to_string(),
    };
    let filtered = v.dir.is_some() || v.kind != KindFilter::All;
    spans.push(Span::styled("showing ", theme::label()));
    spans.push(Span::styled(
        format!("{dir}, {kind}"),
        if filtered {
            theme::info()
        } else {
            Style::new()
        },
    ));
    if v.typing {
        spans.push(Span::styled("  search /", theme::label()));
        spans.push(Span::styled(format!("{}▏", v.search), match_style()));
    } else if !v.search.is_empty() {
        let hits = log.visible().iter().filter(|e| log.matches(e)).count();
        spans.push(Span::styled("  search ", theme::label()));
        spans.push(Span::styled(v.search.clone(), match_style()));
        spans.push(Span::raw(format!(" {hits} match(es)")));
    }
    if v.cursor.is_some() {
        spans.push(Span::styled("  (End follows the newest)", theme::label()));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

fn render_keys(frame: &mut Frame, area: Rect, log: &TrafficLog) {
    let mut keys: Vec<(&str, &str)> = if log.view.typing {
        vec![("Enter", "find"), ("Esc", "cancel")]
    } else {
        vec![
            ("space", "pause"),
            ("d", "direction"),
            ("m", "type"),
            ("e", "errors"),
            ("/", "search"),
            ("n N", "older/newer hit"),
            ("↑↓", "scroll"),
            ("x", "clear"),
            ("Esc", "back"),
        ]
    };
    if log.replay.is_some() && !log.view.typing {
        keys.splice(0..0, [("p", "play/pause"), (".", "step"), ("+-", "speed")]);
    }
    let mut spans = Vec::new();
    for (k, what) in keys {
        spans.push(Span::styled(format!(" {k} "), theme::key()));
        spans.push(Span::raw(format!(" {what} ")));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

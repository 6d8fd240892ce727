//! The setup screens: one page per spec (device, system, flaps, both trims, wig-wag),
//! diagnostics, and backup/erase. Each page is a table of its fields with the value
//! being edited beside what the unit holds, then where each write to the unit
//! stands. Nothing is drawn as saved unless the unit acknowledged it.

pub mod backup;
pub mod device;
pub mod diagnostics;
pub mod dialog;
pub mod motor;
pub mod system;
pub mod wig_wag;

use std::time::Instant;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Row, Table, Wrap};

use super::state::{MotorRun, ViewState};
use super::{MIN_HEIGHT, MIN_WIDTH, theme, title_bar, too_small};
use crate::model::Model;
use crate::setup::view::{
    self, Dialog, Field, Held, Page, SetupView, Tone, WriteLine, WriteStatus, value_text,
};

/// Draws the setup screen for `view.setup.page`.
pub fn render(
    frame: &mut Frame,
    model: &Model,
    view: &ViewState,
    running: Option<MotorRun>,
    now: Instant,
) {
    let area = frame.area();
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        too_small::render(frame, MIN_WIDTH, MIN_HEIGHT);
        return;
    }
    let sv = &view.setup;
    let writes_h = writes_height(&sv.writes, area.width).min(area.height / 3);
    let [title, tabs, body, writes, message, keys] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(writes_h),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    title_bar::render(frame, title, model, now);
    render_tabs(frame, tabs, sv);
    match sv.page {
        Page::Device => device::render(frame, body, model, sv, &view.wires, now),
        Page::System => system::render(frame, body, model, sv, now),
        Page::Flaps | Page::PitchTrim | Page::RollTrim => {
            motor::render(frame, body, model, view, running, now)
        }
        Page::WigWag => wig_wag::render(frame, body, model, sv, now),
        Page::Diagnostics => diagnostics::render(frame, body, model, sv, now),
        Page::Backup => backup::render(frame, body, sv),
    }
    render_writes(frame, writes, &sv.writes);
    render_message(frame, message, view);
    render_keys(frame, keys, sv);
    match &sv.dialog {
        Dialog::None => {}
        d => dialog::render(frame, model, sv, d),
    }
}

fn render_tabs(frame: &mut Frame, area: Rect, sv: &SetupView) {
    let mut spans = vec![Span::styled("SETUP", theme::panel_title())];
    for p in Page::ALL {
        let style = if p == sv.page {
            theme::key().add_modifier(Modifier::BOLD)
        } else {
            theme::label()
        };
        let mark = if sv.is_edited(p) { "*" } else { "" };
        spans.push(Span::raw(" "));
        spans.push(Span::styled(format!(" {}{mark} ", p.title()), style));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

/// The field table of a form page (label, value being edited, what the unit holds),
/// then the selected field's help and `extra` lines below it.
pub fn render_form(
    frame: &mut Frame,
    area: Rect,
    model: &Model,
    sv: &SetupView,
    now: Instant,
    extra: Vec<Line<'static>>,
) {
    let page = sv.page;
    let fields = page.fields();
    let held = Held::from_model(model, sv.forms.device.device_id);
    let [heading, table_area, help] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(fields.len() as u16 + 1),
        Constraint::Fill(1),
    ])
    .areas(area);
    frame.render_widget(
        Paragraph::new(Line::from(vec![
            Span::styled(
                match page {
                    Page::PitchTrim => "Pitch trim ",
                    Page::RollTrim => "Roll trim ",
                    _ => page.title(),
                },
                theme::panel_title(),
            ),
            Span::raw(
                if page.is_form() && !matches!(page, Page::PitchTrim | Page::RollTrim) {
                    " "
                } else {
                    ""
                },
            ),
            Span::styled(format!("— Enter sends {}", page.sends()), theme::label()),
        ])),
        heading,
    );
    let selected = sv.field();
    let rows: Vec<Row> = fields
        .iter()
        .map(|&f| {
            // A part the unit has not reported holds Appendix F's values underneath:
            // never shown as if they were the unit's.
            let read = sv.forms.from_unit.has(f, page);
            let value = match (&sv.typing, f == selected) {
                _ if !read => view::NOT_READ.to_string(),
                (Some(t), true) => format!("{t}▏ → {}", value_text(f, page, &sv.forms)),
                _ if f == selected && f.is_text() => {
                    format!("{}▏", value_text(f, page, &sv.forms))
                }
                _ => value_text(f, page, &sv.forms),
            };
            let setting = view::field_setting(f, page, sv.forms.device.device_id);
            // A value the unit reported long ago carries its age: it is what the unit
            // said then, not necessarily what it holds now.
            let old = setting.and_then(|s| model.setting_old(s, now));
            let holds = held.text(f, page);
            let differs = holds
                .as_deref()
                .is_some_and(|h| h != value_text(f, page, &sv.forms));
            let value_style = if !read {
                theme::unknown()
            } else if differs && sv.is_edited(page) {
                theme::caution()
            } else {
                Style::new()
            };
            let holds_cell = match holds {
                Some(h) if f == Field::DeviceId => Span::styled(h, theme::label()),
                Some(h) => match old {
                    Some(age) => Span::styled(
                        format!("{h} (heard {} ago)", super::values::secs(age)),
                        theme::unknown(),
                    ),
                    None => Span::styled(h, theme::info()),
                },
                None if f == Field::DeviceId => {
                    Span::styled(model.display_name(sv.forms.device.device_id), theme::info())
                }
                None if setting.is_some_and(|s| model.is_unknown(s)) => {
                    Span::styled(view::unknown_text(f), theme::caution())
                }
                None if setting.is_some() => Span::styled(view::NOT_READ_HOLDS, theme::unknown()),
                None => Span::styled("?", theme::unknown()),
            };
            field_row(
                vec![
                    Line::styled(f.label(), theme::label()),
                    Line::styled(value, value_style),
                    Line::from(holds_cell),
                ],
                f == selected,
            )
        })
        .collect();
    let table = Table::new(
        rows,
        [
            Constraint::Length(22),
            Constraint::Length(26),
            Constraint::Fill(1),
        ],
    )
    .header(Row::new(vec!["", "set to", "the unit holds"]).style(theme::label()));
    frame.render_widget(table, table_area);
    let mut lines = vec![Line::styled(
        selected.help(sv.forms.device.device_id, page),
        theme::label(),
    )];
    lines.extend(extra);
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), help);
}

/// One field's row, highlighted when it is the selected one.
fn field_row(cells: Vec<Line<'static>>, selected: bool) -> Row<'static> {
    let row = Row::new(cells);
    if selected {
        row.style(theme::selected_row())
    } else {
        row
    }
}

/// A page of actions rather than settings (diagnostics, backup): its title, each
/// field's label beside `value` (what Enter does, or what came back), then `help`.
fn render_actions(
    frame: &mut Frame,
    area: Rect,
    sv: &SetupView,
    title: &'static str,
    value: impl Fn(Field) -> Span<'static>,
    help: Vec<Line<'static>>,
) {
    let fields = sv.page.fields();
    let rows: Vec<Row> = fields
        .iter()
        .map(|&f| {
            field_row(
                vec![
                    Line::styled(f.label(), theme::label()),
                    Line::from(value(f)),
                ],
                f == sv.field(),
            )
        })
        .collect();
    let [heading, table, help_area] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(fields.len() as u16),
        Constraint::Fill(1),
    ])
    .areas(area);
    frame.render_widget(
        Paragraph::new(Line::styled(title, theme::panel_title())),
        heading,
    );
    frame.render_widget(
        Table::new(rows, [Constraint::Length(22), Constraint::Fill(1)]),
        table,
    );
    frame.render_widget(Paragraph::new(help), help_area);
}

/// A write's status in words and its colour: green only when acknowledged.
pub fn status_span(s: &WriteStatus) -> Span<'static> {
    match s {
        WriteStatus::Queued => Span::styled("queued", theme::unknown()),
        WriteStatus::Sending { attempt, of } => {
            Span::styled(format!("sending (try {attempt}/{of})"), theme::caution())
        }
        WriteStatus::Rereading => Span::styled("acknowledged, re-reading…", theme::caution()),
        WriteStatus::Saved {
            holds,
            matches: true,
        } => Span::styled(format!("saved ✓ unit holds {holds}"), theme::on_off(true)),
        WriteStatus::Saved { holds, .. } => {
            Span::styled(format!("saved ✓ but unit holds {holds}"), theme::caution())
        }
        WriteStatus::Refused { why, by_unit } => Span::styled(
            format!(
                "refused{}: {why}",
                if *by_unit {
                    " by the unit"
                } else {
                    ", not sent"
                }
            ),
            theme::alert(),
        ),
        WriteStatus::NoAnswer => Span::styled(
            format!(
                "no answer after {} tries: what the unit holds is unknown, re-reading…",
                crate::exchange::TRIES
            ),
            theme::alert(),
        ),
        WriteStatus::AckedUnread => Span::styled(
            "acknowledged, but the re-read went unanswered: unknown, re-reading…",
            theme::alert(),
        ),
        WriteStatus::ReadBack {
            holds,
            matches,
            acked,
        } => Span::styled(
            format!(
                "{}; re-read: the unit holds {holds}{}",
                if *acked {
                    "acknowledged"
                } else {
                    "no answer to the write"
                },
                if *matches {
                    " (what was sent)"
                } else {
                    ", not what was sent"
                }
            ),
            if *matches {
                theme::on_off(true)
            } else {
                theme::caution()
            },
        ),
        WriteStatus::NotSent => {
            Span::styled("not sent (an earlier write failed)", theme::unknown())
        }
    }
}

const WHAT_W: usize = 28;

/// Screen rows a write takes when its words wrap at `width`.
fn rows_of(w: &WriteLine, width: u16) -> u16 {
    let len = WHAT_W + status_span(&w.status).content.chars().count();
    len.div_ceil(width.max(1) as usize) as u16
}

fn writes_height(writes: &[WriteLine], width: u16) -> u16 {
    1 + writes.iter().map(|w| rows_of(w, width)).sum::<u16>().max(1)
}

fn render_writes(frame: &mut Frame, area: Rect, writes: &[WriteLine]) {
    let mut lines = vec![Line::styled("Writes to the unit", theme::panel_title())];
    if writes.is_empty() {
        lines.push(Line::styled("none yet", theme::unknown()));
    }
    // The newest that fit: a restore can be long, and its end is what matters.
    let mut room = area.height.saturating_sub(1);
    let mut skip = writes.len();
    while skip > 0 && rows_of(&writes[skip - 1], area.width) <= room {
        room -= rows_of(&writes[skip - 1], area.width);
        skip -= 1;
    }
    for w in &writes[skip..] {
        lines.push(Line::from(vec![
            Span::styled(format!("{:<WHAT_W$}", w.what), theme::label()),
            status_span(&w.status),
        ]));
    }
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: false }), area);
}

fn render_message(frame: &mut Frame, area: Rect, view: &ViewState) {
    let line = match (&view.setup.message, &view.notice) {
        (_, Some(n)) => Line::styled(n.clone(), theme::caution()),
        (Some((tone, text)), None) => Line::styled(
            text.clone(),
            match tone {
                Tone::Info => theme::info(),
                Tone::Good => theme::on_off(true),
                Tone::Bad => theme::alert(),
            },
        ),
        (None, None) => Line::raw(""),
    };
    frame.render_widget(Paragraph::new(line), area);
}

fn render_keys(frame: &mut Frame, area: Rect, sv: &SetupView) {
    let mut spans = Vec::new();
    for (k, what) in view::keys(sv) {
        spans.push(Span::styled(format!(" {k} "), theme::key()));
        spans.push(Span::raw(format!(" {what} ")));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

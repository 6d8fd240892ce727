//! The installation check's screens. Pure widgets over [`CheckView`] and the
//! model: the flow (`crate::check`) changes the view, these draw it.
//!
//! Every step's screen has the same frame: the page's title line, the steps with the
//! one running marked, the COMMUNICATION LOST banner when the link is stale, what the
//! person must do now (and the time left), the step's own panels, one line of news
//! and the keys. Live values come only through the model's `live_*` accessors, so a
//! stale link shows "--", never an old reading. Every ✓ ✗ ⚠ has its word beside it.

pub mod circuits;
pub mod confirm;
pub mod keys;
pub mod list;
pub mod loads;
pub mod motors;

pub mod summary;
pub mod switches;

use std::time::Instant;

use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders};

use super::state::{MotorRun, ViewState};
use super::{
    MIN_HEIGHT, MIN_WIDTH, comm_banner, palette::Palette, theme, title_bar, unwrapped, wrap,
};
use crate::check::state::{CheckView, Mark, Prompt, Step};
use crate::check::words;
use crate::model::Model;

/// Draws the check as the person sees it: [`render`], then repainted in the palette
/// the page chose (`page.theme`: dark, light or no colour). `page` is the page's own
/// view state: its theme and its notice; `running` is the motor run the page is
/// streaming now, read from the controller for this frame.
pub fn draw(
    frame: &mut Frame,
    area: Rect,
    view: &CheckView,
    model: &Model,
    page: &ViewState,
    running: Option<MotorRun>,
    now: Instant,
) {
    render(frame, area, view, model, page, running, now);
    paint(frame.buffer_mut(), area, page.theme.palette);
}

/// Repaints only `area`, so a check drawn in part of a frame leaves the rest alone.
fn paint(buf: &mut Buffer, area: Rect, palette: Palette) {
    let area = area.intersection(buf.area);
    if area == buf.area {
        return palette.paint(buf);
    }
    let mut part = Buffer::empty(area);
    for y in area.top()..area.bottom() {
        for x in area.left()..area.right() {
            part[(x, y)] = buf[(x, y)].clone();
        }
    }
    palette.paint(&mut part);
    for y in area.top()..area.bottom() {
        for x in area.left()..area.right() {
            buf[(x, y)] = part[(x, y)].clone();
        }
    }
}

/// Draws the check in the page's colour words (see [`super::theme`]).
pub fn render(
    frame: &mut Frame,
    area: Rect,
    view: &CheckView,
    model: &Model,
    page: &ViewState,
    running: Option<MotorRun>,
    now: Instant,
) {
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        return too_small(frame.buffer_mut(), area);
    }
    let banner = comm_banner::banner(model, now);
    let prompt = shown_prompt(view);
    let [
        title,
        steps,
        banner_area,
        prompt_area,
        body,
        message,
        keys_area,
    ] = layout(view, model, area, now);
    title_bar::render(frame, title, model, now);
    unwrapped::lines(frame.buffer_mut(), steps, &[steps_line(view, steps.width)]);
    if let Some(b) = &banner {
        comm_banner::render(frame, banner_area, b);
    }
    if let Some(p) = prompt {
        render_prompt(frame, prompt_area, p);
    }
    if view.interrupted.is_some() && view.show_loads {
        summary::render_done(frame, body, view, model, now);
    } else if view.interrupted.is_some() {
        summary::render_interrupted(frame, body, view, model, now);
    } else {
        match view.step {
            Step::Confirm => confirm::render(frame, body, view),
            Step::Switches => switches::render(frame, body, view, model, now),
            Step::Circuits => circuits::render(frame, body, view, model, now),
            Step::Motors => motors::render(frame, body, view, model, running, now),
            // The load analysis's own widget, its circuits scrolled
            // from the selection.
            Step::Loads => loads::render(
                frame.buffer_mut(),
                body,
                view.loads.as_ref(),
                view.current.unwrap_or(0),
            ),
            Step::Done => summary::render_done(frame, body, view, model, now),
        }
    }
    if let Some(m) = &view.message {
        unwrapped::lines(
            frame.buffer_mut(),
            message,
            &[Line::styled(m.clone(), theme::info())],
        );
    }
    keys::render(frame.buffer_mut(), keys_area, view, page);
}

/// The screen's lines: title, steps, banner, prompt, the step's body, news, keys.
fn layout(view: &CheckView, model: &Model, area: Rect, now: Instant) -> [Rect; 7] {
    let banner = comm_banner::banner(model, now);
    let prompt_h = shown_prompt(view).map_or(0, |p| prompt_lines(p, area.width).len() as u16 + 1);
    Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(1),
        Constraint::Length(comm_banner::height(
            banner.as_ref(),
            area.height,
            area.width,
        )),
        Constraint::Length(prompt_h),
        Constraint::Fill(1),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area)
}

/// How far the results of an ended check (or its load analysis) scroll on a screen
/// of `area`: the app keeps [`CheckView::scroll`] within it, so ↑ acts at once after
/// End. 0 while the check runs.
pub fn results_scroll_max(
    view: &CheckView,
    model: &Model,
    _page: &ViewState,
    now: Instant,
    area: Rect,
) -> usize {
    let ended = view.interrupted.is_some() || view.step == Step::Done;
    if !ended || area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        return 0;
    }
    summary::scroll_max(view, model, now, layout(view, model, area, now)[4])
}

/// The prompt, unless the check was interrupted (then nothing is asked of the person
/// but to read what was left).
fn shown_prompt(view: &CheckView) -> Option<&Prompt> {
    view.prompt
        .as_ref()
        .filter(|p| view.interrupted.is_none() && !(p.todo.is_empty() && p.watching.is_empty()))
}

const DO_NOW: &str = " DO NOW ";
const WATCHING: &str = "Watching ";

/// What the person must do, in plain words, then what the page is watching; the
/// time left sits at the end of the first line.
fn prompt_lines(p: &Prompt, width: u16) -> Vec<Line<'static>> {
    let width = usize::from(width);
    let time = p
        .time_left
        .map(|t| format!("  {} left", words::duration(t)));
    let time_w = time.as_ref().map_or(0, |t| t.chars().count());
    let lead = DO_NOW.chars().count() + 1;
    let todo = wrap::text(&p.todo, width.saturating_sub(lead + time_w).max(10));
    let mut out = Vec::new();
    for (i, part) in todo.into_iter().enumerate() {
        let mut spans = if i == 0 {
            vec![
                Span::styled(DO_NOW, theme::banner_waiting()),
                Span::raw(" "),
            ]
        } else {
            vec![Span::raw(" ".repeat(lead))]
        };
        let len = part.chars().count();
        spans.push(Span::styled(
            part,
            Style::new().add_modifier(Modifier::BOLD),
        ));
        if let (0, Some(t)) = (i, &time) {
            let pad = width.saturating_sub(lead + len + time_w);
            spans.push(Span::raw(" ".repeat(pad)));
            spans.push(Span::styled(t.clone(), theme::caution()));
        }
        out.push(Line::from(spans));
    }
    if !p.watching.is_empty() {
        let lead = WATCHING.chars().count();
        for (i, part) in wrap::text(&p.watching, width.saturating_sub(lead).max(10))
            .into_iter()
            .enumerate()
        {
            let head = if i == 0 {
                Span::styled(WATCHING, theme::label())
            } else {
                Span::raw(" ".repeat(lead))
            };
            out.push(Line::from(vec![head, Span::styled(part, theme::info())]));
        }
    }
    // A prompt of a page's length would push the results off a small screen.
    out.truncate(4);
    out
}

fn render_prompt(frame: &mut Frame, area: Rect, p: &Prompt) {
    let block = Block::new()
        .borders(Borders::BOTTOM)
        .border_style(theme::border());
    let inner = block.inner(area);
    frame.render_widget(block, area);
    unwrapped::lines(frame.buffer_mut(), inner, &prompt_lines(p, area.width));
}

/// The steps' short names, for a narrow line.
fn short(step: Step) -> &'static str {
    match step {
        Step::Confirm => "Power",
        Step::Switches => "Switches",
        Step::Circuits => "Circuits",
        Step::Motors => "Motors",
        Step::Loads => "Loads",
        Step::Done => "Report",
    }
}

pub const STEPS: [Step; 6] = [
    Step::Confirm,
    Step::Switches,
    Step::Circuits,
    Step::Motors,
    Step::Loads,
    Step::Done,
];

/// "INSTALLATION CHECK  1 Before power › 2 Switch inputs …": the step running on a
/// badge, steps done in the text colour, steps to come dim, skipped ones struck
/// through in words ("skipped"), never by colour alone. An interrupted check shows
/// the step where it stopped ("3 Circuits stopped", on the alarm badge), the steps
/// after it (the report's included) as never reached.
fn steps_line(view: &CheckView, width: u16) -> Line<'static> {
    // The head in full, short, or (the narrowest, when the step's own badge already
    // says "stopped") none.
    let head = |long: Option<bool>| match (view.interrupted.is_some(), long) {
        (_, None) => Span::raw(""),
        (true, Some(true)) => Span::styled("CHECK INTERRUPTED ", theme::alert()),
        (true, Some(false)) => Span::styled("STOPPED ", theme::alert()),
        (false, Some(true)) => Span::styled("INSTALLATION CHECK ", theme::panel_title()),
        (false, Some(false)) => Span::styled("CHECK ", theme::panel_title()),
    };
    // How much each step is named: 2 every one in full, 1 the running one in full,
    // 0 none.
    let build = |long_head: Option<bool>, full: u8| -> Vec<Span<'static>> {
        let mut spans = vec![head(long_head)];
        for (i, s) in STEPS.into_iter().enumerate() {
            let skipped = view.skipped_steps.contains(&s);
            let name = if full == 2 || (full == 1 && s == view.step) {
                s.title()
            } else {
                short(s)
            };
            // An interrupted check stays on the step where it stopped, said in words.
            let stopped = view.interrupted.is_some() && s == view.step;
            let text = if stopped {
                format!("{} {name} stopped", i + 1)
            } else if skipped {
                format!("{} {name} skipped", i + 1)
            } else {
                format!("{} {name}", i + 1)
            };
            if i > 0 {
                spans.push(Span::styled(" › ", theme::border()));
            }
            let style = if stopped {
                theme::banner_lost()
            } else if s == view.step {
                theme::key().add_modifier(Modifier::BOLD)
            } else if skipped || s > view.step {
                theme::unknown()
            } else {
                theme::label()
            };
            if s == view.step {
                spans.push(Span::styled(format!(" {text} "), style));
            } else {
                spans.push(Span::styled(text, style));
            }
        }
        spans
    };
    let fits = |spans: &[Span]| {
        spans
            .iter()
            .map(|s| s.content.chars().count())
            .sum::<usize>()
            <= usize::from(width)
    };
    let tries = [
        (Some(true), 2),
        (Some(true), 1),
        (Some(false), 1),
        (Some(true), 0),
        (Some(false), 0),
        (None, 0),
    ];
    for (long_head, full) in tries {
        let spans = build(long_head, full);
        if fits(&spans) {
            return Line::from(spans);
        }
    }
    Line::from(build(None, 0))
}

/// A section's title over a rule, as the page's panels have them.
pub(crate) fn section(frame: &mut Frame, area: Rect, title: &str) -> Rect {
    let block = Block::new()
        .borders(Borders::TOP)
        .border_style(theme::border())
        .title(Span::styled(format!(" {title} "), theme::panel_title()));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    inner
}

/// The mark's badge in its colour: green pass, red fail, amber warning; skipped and
/// not run in the label and dim colours. The word is always there.
pub fn mark_span(mark: Mark) -> Span<'static> {
    let style = match mark {
        Mark::Pass => theme::on_off(true),
        Mark::Fail => theme::alert(),
        Mark::Warn => theme::caution(),
        Mark::Skipped => theme::label(),
        Mark::NotRun => theme::unknown(),
    };
    Span::styled(format!("{:<10}", words::badge(mark)), style)
}

/// A result's first column while its step runs: the item under test says so, items
/// still to come say that, and a finished one has its mark.
pub(crate) fn progress_span(mark: Mark, i: usize, current: Option<usize>) -> Span<'static> {
    match (mark, current) {
        (Mark::NotRun, Some(c)) if i == c => Span::styled(
            format!("{:<10}", "▶ TESTING"),
            theme::info().add_modifier(Modifier::BOLD),
        ),
        (Mark::NotRun, Some(c)) if i > c => {
            Span::styled(format!("{:<10}", "· TO DO"), theme::unknown())
        }
        _ => mark_span(mark),
    }
}

/// The words of a result while its step runs: nothing yet for one under test or to
/// come.
pub(crate) fn progress_words(
    mark: Mark,
    i: usize,
    current: Option<usize>,
    words: String,
) -> String {
    match (mark, current) {
        (Mark::NotRun, Some(c)) if i == c => "in progress".into(),
        (Mark::NotRun, Some(c)) if i > c => String::new(),
        _ => words,
    }
}

/// The mark's colour for the words after it.
pub fn words_style(mark: Mark) -> Style {
    match mark {
        Mark::Fail => Style::new().fg(theme::FAULT),
        Mark::Warn => Style::new().fg(theme::CAUTION),
        Mark::Pass => Style::new(),
        Mark::Skipped | Mark::NotRun => theme::label(),
    }
}

/// The narrowest a result's name column is (with a circuit's pin, for circuits).
pub const HEAD_NAME_W: usize = 23;

/// The widest a circuit's name gets in a result's head before it is cut.
const CIRCUIT_NAME_MAX: usize = 16;

/// A circuit's columns in a result's head: its name's width and its pin's, from the
/// circuits the check has (the longest pin whole: "Field_Pri", "Starter").
pub fn circuit_columns(view: &CheckView) -> (usize, usize) {
    let pin_w = view
        .circuits
        .iter()
        .map(|c| c.pin.chars().count())
        .max()
        .unwrap_or(0)
        .max(3);
    let name_w = view
        .circuits
        .iter()
        .map(|c| c.name.chars().count())
        .max()
        .unwrap_or(0)
        .min(CIRCUIT_NAME_MAX)
        .max(HEAD_NAME_W.saturating_sub(1 + pin_w));
    (name_w, pin_w)
}

/// The width of a result's name column (with a circuit's pin, for circuits), the
/// same in every step so the summary's words line up: [`HEAD_NAME_W`], or wider when
/// the circuits' names and pins need it (at most a 16-character name and the
/// longest pin: 26 columns, which leaves the words 43 at 80 columns).
pub fn head_w(view: &CheckView) -> usize {
    let (name_w, pin_w) = circuit_columns(view);
    HEAD_NAME_W.max(name_w + 1 + pin_w)
}

/// "Landing Light" padded or cut to `w` columns, with "…" where cut.
pub fn fit(s: &str, w: usize) -> String {
    let n = s.chars().count();
    if n <= w {
        format!("{s:<w$}")
    } else if w == 0 {
        String::new()
    } else {
        let cut: String = s.chars().take(w - 1).collect();
        format!("{cut}…")
    }
}

/// Below 80×24 the check's lists and prompts would be cut mid-word: it says so.
fn too_small(buf: &mut Buffer, area: Rect) {
    let lines = [
        Line::styled("INSTALLATION CHECK", theme::panel_title()),
        Line::styled("Terminal too small", theme::caution()),
        Line::raw(format!(
            "{}×{} now, needs {MIN_WIDTH}×{MIN_HEIGHT}.",
            area.width, area.height
        )),
        Line::raw("Enlarge the window or use a smaller font."),
        Line::styled("Until then keys do nothing; Ctrl-C quits.", theme::label()),
    ];
    let top = area.y + area.height.saturating_sub(lines.len() as u16) / 2;
    for (i, line) in lines.iter().enumerate() {
        let w = line.width().min(usize::from(area.width)) as u16;
        let x = area.x + (area.width - w) / 2;
        let row = Rect::new(x, top + i as u16, w, 1).intersection(area);
        unwrapped::lines(buf, row, std::slice::from_ref(line));
    }
}

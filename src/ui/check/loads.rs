//! Step 5 on screen: the electrical load analysis as a table of the phases, a bar
//! chart of them against the alternator's rating, and the circuits with where each
//! current came from. Every verdict has its symbol and word beside its colour.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};

use crate::check::state::{LoadsView, Mark};
use crate::check::words;
use crate::loads::analysis::{MARGIN_WARNING_PERCENT, amps_text, minutes_text};
use crate::loads::{Analysis, Figure, Level, Phase};
use crate::ui::{theme, wrap};

fn mark(level: Level) -> Mark {
    Mark::of(level)
}

fn mark_style(level: Level) -> Style {
    match level {
        Level::Ok => theme::on_off(true),
        Level::Warn => theme::caution(),
        Level::Fail => theme::alert(),
    }
}

/// Draws step 5 into `area`: the analysis (its circuits from `first_circuit` on, as
/// many as fit), or what stands in its way; `None` is a step not reached or skipped.
pub fn render(buf: &mut Buffer, area: Rect, loads: Option<&LoadsView>, first_circuit: usize) {
    let mut w = Writer { buf, area, y: 0 };
    match loads {
        None => {
            w.line(&[(
                format!(
                    "{} No load analysis: the step was skipped or not reached.",
                    Mark::Skipped.symbol()
                ),
                theme::label(),
            )]);
        }
        Some(LoadsView::TemplateWritten(path)) => {
            w.line(&[(
                format!("{}: no load file yet.", words::badge(Mark::Warn)),
                theme::caution(),
            )]);
            w.wrapped(
                &format!(
                    "A template listing every circuit was written to {}. Write the \
                     alternator's rating and the battery's capacity in it, turn off what \
                     is off in each phase, type a current for each circuit the check \
                     cannot measure, and run the check again.",
                    path.display()
                ),
                theme::label(),
            );
        }
        Some(LoadsView::Refused(why)) => {
            w.line(&[(
                format!(
                    "{}: the load file cannot be used.",
                    words::badge(Mark::Fail)
                ),
                theme::alert(),
            )]);
            for problem in why.lines() {
                w.wrapped(problem, theme::label());
            }
        }
        Some(LoadsView::Analysed { path, analysis }) => {
            w.line(&[
                ("Load file ".into(), theme::label()),
                (path.display().to_string(), theme::info()),
            ]);
            ratings(&mut w, analysis);
            let chart_rows = Phase::ALL.len() as u16 + 1;
            phase_table(&mut w, analysis);
            for &(id, amps) in &analysis.unlisted {
                let x = w.put(
                    0,
                    &format!("{} ", words::badge(Mark::Warn)),
                    theme::caution(),
                );
                hanging(
                    &mut w,
                    x,
                    &format!(
                        "the {} pin draws {} A but is not in the load file: it is in no phase",
                        crate::protocol::device::device(id).map_or("?", |d| d.system_name),
                        amps_text(amps)
                    ),
                    theme::caution(),
                );
            }
            // The chart only where it fits whole beside a blank line above it.
            if w.left() > chart_rows {
                w.y += 1;
                bar_chart(&mut w, analysis);
            }
            if w.left() > 2 {
                w.y += 1;
                circuit_table(&mut w, analysis, first_circuit);
            }
        }
    }
}

/// Writes lines down an area, clipped to it.
struct Writer<'a> {
    buf: &'a mut Buffer,
    area: Rect,
    y: u16,
}

impl Writer<'_> {
    fn left(&self) -> u16 {
        self.area.height.saturating_sub(self.y)
    }

    /// Spans at `x` (from the area's left) on the current line, without moving down.
    fn put(&mut self, x: u16, text: &str, style: Style) -> u16 {
        if self.y >= self.area.height || x >= self.area.width {
            return x;
        }
        let room = (self.area.width - x) as usize;
        let (end, _) =
            self.buf
                .set_stringn(self.area.x + x, self.area.y + self.y, text, room, style);
        end - self.area.x
    }

    fn line(&mut self, spans: &[(String, Style)]) {
        let mut x = 0;
        for (t, s) in spans {
            x = self.put(x, t, *s);
        }
        self.y += 1;
    }

    /// `text` wrapped at spaces to the area's width.
    fn wrapped(&mut self, text: &str, style: Style) {
        if text.is_empty() {
            return;
        }
        for row in wrap::text(text, usize::from(self.area.width)) {
            self.line(&[(row, style)]);
        }
    }
}

fn ratings(w: &mut Writer, a: &Analysis) {
    w.line(&[
        ("Alternator ".into(), theme::label()),
        (
            format!("{} A", amps_text(a.alternator_amps)),
            theme::panel_title(),
        ),
        ("   Battery ".into(), theme::label()),
        (
            format!(
                "{} Ah × {} usable = {} Ah",
                amps_text(a.battery_amp_hours),
                a.battery_usable,
                amps_text(a.usable_amp_hours())
            ),
            theme::panel_title(),
        ),
    ]);
}

const PHASE_W: u16 = 25;
const TOTAL_W: u16 = 8;

/// One line a phase: its name, its total, its mark and word, and the verdict in words.
fn phase_table(w: &mut Writer, a: &Analysis) {
    let header = theme::label().add_modifier(Modifier::BOLD);
    w.put(0, "Phase", header);
    w.put(PHASE_W + TOTAL_W - 5, "Total", header);
    w.put(PHASE_W + TOTAL_W + 2, "Verdict", header);
    w.y += 1;
    for p in &a.phases {
        let m = mark(p.level);
        w.put(0, p.phase.title(), theme::label());
        let total = format!(
            "{:>w$}",
            format!("{} A", amps_text(p.amps)),
            w = TOTAL_W as usize
        );
        w.put(PHASE_W, &total, theme::panel_title());
        let x = w.put(
            PHASE_W + TOTAL_W + 2,
            &format!("{} {:<7}", m.symbol(), m.word()),
            mark_style(p.level),
        ) + 1;
        // The verdict wrapped under itself, never cut: at 80 columns "margin 15 % of
        // 18 A: under 20 %; at least: no current for …" runs past the edge.
        hanging(w, x, &a.verdict(p.phase), theme::label());
    }
}

/// `text` from column `x` on the current line, wrapped at spaces onto the lines
/// below at the same column; moves past its last line.
fn hanging(w: &mut Writer, x: u16, text: &str, style: Style) {
    let room = usize::from(w.area.width.saturating_sub(x)).max(12);
    for part in wrap::text(text, room) {
        w.put(x, &part, style);
        w.y += 1;
    }
}

/// The chart's short names, so the bars get the width.
fn short(phase: Phase) -> &'static str {
    match phase {
        Phase::Emergency => "emergency",
        p => p.title(),
    }
}

const LABEL_W: u16 = 13;
/// " 26.6 A ⚠" and the emergency phase's " 199 min".
const VALUE_W: u16 = 18;
const EIGHTHS: [&str; 8] = [" ", "▏", "▎", "▍", "▌", "▋", "▊", "▉"];

/// A bar per phase on one scale, the alternator's rating a line down the chart (`│`)
/// and the 80 % mark beside it (`┆`); the emergency phase, on the battery, has no
/// alternator and shows its endurance.
fn bar_chart(w: &mut Writer, a: &Analysis) {
    let bar_w = w.area.width.saturating_sub(LABEL_W + VALUE_W);
    if bar_w < 10 {
        return;
    }
    let top = a
        .phases
        .iter()
        .map(|p| p.amps)
        .fold(a.alternator_amps, f64::max);
    let col =
        |amps: f64| -> u16 { ((amps / top * f64::from(bar_w)).round() as u16).min(bar_w - 1) };
    let alt_col = col(a.alternator_amps);
    let warn_col = col(a.alternator_amps * (100.0 - MARGIN_WARNING_PERCENT) / 100.0);
    for p in &a.phases {
        w.put(0, short(p.phase), theme::label());
        let style = mark_style(p.level).remove_modifier(Modifier::BOLD);
        let eighths = (p.amps / top * f64::from(bar_w) * 8.0).round() as u32;
        let (full, part) = ((eighths / 8) as u16, (eighths % 8) as usize);
        for c in 0..bar_w {
            let (sym, st) = if c < full {
                ("█", style)
            } else if c == full && part > 0 {
                (EIGHTHS[part], style)
            } else if !p.phase.on_battery() && c == alt_col {
                ("│", theme::label())
            } else if !p.phase.on_battery() && c == warn_col {
                ("┆", theme::label())
            } else {
                continue;
            };
            w.put(LABEL_W + c, sym, st);
        }
        let value = match (p.phase.on_battery(), p.endurance_minutes) {
            (true, Some(min)) => format!("{} A {} min", amps_text(p.amps), minutes_text(min)),
            _ => format!("{} A", amps_text(p.amps)),
        };
        let x = w.put(
            LABEL_W + bar_w + 1,
            &format!("{value:>12}"),
            theme::panel_title(),
        );
        w.put(x + 1, mark(p.level).symbol(), mark_style(p.level));
        w.y += 1;
    }
    w.line(&[
        (" ".repeat(LABEL_W as usize), theme::label()),
        (
            format!(
                "│ alternator {} A   ┆ {} % of it (under {MARGIN_WARNING_PERCENT} % spare: {})",
                amps_text(a.alternator_amps),
                100.0 - MARGIN_WARNING_PERCENT,
                Mark::Warn.word()
            ),
            theme::label(),
        ),
    ]);
}

const NAME_W: u16 = 15;
const PIN_W: u16 = 10;
const CURRENT_W: u16 = 15;
const COL_W: u16 = 6;

/// The circuits from `first` on, as many as fit, with each current's source and
/// whether it is on in each phase.
fn circuit_table(w: &mut Writer, a: &Analysis, first: usize) {
    let header = theme::label().add_modifier(Modifier::BOLD);
    w.put(0, "Circuit", header);
    w.put(NAME_W, "Pin", header);
    w.put(NAME_W + PIN_W, "Current", header);
    for (i, label) in ["gnd", "taxi", "t/o", "day", "night", "ldg", "emer"]
        .into_iter()
        .enumerate()
    {
        w.put(NAME_W + PIN_W + CURRENT_W + i as u16 * COL_W, label, header);
    }
    w.y += 1;
    let first = first.min(a.rows.len().saturating_sub(1));
    let rows = &a.rows[first..];
    let room = w.left() as usize;
    let shown = if rows.len() > room {
        room.saturating_sub(1)
    } else {
        rows.len()
    };
    for r in &rows[..shown] {
        w.put(
            0,
            &clipped(&r.name, NAME_W as usize - 1),
            theme::panel_title(),
        );
        w.put(NAME_W, r.pin, theme::label());
        let (current, style) = match r.figure {
            Figure::Missing => (
                format!("{} no current", Mark::Warn.symbol()),
                theme::caution(),
            ),
            f => (
                format!("{} A {}", amps_text(f.amps()), f.source()),
                theme::label(),
            ),
        };
        w.put(NAME_W + PIN_W, &current, style);
        for (i, d) in r.duty.iter().enumerate() {
            let (t, s) = duty_text(*d);
            w.put(NAME_W + PIN_W + CURRENT_W + i as u16 * COL_W, &t, s);
        }
        w.y += 1;
    }
    if shown < rows.len() {
        w.line(&[(
            format!("↓ {} more circuits", rows.len() - shown),
            theme::label(),
        )]);
    }
}

/// "on", "–" for off, or the fraction of the time.
fn duty_text(d: f64) -> (String, Style) {
    if d >= 1.0 {
        ("on".into(), theme::on_off(true))
    } else if d <= 0.0 {
        ("–".into(), theme::label())
    } else {
        (format!("{d}"), theme::on_off(true))
    }
}

/// `text` in at most `width` characters, its last one "…" when cut.
fn clipped(text: &str, width: usize) -> String {
    if text.chars().count() <= width {
        text.to_string()
    } else {
        let mut t: String = text.chars().take(width.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

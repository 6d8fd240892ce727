//! The Appendix A device list: one row per enabled circuit, flaps and trim grouped
//! apart, coloured green=on, white=off, red=faulted.

use std::cmp::Ordering;
use std::time::Instant;

use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line;

use super::panel::Panel;
use super::state::{SortOrder, ViewState};
use super::{theme, values};
use crate::model::{Circuit, CircuitKind, CircuitState, Model};

/// Flaps and trims form their own group under the other devices (Appendix A).
fn is_motor(c: &Circuit) -> bool {
    matches!(c.kind, CircuitKind::Flaps | CircuitKind::Trim(_))
}

/// The rows in display order; see [`super::ordered_circuits`].
pub fn ordered(model: &Model, view: &ViewState, now: Instant) -> Vec<Circuit> {
    let mut rows = model.circuits(now);
    let by = |a: &Circuit, b: &Circuit| -> Ordering {
        let group = is_motor(a).cmp(&is_motor(b));
        let within = match view.sort {
            SortOrder::Pin => a.id.cmp(&b.id),
            SortOrder::Alphabetical => a
                .name
                .to_lowercase()
                .cmp(&b.name.to_lowercase())
                .then(a.id.cmp(&b.id)),
        };
        group.then(within)
    };
    rows.sort_by(by);
    rows
}

/// "A1"/"A2" beside the alternators, so a dual-alternator system shows which is which.
fn role(c: &Circuit) -> &'static str {
    match c.kind {
        CircuitKind::Alternator { primary: true } => "A1",
        CircuitKind::Alternator { primary: false } => "A2",
        _ => "",
    }
}

/// The columns after the name, and their widths: Pin, role, State, Amps, CB, Switch.
const FIXED: [u16; 6] = [9, 2, 13, 4, 3, 6];
/// Between columns.
const SPACING: u16 = 1;
const HIGHLIGHT: &str = "▶";

/// The text and style of each of a circuit's seven cells.
fn cells(c: &Circuit) -> [(String, Style); 7] {
    let dim = theme::unknown();
    if let CircuitState::ResetSent(_) = c.state {
        // "SHORT_CIRCUIT · reset sent" is wider than the State column: it runs on
        // over the amps, breaker and switch until the unit answers the reset.
        let blank = || (String::new(), Style::new());
        return [
            (c.name.clone(), Style::new()),
            (c.pin.to_string(), theme::label()),
            (role(c).to_string(), theme::info()),
            (values::state_text(c.state), theme::state(c.state)),
            blank(),
            blank(),
            blank(),
        ];
    }
    [
        (c.name.clone(), Style::new()),
        (c.pin.to_string(), theme::label()),
        (role(c).to_string(), theme::info()),
        (values::state_text(c.state), theme::state(c.state)),
        (
            values::amps(c.amps),
            if c.amps.is_some() { Style::new() } else { dim },
        ),
        // A spec left unknown by an unanswered write is "?" until re-read, never
        // the value from before the write.
        if c.spec_unknown {
            ("?A".into(), theme::caution())
        } else {
            (
                c.breaker
                    .map_or_else(|| values::BLANK.into(), |b| format!("{b}A")),
                Style::new(),
            )
        },
        match c.kind {
            CircuitKind::Starter => ("VP-X".into(), Style::new()),
            CircuitKind::Flaps => ("flap".into(), Style::new()),
            CircuitKind::Trim(_) => ("trim".into(), Style::new()),
            _ if c.spec_unknown => ("?".into(), theme::caution()),
            _ => (values::switch_short(c.switch), Style::new()),
        },
    ]
}

/// The x of each column and its width, in a list whose inside is `inner`: the
/// highlight mark's column, then the name taking what the fixed columns leave.
fn columns(inner: Rect) -> [(u16, u16); 7] {
    let mark = HIGHLIGHT.chars().count() as u16;
    let fixed: u16 = FIXED.iter().sum::<u16>() + SPACING * FIXED.len() as u16;
    let name_w = inner.width.saturating_sub(mark + fixed);
    let mut out = [(0, 0); 7];
    let mut x = inner.x + mark;
    out[0] = (x, name_w);
    x += name_w;
    for (i, w) in FIXED.iter().enumerate() {
        x += SPACING;
        out[i + 1] = (x, *w);
        x += w;
    }
    out
}

/// One line of the list written straight into the buffer: the list is the largest
/// part of the frame, and a `Table` of styled cells cost more than the rest of the
/// page together.
/// A cell wider than its column runs on over the empty cells after it.
fn write_line(buf: &mut Buffer, inner: Rect, y: u16, cells: &[(&str, Style)]) {
    let right = inner.right();
    let cols = columns(inner);
    for (i, ((x, w), (text, style))) in cols.iter().zip(cells).enumerate() {
        let needed = text.chars().count() as u16;
        let mut w = *w;
        for ((nx, nw), (next, _)) in cols.iter().zip(cells).skip(i + 1) {
            if w >= needed || !next.is_empty() {
                break;
            }
            w = nx + nw - x;
        }
        let w = w.min(right.saturating_sub(*x));
        if w > 0 {
            super::unwrapped::put(buf, *x, y, text, w, *style);
        }
    }
}

/// A breaker over its wire (AC 43.13-1B Table 11-3), marked at the end of the name
/// column with a symbol and a word, so it never rests on colour: the detail pane says
/// which wire and which limit.
pub const UNPROTECTED_MARK: &str = "⚠WIRE";

fn mark_unprotected(buf: &mut Buffer, inner: Rect, y: u16) {
    let (x, w) = columns(inner)[0];
    let n = UNPROTECTED_MARK.chars().count() as u16;
    if w > n {
        super::unwrapped::put(buf, x + w - n, y, UNPROTECTED_MARK, n, theme::alert());
    }
}

/// `rereading`: the unit's names and settings are being read again after a loss
/// (`model::reread`), which the title says.
pub fn render(frame: &mut Frame, area: Rect, rows: &[Circuit], view: &ViewState, rereading: bool) {
    // `None` is the flaps & trim group header.
    let mut lines: Vec<Option<&Circuit>> = Vec::with_capacity(rows.len() + 1);
    let mut selected_index = None;
    let mut in_motors = false;
    for c in rows {
        if is_motor(c) && !in_motors {
            in_motors = true;
            lines.push(None);
        }
        if view.selected == Some(c.id) {
            selected_index = Some(lines.len());
        }
        lines.push(Some(c));
    }
    let sort = match view.sort {
        SortOrder::Pin => "by pin",
        SortOrder::Alphabetical => "A-Z",
    };
    // The offset that keeps the selection on screen (rows are one line each), worked
    // out here so the title can say how many rows are off screen: a short terminal must
    // never hide a device silently.
    let visible = area.height.saturating_sub(2) as usize;
    let total = lines.len();
    let offset = selected_index.map_or(0, |i| (i + 1).saturating_sub(visible));
    let below = total.saturating_sub(offset + visible);
    let mut more = Vec::new();
    if offset > 0 {
        more.push(format!("▲{offset} more"));
    }
    if below > 0 {
        more.push(format!("▼{below} more"));
    }
    let more =
        (!more.is_empty()).then(|| Line::styled(format!(" {} ", more.join(" ")), theme::caution()));
    let mut titles = vec![
        Line::styled(" Devices ", theme::panel_title()),
        Line::styled(format!("{sort} "), theme::label()),
    ];
    if rereading {
        titles.push(Line::styled("re-reading settings… ", theme::caution()));
    }
    let inner = Panel {
        right_side: true,
        border: theme::border(),
        titles: &titles,
        right_title: more.as_ref(),
    }
    .render(area, frame.buffer_mut());
    if inner.height == 0 || inner.width == 0 {
        return;
    }
    let buf = frame.buffer_mut();
    let header_style = theme::label().add_modifier(Modifier::UNDERLINED);
    buf.set_style(Rect { height: 1, ..inner }, header_style);
    let header = ["Device", "Pin", "", "State", "Amps", "CB", "Switch"].map(|t| (t, Style::new()));
    write_line(buf, inner, inner.y, &header);
    // Only the rows on screen are built.
    for (k, line) in lines.iter().skip(offset).take(visible).enumerate() {
        let y = inner.y + 1 + k as u16;
        if y >= inner.bottom() {
            break;
        }
        match line {
            None => write_line(
                buf,
                inner,
                y,
                &[("flaps/trim", theme::label().add_modifier(Modifier::ITALIC))],
            ),
            Some(c) => {
                let cells = cells(c);
                let refs = cells.each_ref().map(|(t, s)| (t.as_str(), *s));
                write_line(buf, inner, y, &refs);
                if crate::loads::wiring::unprotected(&view.wires, c.id, c.breaker) {
                    mark_unprotected(buf, inner, y);
                }
            }
        }
        if selected_index == Some(offset + k) {
            let row = Rect {
                y,
                height: 1,
                ..inner
            };
            super::unwrapped::put(buf, inner.x, y, HIGHLIGHT, 1, Style::new());
            buf.set_style(row, theme::selected_row());
        }
    }
}

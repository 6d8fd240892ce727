//! A list of results under a section title: each row a few fixed columns (mark, name,
//! reading) and then its words, wrapped rather than cut, since a finding cut in half
//! ("no current while on: an open…") loses what the person must do. When the rows do
//! not fit, the list keeps the item in focus in sight and says how many are hidden
//! above and below.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use crate::ui::{theme, unwrapped, wrap};

/// One entry: its fixed columns, then its words.
pub struct Row {
    pub head: Vec<Span<'static>>,
    pub words: String,
    pub words_style: Style,
    /// The item under test now: drawn on the selection band.
    pub current: bool,
}

/// The narrowest column the words get beside the head; below it they go under it.
const MIN_WORDS: usize = 24;
/// Where words that go under the head start.
const UNDER_INDENT: usize = 4;

fn head_width(head: &[Span]) -> usize {
    head.iter().map(|s| s.content.chars().count()).sum()
}

/// The screen lines of `row` at `width`.
pub fn lines_of(row: &Row, width: u16) -> Vec<Line<'static>> {
    let width = usize::from(width);
    let hw = head_width(&row.head);
    let band = if row.current {
        theme::selected_row()
    } else {
        Style::new()
    };
    let mut out = Vec::new();
    // The band of the item under test runs the whole width, as the page's selection.
    let pad = |mut line: Line<'static>| -> Line<'static> {
        let w = line.width();
        if row.current && w < width {
            line.spans.push(Span::raw(" ".repeat(width - w)));
        }
        line
    };
    if row.words.is_empty() {
        out.push(pad(Line::from(row.head.clone()).style(band)));
        return out;
    }
    if width >= hw + MIN_WORDS {
        for (i, part) in wrap::text(&row.words, width - hw).into_iter().enumerate() {
            let mut spans = if i == 0 {
                row.head.clone()
            } else {
                vec![Span::raw(" ".repeat(hw))]
            };
            spans.push(Span::styled(part, row.words_style));
            out.push(pad(Line::from(spans).style(band)));
        }
    } else {
        out.push(pad(Line::from(row.head.clone()).style(band)));
        let indent = UNDER_INDENT.min(width.saturating_sub(1));
        for part in wrap::text(&row.words, width - indent) {
            out.push(pad(Line::from(vec![
                Span::raw(" ".repeat(indent)),
                Span::styled(part, row.words_style),
            ])
            .style(band)));
        }
    }
    out
}

/// Rows `[from, to)` of `rows` to show in `height` lines so that `focus` is seen:
/// a couple of rows before it for context, then as many after it as fit.
fn window(heights: &[usize], height: usize, focus: usize) -> (usize, usize) {
    let focus = focus.min(heights.len().saturating_sub(1));
    let (mut from, mut to) = (focus, focus);
    let mut used = 0;
    let take_after = |to: &mut usize, used: &mut usize| {
        while *to < heights.len() && *used + heights[*to] <= height {
            *used += heights[*to];
            *to += 1;
        }
    };
    // Two rows of context before the focus, if they fit with it.
    let before: usize = heights[focus.saturating_sub(2)..focus].iter().sum();
    if before + heights.get(focus).copied().unwrap_or(0) <= height {
        from = focus.saturating_sub(2);
        used = before;
    }
    take_after(&mut to, &mut used);
    while from > 0 && used + heights[from - 1] <= height {
        from -= 1;
        used += heights[from];
    }
    (from, to.max(from))
}

/// Draws `rows` in `area`, keeping `focus` (or the first row) in sight.
pub fn render(buf: &mut Buffer, area: Rect, rows: &[Row], focus: Option<usize>) {
    if area.height == 0 || rows.is_empty() {
        return;
    }
    let per_row: Vec<Vec<Line>> = rows.iter().map(|r| lines_of(r, area.width)).collect();
    let heights: Vec<usize> = per_row.iter().map(Vec::len).collect();
    let total: usize = heights.iter().sum();
    let h = usize::from(area.height);
    let mut lines: Vec<Line> = Vec::new();
    if total <= h {
        lines = per_row.into_iter().flatten().collect();
    } else {
        // Room for a "more below" line, and a "more above" one only when needed.
        let focus = focus.unwrap_or(0);
        let (mut from, mut to) = window(&heights, h.saturating_sub(1).max(1), focus);
        if from > 0 && to < rows.len() {
            (from, to) = window(&heights, h.saturating_sub(2).max(1), focus);
        }
        if from > 0 {
            lines.push(more(format!("↑ {from} more above")));
        }
        lines.extend(per_row[from..to].iter().flatten().cloned());
        if to < rows.len() {
            lines.push(more(format!("↓ {} more below", rows.len() - to)));
        }
        lines.truncate(h);
    }
    unwrapped::lines(buf, area, &lines);
}

/// What a scrolled list shows: from line `top`, `body` lines, with a line above
/// saying how many are hidden above, and one below for those below.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Scrolled {
    pub top: usize,
    pub body: usize,
    pub above: bool,
    pub below: bool,
}

/// The furthest a list of `total` lines scrolls in `height`: its last line at the
/// bottom, under the "above" line.
pub fn scroll_max_of(total: usize, height: usize) -> usize {
    if total <= height {
        0
    } else {
        total - height.saturating_sub(1).max(1)
    }
}

/// Where a list of `total` lines scrolled to `top` shows its lines in `height`.
pub fn scrolled(total: usize, height: usize, top: usize) -> Scrolled {
    if total <= height {
        return Scrolled {
            top: 0,
            body: total,
            above: false,
            below: false,
        };
    }
    let top = top.min(scroll_max_of(total, height));
    let above = top > 0;
    let room = height.saturating_sub(usize::from(above)).max(1);
    let left = total - top;
    if left <= room {
        Scrolled {
            top,
            body: left,
            above,
            below: false,
        }
    } else {
        Scrolled {
            top,
            body: room.saturating_sub(1).max(1),
            above,
            below: true,
        }
    }
}

/// The lines of `rows` at `width`, one after the other.
fn all_lines(rows: &[Row], width: u16) -> Vec<Line<'static>> {
    rows.iter().flat_map(|r| lines_of(r, width)).collect()
}

/// How far [`render_scrolled`] lets `rows` scroll in `area`.
pub fn scroll_max(area: Rect, rows: &[Row]) -> usize {
    scroll_max_of(all_lines(rows, area.width).len(), usize::from(area.height))
}

/// Draws `rows` in `area` from line `top` on (kept within the list), saying how many
/// lines are hidden above and below: the results of an ended check, which the
/// person scrolls (↑↓ PgUp PgDn Home End).
pub fn render_scrolled(buf: &mut Buffer, area: Rect, rows: &[Row], top: usize) {
    if area.height == 0 || rows.is_empty() {
        return;
    }
    let all = all_lines(rows, area.width);
    let s = scrolled(all.len(), usize::from(area.height), top);
    let mut lines = Vec::new();
    if s.above {
        lines.push(more(format!("↑ {} more lines above", s.top)));
    }
    lines.extend(all[s.top..s.top + s.body].iter().cloned());
    if s.below {
        lines.push(more(format!(
            "↓ {} more lines below",
            all.len() - s.top - s.body
        )));
    }
    unwrapped::lines(buf, area, &lines);
}

fn more(text: String) -> Line<'static> {
    Line::styled(text, theme::label())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Scrolled to the top, the end, or past it: every line is reachable, the last
    /// one ends at the bottom, and what is hidden is said.
    #[test]
    fn a_scrolled_list_reaches_every_line_and_says_what_is_hidden() {
        let s = |total, h, top| scrolled(total, h, top);
        // Fits: all of it, nothing said.
        assert_eq!(
            s(5, 10, 3),
            Scrolled {
                top: 0,
                body: 5,
                above: false,
                below: false
            }
        );
        // 30 lines in 10: the first 9 and "below".
        assert_eq!(
            s(30, 10, 0),
            Scrolled {
                top: 0,
                body: 9,
                above: false,
                below: true
            }
        );
        // In the middle: "above", 8 lines, "below".
        assert_eq!(
            s(30, 10, 5),
            Scrolled {
                top: 5,
                body: 8,
                above: true,
                below: true
            }
        );
        // The end, and past it: "above" and the last 9 lines, 21..30.
        assert_eq!(scroll_max_of(30, 10), 21);
        for top in [21, 22, 1000] {
            assert_eq!(
                s(30, 10, top),
                Scrolled {
                    top: 21,
                    body: 9,
                    above: true,
                    below: false
                }
            );
        }
        // Every line is shown at some scroll.
        let mut seen = [false; 30];
        for top in 0..=scroll_max_of(30, 10) {
            let v = s(30, 10, top);
            assert!(v.body + usize::from(v.above) + usize::from(v.below) <= 10);
            seen[v.top..v.top + v.body]
                .iter_mut()
                .for_each(|x| *x = true);
        }
        assert!(seen.iter().all(|&x| x));
    }

    #[test]
    fn the_focus_stays_in_sight_with_context_before_it() {
        let h = [1; 10];
        assert_eq!(window(&h, 4, 0), (0, 4));
        assert_eq!(window(&h, 4, 6), (4, 8));
        assert_eq!(window(&h, 4, 9), (6, 10));
        // A tall row before the focus is dropped rather than the focus.
        assert_eq!(window(&[5, 5, 1, 1], 3, 2), (2, 4));
    }
}

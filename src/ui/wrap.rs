//! Word wrap: the rows ratatui's `Paragraph` with `Wrap { trim: true }` makes of a
//! line, as lines of their own, for the places that need the rows themselves: to
//! count them, to hang them under a column, to scroll through them. Where a text is
//! only drawn, the `Paragraph` wraps it; the test below holds both to the same rows.
//!
//! Words break at whitespace but not at the non-breaking space; a wrapped row drops
//! the whitespace it would start with; a word longer than a row is cut across rows.
//! ratatui keeps its own wrapper private, so its steps are taken here as it takes them.

use std::collections::VecDeque;

use ratatui::buffer::CellWidth;
use ratatui::style::Style;
use ratatui::text::{Line, Span, StyledGrapheme};

/// The rows of `line`, left-aligned, at most `width` columns each; every row keeps
/// the styles its characters had.
pub fn lines(line: &Line, width: u16) -> Vec<Line<'static>> {
    let mut rows: Vec<Vec<StyledGrapheme>> = Vec::new();
    let mut row: Vec<StyledGrapheme> = Vec::new();
    let (mut row_w, mut word_w, mut space_w) = (0u16, 0u16, 0u16);
    let mut word: Vec<StyledGrapheme> = Vec::new();
    let mut space: VecDeque<StyledGrapheme> = VecDeque::new();
    let mut after_word = false;
    for g in line.styled_graphemes(Style::new()) {
        let blank = g.is_whitespace();
        let w = g.symbol.cell_width();
        if w > width {
            continue;
        }
        let word_found = after_word && blank;
        let word_overflow = row.is_empty() && word_w + w > width;
        let space_overflow = row.is_empty() && space_w + w > width;
        if word_found || word_overflow || space_overflow {
            if !row.is_empty() {
                row.extend(space.drain(..));
                row_w += space_w;
            }
            row.append(&mut word);
            row_w += word_w;
            space.clear();
            (space_w, word_w) = (0, 0);
        }
        if row_w >= width || (w > 0 && row_w + space_w + word_w >= width) {
            let mut room = width.saturating_sub(row_w);
            rows.push(std::mem::take(&mut row));
            row_w = 0;
            // The whitespace that fits at the end of the row ends with it.
            while let Some(first) = space.front() {
                let sw = first.symbol.cell_width();
                if sw > room {
                    break;
                }
                space_w -= sw;
                room -= sw;
                space.pop_front();
            }
            if blank && space.is_empty() {
                continue;
            }
        }
        if blank {
            space_w += w;
            space.push_back(g);
        } else {
            word_w += w;
            word.push(g);
        }
        after_word = !blank;
    }
    if row.is_empty() && word.is_empty() && !space.is_empty() {
        rows.push(Vec::new());
    }
    if !row.is_empty() {
        row.extend(space.drain(..));
    }
    row.append(&mut word);
    if !row.is_empty() || rows.is_empty() {
        rows.push(row);
    }
    rows.into_iter().map(spans).collect()
}

/// Graphemes as spans, one a run of the same style.
fn spans(row: Vec<StyledGrapheme>) -> Line<'static> {
    let mut out: Vec<Span<'static>> = Vec::new();
    for g in row {
        match out.last_mut() {
            Some(last) if last.style == g.style => last.content.to_mut().push_str(g.symbol),
            _ => out.push(Span::styled(g.symbol.to_string(), g.style)),
        }
    }
    Line::from(out)
}

/// `text` in rows of at most `width` columns. A number keeps its unit on its row
/// ("18 %", "4.2 A", "3 s"); the rows have plain spaces (and so has a copy of them
/// from the screen).
pub fn text(text: &str, width: usize) -> Vec<String> {
    let glued = Line::raw(glue(text));
    let width = u16::try_from(width.max(1)).unwrap_or(u16::MAX);
    lines(&glued, width)
        .into_iter()
        .map(|l| {
            l.spans
                .iter()
                .map(|s| s.content.replace('\u{a0}', " "))
                .collect()
        })
        .collect()
}

/// The space between a number and its unit as a non-breaking one.
fn glue(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut prev_digit = false;
    for (i, word) in text.split(' ').enumerate() {
        let unit = word.trim_end_matches([',', ')', ';', '.', ':']);
        if i > 0 {
            let sticks =
                prev_digit && matches!(unit, "%" | "A" | "V" | "s" | "ms" | "min" | "counts");
            out.push(if sticks { '\u{a0}' } else { ' ' });
        }
        out.push_str(word);
        prev_digit = word.ends_with(|c: char| c.is_ascii_digit());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::buffer::Buffer;
    use ratatui::layout::Rect;
    use ratatui::style::{Color, Modifier};
    use ratatui::widgets::{Paragraph, Widget, Wrap};

    /// The rows drawn one under the other are the cells a wrapping `Paragraph` draws,
    /// over many made-up texts of the kinds the page wraps: words glued by
    /// non-breaking spaces, runs of spaces, leading spaces, words longer than the row,
    /// styles changing mid-word. (Not wide characters: a wrapping `Paragraph` may
    /// draw one across its right edge, which a row cut to the width does not.)
    #[test]
    fn rows_are_those_of_a_wrapping_paragraph() {
        let words = [
            "state",
            "ON",
            "\u{a0}o\u{a0}",
            "\u{a0}on\u{a0}(until\u{a0}switch\u{a0}cycled)",
            "FAULT",
            "SHORT_CIRCUIT",
            "(0x05)",
            "·",
            "a-very-long-word-longer-than-rows",
            "",
            "x",
            "°C",
            "▶",
        ];
        let styles = [
            Style::new(),
            Style::new().fg(Color::Red).add_modifier(Modifier::BOLD),
            Style::new().fg(Color::Black).bg(Color::Gray),
        ];
        let mut seed = 5u64;
        let mut next = |n: usize| {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (seed >> 33) as usize % n
        };
        for case in 0..3000 {
            let mut text = Vec::new();
            for _ in 0..1 + next(4) {
                let mut spans = Vec::new();
                for _ in 0..next(8) {
                    let mut s = String::new();
                    s.push_str(&" ".repeat([0, 0, 1, 1, 2, 3][next(6)]));
                    s.push_str(words[next(words.len())]);
                    s.push_str(&" ".repeat([0, 1, 1, 2][next(4)]));
                    spans.push(Span::styled(s, styles[next(styles.len())]));
                }
                let mut line = Line::from(spans);
                if next(5) == 0 {
                    line = line.style(Style::new().add_modifier(Modifier::ITALIC));
                }
                text.push(line);
            }
            let area = Rect::new(1, 1, 1 + next(40) as u16, 1 + next(7) as u16);
            let mut want = Buffer::empty(Rect::new(0, 0, 44, 10));
            Paragraph::new(text.clone())
                .wrap(Wrap { trim: true })
                .render(area, &mut want);
            let rows: Vec<Line> = text.iter().flat_map(|l| lines(l, area.width)).collect();
            let mut got = Buffer::empty(Rect::new(0, 0, 44, 10));
            Paragraph::new(rows).render(area, &mut got);
            if got != want {
                let show = |b: &Buffer| {
                    (0..b.area.height)
                        .map(|y| {
                            (0..b.area.width)
                                .map(|x| b[(x, y)].symbol().replace('\u{a0}', "~"))
                                .collect::<String>()
                        })
                        .collect::<Vec<_>>()
                        .join("|\n")
                };
                panic!(
                    "case {case}: {area:?} {text:?}\ngot:\n{}\nwant:\n{}",
                    show(&got),
                    show(&want)
                );
            }
        }
    }

    #[test]
    fn a_number_keeps_its_unit_and_a_word_too_long_is_cut() {
        assert_eq!(
            text("no current while on: an open circuit", 16),
            ["no current while", "on: an open", "circuit"]
        );
        assert_eq!(text("abcdefghij", 4), ["abcd", "efgh", "ij"]);
        assert_eq!(text("", 10), [""]);
        // A number and its unit stay together, and come out with a plain space.
        assert_eq!(text("moved 0 % → 18 %)", 14), ["moved 0 % →", "18 %)"]);
        assert_eq!(text("at 128 → 159 counts", 14), ["at 128 →", "159 counts"]);
    }
}

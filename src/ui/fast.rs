//! Writing lines of text straight into the buffer: the same cells a left-aligned,
//! unwrapped `Paragraph` writes, without its grapheme machinery for the text the page
//! mostly shows (ASCII, box drawing, arrows, braille). A frame is mostly such lines, and
//! this is what keeps a full 120×40 frame within its time (benches/render.rs).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::Line;

/// One column wide in every terminal and in ratatui's own measure: printable ASCII,
/// Latin-1 (°, ·, the non-breaking space), dashes and the ellipsis, arrows, box
/// drawing, blocks, geometric shapes and braille.
fn narrow(c: char) -> bool {
    matches!(c as u32,
        0x20..=0x7E
        | 0xA0..=0xAC
        | 0xAE..=0xFF
        | 0x2010..=0x2027
        | 0x2190..=0x21FF
        | 0x2500..=0x25FC
        | 0x25FF
        | 0x2800..=0x28FF)
}

/// Writes `text` at (`x`, `y`) in at most `max` columns; returns the column after it.
pub fn put(buf: &mut Buffer, x: u16, y: u16, text: &str, max: u16, style: Style) -> u16 {
    let area = buf.area;
    let end = x.saturating_add(max).min(area.right());
    if y < area.top() || y >= area.bottom() || x < area.left() || x >= end {
        return x;
    }
    let mut cx = x;
    for (i, (at, c)) in (buf.index_of(x, y)..).zip(text.char_indices()) {
        if cx >= end {
            break;
        }
        if !narrow(c) {
            // Anything else (wide, zero-width, control) the way ratatui measures it.
            let (nx, _) = buf.set_stringn(cx, y, &text[at..], (end - cx) as usize, style);
            return nx;
        }
        buf.content[i].set_char(c).set_style(style);
        cx += 1;
    }
    cx
}

/// `lines` from the top of `area`, each cut at its right edge, as `Paragraph` would.
pub fn lines(buf: &mut Buffer, area: Rect, lines: &[Line]) {
    for (line, y) in lines.iter().zip(area.top()..area.bottom()) {
        let mut x = area.x;
        for span in &line.spans {
            let style = line.style.patch(span.style);
            x = put(
                buf,
                x,
                y,
                &span.content,
                area.right().saturating_sub(x),
                style,
            );
        }
    }
}

/// `lines` word-wrapped into `area` as a `Paragraph` with `Wrap { trim: true }` wraps
/// them: the same words on the same rows. Words break at whitespace (not at the
/// non-breaking space), a wrapped row drops the whitespace it starts with, and a word
/// longer than a row is cut. Text beyond the page's usual characters goes to
/// `Paragraph` itself.
pub fn wrapped(buf: &mut Buffer, area: Rect, lines: &[Line]) {
    let area = area.intersection(buf.area);
    if area.is_empty() {
        return;
    }
    let plain = lines.iter().all(|l| {
        l.alignment
            .is_none_or(|a| a == ratatui::layout::Alignment::Left)
            && l.spans.iter().all(|s| s.content.chars().all(narrow))
    });
    if !plain {
        use ratatui::widgets::{Paragraph, Widget, Wrap};
        return Paragraph::new(lines.to_vec())
            .wrap(Wrap { trim: true })
            .render(area, buf);
    }
    let mut rows = Wrapper::new(area.width);
    let mut y = area.y;
    for line in lines {
        let chars = line.spans.iter().flat_map(|span| {
            let style = line.style.patch(span.style);
            span.content.chars().map(move |c| (c, style))
        });
        rows.wrap(chars);
        for row in rows.done.drain(..) {
            if y >= area.bottom() {
                return;
            }
            for ((c, style), x) in row.into_iter().zip(area.x..) {
                let i = buf.index_of(x, y);
                buf.content[i].set_char(c).set_style(style);
            }
            y += 1;
        }
    }
}

/// ratatui's `WordWrapper` (trim on) over characters one column wide, step for step:
/// with every character its own grapheme of width 1, its widths are counts.
struct Wrapper {
    max: usize,
    done: Vec<Vec<(char, Style)>>,
    word: Vec<(char, Style)>,
    space: std::collections::VecDeque<(char, Style)>,
}

impl Wrapper {
    fn new(max: u16) -> Wrapper {
        Wrapper {
            max: usize::from(max),
            done: Vec::new(),
            word: Vec::new(),
            space: std::collections::VecDeque::new(),
        }
    }

    fn wrap(&mut self, chars: impl Iterator<Item = (char, Style)>) {
        let max = self.max;
        let before = self.done.len();
        let mut line: Vec<(char, Style)> = Vec::new();
        self.word.clear();
        self.space.clear();
        let mut after_word = false;
        for (c, style) in chars {
            let blank = c.is_whitespace() && c != '\u{a0}';
            let word_found = after_word && blank;
            let trimmed_overflow = line.is_empty() && self.word.len() + 1 > max;
            let space_overflow = line.is_empty() && self.space.len() + 1 > max;
            if word_found || trimmed_overflow || space_overflow {
                if !line.is_empty() {
                    line.extend(self.space.drain(..));
                }
                line.append(&mut self.word);
                self.space.clear();
            }
            let full = line.len() >= max;
            let word_overflow = line.len() + self.space.len() + self.word.len() >= max;
            if full || word_overflow {
                let mut remaining = max.saturating_sub(line.len());
                self.done.push(std::mem::take(&mut line));
                while !self.space.is_empty() && remaining >= 1 {
                    remaining -= 1;
                    self.space.pop_front();
                }
                if blank && self.space.is_empty() {
                    continue;
                }
            }
            if blank {
                self.space.push_back((c, style));
            } else {
                self.word.push((c, style));
            }
            after_word = !blank;
        }
        if line.is_empty() && self.word.is_empty() && !self.space.is_empty() {
            self.done.push(Vec::new());
        }
        if !line.is_empty() {
            line.extend(self.space.drain(..));
        }
        line.append(&mut self.word);
        if !line.is_empty() {
            self.done.push(line);
        }
        if self.done.len() == before {
            self.done.push(Vec::new());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::style::{Color, Modifier};
    use ratatui::text::Span;
    use ratatui::widgets::{Paragraph, Widget};

    /// The same cells as `Paragraph`, for the kinds of text the page writes, cut at
    /// the edge included.
    #[test]
    fn writes_what_a_paragraph_writes() {
        let text = vec![
            Line::from(vec![
                Span::styled("temp ", Style::new().fg(Color::Gray)),
                Span::styled("31 °C", Style::new().add_modifier(Modifier::BOLD)),
                Span::raw(" │ ●○ ⣀⡀ ↑↓ … 漢字 é"),
            ]),
            Line::styled("flaps/trim", Style::new().fg(Color::Red)),
            Line::from("a line far too long for the area it is written in, cut"),
            Line::from("unseen: below the area"),
        ];
        let area = Rect::new(1, 1, 30, 3);
        let mut want = Buffer::empty(Rect::new(0, 0, 32, 5));
        Paragraph::new(text.clone()).render(area, &mut want);
        let mut got = Buffer::empty(Rect::new(0, 0, 32, 5));
        lines(&mut got, area, &text);
        assert_eq!(got, want);
        // A wide character that does not fit is left out, as ratatui does.
        let mut want = Buffer::empty(Rect::new(0, 0, 4, 1));
        want.set_stringn(0, 0, "abc漢", 4, Style::new());
        let mut got = Buffer::empty(Rect::new(0, 0, 4, 1));
        put(&mut got, 0, 0, "abc漢", 4, Style::new());
        assert_eq!(got, want);
    }

    /// The same rows as `Paragraph` with `Wrap { trim: true }`, over many made-up texts
    /// of the kinds the page wraps: words glued by non-breaking spaces, runs of spaces,
    /// leading spaces, words longer than the row, styles changing mid-word.
    #[test]
    fn wraps_as_a_wrapping_paragraph_does() {
        use ratatui::widgets::{Paragraph, Wrap};
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
            let mut got = Buffer::empty(Rect::new(0, 0, 44, 10));
            wrapped(&mut got, area, &text);
            if got != want {
                let rows = |b: &Buffer| {
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
                    rows(&got),
                    rows(&want)
                );
            }
        }
    }

    /// `narrow` is one column in the measure ratatui uses, for every character it
    /// takes.
    #[test]
    fn narrow_characters_are_one_column_wide() {
        for c in (0..=0x2FFFFu32)
            .filter_map(char::from_u32)
            .filter(|&c| narrow(c))
        {
            let w = Span::raw(c.to_string()).width();
            assert_eq!(w, 1, "{c:?} U+{:04X}", c as u32);
        }
        assert!(!narrow('\u{ad}'), "the soft hyphen has no width");
    }
}

//! Unwrapped text: lines written into the buffer and cut at the area's right edge,
//! the same cells a left-aligned, unwrapped `Paragraph` writes (a test holds it),
//! without its grapheme machinery for the text the page mostly shows (ASCII, box
//! drawing, arrows, braille). Word-wrapped text is `wrap`'s. Kept, not replaced by
//! `Paragraph`, because a frame is mostly such lines: on the same 120×40 frame's text
//! `Paragraph` takes about 5.5 times as long as this (benches/render.rs, "text of a
//! full frame"), some 330 µs more a frame against a frame budget of 200 µs.

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

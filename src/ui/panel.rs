//! A panel's frame: the line along its top (and the side on its right) with its titles,
//! the cells ratatui's `Block` writes for `Borders::TOP` (`| Borders::RIGHT`) with
//! titles, without `Block`'s pass over every cell of the panel to apply a style the page
//! never sets. The panels together cover the whole frame, so that pass cost about as
//! much as a widget (benches/render.rs); the tests below hold this to `Block`'s output.

use ratatui::buffer::Buffer;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::Style;
use ratatui::symbols::line;
use ratatui::text::{Line, Span};
use ratatui::widgets::Widget;

/// Draws the frame of a panel in `area` and returns its inside.
pub struct Panel<'a> {
    /// A line down the right side too (the left column's panels).
    pub right_side: bool,
    pub border: Style,
    /// Titles from the left, one column apart.
    pub titles: &'a [Line<'a>],
    /// A title at the right end of the top line.
    pub right_title: Option<&'a Line<'a>>,
}

impl Panel<'_> {
    pub fn render(&self, area: Rect, buf: &mut Buffer) -> Rect {
        let inside = Rect {
            y: area.y.saturating_add(1).min(area.bottom()),
            height: area.height.saturating_sub(1),
            width: area.width.saturating_sub(u16::from(self.right_side)),
            ..area
        };
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return inside;
        }
        let right = area.right() - 1;
        for x in area.left()..=right {
            cell(buf, x, area.top(), line::HORIZONTAL, self.border);
        }
        if self.right_side {
            for y in area.top()..area.bottom() {
                cell(buf, right, y, line::VERTICAL, self.border);
            }
            cell(buf, right, area.top(), line::TOP_RIGHT, self.border);
        }
        let mut room = Rect {
            width: area.width - u16::from(self.right_side),
            height: 1,
            ..area
        };
        for title in self.titles {
            if room.is_empty() {
                break;
            }
            let w = title.width().min(usize::from(u16::MAX)) as u16;
            let at = Rect {
                width: w.min(room.width),
                ..room
            };
            put_line(buf, at, title, Alignment::Left);
            let advance = w.saturating_add(1);
            room.x = room.x.saturating_add(advance);
            room.width = room.width.saturating_sub(advance);
        }
        if let Some(title) = self.right_title {
            let room = Rect {
                width: area.width - u16::from(self.right_side),
                height: 1,
                ..area
            };
            if !room.is_empty() {
                let w = title.width().min(usize::from(u16::MAX)) as u16;
                let at = Rect {
                    x: room.right().saturating_sub(w).max(room.left()),
                    width: w.min(room.width),
                    ..room
                };
                put_line(buf, at, title, Alignment::Right);
            }
        }
        inside
    }
}

/// The frame of one of the right column's panels, titled `title` (" Events "): a line
/// along its top and no side (the list's line is their left edge). Returns the inside.
pub fn titled(buf: &mut Buffer, area: Rect, title: &str) -> Rect {
    Panel {
        right_side: false,
        border: super::theme::border(),
        titles: &[Line::from(Span::styled(title, super::theme::panel_title()))],
        right_title: None,
    }
    .render(area, buf)
}

fn cell(buf: &mut Buffer, x: u16, y: u16, symbol: &str, style: Style) {
    let i = buf.index_of(x, y);
    buf.content[i].set_symbol(symbol).set_style(style);
}

/// `title` in `at` as `Line` renders it there with `alignment`: the spans one after
/// the other, cut at the edge; a title too wide for a right-aligned place keeps its end.
fn put_line(buf: &mut Buffer, at: Rect, title: &Line, alignment: Alignment) {
    let at = at.intersection(buf.area);
    if at.is_empty() {
        return;
    }
    if alignment == Alignment::Right && title.width() > usize::from(at.width) {
        return title.clone().alignment(alignment).render(at, buf);
    }
    super::unwrapped::lines(buf, at, std::slice::from_ref(title));
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::style::{Color, Modifier};
    use ratatui::widgets::{Block, Borders};

    #[test]
    fn draws_the_cells_ratatuis_block_draws() {
        let border = Style::new().fg(Color::DarkGray);
        let title = Style::new().fg(Color::White).add_modifier(Modifier::BOLD);
        let sets: Vec<(Vec<Line>, Option<Line>)> = vec![
            (vec![Line::from(Span::styled(" Events ", title))], None),
            (
                vec![
                    Line::from(Span::styled(" Devices ", title)),
                    Line::from(Span::styled("by pin ", Style::new().fg(Color::Gray))),
                ],
                Some(Line::styled(
                    " ▲2 more ▼4 more ",
                    Style::new().fg(Color::Yellow),
                )),
            ),
            (
                vec![
                    Line::from(Span::styled(" Devices ", title)),
                    Line::from(Span::styled("A-Z ", Style::new().fg(Color::Gray))),
                    Line::default(),
                ],
                None,
            ),
            (
                vec![Line::from(vec![
                    Span::styled(" Landing Lt ", title),
                    Span::styled("pin 10A-1 · id 17 · device ", Style::new().fg(Color::Gray)),
                ])],
                None,
            ),
        ];
        for (titles, right_title) in &sets {
            for right_side in [false, true] {
                for width in 0..40 {
                    for height in 0..4 {
                        let area = Rect::new(1, 1, width, height);
                        let mut under = Buffer::empty(Rect::new(0, 0, 42, 6));
                        for y in 0..6 {
                            under.set_string(0, y, "x·".repeat(21), Style::new().bg(Color::Blue));
                        }
                        let mut want = under.clone();
                        let mut block = Block::new()
                            .borders(if right_side {
                                Borders::TOP | Borders::RIGHT
                            } else {
                                Borders::TOP
                            })
                            .border_style(border);
                        for t in titles {
                            block = block.title(t.clone());
                        }
                        if let Some(t) = right_title {
                            block = block.title(t.clone().right_aligned());
                        }
                        let want_inside = block.inner(area);
                        block.render(area, &mut want);
                        let mut got = under;
                        let inside = Panel {
                            right_side,
                            border,
                            titles,
                            right_title: right_title.as_ref(),
                        }
                        .render(area, &mut got);
                        assert_eq!(got, want, "{area:?} right side {right_side}");
                        assert_eq!(inside, want_inside, "{area:?}");
                    }
                }
            }
        }
    }
}

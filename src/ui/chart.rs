//! A braille line chart written straight into the buffer: the cells ratatui's `Chart`
//! writes for the bus plot (a y axis labelled at its ends, an optional time axis with
//! labels under it, no legend), without `Chart`'s canvas, which builds a boxed grid and
//! a full layer of cells per line drawn, then walks every layer over the whole graph.
//! The plot was the costliest widget of the frame (benches/render.rs); the tests below
//! hold this chart to `Chart`'s output cell for cell.

use ratatui::buffer::Buffer;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Style};
use ratatui::symbols::braille::BRAILLE;
use ratatui::symbols::line;
use ratatui::text::{Line, Span};
use ratatui::widgets::Widget;

/// One line (or set of dots) on the chart, in chart coordinates.
pub struct Series<'a> {
    pub points: &'a [(f64, f64)],
    pub colour: Color,
    /// Consecutive points joined by a line; otherwise dots only.
    pub joined: bool,
    /// Drawn in every other cell only: a dashed line, told from a solid one without
    /// colour (the limit a trace is read against).
    pub dashed: bool,
}

pub struct Chart<'a> {
    pub x_bounds: [f64; 2],
    pub y_bounds: [f64; 2],
    /// Under the time axis, spread across it; none (or one): no time axis at all.
    pub x_labels: &'a [Span<'a>],
    /// Left of the y axis, from the bottom up; none: no y axis.
    pub y_labels: &'a [Span<'a>],
    pub axis_style: Style,
}

/// Where `Chart` puts its parts in an area (its own layout, for the options used here).
struct Parts {
    label_x: Option<u16>,
    label_y: Option<u16>,
    axis_x: Option<u16>,
    axis_y: Option<u16>,
    graph: Rect,
}

impl Chart<'_> {
    fn parts(&self, area: Rect) -> Option<Parts> {
        if area.is_empty() {
            return None;
        }
        let has_x = !self.x_labels.is_empty();
        let has_y = !self.y_labels.is_empty();
        let mut x = area.left();
        let mut y = area.bottom() - 1;
        let mut label_x = None;
        if has_x && y > area.top() {
            label_x = Some(y);
            y -= 1;
        }
        let label_y = has_y.then_some(x);
        // The y labels' column, also wide enough for the first time label to end under
        // the axis; never more than a third of the chart.
        let mut labels_w = self.y_labels.iter().map(Span::width).max().unwrap_or(0) as u16;
        if let Some(first) = self.x_labels.first() {
            labels_w = labels_w.max((first.width() as u16).saturating_sub(u16::from(has_y)));
        }
        x += labels_w.min(area.width / 3);
        let mut axis_x = None;
        if has_x && y > area.top() {
            axis_x = Some(y);
            y -= 1;
        }
        let mut axis_y = None;
        if has_y && x + 1 < area.right() {
            axis_y = Some(x);
            x += 1;
        }
        let graph = Rect::new(
            x,
            area.top(),
            area.right().saturating_sub(x),
            y.saturating_sub(area.top()).saturating_add(1),
        );
        Some(Parts {
            label_x,
            label_y,
            axis_x,
            axis_y,
            graph,
        })
    }

    pub fn render(&self, area: Rect, buf: &mut Buffer, series: &[Series]) {
        let Some(p) = self.parts(area) else {
            return;
        };
        let g = p.graph;
        let xl = self.x_labels;
        if let (Some(y), true) = (p.label_x, xl.len() >= 2) {
            let n = xl.len() as u16;
            let between = g.width / n;
            let first = Rect::new(area.left(), y, g.left() - area.left(), 1);
            label(buf, first, &xl[0], Alignment::Right);
            for (i, l) in xl[1..xl.len() - 1].iter().enumerate() {
                let x = g.left() + (i as u16 + 1) * between + 1;
                let at = Rect::new(x, y, between.saturating_sub(1), 1);
                label(buf, at, l, Alignment::Center);
            }
            let last = Rect::new(g.right() - between, y, between, 1);
            label(buf, last, &xl[xl.len() - 1], Alignment::Right);
        }
        let yl = self.y_labels;
        if let (Some(x), true) = (p.label_y, yl.len() >= 2) {
            let n = yl.len() as u16;
            for (i, l) in yl.iter().enumerate() {
                let dy = i as u16 * (g.height - 1) / (n - 1);
                if dy < g.bottom() {
                    let width = (g.left() - area.left()).saturating_sub(1);
                    let at = Rect::new(x, g.bottom().saturating_sub(1) - dy, width, 1);
                    label(buf, at, l, Alignment::Left);
                }
            }
        }
        if let Some(y) = p.axis_x {
            for x in g.left()..g.right() {
                buf[(x, y)]
                    .set_symbol(line::HORIZONTAL)
                    .set_style(self.axis_style);
            }
        }
        if let Some(x) = p.axis_y {
            for y in g.top()..g.bottom() {
                buf[(x, y)]
                    .set_symbol(line::VERTICAL)
                    .set_style(self.axis_style);
            }
        }
        if let (Some(x), Some(y)) = (p.axis_y, p.axis_x) {
            buf[(x, y)]
                .set_symbol(line::BOTTOM_LEFT)
                .set_style(self.axis_style);
        }
        if g.is_empty() {
            return;
        }
        // The canvas's background: the terminal's own, as `Chart` leaves it.
        for y in g.top()..g.bottom() {
            let i = buf.index_of(g.x, y);
            for cell in &mut buf.content[i..i + usize::from(g.width)] {
                cell.bg = Color::Reset;
            }
        }
        let dots = Dots::new(g, self.x_bounds, self.y_bounds);
        dots.draw(buf, series);
    }
}

/// A label in `area` as a `Line` with `alignment` renders it: cut to the area, and
/// when too long, the part the alignment keeps.
fn label(buf: &mut Buffer, area: Rect, span: &Span, alignment: Alignment) {
    let area = area.intersection(buf.area);
    let w = span.width();
    if area.is_empty() || w == 0 {
        return;
    }
    let room = usize::from(area.width);
    if w > room {
        return Line::from(span.clone())
            .alignment(alignment)
            .render(area, buf);
    }
    let indent = match alignment {
        Alignment::Left => 0,
        Alignment::Center => (room - w) / 2,
        Alignment::Right => room - w,
    } as u16;
    super::fast::put(
        buf,
        area.x + indent,
        area.y,
        &span.content,
        area.width - indent,
        span.style,
    );
}

/// The graph as braille cells (2×4 dots each) over chart coordinates.
struct Dots {
    graph: Rect,
    x: [f64; 2],
    y: [f64; 2],
    /// Dots across and down.
    res: (f64, f64),
}

impl Dots {
    fn new(graph: Rect, x: [f64; 2], y: [f64; 2]) -> Dots {
        Dots {
            graph,
            x,
            y,
            res: (f64::from(graph.width) * 2.0, f64::from(graph.height) * 4.0),
        }
    }

    /// The dot nearest a point, `None` outside the bounds (as ratatui's canvas rounds).
    fn dot(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let ([left, right], [bottom, top]) = (self.x, self.y);
        if x < left || x > right || y < bottom || y > top {
            return None;
        }
        let (width, height) = (right - left, top - bottom);
        if width <= 0.0 || height <= 0.0 {
            return None;
        }
        let dx = ((x - left) * (self.res.0 - 1.0) / width).round() as usize;
        let dy = ((top - y) * (self.res.1 - 1.0) / height).round() as usize;
        Some((dx, dy))
    }

    /// Each series is a layer over the ones before: where it has dots, its cell (dots
    /// and colour) replaces theirs, as ratatui's canvas layers do.
    fn draw(&self, buf: &mut Buffer, series: &[Series]) {
        let w = usize::from(self.graph.width);
        let cells = w * usize::from(self.graph.height);
        let mut shown: Vec<(u8, Color)> = vec![(0, Color::Reset); cells];
        let mut layer = vec![0u8; cells];
        for s in series {
            let (mut lo, mut hi) = (usize::MAX, 0);
            let dashed = s.dashed;
            let mut paint = |dx: usize, dy: usize| {
                if dashed && dx / 2 % 2 == 1 {
                    return;
                }
                let i = dy / 4 * w + dx / 2;
                if let Some(cell) = layer.get_mut(i) {
                    *cell |= 1 << (dx % 2 + 2 * (dy % 4));
                    lo = lo.min(i);
                    hi = hi.max(i);
                }
            };
            let dots: Vec<Option<(usize, usize)>> =
                s.points.iter().map(|&(x, y)| self.dot(x, y)).collect();
            for &(dx, dy) in dots.iter().flatten() {
                paint(dx, dy);
            }
            if s.joined {
                for (pair, ends) in s.points.windows(2).zip(dots.windows(2)) {
                    // Both ends inside: clipping keeps the segment as it is, and its
                    // ends are the points' own dots.
                    if let [Some(a), Some(b)] = *ends {
                        line_dots(a, b, &mut paint);
                        continue;
                    }
                    let Some(((x1, y1), (x2, y2))) = clip(self.x, self.y, pair[0], pair[1]) else {
                        continue;
                    };
                    if let (Some(a), Some(b)) = (self.dot(x1, y1), self.dot(x2, y2)) {
                        line_dots(a, b, &mut paint);
                    }
                }
            }
            if lo <= hi {
                for (cell, dots) in shown[lo..=hi].iter_mut().zip(&mut layer[lo..=hi]) {
                    if *dots != 0 {
                        *cell = (*dots, s.colour);
                        *dots = 0;
                    }
                }
            }
        }
        let area = self.graph;
        for (i, &(dots, colour)) in shown.iter().enumerate() {
            if dots != 0 {
                let x = area.x + (i % w) as u16;
                let y = area.y + (i / w) as u16;
                buf[(x, y)]
                    .set_char(BRAILLE[usize::from(dots)])
                    .set_fg(colour);
            }
        }
    }
}

/// The part of the segment a–b inside the bounds (Cohen–Sutherland, as ratatui clips).
fn clip(
    [x_min, x_max]: [f64; 2],
    [y_min, y_max]: [f64; 2],
    mut a: (f64, f64),
    mut b: (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    const LEFT: u8 = 1;
    const RIGHT: u8 = 2;
    const BOTTOM: u8 = 4;
    const TOP: u8 = 8;
    let region = |(x, y): (f64, f64)| {
        let mut r = 0;
        if x < x_min {
            r |= LEFT;
        } else if x > x_max {
            r |= RIGHT;
        }
        if y < y_min {
            r |= BOTTOM;
        } else if y > y_max {
            r |= TOP;
        }
        r
    };
    let cut = |(x1, y1): (f64, f64), (x2, y2): (f64, f64), r: u8| {
        let (dx, dy) = (x2 - x1, y2 - y1);
        if r & LEFT != 0 {
            (x_min, y1 + (x_min - x1) * dy / dx)
        } else if r & RIGHT != 0 {
            (x_max, y1 + (x_max - x1) * dy / dx)
        } else if r & BOTTOM != 0 {
            (x1 + (y_min - y1) * dx / dy, y_min)
        } else {
            (x1 + (y_max - y1) * dx / dy, y_max)
        }
    };
    let (mut ra, mut rb) = (region(a), region(b));
    loop {
        if ra & rb != 0 {
            return None;
        } else if ra != 0 {
            a = cut(a, b, ra);
            ra = region(a);
        } else if rb != 0 {
            b = cut(b, a, rb);
            rb = region(b);
        } else {
            return Some((a, b));
        }
    }
}

/// The dots of a line from `a` to `b` (Bresenham, stepping as ratatui's canvas does, so
/// the same pixels light).
fn line_dots((x1, y1): (usize, usize), (x2, y2): (usize, usize), f: &mut impl FnMut(usize, usize)) {
    let (dx, dy) = (x2.abs_diff(x1), y2.abs_diff(y1));
    if dx == 0 {
        (y1.min(y2)..=y1.max(y2)).for_each(|y| f(x1, y));
    } else if dy == 0 {
        (x1.min(x2)..=x1.max(x2)).for_each(|x| f(x, y1));
    } else if dy < dx {
        along_major((x1, y1), (x2, y2), f);
    } else {
        along_major((y1, x1), (y2, x2), &mut |y, x| f(x, y));
    }
}

/// Bresenham along the major axis, the first coordinate of each point (x for a line
/// flatter than 45°, y for a steeper one), one dot a step from its lower end.
fn along_major(
    (p1, q1): (usize, usize),
    (p2, q2): (usize, usize),
    f: &mut impl FnMut(usize, usize),
) {
    let ((p1, q1), (p2, q2)) = if p1 > p2 {
        ((p2, q2), (p1, q1))
    } else {
        ((p1, q1), (p2, q2))
    };
    let (dp, dq) = ((p2 - p1) as isize, (q2 as isize - q1 as isize).abs());
    let mut d = 2 * dq - dp;
    let mut q = q1;
    for p in p1..=p2 {
        f(p, q);
        if d > 0 {
            q = if q1 > q2 {
                q.saturating_sub(1)
            } else {
                q.saturating_add(1)
            };
            d -= 2 * dp;
        }
        d += 2 * dq;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::style::Modifier;
    use ratatui::symbols::Marker;
    use ratatui::widgets::{Axis, Dataset, GraphType};

    /// A small deterministic generator: the cases are the same on every run.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            self.0 >> 33
        }
        fn below(&mut self, n: u64) -> u64 {
            self.next() % n.max(1)
        }
        fn unit(&mut self) -> f64 {
            self.next() as f64 / f64::from(u32::MAX >> 1)
        }
    }

    /// A series as the test makes it: points, colour, joined.
    type Made = (Vec<(f64, f64)>, Color, bool);

    /// Both charts into buffers that already hold text, so what each leaves alone is
    /// compared too.
    fn both(area: Rect, chart: &Chart, series: &[Made]) -> (Buffer, Buffer) {
        let mut under = Buffer::empty(Rect::new(0, 0, area.right() + 2, area.bottom() + 1));
        for y in 0..under.area.height {
            let row = "·x".repeat(usize::from(under.area.width));
            under.set_string(0, y, row, Style::new().fg(Color::Blue).bg(Color::Black));
        }
        let mut want = under.clone();
        let datasets = series
            .iter()
            .map(|(points, colour, joined)| {
                Dataset::default()
                    .marker(Marker::Braille)
                    .graph_type(if *joined {
                        GraphType::Line
                    } else {
                        GraphType::Scatter
                    })
                    .style(Style::new().fg(*colour).add_modifier(Modifier::BOLD))
                    .data(points)
            })
            .collect();
        let mut x_axis = Axis::default()
            .bounds(chart.x_bounds)
            .style(chart.axis_style);
        if !chart.x_labels.is_empty() {
            x_axis = x_axis.labels(chart.x_labels.to_vec());
        }
        let mut y_axis = Axis::default()
            .bounds(chart.y_bounds)
            .style(chart.axis_style);
        if !chart.y_labels.is_empty() {
            y_axis = y_axis.labels(chart.y_labels.to_vec());
        }
        ratatui::widgets::Chart::new(datasets)
            .x_axis(x_axis)
            .y_axis(y_axis)
            .legend_position(None)
            .render(area, &mut want);
        let mut got = under;
        let series: Vec<Series> = series
            .iter()
            .map(|(points, colour, joined)| Series {
                points,
                colour: *colour,
                joined: *joined,
                dashed: false,
            })
            .collect();
        chart.render(area, &mut got, &series);
        (got, want)
    }

    #[test]
    fn draws_the_cells_ratatuis_chart_draws() {
        let mut rng = Lcg(11);
        let label = |s: String| Span::styled(s, Style::new().fg(Color::Gray));
        for case in 0..600 {
            let area = Rect::new(
                rng.below(3) as u16,
                rng.below(3) as u16,
                1 + rng.below(60) as u16,
                1 + rng.below(14) as u16,
            );
            let x_bounds = [-300.0, 0.0];
            let lo = 10.0 + rng.unit() * 5.0;
            let y_bounds = [lo, lo + 0.5 + rng.unit() * 8.0];
            let x_labels: Vec<Span> = match rng.below(4) {
                0 => vec![],
                1 => vec![label("-5 min".into()), label("now".into())],
                2 => ["-5 min", "-2.5 min", "now"]
                    .map(|s| label(s.into()))
                    .to_vec(),
                _ => ["a long first label", "b", "c", "the last"]
                    .map(|s| label(s.into()))
                    .to_vec(),
            };
            let y_labels: Vec<Span> = match rng.below(3) {
                0 => vec![],
                1 => y_bounds.map(|v| label(format!("{v:.1}"))).to_vec(),
                _ => y_bounds.map(|v| label(format!("{v:.0}"))).to_vec(),
            };
            let mut series = Vec::new();
            if rng.below(2) == 0 {
                let l = y_bounds[0] + rng.unit() * (y_bounds[1] - y_bounds[0]);
                series.push((vec![(-300.0, l), (0.0, l)], Color::Red, true));
            }
            for _ in 0..rng.below(5) {
                let n = rng.below(40) as usize;
                let start = -300.0 + rng.unit() * 300.0;
                let points: Vec<(f64, f64)> = (0..n)
                    .map(|k| {
                        // Mostly inside, now and then outside, to exercise clipping.
                        let y = y_bounds[0] - 1.0 + rng.unit() * (y_bounds[1] - y_bounds[0] + 2.0);
                        (start + k as f64 * 3.7, y)
                    })
                    .collect();
                series.push((points, Color::Cyan, n > 1 && rng.below(4) != 0));
            }
            let chart = Chart {
                x_bounds,
                y_bounds,
                x_labels: &x_labels,
                y_labels: &y_labels,
                axis_style: Style::new().fg(Color::DarkGray),
            };
            let (got, want) = both(area, &chart, &series);
            assert_eq!(got, want, "case {case}: {area:?}");
        }
    }

    #[test]
    fn a_dashed_line_leaves_every_other_cell_blank() {
        let area = Rect::new(0, 0, 12, 3);
        let mut buf = Buffer::empty(area);
        let labels = [Span::raw("1"), Span::raw("2")];
        let chart = Chart {
            x_bounds: [0.0, 1.0],
            y_bounds: [0.0, 1.0],
            x_labels: &[],
            y_labels: &labels,
            axis_style: Style::new(),
        };
        let line = [(0.0, 1.0), (1.0, 1.0)];
        let series = |dashed| Series {
            points: &line,
            colour: Color::Red,
            joined: true,
            dashed,
        };
        chart.render(area, &mut buf, &[series(true)]);
        let top: String = (2..12).map(|x| buf[(x, 0)].symbol().to_string()).collect();
        assert_eq!(top, "⠉ ⠉ ⠉ ⠉ ⠉ ");
        chart.render(area, &mut buf, &[series(false)]);
        let top: String = (2..12).map(|x| buf[(x, 0)].symbol().to_string()).collect();
        assert_eq!(top, "⠉⠉⠉⠉⠉⠉⠉⠉⠉⠉");
    }

    #[test]
    fn clipping_keeps_the_part_inside() {
        let b = [0.0, 10.0];
        assert_eq!(
            clip(b, b, (-5.0, 5.0), (5.0, 5.0)),
            Some(((0.0, 5.0), (5.0, 5.0)))
        );
        assert_eq!(clip(b, b, (-5.0, 11.0), (-1.0, 20.0)), None);
        assert_eq!(
            clip(b, b, (2.0, 3.0), (4.0, 5.0)),
            Some(((2.0, 3.0), (4.0, 5.0)))
        );
    }
}

//! The walk-around remote on the page: the overlay with the pairing URL as a QR code
//! (its key in the fragment) and as text, the address and words for a phone without
//! a camera, what is protected, and the title's count of phones.
//!
//! The QR code is drawn with half blocks (two modules a cell), its dark modules as
//! glyphs in xterm black ([`QR_DARK`]) on xterm white ([`QR_LIGHT`]) cells, quiet
//! zone included, whatever the theme: a code must be dark on light to scan. The dark
//! and light palettes keep those two colours, and so does NO_COLOR's (the code is a
//! picture, not coloured words: reverse video would draw it inverted on a light
//! terminal, and the terminal's own colours say nothing of which is light).

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph};

use super::state::RemoteView;
use super::theme;

/// The QR code's dark and light, as xterm's fixed 256-colour indices.
pub const QR_DARK: Color = Color::Indexed(16);
pub const QR_LIGHT: Color = Color::Indexed(231);

/// The QR code of `url` as rows of half blocks (a dark module a glyph) with a quiet
/// zone of `zone` modules; empty if the URL is too long for a code (it is not: a URL
/// is under 60 bytes).
pub fn qr_rows(url: &str, zone: usize) -> Vec<String> {
    let Ok(code) = qrcode::QrCode::with_error_correction_level(url.as_bytes(), qrcode::EcLevel::L)
    else {
        return Vec::new();
    };
    let w = code.width();
    let colors = code.to_colors();
    let dark = |x: isize, y: isize| {
        x >= 0
            && y >= 0
            && (x as usize) < w
            && (y as usize) < w
            && colors[y as usize * w + x as usize] == qrcode::Color::Dark
    };
    let z = zone as isize;
    let side = w as isize + 2 * z;
    let mut lines = Vec::new();
    let mut y = -z;
    while y < side - z {
        let row: String = (-z..side - z)
            .map(|x| match (dark(x, y), dark(x, y + 1)) {
                (true, true) => '█',
                (true, false) => '▀',
                (false, true) => '▄',
                (false, false) => ' ',
            })
            .collect();
        lines.push(row);
        y += 2;
    }
    lines
}

/// Rows of [`qr_rows`] as lines in xterm black on xterm white.
fn qr_lines(rows: &[String]) -> Vec<Line<'static>> {
    let style = Style::new().fg(QR_DARK).bg(QR_LIGHT);
    rows.iter()
        .map(|r| Line::from(Span::styled(r.clone(), style)))
        .collect()
}

/// "1 phone paired", "no phone paired"; with how many by typed words.
pub fn paired_words(n: usize, typed: usize) -> String {
    let n = match n {
        0 => "no phone paired".into(),
        1 => "1 phone paired".into(),
        n => format!("{n} phones paired"),
    };
    match typed {
        0 => n,
        t => format!("{n}, {t} by typed words"),
    }
}

/// What a phone paired by typed words risks, as the overlay and the phone say it.
pub const TYPED_RISK: &str =
    "typed words are weaker than the QR code: anyone on this WiFi who saw them could act";

/// The title's note while the remote is on: how many phones are paired, shorter on a
/// narrow terminal so that the title keeps its own words.
pub fn title_note(remote: &RemoteView, width: u16) -> String {
    if width >= 100 {
        format!(" REMOTE: {} ", paired_words(remote.paired, remote.typed))
    } else if remote.typed > 0 {
        format!(
            " REMOTE: {} paired ({} typed) ",
            remote.paired, remote.typed
        )
    } else {
        format!(" REMOTE: {} paired ", remote.paired)
    }
}

/// The title's note, drawn in `area` at the right end of the title line.
pub fn render_title(frame: &mut Frame, area: Rect, note: &str) {
    frame.render_widget(
        Paragraph::new(Line::from(Span::styled(note.to_string(), theme::caution()))),
        area,
    );
}

/// The overlay's words beside or under the code, each cut to `width`.
fn words_column(remote: &RemoteView, width: usize) -> Vec<Line<'static>> {
    let mut items: Vec<(String, Style)> = vec![
        ("No camera? Open".into(), theme::label()),
        (remote.address.clone(), theme::info()),
        ("and type the words".into(), theme::label()),
        (remote.words.clone(), theme::panel_title()),
        (String::new(), theme::label()),
        (crate::remote::PROTECTED.into(), theme::label()),
        (String::new(), theme::label()),
        (paired_words(remote.paired, remote.typed), theme::label()),
    ];
    if remote.typed > 0 {
        items.push((TYPED_RISK.into(), theme::caution()));
    }
    if remote.loopback_only {
        items.push((
            "no LAN address found: only this laptop can reach it".into(),
            theme::caution(),
        ));
    }
    let mut lines: Vec<Line> = items
        .into_iter()
        .flat_map(|(text, style)| {
            super::wrap::text(&text, width)
                .into_iter()
                .map(move |l| Line::styled(l, style))
        })
        .collect();
    lines.push(Line::from(vec![
        Span::styled(" p ", theme::key()),
        Span::raw(" stop  "),
        Span::styled(" P ", theme::key()),
        Span::raw(" unpair all  "),
        Span::styled(" Esc ", theme::key()),
        Span::raw(" hide"),
    ]));
    lines
}

/// The overlay: the QR code with its quiet zone, the words beside it (a wide, short
/// terminal) or under it, and the URL with its key across the foot.
///
/// Of the ways to lay it out, the first that fits: the full quiet zone (4 modules)
/// above the words, then beside them, then the small zone (2 modules) likewise.
pub fn render(frame: &mut Frame, remote: &RemoteView) {
    let area = frame.area();
    let url = Line::from(vec![
        Span::styled("or open ", theme::label()),
        Span::styled(remote.url.clone(), theme::info()),
    ]);
    let url_w = url.width() as u16;
    // Inside the border: 1 cell of padding each side.
    let inner_w = area.width.saturating_sub(4);
    let inner_h = area.height.saturating_sub(2);
    let mut chosen = None;
    for qr in &remote.qr {
        let (qw, qh) = (
            qr.first().map_or(0, |r| r.chars().count()) as u16,
            qr.len() as u16,
        );
        let stacked_w = qw.max(url_w).max(40).min(inner_w);
        let below = words_column(remote, usize::from(stacked_w));
        // The URL's line under it all.
        if qh + (below.len() as u16) < inner_h {
            chosen = Some((qr, false, stacked_w, below));
            break;
        }
        let side_w = inner_w.saturating_sub(qw + 2).min(44);
        let beside = words_column(remote, usize::from(side_w));
        if side_w >= 24 && qh.max(beside.len() as u16) < inner_h {
            chosen = Some((qr, true, (qw + 2 + side_w).max(url_w), beside));
            break;
        }
    }
    let (qr, side, body_w, words) = chosen.unwrap_or_else(|| {
        let qr = &remote.qr[1];
        let w = inner_w;
        (qr, false, w, words_column(remote, usize::from(w)))
    });
    let qr = qr_lines(qr);
    let qw = qr.first().map_or(0, |l| l.width() as u16);
    let body_h = if side {
        (qr.len() as u16).max(words.len() as u16) + 1
    } else {
        qr.len() as u16 + words.len() as u16 + 1
    };
    let width = (body_w + 4).min(area.width);
    let height = (body_h + 2).min(area.height);
    let [row] = Layout::vertical([Constraint::Length(height)])
        .flex(Flex::Center)
        .areas(area);
    let [popup] = Layout::horizontal([Constraint::Length(width)])
        .flex(Flex::Center)
        .areas(row);
    frame.render_widget(Clear, popup);
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::border())
        .title(Span::styled(" walk-around remote ", theme::panel_title()));
    let inner = block.inner(popup);
    frame.render_widget(block, popup);
    let inner = Rect {
        x: inner.x + 1,
        width: inner.width.saturating_sub(2),
        ..inner
    };
    let [main, foot] = Layout::vertical([Constraint::Fill(1), Constraint::Length(1)]).areas(inner);
    frame.render_widget(Paragraph::new(url.centered()), foot);
    if side {
        let [code, _, text] = Layout::horizontal([
            Constraint::Length(qw),
            Constraint::Length(2),
            Constraint::Fill(1),
        ])
        .areas(main);
        frame.render_widget(Paragraph::new(qr), code);
        frame.render_widget(Paragraph::new(words), text);
    } else {
        let [code, text] =
            Layout::vertical([Constraint::Length(qr.len() as u16), Constraint::Fill(1)])
                .areas(main);
        frame.render_widget(
            Paragraph::new(qr.into_iter().map(Line::centered).collect::<Vec<_>>()),
            code,
        );
        frame.render_widget(
            Paragraph::new(words.into_iter().map(Line::centered).collect::<Vec<_>>()),
            text,
        );
    }
}

//! The walk-around remote on the page: the overlay with the pairing URL as text, the
//! same URL as a QR code, and the code in words; and the title's count of phones.
//!
//! The QR code is drawn with half blocks (two modules a cell), its dark modules as
//! glyphs in xterm black on xterm white cells, quiet zone included, whatever the
//! theme: a code must be dark on light to scan, and the palettes keep a badge's own
//! colours (`palette::badge_text`), so dark and light pages draw it the same. Without
//! colour (NO_COLOR) the cells go to reverse video, dark on light on a dark terminal;
//! on a light one the code comes out inverted, which phone cameras read too.

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph};

use super::state::RemoteView;
use super::theme;

/// The QR code's dark and light, as xterm's fixed 256-colour indices.
const QR_DARK: Color = Color::Indexed(16);
const QR_LIGHT: Color = Color::Indexed(231);

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

/// "482 913": the code in two groups, as the page says it.
pub fn spaced_code(code: &str) -> String {
    if code.len() == 6 {
        format!("{} {}", &code[..3], &code[3..])
    } else {
        code.to_string()
    }
}

/// "1 phone paired", "no phone paired".
pub fn paired_words(n: usize) -> String {
    match n {
        0 => "no phone paired".into(),
        1 => "1 phone paired".into(),
        n => format!("{n} phones paired"),
    }
}

/// The title's note while the remote is on: how many phones are paired, shorter on a
/// narrow terminal so that the title keeps its own words.
pub fn title_note(remote: &RemoteView, width: u16) -> String {
    if width >= 100 {
        format!(" REMOTE: {} ", paired_words(remote.paired))
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

/// The overlay: URL, QR code, pairing code, how many phones, the keys.
pub fn render(frame: &mut Frame, remote: &RemoteView) {
    let area = frame.area();
    // A full quiet zone where the terminal has room; two modules on a small one (a
    // phone still finds the code; the light cells around it are the zone's rest).
    let text_rows = 5 + u16::from(remote.loopback_only);
    let [big, small] = &remote.qr;
    let qr = if big.len() as u16 + text_rows + 2 <= area.height {
        qr_lines(big)
    } else {
        qr_lines(small)
    };
    let qr_w = qr.first().map_or(0, |l| l.width() as u16);
    let mut lines: Vec<Line> = Vec::new();
    lines.push(Line::from(vec![
        Span::styled("open ", theme::label()),
        Span::styled(remote.url.clone(), theme::info()),
    ]));
    if remote.loopback_only {
        lines.push(Line::styled(
            "no LAN address found: only this laptop can reach it",
            theme::caution(),
        ));
    }
    let mut body = Vec::new();
    body.extend(qr.iter().cloned().map(|l| l.centered()));
    body.extend(lines.into_iter().map(|l| l.centered()));
    body.push(
        Line::from(vec![
            Span::styled("pairing code ", theme::label()),
            Span::styled(spaced_code(&remote.code), theme::panel_title()),
        ])
        .centered(),
    );
    body.push(Line::styled(paired_words(remote.paired), theme::label()).centered());
    body.push(
        Line::from(vec![
            Span::styled(" p ", theme::key()),
            Span::raw(" stop  "),
            Span::styled(" P ", theme::key()),
            Span::raw(" unpair all  "),
            Span::styled(" Esc ", theme::key()),
            Span::raw(" hide"),
        ])
        .centered(),
    );
    let text_w = body.iter().map(Line::width).max().unwrap_or(0) as u16;
    let width = (qr_w.max(text_w) + 4).min(area.width);
    let height = (body.len() as u16 + 2).min(area.height);
    let [row] = Layout::vertical([Constraint::Length(height)])
        .flex(Flex::Center)
        .areas(area);
    let [popup] = Layout::horizontal([Constraint::Length(width)])
        .flex(Flex::Center)
        .areas(row);
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(body).block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .border_style(theme::border())
                .title(Span::styled(" walk-around remote ", theme::panel_title())),
        ),
        popup,
    );
}

//! The selected device: its spec, its fault with the Appendix E description, action and
//! how it clears, and what each key will do to it right now.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use super::panel::Panel;
use super::{theme, values};
use crate::check::trend::{self, LastCheck};
use crate::loads::wire;
use crate::loads::wiring::{self, Row, Verdict};
use crate::model::{Circuit, CircuitKind, CircuitState, Model, TrimKind};
use crate::protocol::device;
use crate::protocol::message::FlapMode;

/// One key and what it does; `enabled: false` is drawn dimmed and the control module
/// refuses it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyAction {
    pub key: &'static str,
    pub action: String,
    pub enabled: bool,
}

fn act(key: &'static str, action: impl Into<String>, enabled: bool) -> KeyAction {
    KeyAction {
        key,
        action: action.into(),
        enabled,
    }
}

/// What the keys do to `c` (Appendix A: reset dimmed unless faulted; the starter can
/// only be reset; trim and flap rows show up/down or left/right).
pub fn key_actions(c: &Circuit) -> Vec<KeyAction> {
    let faulted = matches!(c.state, CircuitState::Fault(_) | CircuitState::ResetSent(_));
    let live = c.state != CircuitState::Unknown;
    let reset = match c.state {
        CircuitState::ResetSent(_) => act("r", "reset sent: waiting for the unit", false),
        _ => act("r", "reset fault", faulted && !c.faulted_again),
    };
    // AC 43.13-1B: reset once, then find the cause; a second reset is asked for.
    let again = c
        .faulted_again
        .then(|| act("Y", "reset again: it faulted again after a reset", true));
    let mut keys = match c.kind {
        CircuitKind::Starter => vec![
            act("o/f", "starter is switched by the VP-X only", false),
            reset,
        ],
        CircuitKind::Flaps => vec![
            act("hold u / Shift+↑", "flaps up", live && !faulted),
            act("hold d / Shift+↓", "flaps down", live && !faulted),
            reset,
        ],
        CircuitKind::Trim(TrimKind::Pitch) => vec![
            act("hold u / Shift+↑", "pitch trim up", live && !faulted),
            act("hold d / Shift+↓", "pitch trim down", live && !faulted),
            reset,
        ],
        CircuitKind::Trim(TrimKind::Roll) => vec![
            act("hold , / Shift+←", "roll trim left", live && !faulted),
            act("hold . / Shift+→", "roll trim right", live && !faulted),
            reset,
        ],
        CircuitKind::Device | CircuitKind::Alternator { .. } => vec![
            act(
                "o",
                "on (until switch cycled)",
                live && c.state != CircuitState::On,
            ),
            act(
                "f",
                "off (until switch cycled)",
                live && c.state != CircuitState::Off,
            ),
            reset,
        ],
    };
    keys.extend(again);
    keys
}

/// Non-breaking space: a wrapped line never splits a key from what it does.
pub const NBSP: char = '\u{a0}';

pub fn key_spans(actions: &[KeyAction]) -> Vec<Span<'static>> {
    let glue = |s: &str| s.replace(' ', &NBSP.to_string());
    let mut spans = Vec::new();
    for a in actions {
        let (ks, ts) = if a.enabled {
            (theme::key(), Style::new())
        } else {
            (theme::key_dimmed(), theme::key_dimmed())
        };
        spans.push(Span::styled(glue(&format!(" {} ", a.key)), ks));
        spans.push(Span::styled(glue(&format!(" {}", a.action)), ts));
        spans.push(Span::raw("  "));
    }
    spans
}

fn field(label: &str, value: String) -> Vec<Span<'static>> {
    let glue = |s: &str| s.replace(' ', &NBSP.to_string());
    vec![
        Span::styled(glue(&format!("{label} ")), theme::label()),
        Span::raw(glue(&value)),
        Span::raw("  "),
    ]
}

fn spec_line(model: &Model, c: &Circuit) -> Line<'static> {
    let info = device::device(c.id);
    let mut spans = Vec::new();
    match c.kind {
        CircuitKind::Flaps => match model.flap_spec.map(|s| s.value) {
            Some(s) => {
                spans.extend(field("breaker", format!("{} A", s.circuit_breaker)));
                spans.extend(field(
                    "mode",
                    match s.mode {
                        FlapMode::Momentary => "momentary".into(),
                        FlapMode::PositionBased => "position".into(),
                    },
                ));
                spans.extend(field("up/down", format!("{}/{}", s.up, s.down)));
                spans.extend(field("mid", format!("{}/{}", s.midpoint_1, s.midpoint_2)));
                // Speeds are knots, as the setup screens and backups say them (the
                // EFIS's own unit, icd-reading R20).
                spans.extend(field("max speed", format!("{} kt", s.max_speed)));
            }
            None => spans.extend(field("spec", "not received".into())),
        },
        CircuitKind::Trim(kind) => {
            let spec = match kind {
                TrimKind::Pitch => model.pitch_trim_spec,
                TrimKind::Roll => model.roll_trim_spec,
            };
            spans.extend(field("breaker", "2 A fixed".into()));
            match spec.map(|s| s.value) {
                Some(s) => {
                    spans.extend(field("up/down", format!("{}/{}", s.up, s.down)));
                    spans.extend(field("neutral", s.neutral.to_string()));
                    if kind == TrimKind::Pitch {
                        spans.extend(field(
                            "power",
                            format!("{} % above {} kt", s.power, s.speed),
                        ));
                    }
                }
                None => spans.extend(field("spec", "not received".into())),
            }
        }
        _ => {
            spans.extend(field(
                "breaker",
                c.breaker
                    .map_or_else(|| "not received".into(), |b| format!("{b} A")),
            ));
            if let Some(i) = info {
                spans.extend(field("range", format!("{}–{} A", i.amps_min, i.amps_max)));
            }
            if c.kind == CircuitKind::Starter {
                spans.extend(field("switch", "VP-X (off above 500 RPM)".into()));
            } else {
                spans.extend(field(
                    "switch",
                    c.switch
                        .map_or_else(|| "not received".into(), |s| s.label()),
                ));
            }
            let cf = model.device_specs[c.id as usize].map(|s| s.value.current_fault);
            if let Some(cf) = cf {
                spans.extend(field("current fault", if cf { "on" } else { "off" }.into()));
            }
        }
    }
    Line::from(spans)
}

/// The circuit's wire and its verdict (`loads::wiring`), in words with a symbol.
fn wire_line(r: &Row) -> Line<'static> {
    let Some(w) = r.wire else {
        return Line::from(vec![
            Span::styled("wire ", theme::label()),
            Span::styled("not entered (the load file's wire lines)", theme::unknown()),
        ]);
    };
    if r.verdict == Verdict::Unprotected {
        // Short, so that a short panel still has room for the keys under it.
        let words = r.unprotected_words().unwrap_or_default();
        return Line::from(vec![
            Span::styled(format!("⚠{NBSP}UNPROTECTED "), theme::alert()),
            Span::styled(words, theme::alert()),
        ]);
    }
    let mut spans = field("wire", w.to_string());
    if let Some(run) = r.run_feet {
        let ret = if r.return_assumed {
            " (ground at load)"
        } else {
            ""
        };
        spans.extend(field("run", format!("{}{ret}", wire::feet_text(run))));
    }
    if let Some(m) = r.max_breaker_amps {
        spans.extend(field("allows", format!("{} A", wiring::amps_text(m))));
    }
    if let (Some(d), Some(l)) = (r.drop_volts, r.drop_limit_volts) {
        spans.extend(field("drop", format!("{d:.2} V of {l} V")));
    }
    match r.verdict {
        Verdict::Drop => {
            let under = r
                .longest_run_feet
                .map(|f| format!(": a run of at most {} would pass", wire::feet_text(f)))
                .unwrap_or_default();
            spans.push(Span::styled(
                format!("⚠{NBSP}DROP over the limit{under}"),
                theme::caution(),
            ));
        }
        _ => spans.push(Span::raw(format!("✓{NBSP}{}", r.verdict.word()))),
    }
    Line::from(spans)
}

/// The selected circuit at the aircraft's last check (`check::trend`): "last check
/// 6.1 A, 2026-11-03 18:30 UTC", or why there is no figure. `None` without a last
/// check.
pub fn last_check_line(last: &LastCheck, c: &Circuit) -> Option<Line<'static>> {
    let words = trend::trend(Some(last), c.pin, &c.name, None).words()?;
    let when = last.when.map_or_else(String::new, |w| {
        let t = crate::utc::utc_text(w);
        format!(", {} {} UTC", &t[..10], &t[11..16])
    });
    Some(Line::from(vec![
        Span::styled("history ", theme::label()),
        Span::raw(format!("{words}{when}")),
    ]))
}

pub fn render(
    frame: &mut Frame,
    area: Rect,
    model: &Model,
    selected: Option<&Circuit>,
    wire: Option<&Row>,
    last: Option<&LastCheck>,
) {
    let panel = |frame: &mut Frame, title: Line| {
        Panel {
            right_side: true,
            border: theme::border(),
            titles: &[title],
            right_title: None,
        }
        .render(area, frame.buffer_mut())
    };
    let Some(c) = selected else {
        let inner = panel(frame, Line::styled(" Detail ", theme::panel_title()));
        let hint = Line::styled("select a device with ↑/↓ or j/k", theme::label());
        super::unwrapped::lines(frame.buffer_mut(), inner, &[hint]);
        return;
    };
    let role = match c.kind {
        CircuitKind::Starter => "starter",
        CircuitKind::Alternator { primary: true } => "primary alternator field",
        CircuitKind::Alternator { primary: false } => "secondary alternator",
        CircuitKind::Flaps => "flap motor",
        CircuitKind::Trim(TrimKind::Pitch) => "pitch trim motor",
        CircuitKind::Trim(TrimKind::Roll) => "roll trim motor",
        CircuitKind::Device => "device",
    };
    let title = Line::from(vec![
        Span::styled(format!(" {} ", c.name), theme::panel_title()),
        Span::styled(
            format!("pin {} · id {} · {role} ", c.pin, c.id),
            theme::label(),
        ),
    ]);
    let mut lines = vec![Line::from(vec![
        Span::styled("state ", theme::label()),
        Span::styled(values::state_text(c.state), theme::state(c.state)),
        Span::styled("  amps ", theme::label()),
        Span::styled(
            values::amps(c.amps),
            if c.amps.is_some() {
                Style::new()
            } else {
                theme::unknown()
            },
        ),
    ])];
    lines.extend(last.and_then(|l| last_check_line(l, c)));
    // Most important first: a short panel cuts the bottom lines off.
    let fault = match c.state {
        CircuitState::Fault(code) => Some(code),
        _ => None,
    };
    let info = fault
        .and_then(|code| code.info())
        .filter(|i| !i.description.is_empty());
    if let CircuitState::ResetSent(code) = c.state {
        lines.push(Line::from(vec![
            Span::styled(
                format!("RESET SENT for {} ({:#04x}) ", code.name(), code.to_byte()),
                theme::caution(),
            ),
            Span::raw("waiting for the unit's next broadcast to say whether it cleared"),
        ]));
    }
    if let Some(code) = fault {
        let what = info.map_or("Code not described in ICD Appendix E.", |i| i.description);
        lines.push(Line::from(vec![
            Span::styled(
                format!("FAULT {} ({:#04x}) ", code.name(), code.to_byte()),
                theme::alert(),
            ),
            Span::raw(what),
        ]));
    }
    // A breaker over its wire is a fire risk: said before the keys, where a short
    // panel cannot cut it off; any other wire verdict after the spec.
    let wire = wire.map(|r| (r.verdict == Verdict::Unprotected, wire_line(r)));
    let wire_after = match wire {
        Some((true, line)) => {
            lines.push(line);
            None
        }
        Some((false, line)) => Some(line),
        None => None,
    };
    lines.push(Line::from(key_spans(&key_actions(c))));
    if let Some(i) = info {
        lines.push(Line::from(vec![
            Span::styled("action ", theme::label()),
            Span::raw(i.action),
        ]));
        lines.push(Line::from(vec![
            Span::styled("clears ", theme::label()),
            Span::raw(i.clears),
        ]));
    }
    lines.push(spec_line(model, c));
    lines.extend(wire_after);
    let inner = panel(frame, title);
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), inner);
}

//! The page's two per-update costs: drawing a full frame, and folding a second of the
//! unit's broadcasts into the model.
//!
//! The frame is 120×40 with a fully configured unit and ten minutes of bus history, so
//! every widget (device list, gauges, plot over a full window) has work to do. The goal
//! is ≤ 200 µs, which keeps redrawing on every change far below 1 % of a core.

use std::hint::black_box;
use std::time::{Duration, Instant};

#[cfg(unix)]
use criterion::BenchmarkGroup;
#[cfg(unix)]
use criterion::Throughput;
#[cfg(unix)]
use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{Criterion, criterion_group, criterion_main};
#[cfg(unix)]
use ratatui::Frame;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
#[cfg(unix)]
use ratatui::buffer::Buffer;
#[cfg(unix)]
use ratatui::layout::Rect;
#[cfg(unix)]
use ratatui::text::{Line, Span};
#[cfg(unix)]
use ratatui::widgets::{Block, Borders, Paragraph, Widget};
use vpx_efis::model::{Model, Source};
use vpx_efis::protocol::device::EFIS;
use vpx_efis::protocol::message::{
    DeviceEnable, DeviceName, DeviceSpec, DeviceStatus, EnableFlag, FaultStatus, FlapTrimStatus,
    SignedTenths, SwitchId, SwitchInputs, SystemStatus, Tenths,
};
use vpx_efis::protocol::{FaultCode, Message, Packet};
#[cfg(unix)]
use vpx_efis::ui;
use vpx_efis::ui::palette::{Palette, ThemeChoice, Why};
use vpx_efis::ui::state::{ControlState, ViewState};

fn system(i: u64) -> SystemStatus {
    SystemStatus {
        system_current: Tenths(140 + (i % 13) as u16),
        main_bus_volts: SignedTenths(135 + (i % 7) as i16),
        aux_battery_volts: Tenths(126),
        internal_temp: 33,
        switches: SwitchInputs::from_word(0x00FF),
        ..Default::default()
    }
}

fn devices() -> DeviceStatus {
    let mut d = DeviceStatus::default();
    for id in (2..29).step_by(2) {
        d.on[id] = true;
        d.current[id] = Tenths(10 + id as u16);
    }
    d
}

/// The snapshot tests' configured unit, so the bench draws what they pin.
#[path = "../tests/common/configured.rs"]
#[allow(dead_code)]
mod configured;

fn flap_trim(i: u64) -> FlapTrimStatus {
    configured::flap_trim((20 + (i % 200) as u8, 128, 120))
}

fn fault() -> FaultStatus {
    configured::faults(&[(EFIS, FaultCode::OverCurrent)], false)
}

/// One second of what the unit broadcasts (ICD Table 6), the busier case with a fault:
/// SYSTEM_STATUS, DEVICE_STATUS and FAULT_STATUS at 1 Hz, FLAP_TRIM_STATUS at 10 Hz.
fn second(i: u64) -> Vec<(Duration, Packet)> {
    let mut out = vec![
        (Duration::ZERO, Packet::from_vpx(0, system(i))),
        (Duration::ZERO, Packet::from_vpx(1, devices())),
        (Duration::from_millis(5), Packet::from_vpx(2, fault())),
    ];
    for k in 0..10u64 {
        out.push((
            Duration::from_millis(k * 100),
            Packet::from_vpx(3 + k as u8, flap_trim(i * 10 + k)),
        ));
    }
    out
}

/// A configured unit with ten minutes of history; returns the model and "now".
fn configured() -> (Model, Instant) {
    let t0 = Instant::now();
    let mut m = Model::new(Source::Simulated {
        scenario: "bench".into(),
    });
    m.note_connected(t0, "bench".into());
    let setup: Vec<Message> = (4..29u8)
        .flat_map(|id| {
            [
                DeviceEnable {
                    device_id: id,
                    flag: EnableFlag::Enabled,
                }
                .into(),
                DeviceName::new(id, &format!("Circuit {id}"))
                    .unwrap()
                    .into(),
                DeviceSpec {
                    device_id: id,
                    circuit_breaker: 2,
                    switch_id: SwitchId::Input(id % 10 + 1),
                    current_fault: true,
                    switch_raw: None,
                }
                .into(),
            ]
        })
        .collect();
    for msg in setup {
        m.apply_packet(t0, &Packet::from_vpx(0, msg));
    }
    let secs = 600;
    for i in 0..secs {
        let at = t0 + Duration::from_secs(i);
        for (dt, p) in second(i) {
            m.apply_packet(at + dt, &p);
        }
    }
    (m, t0 + Duration::from_millis(secs * 1000 - 600))
}

/// This thread's CPU time: on a shared, loaded machine wall time also counts the time
/// the thread waited for a core, which says nothing about the page's cost. Read with
/// clock_gettime, so the CPU-time group exists on Unix only.
#[cfg(unix)]
struct ThreadCpu;

#[cfg(unix)]
fn thread_cpu_ns() -> u64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime only writes the timespec it is given.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64
}

#[cfg(unix)]
struct Nanos;

#[cfg(unix)]
impl ValueFormatter for Nanos {
    fn scale_values(&self, typical: f64, values: &mut [f64]) -> &'static str {
        let (div, unit) = if typical >= 1e6 {
            (1e6, "ms")
        } else if typical >= 1e3 {
            (1e3, "µs")
        } else {
            (1.0, "ns")
        };
        values.iter_mut().for_each(|v| *v /= div);
        unit
    }
    fn scale_throughputs(&self, _: f64, _: &Throughput, values: &mut [f64]) -> &'static str {
        values.iter_mut().for_each(|v| *v = 1e9 / *v);
        "iter/s"
    }
    fn scale_for_machines(&self, _: &mut [f64]) -> &'static str {
        "ns"
    }
}

#[cfg(unix)]
impl Measurement for ThreadCpu {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        thread_cpu_ns()
    }
    fn end(&self, i: u64) -> u64 {
        thread_cpu_ns().saturating_sub(i)
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &Nanos
    }
}

/// The view the page draws with: the EFIS selected, painted in the dark palette (the
/// palette pass is part of every frame the person sees).
fn view() -> ViewState {
    ViewState {
        selected: Some(EFIS),
        theme: ThemeChoice {
            palette: Palette::Dark,
            why: Why::Asked,
        },
        ..Default::default()
    }
}

/// The configured unit's page on a 120×40 test terminal, in [`view`], no motor key held.
struct Page {
    model: Model,
    now: Instant,
    view: ViewState,
    control: ControlState,
    terminal: Terminal<TestBackend>,
}

impl Page {
    fn new() -> Page {
        let (model, now) = configured();
        Page {
            model,
            now,
            view: view(),
            control: ControlState::default(),
            terminal: Terminal::new(TestBackend::new(120, 40)).unwrap(),
        }
    }

    /// Draws the whole page over the terminal's previous frame, as the page does.
    fn draw(&mut self) {
        let Page {
            model,
            now,
            view,
            control,
            terminal,
        } = self;
        terminal
            .draw(|f| vpx_efis::ui::draw(f, black_box(model), view, control, *now))
            .unwrap();
    }

    /// Draws the whole page after a clear, so that every cell differs: a full redraw,
    /// not an empty diff.
    fn draw_in_full(&mut self) {
        self.terminal.clear().unwrap();
        self.draw();
    }
}

#[cfg(unix)]
fn bench_cpu(c: &mut Criterion<ThreadCpu>) {
    let mut page = Page::new();
    c.bench_function("cpu time: render 120x40 full frame", |b| {
        b.iter(|| page.draw_in_full())
    });
}

/// `draw`, one widget, benchmarked as `name` in `g`: drawn over `terminal`'s previous
/// frame, like the page.
#[cfg(unix)]
fn widget(
    g: &mut BenchmarkGroup<ThreadCpu>,
    terminal: &mut Terminal<TestBackend>,
    name: &str,
    draw: impl Fn(&mut Frame),
) {
    g.bench_function(name, |b| {
        b.iter(|| {
            terminal.draw(|f| draw(f)).unwrap();
        })
    });
}

/// Each widget alone, in the area it gets in the 120×40 frame, so a regression
/// points at its widget. Drawn over the terminal's previous frame, like the page.
#[cfg(unix)]
fn bench_widgets(c: &mut Criterion<ThreadCpu>) {
    let Page {
        model,
        now,
        view,
        control,
        mut terminal,
    } = Page::new();
    let rows = ui::ordered_circuits(&model, &view, now);
    let selected = rows.iter().find(|c| Some(c.id) == view.selected).cloned();
    let mut g = c.benchmark_group("cpu time: widget");
    let left = Rect::new(0, 1, 66, 26);
    let right = Rect::new(66, 1, 54, 38);
    let t = &mut terminal;
    widget(&mut g, t, "title bar", |f| {
        ui::title_bar::render(f, Rect::new(0, 0, 120, 1), &model, now)
    });
    widget(&mut g, t, "device list", |f| {
        ui::device_list::render(f, left, black_box(&rows), &view, false)
    });
    g.bench_function("ordering the rows", |b| {
        b.iter(|| ui::ordered_circuits(black_box(&model), &view, now))
    });
    widget(&mut g, t, "detail", |f| {
        let area = Rect::new(0, 27, 66, 12);
        ui::detail::render(f, area, &model, selected.as_ref(), None, None)
    });
    widget(&mut g, t, "system panel", |f| {
        ui::system_panel::render(f, Rect { height: 7, ..right }, &model, now)
    });
    widget(&mut g, t, "switches", |f| {
        ui::switches::render(f, Rect { height: 3, ..right }, &model, now)
    });
    widget(&mut g, t, "flaps and trim", |f| {
        ui::motors::render(f, Rect { height: 5, ..right }, &model, &control, now)
    });
    widget(&mut g, t, "plot", |f| {
        ui::plot::render(
            f,
            Rect {
                height: 14,
                ..right
            },
            &model,
            now,
        )
    });
    widget(&mut g, t, "events", |f| {
        ui::events::render(f, Rect { height: 4, ..right }, &model, now)
    });
    widget(&mut g, t, "link", |f| {
        ui::link_health::render(f, Rect { height: 4, ..right }, &model, now)
    });
    g.bench_function("palette: paint 120x40", |b| {
        let mut buf = Buffer::empty(Rect::new(0, 0, 120, 40));
        b.iter(|| Palette::Dark.paint(black_box(&mut buf)))
    });
    widget(&mut g, t, "baseline: draw nothing", |_| {});
    g.finish();
}

fn bench(c: &mut Criterion) {
    let mut page = Page::new();
    c.bench_function("render 120x40 full frame", |b| {
        b.iter(|| page.draw_in_full())
    });
    c.bench_function("render 120x40 unchanged frame", |b| b.iter(|| page.draw()));
    c.bench_function("baseline: clear and draw nothing 120x40", |b| {
        b.iter(|| {
            page.terminal.clear().unwrap();
            page.terminal.draw(|_| {}).unwrap();
        })
    });
    let packets = second(7);
    let mut m = page.model.clone();
    let base = page.now;
    c.bench_function("apply one second of broadcasts", |b| {
        b.iter(|| {
            for (dt, p) in &packets {
                m.apply_packet(base + *dt, black_box(p));
            }
        })
    });
}

/// Every row of the full frame as a line of styled spans: the most text a frame can
/// hold, in the characters and styles the page draws.
#[cfg(unix)]
fn frame_lines(terminal: &Terminal<TestBackend>) -> Vec<Line<'static>> {
    let buf = terminal.backend().buffer();
    (buf.area.top()..buf.area.bottom())
        .map(|y| {
            let mut spans: Vec<Span<'static>> = Vec::new();
            for x in buf.area.left()..buf.area.right() {
                let cell = &buf[(x, y)];
                match spans.last_mut() {
                    Some(s) if s.style == cell.style() => {
                        s.content.to_mut().push_str(cell.symbol())
                    }
                    _ => spans.push(Span::styled(cell.symbol().to_string(), cell.style())),
                }
            }
            Line::from(spans)
        })
        .collect()
}

/// The page's own text writer and panel frame against ratatui's `Paragraph` and
/// `Block`, in one run so that they are compared on the same machine load: a full
/// frame's text (as one block of 40 lines, and a line per call: the page makes fewer,
/// larger calls than that), with `Buffer::set_line` for the cost of no widget at all,
/// and a panel as large as the frame.
#[cfg(unix)]
fn bench_text(c: &mut Criterion<ThreadCpu>) {
    let mut page = Page::new();
    page.draw();
    let lines = frame_lines(&page.terminal);
    let area = Rect::new(0, 0, 120, 40);
    let rows: Vec<Rect> = area.rows().collect();
    let block = Paragraph::new(lines.clone());
    let each: Vec<Paragraph> = lines.iter().map(|l| Paragraph::new(l.clone())).collect();
    let mut buf = Buffer::empty(area);
    let mut g = c.benchmark_group("cpu time: text of a full frame");
    g.bench_function("Paragraph, 40 lines", |b| {
        b.iter(|| black_box(&block).render(area, &mut buf))
    });
    g.bench_function("Paragraph, a line per call", |b| {
        b.iter(|| {
            for (p, row) in black_box(&each).iter().zip(&rows) {
                p.render(*row, &mut buf);
            }
        })
    });
    g.bench_function("unwrapped::lines, 40 lines", |b| {
        b.iter(|| ui::unwrapped::lines(&mut buf, area, black_box(&lines)))
    });
    g.bench_function("unwrapped::lines, a line per call", |b| {
        b.iter(|| {
            for (l, row) in black_box(&lines).iter().zip(&rows) {
                ui::unwrapped::lines(&mut buf, *row, std::slice::from_ref(l));
            }
        })
    });
    g.bench_function("Buffer::set_line, 40 lines", |b| {
        b.iter(|| {
            for (l, row) in black_box(&lines).iter().zip(&rows) {
                buf.set_line(row.x, row.y, l, row.width);
            }
        })
    });
    // The panels' frames together cover the whole frame: one panel as large, with the
    // device list's titles.
    let titles = [
        Line::styled(" Devices ", ui::theme::panel_title()),
        Line::styled("by pin ", ui::theme::label()),
    ];
    let more = Line::styled(" ▲2 more ▼4 more ", ui::theme::caution());
    g.bench_function("Block, a 120x40 panel", |b| {
        b.iter(|| {
            let block = Block::new()
                .borders(Borders::TOP | Borders::RIGHT)
                .border_style(ui::theme::border())
                .title(titles[0].clone())
                .title(titles[1].clone())
                .title(more.clone().right_aligned());
            black_box(block.inner(area));
            block.render(area, &mut buf)
        })
    });
    g.bench_function("Panel, a 120x40 panel", |b| {
        b.iter(|| {
            let panel = ui::panel::Panel {
                right_side: true,
                border: ui::theme::border(),
                titles: &titles,
                right_title: Some(&more),
            };
            black_box(panel.render(area, &mut buf))
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
#[cfg(unix)]
criterion_group! {
    name = cpu;
    config = Criterion::default().with_measurement(ThreadCpu);
    targets = bench_cpu, bench_widgets, bench_text
}
#[cfg(unix)]
criterion_main!(benches, cpu);
#[cfg(not(unix))]
criterion_main!(benches);

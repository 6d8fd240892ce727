//! A check's results as the logbook keeps them ([`crate::logbook::record::Check`]):
//! what its report shows, each circuit's measured current and verdict, the switches,
//! the motors and the load analysis's figures, in the report's own words.

use super::report::{About, tally};
use super::state::{CheckView, CircuitFinding, LoadsView, Outcome};
use super::words;
use crate::loads::Level;
use crate::logbook::record::{Check, CheckCircuit, CheckItem, CheckLoad, CheckMotor};

/// The record of the check `view` shows; `load_file` is the load file's text as the
/// check read it (`None` when there was none, or it could not be read again).
pub fn check(view: &CheckView, about: &About, load_file: Option<String>) -> Check {
    let mut out = Check {
        port: about.port.clone(),
        program: about.ours.clone(),
        tally: tally(view),
        interrupted: view.interrupted.as_ref().map(|i| i.cause.clone()),
        report: view.report.as_ref().map(|p| p.display().to_string()),
        load_file,
        ..Check::default()
    };
    for c in &view.circuits {
        let amps = match &c.outcome {
            Outcome::Found(
                CircuitFinding::Within { amps, .. } | CircuitFinding::NearBreaker { amps, .. },
            ) => Some(f64::from(*amps)),
            Outcome::Found(CircuitFinding::NoCurrent) => Some(0.0),
            _ => None,
        };
        out.circuits.push(CheckCircuit {
            device: c.id,
            name: c.name.clone(),
            pin: c.pin.to_string(),
            breaker: c.breaker,
            switch: c.switch.map(words::switch_id),
            // The unit's tenths as the report prints them (f32 → f64 keeps
            // 6.1 as 6.099999904632568 otherwise).
            amps: amps.map(|a| (a * 10.0).round() / 10.0),
            verdict: c.mark().word().to_string(),
            finding: words::circuit(c),
        });
    }
    for s in &view.switches {
        let names: Vec<String> = s.circuits.iter().map(|&id| view.name_of(id)).collect();
        out.switches.push(CheckItem {
            input: s.input.label(),
            circuits: names.join(", "),
            verdict: s.mark().word().to_string(),
            finding: words::switch(s, |id| view.name_of(id)),
        });
    }
    for m in &view.motors {
        let pos: Vec<String> = m.positions.iter().map(u8::to_string).collect();
        out.motors.push(CheckMotor {
            motor: m.motor.name().to_string(),
            positions: pos.join(" "),
            verdict: m.mark().word().to_string(),
            finding: words::motor(m),
        });
    }
    if let Some(LoadsView::Analysed { path, analysis }) = &view.loads {
        out.load_path = Some(path.display().to_string());
        out.alternator_amps = Some(analysis.alternator_amps);
        out.battery_amp_hours = Some(analysis.battery_amp_hours);
        out.battery_usable = Some(analysis.battery_usable);
        for p in &analysis.phases {
            out.loads.push(CheckLoad {
                phase: p.phase.title().to_string(),
                amps: p.amps,
                margin_percent: p.margin_percent,
                endurance_minutes: p.endurance_minutes,
                level: match p.level {
                    Level::Ok => "ok",
                    Level::Warn => "warning",
                    Level::Fail => "failed",
                }
                .to_string(),
            });
        }
    }
    out
}

/// The line `vpx-efis log` lists for it: "check: 1 failed, 14 passed".
pub fn summary(record: &Check) -> String {
    match &record.interrupted {
        Some(why) => format!("check, stopped ({why}): {}", record.tally),
        None => format!("check: {}", record.tally),
    }
}

//! The load file's template for the `install` scenario's aircraft, as the check writes
//! it on a first run: each circuit's phases guessed from its name and marked as a
//! guess, so that its analysis already tells the phases apart.

use std::time::{Duration, Instant};

use vpx_efis::loads::{self, Phase, file};
use vpx_efis::model::{Circuit, Model, Setting, Source};
use vpx_efis::protocol::message::DeviceStatusQuery;
use vpx_efis::protocol::{Decoder, Event, Packet};
use vpx_efis::sim::{self, SimOptions};

/// The circuits the page lists for the `install` scenario's unit, asked for as the
/// page asks at connect.
fn install_circuits() -> Vec<Circuit> {
    let t0 = Instant::now();
    let opts = SimOptions::new(sim::load_scenario("install").unwrap());
    let mut unit = sim::build_unit(&opts, t0);
    let mut model = Model::new(Source::Simulated {
        scenario: "install".into(),
    });
    let mut asks: Vec<_> = Setting::all().map(Setting::query).collect();
    asks.push(DeviceStatusQuery.into());
    for (cnt, m) in asks.into_iter().enumerate() {
        unit.feed(&Packet::request(cnt as u8, m).to_bytes(), t0);
    }
    let now = t0 + Duration::from_millis(10);
    unit.tick(now);
    let mut decoder = Decoder::new();
    let mut packets = Vec::new();
    decoder.push(&unit.take_output(), |e| {
        if let Event::Frame(f) = e {
            packets.push(Packet::parse(&f).unwrap());
        }
    });
    for p in &packets {
        model.apply_packet(now, p);
    }
    assert!(Setting::all().all(|s| model.setting_heard(s).is_some()));
    model.circuits(now)
}

#[test]
fn the_install_template_guesses_each_circuits_phases_and_marks_them() {
    let circuits = install_circuits();
    let text = file::template(&circuits);
    // Every circuit of the unit, the guessed ones marked beside each phase.
    for c in &circuits {
        assert!(text.contains(&format!("[circuit.{}]", c.pin)), "{text}");
    }
    let section = |pin: &str| -> String {
        let start = text.find(&format!("[circuit.{pin}]\n")).unwrap();
        let rest = &text[start..];
        let end = rest[1..].find("\n[").map_or(rest.len(), |e| e + 1);
        rest[..end].trim_end().to_string()
    };
    assert_eq!(
        section("10A-1"),
        "[circuit.10A-1]\n\
         name = \"Landing Lt\"\n\
         # amps = 0.0\n\
         # wire = \"\"            # not entered: a gauge (\"22 AWG\") or metric (\"1.0 mm2\")\n\
         # wire_length = \"\"     # not entered: pin to load, \"12 ft\" or \"3.6 m\"\n\
         # return_length = \"\"   # not entered: load to ground block, if not grounded at the load\n\
         # guessed from the name: a landing or taxi light: on to taxi, take off and land; \
         the one light kept on the battery\n\
         ground = false       # guess: check\n\
         taxi = true          # guess: check\n\
         take_off = true      # guess: check\n\
         cruise_day = false   # guess: check\n\
         cruise_night = false # guess: check\n\
         landing = true       # guess: check\n\
         emergency = true     # guess: check"
    );
    assert!(
        section("5A-1").contains("cruise_night = true"),
        "nav at night"
    );
    assert!(section("10A-4").contains("pitot heat: off unless you turn it on"));
    assert!(section("Flaps").contains("take_off = 0.1"));
    // The starter and the alternator field are no guess.
    assert!(!section("Starter").contains("guess"));
    assert!(!section("Field_Pri").contains("guess"));
    // The file reads back as the circuits the template says.
    let rated = text
        .replace("# alternator_amps = 40", "alternator_amps = 40")
        .replace("# battery_amp_hours = 17", "battery_amp_hours = 17");
    let f = file::parse(&rated).unwrap();
    assert_eq!(f.circuits, file::template_circuits(&circuits));
}

/// With 2 A measured on every circuit, the phases now differ, by hand: ground has the
/// EFIS, the field, four avionics and the boost pump (7 × 2 A); taxi, take-off and
/// landing add strobe, beacon, landing and taxi lights, the flaps a tenth and two
/// trims a tenth each (11.3 × 2); cruise by day has strobe and beacon and the trims
/// (9.2 × 2), by night the nav light too (10.2 × 2); on the battery, the EFIS, four
/// avionics and the landing light (6 × 2).
#[test]
fn the_install_templates_analysis_tells_the_phases_apart() {
    let circuits = install_circuits();
    let text = file::template(&circuits)
        .replace("# alternator_amps = 40", "alternator_amps = 40")
        .replace("# battery_amp_hours = 17", "battery_amp_hours = 17");
    let f = file::parse(&text).unwrap();
    let measured: Vec<(u8, f32)> = circuits.iter().map(|c| (c.id, 2.0)).collect();
    let a = loads::analyse(&f, &measured);
    let totals: Vec<(Phase, f64)> = a.phases.iter().map(|p| (p.phase, p.amps)).collect();
    let want = [
        (Phase::Ground, 14.0),
        (Phase::Taxi, 22.6),
        (Phase::TakeOff, 22.6),
        (Phase::CruiseDay, 18.4),
        (Phase::CruiseNight, 20.4),
        (Phase::Landing, 22.6),
        (Phase::Emergency, 12.0),
    ];
    for ((p, got), (q, want)) in totals.iter().zip(want) {
        assert_eq!(*p, q);
        assert!((got - want).abs() < 1e-9, "{p:?}: {got} A, not {want} A");
    }
}

//! Data back after COMMUNICATION LOST, end to end: the page against the virtual VP-X
//! through a real pseudo-terminal, the sim's line paced at the real 5760 bytes a
//! second. The unit is renamed while it is silent (as from another display with the
//! cable out); when its data returns the page re-reads every setting at once, never
//! shows the old name as current, and shows the new one within 5 s.
// Needs a pseudo-terminal (serialport::TTYPort), which only Unix has.
#![cfg(unix)]

use std::time::{Duration, Instant};

use ratatui::buffer::Buffer;
use vpx_efis::app::AppOptions;
use vpx_efis::protocol::message::DeviceName;
use vpx_efis::sim::{Scenario, SimCommand, SimOptions};

mod page_rig;
use page_rig::*;

/// The device list's columns at the rig's 120 columns (the right column, with the
/// event log that tells of the rename, starts further right).
const LIST_COLUMNS: u16 = 60;

fn list_text(buf: &Buffer) -> String {
    (0..buf.area.height)
        .map(|y| {
            (0..LIST_COLUMNS)
                .map(|x| buf[(x, y)].symbol().to_string())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn name_of_9(rig: &Rig, now: Instant) -> Option<String> {
    rig.app
        .model()
        .circuits(now)
        .into_iter()
        .find(|c| c.id == 9)
        .map(|c| c.name)
}

#[test]
fn a_unit_renamed_while_silent_shows_its_new_name_within_5_s_and_never_the_old() {
    let scenario = Scenario::from_toml(SCENARIO).expect("scenario");
    let mut rig = Rig::with_sim(AppOptions::default(), SimOptions::new(scenario).paced());
    rig.ready();
    assert_eq!(name_of_9(&rig, Instant::now()).as_deref(), Some("GPS 1"));
    assert!(list_text(&rig.render()).contains("GPS 1"));

    rig.sim
        .inject(SimCommand::Silent(Duration::from_millis(3500)));
    rig.until("COMMUNICATION LOST", Duration::from_secs(5), |app, now| {
        app.model().comm_lost(now)
    });
    rig.sim.inject(SimCommand::Rename(
        DeviceName::new(9, "Landing Lt").unwrap(),
    ));
    let back = rig.until("the data's return", Duration::from_secs(5), |app, now| {
        !app.model().comm_lost(now)
    });

    let mut saw_rereading = false;
    let end = back + Duration::from_secs(5);
    let shown = loop {
        let now = Instant::now();
        let name = name_of_9(&rig, now);
        assert_ne!(
            name.as_deref(),
            Some("GPS 1"),
            "the old name shown as current {:?} after the data returned",
            now - back
        );
        let list = list_text(&rig.render());
        assert!(
            !list.contains("GPS 1"),
            "the old name on the list {:?} after the data returned:\n{list}",
            now - back
        );
        saw_rereading |= list.contains("re-reading settings");
        if name.as_deref() == Some("Landing Lt") && list.contains("Landing Lt") {
            break now;
        }
        assert!(now < end, "no new name within 5 s of the data's return");
        rig.app.pump_until(now + Duration::from_millis(10));
    };
    eprintln!(
        "new name on the page {:?} after the data returned",
        shown - back
    );
    assert!(
        saw_rereading,
        "the list never said it was re-reading settings"
    );
    let done = rig.until(
        "every setting re-read",
        end.saturating_duration_since(Instant::now()),
        |app, _| app.model().rereading().is_none(),
    );
    eprintln!(
        "every setting re-read {:?} after the data returned",
        done - back
    );
    assert!(!list_text(&rig.render()).contains("re-reading"));
    let m = rig.app.model();
    assert!(
        m.events
            .iter()
            .any(|e| e.text.contains("\"GPS 1\" is now \"Landing Lt\"")),
        "the rename is logged"
    );
}

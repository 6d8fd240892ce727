//! `vpx-efis log --export FILE.html`: the aircraft's records as one printable page,
//! for the annual condition inspection and for the aircraft's papers (ASTM F2490 asks
//! that the load analysis be kept for the aircraft's life).
//!
//! One self-contained file: its style inside it, no script, no image, no link, no
//! reference to anything outside it, so it opens the same on a laptop in a hangar with
//! no network and in twenty years. Black on white, in print too (`@media print`); a
//! verdict or a change is always in words and symbols ("⚠ changed since the last
//! check", "✗ FAIL"), never by colour alone. Every text from the unit or a file (a
//! circuit's name, a setting's value) is escaped.
//!
//! Pure: the caller gathers the records ([`crate::logbook::query`]) into a [`Page`].

use std::fmt::Write as _;
use std::time::SystemTime;

use super::circuit_history::minute;
use crate::check::trend::{self, Reading, amps_text, change_text};
use crate::loads::analysis::amps_text as analysis_amps;
use crate::loads::wiring::{self, Verdict};
use crate::loads::{Analysis, Phase};

/// Everything on the page.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Page {
    /// The registration ("N123AB"), or how the records are known without one.
    pub aircraft: String,
    /// The unit as last seen: "VP-X Pro, software 1.4".
    pub unit: Option<String>,
    /// When the page was made.
    pub written: Option<SystemTime>,
    /// Our version.
    pub ours: String,
    /// The wiring as the latest check found it.
    pub as_built: Option<AsBuilt>,
    /// The latest load analysis, and when it was made.
    pub analysis: Option<(SystemTime, Analysis)>,
    /// Every check, oldest first.
    pub checks: Vec<CheckEntry>,
    pub settings: Vec<SettingChange>,
    pub firmware: Vec<FirmwareUpdate>,
}

/// The wiring as built: what the latest check saw of each circuit, with its wire
/// from the load file as it was then.
#[derive(Debug, Clone, PartialEq)]
pub struct AsBuilt {
    pub when: SystemTime,
    pub circuits: Vec<BuiltCircuit>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct BuiltCircuit {
    pub pin: String,
    pub name: String,
    pub breaker: Option<u8>,
    /// "switch 3", "always on".
    pub switch: Option<String>,
    /// Its wire against its breaker ([`wiring::row`]), if the load file gave one.
    pub wire: Option<wiring::Row>,
}

/// One check: when, its result in words, who ran it, and each circuit's reading.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckEntry {
    pub when: SystemTime,
    /// "PASSED", "FAILED", "INCOMPLETE".
    pub result: String,
    /// "key", "command line"...
    pub by: String,
    pub readings: Vec<Reading>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct SettingChange {
    pub when: SystemTime,
    pub setting: String,
    pub old: String,
    pub new: String,
    pub confirmed: bool,
    pub by: String,
}

#[derive(Debug, Clone, PartialEq)]
pub struct FirmwareUpdate {
    pub when: SystemTime,
    pub sha256: String,
    pub before: String,
    pub after: String,
    pub outcome: String,
}

/// Text made safe inside an element or a quoted attribute.
pub fn escape(text: &str) -> String {
    let mut o = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            c => o.push(c),
        }
    }
    o
}

/// Checks per table of currents: a wider table would not fit a printed page.
const CHECKS_PER_TABLE: usize = 8;

/// Black on white on screen and on paper; borders, not shades, separate the cells;
/// a table's header repeats on each printed page and a row is never split.
const STYLE: &str = "
body { font-family: sans-serif; color: #000; background: #fff; margin: 2em; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; }
h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 2px solid #000; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { border: 1px solid #000; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }
th { font-weight: bold; }
td.num { text-align: right; white-space: nowrap; }
.changed { font-weight: bold; }
.note { font-size: 0.9em; }
code { font-family: monospace; }
@page { size: A4 portrait; margin: 15mm; }
@media print {
  body { margin: 0; font-size: 10pt; }
  h2 { break-after: avoid; }
  table { break-inside: auto; }
  tr { break-inside: avoid; }
  thead { display: table-header-group; }
}
";

/// The page, whole.
pub fn html(page: &Page) -> String {
    let mut o = String::new();
    let title = format!("{}: electrical records", page.aircraft);
    let _ = write!(
        o,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n",
        escape(&title),
        escape(&title)
    );
    o.push_str("<p>");
    if let Some(u) = &page.unit {
        let _ = write!(o, "Unit: {}. ", escape(u));
    }
    if let Some(w) = page.written {
        let _ = write!(o, "Written {} UTC ", minute(w));
    }
    let _ = writeln!(o, "by vpx-efis {}.</p>", escape(&page.ours));
    as_built(&mut o, page.as_built.as_ref());
    analysis(&mut o, page.analysis.as_ref());
    checks(&mut o, &page.checks);
    currents(&mut o, &page.checks);
    settings(&mut o, &page.settings);
    firmware(&mut o, &page.firmware);
    o.push_str("</body>\n</html>\n");
    o
}

/// A section's heading, then `nothing` when it is `empty`; whether there is more to say.
fn section(o: &mut String, title: &str, empty: bool, nothing: &str) -> bool {
    let _ = writeln!(o, "<h2>{title}</h2>");
    if empty {
        let _ = writeln!(o, "<p>{nothing}</p>");
    }
    !empty
}

/// A table's opening and its head row; [`TABLE_END`] closes it.
fn table_head<'a>(o: &mut String, heads: impl IntoIterator<Item = &'a str>) {
    o.push_str("<table>\n<thead><tr>");
    for h in heads {
        let _ = write!(o, "<th>{}</th>", escape(h));
    }
    o.push_str("</tr></thead>\n<tbody>\n");
}

const TABLE_END: &str = "</tbody>\n</table>\n";

fn dash<T>(v: Option<T>, f: impl Fn(T) -> String) -> String {
    v.map_or_else(|| "—".into(), f)
}

fn as_built(o: &mut String, built: Option<&AsBuilt>) {
    o.push_str("<h2>The wiring as built</h2>\n");
    let Some(b) = built else {
        o.push_str("<p>No check has recorded the wiring yet.</p>\n");
        return;
    };
    let _ = writeln!(
        o,
        "<p>As the latest check found it, {} UTC; the wires as the load file gave them \
         then, each held against its breaker (AC 43.13-1B Table 11-3).</p>",
        minute(b.when)
    );
    table_head(
        o,
        "Pin|Circuit|Breaker|Switch|Wire|Run|Wire against breaker".split('|'),
    );
    for c in &b.circuits {
        let w = c.wire.as_ref();
        let verdict = match w.map(|w| w.verdict) {
            Some(Verdict::Unprotected) => "✗ UNPROTECTED".to_string(),
            Some(Verdict::Drop) => "⚠ drop over the limit".to_string(),
            Some(Verdict::Ok) => "✓ ok".to_string(),
            Some(Verdict::NotEntered) | None => "not entered".to_string(),
        };
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td><td>{}</td>\
             <td class=\"num\">{}</td><td>{}</td></tr>",
            escape(&c.pin),
            escape(&c.name),
            dash(c.breaker, |b| format!("{b} A")),
            escape(c.switch.as_deref().unwrap_or("—")),
            dash(w.and_then(|w| w.wire), |w| escape(&w.to_string())),
            dash(w.and_then(|w| w.run_feet), crate::loads::wire::feet_text),
            escape(&verdict),
        );
    }
    o.push_str(TABLE_END);
    for c in &b.circuits {
        if let Some(t) = c.wire.as_ref().and_then(wiring::Row::unprotected_words) {
            let _ = writeln!(o, "<p class=\"changed\">✗ {}.</p>", escape(&t));
        }
    }
}

fn analysis(o: &mut String, a: Option<&(SystemTime, Analysis)>) {
    o.push_str("<h2>The latest load analysis</h2>\n");
    let Some((when, a)) = a else {
        o.push_str("<p>No check has made a load analysis yet.</p>\n");
        return;
    };
    let _ = writeln!(
        o,
        "<p>Made by the check of {} UTC. Alternator {} A rated; battery {} Ah rated × {} \
         usable = {} Ah.</p>",
        minute(*when),
        analysis_amps(a.alternator_amps),
        analysis_amps(a.battery_amp_hours),
        a.battery_usable,
        analysis_amps(a.usable_amp_hours())
    );
    table_head(o, "Phase|Total|Result|Margin or endurance".split('|'));
    for p in &a.phases {
        let mark = crate::check::state::Mark::of(p.level);
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td class=\"num\">{} A</td><td>{} {}</td><td>{}</td></tr>",
            escape(p.phase.title()),
            analysis_amps(p.amps),
            mark.symbol(),
            mark.word(),
            escape(&a.verdict(p.phase))
        );
    }
    o.push_str(TABLE_END);
    table_head(
        o,
        ["Circuit", "Pin", "Current", "From"]
            .into_iter()
            .chain(Phase::ALL.map(Phase::title)),
    );
    for r in &a.rows {
        let _ = write!(
            o,
            "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td>",
            escape(&r.name),
            escape(r.pin),
            match r.figure {
                crate::loads::Figure::Missing => "none".to_string(),
                f => format!("{} A", analysis_amps(f.amps())),
            },
            escape(r.figure.source())
        );
        for p in Phase::ALL {
            let d = r.duty[p.index()];
            let _ = write!(
                o,
                "<td class=\"num\">{}</td>",
                if d >= 1.0 {
                    "on".to_string()
                } else if d <= 0.0 {
                    "–".to_string()
                } else {
                    format!("{d}")
                }
            );
        }
        o.push_str("</tr>\n");
    }
    o.push_str(TABLE_END);
}

fn checks(o: &mut String, checks: &[CheckEntry]) {
    if !section(o, "The checks", checks.is_empty(), "No check is recorded.") {
        return;
    }
    table_head(
        o,
        "When (UTC)|Result|By|Circuits measured|Changed since the check before".split('|'),
    );
    let mut before: Option<&CheckEntry> = None;
    for c in checks {
        let measured = c.readings.iter().filter(|r| r.tenths.is_some()).count();
        let changed: Vec<String> = c
            .readings
            .iter()
            .filter(|r| {
                trend::trend(before.map(last_of).as_ref(), &r.pin, &r.name, r.tenths).changed()
            })
            .map(|r| escape(&r.name))
            .collect();
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{measured}</td><td>{}</td></tr>",
            minute(c.when),
            escape(&c.result),
            escape(&c.by),
            if changed.is_empty() {
                "—".to_string()
            } else {
                format!("⚠ {}", changed.join(", "))
            }
        );
        before = Some(c);
    }
    o.push_str(TABLE_END);
}

fn last_of(c: &CheckEntry) -> trend::LastCheck {
    trend::LastCheck {
        when: Some(c.when),
        circuits: c.readings.clone(),
    }
}

/// Each circuit's currents over time: a row per circuit (by name, in the pin order
/// of its latest check), a column per check, each figure with its change against
/// the check before and the words when the trend rule marks it.
fn currents(o: &mut String, checks: &[CheckEntry]) {
    if !section(
        o,
        "Each circuit's current at each check",
        checks.iter().all(|c| c.readings.is_empty()),
        "No current is recorded.",
    ) {
        return;
    }
    let _ = writeln!(
        o,
        "<p class=\"note\">Against the check before: a change over {} % and at least {} \
         is marked ⚠ {}.</p>",
        trend::CHANGED_PERCENT,
        amps_text(trend::CHANGED_MIN_TENTHS as u16),
        trend::CHANGED_WORDS
    );
    // The circuits: the latest check's first (in its order, the unit's), then any
    // seen only before.
    let mut names: Vec<(String, String)> = Vec::new();
    for c in checks.iter().rev() {
        for r in &c.readings {
            if !names
                .iter()
                .any(|(n, _)| n.trim().eq_ignore_ascii_case(r.name.trim()))
            {
                names.push((r.name.clone(), r.pin.clone()));
            }
        }
    }
    for (part, chunk) in checks.chunks(CHECKS_PER_TABLE).enumerate() {
        let start = part * CHECKS_PER_TABLE;
        let when: Vec<String> = chunk.iter().map(|c| minute(c.when)).collect();
        table_head(
            o,
            ["Circuit"]
                .into_iter()
                .chain(when.iter().map(String::as_str)),
        );
        for (name, pin) in &names {
            let _ = write!(
                o,
                "<tr><td>{} <span class=\"note\">({})</span></td>",
                escape(name),
                escape(pin)
            );
            for (i, c) in chunk.iter().enumerate() {
                let idx = start + i;
                let now = c
                    .readings
                    .iter()
                    .find(|r| r.name.trim().eq_ignore_ascii_case(name.trim()));
                let Some(now) = now else {
                    o.push_str("<td class=\"num\">—</td>");
                    continue;
                };
                let Some(t) = now.tenths else {
                    o.push_str("<td class=\"num\">none</td>");
                    continue;
                };
                let prev = idx
                    .checked_sub(1)
                    .map(|j| last_of(&checks[j]))
                    .map(|l| trend::trend(Some(&l), &now.pin, &now.name, Some(t)));
                match prev
                    .as_ref()
                    .and_then(|tr| tr.then_tenths().map(|b| (tr, b)))
                {
                    Some((tr, b)) if tr.changed() => {
                        let _ = write!(
                            o,
                            "<td class=\"num changed\">{} ({})<br>⚠ changed</td>",
                            amps_text(t),
                            change_text(b, t)
                        );
                    }
                    Some((_, b)) => {
                        let _ = write!(
                            o,
                            "<td class=\"num\">{} ({})</td>",
                            amps_text(t),
                            change_text(b, t)
                        );
                    }
                    None => {
                        let _ = write!(o, "<td class=\"num\">{}</td>", amps_text(t));
                    }
                }
            }
            o.push_str("</tr>\n");
        }
        o.push_str(TABLE_END);
    }
}

fn settings(o: &mut String, changes: &[SettingChange]) {
    if !section(
        o,
        "Settings changed",
        changes.is_empty(),
        "No setting change is recorded.",
    ) {
        return;
    }
    table_head(o, "When (UTC)|Setting|Was|Now|Unit confirmed|By".split('|'));
    for c in changes {
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            minute(c.when),
            escape(&c.setting),
            escape(&c.old),
            escape(&c.new),
            if c.confirmed {
                "✓ yes"
            } else {
                "✗ NOT confirmed"
            },
            escape(&c.by)
        );
    }
    o.push_str(TABLE_END);
}

fn firmware(o: &mut String, updates: &[FirmwareUpdate]) {
    if !section(
        o,
        "Firmware updates",
        updates.is_empty(),
        "No firmware update is recorded.",
    ) {
        return;
    }
    table_head(
        o,
        "When (UTC)|Before|After|Outcome|Image SHA-256".split('|'),
    );
    for u in updates {
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td><code>{}</code></td></tr>",
            minute(u.when),
            escape(&u.before),
            escape(&u.after),
            escape(&u.outcome),
            escape(&u.sha256)
        );
    }
    o.push_str(TABLE_END);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn at(day: u64) -> SystemTime {
        std::time::UNIX_EPOCH + Duration::from_secs(1_796_149_800 + day * 86_400)
    }

    fn reading(pin: &str, name: &str, tenths: Option<u16>) -> Reading {
        Reading {
            pin: pin.into(),
            name: name.into(),
            tenths,
        }
    }

    pub(crate) fn sample(name: &str) -> Page {
        Page {
            aircraft: "N123AB".into(),
            unit: Some("VP-X Pro, software 1.4".into()),
            written: Some(at(3)),
            ours: "0.1.0".into(),
            as_built: Some(AsBuilt {
                when: at(2),
                circuits: vec![BuiltCircuit {
                    pin: "J5-3".into(),
                    name: name.into(),
                    breaker: Some(10),
                    switch: Some("switch 3".into()),
                    wire: None,
                }],
            }),
            analysis: None,
            checks: vec![
                CheckEntry {
                    when: at(0),
                    result: "PASSED".into(),
                    by: "key".into(),
                    readings: vec![reading("J5-3", name, Some(61))],
                },
                CheckEntry {
                    when: at(2),
                    result: "PASSED".into(),
                    by: "command line".into(),
                    readings: vec![reading("J5-3", name, Some(75))],
                },
            ],
            settings: vec![SettingChange {
                when: at(1),
                setting: format!("{name} breaker"),
                old: "8 A".into(),
                new: "10 A".into(),
                confirmed: true,
                by: "setup".into(),
            }],
            firmware: vec![FirmwareUpdate {
                when: at(1),
                sha256: "ab".repeat(32),
                before: "1.3".into(),
                after: "1.4".into(),
                outcome: "updated".into(),
            }],
        }
    }

    /// Self-contained: nothing the page refers to lies outside it.
    #[test]
    fn the_page_refers_to_nothing_outside_itself() {
        let p = html(&sample("Landing Lt"));
        for bad in [
            "http", "//", "src=", "href=", "url(", "@import", "<script", "<link",
        ] {
            assert!(!p.contains(bad), "{bad} in the page:\n{p}");
        }
        assert!(p.starts_with("<!DOCTYPE html>"));
        assert!(p.contains("@media print"));
    }

    #[test]
    fn names_from_the_unit_are_escaped() {
        let p = html(&sample("<img src=x onerror=alert(1)>&\"'"));
        assert!(!p.contains("<img"), "{p}");
        assert!(p.contains("&lt;img src=x onerror=alert(1)&gt;&amp;&quot;&#39;"));
        // The page's own markup is intact: the same number of rows as with a plain name.
        let plain = html(&sample("Landing Lt"));
        assert_eq!(p.matches("<tr>").count(), plain.matches("<tr>").count());
    }

    /// The change is said in words and a symbol, not by colour: there is no colour
    /// but black and white in the page.
    #[test]
    fn a_change_is_in_words_and_the_page_is_black_on_white() {
        let p = html(&sample("Landing Lt"));
        assert!(p.contains("7.5 A (+23 %)<br>⚠ changed"), "{p}");
        assert!(p.contains("<td>⚠ Landing Lt</td>"), "{p}");
        let colours: Vec<&str> = p.match_indices('#').map(|(i, _)| &p[i..i + 4]).collect();
        assert!(
            colours.iter().all(|c| *c == "#000" || *c == "#fff"),
            "{colours:?}"
        );
        for section in [
            "The wiring as built",
            "The latest load analysis",
            "The checks",
            "Each circuit's current at each check",
            "Settings changed",
            "Firmware updates",
        ] {
            assert!(p.contains(&format!("<h2>{section}</h2>")), "{section}");
        }
    }

    #[test]
    fn many_checks_are_split_into_tables_that_fit_a_page() {
        let mut page = sample("Landing Lt");
        page.checks = (0..10)
            .map(|d| CheckEntry {
                when: at(d),
                result: "PASSED".into(),
                by: "key".into(),
                readings: vec![reading("J5-3", "Landing Lt", Some(60))],
            })
            .collect();
        let p = html(&page);
        let part = p.split("Each circuit's current").nth(1).unwrap();
        let part = part.split("<h2>Settings").next().unwrap();
        assert_eq!(part.matches("<table>").count(), 2);
    }
}

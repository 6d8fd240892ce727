//! The page's event log as a test reads it: the texts of its lines, oldest first.
//! Included by `#[path]` where a test does not load all of `common`.

use vpx_efis::model::Model;

/// Every line's text.
pub fn texts(m: &Model) -> Vec<String> {
    m.events.iter().map(|e| e.text.clone()).collect()
}

/// The lines whose text contains `words`.
pub fn containing(m: &Model, words: &str) -> Vec<String> {
    m.events
        .iter()
        .filter(|e| e.text.contains(words))
        .map(|e| e.text.clone())
        .collect()
}

/// Fails, showing the whole log, unless a line starts with `start`.
#[track_caller]
pub fn assert_a_line_starts(m: &Model, start: &str) {
    let log = texts(m);
    assert!(
        log.iter().any(|l| l.starts_with(start)),
        "no line starts {start:?}: {log:#?}"
    );
}

//! The guide's traceability table (`docs/src/contributing/traceability.md`) is held
//! here: every message the codec crate knows (ICD Appendix D, the §6.2 messages beyond
//! it, and the bootloader's commands) has a row, and every file and test the table
//! names exists, so a renamed test or a moved file cannot leave it pointing nowhere.

#[path = "common/cited_rows.rs"]
mod cited_rows;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use vpx_efis::protocol::bootloader::BootCommand;
use vpx_efis::protocol::message::{ALL_IDS, lookup};

const TABLE: &str = "docs/src/contributing/traceability.md";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The table's rows: the first cell (the message or recommendation) and every
/// backticked item of the row.
fn rows(text: &str) -> Vec<(String, Vec<String>)> {
    text.lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("|---"))
        .map(|l| {
            let first = l
                .trim_start_matches("| ")
                .split(" |")
                .next()
                .unwrap_or("")
                .trim();
            let items = l
                .split('`')
                .enumerate()
                .filter(|(i, _)| i % 2 == 1)
                .map(|(_, s)| s.to_string())
                .collect();
            (first.to_string(), items)
        })
        .collect()
}

/// What is wrong with one backticked item: a path that does not exist, or a
/// `file::test` whose file has no such function.
fn check_item(root: &Path, item: &str) -> Option<String> {
    let (file, test) = match item.split_once(".rs::") {
        Some((f, t)) => (format!("{f}.rs"), Some(t)),
        None if item.ends_with(".rs") || item.ends_with('/') => (item.to_string(), None),
        None => return None,
    };
    let path = root.join(&file);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Some(format!("{file}: no such file"));
    };
    let test = test?;
    let declared = [format!("fn {test}("), format!("fn {test}<")];
    (!declared.iter().any(|d| text.contains(d.as_str())))
        .then(|| format!("{file}: no function {test}"))
}

fn problems(root: &Path, text: &str) -> Vec<String> {
    let mut found = cited_rows::missing(root, text);
    for (_, items) in rows(text) {
        for item in items {
            found.extend(check_item(root, &item));
        }
    }
    found
}

#[test]
fn every_message_the_codec_knows_has_a_row_and_every_name_in_the_table_exists() {
    let text = std::fs::read_to_string(root().join(TABLE)).unwrap();
    let listed: BTreeSet<String> = rows(&text).into_iter().map(|(m, _)| m).collect();
    let mut missing = Vec::new();
    for id in ALL_IDS {
        let (name, _) = lookup(*id).expect("every id of ALL_IDS has a name");
        if !listed.contains(name) {
            missing.push(name.to_string());
        }
    }
    let boot = [
        BootCommand::serial_conf(),
        BootCommand::FlashErase,
        BootCommand::flash_prog(0, &[0xFF]).unwrap(),
        BootCommand::QueryPort,
        BootCommand::flash_read_page(0),
        BootCommand::Signature,
        BootCommand::Version,
        BootCommand::Exit,
    ];
    for command in boot {
        if !listed.contains(command.name()) {
            missing.push(format!("bootloader {}", command.name()));
        }
    }
    assert!(missing.is_empty(), "{TABLE} has no row for: {missing:?}");
    // The five recommendations of ICD §2.1 and 25 + 8 messages, at least.
    assert!(rows(&text).len() >= 5 + 25 + 8, "{}", rows(&text).len());

    let problems = problems(&root(), &text);
    assert!(
        problems.is_empty(),
        "{TABLE} names what does not exist:\n  {}",
        problems.join("\n  ")
    );
}

/// A planted missing test and a planted missing file are found.
#[test]
fn a_name_that_does_not_exist_is_found() {
    let text = "| PING | `tests/sim_icd.rs::s8_1_1_ping`, `tests/sim_icd.rs::no_such_test`, \
                `src/no_such_file.rs`, \
                `crates/vpx-protocol/tests/protocol_vectors.rs::every_vector_parses_and_emits_as_its_icd_table_says` \
                (rows \"PING request\" and \"PING sideways\") |\n";
    let found = problems(&root(), text);
    assert_eq!(
        found,
        [
            "crates/vpx-protocol/tests/protocol_vectors.rs: no row \"PING sideways\"",
            "tests/sim_icd.rs: no function no_such_test",
            "src/no_such_file.rs: no such file"
        ]
    );
}

//! The readings of the ICD and the XFSp draft live in `docs/src/contributing/icd-reading.md`, inside the
//! repository. This test keeps the code and that file in step:
//!
//! * every citation `icd-reading R7` (or `icd-reading R17 and R24`, `icd-reading X3`)
//!   in the Rust sources and the README names an entry that the file has;
//! * nothing cites the old notes outside the repository any more;
//! * every file and every test the entries name exists, so an entry cannot point at
//!   code that has moved or a test that was renamed, nor a table's row that is gone.

#[path = "common/cited_rows.rs"]
mod cited_rows;
#[path = "common/files.rs"]
#[allow(dead_code)]
mod files;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

const DOC: &str = "docs/src/contributing/icd-reading.md";

/// Where citations are looked for, from the repository root.
const SOURCE_DIRS: &[&str] = &["src", "tests", "benches", "crates"];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The entry ids the document defines: `## R7: ...` gives `R7`.
fn entries(doc: &str) -> Result<BTreeSet<String>, String> {
    let mut ids = BTreeSet::new();
    for line in doc.lines() {
        let Some(rest) = line.strip_prefix("## ") else {
            continue;
        };
        let Some((id, _title)) = rest.split_once(':') else {
            continue;
        };
        if let Some(id) = entry_id(id)
            && !ids.insert(id.to_string())
        {
            return Err(format!("{DOC}: entry {id} is defined twice"));
        }
    }
    Ok(ids)
}

/// `R7` or `X3`: a letter R or X and a number, nothing else.
fn entry_id(s: &str) -> Option<&str> {
    let digits = s.strip_prefix(['R', 'X'])?;
    (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())).then_some(s)
}

/// A source with each line's comment marker (`//`, `///`, `//!`) taken off the start of
/// the line after a line break, so that a citation wrapped over two comment lines reads
/// as one.
fn joined(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for (i, line) in text.lines().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        let t = line.trim_start();
        let t = t
            .strip_prefix("//!")
            .or_else(|| t.strip_prefix("///"))
            .or_else(|| t.strip_prefix("//"))
            .unwrap_or(t);
        out.push_str(t.trim());
    }
    out
}

/// The ids each `icd-reading` citation in `text` names, or a problem with one, each
/// with a few words of its context. `icd-reading.md` (the file itself) is not a
/// citation of an entry.
fn citations(text: &str) -> Vec<Result<String, String>> {
    let mut found = Vec::new();
    for (at, _) in text.match_indices("icd-reading") {
        let rest = &text[at + "icd-reading".len()..];
        if rest.starts_with(".md") {
            continue;
        }
        let context: String = text[at..].chars().take(40).collect();
        let mut rest = rest.trim_start();
        let mut any = false;
        loop {
            let len = rest
                .char_indices()
                .find(|&(i, c)| !(c.is_ascii_digit() || (i == 0 && (c == 'R' || c == 'X'))))
                .map_or(rest.len(), |(i, _)| i);
            match entry_id(&rest[..len]) {
                Some(id) => {
                    found.push(Ok(id.to_string()));
                    any = true;
                }
                None => break,
            }
            rest = &rest[len..];
            match [", ", " and "]
                .iter()
                .find_map(|sep| rest.strip_prefix(sep))
            {
                Some(next) if next.starts_with(['R', 'X']) => rest = next,
                _ => break,
            }
        }
        if !any {
            found.push(Err(format!("a citation without an entry id: `{context}`")));
        }
    }
    found
}

/// The folder beside the repository that the project must not need, spelt in two
/// pieces so that this test, which only looks for it, does not read as a reader of it.
const OUTSIDE: &str = concat!("..", "/shared");

/// Old citations: of the notes file outside the repository, or in the words used
/// before this document existed.
fn stale_citations(text: &str) -> Vec<String> {
    let lower = text.to_lowercase();
    ["reading note", "reading-notes", OUTSIDE, "shared/spec"]
        .iter()
        .filter_map(|old| {
            lower.find(old).map(|at| {
                let context: String = text[at..].chars().take(40).collect();
                format!("cites `{old}`: `{context}`")
            })
        })
        .collect()
}

/// Every problem with the citations in the sources, as `path: problem`.
fn citation_problems(ids: &BTreeSet<String>, files: &[(String, String)]) -> Vec<String> {
    let mut problems = Vec::new();
    for (path, text) in files {
        let text = joined(text);
        for c in citations(&text) {
            match c {
                Ok(id) if ids.contains(&id) => {}
                Ok(id) => problems.push(format!("{path}: cites {id}, which {DOC} lacks")),
                Err(e) => problems.push(format!("{path}: {e}")),
            }
        }
        for e in stale_citations(&text) {
            problems.push(format!("{path}: {e}"));
        }
    }
    problems
}

fn sources() -> Vec<(String, String)> {
    let mut paths: Vec<PathBuf> = SOURCE_DIRS
        .iter()
        .flat_map(|dir| files::below(&root().join(dir), "rs"))
        .collect();
    paths.push(root().join("README.md"));
    let this = root().join("tests").join("icd_reading.rs");
    paths
        .into_iter()
        .filter(|p| *p != this)
        .map(|p| {
            let text = fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let name = p.strip_prefix(root()).unwrap_or(&p).display().to_string();
            (name, text)
        })
        .collect()
}

fn doc() -> String {
    fs::read_to_string(root().join(DOC)).unwrap_or_else(|e| panic!("{DOC}: {e}"))
}

#[test]
fn every_citation_names_an_entry_and_none_cites_the_old_notes() {
    let ids = entries(&doc()).unwrap();
    assert!(ids.contains("R1") && ids.contains("X1"), "{ids:?}");
    let files = sources();
    let cited = files
        .iter()
        .map(|(_, t)| citations(&joined(t)).into_iter().flatten().count())
        .sum::<usize>();
    // The sources do cite the document (guards against a scan that reads nothing).
    assert!(cited > 100, "only {cited} citations found");
    let problems = citation_problems(&ids, &files);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_bad_citation_is_caught() {
    let ids = entries(&doc()).unwrap();
    let files = |text: &str| vec![("src/planted.rs".to_string(), text.to_string())];
    let good = "/// Tenths of a second (icd-reading R23), and (icd-reading R17 and\n/// R24).";
    assert_eq!(citation_problems(&ids, &files(good)), Vec::<String>::new());
    for (bad, why) in [
        ("// (icd-reading R99).", "cites R99"),
        ("// icd-reading R17 and R98.", "cites R98"),
        ("// icd-reading X10.", "cites X10"),
        ("// see icd-reading for this.", "without an entry id"),
        ("// (reading note 9)", "`reading note`"),
        ("// Reading\n// notes 17 and 24", "`reading note`"),
        ("// READING-NOTES.md", "`reading-notes`"),
        (
            concat!("// ..", "/shared/spec/vpx-icd-v2.1.txt"),
            concat!("`..", "/shared`"),
        ),
    ] {
        let problems = citation_problems(&ids, &files(bad));
        assert!(
            problems.iter().any(|p| p.contains(why)),
            "{bad:?}: {problems:?}"
        );
    }
}

/// The backticked `path` and `path::test` names of the document.
fn named_in_doc(doc: &str) -> Vec<(String, Option<String>)> {
    doc.split('`')
        .skip(1)
        .step_by(2)
        .filter(|s| s.contains(".rs"))
        .map(|s| match s.split_once(".rs::") {
            Some((path, test)) => (format!("{path}.rs"), Some(test.to_string())),
            None => (s.to_string(), None),
        })
        .collect()
}

#[test]
fn every_file_and_test_the_document_names_exists() {
    let doc = doc();
    let named = named_in_doc(&doc);
    assert!(named.len() > 100, "only {} names read", named.len());
    let mut missing = Vec::new();
    for (path, test) in &named {
        let Ok(text) = fs::read_to_string(root().join(path)) else {
            missing.push(format!("{path}: no such file"));
            continue;
        };
        if let Some(test) = test {
            let defined = text.match_indices(&format!("fn {test}")).any(|(at, _)| {
                let after = &text[at + 3 + test.len()..];
                after.starts_with('(') || after.starts_with('<')
            });
            if !defined {
                missing.push(format!("{path}: no fn {test}"));
            }
        }
    }
    missing.extend(cited_rows::missing(root(), &doc));
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

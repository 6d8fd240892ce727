//! Every relative link and image in `README.md` and the guide (`docs/src/**/*.md`)
//! leads somewhere: the file exists, and a `#anchor` names a heading of that page,
//! computed as mdBook and GitHub compute them. Links to the web are not followed.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Component, Path, PathBuf};

#[path = "common/files.rs"]
#[allow(dead_code)]
mod files;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The Markdown files checked: the README and every page of the guide.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![root().join("README.md")];
    docs.extend(files::below(&root().join("docs/src"), "md"));
    docs
}

/// For each line, whether it belongs to a fenced code block (its fences included).
fn in_fence(text: &str) -> Vec<bool> {
    let mut open: Option<String> = None;
    text.lines()
        .map(|line| {
            let trimmed = line.trim();
            let ticks: String = trimmed
                .chars()
                .take_while(|&c| c == '`' || c == '~')
                .collect();
            match &open {
                Some(fence) => {
                    if ticks.len() >= fence.len() && trimmed == ticks {
                        open = None;
                    }
                    true
                }
                None if ticks.len() >= 3 => {
                    open = Some(ticks);
                    true
                }
                None => false,
            }
        })
        .collect()
}

/// The text with fenced code blocks and inline code blanked out (lines kept), so that
/// nothing in code is taken for a link.
fn prose_only(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for (line, fenced) in text.lines().zip(in_fence(text)) {
        if !fenced {
            let mut in_code = false;
            for c in line.chars() {
                if c == '`' {
                    in_code = !in_code;
                    out.push(' ');
                } else {
                    out.push(if in_code { ' ' } else { c });
                }
            }
        }
        out.push('\n');
    }
    out
}

/// A heading's anchor as mdBook and GitHub make it: lower case, letters, digits, `-`
/// and `_` kept, spaces made `-`, everything else dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .chars()
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                Some(c.to_lowercase().collect::<String>())
            } else if c == ' ' {
                Some("-".into())
            } else {
                None
            }
        })
        .collect()
}

/// A heading's text as it reads: code spans' backticks, emphasis and link targets
/// gone.
fn heading_text(raw: &str) -> String {
    let mut text = String::new();
    let mut chars = raw.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '`' | '*' => {}
            ']' if chars.peek() == Some(&'(') => {
                for d in chars.by_ref() {
                    if d == ')' {
                        break;
                    }
                }
            }
            '[' => {}
            _ => text.push(c),
        }
    }
    text
}

/// Every heading anchor of a page, duplicates numbered `-1`, `-2`… as both tools do.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    for (line, fenced) in text.lines().zip(in_fence(text)) {
        if fenced {
            continue;
        }
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if (1..=6).contains(&hashes) && line[hashes..].starts_with(' ') {
            let base = anchor(&heading_text(&line[hashes..]));
            let mut id = base.clone();
            let mut n = 0;
            while found.contains(&id) {
                n += 1;
                id = format!("{base}-{n}");
            }
            found.insert(id);
        }
    }
    found
}

/// Every link target of a page with its line: `[text](target)`, `![alt](target)` and
/// `src="target"` / `href="target"` in HTML.
fn links(text: &str) -> Vec<(usize, String)> {
    let prose = prose_only(text);
    let mut found = Vec::new();
    for (n, line) in prose.lines().enumerate() {
        let mut rest = line;
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let end = after.find(')').unwrap_or(after.len());
            let target = after[..end].split_whitespace().next().unwrap_or("");
            found.push((n + 1, target.to_string()));
            rest = &after[end..];
        }
        for attr in ["src=\"", "href=\""] {
            let mut rest = line;
            while let Some(i) = rest.find(attr) {
                let after = &rest[i + attr.len()..];
                let end = after.find('"').unwrap_or(after.len());
                found.push((n + 1, after[..end].to_string()));
                rest = &after[end..];
            }
        }
    }
    found
}

fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// What is wrong with each relative link of these documents, one line each.
fn broken(docs: &[PathBuf]) -> Vec<String> {
    let mut problems = Vec::new();
    for doc in docs {
        let text = fs::read_to_string(doc).unwrap();
        let shown = doc
            .strip_prefix(root())
            .unwrap_or(doc)
            .display()
            .to_string();
        for (line, target) in links(&text) {
            if target.is_empty() {
                problems.push(format!("{shown}:{line}: an empty link"));
                continue;
            }
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (path, fragment) = match target.split_once('#') {
                Some((p, f)) => (p, Some(f)),
                None => (target.as_str(), None),
            };
            let file = if path.is_empty() {
                doc.clone()
            } else {
                normalize(&doc.parent().unwrap().join(path))
            };
            if !file.exists() {
                problems.push(format!("{shown}:{line}: {target}: no such file"));
                continue;
            }
            if let Some(fragment) = fragment {
                if file.extension().is_none_or(|e| e != "md") {
                    problems.push(format!(
                        "{shown}:{line}: {target}: an anchor into a file that is not Markdown"
                    ));
                    continue;
                }
                let target_text = fs::read_to_string(&file).unwrap();
                if !anchors(&target_text).contains(fragment) {
                    problems.push(format!(
                        "{shown}:{line}: {target}: no heading with that anchor"
                    ));
                }
            }
        }
    }
    problems
}

#[test]
fn every_relative_link_and_anchor_in_the_readme_and_the_guide_leads_somewhere() {
    let docs = documents();
    assert!(docs.len() > 20, "the guide's pages: {docs:?}");
    let problems = broken(&docs);
    assert!(
        problems.is_empty(),
        "broken links:\n  {}",
        problems.join("\n  ")
    );
}

#[test]
fn every_page_of_the_guide_is_in_its_summary() {
    let src = root().join("docs/src");
    let summary = fs::read_to_string(src.join("SUMMARY.md")).unwrap();
    let listed: BTreeSet<String> = links(&summary).into_iter().map(|(_, t)| t).collect();
    for doc in documents().iter().filter(|d| d.starts_with(&src)) {
        let rel = doc
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if rel == "SUMMARY.md" {
            continue;
        }
        assert!(listed.contains(&rel), "docs/src/{rel} is not in SUMMARY.md");
    }
}

#[test]
fn anchors_are_made_as_mdbook_and_github_make_them() {
    assert_eq!(
        anchor("Light and dark terminals, and NO_COLOR"),
        "light-and-dark-terminals-and-no_color"
    );
    assert_eq!(anchor(&heading_text("`vpx-efis sim`")), "vpx-efis-sim");
    assert_eq!(anchor("A phone that won't pair"), "a-phone-that-wont-pair");
    let page = "# A\n\n```\n# not a heading\n```\n\n## A\n";
    assert_eq!(
        anchors(page),
        BTreeSet::from(["a".to_string(), "a-1".to_string()])
    );
}

/// A planted broken link, and a planted broken anchor, are found.
#[test]
fn a_broken_link_or_anchor_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.md");
    fs::write(dir.path().join("b.md"), "# Here\n").unwrap();
    fs::write(
        &a,
        "[ok](b.md#here) [gone](c.md) [bad](b.md#there) `[code](x.md)`\n",
    )
    .unwrap();
    let problems = broken(&[a]);
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].contains("c.md: no such file"), "{problems:?}");
    assert!(
        problems[1].contains("b.md#there: no heading"),
        "{problems:?}"
    );
}

/// The README fits two screens, and CI runs exactly the test command it gives.
#[test]
fn the_readme_is_short_and_ci_runs_its_test_command() {
    let readme = fs::read_to_string(root().join("README.md")).unwrap();
    let lines = readme.lines().count();
    assert!(
        lines <= 200,
        "README.md has {lines} lines: the guide is the place for more"
    );
    let command = readme
        .split("Run the tests:\n\n```sh\n")
        .nth(1)
        .and_then(|s| s.lines().next())
        .expect("the README's set-up gives the test command");
    assert!(command.starts_with("cargo test "), "{command}");
    let ci = fs::read_to_string(root().join(".ci/run")).unwrap();
    assert!(
        ci.lines().any(|l| l.starts_with(command)),
        ".ci/run does not run the README's test command {command:?}"
    );
}

//! The guide's reference pages (`docs/src/reference/*.md`) are generated from the code
//! (`vpx_efis::cli::reference`); this test regenerates them and fails when a committed
//! page differs, in the spirit of the snapshots: a key, a subcommand, an option, a
//! route, an exit code or a fault's words changed without regenerating.

use std::path::Path;

use vpx_efis::cli::reference::{DIR, REGENERATE, pages};

#[test]
fn every_reference_page_is_as_the_code_generates_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut stale = Vec::new();
    for (name, text) in pages() {
        let path = root.join(DIR).join(name);
        match std::fs::read_to_string(&path) {
            Ok(committed) if committed == text => {}
            Ok(committed) => {
                let line = committed
                    .lines()
                    .zip(text.lines())
                    .position(|(a, b)| a != b)
                    .unwrap_or(committed.lines().count().min(text.lines().count()));
                stale.push(format!("{DIR}/{name} differs from line {}", line + 1));
            }
            Err(e) => stale.push(format!("{DIR}/{name}: {e}")),
        }
    }
    assert!(
        stale.is_empty(),
        "the guide's reference pages are out of date with the code:\n  {}\nregenerate them \
         with `{REGENERATE}` (from the repository's root) and commit the result",
        stale.join("\n  ")
    );
}

#[test]
fn the_reference_names_every_visible_subcommand_and_every_key() {
    let pages = pages();
    let page = |n: &str| &pages.iter().find(|(name, _)| *name == n).unwrap().1;
    let cli = page("command-line.md");
    for sub in [
        "sim", "ports", "backup", "restore", "flash", "check", "gateway", "config",
    ] {
        assert!(cli.contains(&format!("## vpx-efis {sub}\n")), "{sub}");
    }
    assert!(
        !cli.contains("## vpx-efis reference"),
        "the generator itself is hidden"
    );
    assert!(cli.contains("`--port <PATH|tcp://HOST:PORT>`"), "{cli}");
    let keys = page("keys.md");
    for key in ["`q`", "`Ctrl-C`", "`r`", "`Y`", "`p`", "`P`"] {
        assert!(keys.contains(key), "{key}");
    }
    let faults = page("fault-codes.md");
    assert!(faults.contains("## OVER_CURRENT\n\nCode `0x08`. Device over-current."));
}

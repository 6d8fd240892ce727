//! What a test finds in a folder: the names the program wrote there, or the source
//! files of a tree.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The names in `dir`, sorted; a folder that cannot be read fails the test, named.
pub fn names_in(dir: &Path) -> Vec<String> {
    let read = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let names: BTreeSet<String> = read
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.into_iter().collect()
}

/// The files below `dir` whose names end in `.ext`, at any depth but in no build
/// output (a folder named `target`), sorted by path; a folder that cannot be read
/// fails the test, named.
pub fn below(dir: &Path, ext: &str) -> Vec<PathBuf> {
    fn walk(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
        let read = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        for entry in read {
            let path = entry
                .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
                .path();
            if path.is_dir() {
                if !path.ends_with("target") {
                    walk(&path, ext, out);
                }
            } else if path.extension().is_some_and(|e| e == ext) {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, ext, &mut out);
    out.sort();
    out
}

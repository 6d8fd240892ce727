//! What a test finds in a folder the program wrote to.

use std::collections::BTreeSet;
use std::path::Path;

/// The names in `dir`, sorted; a folder that cannot be read fails the test, named.
pub fn names_in(dir: &Path) -> Vec<String> {
    let read = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let names: BTreeSet<String> = read
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.into_iter().collect()
}

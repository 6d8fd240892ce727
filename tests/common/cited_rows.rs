//! A table-driven test cited with the row it holds: `` `file.rs::test` (row "X") `` or
//! `` (rows "X" and "Y") ``. A renamed or removed row must not leave a document
//! pointing at nothing, so each cited row's quoted name must stand in its file.

use std::path::Path;

/// Each `(file, row)` a document cites, in order.
pub fn cited(doc: &str) -> Vec<(String, String)> {
    let mut found = Vec::new();
    let mut rest = doc;
    while let Some(at) = rest.find(".rs::") {
        let before = &rest[..at];
        let file_start = before.rfind('`').map_or(0, |i| i + 1);
        let file = format!("{}.rs", &before[file_start..]);
        rest = &rest[at..];
        let Some(close) = rest.find('`') else { break };
        rest = &rest[close + 1..];
        let Some(cite) = rest
            .strip_prefix(" (row ")
            .or_else(|| rest.strip_prefix(" (rows "))
        else {
            continue;
        };
        let Some(end) = cite.find(')') else { break };
        for row in cite[..end].split(" and ") {
            found.push((file.clone(), row.trim_matches('"').to_string()));
        }
    }
    found
}

/// The cited rows whose name does not stand, quoted, in their file.
pub fn missing(root: &Path, doc: &str) -> Vec<String> {
    cited(doc)
        .into_iter()
        .filter(|(file, row)| {
            std::fs::read_to_string(root.join(file))
                .map_or(true, |text| !text.contains(&format!("\"{row}\"")))
        })
        .map(|(file, row)| format!("{file}: no row \"{row}\""))
        .collect()
}

//! The installation check's report, read back as a builder reads it.

/// The Interrupted section of `md`, once the report has said at its top and at the
/// section's that the check stopped for `cause`.
pub fn interrupted<'a>(md: &'a str, cause: &str) -> &'a str {
    let result = format!("**Result: INCOMPLETE.** The check was interrupted ({cause})");
    assert!(md.contains(&result), "no {result:?} in\n{md}");
    let after = md
        .split("## Interrupted\n\n")
        .nth(1)
        .unwrap_or_else(|| panic!("no Interrupted section in\n{md}"));
    let stopped = format!("The check stopped: {cause}.\n");
    assert!(
        after.starts_with(&stopped),
        "no {stopped:?} first in\n{after}"
    );
    after
}

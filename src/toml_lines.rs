//! TOML a person edits by hand (the config file, the load file): every value read
//! with where it stands, so a problem is named by the line to go to, and serde's
//! refusals taken apart so each file can say them in its own words.

use serde::de::DeserializeOwned;

/// A value of the file and where it stands in the text.
pub type Value = toml::Spanned<toml::Value>;

/// Why the text is not the file's shape, as serde said it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    /// The line it is on, when serde knows.
    pub line: Option<usize>,
    /// serde's own words.
    pub message: String,
    /// The key the file does not have, when that is why.
    pub unknown_key: Option<String>,
}

/// Reads `text` as `T` (a struct of [`Value`]s, `deny_unknown_fields`).
pub fn parse<T: DeserializeOwned>(text: &str) -> Result<T, Refusal> {
    toml::from_str(text).map_err(|e: toml::de::Error| {
        let message = e.message().trim().to_string();
        let unknown_key = message
            .starts_with("unknown field")
            .then(|| message.split('`').nth(1).unwrap_or("?").to_string());
        Refusal {
            line: e.span().map(|s| line_of(text, s.start)),
            message,
            unknown_key,
        }
    })
}

/// The 1-based line of a byte offset.
pub fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The line `v` stands on.
pub fn line<T>(text: &str, v: &toml::Spanned<T>) -> usize {
    line_of(text, v.span().start)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct File {
        a: Option<Value>,
        b: Option<Value>,
    }

    #[test]
    fn values_keep_their_lines_and_refusals_name_the_line_and_key() {
        let text = "# top\na = 1\n\nb = \"x\"\n";
        let f: File = parse(text).unwrap();
        assert_eq!(line(text, f.a.as_ref().unwrap()), 2);
        assert_eq!(line(text, f.b.as_ref().unwrap()), 4);
        assert_eq!(line_of(text, 0), 1);
        assert_eq!(line_of(text, 10_000), 5, "past the end: the last line");

        let r = parse::<File>("a = 1\nc = 2\n").unwrap_err();
        assert_eq!(r.line, Some(2));
        assert_eq!(r.unknown_key.as_deref(), Some("c"));
        let r = parse::<File>("a = \n").unwrap_err();
        assert_eq!(r.line, Some(1));
        assert_eq!(r.unknown_key, None);
        assert!(!r.message.is_empty());
    }
}

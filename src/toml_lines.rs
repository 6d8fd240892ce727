//! Files a person edits by hand (the config file, the load file, a backup): every
//! value read with where it stands, and one way to say what is wrong with them. A
//! reader lists every problem at once, each with its line and its field, so a person
//! fixes them all in one go, not one a run; only text that is not TOML at all stops
//! at its first mistake (the parser cannot go on).

use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;

use serde::de::DeserializeOwned;

/// A value of the file and where it stands in the text.
pub type Value = toml::Spanned<toml::Value>;

/// One thing wrong with a file a person edits: where to go, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// The 1-based line, when the problem stands on one (not for a key the file
    /// lacks altogether).
    pub line: Option<usize>,
    /// The field as the file spells it (`baud`, `[circuit.5A-7] taxi`,
    /// `devices.5A-3.breaker_amps`); empty for the text as a whole.
    pub field: String,
    pub message: String,
}

impl Problem {
    pub fn new(line: Option<usize>, field: impl Into<String>, message: impl Into<String>) -> Self {
        Problem {
            line,
            field: field.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(l) = self.line {
            write!(f, "line {l}: ")?;
        }
        if !self.field.is_empty() {
            write!(f, "{}: ", self.field)?;
        }
        f.write_str(&self.message)
    }
}

/// A file a person edits that cannot be used: which one, and every problem in it,
/// one a line, each named by the file's path (`config file …, line 3: baud: …`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileError {
    /// What the file is to the person: "config file", "load file", "backup file".
    pub kind: &'static str,
    pub path: PathBuf,
    /// At least one.
    pub problems: Vec<Problem>,
}

impl FileError {
    /// A file that could not be read at all.
    pub fn unreadable(kind: &'static str, path: PathBuf, error: &std::io::Error) -> Self {
        FileError {
            kind,
            path,
            problems: vec![Problem::new(None, "", format!("cannot read it: {error}"))],
        }
    }
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, p) in self.problems.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            let sep = if p.line.is_some() || !p.field.is_empty() {
                ", "
            } else {
                ": "
            };
            write!(f, "{} {}{sep}{p}", self.kind, self.path.display())?;
        }
        Ok(())
    }
}

impl std::error::Error for FileError {}

/// serde's or the parser's refusal, as one problem on its line.
fn refused(text: &str, e: &toml::de::Error, words: &str) -> Problem {
    Problem::new(
        e.span().map(|s| line_of(text, s.start)),
        "",
        format!("{words}{}", e.message().trim()),
    )
}

/// Reads `text` as a table, or says where it is not TOML.
pub fn table(text: &str) -> Result<toml::Table, Problem> {
    text.parse::<toml::Table>()
        .map_err(|e| refused(text, &e, "not valid TOML: "))
}

/// Reads `text` as `T` (a struct of [`Value`]s). A text that is not TOML, or not of
/// `T`'s shape (a value where a section belongs), is one problem with its line.
pub fn parse<T: DeserializeOwned>(text: &str) -> Result<T, Problem> {
    table(text)?;
    toml::from_str(text).map_err(|e: toml::de::Error| refused(text, &e, ""))
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

/// Every key of a text, by its dotted path (`devices.5A-3.breaker_amps`), with the
/// line it is written on: to name the line of a problem found by path, and the keys
/// a reader does not know.
#[derive(Debug, Clone, Default)]
pub struct Keys(BTreeMap<Vec<String>, usize>);

impl Keys {
    /// The keys of `text`; none if it is not TOML ([`parse`] or [`table`] says why).
    pub fn of(text: &str) -> Keys {
        fn walk(text: &str, at: &[String], t: &toml::de::DeTable, out: &mut Keys) {
            for (k, v) in t {
                let mut path = at.to_vec();
                path.push(k.get_ref().to_string());
                if let toml::de::DeValue::Table(inner) = v.get_ref() {
                    walk(text, &path, inner, out);
                }
                out.0.insert(path, line_of(text, k.span().start));
            }
        }
        let mut out = Keys::default();
        if let Ok(root) = toml::de::DeTable::parse(text) {
            walk(text, &[], root.get_ref(), &mut out);
        }
        out
    }

    /// The line of `path` (dotted), or of the nearest table above it that the text
    /// has (a missing key is found in its table).
    pub fn line(&self, path: &str) -> Option<usize> {
        let mut parts: Vec<String> = path.split('.').map(str::to_string).collect();
        while !parts.is_empty() {
            if let Some(&l) = self.0.get(&parts) {
                return Some(l);
            }
            parts.pop();
        }
        None
    }

    /// Every key path `known` refuses, with its line, outermost first.
    pub fn unknown(&self, known: impl Fn(&[String]) -> bool) -> Vec<(Vec<String>, usize)> {
        self.0
            .iter()
            .filter(|(p, _)| !known(p))
            // A key under one already refused is not another problem.
            .fold(Vec::new(), |mut out: Vec<(Vec<String>, usize)>, (p, &l)| {
                if !out.iter().any(|(q, _)| p.starts_with(q)) {
                    out.push((p.clone(), l));
                }
                out
            })
    }
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
    fn values_keep_their_lines_and_refusals_name_the_line() {
        let text = "# top\na = 1\n\nb = \"x\"\n";
        let f: File = parse(text).unwrap();
        assert_eq!(line(text, f.a.as_ref().unwrap()), 2);
        assert_eq!(line(text, f.b.as_ref().unwrap()), 4);
        assert_eq!(line_of(text, 0), 1);
        assert_eq!(line_of(text, 10_000), 5, "past the end: the last line");

        let r = parse::<File>("a = 1\nc = 2\n").unwrap_err();
        assert_eq!(r.line, Some(2));
        assert!(r.message.contains("unknown field `c`"), "{r}");
        let r = parse::<File>("a = \n").unwrap_err();
        assert_eq!(r.line, Some(1));
        assert!(r.message.starts_with("not valid TOML: "), "{r}");
        let r = table("a = 1\n[b\n").unwrap_err();
        assert_eq!((r.line, r.field.as_str()), (Some(2), ""));
    }

    #[test]
    fn keys_have_their_lines_and_a_missing_key_its_tables() {
        let text = "top = 1\n\n[dev.\"5A-3\"]\nbreaker = 5\n[dev.\"5A-4\"]\nname = \"x\"\n";
        let k = Keys::of(text);
        assert_eq!(k.line("top"), Some(1));
        assert_eq!(k.line("dev.5A-3.breaker"), Some(4));
        assert_eq!(k.line("dev.5A-4.breaker"), Some(5), "missing: its table");
        assert_eq!(k.line("nothing.here"), None);
        let unknown = k.unknown(|p| p[0] == "top" || (p[0] == "dev" && p.len() < 3));
        assert_eq!(
            unknown,
            vec![
                (vec!["dev".into(), "5A-3".into(), "breaker".into()], 4),
                (vec!["dev".into(), "5A-4".into(), "name".into()], 6),
            ]
        );
        let under = Keys::of("x = 1\n[y]\nz = 2\n").unknown(|p| p[0] == "x");
        assert_eq!(under, vec![(vec!["y".into()], 2)], "not y.z again");
    }

    #[test]
    fn a_file_error_names_path_line_and_field_of_each_problem() {
        let e = FileError {
            kind: "load file",
            path: "loads.toml".into(),
            problems: vec![
                Problem::new(Some(3), "[circuit.5A-7] taxi", "1.5 is not on or off"),
                Problem::new(None, "alternator_amps", "missing"),
                Problem::new(Some(9), "", "not valid TOML: x"),
            ],
        };
        assert_eq!(
            e.to_string(),
            "load file loads.toml, line 3: [circuit.5A-7] taxi: 1.5 is not on or off\n\
             load file loads.toml, alternator_amps: missing\n\
             load file loads.toml, line 9: not valid TOML: x"
        );
        let io = std::io::Error::from(std::io::ErrorKind::PermissionDenied);
        let e = FileError::unreadable("config file", "c.toml".into(), &io);
        assert_eq!(
            e.to_string(),
            "config file c.toml: cannot read it: permission denied"
        );
    }
}

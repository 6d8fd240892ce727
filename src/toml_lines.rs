//! Files a person edits by hand (the config file, the load file, a backup): every
//! value read with where it stands, and one way to say what is wrong with them. A
//! reader lists every problem at once, each with its line and its field, so a person
//! fixes them all in one go, not one a run; only text that is not TOML at all stops
//! at its first mistake (the parser cannot go on).

use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::PathBuf;

use serde::de::DeserializeOwned;
use toml::de::{DeArray, DeTable, DeValue};

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

/// Reads `text` as `T`, listing every problem at once. Where serde refuses a key, or
/// an entry of an array of tables (`[[event]]`), that part is set aside with its
/// problem and the rest is read again, so one mistake hides no other; a table that
/// then lacks a key it needs, because that key was set aside, is set aside too,
/// without a second problem. Gives `T` as read from what remains (`None` if nothing
/// does: text that is not TOML), the keys of what remains with their lines (for the
/// problems a reader finds in the values; an entry of an array is a key of its
/// number, from 0), and the problems in line order.
pub fn read_all<T: DeserializeOwned>(text: &str) -> (Option<T>, Keys, Vec<Problem>) {
    let mut root = match DeTable::parse(text) {
        Ok(root) => root,
        Err(e) => {
            return (
                None,
                Keys::default(),
                vec![refused(text, &e, "not valid TOML: ")],
            );
        }
    };
    let mut problems = Vec::new();
    let mut emptied: Vec<Vec<String>> = Vec::new();
    loop {
        let e = match T::deserialize(toml::de::Deserializer::from(root.clone())) {
            Ok(t) => {
                problems.sort_by_key(|p: &Problem| p.line);
                return (Some(t), Keys::of_table(text, root.get_ref()), problems);
            }
            Err(e) => e,
        };
        let keys = Keys::of_table(text, root.get_ref());
        let culprit = e.span().and_then(|s| culprit(root.get_ref(), &s));
        match culprit {
            Some(path) if set_aside(root.get_mut(), &path) => {
                if !emptied.contains(&path) {
                    problems.push(keys.problem(&path.join("."), e.message().trim()));
                }
                emptied.push(path[..path.len() - 1].to_vec());
            }
            _ => {
                problems.push(refused(text, &e, ""));
                problems.sort_by_key(|p: &Problem| p.line);
                return (None, keys, problems);
            }
        }
    }
}

/// The path of the part of `t` that an error at `span` is about: the deepest key or
/// entry that holds its start.
fn culprit(t: &DeTable<'_>, span: &Range<usize>) -> Option<Vec<String>> {
    let mut deepest: Option<Vec<String>> = None;
    parts(t, &mut Vec::new(), &mut |path, spans| {
        let holds = |s: &Range<usize>| s.start <= span.start && span.start < s.end;
        if spans.iter().any(holds) && deepest.as_ref().is_none_or(|d| path.len() > d.len()) {
            deepest = Some(path.to_vec());
        }
    });
    deepest
}

/// Calls `each` with the path and spans (key and value) of every key of `t` and every
/// table entry of an array, outermost first.
fn parts(t: &DeTable<'_>, at: &mut Vec<String>, each: &mut impl FnMut(&[String], &[Range<usize>])) {
    for (k, v) in t {
        at.push(k.get_ref().to_string());
        each(at, &[k.span(), v.span()]);
        match v.get_ref() {
            DeValue::Table(inner) => parts(inner, at, each),
            DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    if let DeValue::Table(inner) = item.get_ref() {
                        at.push(i.to_string());
                        each(at, &[item.span()]);
                        parts(inner, at, each);
                        at.pop();
                    }
                }
            }
            _ => {}
        }
        at.pop();
    }
}

/// Takes the key or array entry at `path` out of `t`; false if it has none there.
fn set_aside(t: &mut DeTable<'_>, path: &[String]) -> bool {
    let [first, rest @ ..] = path else {
        return false;
    };
    if rest.is_empty() {
        let key = t.keys().find(|k| k.get_ref() == first).cloned();
        return key.is_some_and(|k| t.remove(&k).is_some());
    }
    let value = t.iter_mut().find(|(k, _)| k.get_ref() == first);
    match (value.map(|(_, v)| v.get_mut()), rest[0].parse::<usize>()) {
        (Some(DeValue::Table(inner)), _) => set_aside(inner, rest),
        (Some(DeValue::Array(items)), Ok(n)) if n < items.len() => {
            if rest.len() > 1 {
                let DeValue::Table(inner) = items.as_mut()[n].get_mut() else {
                    return false;
                };
                return set_aside(inner, &rest[1..]);
            }
            let mut kept = DeArray::new();
            for (_, item) in items.iter().enumerate().filter(|(i, _)| *i != n) {
                kept.push(item.clone());
            }
            *items = kept;
            true
        }
        _ => false,
    }
}

/// What a value is, in a person's words, for the problem that says what was expected.
pub fn kind(v: &toml::Value) -> &'static str {
    match v {
        toml::Value::String(_) => "text",
        toml::Value::Integer(_) => "a whole number",
        toml::Value::Float(_) => "a decimal number",
        toml::Value::Boolean(_) => "true/false",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "a list",
        toml::Value::Table(_) => "a section",
    }
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
        match DeTable::parse(text) {
            Ok(root) => Keys::of_table(text, root.get_ref()),
            Err(_) => Keys::default(),
        }
    }

    /// The keys of `text` as read into `root`.
    fn of_table(text: &str, root: &DeTable<'_>) -> Keys {
        let mut out = Keys::default();
        parts(root, &mut Vec::new(), &mut |path, spans| {
            let first = spans.first().map_or(0, |s| s.start);
            out.0.insert(path.to_vec(), line_of(text, first));
        });
        out
    }

    /// A problem with the part at `path` (dotted, as [`Keys::line`]), named by its keys
    /// (an array entry's number left out: its line tells which).
    pub fn problem(&self, path: &str, message: impl Into<String>) -> Problem {
        let field: Vec<&str> = path
            .split('.')
            .filter(|k| k.parse::<usize>().is_err())
            .collect();
        Problem::new(self.line(path), field.join("."), message)
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
    fn read_all_sets_aside_what_is_refused_and_lists_every_problem() {
        #[derive(Debug, PartialEq, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Doc {
            top: Option<u8>,
            #[serde(default)]
            part: Vec<Part>,
        }
        #[derive(Debug, PartialEq, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Part {
            id: u8,
            #[serde(default)]
            size: u8,
        }
        let text = "top = \"x\"\n\
                    [[part]]\nid = 1\nsize = 300\nsiez = 2\n\
                    [[part]]\nid = \"two\"\n\
                    [[part]]\nid = 3\n";
        let (doc, keys, problems) = read_all::<Doc>(text);
        let got: Vec<(Option<usize>, &str)> = problems
            .iter()
            .map(|p| (p.line, p.field.as_str()))
            .collect();
        // A part whose needed `id` is refused is set aside once, not again as missing.
        assert_eq!(
            got,
            [
                (Some(1), "top"),
                (Some(4), "part.size"),
                (Some(5), "part.siez"),
                (Some(7), "part.id"),
            ],
            "{problems:?}"
        );
        assert!(
            problems[2].message.contains("unknown field `siez`"),
            "{problems:?}"
        );
        let parts = vec![Part { id: 1, size: 0 }, Part { id: 3, size: 0 }];
        assert_eq!(
            doc,
            Some(Doc {
                top: None,
                part: parts
            })
        );
        assert_eq!(
            keys.line("part.1.id"),
            Some(9),
            "what remains, numbered anew"
        );
        let (doc, _, problems) = read_all::<Doc>("top = [\n");
        assert_eq!(
            (doc, problems.len()),
            (None, 1),
            "not TOML: its first mistake"
        );
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

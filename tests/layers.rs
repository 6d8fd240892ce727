//! The layers sketched in `src/lib.rs`, held by a test: the program's top-level modules
//! import only downward, and no two of them import each other, directly or round a
//! circle. It reads `src/` as text (every `crate::x` path, `use crate::{a, b}` groups
//! included, comments left out) and names the file and line of each import it refuses.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

#[path = "common/files.rs"]
#[allow(dead_code)]
mod files;

/// The layers, lowest first. A module may import its own layer's modules and those
/// below it; never one above. The two codecs are crates of their own
/// (`crates/vpx-protocol`, `crates/xfsp`), below everything here.
const LAYERS: &[(&str, &[&str])] = &[
    (
        "leaves: the codecs' re-exports and the small pure helpers",
        &[
            "protocol",
            "program",
            "places",
            "utc",
            "files",
            "toml_lines",
            "platform",
            "transient",
            "staleness",
            "exchange",
        ],
    ),
    (
        "bytes in and out, and the record of them",
        &["link", "traffic", "audit", "logbook"],
    ),
    ("what we know, and the virtual unit", &["model", "sim"]),
    ("intent into commands under the safety rules", &["control"]),
    (
        "flows and maintenance",
        &[
            "check", "setup", "loads", "backup", "flash", "xfsp", "settings",
        ],
    ),
    (
        "the walk-around remote's server: the model's state out, commands to the page",
        &["remote"],
    ),
    ("drawing", &["ui"]),
    ("wiring", &["app"]),
    ("one file per subcommand", &["cmd"]),
    ("the command line", &["cli"]),
];

/// One import of another top-level module: where it is, and what it names.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Import {
    from: String,
    to: String,
    file: String,
    line: usize,
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS
        .iter()
        .position(|(_, modules)| modules.contains(&module))
}

/// The top-level module a file under `src/` belongs to (`app.rs` and `app/…` are `app`).
fn top_module(rel: &Path) -> Option<String> {
    let first = rel.components().next()?.as_os_str().to_str()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    (name != "lib" && name != "main").then(|| name.to_owned())
}

/// Source text with comments blanked (kept the same length, so offsets give lines).
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let (mut in_line, mut in_block, mut in_str) = (false, 0usize, false);
    while let Some(c) = chars.next() {
        if in_line {
            if c == '\n' {
                in_line = false;
                out.push('\n');
            } else {
                out.push(' ');
            }
        } else if in_block > 0 {
            if c == '*' && chars.peek() == Some(&'/') {
                chars.next();
                in_block -= 1;
                out.push_str("  ");
            } else {
                out.push(if c == '\n' { '\n' } else { ' ' });
            }
        } else if in_str {
            if c == '\\' {
                out.push(' ');
                if let Some(n) = chars.next() {
                    out.push(if n == '\n' { '\n' } else { ' ' });
                }
            } else {
                if c == '"' {
                    in_str = false;
                }
                out.push(if c == '\n' { '\n' } else { ' ' });
            }
        } else if c == '/' && chars.peek() == Some(&'/') {
            in_line = true;
            out.push(' ');
        } else if c == '/' && chars.peek() == Some(&'*') {
            chars.next();
            in_block += 1;
            out.push_str("  ");
        } else if c == '"' {
            in_str = true;
            out.push(' ');
        } else {
            out.push(c);
        }
    }
    out
}

/// The top-level modules a text names through `crate::`, with the byte offset of each.
fn crate_paths(code: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let bytes = code.as_bytes();
    let mut at = 0;
    while let Some(i) = code[at..].find("crate::") {
        let start = at + i;
        at = start + "crate::".len();
        // `$crate::` and `foo_crate::` are not ours.
        if start > 0 {
            let before = bytes[start - 1];
            if before == b'$' || before.is_ascii_alphanumeric() || before == b'_' {
                continue;
            }
        }
        if bytes.get(at) == Some(&b'{') {
            // A group: the first name of each of its items (`a::b`, `c`, `d::{e, f}`).
            let mut depth = 0usize;
            let mut item_start = at + 1;
            for (j, &b) in bytes.iter().enumerate().skip(at) {
                match b {
                    b'{' => depth += 1,
                    b'}' | b',' if depth == 1 => {
                        let item = &code[item_start..j];
                        let lead = item.len() - item.trim_start().len();
                        let name: String = item
                            .trim_start()
                            .chars()
                            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                            .collect();
                        if !name.is_empty() {
                            found.push((item_start + lead, name));
                        }
                        item_start = j + 1;
                        if b == b'}' {
                            break;
                        }
                    }
                    b'}' => depth -= 1,
                    _ => {}
                }
            }
        } else {
            let name: String = code[at..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            found.push((start, name));
        }
    }
    found
}

/// The program's sources: `src/`.
fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The Rust files below `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    files::below(dir, "rs")
}

/// Every import of one top-level module by another, under `src`.
fn imports(src: &Path) -> Vec<Import> {
    let files = rust_files(src);
    let mut out = Vec::new();
    for path in files {
        let rel = path.strip_prefix(src).expect("under src");
        let Some(from) = top_module(rel) else {
            continue;
        };
        let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let code = without_comments(&text);
        for (offset, to) in crate_paths(&code) {
            if to == from || layer_of(&to).is_none() {
                continue;
            }
            let line = code[..offset].matches('\n').count() + 1;
            out.push(Import {
                from: from.clone(),
                to,
                // `/` on every OS, so a report reads the same on Windows.
                file: std::iter::once("src".to_owned())
                    .chain(rel.iter().map(|c| c.to_string_lossy().into_owned()))
                    .collect::<Vec<_>>()
                    .join("/"),
                line,
            });
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The imports that break the rule: upward, or round a circle between modules of one layer.
fn breaches(imports: &[Import]) -> BTreeMap<String, Vec<Import>> {
    let mut graph: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for i in imports {
        graph.entry(&i.from).or_default().insert(&i.to);
    }
    let reaches = |a: &str, b: &str| -> bool {
        let mut seen = BTreeSet::new();
        let mut todo = vec![a];
        while let Some(m) = todo.pop() {
            if m == b {
                return true;
            }
            if seen.insert(m) {
                todo.extend(graph.get(m).into_iter().flatten().copied());
            }
        }
        false
    };
    let mut out: BTreeMap<String, Vec<Import>> = BTreeMap::new();
    for i in imports {
        let (Some(lf), Some(lt)) = (layer_of(&i.from), layer_of(&i.to)) else {
            continue;
        };
        // A circle through another layer has an upward import in it, named as such.
        if lt > lf || (lt == lf && reaches(&i.to, &i.from)) {
            out.entry(format!("{} -> {}", i.from, i.to))
                .or_default()
                .push(i.clone());
        }
    }
    out
}

fn report(found: &BTreeMap<String, Vec<Import>>, keys: &[&String]) -> String {
    let mut s = String::new();
    for k in keys {
        for i in &found[*k] {
            let why = if layer_of(&i.to) > layer_of(&i.from) {
                "imports a higher layer"
            } else {
                "closes a circle"
            };
            s.push_str(&format!("  {}:{}: {} ({why})\n", i.file, i.line, k));
        }
    }
    s
}

#[test]
fn every_top_level_module_has_a_layer() {
    let src = src();
    let mut missing = Vec::new();
    for e in fs::read_dir(&src).expect("src") {
        let p = e.expect("entry").path();
        if let Some(m) = top_module(p.strip_prefix(&src).expect("under src"))
            && layer_of(&m).is_none()
        {
            missing.push(m);
        }
    }
    assert!(
        missing.is_empty(),
        "give these modules a layer in LAYERS: {missing:?}"
    );
}

/// `lib.rs`'s data-flow sketch names every module the crate has,
/// so a new module cannot be added without saying where it stands.
#[test]
fn the_sketch_in_lib_rs_names_every_module() {
    let lib = fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs"))
        .expect("src/lib.rs");
    let sketch: String = lib
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join(" ");
    let modules: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod ")?.strip_suffix(';'))
        .collect();
    assert!(
        modules.len() > 10,
        "read the modules of lib.rs: {modules:?}"
    );
    let unnamed: Vec<_> = modules
        .iter()
        .filter(|m| !sketch.contains(&format!("[`{m}`]")))
        .collect();
    assert!(
        unnamed.is_empty(),
        "lib.rs's sketch does not name these modules: {unnamed:?}"
    );
}

#[test]
fn the_layers_hold() {
    let src = src();
    let found = breaches(&imports(&src));
    let all: Vec<&String> = found.keys().collect();
    assert!(
        all.is_empty(),
        "imports against the layers (see LAYERS in tests/layers.rs):\n{}",
        report(&found, &all)
    );
}

#[test]
fn a_planted_upward_import_and_a_circle_are_named_with_file_and_line() {
    let dir = tempfile::tempdir().expect("temp dir");
    let src = dir.path().join("src");
    fs::create_dir_all(src.join("model")).expect("mkdir");
    fs::write(
        src.join("model/hold.rs"),
        "//! crate::ui in a comment is no import\nuse std::fmt;\nuse crate::{\n    protocol::Message,\n    ui::palette::Palette,\n};\n",
    )
    .expect("write");
    fs::write(src.join("link.rs"), "use crate::traffic::Log;\n").expect("write");
    fs::write(src.join("traffic.rs"), "fn f() { crate::link::open(); }\n").expect("write");
    fs::write(
        src.join("ui.rs"),
        "use crate::model::Model;\nconst S: &str = \"crate::app\";\n",
    )
    .expect("write");
    let found = breaches(&imports(&src));
    let keys: Vec<&str> = found.keys().map(String::as_str).collect();
    assert_eq!(keys, ["link -> traffic", "model -> ui", "traffic -> link"]);
    assert_eq!(
        found["model -> ui"],
        [Import {
            from: "model".into(),
            to: "ui".into(),
            file: "src/model/hold.rs".into(),
            line: 5
        }]
    );
    assert_eq!(found["traffic -> link"][0].line, 1);
}

/// Every Rust source directory of the workspace: the page's and each codec crate's.
fn source_roots() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut roots = vec![root.join("src")];
    for krate in fs::read_dir(root.join("crates")).expect("crates/") {
        let src = krate.expect("crates entry").path().join("src");
        if src.is_dir() {
            roots.push(src);
        }
    }
    roots
}

/// One module layout: a module with children is `foo/mod.rs`,
/// never `foo.rs` beside `foo/`, so that a reader finds a module in one place.
#[test]
fn modules_with_children_live_in_mod_rs() {
    let files: Vec<PathBuf> = source_roots().iter().flat_map(|r| rust_files(r)).collect();
    let beside: Vec<String> = files
        .iter()
        .filter(|f| f.with_extension("").is_dir())
        .map(|f| f.display().to_string())
        .collect();
    assert!(
        beside.is_empty(),
        "move each to its folder's mod.rs: {beside:?}"
    );
}

/// No file holds more than this many lines of code before its tests.
const MAX_CODE_LINES: usize = 1000;

/// Lines of a file before its inline `#[cfg(test)] mod … {` block, blank lines and
/// comments left out. A `#[cfg(test)] mod tests;` that names a file of its own is one
/// line like any other, so that declaring it early hides no code.
fn code_lines(text: &str) -> usize {
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    let end = (0..lines.len())
        .find(|&i| {
            lines[i] == "#[cfg(test)]"
                && lines[i + 1..]
                    .iter()
                    .find(|l| !l.is_empty())
                    .is_some_and(|l| l.starts_with("mod ") && l.ends_with('{'))
        })
        .unwrap_or(lines.len());
    lines[..end]
        .iter()
        .filter(|l| !l.is_empty() && !l.starts_with("//"))
        .count()
}

#[test]
fn no_file_is_over_a_thousand_lines_of_code() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files: Vec<PathBuf> = source_roots().iter().flat_map(|r| rust_files(r)).collect();
    let mut long = Vec::new();
    for file in files {
        let rel = file.strip_prefix(root).expect("under the root");
        let rel = rel.to_string_lossy().replace('\\', "/");
        // A test module kept in a file of its own is all tests.
        if rel.contains("/tests/") || rel.ends_with("/tests.rs") {
            continue;
        }
        let n = code_lines(&fs::read_to_string(&file).expect("read"));
        if n > MAX_CODE_LINES {
            long.push((rel, n));
        }
    }
    assert!(long.is_empty(), "split these: {long:?}");
}

#[test]
fn code_lines_skip_comments_blanks_and_tests() {
    let text = "// a\nfn a() {}\n\n/// doc\nfn b() {}\n#[cfg(test)]\nmod tests {\n fn c() {}\n}\n";
    assert_eq!(code_lines(text), 2);
    // A test module in a file of its own, declared first, hides nothing after it.
    let early = "#[cfg(test)]\nmod tests;\nfn a() {}\nfn b() {}\n";
    assert_eq!(code_lines(early), 4);
}

/// What a flow must not do itself: read a clock, touch a file,
/// read stdin or know the terminal. The app does these and hands the results in.
const FLOW_IO: &[&str] = &[
    "Instant::now",
    "SystemTime::now",
    "std::fs",
    "fs::",
    "File::",
    "stdin",
    "crossterm",
    "ratatui",
    "std::env",
];

/// A file's lines before its first `#[cfg(test)]`, numbered from 1.
fn lines_before_tests(code: &str) -> impl Iterator<Item = (usize, &str)> {
    let end = code
        .lines()
        .position(|l| l.trim() == "#[cfg(test)]")
        .unwrap_or(usize::MAX);
    code.lines()
        .enumerate()
        .take_while(move |(i, _)| *i < end)
        .map(|(i, l)| (i + 1, l))
}

/// The lines of a flow file's code that do I/O, outside its tests.
fn flow_io_lines(code: &str) -> Vec<(usize, &'static str)> {
    lines_before_tests(code)
        .flat_map(|(i, l)| {
            FLOW_IO
                .iter()
                .filter(move |w| l.contains(*w))
                .map(move |w| (i, *w))
        })
        .collect()
}

#[test]
fn the_flows_read_no_clock_file_stdin_or_terminal() {
    let src = src();
    let mut found = Vec::new();
    for flow in ["check", "setup"] {
        for file in rust_files(&src.join(flow)) {
            let rel = file.strip_prefix(&src).expect("under src");
            if rel.components().any(|c| c.as_os_str() == "tests") {
                continue;
            }
            let code = without_comments(&fs::read_to_string(&file).expect("read"));
            for (line, what) in flow_io_lines(&code) {
                found.push(format!("src/{}:{line}: {what}", rel.display()));
            }
        }
    }
    assert!(found.is_empty(), "a flow does I/O itself: {found:#?}");
}

#[test]
fn flow_io_is_found_in_code_and_not_in_its_tests() {
    let code = "fn a() {\n    let t = Instant::now();\n}\n#[cfg(test)]\nmod tests {\n    fn b() { std::fs::read(\"x\"); }\n}\n";
    assert_eq!(flow_io_lines(code), vec![(2, "Instant::now")]);
}

/// `ui` draws for the page, and the page alone uses it: a subcommand or the command
/// line that needs a word of it (a theme's name) takes it from where `ui` does.
#[test]
fn nothing_but_app_imports_ui() {
    let src = src();
    let wrong: Vec<String> = imports(&src)
        .into_iter()
        .filter(|i| i.to == "ui" && i.from != "ui" && i.from != "app")
        .map(|i| format!("{}:{}: {} -> ui", i.file, i.line, i.from))
        .collect();
    assert!(wrong.is_empty(), "only app draws: {wrong:#?}");
}

/// Where a way to the unit's wire may be held: the link itself, the
/// virtual unit, `control` (which decides every motor's stop), and the app's stop gate,
/// which every command and the panic's emergency stop go through, in order, audited.
const WIRE_HOLDERS: &[&str] = &["link/", "sim/", "control/", "app/stop_gate.rs"];

/// Lines of a file's code, before its tests, that could write to a link around the
/// stop gate: a `LinkHandle` named, or a link's handle taken for anything but the gate.
fn around_the_gate(code: &str) -> Vec<usize> {
    let code = without_comments(code);
    lines_before_tests(&code)
        .filter(|(_, l)| {
            l.contains("LinkHandle") || (l.contains(".handle()") && !l.contains("StopGate::"))
        })
        .map(|(i, _)| i)
        .collect()
}

/// Outside the link, the sim, `control` and the stop gate, no code holds a way to the
/// wire: a stop (or any packet) written there would pass the gate that keeps a move
/// from following the panic's stop, and would miss the audit log.
#[test]
fn nothing_writes_to_a_link_around_the_stop_gate() {
    let src = src();
    let mut found = Vec::new();
    for file in rust_files(&src) {
        let rel = file.strip_prefix(&src).expect("under src");
        let rel = rel.to_string_lossy().replace('\\', "/");
        if WIRE_HOLDERS.iter().any(|h| rel.starts_with(h)) || rel.contains("/tests/") {
            continue;
        }
        for line in around_the_gate(&fs::read_to_string(&file).expect("read")) {
            found.push(format!("src/{rel}:{line}"));
        }
    }
    assert!(
        found.is_empty(),
        "a way to the wire around the stop gate (send through the app's StopGate): {found:#?}"
    );
}

/// The headless check's old panic hook, planted: found, line by line; the gate's own
/// use of the handle and test code are not.
#[test]
fn a_stop_written_around_the_gate_is_found() {
    let planted = "\
fn arm(app: &App) {
    let handle = app.link.handle();
    set_emergency_stop(move || {
        for p in MotorStreamer::emergency_stop_packets() {
            let _ = handle.send(p);
        }
    });
}
fn hold(h: crate::link::LinkHandle) {}
fn gate(link: &Link) -> StopGate { StopGate::new(link.handle()) }
// a comment about link.handle() is no code
#[cfg(test)]
mod tests {
    fn t(link: &Link) { let _ = link.handle().send(stop()); }
}
";
    assert_eq!(around_the_gate(planted), vec![2, 9]);
}

/// Every motor run, from every origin, goes through `control`'s one entry.
/// So outside `control` (the virtual unit and the codecs aside) no code but tests:
/// builds a TRIM_MOVE or FLAP_MOVE, holds a `MotorStreamer` (its stateless
/// `emergency_stop_packets` is for the stop gate and the panic paths), or records a
/// motor with `Against`.
const MOTOR_RUN_SIGNS: &[(&str, &str)] = &[
    ("TrimMove {", "builds a TRIM_MOVE"),
    ("FlapMove {", "builds a FLAP_MOVE"),
    ("move_packet(", "builds a TRIM_MOVE or FLAP_MOVE"),
    ("MotorStreamer::new", "holds a MotorStreamer"),
    (": MotorStreamer", "holds a MotorStreamer"),
    ("against.record(", "records with Against"),
    ("Against::record", "records with Against"),
];

/// What of [`MOTOR_RUN_SIGNS`] the code before its `#[cfg(test)]` shows, by line.
fn motor_run_lines(code: &str) -> Vec<(usize, &'static str)> {
    let code = without_comments(code);
    code.lines()
        .take_while(|l| l.trim() != "#[cfg(test)]")
        .enumerate()
        .flat_map(|(i, l)| {
            MOTOR_RUN_SIGNS
                .iter()
                .filter(move |(sign, _)| l.contains(sign))
                .map(move |(_, what)| (i + 1, *what))
        })
        .collect()
}

#[test]
fn motor_runs_are_assembled_only_in_control() {
    let src = src();
    let mut found: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for file in rust_files(&src) {
        let rel = file.strip_prefix(&src).expect("under src");
        let top = top_module(rel).unwrap_or_default();
        if ["control", "sim", "protocol"].contains(&top.as_str())
            || rel.components().any(|c| c.as_os_str() == "tests")
        {
            continue;
        }
        let text = fs::read_to_string(&file).expect("read");
        for (line, what) in motor_run_lines(&text) {
            let key = format!("src/{}: {what}", rel.display()).replace('\\', "/");
            found.entry(key).or_default().push(line);
        }
    }
    let found: Vec<String> = found
        .iter()
        .map(|(k, lines)| format!("{k} (lines {lines:?})"))
        .collect();
    assert!(
        found.is_empty(),
        "a motor run assembled outside control: {found:#?}"
    );
}

#[test]
fn a_planted_motor_run_is_found_in_code_and_not_in_comments_strings_or_tests() {
    let code = "struct D {\n    s: MotorStreamer,\n}\n\
                // MotorStreamer::new in a comment\n\
                fn f() { log(\"TrimMove { on }\"); self.against.record(m, d); }\n\
                #[cfg(test)]\nmod tests {\n    fn t() { move_packet(0, m, d, true); }\n}\n";
    assert_eq!(
        motor_run_lines(code),
        vec![(2, "holds a MotorStreamer"), (5, "records with Against")]
    );
}

//! Writing files so that no reader ever sees half of one, and, where asked, so that
//! no file already there is ever replaced. Backups, the load file's template, the
//! check's report and the virtual unit's EEPROM all write through here; nothing else
//! in the program writes a file it must keep.
//!
//! Both ways write a temporary file in the target's own folder first (a rename or a
//! link only stays on one file system), flush it to the disk, and only then give it
//! its name. Temporary files are named `.NAME.tmp-PID-N` and removed on every error.
//!
//! A process killed between creating its temporary file and giving it its name (a
//! SIGKILL, a power cut) leaves one behind; nothing else ever removes it. So each
//! write first removes the stale ones of its own kind in its folder ([`STALE_AFTER`],
//! [`ours_and_stale`]): a hidden file of exactly this form, for the same name or one
//! of the same family (the same up to its first digit and with the same extension:
//! the dated reports `vpx-check-2026-12-01T1830Z.md`, the backups), a regular file,
//! and last written more than ten minutes ago. Anything else, another program's files
//! above all, is never touched.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// Replaces (or creates) `path` with `bytes`, whole: an interruption at any point
/// leaves either the old file or the new one, never part of either. Written to a
/// temporary file, flushed, renamed over `path`, then the folder flushed so the
/// rename itself survives a power cut (best effort: not every system can open a
/// folder to flush it, and the file is safe by then).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let (dir, tmp, file) = temporary(path)?;
    let result =
        fill(file, bytes, &|f, b| f.write_all(b)).and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
        return result;
    }
    sync_dir(&dir);
    Ok(())
}

/// Writes `bytes` to `path` only if no file has that name, and never leaves a part of
/// them under it. Returns `Ok(true)` when it wrote, `Ok(false)` when the name was
/// taken (nothing written, the file there untouched), even if that file appeared
/// while this one was being written.
///
/// How: the bytes go to a temporary file, flushed, which is then hard-linked to
/// `path`. Unlike a rename, a link fails when the name is taken, so a report or a
/// builder's file that appeared meanwhile is never replaced, and the name appears
/// with the whole text behind it.
///
/// FAT and exFAT (most USB sticks, where a builder may keep the log) have no hard
/// links: Linux answers EPERM, macOS ENOTSUP, Windows ERROR_INVALID_FUNCTION. Since
/// these differ, any failure of the link other than "the name is taken" falls back to
/// creating `path` itself with `create_new` (which also refuses a taken name) and
/// writing into it. On an error there the half-written file is removed; only a power
/// cut in those few milliseconds can leave a short file, which the load file's reader
/// refuses by its line and a person sees as a cut report. (Creating `path` empty, to
/// hold the name, and renaming a full temporary file over it would not be safer: the
/// rename replaces whatever is under the name by then, and a power cut still leaves
/// an empty file.)
pub fn write_new(path: &Path, bytes: &[u8]) -> io::Result<bool> {
    write_new_with(path, bytes, &REAL)
}

/// The two steps of [`write_new`] a test replaces, to see what happens when a file
/// appears at the wrong moment, a file system has no links, or a disk fills up.
struct Ops<'a> {
    link: &'a dyn Fn(&Path, &Path) -> io::Result<()>,
    write: &'a dyn Fn(&mut File, &[u8]) -> io::Result<()>,
}

const REAL: Ops<'static> = Ops {
    link: &|from, to| std::fs::hard_link(from, to),
    write: &|f, b| f.write_all(b),
};

fn write_new_with(path: &Path, bytes: &[u8], ops: &Ops) -> io::Result<bool> {
    let (dir, tmp, file) = temporary(path)?;
    if let Err(e) = fill(file, bytes, ops.write) {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    let linked = (ops.link)(&tmp, path);
    let _ = std::fs::remove_file(&tmp);
    match linked {
        Ok(()) => {
            sync_dir(&dir);
            Ok(true)
        }
        Err(e) if e.kind() == io::ErrorKind::AlreadyExists => Ok(false),
        Err(_) => in_place(path, bytes, ops),
    }
}

/// The fallback of [`write_new`] where links are not supported.
fn in_place(path: &Path, bytes: &[u8], ops: &Ops) -> io::Result<bool> {
    let mut f = match OpenOptions::new().write(true).create_new(true).open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == io::ErrorKind::AlreadyExists => return Ok(false),
        Err(e) => return Err(e),
    };
    let written = (ops.write)(&mut f, bytes).and_then(|()| f.sync_all());
    drop(f);
    if let Err(e) = written {
        // Ours, created a moment ago: a short file must not stay under the name.
        let _ = std::fs::remove_file(path);
        return Err(e);
    }
    if let Some(dir) = path.parent() {
        sync_dir(dir);
    }
    Ok(true)
}

/// Writes the temporary file and flushes it to the disk.
fn fill(
    mut file: File,
    bytes: &[u8],
    write: &dyn Fn(&mut File, &[u8]) -> io::Result<()>,
) -> io::Result<()> {
    write(&mut file, bytes).and_then(|()| file.sync_all())
}

/// Distinguishes the temporary files of threads of one process.
static NEXT: AtomicU32 = AtomicU32::new(0);

/// How old a temporary file of ours must be before a later write takes it for left
/// behind. Judged by age and not by whether its process is still alive: a PID is
/// reused (a live one may not be the writer), finding whether one lives takes code
/// per platform, and a temporary file of a live writer is never this old: it lives
/// for one write and one flush, milliseconds, seconds on the slowest USB stick. Ten
/// minutes is a margin of hundreds over that, and short enough that a folder a
/// builder opens again the same day is clean.
pub const STALE_AFTER: std::time::Duration = std::time::Duration::from_secs(600);

/// A name's family: the part before its first digit, and its extension.
/// `vpx-check-2026-12-01T1830Z-2.md` → (`vpx-check-`, `md`); `loads.toml` →
/// (`loads.toml`, `toml`): a name with no digit is its own family.
fn family(name: &str) -> (&str, &str) {
    let stem = name
        .find(|c: char| c.is_ascii_digit())
        .map_or(name, |i| &name[..i]);
    let ext = name.rsplit_once('.').map_or("", |(_, e)| e);
    (stem, ext)
}

/// Whether `entry` (a file name in the target's folder) is a temporary file this
/// module made for a file of `name`'s family: `.NAME.tmp-PID-N` with digits for PID
/// and N.
fn ours(entry: &str, name: &str) -> bool {
    let Some(rest) = entry.strip_prefix('.') else {
        return false;
    };
    let Some((target, tail)) = rest.rsplit_once(".tmp-") else {
        return false;
    };
    let Some((pid, n)) = tail.split_once('-') else {
        return false;
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    digits(pid) && digits(n) && !target.is_empty() && family(target) == family(name)
}

/// The temporary files of ours for `name`'s family in `dir` that a killed writer
/// left: see the module's docs. Regular files only (never a link or a folder), older
/// than `stale_after` by their last write.
fn ours_and_stale(dir: &Path, name: &str, stale_after: std::time::Duration) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let now = std::time::SystemTime::now();
    entries
        .filter_map(Result::ok)
        .filter(|e| ours(&e.file_name().to_string_lossy(), name))
        .filter(|e| {
            // `symlink_metadata`: a link is not followed, and not a regular file.
            std::fs::symlink_metadata(e.path()).is_ok_and(|m| {
                m.file_type().is_file()
                    && m.modified()
                        .is_ok_and(|t| now.duration_since(t).is_ok_and(|age| age > stale_after))
            })
        })
        .map(|e| e.path())
        .collect()
}

/// Removes what [`ours_and_stale`] finds; best effort, a write goes on regardless.
fn remove_stale(dir: &Path, name: &str) {
    for path in ours_and_stale(dir, name, STALE_AFTER) {
        let _ = std::fs::remove_file(path);
    }
}

/// A new temporary file beside `path`: its folder, its name, the file open for
/// writing. Never one already there (another writer's, or one a crash left).
fn temporary(path: &Path) -> io::Result<(PathBuf, PathBuf, File)> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::other(format!("{} is not a file name", path.display())))?
        .to_string_lossy()
        .into_owned();
    remove_stale(&dir, &name);
    let mut last = None;
    for _ in 0..100 {
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(".{name}.tmp-{}-{n}", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((dir, tmp, f)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| io::Error::other("no temporary name free")))
}

/// Flushes a folder's entries (a new name) to the disk, where the system allows.
fn sync_dir(dir: &Path) {
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

#[cfg(test)]
/// A folder's entries by name, sorted: what a test sees left in it.
pub(crate) fn entries(dir: &Path) -> Vec<String> {
    let mut e: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    e.sort();
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    /// Linux's answer on FAT and exFAT (EPERM), which std calls PermissionDenied.
    fn no_links(_: &Path, _: &Path) -> io::Result<()> {
        Err(io::Error::from(io::ErrorKind::PermissionDenied))
    }

    #[test]
    fn a_new_file_is_written_whole_and_no_temporary_stays() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.md");
        assert!(write_new(&path, b"# report").unwrap());
        assert_eq!(std::fs::read(&path).unwrap(), b"# report");
        assert_eq!(entries(dir.path()), ["report.md"]);
    }

    #[test]
    fn a_file_already_there_is_never_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.md");
        std::fs::write(&path, "mine").unwrap();
        assert!(!write_new(&path, b"new").unwrap());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "mine");
        assert_eq!(entries(dir.path()), ["report.md"]);
    }

    /// The race of naming then writing: another writer takes the name after this one
    /// chose it and wrote its temporary file, just before it publishes.
    #[test]
    fn a_file_that_appears_while_writing_is_not_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.md");
        let sneak = |from: &Path, to: &Path| {
            std::fs::write(to, "theirs")?;
            std::fs::hard_link(from, to)
        };
        let ops = Ops {
            link: &sneak,
            ..REAL
        };
        assert!(!write_new_with(&path, b"ours", &ops).unwrap());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "theirs");
        assert_eq!(entries(dir.path()), ["report.md"]);
    }

    #[test]
    fn without_hard_links_the_file_is_created_in_place() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("loads.toml");
        let fat = Ops {
            link: &no_links,
            ..REAL
        };
        assert!(write_new_with(&path, b"template", &fat).unwrap());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "template");
        assert_eq!(entries(dir.path()), ["loads.toml"]);
        // And still never over a file there, even one that appears at the last moment.
        assert!(!write_new_with(&path, b"again", &fat).unwrap());
        let sneak = |_: &Path, to: &Path| {
            std::fs::write(to, "theirs")?;
            no_links(to, to)
        };
        let other = dir.path().join("other.toml");
        let ops = Ops {
            link: &sneak,
            ..REAL
        };
        assert!(!write_new_with(&other, b"ours", &ops).unwrap());
        assert_eq!(std::fs::read_to_string(&other).unwrap(), "theirs");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "template");
        assert_eq!(entries(dir.path()), ["loads.toml", "other.toml"]);
    }

    /// A disk full half-way: the temporary file's writing fails, or, without links,
    /// the file's own. Neither leaves a file behind, nor part of one under the name.
    #[test]
    fn a_write_that_fails_leaves_no_file_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.md");
        let half = |f: &mut File, b: &[u8]| {
            f.write_all(&b[..b.len() / 2])?;
            Err(io::Error::other("no space left on device"))
        };
        for link in [REAL.link, &no_links] {
            let ops = Ops { link, write: &half };
            let e = write_new_with(&path, b"# a whole report", &ops).unwrap_err();
            assert_eq!(e.to_string(), "no space left on device");
            assert_eq!(entries(dir.path()), Vec::<String>::new());
        }
        // The fallback's own write failing (links unsupported, the temporary file
        // fine): the file it created is taken back.
        let calls = std::cell::Cell::new(0);
        let second_fails = |f: &mut File, b: &[u8]| {
            calls.set(calls.get() + 1);
            if calls.get() == 1 {
                f.write_all(b)
            } else {
                half(f, b)
            }
        };
        let ops = Ops {
            link: &no_links,
            write: &second_fails,
        };
        assert!(write_new_with(&path, b"# a whole report", &ops).is_err());
        assert_eq!(calls.get(), 2);
        assert_eq!(entries(dir.path()), Vec::<String>::new());
    }

    #[test]
    fn a_missing_folder_is_an_error_that_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing").join("report.md");
        assert_eq!(
            write_new(&path, b"x").unwrap_err().kind(),
            io::ErrorKind::NotFound
        );
        assert_eq!(
            write_atomically(&path, b"x").unwrap_err().kind(),
            io::ErrorKind::NotFound
        );
        assert_eq!(entries(dir.path()), Vec::<String>::new());
    }

    #[test]
    fn an_atomic_write_replaces_the_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("unit.toml");
        std::fs::write(&path, "old").unwrap();
        write_atomically(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(entries(dir.path()), ["unit.toml"]);
    }

    #[test]
    fn an_atomic_write_that_fails_keeps_the_old_file_whole() {
        let dir = tempfile::tempdir().unwrap();
        // The rename cannot replace a non-empty folder: the write fails at its last
        // step, as an interrupted one would.
        let path = dir.path().join("unit.toml");
        std::fs::create_dir(&path).unwrap();
        std::fs::write(path.join("keep"), "old").unwrap();
        assert!(write_atomically(&path, b"new").is_err());
        assert_eq!(entries(dir.path()), ["unit.toml"]);
        assert_eq!(std::fs::read_to_string(path.join("keep")).unwrap(), "old");
    }

    /// A writer killed between creating its temporary file and naming it leaves
    /// `.NAME.tmp-PID-N`: the next write of that name, or of one of its family,
    /// removes it once it is older than [`STALE_AFTER`]. A fresh one (a writer busy
    /// now), one of another family, a name of another form, a folder or a link of
    /// that form, are left alone.
    #[test]
    fn stale_temporary_files_of_ours_are_removed_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let old = std::time::SystemTime::now() - STALE_AFTER - Duration::from_secs(60);
        let make = |name: &str, when: Option<std::time::SystemTime>| {
            let f = File::create(d.join(name)).unwrap();
            if let Some(t) = when {
                f.set_modified(t).unwrap();
            }
        };
        // Ours and stale: the same name, and a report of another minute.
        make(".vpx-check-2026-12-01T1830Z.md.tmp-4242-0", Some(old));
        make(".vpx-check-2026-11-30T0900Z-2.md.tmp-77-3", Some(old));
        // Ours but fresh: a writer at work now.
        make(".vpx-check-2026-12-01T1830Z.md.tmp-4243-1", None);
        // Not ours, however old: another family, another extension, other forms.
        make(".loads.toml.tmp-4242-0", Some(old));
        make(".vpx-check-2026-12-01T1830Z.csv.tmp-4242-0", Some(old));
        make(".vpx-check-2026-12-01T1830Z.md.tmp-abc-0", Some(old));
        make(".vpx-check-2026-12-01T1830Z.md.tmp-4242", Some(old));
        make("vpx-check-2026-12-01T1830Z.md.tmp-4242-0", Some(old));
        make(".vpx-check-2026-12-01T1830Z.md.swp", Some(old));
        std::fs::create_dir(d.join(".vpx-check-2026-12-01T1830Z.md.tmp-9-9")).unwrap();
        let before = entries(d);
        assert!(write_new(&d.join("vpx-check-2026-12-02T0800Z.md"), b"# new").unwrap());
        let mut expected: Vec<String> = before
            .into_iter()
            .filter(|e| {
                e != ".vpx-check-2026-12-01T1830Z.md.tmp-4242-0"
                    && e != ".vpx-check-2026-11-30T0900Z-2.md.tmp-77-3"
            })
            .collect();
        expected.push("vpx-check-2026-12-02T0800Z.md".into());
        expected.sort();
        assert_eq!(entries(d), expected);
        // The load file's write takes its own stale one, not the reports'.
        write_atomically(&d.join("loads.toml"), b"x").unwrap();
        assert!(!entries(d).contains(&".loads.toml.tmp-4242-0".to_string()));
        assert!(entries(d).contains(&".vpx-check-2026-12-01T1830Z.md.tmp-4243-1".to_string()));
    }

    #[test]
    fn a_names_family_is_its_part_before_the_first_digit_and_its_extension() {
        assert_eq!(
            family("vpx-check-2026-12-01T1830Z-2.md"),
            ("vpx-check-", "md")
        );
        assert_eq!(family("loads.toml"), ("loads.toml", "toml"));
        assert!(ours(".report.md.tmp-1-2", "report.md"));
        assert!(!ours(".report.md.tmp-1-2", "other.md"));
        assert!(!ours(".report.md.tmp--2", "report.md"));
        assert!(!ours("..tmp-1-2", ".md"));
    }

    /// Two threads writing the same file at once: each has its own temporary file,
    /// and exactly one of two no-clobber writes wins.
    #[test]
    fn writers_at_once_do_not_share_a_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.md");
        let wins: Vec<bool> = std::thread::scope(|s| {
            let a = s.spawn(|| write_new(&path, b"a").unwrap());
            let b = s.spawn(|| write_new(&path, b"b").unwrap());
            vec![a.join().unwrap(), b.join().unwrap()]
        });
        assert_eq!(wins.iter().filter(|w| **w).count(), 1, "{wins:?}");
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text, if wins[0] { "a" } else { "b" });
        assert_eq!(entries(dir.path()), ["report.md"]);
    }
}

//! The installation check's report on the disk: the text the check builds
//! ([`crate::check::report`]), written into the reports folder by the app, since the
//! flow writes no file.

use std::path::{Path, PathBuf};

use crate::check::report::{About, csv, markdown, stem};
use crate::check::state::CheckView;
use crate::files;

/// The two files written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    pub markdown: PathBuf,
    pub csv: PathBuf,
}

/// Writes the Markdown report and the CSV into `dir`, creating the folder (and its
/// parents) if it is missing: the report comes at the end of a check that took the
/// builder many minutes, and refusing it then for a folder not made yet would lose
/// it. (The headless check makes the folder before it starts, so a folder that cannot
/// be made is said before anything is switched on; the path written is printed.)
///
/// Each file is written whole or not at all and never over another
/// ([`crate::files::write_new`]): a second check in the same minute gets `-2`, `-3`…,
/// the name chosen by the write itself, so a report that appears between choosing a
/// name and writing it is never replaced. The two files share their name: when the
/// CSV's is taken (a stray file), the Markdown just written is taken back and the next
/// pair is tried; when the CSV cannot be written, the Markdown is taken back too, so a
/// failed write leaves nothing behind.
pub fn write(dir: &Path, view: &CheckView, about: &About) -> std::io::Result<Written> {
    prepare(dir)?;
    let stem = stem(about.when);
    let (md_text, csv_text) = (markdown(view, about), csv(view, about));
    for n in 1..1000 {
        let name = if n == 1 {
            stem.clone()
        } else {
            format!("{stem}-{n}")
        };
        let md = dir.join(format!("{name}.md"));
        let csv_path = dir.join(format!("{name}.csv"));
        if !files::write_new(&md, md_text.as_bytes())? {
            continue;
        }
        match files::write_new(&csv_path, csv_text.as_bytes()) {
            Ok(true) => {
                return Ok(Written {
                    markdown: md,
                    csv: csv_path,
                });
            }
            Ok(false) => {
                let _ = std::fs::remove_file(&md);
            }
            Err(e) => {
                let _ = std::fs::remove_file(&md);
                return Err(e);
            }
        }
    }
    Err(std::io::Error::other(format!(
        "{}: a thousand reports named {stem} already",
        dir.display()
    )))
}

/// Makes the report folder if it is missing; an error names the folder.
pub fn prepare(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| {
        std::io::Error::new(
            e.kind(),
            format!("cannot make the report folder {}: {e}", dir.display()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::entries;

    #[test]
    fn a_name_half_taken_moves_both_files_to_the_next_name() {
        let dir = tempfile::tempdir().unwrap();
        let view = CheckView::default();
        let about = crate::check::report::tests::about();
        // A CSV left alone under the first name (its report deleted), a report alone
        // under the second: the check's pair goes to the third, and neither is touched.
        std::fs::write(dir.path().join("vpx-check-2026-12-01T1830Z.csv"), "old csv").unwrap();
        std::fs::write(dir.path().join("vpx-check-2026-12-01T1830Z-2.md"), "old md").unwrap();
        let w = write(dir.path(), &view, &about).unwrap();
        assert_eq!(
            w.markdown,
            dir.path().join("vpx-check-2026-12-01T1830Z-3.md")
        );
        assert_eq!(w.csv, dir.path().join("vpx-check-2026-12-01T1830Z-3.csv"));
        assert_eq!(
            entries(dir.path()),
            [
                "vpx-check-2026-12-01T1830Z-2.md",
                "vpx-check-2026-12-01T1830Z-3.csv",
                "vpx-check-2026-12-01T1830Z-3.md",
                "vpx-check-2026-12-01T1830Z.csv",
            ]
        );
        let read = |n: &str| std::fs::read_to_string(dir.path().join(n)).unwrap();
        assert_eq!(read("vpx-check-2026-12-01T1830Z.csv"), "old csv");
        assert_eq!(read("vpx-check-2026-12-01T1830Z-2.md"), "old md");
        assert_eq!(
            read("vpx-check-2026-12-01T1830Z-3.md"),
            markdown(&view, &about)
        );
    }

    #[test]
    fn a_missing_folder_is_made_and_one_that_cannot_be_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("logs").join("checks");
        prepare(&folder).unwrap();
        assert!(folder.is_dir());
        // A file where a folder must go.
        let blocked = dir.path().join("file");
        std::fs::write(&blocked, "x").unwrap();
        let e = prepare(&blocked.join("reports")).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!(
                "cannot make the report folder {}: ",
                blocked.join("reports").display()
            )),
            "{e}"
        );
    }
}

//! The load file on disk: read it, or on the first run write its template, never
//! over a file that is there (it holds the builder's work).

use std::path::{Path, PathBuf};

use super::file::{self, LoadFile};
use crate::model::Circuit;
use crate::toml_lines::{FileError, Problem};

/// What the load file is called in what is said of it.
const KIND: &str = "load file";

/// What the check found at the file's path.
#[derive(Debug, Clone, PartialEq)]
pub enum Opened {
    /// There was none: the template was written there, for the builder to fill in.
    TemplateWritten(PathBuf),
    /// The builder's file, read.
    Read(LoadFile),
}

/// Reads the file at `path`.
pub fn read(path: &Path) -> Result<LoadFile, FileError> {
    read_with(path, file::parse)
}

fn read_with<T>(
    path: &Path,
    parse: impl Fn(&str) -> Result<T, Vec<Problem>>,
) -> Result<T, FileError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| FileError::unreadable(KIND, path.to_path_buf(), &e))?;
    parse(&text).map_err(|problems| FileError {
        kind: KIND,
        path: path.to_path_buf(),
        problems,
    })
}

/// Reads only the circuits of the file at `path` (its wires), not its ratings.
pub fn read_circuits(path: &Path) -> Result<Vec<file::LoadCircuit>, FileError> {
    read_with(path, file::parse_circuits)
}

/// Reads the file at `path`, or, when there is none, writes the template listing
/// `circuits` there (and the folders it needs).
pub fn open_or_create(path: &Path, circuits: &[Circuit]) -> Result<Opened, FileError> {
    let io = |e: std::io::Error| FileError {
        kind: KIND,
        path: path.to_path_buf(),
        problems: vec![Problem::new(
            None,
            "",
            format!("cannot write its template: {e}"),
        )],
    };
    if !path.exists() {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(io)?;
        }
        if crate::files::write_new(path, file::template(circuits).as_bytes()).map_err(io)? {
            return Ok(Opened::TemplateWritten(path.to_path_buf()));
        }
    }
    read(path).map(Opened::Read)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::entries;
    use crate::model::CircuitKind;
    use crate::protocol::device::EFIS;

    fn efis() -> Vec<Circuit> {
        vec![crate::loads::test_circuit(
            EFIS,
            "EFIS 1",
            CircuitKind::Device,
        )]
    }

    #[test]
    fn the_first_run_writes_the_template_and_the_next_reads_the_builders_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("new").join("loads.toml");
        assert_eq!(
            open_or_create(&path, &efis()).unwrap(),
            Opened::TemplateWritten(path.clone())
        );
        assert_eq!(entries(&dir.path().join("new")), ["loads.toml"]);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains("[circuit.EFIS]\nname = \"EFIS 1\"\n"),
            "{text}"
        );
        // Unedited, it is refused with the path and what to write.
        let e = open_or_create(&path, &efis()).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "load file {0}, alternator_amps: missing: write alternator_amps = the \
                 alternator's rated output in amperes\n\
                 load file {0}, battery_amp_hours: missing: write battery_amp_hours = the \
                 battery's rated capacity in ampere-hours",
                path.display()
            )
        );
        let edited = text
            .replace("# alternator_amps = 40", "alternator_amps = 40")
            .replace("# battery_amp_hours = 17", "battery_amp_hours = 17");
        std::fs::write(&path, &edited).unwrap();
        let Opened::Read(f) = open_or_create(&path, &[]).unwrap() else {
            panic!("the builder's file was not read");
        };
        assert_eq!(f.circuits.len(), 1);
        // Never written over, even with other circuits on offer.
        assert_eq!(std::fs::read_to_string(&path).unwrap(), edited);
    }

    #[test]
    fn a_file_already_there_is_never_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("loads.toml");
        std::fs::write(&path, "mine").unwrap();
        assert!(!crate::files::write_new(&path, b"template").unwrap());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "mine");
        assert_eq!(entries(dir.path()), ["loads.toml"]);
        let e = open_or_create(&path, &efis()).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("load file {}, line 1", path.display())),
            "{e}"
        );
    }
}

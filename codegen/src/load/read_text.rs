//! Reading one description file as text: bounded in size, and UTF-8 or a diagnostic that
//! points at the first byte that is not.

use std::io::Read;
use std::path::Path;

use crate::diagnostic::{Diagnostic, FileId, Files, Span};

/// Description files larger than this are refused without being read further: the largest
/// shipped one is well under 1 MiB, and an include of `/dev/zero` (or of a huge log by mistake)
/// must not exhaust memory.
pub const MAX_FILE_BYTES: u64 = 8 << 20;

/// Rule of the diagnostics for files that are not UTF-8 text.
const UTF8_RULE: &str = "files_are_utf8";
/// Rule of the diagnostics for files past [`MAX_FILE_BYTES`].
const SIZE_RULE: &str = "files_are_small";

/// Reads `path` and registers it in `files`. A file that cannot be read, is larger than
/// [`MAX_FILE_BYTES`] or is not UTF-8 is reported and `None` returned: a file that is not UTF-8 at
/// its first offending byte, the others where they were included from, by `located(rule,
/// message)` (`rule` is `None` for the operating system's errors, which the includer names).
pub fn read(
    path: &Path,
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
    located: impl Fn(Option<&'static str>, String) -> Diagnostic,
) -> Option<FileId> {
    let bytes = match read_bounded(path) {
        Ok(bytes) => bytes,
        Err(Problem::Io(e)) => {
            let message = format!("cannot read `{}`: {e}", path.display());
            diagnostics.push(located(None, message));
            return None;
        }
        Err(Problem::TooLarge) => {
            let message = format!(
                "`{}` is larger than {} MiB, the most a description file may hold",
                path.display(),
                MAX_FILE_BYTES >> 20
            );
            diagnostics.push(located(Some(SIZE_RULE), message));
            return None;
        }
    };
    match String::from_utf8(bytes) {
        Ok(text) => Some(files.add(path.to_path_buf(), text)),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let byte = e.as_bytes()[at];
            let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
            let id = files.add(path.to_path_buf(), text);
            let replacement = char::REPLACEMENT_CHARACTER.len_utf8();
            diagnostics.push(
                Diagnostic::error(
                    UTF8_RULE,
                    Span::new(id, at..at + replacement),
                    format!(
                        "the file is not UTF-8: byte {byte:#04X} here begins no UTF-8 character"
                    ),
                )
                .help("a description is UTF-8 text; save the file as UTF-8"),
            );
            None
        }
    }
}

/// Why a file's bytes were not read.
enum Problem {
    /// The operating system's error.
    Io(std::io::Error),
    /// More than [`MAX_FILE_BYTES`].
    TooLarge,
}

/// The file's bytes, reading at most one byte past the limit.
fn read_bounded(path: &Path) -> Result<Vec<u8>, Problem> {
    let file = std::fs::File::open(path).map_err(Problem::Io)?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(Problem::Io)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(Problem::TooLarge);
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_one(path: &Path) -> (Option<FileId>, Vec<Diagnostic>) {
        let mut files = Files::default();
        let mut diagnostics = Vec::new();
        let id = read(path, &mut files, &mut diagnostics, |rule, message| {
            Diagnostic::error_at_no_place(rule.unwrap_or("io"), message)
        });
        (id, diagnostics)
    }

    #[test]
    fn an_endless_file_is_refused_after_the_limit() {
        let (id, diagnostics) = read_one(Path::new("/dev/zero"));
        assert!(id.is_none());
        assert_eq!(diagnostics.len(), 1);
        assert_eq!(diagnostics[0].rule, SIZE_RULE);
    }

    #[test]
    fn a_missing_file_is_an_operating_system_error() {
        let (id, diagnostics) = read_one(Path::new("/nonexistent/device.toml"));
        assert!(id.is_none());
        assert_eq!(diagnostics[0].rule, "io");
    }
}

//! Loading: read a description's files (following `include`), keep spans, lower to the IR.

mod lower;
mod only;
mod raw;
mod raw_identity;
mod raw_lock;
mod raw_mapping;
mod raw_ramp;
mod read_text;
pub mod subindex_range;

use std::path::{Path, PathBuf};

use crate::diagnostic::{Diagnostic, FileId, Files, Span};
use raw::{RawFile, RawInclude};

pub use lower::lower;
pub use read_text::MAX_FILE_BYTES;

/// The file a folder description is loaded through.
pub const DEVICE_FILE: &str = "device.toml";

/// Includes nested deeper than this are refused (and cycles are reported before that).
const MAX_INCLUDE_DEPTH: usize = 8;

/// A parsed file and the names its includer asked for (`None` = everything).
pub struct LoadedFile {
    /// Which file.
    pub id: FileId,
    /// Its contents.
    pub raw: RawFile,
    /// The `only` filter of the include that brought it in.
    pub only: Option<raw::RawOnly>,
}

/// Reads a description file (or a folder's `device.toml`) and everything it includes.
///
/// Files are returned root first. Problems are pushed to `diagnostics`; a file that cannot be read
/// or parsed is left out.
pub fn read_files(
    path: &Path,
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<LoadedFile> {
    let root = if path.is_dir() {
        path.join(DEVICE_FILE)
    } else {
        path.to_path_buf()
    };
    read_from(&root, None, files, diagnostics)
}

/// [`read_files`] of a description file whose text is `text` (not read from disk: an overlay
/// checked before it is written); the files it includes are read from disk.
pub fn read_files_with_text(
    path: &Path,
    text: String,
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<LoadedFile> {
    read_from(path, Some(text), files, diagnostics)
}

fn read_from(
    root: &Path,
    text: Option<String>,
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<LoadedFile> {
    let mut loaded = Vec::new();
    let mut chain = Vec::new();
    read_recursive(
        root,
        (None, None, text),
        files,
        diagnostics,
        &mut loaded,
        &mut chain,
    );
    loaded
}

/// Reads `path` (whose text is given when it is not to be read from disk), brought in by the
/// include at `included_at` with its `only` filter, and what it includes.
fn read_recursive(
    path: &Path,
    (only, included_at, given): (Option<raw::RawOnly>, Option<Span>, Option<String>),
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
    loaded: &mut Vec<LoadedFile>,
    chain: &mut Vec<PathBuf>,
) {
    let canonical = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    let located = |rule: Option<&'static str>, message: String| match &included_at {
        Some(span) => Diagnostic::error(rule.unwrap_or("includes_resolve"), span.clone(), message),
        None => Diagnostic::error_at_no_place(rule.unwrap_or("io"), message),
    };
    if chain.contains(&canonical) {
        let message = format!("`{}` includes itself", path.display());
        diagnostics.push(located(Some("includes_resolve"), message));
        return;
    }
    if chain.len() >= MAX_INCLUDE_DEPTH {
        let message = format!(
            "`{}` is included {MAX_INCLUDE_DEPTH} levels deep, the most allowed",
            path.display()
        );
        diagnostics.push(located(Some("includes_resolve"), message));
        return;
    }
    // Text given by the caller (an overlay checked before it is saved) is in memory already.
    let read = match given {
        Some(text) => Some(files.add(path.to_path_buf(), text)),
        None => read_text::read(path, files, diagnostics, located),
    };
    let Some(id) = read else {
        return;
    };
    let raw: RawFile = match toml::from_str(files.text(id)) {
        Ok(raw) => raw,
        Err(e) => {
            diagnostics.push(syntax_error(id, &e));
            return;
        }
    };
    let includes: Vec<_> = raw
        .include
        .iter()
        .map(|i| (i.get_ref().clone(), i.span()))
        .collect();
    loaded.push(LoadedFile { id, raw, only });
    chain.push(canonical);
    let base = path.parent().unwrap_or(Path::new("."));
    for (include, range) in includes {
        let (target, only) = match include {
            RawInclude::Path(p) => (p, None),
            RawInclude::Table(table) => (table.path, table.only),
        };
        let span = Span::new(id, range);
        read_recursive(
            &base.join(target),
            (only, Some(span), None),
            files,
            diagnostics,
            loaded,
            chain,
        );
    }
    chain.pop();
}

/// serde names the Rust type of a value that can take several shapes; say what is expected instead.
const SHAPES: &[(&str, &str)] = &[
    (
        "RawInclude",
        "an include is a path string or `{ path, only = [names] }` (or `only = { parameters, enums, flags, records }`)",
    ),
    (
        "OneOrMany",
        "expected one address table or an array of them, with only the documented keys",
    ),
    (
        "RawScalar",
        "expected a number or a fraction string (\"1/100\")",
    ),
    (
        "RawScale",
        "a scale is a number, a fraction string (\"1/100\"), `{ factor, offset }` or `{ expr }`",
    ),
    ("RawNumber", "expected a number"),
    ("RawPdo", "`pdo` is false, \"rx\", \"tx\" or \"both\""),
    (
        "RawSrdoCobId",
        "an SRDO COB-ID is a number or `{ base, node_id_factor }`",
    ),
    (
        "RawOnly",
        "`only` is a list of names or `{ parameters, enums, flags, records }`, each a list of names",
    ),
];

fn syntax_error(id: FileId, error: &toml::de::Error) -> Diagnostic {
    let span = Span::new(id, error.span().unwrap_or(0..0));
    let raw = error.message().trim_end();
    let message = SHAPES
        .iter()
        .find(|(ty, _)| raw.contains(&format!("untagged enum {ty}")))
        .map_or_else(|| raw.to_owned(), |(_, text)| (*text).to_owned());
    Diagnostic::error("syntax", span, message)
}

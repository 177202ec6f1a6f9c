//! drivegen: typed Rust driver crates for industrial motor drives, generated from descriptions.
//!
//! The data path is `load → validate → IR → emit`:
//!
//! * [`load`] reads the TOML files of a description (following `include`) with source spans and
//!   lowers them to the [`ir`], reporting malformed values;
//! * [`validate`] runs one pass per rule over the IR;
//! * [`emit`] turns a valid IR into Rust source;
//! * [`diff`] compares two descriptions and classifies each change by its impact on user code;
//! * [`eds`] reads CiA 306 EDS / DCF files (alone or under a TOML overlay) and writes EDS files;
//! * [`config_file`] reads and writes the configuration backups of `drivegen config`, each entry
//!   with its line;
//! * [`network_file`] reads the network files of `drivegen network boot` (issue 31), each node
//!   with its line;
//! * [`gateway_file`] reads the configuration of `drivegen gateway` (issue 35), each drive with
//!   its line;
//! * [`names`] is the naming policy (description names to Rust identifiers) that validation,
//!   the EDS reader and writer and the emitter share;
//! * [`Builder`] is the `build.rs` entry point of drive crates.

mod builder;
pub mod config_file;
pub mod dbc;
pub mod diagnostic;
pub mod diff;
pub mod eds;
pub mod emit;
pub mod file_error;
pub mod gateway_file;
pub mod ir;
pub mod load;
mod mandatory_objects;
pub mod names;
pub mod network_file;
#[cfg(test)]
mod test_support;
mod toml_file;
pub mod validate;

use std::path::Path;

pub use builder::{BuildError, Builder};
pub use diagnostic::{Diagnostic, Files, Severity};

/// The result of checking a description: its files, its findings, and the IR if it is valid.
#[derive(Debug)]
pub struct Checked {
    /// Every file read, for rendering diagnostics.
    pub files: Files,
    /// Errors and warnings, in the order found.
    pub diagnostics: Vec<Diagnostic>,
    /// The device model; `None` when any error was found.
    pub device: Option<ir::Device>,
}

impl Checked {
    /// Every diagnostic rendered, rustc-style.
    pub fn render(&self) -> String {
        self.diagnostics
            .iter()
            .map(|d| d.render(&self.files))
            .collect::<Vec<_>>()
            .join("\n")
    }
}

/// Loads, lowers and validates a description file or folder. A `.eds` / `.dcf` path is read as an
/// EDS alone ([`eds::check_eds`]); a TOML file with `eds = "..."` is an overlay of that EDS.
pub fn check(path: &Path) -> Checked {
    if eds::is_eds_path(path) {
        return eds::check_eds(path);
    }
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let loaded = load::read_files(path, &mut files, &mut diagnostics);
    check_loaded(loaded, files, diagnostics)
}

/// [`check`] of a description file `path` whose text is `text`, not read from disk (an overlay
/// checked before it is written).
pub fn check_text(path: &Path, text: String) -> Checked {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let loaded = load::read_files_with_text(path, text, &mut files, &mut diagnostics);
    check_loaded(loaded, files, diagnostics)
}

/// Lowers and validates the files of a description (and the EDS it overlays).
fn check_loaded(
    loaded: Vec<load::LoadedFile>,
    mut files: Files,
    mut diagnostics: Vec<Diagnostic>,
) -> Checked {
    let overlay_of = loaded.first().and_then(|root| {
        let eds = root.raw.eds.as_ref()?;
        let span = diagnostic::Span::new(root.id, eds.span());
        Some((files.path(root.id).with_file_name(eds.get_ref()), span))
    });
    let eds = overlay_of
        .and_then(|(eds, span)| eds::read(&eds, Some(span), &mut files, &mut diagnostics));
    let device = load::lower(loaded, &files, eds.as_ref(), &mut diagnostics);
    finish_check(files, diagnostics, device)
}

/// Validates a lowered device unless lowering already failed.
pub(crate) fn finish_check(
    files: Files,
    mut diagnostics: Vec<Diagnostic>,
    device: Option<ir::Device>,
) -> Checked {
    if let Some(device) = &device {
        if !diagnostic::has_errors(&diagnostics) {
            diagnostics.extend(validate::validate(device));
        }
    }
    let device = device.filter(|_| !diagnostic::has_errors(&diagnostics));
    Checked {
        files,
        diagnostics,
        device,
    }
}

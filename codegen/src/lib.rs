//! drivegen: typed Rust driver crates for industrial motor drives, generated from descriptions.
//!
//! The data path is `load → validate → IR → emit`:
//!
//! * [`load`] reads the TOML files of a description (following `include`) with source spans and
//!   lowers them to the [`ir`], reporting malformed values;
//! * [`validate`] runs one pass per rule over the IR;
//! * [`emit`] turns a valid IR into Rust source;
//! * [`Builder`] is the `build.rs` entry point of drive crates.
#![deny(missing_docs)]

mod builder;
pub mod diagnostic;
pub mod emit;
pub mod ir;
pub mod load;
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

/// Loads, lowers and validates a description file or folder.
pub fn check(path: &Path) -> Checked {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let loaded = load::read_files(path, &mut files, &mut diagnostics);
    let device = load::lower(loaded, &files, &mut diagnostics);
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

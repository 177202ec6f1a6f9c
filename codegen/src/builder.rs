//! The `build.rs` entry point of drive crates, in the style of prost-build:
//!
//! ```no_run
//! drivegen::Builder::new("descriptions/lafert-smartris").compile().unwrap();
//! ```
//!
//! The path is relative to the crate, and the description (with the profiles it includes) should
//! be inside it, so that the published crate builds on its own.

use std::fmt;
use std::path::{Path, PathBuf};

/// Generates a drive crate's Rust source into `OUT_DIR` from a description.
#[derive(Debug, Clone)]
pub struct Builder {
    description: PathBuf,
    out_dir: Option<PathBuf>,
    file_name: String,
    emit_rerun: bool,
}

/// Why generation failed: the rendered diagnostics, or an I/O problem.
#[derive(Debug)]
pub enum BuildError {
    /// The description has errors; the text is every diagnostic, rendered.
    Invalid(String),
    /// Writing the output failed.
    Io(std::io::Error),
    /// `OUT_DIR` is not set and no output directory was given.
    NoOutDir,
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid(diagnostics) => write!(f, "the description is invalid:\n{diagnostics}"),
            Self::Io(e) => write!(f, "cannot write the generated code: {e}"),
            Self::NoOutDir => write!(f, "OUT_DIR is not set; call Builder::out_dir"),
        }
    }
}

impl std::error::Error for BuildError {}

impl Builder {
    /// A builder for the description file or folder at `description`.
    pub fn new(description: impl Into<PathBuf>) -> Self {
        Self {
            description: description.into(),
            out_dir: None,
            file_name: "drive.rs".into(),
            emit_rerun: true,
        }
    }

    /// Writes into `dir` instead of `OUT_DIR`.
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out_dir = Some(dir.into());
        self
    }

    /// Names the generated file (default `drive.rs`).
    pub fn file_name(mut self, name: impl Into<String>) -> Self {
        self.file_name = name.into();
        self
    }

    /// Whether to print `cargo:rerun-if-changed` lines (default yes; off outside build scripts).
    pub fn emit_rerun_if_changed(mut self, emit: bool) -> Self {
        self.emit_rerun = emit;
        self
    }

    /// Checks the description and writes the generated source; returns its path.
    ///
    /// Output is written to a temporary file and renamed, so a failure never leaves a partial file.
    pub fn compile(self) -> Result<PathBuf, BuildError> {
        let checked = crate::check(&self.description);
        if self.emit_rerun {
            for path in checked.files.paths() {
                println!("cargo:rerun-if-changed={}", path.display());
            }
        }
        for warning in checked
            .diagnostics
            .iter()
            .filter(|d| d.severity == crate::Severity::Warning)
        {
            for line in warning.render(&checked.files).lines() {
                println!("cargo:warning={line}");
            }
        }
        let Some(device) = &checked.device else {
            return Err(BuildError::Invalid(checked.render()));
        };
        let out_dir = match self.out_dir {
            Some(dir) => dir,
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        let origin = self.description.file_name().map_or_else(
            || self.description.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let source = crate::emit::rust::generate(device, &origin);
        write_atomically(&out_dir.join(&self.file_name), &source).map_err(BuildError::Io)
    }
}

fn write_atomically(path: &Path, text: &str) -> std::io::Result<PathBuf> {
    let tmp = path.with_extension("rs.tmp");
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)?;
    Ok(path.to_path_buf())
}

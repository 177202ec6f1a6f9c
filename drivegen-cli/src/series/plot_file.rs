//! `--plot FILE.svg` / `--plot FILE.html`: the file a run's series are drawn into. It is
//! created when the arguments are read, before any bus is opened, so a path that cannot be
//! written is refused before anything is sent.

use std::path::{Path, PathBuf};

use super::{html, svg, Series};
use crate::error::CliError;

/// What a plot file holds, from its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Svg,
    Html,
}

/// A plot file that could be created.
#[derive(Debug)]
pub struct PlotFile {
    path: PathBuf,
    format: Format,
}

impl PlotFile {
    /// Checks the extension (`.svg`, `.html` or `.htm`) and creates the file (empty until the
    /// first [`PlotFile::write`]).
    pub fn create(path: &Path) -> Result<Self, CliError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let format = match extension.as_deref() {
            Some("svg") => Format::Svg,
            Some("html" | "htm") => Format::Html,
            _ => {
                return Err(CliError::Usage(format!(
                    "--plot {}: the file must end in .svg or .html",
                    path.display()
                )))
            }
        };
        std::fs::File::create(path).map_err(|e| {
            CliError::Io(format!("--plot {}: cannot be written: {e}", path.display()))
        })?;
        Ok(Self {
            path: path.to_owned(),
            format,
        })
    }

    /// Draws `series` into the file, replacing what it held. The drawing goes to a sibling file
    /// first and is renamed over the plot, so a browser reloading it (or a run interrupted
    /// while writing) never sees half a document.
    pub fn write(&self, title: &str, series: &[Series]) -> Result<(), CliError> {
        let text = match self.format {
            Format::Svg => svg::render(series),
            Format::Html => html::render(title, series),
        };
        let mut partial = self.path.clone().into_os_string();
        partial.push(".partial");
        let partial = PathBuf::from(partial);
        let failed = |e: std::io::Error| {
            CliError::Io(format!(
                "--plot {}: cannot be written: {e}",
                self.path.display()
            ))
        };
        std::fs::write(&partial, text).map_err(failed)?;
        std::fs::rename(&partial, &self.path).map_err(failed)
    }
}

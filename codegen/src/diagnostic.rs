//! Diagnostics: an error or warning that points at a file, line and column, rendered like rustc.

use std::fmt::Write as _;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// Index of a loaded file in a [`Files`] table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct FileId(pub usize);

/// A byte range in one loaded file.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The file.
    pub file: FileId,
    /// Byte offsets into its text.
    pub range: Range<usize>,
}

impl Span {
    /// A span in `file` covering `range`.
    pub fn new(file: FileId, range: Range<usize>) -> Self {
        Self { file, range }
    }
}

/// Every file a description was loaded from, with its text, so diagnostics can quote it.
#[derive(Debug, Default, Clone)]
pub struct Files {
    entries: Vec<(PathBuf, String)>,
}

impl Files {
    /// Registers a file's text.
    pub fn add(&mut self, path: PathBuf, text: String) -> FileId {
        self.entries.push((path, text));
        FileId(self.entries.len() - 1)
    }
    /// The path of a file.
    pub fn path(&self, id: FileId) -> &Path {
        &self.entries[id.0].0
    }
    /// The text of a file.
    pub fn text(&self, id: FileId) -> &str {
        &self.entries[id.0].1
    }
    /// Every file path, in load order.
    pub fn paths(&self) -> impl Iterator<Item = &Path> {
        self.entries.iter().map(|(p, _)| p.as_path())
    }
    /// 1-based line and column of a byte offset.
    pub fn line_col(&self, id: FileId, offset: usize) -> (usize, usize) {
        let text = self.text(id);
        let offset = offset.min(text.len());
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (line, before[line_start..].chars().count() + 1)
    }
}

/// How bad a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The description cannot be used.
    Error,
    /// The description is usable but probably not what was meant.
    Warning,
}

/// One finding about a description.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// The rule that found it (a validation pass name, or `syntax`, `io`...).
    pub rule: &'static str,
    /// What is wrong, in one sentence.
    pub message: String,
    /// Where; `None` for problems with no location (a missing file).
    pub span: Option<Span>,
    /// The label under the snippet.
    pub label: String,
    /// How to fix it.
    pub help: Option<String>,
}

impl Diagnostic {
    /// An error of `rule` at `span`.
    pub fn error(rule: &'static str, span: Span, message: impl Into<String>) -> Self {
        Self {
            severity: Severity::Error,
            rule,
            message: message.into(),
            span: Some(span),
            label: String::new(),
            help: None,
        }
    }
    /// An error without a location.
    pub fn error_at_no_place(rule: &'static str, message: impl Into<String>) -> Self {
        Self {
            span: None,
            ..Self::error(rule, Span::default(), message)
        }
    }
    /// Turns this into a warning.
    pub fn warning(mut self) -> Self {
        self.severity = Severity::Warning;
        self
    }
    /// Adds a label under the snippet.
    pub fn label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }
    /// Adds a help line.
    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// Renders the diagnostic rustc-style, with the file path as given.
    pub fn render(&self, files: &Files) -> String {
        let level = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let mut out = format!("{level}[{}]: {}\n", self.rule, self.message);
        let mut pad = String::new();
        if let Some(span) = &self.span {
            pad = render_snippet(&mut out, files, span, &self.label);
        }
        if let Some(help) = &self.help {
            let _ = writeln!(out, "{pad} = help: {help}");
        }
        out
    }
}

/// Writes the location and the quoted line; returns the gutter padding for follow-up lines.
fn render_snippet(out: &mut String, files: &Files, span: &Span, label: &str) -> String {
    let (line, col) = files.line_col(span.file, span.range.start);
    let text = files.text(span.file);
    let source_line = text.lines().nth(line - 1).unwrap_or("");
    let gutter = line.to_string().len();
    let pad = " ".repeat(gutter);
    let path = files.path(span.file).display();
    let _ = writeln!(out, "{pad}--> {path}:{line}:{col}");
    let _ = writeln!(out, "{pad} |");
    let _ = writeln!(out, "{line} | {source_line}");
    let line_chars = source_line.chars().count();
    let width = text
        .get(span.range.clone())
        .map_or(1, |s| s.lines().next().unwrap_or("").chars().count())
        .clamp(1, line_chars.saturating_sub(col - 1).max(1));
    let marker = format!("{}{}", " ".repeat(col - 1), "^".repeat(width));
    let _ = writeln!(out, "{}", format!("{pad} | {marker} {label}").trim_end());
    pad
}

/// Whether any of `diagnostics` is an error (warnings do not stop generation).
pub fn has_errors(diagnostics: &[Diagnostic]) -> bool {
    diagnostics.iter().any(|d| d.severity == Severity::Error)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_file_line_column_snippet_and_help() {
        let mut files = Files::default();
        let id = files.add("dev.toml".into(), "format = 1\nname = \"x y\"\n".into());
        let d = Diagnostic::error("names_are_valid", Span::new(id, 18..23), "bad name")
            .label("here")
            .help("use snake_case");
        assert_eq!(
            d.render(&files),
            "error[names_are_valid]: bad name\n --> dev.toml:2:8\n  |\n2 | name = \"x y\"\n  |        ^^^^^ here\n  = help: use snake_case\n"
        );
    }
}

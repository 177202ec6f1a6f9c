//! EDS to a TOML overlay skeleton: one `[[record]]` / `[[parameter]]` per EDS object, named in
//! snake_case and citing its EDS line, ready to be enriched (units, scales, enums) by hand.

use std::fmt::Write as _;
use std::path::Path;

use super::lower::EdsModel;
use crate::diagnostic::{has_errors, Files};

/// Why no overlay could be written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ImportError {
    /// The EDS has errors (an unreadable file, an object without a usable DataType...): the
    /// rendered diagnostics.
    Invalid(String),
}

impl std::fmt::Display for ImportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ImportError::Invalid(diagnostics) => {
                write!(f, "the EDS cannot be imported:\n{diagnostics}")
            }
        }
    }
}

impl std::error::Error for ImportError {}

/// The overlay skeleton of the EDS at `eds_path`, to be saved beside it (it names the EDS by its
/// file name). It passes `drivegen::check` as written.
pub fn import_overlay(eds_path: &Path) -> Result<String, ImportError> {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let model = super::read(eds_path, None, &mut files, &mut diagnostics);
    let render = |d: &[crate::Diagnostic], files: &Files| {
        d.iter()
            .map(|d| d.render(files))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let Some(model) = model.filter(|_| !has_errors(&diagnostics)) else {
        return Err(ImportError::Invalid(render(&diagnostics, &files)));
    };
    if let Some(problem) = model
        .entries
        .iter()
        .find_map(|e| e.data_type.err().map(|p| e.type_problem(p)))
    {
        return Err(ImportError::Invalid(render(&[problem], &files)));
    }
    let file_name = eds_path.file_name().map_or_else(
        || eds_path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    Ok(skeleton(&model, &file_name))
}

fn quote(text: &str) -> String {
    toml::Value::String(text.to_owned()).to_string()
}

fn skeleton(model: &EdsModel, file_name: &str) -> String {
    let name = model
        .device
        .product_name
        .clone()
        .filter(|n| !n.trim().is_empty())
        .unwrap_or_else(|| file_name.trim_end_matches(".eds").to_owned());
    let mut out = String::new();
    let _ = writeln!(out, "# Overlay of {file_name}, written by `drivegen eds import`. Every object of the EDS is listed;");
    let _ = writeln!(
        out,
        "# add doc, unit, scale, enum, flags, effect... to an entry, or delete entries you do not"
    );
    let _ = writeln!(
        out,
        "# need to refine (objects not listed here are still generated, named after the EDS)."
    );
    let _ = writeln!(
        out,
        "# The source id \"eds\" (the EDS file itself) is declared implicitly."
    );
    let _ = writeln!(out, "format = 1");
    let _ = writeln!(out, "eds = {}", quote(file_name));
    let _ = writeln!(out, "\n[device]");
    let _ = writeln!(out, "name = {}", quote(&name));
    let _ = writeln!(out, "handle = {}", quote(&crate::emit::ident::camel(&name)));
    if let Some(vendor) = &model.device.vendor_name {
        let _ = writeln!(out, "vendor = {}", quote(vendor));
    }
    for r in &model.records {
        let kind = match r.kind {
            crate::ir::RecordKind::Array => "array",
            crate::ir::RecordKind::Record => "record",
        };
        let _ = writeln!(out, "\n[[record]]");
        let _ = writeln!(out, "name = {}", quote(&r.name));
        let _ = writeln!(out, "kind = \"{kind}\"");
        let _ = writeln!(out, "index = 0x{:04X}", r.index);
        cite(&mut out, r.source.as_ref());
    }
    for e in &model.entries {
        let _ = writeln!(out, "\n[[parameter]]");
        let _ = writeln!(out, "name = {}", quote(&e.name));
        let _ = writeln!(
            out,
            "doc = {}",
            quote(
                e.variable
                    .description
                    .as_deref()
                    .unwrap_or(&e.variable.name)
            )
        );
        let _ = writeln!(
            out,
            "canopen = {{ index = 0x{:04X}, subindex = {} }}",
            e.index, e.variable.subindex
        );
        cite(&mut out, Some(&e.citation(&model.cited)));
    }
    out
}

fn cite(out: &mut String, citation: Option<&crate::ir::Citation>) {
    if let Some(c) = citation {
        let section = c.section.as_deref().unwrap_or("");
        let line = c.line.unwrap_or(1);
        let _ = writeln!(
            out,
            "source = {{ doc = \"eds\", section = {}, line = {line} }}",
            quote(section)
        );
    }
}

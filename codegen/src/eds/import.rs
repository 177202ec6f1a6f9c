//! EDS to a TOML overlay skeleton: one `[[record]]` / `[[parameter]]` per EDS object, named in
//! snake_case and citing its EDS line, ready to be enriched (units, scales, enums) by hand.

use std::fmt::Write as _;
use std::path::{Component, Path, PathBuf};

use super::lower::{EdsEntry, EdsModel, TypeProblem};
use crate::diagnostic::Files;
use crate::Checked;

/// Why no overlay could be written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ImportError {
    /// The EDS cannot be read (a missing file): the rendered diagnostic.
    Unreadable(String),
}

impl std::fmt::Display for ImportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ImportError::Unreadable(diagnostics) => {
                write!(f, "the EDS cannot be imported:\n{diagnostics}")
            }
        }
    }
}

impl std::error::Error for ImportError {}

/// An overlay skeleton and the check of it, as it will be saved.
#[derive(Debug)]
pub struct Imported {
    /// The TOML text of the overlay.
    pub overlay: String,
    /// `drivegen::check` of the overlay at the path it is saved to: the findings of the EDS
    /// (warnings for every leniency applied) and of the skeleton; `checked.device` is `None` when
    /// the overlay does not check.
    pub checked: Checked,
}

impl Imported {
    /// Whether the overlay checks (warnings allowed).
    pub fn checks(&self) -> bool {
        self.checked.device.is_some()
    }
}

/// Where an overlay of `eds_path` is saved when no path is given: beside it, `<stem>.toml`.
pub fn default_overlay_path(eds_path: &Path) -> PathBuf {
    eds_path.with_extension("toml")
}

/// The overlay skeleton of the EDS at `eds_path`, to be saved at `overlay_path` (it names the
/// EDS relative to that file), and its check there: the overlay is checked before it is written,
/// so an import never claims a skeleton works when it does not.
pub fn import_overlay(eds_path: &Path, overlay_path: &Path) -> Result<Imported, ImportError> {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let Some(model) = super::read(eds_path, None, &mut files, &mut diagnostics) else {
        let rendered = diagnostics
            .iter()
            .map(|d| d.render(&files))
            .collect::<Vec<_>>();
        return Err(ImportError::Unreadable(rendered.join("\n")));
    };
    let reference = eds_reference(eds_path, overlay_path);
    let overlay = skeleton(&model, &reference);
    let checked = crate::check_text(overlay_path, overlay.clone());
    Ok(Imported { overlay, checked })
}

/// How an overlay at `overlay_path` names the EDS at `eds_path`: its file name when both are in
/// one folder, else a path relative to the overlay's folder (absolute when there is none).
fn eds_reference(eds_path: &Path, overlay_path: &Path) -> String {
    let folder = |p: &Path| {
        let parent = p.parent().filter(|f| !f.as_os_str().is_empty());
        let parent = parent.unwrap_or(Path::new("."));
        parent
            .canonicalize()
            .unwrap_or_else(|_| parent.to_path_buf())
    };
    let (eds_folder, overlay_folder) = (folder(eds_path), folder(overlay_path));
    let file_name = eds_path.file_name().unwrap_or(eds_path.as_os_str());
    let relative = relative_path(&eds_folder, &overlay_folder)
        .map_or_else(|| eds_folder.join(file_name), |r| r.join(file_name));
    relative.to_string_lossy().into_owned()
}

/// `target` relative to `base` (both absolute), or `None` when they share nothing but the root
/// (an absolute path reads better than a climb to the root).
fn relative_path(target: &Path, base: &Path) -> Option<PathBuf> {
    let target: Vec<_> = target.components().collect();
    let base: Vec<_> = base.components().collect();
    let rooted =
        |c: Option<&Component>| matches!(c, Some(Component::RootDir | Component::Prefix(_)));
    if !rooted(target.first()) || !rooted(base.first()) {
        return None;
    }
    let common = target.iter().zip(&base).take_while(|(a, b)| a == b).count();
    if common < 2 && target.len() > 1 {
        return None;
    }
    let up = base[common..].iter().map(|_| Component::ParentDir);
    Some(up.chain(target[common..].iter().copied()).collect())
}

fn quote(text: &str) -> String {
    toml::Value::String(text.to_owned()).to_string()
}

fn skeleton(model: &EdsModel, reference: &str) -> String {
    let file_name = Path::new(reference).file_name().map_or_else(
        || reference.to_owned(),
        |n| n.to_string_lossy().into_owned(),
    );
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
    let _ = writeln!(out, "eds = {}", quote(reference));
    let _ = writeln!(out, "\n[device]");
    let _ = writeln!(out, "name = {}", quote(&name));
    let _ = writeln!(out, "handle = {}", quote(&crate::names::camel(&name)));
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
        type_comment(&mut out, e);
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

/// For an entry whose EDS type drivegen cannot use: why it is read as octets, and where to type it.
fn type_comment(out: &mut String, e: &EdsEntry) {
    let why = match e.data_type {
        Ok(_) => return,
        Err(TypeProblem::Missing) => "The EDS gives no usable DataType".to_owned(),
        Err(TypeProblem::Unsupported(code)) => {
            format!("DataType {code:#06X} is vendor-specific or reserved")
        }
    };
    let _ = writeln!(
        out,
        "# {why}: read as an octet string. Give the type the vendor documents, e.g.\n# type = \"u32\""
    );
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_eds_is_named_relative_to_the_overlay_unless_only_the_root_is_shared() {
        let relative = |t: &str, b: &str| relative_path(Path::new(t), Path::new(b));
        assert_eq!(relative("/a/b", "/a/b"), Some(PathBuf::new()));
        assert_eq!(
            relative("/a/vendor", "/a/overlays"),
            Some("../vendor".into())
        );
        assert_eq!(relative("/a/b/c", "/a"), Some("b/c".into()));
        assert_eq!(relative("/work/x", "/tmp"), None);
        assert_eq!(relative("a/b", "/a/b"), None);
    }
}

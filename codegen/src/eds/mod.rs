//! CiA 306 electronic data sheets (EDS) and device configuration files (DCF).
//!
//! * [`read`] parses an EDS leniently into an [`EdsModel`] (objects, derived names, citations of
//!   EDS lines), reporting problems as rustc-style diagnostics; it never panics.
//! * [`check_eds`] turns an EDS alone into a device (`drivegen::check` calls it for `.eds` / `.dcf`
//!   paths); a TOML description with a top-level `eds = "vendor.eds"` key is an *overlay* that adds
//!   names, enums, units... to the EDS's objects (see `docs/description-format.md`).
//! * [`export`] writes the EDS of a description's CANopen objects.
//! * [`import_overlay`] writes a TOML overlay skeleton for an EDS, and checks it.

mod data_type;
mod dictionary;
mod encoding;
mod export;
mod import;
mod lower;
mod names;
pub(crate) mod node_id;
mod parse;
mod pdo_objects;
mod short_text;
mod trim;
mod values;
mod word_hash;

use std::path::Path;
use std::sync::Arc;

use crate::diagnostic::{Diagnostic, Files, Span};
use crate::{ir, Checked};

pub use data_type::{from_code, to_code, Code};
pub use dictionary::{DeviceInfo, Dictionary, Object, ObjectKind, Text, Variable};
pub use encoding::{decode, Encoding};
pub use export::export;
pub use import::{default_overlay_path, import_overlay, ImportError, Imported};
pub use lower::{EdsEntry, EdsModel, TypeProblem, EDS_SOURCE_ID};
pub use names::snake_name;
pub use node_id::{parse_value, EdsValue};
pub use parse::{parse_ini, Ini};
pub use pdo_objects::{pdo_objects, PdoObjects};
pub use short_text::ShortText;

/// True for paths ending `.eds` or `.dcf` (any case).
pub fn is_eds_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("eds") || e.eq_ignore_ascii_case("dcf"))
}

/// Reads and lowers the EDS at `path`; `None` if it cannot be read. `referenced_at` locates the
/// `eds = "..."` key of an overlay for I/O errors.
pub fn read(
    path: &Path,
    referenced_at: Option<Span>,
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<EdsModel> {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) => {
            let message = format!("cannot read `{}`: {e}", path.display());
            diagnostics.push(match referenced_at {
                Some(span) => Diagnostic::error("eds_resolves", span, message),
                None => Diagnostic::error_at_no_place("io", message),
            });
            return None;
        }
    };
    Some(read_bytes(path, &bytes, files, diagnostics))
}

/// Parses EDS `bytes` registered in `files` under `path`.
pub fn read_bytes(
    path: &Path,
    bytes: &[u8],
    files: &mut Files,
    diagnostics: &mut Vec<Diagnostic>,
) -> EdsModel {
    let (text, encoding) = decode(bytes);
    let file = files.add(path.to_path_buf(), text);
    let start = Span::new(file, 0..0);
    match encoding {
        Encoding::Utf8 => {}
        Encoding::Utf8WithBom => diagnostics.push(
            Diagnostic::error(
                "eds_encoding",
                start,
                "the file starts with a UTF-8 byte-order mark",
            )
            .warning()
            .help("drivegen skips it, but other CANopen tools (python canopen) refuse the file"),
        ),
        Encoding::Cp1252 => diagnostics.push(
            Diagnostic::error(
                "eds_encoding",
                start,
                "the file is not UTF-8; read as Windows-1252",
            )
            .warning(),
        ),
    }
    let ini = parse_ini(file, files.text(file), diagnostics);
    let dictionary = dictionary::read(&ini, diagnostics);
    // Freed before lowering, which then reuses its memory (still in cache) for the entries.
    drop(ini);
    lower::lower(dictionary, file, files)
}

/// An EDS alone as a device: every object becomes a parameter named after its `ParameterName`.
pub fn check_eds(path: &Path) -> Checked {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let device = read(path, None, &mut files, &mut diagnostics).map(|model| {
        let name = model
            .device
            .product_name
            .clone()
            .filter(|n| !n.trim().is_empty())
            .unwrap_or_else(|| {
                path.file_stem()
                    .map_or("device".into(), |s| s.to_string_lossy().into_owned())
            });
        let mut device = empty_device(&name, &model);
        let parameters = typed_parameters(model.entries, &model.cited, &mut diagnostics);
        device.parameters = parameters;
        device
    });
    crate::finish_check(files, diagnostics, device)
}

/// A device with the identity of an EDS and its records, no parameters yet.
pub fn empty_device(name: &str, model: &EdsModel) -> ir::Device {
    ir::Device {
        schema: ir::IR_SCHEMA_VERSION,
        device: ir::Identity {
            name: name.to_owned(),
            handle: crate::names::camel(name),
            vendor: model.device.vendor_name.clone(),
            firmware: None,
            doc: (!model.device.comments.is_empty()).then(|| model.device.comments.join("\n")),
            source: None,
            is_profile: false,
        },
        sources: vec![model.source.clone()],
        modbus: None,
        canopen: Some(ir::CanOpenCaps {
            default_node_id: model.device.node_id.unwrap_or(1),
            lss: lss(&model.device),
            source: None,
        }),
        identity: None,
        lock: None,
        variants: Vec::new(),
        enums: Vec::new(),
        flags: Vec::new(),
        records: model.records.clone(),
        parameters: Vec::new(),
        cia402: None,
        state_machine: None,
        ramps: Vec::new(),
        mappings: Vec::new(),
        indexed: Vec::new(),
        refinements: Vec::new(),
        constants: Vec::new(),
        models: Vec::new(),
    }
}

/// The parameters of `entries` of the EDS `cited`; entries without a usable type are octet
/// strings, with a warning.
pub fn typed_parameters(
    mut entries: Vec<EdsEntry>,
    cited: &Arc<ir::CitedDoc>,
    diagnostics: &mut Vec<Diagnostic>,
) -> Vec<ir::Parameter> {
    // Sized up front: parameters are large, and growing a vector of thousands moves megabytes.
    let mut parameters = Vec::with_capacity(entries.len());
    for e in &mut entries {
        let ty = e.usable_type(diagnostics);
        parameters.push(e.take_parameter(cited, ty, diagnostics));
    }
    parameters
}

/// LSS support as `[DeviceInfo] LSS_Supported` states it (CiA 306); the EDS is the citation.
pub(crate) fn lss(device: &DeviceInfo) -> Option<crate::ir::Lss> {
    device.lss_supported.then(|| crate::ir::Lss {
        source: None,
        span: crate::diagnostic::Span::default(),
    })
}

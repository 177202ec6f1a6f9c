//! What must hold of any device the generator accepts, whatever description it came from.

use std::collections::BTreeSet;
use std::path::Path;

use drivegen::diagnostic::Files;
use drivegen::ir::Device;
use drivegen::{emit, Severity};

/// The generated Rust parses with `syn`, every parameter gets its own accessor name, and the
/// device's EDS export reads back with (at least) the same CANopen objects.
pub fn check(device: &Device) {
    let source = emit::rust::generate(device, "fuzz");
    if let Err(e) = syn::parse_file(&source) {
        panic!("generated code does not parse: {e}\n{source}");
    }
    let mut methods = BTreeSet::new();
    for p in &device.parameters {
        let method = drivegen::names::method(&p.name);
        assert!(
            methods.insert(method.clone()),
            "two parameters named `{method}`"
        );
    }
    let exported = drivegen::eds::export(device);
    let again = eds_device(exported.as_bytes());
    let lost: Vec<_> = objects(device)
        .difference(&objects(&again.device))
        .copied()
        .collect();
    assert!(
        lost.is_empty(),
        "objects {lost:04X?} lost in the EDS export:\n{exported}"
    );
}

/// The (index, subindex) of every CANopen address of `device`'s parameters.
pub fn objects(device: &Device) -> BTreeSet<(u16, u8)> {
    device
        .parameters
        .iter()
        .flat_map(|p| p.canopen.iter().map(|a| (a.index, a.subindex)))
        .collect()
}

/// A device read from EDS bytes, as `drivegen check x.eds` reads it.
pub struct EdsDevice {
    /// The device, valid or not.
    pub device: Device,
    /// Whether reading or validating it found an error.
    pub has_errors: bool,
}

/// Reads EDS `bytes` into a device and validates it; every diagnostic is rendered once.
pub fn eds_device(bytes: &[u8]) -> EdsDevice {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let model =
        drivegen::eds::read_bytes(Path::new("fuzz.eds"), bytes, &mut files, &mut diagnostics);
    let mut device = drivegen::eds::empty_device("Fuzz", &model);
    device.parameters =
        drivegen::eds::typed_parameters(model.entries, &model.cited, &mut diagnostics);
    diagnostics.extend(drivegen::validate::validate(&device));
    for d in &diagnostics {
        let _ = d.render(&files);
    }
    EdsDevice {
        has_errors: diagnostics.iter().any(|d| d.severity == Severity::Error),
        device,
    }
}

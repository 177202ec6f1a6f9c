//! IR to EDS (CiA 306 v4.0): the CANopen objects of a description, loadable by CANopen masters.
//!
//! The output is what strict readers (python canopen) accept: canonical key spelling, no BOM,
//! every sub-section after its parent, no duplicate section or key. Only the default variant's
//! addresses are written. `$NODEID`-relative defaults stay relative. Declared PDOs add their
//! communication and mapping objects ([`super::pdo_objects`]).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::data_type::to_code;
use super::pdo_objects::pdo_objects;
use crate::ir::{self, Device, Number, Parameter};

/// One variable to write.
struct Entry<'d> {
    parameter: &'d Parameter,
    address: &'d ir::ObjectAddress,
}

/// The EDS text of `device`'s CANopen objects.
pub fn export(device: &Device) -> String {
    let pdo = pdo_objects(device);
    let objects = objects(device, &pdo.parameters);
    let records: Vec<&ir::Record> = device.records.iter().chain(&pdo.records).collect();
    let mut out = String::new();
    header(&mut out, device);
    object_lists(&mut out, &objects);
    for (index, entries) in &objects {
        let record = records.iter().copied().find(|r| r.index == *index);
        object(&mut out, record, *index, entries);
    }
    out
}

/// CANopen addresses of the default variant, grouped by index, first description wins; then
/// the objects derived from PDOs.
fn objects<'d>(
    device: &'d Device,
    derived: &'d [Parameter],
) -> BTreeMap<u16, BTreeMap<u8, Entry<'d>>> {
    let default_variant = device.variants.first().map(|v| v.name.as_str());
    let in_default = |v: &Option<String>| v.is_none() || v.as_deref() == default_variant;
    let mut objects: BTreeMap<u16, BTreeMap<u8, Entry<'_>>> = BTreeMap::new();
    let described = device.parameters.iter().filter(|p| {
        p.variants.is_empty() || default_variant.is_some_and(|d| p.variants.iter().any(|v| v == d))
    });
    for parameter in described.chain(derived) {
        for address in parameter.canopen.iter().filter(|a| in_default(&a.variant)) {
            objects
                .entry(address.index)
                .or_default()
                .entry(address.subindex)
                .or_insert(Entry { parameter, address });
        }
    }
    objects
}

fn header(out: &mut String, device: &Device) {
    let id = &device.device;
    let _ = writeln!(out, "[FileInfo]");
    let _ = writeln!(
        out,
        "FileName={}.eds",
        clean(&crate::names::snake(&id.handle))
    );
    let _ = writeln!(out, "FileVersion=1");
    let _ = writeln!(out, "FileRevision=0");
    let _ = writeln!(out, "EDSVersion=4.0");
    let _ = writeln!(out, "Description={}", clean(&id.name));
    let _ = writeln!(out, "CreatedBy=drivegen {}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(out, "\n[DeviceInfo]");
    let _ = writeln!(
        out,
        "VendorName={}",
        clean(id.vendor.as_deref().unwrap_or(""))
    );
    let _ = writeln!(out, "ProductName={}", clean(&id.name));
    // CiA 306 [DeviceInfo] LSS_Supported: the device is an LSS slave (CiA 305).
    if device.canopen.as_ref().is_some_and(|c| c.lss.is_some()) {
        let _ = writeln!(out, "LSS_Supported=1");
    }
    if let Some(doc) = &id.doc {
        let lines: Vec<&str> = doc.lines().collect();
        let _ = writeln!(out, "\n[Comments]\nLines={}", lines.len());
        for (i, line) in lines.iter().enumerate() {
            let _ = writeln!(out, "Line{}={}", i + 1, clean(line));
        }
    }
}

/// `[MandatoryObjects]`, `[OptionalObjects]` and `[ManufacturerObjects]` (CiA 306 §4.5).
fn object_lists(out: &mut String, objects: &BTreeMap<u16, BTreeMap<u8, Entry<'_>>>) {
    let mandatory = |i: u16| {
        crate::mandatory_objects::MANDATORY_OBJECTS
            .iter()
            .any(|(index, _, _)| *index == i)
    };
    let manufacturer = |i: u16| (0x2000..0x6000).contains(&i);
    let lists: [(&str, &dyn Fn(u16) -> bool); 3] = [
        ("MandatoryObjects", &mandatory),
        ("OptionalObjects", &|i| !mandatory(i) && !manufacturer(i)),
        ("ManufacturerObjects", &manufacturer),
    ];
    for (name, belongs) in lists {
        let indices: Vec<u16> = objects.keys().copied().filter(|&i| belongs(i)).collect();
        let _ = writeln!(out, "\n[{name}]\nSupportedObjects={}", indices.len());
        for (n, index) in indices.iter().enumerate() {
            let _ = writeln!(out, "{}=0x{index:04X}", n + 1);
        }
    }
}

fn object(
    out: &mut String,
    record: Option<&ir::Record>,
    index: u16,
    entries: &BTreeMap<u8, Entry<'_>>,
) {
    let single = entries.len() == 1 && entries.contains_key(&0);
    match (record, single, entries.get(&0)) {
        (None, true, Some(entry)) => variable(out, &format!("{index:04X}"), entry),
        _ => {
            let (name, code) = match record {
                Some(r) if r.kind == ir::RecordKind::Array => (r.name.as_str(), 0x8),
                Some(r) => (r.name.as_str(), 0x9),
                None => (
                    entries
                        .values()
                        .next()
                        .map_or("", |e| e.parameter.name.as_str()),
                    0x9,
                ),
            };
            let _ = writeln!(out, "\n[{index:04X}]");
            let _ = writeln!(out, "ParameterName={}", clean(name));
            let _ = writeln!(out, "ObjectType=0x{code:X}");
            let _ = writeln!(out, "SubNumber={}", entries.len());
            for (sub, entry) in entries {
                variable(out, &format!("{index:04X}sub{sub:X}"), entry);
            }
        }
    }
}

fn variable(out: &mut String, section: &str, entry: &Entry<'_>) {
    let p = entry.parameter;
    let a = entry.address;
    let _ = writeln!(out, "\n[{section}]");
    let _ = writeln!(out, "ParameterName={}", clean(&p.name));
    let _ = writeln!(out, "ObjectType=0x7");
    let _ = writeln!(out, "DataType=0x{:04X}", to_code(p.data_type));
    let _ = writeln!(out, "AccessType={}", access_type(a));
    if let Some(default) = p.default {
        let value = if p.default_plus_node_id {
            node_relative(default)
        } else {
            default.to_string()
        };
        let _ = writeln!(out, "DefaultValue={value}");
    }
    if let Some(range) = &p.range {
        let _ = writeln!(out, "LowLimit={}", range.min);
        let _ = writeln!(out, "HighLimit={}", range.max);
    }
    let _ = writeln!(out, "PDOMapping={}", u8::from(a.pdo != ir::Pdo::None));
}

/// CiA 306 access type; `rwr` / `rww` keep the PDO direction of a read-write object.
fn access_type(a: &ir::ObjectAddress) -> &'static str {
    match (a.constant, a.access.read, a.access.write, a.pdo) {
        (true, ..) => "const",
        (false, true, true, ir::Pdo::Tx) => "rwr",
        (false, true, true, ir::Pdo::Rx) => "rww",
        (false, true, true, _) => "rw",
        (false, false, true, _) => "wo",
        _ => "ro",
    }
}

/// `$NODEID+0x...`; with an explicit `+0x0` for the node id itself, since python canopen drops a
/// bare `$NODEID` default (it parses what is left after removing `$NODEID+`).
fn node_relative(offset: Number) -> String {
    match offset.as_int() {
        Some(o) if o >= 0 => format!("$NODEID+0x{o:X}"),
        _ => format!("$NODEID+{offset}"),
    }
}

/// One line of text: no line breaks, no `;` comment starts, no section brackets at the start.
fn clean(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() || c == ';' { ' ' } else { c })
        .collect::<String>()
        .trim()
        .trim_start_matches('[')
        .to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_cannot_break_out_of_its_line() {
        assert_eq!(clean("a\nb ; c\r"), "a b   c");
        assert_eq!(clean("[1000]"), "1000]");
    }

    #[test]
    fn node_relative_defaults_stay_relative() {
        assert_eq!(node_relative(Number::Int(0x180)), "$NODEID+0x180");
        assert_eq!(node_relative(Number::Int(0)), "$NODEID+0x0");
    }
}

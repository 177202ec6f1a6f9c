//! The rustdoc of a parameter: what it is, where it lives, its type, unit, access and citation.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use proc_macro2::TokenStream;
use quote::quote;

use crate::emit::doc;
use crate::ir::{
    Access, Citation, Command, CommandKind, Device, Effect, Parameter, Scale, Table, WordOrder,
};

fn access(a: Access) -> &'static str {
    match (a.read, a.write) {
        (true, true) => "read/write",
        (true, false) => "read-only",
        (false, true) => "write-only",
        (false, false) => "no access",
    }
}

/// The full doc text of a parameter's marker type.
pub fn text(p: &Parameter, device: &Device) -> String {
    let mut out = doc::escape(p.doc.as_deref().unwrap_or(&p.name));
    out.push_str("\n\n| | |\n|---|---|\n");
    let row = |out: &mut String, key: &str, value: String| {
        let _ = writeln!(out, "| {key} | {value} |");
    };
    for a in &p.modbus {
        let variant = a
            .variant
            .as_deref()
            .map(|v| format!(" (variant `{v}`)"))
            .unwrap_or_default();
        let words = match (a.words, a.word_order) {
            (1, _) => String::new(),
            (n, WordOrder::LowFirst) => format!(", {n} words, low word first"),
            (n, WordOrder::HighFirst) => format!(", {n} words, high word first"),
            (n, WordOrder::Text) => format!(", {n} words of text, in address order"),
        };
        let table = match a.table {
            Table::Input => "Input",
            Table::Holding => "Holding",
        };
        row(
            &mut out,
            "Modbus",
            format!(
                "{table} register `0x{:04X}`{words}, {}{variant}",
                a.address,
                access(a.access)
            ),
        );
    }
    if let Some(note) = p.safety_write_note() {
        row(&mut out, "Safety", note.into());
    }
    if let Some(stops) = &p.stops {
        let which = match &stops.patterns {
            None => "every write".to_owned(),
            Some(patterns) => {
                let each: Vec<String> = patterns
                    .iter()
                    .map(|s| format!("`raw & {:#06x} == {:#06x}`", s.mask, s.value))
                    .collect();
                format!("a write with {}", each.join(" or "))
            }
        };
        let note = format!(
            "{which}: always sent, whatever the handle believes of locks, identity or variant"
        );
        row(&mut out, "Stops the drive", note);
    }
    for a in &p.canopen {
        row(
            &mut out,
            "CANopen",
            format!(
                "object `{:#06X}:{}`, {}{}",
                a.index,
                a.subindex,
                access(a.access),
                if a.constant { " (const)" } else { "" }
            )
            .replace("0X", "0x"),
        );
    }
    for a in &p.rs232 {
        row(
            &mut out,
            "RS-232",
            format!(
                "object `{:#06X}:{}`, {}",
                a.index,
                a.subindex,
                access(a.access)
            )
            .replace("0X", "0x"),
        );
    }
    let mut ty = format!("`{}`", p.data_type.name());
    if let Some(unit) = &p.unit {
        let _ = write!(ty, ", unit {}", doc::escape(unit));
    }
    match &p.scale {
        Some(Scale::Fixed(scale)) => {
            let (factor, offset) = (scale.factor, scale.offset);
            let _ = write!(
                ty,
                ", scale {}/{}",
                factor.numerator(),
                factor.denominator()
            );
            if offset != drivebus_model::Ratio::ZERO {
                let _ = write!(
                    ty,
                    ", offset {}/{}",
                    offset.numerator(),
                    offset.denominator()
                );
            }
        }
        Some(Scale::Runtime { expr, .. }) => {
            let _ = write!(ty, ", scale `{}` (read at run time)", doc::escape(expr));
        }
        None => {}
    }
    row(&mut out, "Type", ty);
    if let Some(r) = &p.range {
        row(&mut out, "Range (raw)", format!("{}..={}", r.min, r.max));
    }
    if !p.allowed.is_empty() {
        row(
            &mut out,
            "Allowed (raw)",
            p.allowed
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", "),
        );
    }
    match p.default {
        Some(d) if p.default_plus_node_id => {
            row(&mut out, "Default (raw)", format!("node id + {d}"));
            // Limits that hold on some node IDs only (a vendor EDS, issue #27): said where a user
            // of the generated crate reads about the default.
            if let Some(ids) = device.default_node_ids(p).filter(|ids| !ids.is_all()) {
                row(
                    &mut out,
                    "Node IDs",
                    format!("the default is a value this parameter accepts on node IDs {ids} only"),
                );
            }
        }
        Some(d) => row(&mut out, "Default (raw)", d.to_string()),
        None => {}
    }
    match p.effect {
        Effect::Immediate => {}
        Effect::AfterReset => row(&mut out, "Takes effect", "after a reset".into()),
        Effect::AfterStoreReset => row(&mut out, "Takes effect", "after store + reset".into()),
    }
    if let Some(c) = &p.command {
        row(
            &mut out,
            "Command",
            format!("{}; never retried", command_text(c)),
        );
    }
    if !p.variants.is_empty() {
        row(&mut out, "Variants", p.variants.join(", "));
    }
    if let Some(c) = &p.source {
        row(&mut out, "Source", citation(c, device));
        if let Some(example) = &c.example {
            row(&mut out, "Manual example", doc::escape(example));
        }
    }
    if let Some(e) = &p.erratum {
        row(&mut out, "Erratum", doc::escape(e).replace('\n', " "));
    }
    out
}

/// A citation as doc text (escaped): the manual's title and file, section and line.
pub fn citation(c: &Citation, device: &Device) -> String {
    let title = device
        .sources
        .iter()
        .find(|s| s.id == c.doc())
        .map_or(c.file(), |s| s.title.as_str());
    let mut cite = format!("{} (`{}`)", doc::escape(title), doc::escape(c.file()));
    if let Some(section) = &c.section {
        let _ = write!(cite, " §{}", doc::escape(section));
    }
    if let Some(line) = c.line {
        let _ = write!(cite, ", line {line}");
    }
    cite
}

/// What a command register does, in words: `store, trigger value 1`.
fn command_text(c: &Command) -> String {
    let kind = match c.kind {
        CommandKind::Store => "store",
        CommandKind::RestoreFactory => "restore factory settings",
        CommandKind::Reset => "reset",
        CommandKind::Action => "action",
    };
    match c.value {
        Some(value) => format!("{kind}, trigger value {value}"),
        None => kind.to_owned(),
    }
}

/// `#[doc(alias = "...")]` with the names and addresses the manuals print, so rustdoc's search
/// finds a parameter by them: the manual's own name (`BUS DC LINK`, from the citation's `name`),
/// `0x0064` for a Modbus register, `6041h` and `0x6041` for an object (and `6041h:01` for a
/// sub-index other than 0).
pub fn aliases(p: &Parameter) -> TokenStream {
    let manual_name = p.source.as_ref().and_then(|c| c.name.clone());
    let modbus = p.modbus.iter().map(|a| format!("0x{:04X}", a.address));
    let objects = p.canopen.iter().chain(&p.rs232).flat_map(|a| {
        let sub = (a.subindex != 0).then(|| format!("{:04X}h:{:02X}", a.index, a.subindex));
        [
            Some(format!("{:04X}h", a.index)),
            Some(format!("0x{:04X}", a.index)),
            sub,
        ]
        .into_iter()
        .flatten()
    });
    let unique: BTreeSet<String> = manual_name
        .into_iter()
        .chain(modbus)
        .chain(objects)
        .collect();
    let attrs = unique.iter().map(|alias| quote! { #[doc(alias = #alias)] });
    quote! { #( #attrs )* }
}

#[cfg(test)]
mod tests {
    /// A node-relative default whose limits hold on some node IDs only says which, where the
    /// default is documented (the vendor EDS of issue #27 item 7).
    #[test]
    fn a_narrowed_node_relative_default_names_its_node_ids() {
        let checked = crate::check(std::path::Path::new(
            "tests/eds/node_id_default_narrowed.eds",
        ));
        let device = checked.device.expect("the file checks, with warnings");
        let text = |name: &str| super::text(device.parameter(name).unwrap(), &device);
        let cob_id = text("cob_id_used_by_tpdo1");
        assert!(
            cob_id.contains("| Default (raw) | node id + 384 |"),
            "{cob_id}"
        );
        assert!(
            cob_id.contains("| Node IDs | the default is a value this parameter accepts on node IDs 1..=15 only |"),
            "{cob_id}"
        );
        assert!(text("gateway_id").contains("on node IDs 16..=32 only"));
        assert!(!text("transmission_type").contains("Node IDs"));
    }
}

//! The rustdoc of a parameter: what it is, where it lives, its type, unit, access and citation.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use proc_macro2::TokenStream;
use quote::quote;

use crate::emit::doc;
use crate::ir::{
    Access, Citation, Command, CommandKind, Device, Effect, Parameter, Scale, Table, WordOrder,
};
use crate::names;

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
    let mut rows: Vec<(&str, String)> = Vec::new();
    let row = |rows: &mut Vec<(&'static str, String)>, key: &'static str, value: String| {
        rows.push((key, value));
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
        let read_back = a
            .read_back_of
            .as_deref()
            .map(|owner| format!(", the register of `{owner}` read back"))
            .unwrap_or_default();
        row(
            &mut rows,
            "Modbus",
            format!(
                "{table} register `0x{:04X}`{words}, {}{variant}{read_back}",
                a.address,
                access(a.access)
            ),
        );
    }
    if let Some(note) = p.safety_write_note() {
        row(&mut rows, "Safety", note.into());
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
        row(&mut rows, "Stops the drive", note);
    }
    // A run's marker describes every sub-index of the run, not only its own first one.
    let run_end = device
        .indexed
        .iter()
        .find(|run| run.name == p.name)
        .map(|run| format!("..={}", run.last));
    for a in &p.canopen {
        row(
            &mut rows,
            "CANopen",
            format!(
                "object `{:#06X}:{}{}`, {}{}",
                a.index,
                a.subindex,
                run_end.as_deref().unwrap_or(""),
                access(a.access),
                if a.constant { " (const)" } else { "" }
            )
            .replace("0X", "0x"),
        );
    }
    if let Some(run) = device.indexed.iter().find(|run| run.name == p.name) {
        let marker = names::camel(&run.marker_name());
        let note = format!(
            "sub-indices {}..={}: `drive.{}(n)`; one of them as a type is \
             `drivebus::indexed::At<params::{marker}, N>`. This marker on its own is sub-index {}",
            run.first,
            run.last,
            names::method(&run.name),
            run.first
        );
        row(&mut rows, "Run", note);
    }
    for a in &p.rs232 {
        row(
            &mut rows,
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
    row(&mut rows, "Type", ty);
    if let Some(r) = &p.range {
        row(&mut rows, "Range (raw)", format!("{}..={}", r.min, r.max));
    }
    if !p.allowed.is_empty() {
        row(
            &mut rows,
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
            row(&mut rows, "Default (raw)", format!("node id + {d}"));
            // Limits that hold on some node IDs only (a vendor EDS, issue #27): said where a user
            // of the generated crate reads about the default.
            if let Some(ids) = device.default_node_ids(p).filter(|ids| !ids.is_all()) {
                row(
                    &mut rows,
                    "Node IDs",
                    format!("the default is a value this parameter accepts on node IDs {ids} only"),
                );
            }
        }
        Some(d) => row(&mut rows, "Default (raw)", d.to_string()),
        None => {}
    }
    match p.effect {
        Effect::Immediate => {}
        Effect::AfterReset => row(&mut rows, "Takes effect", "after a reset".into()),
        Effect::AfterStoreReset => row(&mut rows, "Takes effect", "after store + reset".into()),
    }
    if let Some(c) = &p.command {
        row(
            &mut rows,
            "Command",
            format!("{}; never retried", command_text(c)),
        );
    }
    if !p.variants.is_empty() {
        row(&mut rows, "Variants", p.variants.join(", "));
    }
    if let Some(c) = &p.source {
        row(&mut rows, "Source", citation(c, device));
        if let Some(example) = &c.example {
            row(&mut rows, "Manual example", doc::escape(example));
        }
    }
    if let Some(e) = &p.erratum {
        row(&mut rows, "Erratum", doc::escape(e).replace('\n', " "));
    }
    let mut out = doc::escape(p.doc.as_deref().unwrap_or(&p.name));
    table(&rows, &mut out);
    out
}

/// The longest row kept in the list: a row is one line, and a line of the generated source
/// stays within 100 columns (after `    /// `).
const ROW_WIDTH: usize = 92;

/// The short rows as a list (`- Type: ...`: a table would cost two more lines per parameter),
/// then each long one as a paragraph (`**Erratum:** ...`), which the emitter can wrap.
fn table(rows: &[(&str, String)], out: &mut String) {
    let line = |(key, value): &(&str, String)| format!("- {key}: {value}");
    let (short, long): (Vec<_>, Vec<_>) = rows
        .iter()
        .partition(|r| line(r).chars().count() <= ROW_WIDTH);
    if !short.is_empty() {
        out.push('\n');
        for r in short {
            let _ = write!(out, "\n{}", line(r));
        }
    }
    for (key, value) in long {
        let _ = write!(out, "\n\n**{key}:** {value}");
    }
}

/// A citation as doc text (escaped): the manual's title (its file when the description gives no
/// title), section and line. The file behind a title is in the description's `[device] source`.
pub fn citation(c: &Citation, device: &Device) -> String {
    // A described source by its id, its title given once in the `params` module's docs
    // (`sources_doc`); the table row stays one line.
    let mut cite = match device.sources.iter().find(|s| s.id == c.doc()) {
        Some(source) => format!("`{}`", doc::escape(&source.id)),
        None => format!("`{}`", doc::escape(c.file())),
    };
    if let Some(section) = &c.section {
        let _ = write!(cite, " §{}", doc::escape(section));
    }
    if let Some(line) = c.line {
        let _ = write!(cite, ", line {line}");
    }
    cite
}

/// The `params` module's list of the sources the parameters' and mappings' Source rows cite by
/// id; a source only an included profile's unselected objects cite is left out.
pub fn sources_doc(device: &Device) -> String {
    let parameters = device.parameters.iter().filter_map(|p| p.source.as_ref());
    let mappings = device.mappings.iter().filter_map(|m| m.source.as_ref());
    let cited: std::collections::BTreeSet<&str> =
        parameters.chain(mappings).map(|c| c.doc()).collect();
    let listed: Vec<String> = device
        .sources
        .iter()
        .filter(|s| cited.contains(s.id.as_str()))
        .map(|s| format!("`{}`: {}", doc::escape(&s.id), doc::escape(&s.title)))
        .collect();
    if listed.is_empty() {
        return String::new();
    }
    // One paragraph each, not a list: a long title wraps, and a list item's wrapped lines would
    // need an indentation the doc wrapper does not give.
    format!("\n\nSources cited by id:\n\n{}", listed.join("\n\n"))
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

/// `#[doc(alias("...", ...))]` with the names and addresses the manuals print, so rustdoc's search
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
    if unique.is_empty() {
        return quote! {};
    }
    quote! { #[doc(alias(#( #unique ),*))] }
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
            cob_id.contains("- Default (raw): node id + 384"),
            "{cob_id}"
        );
        assert!(
            cob_id.contains(
                "- Node IDs: the default is a value this parameter accepts on node IDs 1..=15 only"
            ),
            "{cob_id}"
        );
        assert!(text("gateway_id").contains("on node IDs 16..=32 only"));
        assert!(!text("transmission_type").contains("Node IDs"));
    }
}

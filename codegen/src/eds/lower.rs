//! EDS objects to IR records and parameters, with names derived from `ParameterName` and every
//! value citing its EDS line.

use std::sync::Arc;

use super::data_type::{from_code, Code, UNSIZED_CAPACITY};
use super::dictionary::{Dictionary, ObjectKind, Variable};
use super::names::{repeated, snake_name, unique_names, Address, NameList};
use super::node_id::EdsValue;
use crate::diagnostic::{Diagnostic, FileId, Files, Span};
use crate::ir::{self, DataType, Number};

/// The `[[source]]` id under which EDS-derived values cite the EDS file.
pub const EDS_SOURCE_ID: &str = "eds";

const RULE_VALUE: &str = "eds_values";
const RULE_TYPE: &str = "eds_data_type";

/// Why an entry has no usable type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TypeProblem {
    /// No `DataType` key (or an unreadable one, already reported).
    Missing,
    /// A reserved or unknown code.
    Unsupported(u16),
}

/// One EDS variable, ready to become a parameter once its type is known.
#[derive(Debug, Clone)]
pub struct EdsEntry {
    /// Object index.
    pub index: u16,
    /// The record it is a member of.
    pub record: Option<String>,
    /// snake_case name, unique among the EDS's names.
    pub name: String,
    /// The EDS variable.
    pub variable: Variable,
    /// Its type, unless the EDS does not give one.
    pub data_type: Result<DataType, TypeProblem>,
}

/// Everything an EDS contributes to a device.
#[derive(Debug, Clone)]
pub struct EdsModel {
    /// The EDS as a cited source.
    pub source: ir::SourceDoc,
    /// The EDS as citations name it, shared by all of them (entries do not hold it: every
    /// reference count touched per entry costs an atomic operation).
    pub cited: Arc<ir::CitedDoc>,
    /// Identity read from `[DeviceInfo]` / `[DeviceComissioning]` / `[Comments]`.
    pub device: super::dictionary::DeviceInfo,
    /// ARRAY and RECORD objects.
    pub records: Vec<ir::Record>,
    /// Every variable.
    pub entries: Vec<EdsEntry>,
}

/// Lowers a dictionary read from file `file`.
pub fn lower(dictionary: Dictionary, file: FileId, files: &Files) -> EdsModel {
    let Dictionary {
        device,
        objects,
        variables,
    } = dictionary;
    let path = files.path(file);
    let file_name = path.display().to_string();
    let source = ir::SourceDoc {
        id: EDS_SOURCE_ID.into(),
        file: file_name.clone(),
        title: device
            .product_name
            .clone()
            .map_or_else(|| "EDS".into(), |p| format!("{p} EDS")),
        standard: false,
    };
    let cited = ir::CitedDoc::shared(EDS_SOURCE_ID, &file_name);
    let cite = |span: &Span, line: u32, section: String| ir::Citation {
        cited: Arc::clone(&cited),
        section: Some(section),
        line: Some(line),
        example: None,
        name: None,
        span: span.clone(),
    };
    let is_record = |kind| matches!(kind, ObjectKind::Array | ObjectKind::Record);
    let mut records = Vec::with_capacity(objects.iter().filter(|o| is_record(o.kind)).count());
    let count = variables.len();
    // A snake name is about as long as the name, plus an underscore or two.
    let snake_bytes = variables.iter().map(|v| v.name.len() + 2).sum();
    let mut variables = variables.into_iter();
    let mut entries = Vec::with_capacity(count);
    let mut snakes = NameList::with_capacity(count, snake_bytes);
    for object in objects {
        let record_object = match object.kind {
            ObjectKind::Array | ObjectKind::Record => {
                let kind = if object.kind == ObjectKind::Array {
                    ir::RecordKind::Array
                } else {
                    ir::RecordKind::Record
                };
                let source = cite(&object.span, object.line, section_name(object.index, None));
                records.push(ir::Record {
                    name: snake_name(&object.name),
                    kind,
                    index: object.index,
                    doc: Some(object.name),
                    source: Some(source),
                    span: object.span,
                });
                true
            }
            ObjectKind::Var | ObjectKind::Domain => false,
        };
        let record = records
            .last()
            .filter(|_| record_object)
            .map(|r| r.name.as_str());
        let members = variables.by_ref().take(object.variables.len());
        entries.extend(members.map(|v| EdsEntry {
            index: object.index,
            record: record.map(str::to_owned),
            // Named once every name is known, by `name_uniquely`.
            name: {
                snakes.push_snake(&v.name);
                String::new()
            },
            data_type: entry_type(&v, object.kind),
            variable: v,
        }));
    }
    name_uniquely(&snakes, &mut entries, &mut records);
    EdsModel {
        source,
        cited,
        device,
        records,
        entries,
    }
}

fn entry_type(v: &Variable, kind: ObjectKind) -> Result<DataType, TypeProblem> {
    match (v.data_type, kind) {
        (Some(code), _) => match from_code(code, UNSIZED_CAPACITY) {
            Code::Type(t) => Ok(t),
            Code::Unsupported => Err(TypeProblem::Unsupported(code)),
        },
        (None, ObjectKind::Domain) => Ok(DataType::Octets(UNSIZED_CAPACITY)),
        (None, _) => Err(TypeProblem::Missing),
    }
}

/// `[1018sub1]`, or `[1018]` without a sub-index: how an EDS names the section of an object.
/// Written digit by digit: `format!` is costly when thousands of objects are cited.
fn section_name(index: u16, subindex: Option<u8>) -> String {
    let mut name = String::with_capacity(12);
    name.push('[');
    push_hex(&mut name, index, 4);
    if let Some(sub) = subindex {
        name.push_str("sub");
        push_hex(&mut name, sub.into(), 1);
    }
    name.push(']');
    name
}

/// `value` in upper-case hex, zero-padded to at least `min_digits` digits.
fn push_hex(out: &mut String, value: u16, min_digits: u32) {
    const DIGITS: &[u8; 16] = b"0123456789ABCDEF";
    let digits = (u16::BITS - value.leading_zeros())
        .div_ceil(4)
        .max(min_digits);
    for shift in (0..digits).rev() {
        let digit = (value >> (shift * 4)) & 0xF;
        out.push(char::from(DIGITS[usize::from(digit)]));
    }
}

/// Names every entry (see [`unique_names`]); records sharing a name get their index appended.
fn name_uniquely(snakes: &NameList, entries: &mut [EdsEntry], records: &mut [ir::Record]) {
    let names = unique_names(snakes, |i| Address {
        record: entries[i].record.as_deref(),
        index: entries[i].index,
        subindex: entries[i].variable.subindex,
    });
    for (e, name) in entries.iter_mut().zip(names) {
        e.name = name;
    }
    let records_clash = repeated(records.iter().map(|r| r.name.as_str()));
    for (r, _) in records
        .iter_mut()
        .zip(records_clash)
        .filter(|(_, clash)| *clash)
    {
        let renamed = format!("{}_{:04x}", r.name, r.index);
        for e in entries.iter_mut().filter(|e| e.index == r.index) {
            e.record = Some(renamed.clone());
        }
        r.name = renamed;
    }
}

impl EdsEntry {
    /// The EDS section it is written in: `[1018sub1]`, or `[1000]` for a VAR.
    pub fn section(&self) -> String {
        let sub = self.record.as_ref().map(|_| self.variable.subindex);
        section_name(self.index, sub)
    }

    /// The citation of its EDS line, in the EDS `cited`.
    pub fn citation(&self, cited: &Arc<ir::CitedDoc>) -> ir::Citation {
        ir::Citation {
            cited: Arc::clone(cited),
            section: Some(self.section()),
            line: Some(self.variable.line),
            example: None,
            name: None,
            span: self.variable.span.clone(),
        }
    }

    /// The diagnostic for an entry whose type is unknown: a warning, the entry being read as an
    /// octet string (see [`EdsEntry::usable_type`]).
    pub fn type_problem(&self, problem: TypeProblem) -> Diagnostic {
        const OVERLAY: &str = "give its `type` in an overlay `[[parameter]]` with this `canopen` address (`drivegen eds import` marks it)";
        let (message, help) = match problem {
            TypeProblem::Missing => (
                format!("object {} has no DataType", self.address()),
                format!("add `DataType=0x...` to the EDS, or {OVERLAY}"),
            ),
            TypeProblem::Unsupported(code) => (
                format!(
                    "object {} has DataType {code:#06X}, which CiA 301 reserves or does not define (vendor-specific?)",
                    self.address()
                ),
                OVERLAY.to_owned(),
            ),
        };
        Diagnostic::error(RULE_TYPE, self.variable.span.clone(), message)
            .warning()
            .label("read as an octet string (DOMAIN)")
            .help(help)
    }

    /// Its type; when the EDS gives none usable, an octet string of unknown length, with a
    /// warning (the overlay may give the real `type`).
    pub fn usable_type(&self, diagnostics: &mut Vec<Diagnostic>) -> DataType {
        match self.data_type {
            Ok(ty) => ty,
            Err(problem) => {
                push_once_per_range(self, diagnostics, self.type_problem(problem));
                DataType::Octets(UNSIZED_CAPACITY)
            }
        }
    }

    /// `0x1018 sub 1`, or `0x2300 subs 1..=24` for the shared description of a compact array.
    pub fn address(&self) -> String {
        match self.variable.compact {
            Some(count) => format!("{:#06X} subs 1..={count}", self.index),
            None => format!("{:#06X} sub {}", self.index, self.variable.subindex),
        }
    }

    /// The parameter this entry of the EDS `cited` describes, with type `ty`.
    pub fn parameter(
        &self,
        cited: &Arc<ir::CitedDoc>,
        ty: DataType,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> ir::Parameter {
        let names = Names {
            name: self.name.clone(),
            record: self.record.clone(),
            doc: self.doc(),
            source: self.citation(cited),
        };
        self.parameter_named(names, ty, diagnostics)
    }

    /// [`EdsEntry::parameter`], moving the entry's strings instead of copying them: a vector of
    /// entries becomes parameters without moving each (large) entry out of it first. The entry
    /// is left without its name, record and doc.
    pub(super) fn take_parameter(
        &mut self,
        cited: &Arc<ir::CitedDoc>,
        ty: DataType,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> ir::Parameter {
        // The citation first: it names the section by whether the entry is a record member.
        let source = self.citation(cited);
        let names = Names {
            name: std::mem::take(&mut self.name),
            record: self.record.take(),
            doc: self.take_doc(),
            source,
        };
        self.parameter_named(names, ty, diagnostics)
    }

    /// `Description`, or else `ParameterName`.
    fn doc(&self) -> String {
        let v = &self.variable;
        v.description.clone().unwrap_or_else(|| v.name.clone())
    }

    /// [`EdsEntry::doc`], moved out of the entry.
    fn take_doc(&mut self) -> String {
        let v = &mut self.variable;
        v.description
            .take()
            .unwrap_or_else(|| std::mem::take(&mut v.name))
    }

    fn parameter_named(
        &self,
        names: Names,
        ty: DataType,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> ir::Parameter {
        let v = &self.variable;
        let (access, constant, pdo) = self.access(diagnostics);
        let values = self.values(ty, diagnostics);
        let (default, default_plus_node_id, default_span) = match values.default {
            Some((EdsValue::Number(n), span)) => (Some(n), false, Some(span)),
            Some((EdsValue::NodeIdPlus(n), span)) => (Some(Number::Int(n)), true, Some(span)),
            None => (None, false, None),
        };
        ir::Parameter {
            name: names.name,
            doc: Some(names.doc),
            data_type: ty,
            unit: None,
            scale: None,
            default,
            default_plus_node_id,
            range: values.range,
            allowed: Vec::new(),
            enumeration: None,
            flags: None,
            record: names.record,
            modbus: Vec::new(),
            canopen: vec![ir::ObjectAddress {
                index: self.index,
                subindex: v.subindex,
                access,
                constant,
                pdo,
                variant: None,
                span: v.span.clone(),
            }],
            rs232: Vec::new(),
            effect: ir::Effect::Immediate,
            command: None,
            variants: Vec::new(),
            source: Some(names.source),
            erratum: None,
            safety: false,
            bounds: None,
            stops: None,
            spans: ir::ParameterSpans {
                name: v.span.clone(),
                data_type: v.span.clone(),
                default: default_span,
                range: values.range_span,
                ..Default::default()
            },
        }
    }

    fn access(&self, diagnostics: &mut Vec<Diagnostic>) -> (ir::Access, bool, ir::Pdo) {
        let v = &self.variable;
        let written = v.access.as_ref().map_or("", |t| &*t.value);
        let text = canonical_access(written);
        let (access, constant) = match text {
            "ro" => (ir::Access::READ, false),
            "wo" => (ir::Access::WRITE, false),
            "rw" | "rwr" | "rww" => (ir::Access::READ_WRITE, false),
            "const" => (ir::Access::READ, true),
            _ => {
                let span = v
                    .access
                    .as_ref()
                    .map_or(v.span.clone(), |t| t.span(v.span.file));
                let message = if written.is_empty() {
                    format!("object {} has no AccessType; read as `ro`", self.address())
                } else {
                    format!("unknown AccessType `{written}`; read as `ro`")
                };
                push_once_per_range(
                    self,
                    diagnostics,
                    Diagnostic::error(RULE_VALUE, span, message)
                        .warning()
                        .help("CiA 306 access types: ro, wo, rw, rwr, rww, const"),
                );
                (ir::Access::READ, false)
            }
        };
        let pdo = match (v.pdo_mapping, text) {
            (false, _) => ir::Pdo::None,
            (true, "rww" | "wo") => ir::Pdo::Rx,
            (true, "rw") => ir::Pdo::Both,
            (true, _) => ir::Pdo::Tx,
        };
        (access, constant, pdo)
    }
}

/// Pushes `d`, a diagnostic about `entry`, unless `entry` is a sub-index of a compact array and
/// the same diagnostic was reported already: the sub-indices of a compact array share one
/// description, whose problems are reported once, naming the range.
pub(super) fn push_once_per_range(
    entry: &EdsEntry,
    diagnostics: &mut Vec<Diagnostic>,
    mut d: Diagnostic,
) {
    let v = &entry.variable;
    let own_value = v.parameter_value.as_ref().filter(|_| v.own_value);
    let own_span = own_value.map(|t| t.span(v.span.file));
    if v.compact.is_none() || d.span == own_span {
        diagnostics.push(d);
        return;
    }
    let range = entry.address();
    if !d.message.contains(&range) {
        d.message = format!("{} (object {range}, a compact array)", d.message);
    }
    if !diagnostics.contains(&d) {
        diagnostics.push(d);
    }
}

/// The strings a parameter takes from its entry.
struct Names {
    name: String,
    record: Option<String>,
    doc: String,
    source: ir::Citation,
}

/// The lower-case CiA 306 spelling of an access type written in any case; `""` when unknown.
fn canonical_access(written: &str) -> &'static str {
    ["ro", "wo", "rw", "rwr", "rww", "const"]
        .into_iter()
        .find(|a| written.eq_ignore_ascii_case(a))
        .unwrap_or("")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_are_named_in_upper_case_hex() {
        assert_eq!(section_name(0x1018, Some(1)), "[1018sub1]");
        assert_eq!(section_name(0x00a, Some(0x1f)), "[000Asub1F]");
        assert_eq!(section_name(0xFFFF, None), "[FFFF]");
        assert_eq!(section_name(0x2000, Some(0)), "[2000sub0]");
    }
}

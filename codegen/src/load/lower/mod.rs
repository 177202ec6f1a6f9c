//! Lowering: the raw, spanned file contents become the IR. Problems of form (an unknown type name,
//! a malformed scale, a citation of an unknown manual) are reported here; rules that relate
//! several values to each other are validation passes.

use std::collections::BTreeMap;
use std::sync::Arc;

mod commands;
mod control;
mod identity;
mod lock;
mod mapping;
mod models;
mod occupies;
mod overlay;
mod ramps;
mod read_blocks;
mod refine;
mod stops;
mod subindex_range;

use toml::Spanned;

use super::only::{Filter, Kind};
use super::raw::*;
use super::LoadedFile;
use crate::diagnostic::{Diagnostic, FileId, Files, Span};
use crate::eds::EdsModel;
use crate::ir::{self, DataType, Expr, Number};
use drivebus_model::Ratio;
use overlay::Overlay;

/// Turns loaded files into one device model. Returns `None` if the root file has neither
/// `[device]` nor `[profile]`. With `eds`, the root file is an overlay of that EDS: its
/// `[[parameter]]` entries with a `canopen` address refine the EDS object at that address, and the
/// objects it does not mention are added as the EDS describes them.
pub fn lower(
    loaded: Vec<LoadedFile>,
    files: &Files,
    eds: Option<&EdsModel>,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<ir::Device> {
    let mut files_iter = loaded.into_iter();
    let root = files_iter.next()?;
    let mut cx = Lowering {
        diagnostics,
        sources: BTreeMap::new(),
        file: root.id,
        overlay: eds.map(|m| Overlay::new(m, root.id)),
    };
    let mut device = cx.device(&root.raw, files)?;
    if let Some(model) = eds {
        let source = &model.source;
        cx.sources.insert(
            source.id.clone(),
            ir::CitedDoc::shared(&source.id, &source.file),
        );
        device.sources.push(model.source.clone());
    }
    let included: Vec<LoadedFile> = files_iter.collect();
    for file in std::iter::once(&root).chain(&included) {
        cx.file = file.id;
        cx.sources(&file.raw, &mut device);
    }
    for (i, file) in std::iter::once(&root).chain(&included).enumerate() {
        cx.file = file.id;
        let keep = Filter::new(file, cx.diagnostics);
        if i == 0 {
            cx.root_items(&file.raw, &mut device);
        } else {
            cx.refuse_included_mappings(&file.raw);
        }
        cx.items(&file.raw, &keep, &mut device);
        cx.models(&file.raw, &mut device);
    }
    for file in std::iter::once(&root).chain(&included) {
        cx.file = file.id;
        cx.refinements(&file.raw, &mut device);
    }
    cx.command_enums(&mut device);
    if let Some(overlay) = cx.overlay.take() {
        overlay.finish(&mut device, cx.diagnostics);
    }
    Some(device)
}

pub(super) struct Lowering<'d> {
    pub(super) diagnostics: &'d mut Vec<Diagnostic>,
    /// Declared sources by id, shared by every citation of them.
    sources: BTreeMap<String, Arc<ir::CitedDoc>>,
    pub(super) file: FileId,
    /// The EDS the root file is an overlay of.
    pub(super) overlay: Option<Overlay<'d>>,
}

const VALUE_RULE: &str = "values_are_well_formed";

impl Lowering<'_> {
    pub(super) fn span<T>(&self, s: &Spanned<T>) -> Span {
        Span::new(self.file, s.span())
    }

    fn error(&mut self, rule: &'static str, span: Span, message: impl Into<String>) {
        self.diagnostics
            .push(Diagnostic::error(rule, span, message));
    }

    fn error_help(
        &mut self,
        rule: &'static str,
        span: Span,
        message: impl Into<String>,
        help: impl Into<String>,
    ) {
        self.diagnostics
            .push(Diagnostic::error(rule, span, message).help(help));
    }

    fn device(&mut self, raw: &RawFile, files: &Files) -> Option<ir::Device> {
        if *raw.format.get_ref() != 1 {
            let span = self.span(&raw.format);
            self.error_help(
                VALUE_RULE,
                span,
                "unsupported description format",
                "this drivegen reads `format = 1`",
            );
        }
        let identity = match (&raw.device, &raw.profile) {
            (Some(d), None) => ir::Identity {
                name: d.name.get_ref().clone(),
                handle: d.handle.get_ref().clone(),
                vendor: d.vendor.clone(),
                firmware: d.firmware.clone(),
                doc: d.doc.clone(),
                source: None,
                is_profile: false,
            },
            (None, Some(p)) => ir::Identity {
                name: p.name.get_ref().clone(),
                handle: String::new(),
                vendor: None,
                firmware: None,
                doc: p.doc.clone(),
                source: None,
                is_profile: true,
            },
            _ => {
                self.diagnostics.push(
                    Diagnostic::error(
                        VALUE_RULE,
                        Span::new(self.file, 0..0),
                        format!(
                            "`{}` needs exactly one of `[device]` or `[profile]`",
                            files.path(self.file).display()
                        ),
                    )
                    .help("a drive description has `[device]`; a shared fragment has `[profile]`"),
                );
                return None;
            }
        };
        Some(ir::Device {
            schema: ir::IR_SCHEMA_VERSION,
            device: identity,
            sources: Vec::new(),
            modbus: None,
            canopen: None,
            identity: None,
            lock: None,
            variants: Vec::new(),
            enums: Vec::new(),
            flags: Vec::new(),
            records: Vec::new(),
            parameters: Vec::new(),
            cia402: None,
            state_machine: None,
            ramps: Vec::new(),
            mappings: Vec::new(),
            indexed: Vec::new(),
            refinements: Vec::new(),
            constants: Vec::new(),
            models: Vec::new(),
        })
    }

    fn sources(&mut self, raw: &RawFile, device: &mut ir::Device) {
        for source in &raw.source {
            let id = source.id.get_ref();
            match self.sources.get(id) {
                Some(cited) if cited.file != source.file => {
                    let span = self.span(&source.id);
                    self.error(
                        "sources_are_unique",
                        span,
                        format!("source `{id}` is declared twice with different files"),
                    );
                }
                Some(_) => {}
                None => {
                    let cited = if source.standard {
                        ir::CitedDoc::standard(id, &source.file)
                    } else {
                        ir::CitedDoc::shared(id, &source.file)
                    };
                    self.sources.insert(id.clone(), cited);
                    device.sources.push(ir::SourceDoc {
                        id: id.clone(),
                        file: source.file.clone(),
                        title: source.title.clone(),
                        standard: source.standard,
                    });
                }
            }
        }
    }

    /// Identity citation, capabilities, variants, control, ramps and PDO mappings come from the root
    /// file only.
    fn root_items(&mut self, raw: &RawFile, device: &mut ir::Device) {
        device.device.source = raw
            .device
            .as_ref()
            .and_then(|d| d.source.as_ref())
            .or(raw.profile.as_ref().and_then(|p| p.source.as_ref()))
            .and_then(|c| self.citation(c));
        device.modbus = raw.modbus.as_ref().map(|m| self.modbus_caps(m));
        device.canopen = raw.canopen.as_ref().map(|c| self.canopen_caps(c));
        device.identity = raw.identity.as_ref().map(|i| self.expected_identity(i));
        device.lock = self.lock(raw.lock.as_ref(), &raw.unlock, raw.watchdog.as_ref());
        device.variants = raw.variant.iter().map(|v| self.variant(v)).collect();
        device.cia402 = raw.cia402.as_ref().map(|c| self.cia402(c));
        device.mappings = self.mappings(raw);
        device.state_machine = raw
            .state_machine
            .as_ref()
            .map(|m| self.state_machine(m, &raw.state, &raw.transition));
        device.ramps = raw.ramp.iter().filter_map(|r| self.ramp(r)).collect();
        if raw.state_machine.is_none() {
            if let Some(stray) = raw
                .state
                .first()
                .map(|s| self.span(s))
                .or(raw.transition.first().map(|t| self.span(t)))
            {
                self.error_help(
                    VALUE_RULE,
                    stray,
                    "`[[state]]` and `[[transition]]` need a `[state_machine]`",
                    "add `[state_machine]` with `name`, `status` and `command`",
                );
            }
        }
    }

    fn items(&mut self, raw: &RawFile, keep: &Filter, device: &mut ir::Device) {
        let modbus_order = device
            .modbus
            .as_ref()
            .map_or(ir::WordOrder::HighFirst, |m| m.word_order);
        for e in raw
            .enums
            .iter()
            .filter(|e| keep.keeps(Kind::Enum, e.name.get_ref()))
        {
            if let Some(e) = self.enumeration(e) {
                device.enums.push(e);
            }
        }
        for f in raw
            .flags
            .iter()
            .filter(|f| keep.keeps(Kind::Flags, f.name.get_ref()))
        {
            if let Some(f) = self.flags(f) {
                device.flags.push(f);
            }
        }
        for r in raw
            .record
            .iter()
            .filter(|r| keep.keeps(Kind::Record, r.name.get_ref()))
        {
            if let Some(r) = self.record(r) {
                device.records.push(r);
            }
        }
        for p in raw
            .parameter
            .iter()
            .filter(|p| keep.keeps(Kind::Parameter, p.name.get_ref()))
        {
            if let Some(lowered) = self.parameter(p, modbus_order) {
                self.push_expanded(p, lowered, device);
            }
        }
    }

    fn citation(&mut self, raw: &Spanned<RawCitation>) -> Option<ir::Citation> {
        let c = raw.get_ref();
        let doc = c.doc.get_ref();
        let Some(cited) = self.sources.get(doc).cloned() else {
            let span = self.span(&c.doc);
            let known: Vec<&str> = self.sources.keys().map(String::as_str).collect();
            self.error_help(
                "citations_resolve",
                span,
                format!("source `{doc}` is not declared"),
                format!(
                    "declare it with [[source]] id = \"{doc}\"; declared: {}",
                    if known.is_empty() {
                        "none".into()
                    } else {
                        known.join(", ")
                    }
                ),
            );
            return None;
        };
        let line = match &c.line {
            Some(l) if *l.get_ref() < 1 || *l.get_ref() > u32::MAX as i64 => {
                let span = self.span(l);
                self.error(VALUE_RULE, span, "a line number starts at 1");
                None
            }
            Some(l) => Some(*l.get_ref() as u32),
            None => None,
        };
        Some(ir::Citation {
            cited,
            section: c.section.clone(),
            line,
            example: c.example.clone(),
            name: c.name.clone(),
            span: self.span(raw),
        })
    }

    fn int_in<T: TryFrom<i64>>(&mut self, value: &Spanned<i64>, what: &str) -> Option<T> {
        let v = *value.get_ref();
        let converted = T::try_from(v).ok();
        if converted.is_none() {
            let span = self.span(value);
            self.error(VALUE_RULE, span, format!("{what} {v} is out of range"));
        }
        converted
    }

    fn word_order(&mut self, text: &str, span: Span) -> Option<ir::WordOrder> {
        match text {
            "high-first" => Some(ir::WordOrder::HighFirst),
            "low-first" => Some(ir::WordOrder::LowFirst),
            other => {
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown word order `{other}`"),
                    "use \"high-first\" or \"low-first\"",
                );
                None
            }
        }
    }

    fn modbus_caps(&mut self, raw: &RawModbusCaps) -> ir::ModbusCaps {
        let int16 = |v: &Option<Spanned<i64>>, what: &str, default: u16, me: &mut Self| {
            v.as_ref()
                .and_then(|v| me.int_in::<u16>(v, what))
                .unwrap_or(default)
        };
        let max_read_registers = int16(&raw.max_read_registers, "max_read_registers", 125, self);
        let max_write_registers = int16(&raw.max_write_registers, "max_write_registers", 123, self);
        let functions = match &raw.functions {
            Some(f) => {
                let span = self.span(f);
                let codes: Vec<u8> = f
                    .get_ref()
                    .iter()
                    .filter_map(|&c| u8::try_from(c).ok())
                    .collect();
                if codes.len() != f.get_ref().len() {
                    self.error(VALUE_RULE, span, "function codes are bytes (1..=127)");
                }
                codes
            }
            None => vec![0x03, 0x04, 0x06, 0x10],
        };
        let word_order = match &raw.word_order {
            Some(w) => {
                let span = self.span(w);
                self.word_order(w.get_ref(), span)
                    .unwrap_or(ir::WordOrder::HighFirst)
            }
            None => ir::WordOrder::HighFirst,
        };
        let exception = |v: &Option<Spanned<i64>>, default: u8, me: &mut Self| {
            v.as_ref()
                .and_then(|v| me.int_in::<u8>(v, "exception code"))
                .unwrap_or(default)
        };
        ir::ModbusCaps {
            max_read_registers,
            max_write_registers,
            functions,
            broadcast: raw.broadcast.unwrap_or(false),
            read_gaps: raw.read_gaps.unwrap_or(true),
            word_order,
            illegal_address_exception: exception(&raw.illegal_address_exception, 0x02, self),
            illegal_value_exception: exception(&raw.illegal_value_exception, 0x03, self),
            read_blocks: raw
                .read_blocks
                .iter()
                .filter_map(|b| self.read_block(b))
                .collect(),
            exception_functions: self.exception_functions(raw),
            input_reads_holding: raw.input_reads_holding.unwrap_or(false),
            combined_commands: raw
                .combined_commands
                .as_ref()
                .and_then(|c| self.combined_commands(c)),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            register_lists: Default::default(),
        }
    }

    fn combined_commands(
        &mut self,
        raw: &Spanned<RawCombinedCommands>,
    ) -> Option<ir::CombinedCommands> {
        let c = raw.get_ref();
        let address = self.int_in::<u16>(&c.address, "combined_commands address")?;
        let refusal = self.int_in::<u8>(&c.refusal, "exception code")?;
        Some(ir::CombinedCommands {
            address,
            obeys: c.obeys.clone(),
            refusal,
            source: c.source.as_ref().and_then(|s| self.citation(s)),
            span: self.span(raw),
        })
    }

    fn canopen_caps(&mut self, raw: &RawCanOpenCaps) -> ir::CanOpenCaps {
        let default_node_id = raw
            .default_node_id
            .as_ref()
            .and_then(|n| self.int_in::<u8>(n, "node id"))
            .unwrap_or(1);
        ir::CanOpenCaps {
            default_node_id,
            lss: raw.lss.as_ref().map(|lss| ir::Lss {
                source: lss.get_ref().source.as_ref().and_then(|c| self.citation(c)),
                span: self.span(lss),
            }),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
        }
    }

    fn variant(&mut self, raw: &RawVariant) -> ir::Variant {
        ir::Variant {
            name: raw.name.get_ref().clone(),
            doc: raw.doc.clone(),
            selected_by: raw.selected_by.as_ref().map(|s| ir::VariantSelector {
                parameter: s.get_ref().parameter.clone(),
                value: s.get_ref().value,
                span: self.span(s),
            }),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&raw.name),
        }
    }

    pub(super) fn data_type(
        &mut self,
        ty: &Spanned<String>,
        length: Option<&Spanned<i64>>,
    ) -> Option<DataType> {
        let len = length.map_or(0, |l| *l.get_ref());
        let parsed = DataType::parse(ty.get_ref(), u16::try_from(len).unwrap_or(0));
        if parsed.is_none() {
            let span = self.span(ty);
            self.error_help(
                "types_are_known",
                span,
                format!("unknown type `{}`", ty.get_ref()),
                "use bool, u8..u64, i8..i64 (also 24/40/48/56 bits), f32, f64, string or octets",
            );
        }
        parsed
    }

    fn integer_type(&mut self, ty: &Spanned<String>, what: &str) -> Option<DataType> {
        let parsed = self.data_type(ty, None)?;
        if !parsed.is_integer() {
            let span = self.span(ty);
            self.error(
                "types_are_known",
                span,
                format!("{what} need an integer type, not `{}`", ty.get_ref()),
            );
            return None;
        }
        Some(parsed)
    }

    fn enumeration(&mut self, raw: &RawEnum) -> Option<ir::Enum> {
        let data_type = self.integer_type(&raw.ty, "enumerations")?;
        let values = raw
            .values
            .iter()
            .map(|v| {
                let inner = v.get_ref();
                ir::EnumValue {
                    name: inner.name.get_ref().clone(),
                    value: *inner.value.get_ref(),
                    doc: inner.doc.clone(),
                    class: inner.class.map(|class| match class {
                        RawValueClass::Fault => ir::ValueClass::Fault,
                        RawValueClass::Warning => ir::ValueClass::Warning,
                    }),
                    led: inner.led.as_ref().and_then(|led| self.led_code(led)),
                    meaning: inner.meaning.clone(),
                    span: self.span(&inner.value),
                }
            })
            .collect();
        Some(ir::Enum {
            name: raw.name.get_ref().clone(),
            data_type,
            doc: raw.doc.clone(),
            values,
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            erratum: raw.erratum.clone(),
            span: self.span(&raw.name),
        })
    }

    /// `led = [first, second]`: exactly two blink counts.
    fn led_code(&mut self, led: &Spanned<Vec<u8>>) -> Option<[u8; 2]> {
        match led.get_ref().as_slice() {
            &[first, second] => Some([first, second]),
            _ => {
                let span = self.span(led);
                self.error(
                    VALUE_RULE,
                    span,
                    "an LED code is two blink counts, `[first, second]`",
                );
                None
            }
        }
    }

    fn flags(&mut self, raw: &RawFlags) -> Option<ir::Flags> {
        let data_type = self.integer_type(&raw.ty, "flags")?;
        let bits = raw
            .bits
            .iter()
            .filter_map(|b| {
                let inner = b.get_ref();
                let bit = self.int_in::<u32>(&inner.bit, "bit number")?;
                Some(ir::Bit {
                    name: inner.name.get_ref().clone(),
                    bit,
                    doc: inner.doc.clone(),
                    code: inner.code.as_ref().map(|c| *c.get_ref()),
                    span: self.span(&inner.bit),
                })
            })
            .collect();
        let fields = raw
            .fields
            .iter()
            .filter_map(|f| {
                let inner = f.get_ref();
                Some(ir::BitField {
                    name: inner.name.get_ref().clone(),
                    lsb: self.int_in::<u32>(&inner.lsb, "lsb")?,
                    width: self.int_in::<u32>(&inner.width, "width")?,
                    doc: inner.doc.clone(),
                    enumeration: inner.enumeration.as_ref().map(|e| e.get_ref().clone()),
                    span: self.span(f),
                })
            })
            .collect();
        Some(ir::Flags {
            name: raw.name.get_ref().clone(),
            data_type,
            doc: raw.doc.clone(),
            bits,
            fields,
            codes: raw.codes.as_ref().map(|c| c.get_ref().clone()),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            erratum: raw.erratum.clone(),
            span: self.span(&raw.name),
        })
    }

    fn record(&mut self, raw: &RawRecord) -> Option<ir::Record> {
        let kind = match raw.kind.get_ref().as_str() {
            "record" => ir::RecordKind::Record,
            "array" => ir::RecordKind::Array,
            other => {
                let span = self.span(&raw.kind);
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown record kind `{other}`"),
                    "use \"record\" or \"array\"",
                );
                return None;
            }
        };
        Some(ir::Record {
            name: raw.name.get_ref().clone(),
            kind,
            index: self.int_in::<u16>(&raw.index, "object index")?,
            doc: raw.doc.clone(),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&raw.name),
        })
    }

    fn number(&mut self, raw: &Spanned<RawNumber>, ty: DataType) -> Option<Number> {
        match (*raw.get_ref(), ty.is_integer() || ty == DataType::Bool) {
            (RawNumber::Int(i), _) => Some(Number::Int(i)),
            (RawNumber::Float(f), false) => Some(Number::Float(f)),
            (RawNumber::Float(f), true) => {
                let span = self.span(raw);
                // TOML reads an integer beyond i64 (u64::MAX, say) as a float: say so rather than
                // call a whole number fractional.
                let (message, help) = if f.fract() == 0.0 && f.abs() >= 9.2e18 {
                    (
                        format!("{f} is beyond the largest TOML integer, {}", i64::MAX),
                        "a raw value of a u64 parameter can be at most i64::MAX here",
                    )
                } else {
                    (
                        format!("{f} is not a raw integer"),
                        "defaults, ranges and allowed values are raw wire values, before scaling",
                    )
                };
                self.error_help(VALUE_RULE, span, message, help);
                None
            }
        }
    }

    fn numbers(&mut self, raw: &Spanned<Vec<RawNumber>>, ty: DataType) -> Option<Vec<Number>> {
        let span = raw.span();
        raw.get_ref()
            .iter()
            .map(|n| self.number(&Spanned::new(span.clone(), *n), ty))
            .collect()
    }

    fn scale(&mut self, raw: &Spanned<RawScale>) -> Option<ir::Scale> {
        let span = self.span(raw);
        let (factor, offset) = match raw.get_ref() {
            RawScale::Int(i) => (Some(Ratio::int(*i)), Some(Ratio::ZERO)),
            RawScale::Float(f) => (float_ratio(*f), Some(Ratio::ZERO)),
            RawScale::Text(t) => (Ratio::parse(t), Some(Ratio::ZERO)),
            RawScale::Table(RawScaleTable {
                expr: Some(expr),
                factor: None,
                offset: None,
            }) => {
                return match Expr::parse(expr) {
                    Ok(ast) => Some(ir::Scale::Runtime {
                        expr: expr.clone(),
                        inputs: ast.inputs(),
                        ast,
                    }),
                    Err(e) => {
                        self.error(
                            "scales_are_valid",
                            span,
                            format!("scale expression `{expr}`: {e}"),
                        );
                        None
                    }
                };
            }
            RawScale::Table(RawScaleTable {
                expr: None,
                factor,
                offset,
            }) => (
                factor.as_ref().map_or(Some(Ratio::ONE), exact_scalar),
                offset.as_ref().map_or(Some(Ratio::ZERO), exact_scalar),
            ),
            RawScale::Table(_) => {
                self.error_help(
                    "scales_are_valid",
                    span,
                    "`expr` cannot be combined with `factor` or `offset`",
                    "fold the offset into the expression's parameter instead",
                );
                return None;
            }
        };
        match (factor, offset) {
            (Some(factor), Some(offset)) => {
                Some(ir::Scale::Fixed(drivebus_model::Scale { factor, offset }))
            }
            _ => {
                self.error_help(
                    "scales_are_valid",
                    span,
                    "scale is not an exact number",
                    "write an integer, a decimal (\"0.1\") or a fraction (\"1/100\")",
                );
                None
            }
        }
    }

    /// A Modbus address's access: `r`, `w` or `rw` (the default depends on the table).
    fn modbus_access(
        &mut self,
        text: Option<&str>,
        span: &Span,
        default: ir::Access,
    ) -> Option<ir::Access> {
        Some(match text {
            None => default,
            Some("r") => ir::Access::READ,
            Some("w") => ir::Access::WRITE,
            Some("rw") => ir::Access::READ_WRITE,
            Some(other) => {
                let help = if matches!(other, "ro" | "wo" | "rwr" | "rww" | "const") {
                    format!("`{other}` is a CANopen access type; a Modbus address takes \"r\", \"w\" or \"rw\"")
                } else {
                    "use \"r\", \"w\" or \"rw\"".to_owned()
                };
                self.error_help(
                    VALUE_RULE,
                    span.clone(),
                    format!("unknown Modbus access `{other}`"),
                    &help,
                );
                return None;
            }
        })
    }

    /// A CANopen (or RS-232) object's access, and whether it is `const`: the CiA 306 spellings
    /// plus `r` / `w`.
    fn object_access(&mut self, text: Option<&str>, span: &Span) -> Option<(ir::Access, bool)> {
        Some(match text {
            None => (ir::Access::READ_WRITE, false),
            Some("r" | "ro") => (ir::Access::READ, false),
            Some("w" | "wo") => (ir::Access::WRITE, false),
            Some("rw" | "rwr" | "rww") => (ir::Access::READ_WRITE, false),
            Some("const") => (ir::Access::READ, true),
            Some(other) => {
                self.error_help(
                    VALUE_RULE,
                    span.clone(),
                    format!("unknown access `{other}`"),
                    "use \"ro\", \"wo\", \"rw\", \"rwr\", \"rww\" or \"const\" (or \"r\", \"w\")",
                );
                return None;
            }
        })
    }

    fn modbus_address(
        &mut self,
        raw: &RawModbusAddress,
        span: &Span,
        ty: DataType,
        default_order: ir::WordOrder,
    ) -> Option<ir::ModbusAddress> {
        let table = match raw.table.as_str() {
            "input" => ir::Table::Input,
            "holding" => ir::Table::Holding,
            other => {
                self.error_help(
                    VALUE_RULE,
                    span.clone(),
                    format!("unknown Modbus table `{other}`"),
                    "use \"input\" (FC 0x04) or \"holding\" (FC 0x03/0x06/0x10)",
                );
                return None;
            }
        };
        let spanned = |v: i64| Spanned::new(span.range.clone(), v);
        let address = self.int_in::<u16>(&spanned(raw.address), "register address")?;
        let natural_words = ty.bytes().div_ceil(2).max(1) as i64;
        let words =
            self.int_in::<u16>(&spanned(raw.words.unwrap_or(natural_words)), "word count")?;
        let occupies = self.occupied_registers(raw.occupies, words, span)?;
        let word_order = match &raw.word_order {
            _ if matches!(ty, DataType::String(_) | DataType::Octets(_)) => ir::WordOrder::Text,
            Some(w) => self.word_order(w, span.clone())?,
            None => default_order,
        };
        let default_access = if table == ir::Table::Input {
            ir::Access::READ
        } else {
            ir::Access::READ_WRITE
        };
        let access = self.modbus_access(raw.access.as_deref(), span, default_access)?;
        Some(ir::ModbusAddress {
            wire: drivebus_model::modbus::ModbusAddress {
                table,
                address,
                words,
                word_order,
            },
            occupies,
            access,
            variant: raw.variant.clone(),
            read_back_of: raw.read_back_of.clone(),
            span: span.clone(),
        })
    }

    fn object_address(
        &mut self,
        raw: &RawCanOpenAddress,
        span: &Span,
    ) -> Option<ir::ObjectAddress> {
        let spanned = |v: i64| Spanned::new(span.range.clone(), v);
        let index = self.int_in::<u16>(&spanned(raw.index), "object index")?;
        let first = self.first_subindex(raw, span)?;
        let subindex = self.int_in::<u8>(&spanned(first), "subindex")?;
        let (access, constant) = self.object_access(raw.access.as_deref(), span)?;
        let pdo = match &raw.pdo {
            None | Some(RawPdo::Flag(false)) => ir::Pdo::None,
            Some(RawPdo::Flag(true)) => ir::Pdo::Both,
            Some(RawPdo::Direction(d)) => match d.as_str() {
                "rx" => ir::Pdo::Rx,
                "tx" => ir::Pdo::Tx,
                "both" => ir::Pdo::Both,
                other => {
                    self.error_help(
                        VALUE_RULE,
                        span.clone(),
                        format!("unknown PDO direction `{other}`"),
                        "use false, \"rx\", \"tx\" or \"both\"",
                    );
                    return None;
                }
            },
        };
        Some(ir::ObjectAddress {
            index,
            subindex,
            access,
            constant,
            pdo,
            variant: raw.variant.clone(),
            span: span.clone(),
        })
    }

    fn effect(&mut self, raw: &Spanned<String>) -> Option<ir::Effect> {
        Some(match raw.get_ref().as_str() {
            "immediate" => ir::Effect::Immediate,
            "after-reset" => ir::Effect::AfterReset,
            "after-store-reset" => ir::Effect::AfterStoreReset,
            other => {
                let span = self.span(raw);
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown effect `{other}`"),
                    "use \"immediate\", \"after-reset\" or \"after-store-reset\"",
                );
                return None;
            }
        })
    }

    fn command(&mut self, c: &RawCommand) -> Option<ir::Command> {
        let kind = match c.kind.get_ref().as_str() {
            "store" => ir::CommandKind::Store,
            "restore-factory" => ir::CommandKind::RestoreFactory,
            "reset" => ir::CommandKind::Reset,
            "action" => ir::CommandKind::Action,
            other => {
                let span = self.span(&c.kind);
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown command kind `{other}`"),
                    "use \"store\", \"restore-factory\", \"reset\" or \"action\"",
                );
                return None;
            }
        };
        Some(ir::Command {
            kind,
            value: c.value.as_ref().map(|v| *v.get_ref()),
            name: c.name.as_ref().map(|n| n.get_ref().clone()),
            doc: c.doc.clone(),
            more: Vec::new(),
        })
    }

    fn parameter(
        &mut self,
        raw: &RawParameter,
        modbus_order: ir::WordOrder,
    ) -> Option<ir::Parameter> {
        let matched = self.overlay_match(raw)?;
        let data_type = self.parameter_type(raw, matched)?;
        let mut ok = true;
        let addresses = |list: &Option<Spanned<OneOrMany<RawCanOpenAddress>>>,
                         me: &mut Self,
                         ok: &mut bool|
         -> Vec<ir::ObjectAddress> {
            let Some(list) = list else { return Vec::new() };
            let span = me.span(list);
            let parsed: Vec<_> = match list.get_ref() {
                OneOrMany::One(a) => vec![me.object_address(a, &span)],
                OneOrMany::Many(many) => many.iter().map(|a| me.object_address(a, &span)).collect(),
            };
            *ok &= parsed.iter().all(Option::is_some);
            parsed.into_iter().flatten().collect()
        };
        let canopen = addresses(&raw.canopen, self, &mut ok);
        let rs232 = addresses(&raw.rs232, self, &mut ok);
        let modbus = match &raw.modbus {
            None => Vec::new(),
            Some(list) => {
                let span = self.span(list);
                let parsed: Vec<_> = match list.get_ref() {
                    OneOrMany::One(a) => {
                        vec![self.modbus_address(a, &span, data_type, modbus_order)]
                    }
                    OneOrMany::Many(many) => many
                        .iter()
                        .map(|a| self.modbus_address(a, &span, data_type, modbus_order))
                        .collect(),
                };
                ok &= parsed.iter().all(Option::is_some);
                parsed.into_iter().flatten().collect()
            }
        };
        let default = match &raw.default {
            Some(d) => Some(self.number(d, data_type)?),
            None => None,
        };
        let range = match &raw.range {
            Some(r) => match self.numbers(r, data_type)?.as_slice() {
                [min, max] => Some(ir::Range {
                    min: *min,
                    max: *max,
                }),
                _ => {
                    let span = self.span(r);
                    self.error(VALUE_RULE, span, "a range is `[min, max]`");
                    return None;
                }
            },
            None => None,
        };
        let allowed = match &raw.allowed {
            Some(a) => self.numbers(a, data_type)?,
            None => Vec::new(),
        };
        let scale = match &raw.scale {
            Some(s) => Some(self.scale(s)?),
            None => None,
        };
        let effect = match &raw.effect {
            Some(e) => self.effect(e)?,
            None => ir::Effect::Immediate,
        };
        let command = self.commands(raw.command.as_ref(), raw.commands.as_ref())?;
        let stops = match &raw.stops {
            Some(s) => self.stop_writes(s)?,
            None => None,
        };
        let spans = ir::ParameterSpans {
            name: self.span(&raw.name),
            data_type: raw
                .ty
                .as_ref()
                .map_or_else(|| self.span(&raw.name), |t| self.span(t)),
            default: raw.default.as_ref().map(|d| self.span(d)),
            range: raw.range.as_ref().map(|r| self.span(r)),
            allowed: raw.allowed.as_ref().map(|a| self.span(a)),
            scale: raw.scale.as_ref().map(|s| self.span(s)),
            unit: raw.unit.as_ref().map(|u| self.span(u)),
            enumeration: raw.enumeration.as_ref().map(|e| self.span(e)),
            flags: raw.flags.as_ref().map(|f| self.span(f)),
            record: raw.record.as_ref().map(|r| self.span(r)),
            variants: raw
                .variants
                .iter()
                .flatten()
                .map(|v| self.span(v))
                .collect(),
        };
        let source = raw.source.as_ref().and_then(|c| self.citation(c));
        let parameter = ok.then(|| ir::Parameter {
            name: raw.name.get_ref().clone(),
            doc: raw.doc.clone(),
            data_type,
            unit: raw.unit.as_ref().map(|u| u.get_ref().clone()),
            scale,
            default,
            default_plus_node_id: false,
            range,
            bounds: raw.bounds.as_ref().map(|b| ir::Bounds {
                min: b.get_ref().min.clone(),
                max: b.get_ref().max.clone(),
                magnitude: b.get_ref().magnitude.clone(),
                span: self.span(b),
            }),
            allowed,
            enumeration: raw.enumeration.as_ref().map(|e| e.get_ref().clone()),
            flags: raw.flags.as_ref().map(|f| f.get_ref().clone()),
            record: raw.record.as_ref().map(|r| r.get_ref().clone()),
            modbus,
            canopen,
            rs232,
            effect,
            command,
            variants: raw
                .variants
                .iter()
                .flatten()
                .map(|v| v.get_ref().clone())
                .collect(),
            source,
            erratum: raw.erratum.clone(),
            safety: raw.safety.unwrap_or(false),
            stops,
            spans,
        })?;
        Some(match matched {
            Some(entry) => self.overlay_merge(entry, parameter, raw),
            None => parameter,
        })
    }
}

/// The exact value of a number as a description writes it: an integer, a float (its shortest
/// decimal representation) or a string (`"1/100"`, `"0.1"`).
fn exact_scalar(value: &RawScalar) -> Option<Ratio> {
    match value {
        RawScalar::Int(i) => Some(Ratio::int(*i)),
        RawScalar::Float(f) => float_ratio(*f),
        RawScalar::Text(t) => Ratio::parse(t),
    }
}

/// The exact value of a float as its shortest decimal representation (`0.1` → 1/10).
fn float_ratio(value: f64) -> Option<Ratio> {
    value
        .is_finite()
        .then(|| Ratio::parse(&value.to_string()))
        .flatten()
}

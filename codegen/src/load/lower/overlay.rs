//! A description that is an overlay of an EDS (`eds = "vendor.eds"`): its `[[parameter]]` entries
//! match EDS objects by `canopen` address and add or override fields; the objects it does not
//! mention are added with the names derived from their EDS `ParameterName`.

use std::collections::{BTreeMap, BTreeSet};

use super::Lowering;
use crate::diagnostic::{Diagnostic, FileId};
use crate::eds::EdsModel;
use crate::ir::{self, DataType};
use crate::load::raw::{OneOrMany, RawCanOpenAddress, RawParameter, RawSubindex};

const RULE: &str = "overlay_matches_eds";

/// The EDS of an overlay and which of its entries the overlay refined.
pub struct Overlay<'m> {
    model: &'m EdsModel,
    matched: Vec<bool>,
    /// The overlay file: only its entries must match an EDS object (included profiles may describe
    /// objects the EDS lacks).
    root: FileId,
}

/// Which fields an overlay entry writes itself (the others come from the EDS).
struct Present {
    doc: bool,
    default: bool,
    range: bool,
    record: bool,
    source: bool,
    access: bool,
    pdo: bool,
}

impl Present {
    fn of(raw: &RawParameter) -> Present {
        let address = first_address(raw);
        Present {
            doc: raw.doc.is_some(),
            default: raw.default.is_some(),
            range: raw.range.is_some(),
            record: raw.record.is_some(),
            source: raw.source.is_some(),
            access: address.is_some_and(|a| a.access.is_some()),
            pdo: address.is_some_and(|a| a.pdo.is_some()),
        }
    }
}

fn first_address(raw: &RawParameter) -> Option<&RawCanOpenAddress> {
    match raw.canopen.as_ref()?.get_ref() {
        OneOrMany::One(a) => Some(a),
        OneOrMany::Many(many) => many.first(),
    }
}

impl<'m> Overlay<'m> {
    /// An overlay of `model` written in file `root`.
    pub fn new(model: &'m EdsModel, root: FileId) -> Self {
        Self {
            model,
            matched: vec![false; model.entries.len()],
            root,
        }
    }

    fn find(&self, index: i64, subindex: i64) -> Option<usize> {
        self.model
            .entries
            .iter()
            .position(|e| i64::from(e.index) == index && i64::from(e.variable.subindex) == subindex)
    }

    /// Adds the EDS records and the objects no overlay entry mentioned.
    pub fn finish(self, device: &mut ir::Device, diagnostics: &mut Vec<Diagnostic>) {
        let mut renamed: BTreeMap<&str, String> = BTreeMap::new();
        for record in &self.model.records {
            match device.records.iter().find(|r| r.index == record.index) {
                Some(own) => {
                    renamed.insert(&record.name, own.name.clone());
                }
                None => device.records.push(record.clone()),
            }
        }
        let taken: BTreeSet<String> = device.parameters.iter().map(|p| p.name.clone()).collect();
        for (entry, _) in self
            .model
            .entries
            .iter()
            .zip(&self.matched)
            .filter(|(_, m)| !**m)
        {
            let ty = entry.usable_type(diagnostics);
            let mut p = entry.parameter(&self.model.cited, ty, diagnostics);
            if taken.contains(&p.name) {
                p.name = format!("{}_{:04x}_{}", p.name, entry.index, entry.variable.subindex);
            }
            device.parameters.push(p);
        }
        for p in &mut device.parameters {
            if let Some(name) = p.record.as_deref().and_then(|r| renamed.get(r)) {
                p.record = Some(name.clone());
            }
        }
        if device.canopen.is_none() {
            device.canopen = Some(ir::CanOpenCaps {
                default_node_id: self.model.device.node_id.unwrap_or(1),
                lss: crate::eds::lss(&self.model.device),
                source: None,
            });
        }
    }
}

impl Lowering<'_> {
    /// The EDS entry an overlay parameter refines. `Some(None)`: not an overlay entry; `None`: an
    /// overlay entry whose address the EDS lacks (reported).
    pub(super) fn overlay_match(&mut self, raw: &RawParameter) -> Option<Option<usize>> {
        let (Some(overlay), Some(address)) = (&mut self.overlay, first_address(raw)) else {
            return Some(None);
        };
        let subindex = address.subindex.as_ref().map_or(0, RawSubindex::first);
        if let Some(i) = overlay.find(address.index, subindex) {
            overlay.matched[i] = true;
            return Some(Some(i));
        }
        if self.file != overlay.root {
            return Some(None);
        }
        let (index, eds) = (address.index, overlay.model.source.file.clone());
        let span = raw
            .canopen
            .as_ref()
            .map_or_else(|| self.span(&raw.name), |c| self.span(c));
        self.diagnostics.push(
            Diagnostic::error(
                RULE,
                span,
                format!("`{}` refines object {index:#06X} sub {subindex}, which `{eds}` does not describe", raw.name.get_ref()),
            )
            .label("no such object in the EDS")
            .help("check `index` and `subindex` against the EDS sections `[XXXX]` / `[XXXXsubN]`"),
        );
        None
    }

    /// The type of a parameter: its own `type`, else its EDS object's `DataType`.
    pub(super) fn parameter_type(
        &mut self,
        raw: &RawParameter,
        matched: Option<usize>,
    ) -> Option<DataType> {
        if let Some(ty) = &raw.ty {
            return self.data_type(ty, raw.length.as_ref());
        }
        let model = self.overlay.as_ref().map(|o| o.model);
        let entry = matched.zip(model).map(|(i, m)| &m.entries[i]);
        match entry {
            Some(entry) => Some(with_length(entry.usable_type(self.diagnostics), raw)),
            None => {
                let span = self.span(&raw.name);
                self.diagnostics.push(
                    Diagnostic::error("syntax", span, format!("`{}` has no `type`", raw.name.get_ref()))
                        .help("every parameter needs `type`; only an overlay entry matching an EDS object with a DataType may leave it out"),
                );
                None
            }
        }
    }

    /// `parameter` with every field it leaves out taken from its EDS entry.
    pub(super) fn overlay_merge(
        &mut self,
        entry: usize,
        mut p: ir::Parameter,
        raw: &RawParameter,
    ) -> ir::Parameter {
        let Some(model) = self.overlay.as_ref().map(|o| o.model) else {
            return p;
        };
        let base = model.entries[entry].parameter(&model.cited, p.data_type, self.diagnostics);
        let present = Present::of(raw);
        if !present.doc {
            p.doc = base.doc;
        }
        if !present.default {
            p.default = base.default;
            p.default_plus_node_id = base.default_plus_node_id;
            p.spans.default = base.spans.default;
        }
        if !present.range {
            p.range = base.range;
            p.spans.range = base.spans.range;
        }
        if !present.record {
            p.record = base.record;
        }
        if !present.source {
            p.source = base.source;
        }
        if let (Some(own), Some(eds)) = (p.canopen.first_mut(), base.canopen.first()) {
            if !present.access {
                own.access = eds.access;
                own.constant = eds.constant;
            }
            if !present.pdo {
                own.pdo = eds.pdo;
            }
        }
        p
    }
}

/// A string's capacity from the overlay's `length`.
fn with_length(ty: DataType, raw: &RawParameter) -> DataType {
    let length = raw
        .length
        .as_ref()
        .and_then(|l| u16::try_from(*l.get_ref()).ok());
    match (ty, length) {
        (DataType::String(_), Some(n)) => DataType::String(n),
        (DataType::Octets(_), Some(n)) => DataType::Octets(n),
        (ty, _) => ty,
    }
}

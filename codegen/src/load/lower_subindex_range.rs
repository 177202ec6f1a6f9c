//! Lowering of a member described once over a run of sub-indices (`subindex = "1..=8"`): the
//! parameter is expanded into one parameter per sub-index, named `<name>_<sub-index>`, and the
//! run is kept as an [`ir::IndexedParameter`] for the indexed accessor.

use super::{Lowering, VALUE_RULE};
use crate::diagnostic::Span;
use crate::ir;
use crate::load::raw::*;
use crate::load::subindex_range;

impl Lowering<'_> {
    /// The sub-index of an address, or the first of its run; a malformed run is reported.
    pub(super) fn first_subindex(&mut self, raw: &RawCanOpenAddress, span: &Span) -> Option<i64> {
        match &raw.subindex {
            None => Some(0),
            Some(RawSubindex::Number(n)) => Some(*n),
            Some(RawSubindex::Range(text)) => match subindex_range::parse(text) {
                Ok((first, _)) => Some(i64::from(first)),
                Err(message) => {
                    self.error_help(
                        VALUE_RULE,
                        span.clone(),
                        message,
                        "write a run as \"1..=8\": first and last sub-index, both within 1..=254",
                    );
                    None
                }
            },
        }
    }

    /// Adds `lowered` to the device, expanded over its sub-index run if it has one.
    pub(super) fn push_expanded(
        &mut self,
        raw: &RawParameter,
        lowered: ir::Parameter,
        device: &mut ir::Device,
    ) {
        let Some((first, last)) = self.subindex_run(raw) else {
            device.parameters.push(lowered);
            return;
        };
        let members = (first..=last)
            .map(|subindex| ir::IndexedParameter::member_name(&lowered.name, subindex))
            .collect();
        device.indexed.push(ir::IndexedParameter {
            name: lowered.name.clone(),
            doc: lowered.doc.clone(),
            index: lowered.canopen.first().map_or(0, |a| a.index),
            first,
            last,
            members,
            span: lowered.spans.name.clone(),
        });
        for subindex in first..=last {
            device.parameters.push(member(&lowered, subindex));
        }
    }

    /// The run of `raw`'s CANopen address, if it has one and the parameter can carry it: one
    /// CANopen address and no Modbus or RS-232 address (a run names CANopen sub-indices only).
    fn subindex_run(&mut self, raw: &RawParameter) -> Option<(u8, u8)> {
        let list = raw.canopen.as_ref()?;
        let addresses: Vec<&RawCanOpenAddress> = match list.get_ref() {
            OneOrMany::One(a) => vec![a],
            OneOrMany::Many(many) => many.iter().collect(),
        };
        let text = addresses.iter().find_map(|a| match &a.subindex {
            Some(RawSubindex::Range(text)) => Some(text),
            _ => None,
        })?;
        let run = subindex_range::parse(text).ok()?;
        if addresses.len() > 1 || raw.modbus.is_some() || raw.rs232.is_some() {
            let span = self.span(list);
            self.error_help(
                VALUE_RULE,
                span,
                "a parameter described over a sub-index run has exactly one address, a CANopen one",
                "describe the other addresses as separate parameters",
            );
            return None;
        }
        Some(run)
    }
}

/// The parameter of the run at `subindex`.
fn member(run: &ir::Parameter, subindex: u8) -> ir::Parameter {
    let mut p = run.clone();
    p.name = ir::IndexedParameter::member_name(&run.name, subindex);
    p.doc = Some(match &run.doc {
        Some(doc) => format!("{doc} Sub-index {subindex}."),
        None => format!("Sub-index {subindex}."),
    });
    for address in &mut p.canopen {
        address.subindex = subindex;
    }
    p
}

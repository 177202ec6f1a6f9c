//! Lowering of a member described once over a run of sub-indices (`subindex = "1..=8"`): the run
//! stays one parameter, an [`ir::IndexedParameter`] (one marker and one indexed accessor in the
//! generated crate), and each sub-index is also listed as a member parameter named
//! `<name>_<sub-index>` for what addresses single objects (object dictionaries, EDS, overlap).

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
            parameter: lowered.clone(),
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

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{device, messages};

    const RUN: &str = r#"
[[parameter]]
name = "sls_limit"
doc = "SLS limit."
type = "u32"
default = 7
canopen = { index = 0x6693, subindex = "1..=3", access = "rw" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn a_run_expands_into_one_parameter_per_sub_index_and_is_kept_as_a_run() {
        let device = device(RUN);
        let names: Vec<_> = device.parameters.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["sls_limit_1", "sls_limit_2", "sls_limit_3"]);
        let subs: Vec<_> = device
            .parameters
            .iter()
            .map(|p| p.canopen[0].subindex)
            .collect();
        assert_eq!(subs, [1, 2, 3]);
        assert!(device.parameters.iter().all(|p| p.default.is_some()));
        let run = &device.indexed[0];
        assert_eq!(
            (run.name.as_str(), run.index, run.first, run.last),
            ("sls_limit", 0x6693, 1, 3)
        );
        assert_eq!(run.members, names);
        assert_eq!(run.parameter.name, "sls_limit");
        assert_eq!(run.parameter.canopen[0].subindex, 1);
        assert_eq!(
            device.parameters[1].doc.as_deref(),
            Some("SLS limit. Sub-index 2.")
        );
    }

    #[test]
    fn a_malformed_run_is_reported_at_its_address() {
        let bad = RUN.replace("1..=3", "3..=1");
        let found = messages("values_are_well_formed", &bad);
        assert!(found.iter().any(|m| m.contains("empty")), "{found:?}");
        let zero = RUN.replace("1..=3", "0..=3");
        assert!(!messages("values_are_well_formed", &zero).is_empty());
    }

    #[test]
    fn a_run_has_exactly_one_address() {
        let two = RUN.replace(
            r#"canopen = { index = 0x6693, subindex = "1..=3", access = "rw" }"#,
            r#"canopen = [{ index = 0x6693, subindex = "1..=3", access = "rw" }, { index = 0x2000, access = "rw" }]"#,
        );
        let found = messages("values_are_well_formed", &two);
        assert!(
            found.iter().any(|m| m.contains("exactly one address")),
            "{found:?}"
        );
    }

    #[test]
    fn a_member_name_taken_by_another_parameter_is_a_name_clash() {
        let clash = format!(
            "{RUN}\n[[parameter]]\nname = \"sls_limit_2\"\ntype = \"u8\"\ncanopen = {{ index = 0x2000, access = \"rw\" }}\nsource = {{ doc = \"m\", line = 1 }}\n"
        );
        assert!(!messages("names_are_unique", &clash).is_empty());
    }
}

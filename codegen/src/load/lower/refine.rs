//! Lowering of `[[refine]]`: a description adds protocol addresses to a parameter of an included
//! profile (Kinco reaches the CiA 402 objects over Modbus and RS-232 too) and overrides what its
//! drive does differently — unit, scale, default, range, allowed values, enum, doc — citing its
//! own manual, instead of redefining the parameter. Every refinement is kept in the IR
//! (`Device::refinements`) so the generated docs cite it.

use toml::Spanned;

use super::Lowering;
use crate::diagnostic::Diagnostic;
use crate::ir;
use crate::load::raw::{OneOrMany, RawCanOpenAddress, RawFile, RawRefine};

const RULE: &str = "refinements_resolve";

impl Lowering<'_> {
    /// Applies the file's `[[refine]]` entries to the parameters already lowered.
    pub(super) fn refinements(&mut self, raw: &RawFile, device: &mut ir::Device) {
        let order = device
            .modbus
            .as_ref()
            .map_or(ir::WordOrder::HighFirst, |m| m.word_order);
        for r in &raw.refine {
            let name = r.parameter.get_ref();
            let span = self.span(&r.parameter);
            let Some(index) = device.parameters.iter().position(|p| &p.name == name) else {
                self.error_help(
                    RULE,
                    span,
                    format!("`[[refine]]` names `{name}`, which is not an included parameter"),
                    "refine a parameter an `include` brings in (check `only`)",
                );
                continue;
            };
            if device.parameters[index].spans.name.file == self.file {
                self.error_help(
                    RULE,
                    span,
                    format!("`{name}` is defined in this file: change it instead of refining it"),
                    "`[[refine]]` is for parameters of included profiles",
                );
                continue;
            }
            if r.source.is_none() {
                self.diagnostics.push(
                    Diagnostic::error(
                        "values_cite_sources",
                        span.clone(),
                        format!("the refinement of `{name}` cites no source"),
                    )
                    .help("add `source = { doc, section, line }`: an override comes from a manual"),
                );
            }
            let mut p = device.parameters[index].clone();
            if let Some(keys) = self.refine(r, &mut p, order) {
                device.parameters[index] = p;
                let source = r.source.as_ref().and_then(|c| self.citation(c));
                device.refinements.push(ir::Refinement {
                    parameter: name.clone(),
                    keys,
                    source,
                    erratum: r.erratum.clone(),
                    span,
                });
            }
        }
    }

    /// Applies one entry to `p`; returns the keys it set, or `None` if a value is malformed.
    fn refine(
        &mut self,
        r: &RawRefine,
        p: &mut ir::Parameter,
        order: ir::WordOrder,
    ) -> Option<Vec<String>> {
        let mut keys = Vec::new();
        let ty = p.data_type;
        if let Some(doc) = &r.doc {
            p.doc = Some(doc.clone());
            keys.push("doc");
        }
        if let Some(unit) = &r.unit {
            p.unit = Some(unit.get_ref().clone());
            p.spans.unit = Some(self.span(unit));
            keys.push("unit");
        }
        if let Some(scale) = &r.scale {
            p.scale = Some(self.scale(scale)?);
            p.spans.scale = Some(self.span(scale));
            keys.push("scale");
        }
        if let Some(default) = &r.default {
            p.default = Some(self.number(default, ty)?);
            p.spans.default = Some(self.span(default));
            keys.push("default");
        }
        if let Some(range) = &r.range {
            let [min, max] = self.numbers(range, ty)?[..] else {
                let span = self.span(range);
                self.error(super::VALUE_RULE, span, "a range is `[min, max]`");
                return None;
            };
            p.range = Some(ir::Range { min, max });
            p.spans.range = Some(self.span(range));
            keys.push("range");
        }
        if let Some(allowed) = &r.allowed {
            p.allowed = self.numbers(allowed, ty)?;
            p.spans.allowed = Some(self.span(allowed));
            keys.push("allowed");
        }
        if let Some(e) = &r.enumeration {
            // The enum becomes the value type, replacing a flags type the profile gave.
            p.enumeration = Some(e.get_ref().clone());
            p.spans.enumeration = Some(self.span(e));
            p.flags = None;
            p.spans.flags = None;
            keys.push("enum");
        }
        if let Some(list) = &r.modbus {
            let span = self.span(list);
            for a in list.get_ref().iter() {
                p.modbus.push(self.modbus_address(a, &span, ty, order)?);
            }
            keys.push("modbus");
        }
        if let Some(list) = &r.canopen {
            p.canopen.extend(self.refined_objects(list)?);
            keys.push("canopen");
        }
        if let Some(list) = &r.rs232 {
            p.rs232.extend(self.refined_objects(list)?);
            keys.push("rs232");
        }
        Some(keys.into_iter().map(str::to_owned).collect())
    }

    fn refined_objects(
        &mut self,
        list: &Spanned<OneOrMany<RawCanOpenAddress>>,
    ) -> Option<Vec<ir::ObjectAddress>> {
        let span = self.span(list);
        list.get_ref()
            .iter()
            .map(|a| self.object_address(a, &span))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::HEADER;

    /// A description including the CiA 402 profile with `only`, plus `body`.
    fn including(only: &str, body: &str) -> String {
        let profile = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../descriptions/profiles/cia402.toml"
        );
        let include = format!("format = 1\ninclude = [{{ path = {profile:?}, only = {only} }}]\n");
        HEADER.replacen("format = 1\n", &include, 1) + body
    }

    fn checked(text: &str) -> crate::Checked {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("drivegen-refine-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("device.toml");
        std::fs::write(&path, text).unwrap();
        let checked = crate::check(&path);
        std::fs::remove_dir_all(&dir).unwrap();
        checked
    }

    fn device(text: &str) -> crate::ir::Device {
        let checked = checked(text);
        match checked.device {
            Some(d) if !checked.render().contains("error") => d,
            _ => panic!("invalid test description:\n{}", checked.render()),
        }
    }

    const REFINE: &str = r#"
[[refine]]
parameter = "controlword"
modbus = { table = "holding", address = 0x3100 }
rs232 = { index = 0x6040, subindex = 0, access = "rw" }
source = { doc = "m", section = "8.1", line = 1935 }
"#;

    #[test]
    fn a_refinement_adds_addresses_and_is_recorded() {
        // `include` must come before the tables, so the header is written after it here.
        let d = device(&including(r#"["controlword"]"#, REFINE));
        let cw = d.parameter("controlword").unwrap();
        assert_eq!(cw.canopen[0].index, 0x6040, "the profile's address stays");
        assert_eq!(cw.modbus[0].address, 0x3100);
        assert_eq!(cw.rs232[0].index, 0x6040);
        assert_eq!(d.refinements[0].keys, ["modbus", "rs232"]);
        assert_eq!(d.refinements[0].source.as_ref().unwrap().line, Some(1935));
    }

    #[test]
    fn an_override_replaces_the_profile_value() {
        let body = r#"
[[refine]]
parameter = "polarity"
range = [0, 1]
source = { doc = "m", section = "8.3", line = 1959 }
"#;
        let d = device(&including(r#"["polarity"]"#, body));
        let range = d.parameter("polarity").unwrap().range.clone().unwrap();
        assert_eq!((range.min.as_f64(), range.max.as_f64()), (0.0, 1.0));
    }

    #[test]
    fn refining_an_unknown_or_uncited_parameter_is_an_error() {
        let unknown = checked(&including(r#"["statusword"]"#, REFINE));
        assert!(
            unknown
                .render()
                .contains("`[[refine]]` names `controlword`"),
            "{}",
            unknown.render()
        );
        let uncited = REFINE.replace(
            "source = { doc = \"m\", section = \"8.1\", line = 1935 }",
            "",
        );
        let found = checked(&including(r#"["controlword"]"#, &uncited));
        assert!(
            found.render().contains("cites no source"),
            "{}",
            found.render()
        );
    }

    #[test]
    fn only_by_kind_takes_the_parameter_without_its_enum() {
        let body = r#"
[[enum]]
name = "modes_of_operation"
type = "i8"
source = { doc = "m", line = 1937 }
values = [{ name = "position", value = 1 }, { name = "immediate_velocity", value = -3 }]
"#;
        let d = device(&including(
            r#"{ parameters = ["modes_of_operation"] }"#,
            body,
        ));
        let modes = d.enumeration("modes_of_operation").unwrap();
        assert_eq!(
            modes.values.len(),
            2,
            "the description's own modes, not the profile's"
        );
        let unknown = checked(&including(r#"{ enums = ["controlword"] }"#, ""));
        assert!(
            unknown.render().contains("`only` names `controlword`"),
            "{}",
            unknown.render()
        );
    }
}

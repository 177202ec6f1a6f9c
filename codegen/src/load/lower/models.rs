//! Lowering of `[[constant]]` / `[[model]]` (per-model constants) and of the `[modbus]`
//! `exception_functions` quirk. What the models give is checked by `models_give_constants`.

use super::exact_scalar;
use super::{Lowering, VALUE_RULE};
use crate::ir;
use crate::load::raw::{RawFile, RawModbusCaps};

impl Lowering<'_> {
    /// Adds the file's constants and models to `device`.
    pub(super) fn models(&mut self, raw: &RawFile, device: &mut ir::Device) {
        for c in &raw.constant {
            device.constants.push(ir::Constant {
                name: c.name.get_ref().clone(),
                doc: c.doc.clone(),
                unit: c.unit.as_ref().map(|u| u.get_ref().clone()),
                source: c.source.as_ref().and_then(|s| self.citation(s)),
                span: self.span(&c.name),
            });
        }
        for m in &raw.model {
            let constants_span = self.span(&m.constants);
            let mut constants = Vec::new();
            for (name, value) in m.constants.get_ref() {
                match exact_scalar(value) {
                    Some(value) => constants.push((name.clone(), value)),
                    None => self.error_help(
                        VALUE_RULE,
                        constants_span.clone(),
                        format!("constant `{name}` is not an exact number"),
                        "write an integer, a decimal (\"1.414\") or a fraction (\"45/2\")",
                    ),
                }
            }
            device.models.push(ir::Model {
                name: m.name.get_ref().clone(),
                doc: m.doc.clone(),
                constants,
                source: m.source.as_ref().and_then(|s| self.citation(s)),
                erratum: m.erratum.clone(),
                span: self.span(&m.name),
                constants_span,
            });
        }
    }

    /// `exception_functions`: each answer has bit 7 set, each request is a function code.
    pub(super) fn exception_functions(
        &mut self,
        raw: &RawModbusCaps,
    ) -> Vec<ir::ExceptionFunction> {
        let Some(list) = &raw.exception_functions else {
            return Vec::new();
        };
        let span = self.span(list);
        let mut out = Vec::new();
        for e in list.get_ref() {
            let request = u8::try_from(e.request)
                .ok()
                .filter(|r| (1..0x80).contains(r));
            let answer = u8::try_from(e.answer).ok().filter(|a| a & 0x80 != 0);
            match (request, answer) {
                (Some(request), Some(answer)) => {
                    out.push(ir::ExceptionFunction { request, answer })
                }
                _ => self.error_help(
                    VALUE_RULE,
                    span.clone(),
                    format!(
                        "exception function {{ request = {}, answer = {} }} is not a request code (1..=127) answered with bit 7 set",
                        e.request, e.answer
                    ),
                    "e.g. `{ request = 0x03, answer = 0x81 }`",
                ),
            }
        }
        out
    }
}

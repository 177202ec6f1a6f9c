//! Flag bits and multi-bit fields lie inside the word and do not overlap each other; flags use
//! unsigned types.

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{DataType, Device};

const RULE: &str = super::rule_name(module_path!());

/// Reports bits outside the word, empty fields and overlaps.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for f in &device.flags {
        if !matches!(f.data_type, DataType::Unsigned(_)) {
            out.push(Diagnostic::error(
                RULE,
                f.span.clone(),
                format!("flags `{}` need an unsigned type", f.name),
            ));
            continue;
        }
        let width = f.data_type.bytes() as u32 * 8;
        let mut used: Vec<(u32, u32, &str, &Span)> = Vec::new();
        let bits = f.bits.iter().map(|b| (b.bit, 1, b.name.as_str(), &b.span));
        let fields = f
            .fields
            .iter()
            .map(|x| (x.lsb, x.width, x.name.as_str(), &x.span));
        for (lsb, w, name, span) in bits.chain(fields) {
            if w == 0 || lsb.saturating_add(w) > width {
                let message = format!(
                    "`{name}` (bits {lsb}..{}) does not fit the {width}-bit `{}`",
                    lsb.saturating_add(w),
                    f.name
                );
                out.push(Diagnostic::error(RULE, span.clone(), message));
                continue;
            }
            if let Some((_, _, other, _)) = used
                .iter()
                .find(|(l, ow, _, _)| lsb < l + ow && *l < lsb + w)
            {
                let message = format!("`{name}` overlaps `{other}` in `{}`", f.name);
                out.push(Diagnostic::error(RULE, span.clone(), message));
            }
            used.push((lsb, w, name, span));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn bit_outside_the_word_and_overlaps_are_reported() {
        let body = r#"
[[flags]]
name = "status"
type = "u8"
bits = [{ name = "alarm", bit = 8 }, { name = "run", bit = 1 }]
fields = [{ name = "mode", lsb = 0, width = 2 }]
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            [
                "`alarm` (bits 8..9) does not fit the 8-bit `status`",
                "`mode` overlaps `run` in `status`"
            ]
        );
    }
}

//! Changes to product models (`[[model]]`) and the values of their per-model constants.

use super::{match_by_name, Change, Impact};
use crate::ir::Model;

/// A removed model removes a `Model` variant (breaking); a changed constant value scales values
/// differently (behaviour); a new model only adds.
pub(super) fn compare(old: &[Model], new: &[Model], out: &mut Vec<Change>) {
    let matched = match_by_name(old, new, |m| &m.name);
    for m in matched.removed {
        out.push(Change::new(Impact::Breaking, subject(m), "removed"));
    }
    for m in matched.added {
        out.push(Change::new(Impact::Compatible, subject(m), "added"));
    }
    for (o, n) in matched.both {
        for (constant, before) in &o.constants {
            let after = n.value(constant);
            if after != Some(*before) {
                let shown = after.map_or("none".to_owned(), |a| {
                    format!("{}/{}", a.numerator(), a.denominator())
                });
                let what = format!(
                    "constant `{constant}` {}/{} → {shown}",
                    before.numerator(),
                    before.denominator()
                );
                out.push(Change::new(Impact::Behaviour, subject(o), what));
            }
        }
    }
}

fn subject(m: &Model) -> String {
    format!("model `{}`", m.name)
}

#[cfg(test)]
mod tests {
    use crate::diff::{diff, Impact};
    use crate::validate::test_support::device;

    fn models(fd123: i64, extra: &str) -> String {
        format!(
            "[[constant]]\nname = \"peak_current\"\nsource = {{ doc = \"m\", line = 1 }}\n\
             [[model]]\nname = \"fd123\"\nconstants = {{ peak_current = {fd123} }}\nsource = {{ doc = \"m\", line = 1 }}\n{extra}\
             [[parameter]]\nname = \"x\"\ntype = \"u8\"\nmodbus = {{ table = \"holding\", address = 1 }}\nsource = {{ doc = \"m\", line = 1 }}\n"
        )
    }

    #[test]
    fn removed_models_break_and_changed_constants_behave_differently() {
        let fd133 = "[[model]]\nname = \"fd133\"\nconstants = { peak_current = 50 }\nsource = { doc = \"m\", line = 1 }\n";
        let found: Vec<_> = diff(&device(&models(45, fd133)), &device(&models(48, "")))
            .into_iter()
            .map(|c| (c.impact, format!("{}: {}", c.subject, c.what)))
            .collect();
        assert_eq!(
            found,
            [
                (Impact::Breaking, "model `fd133`: removed".to_owned()),
                (
                    Impact::Behaviour,
                    "model `fd123`: constant `peak_current` 45/1 → 48/1".to_owned()
                ),
            ]
        );
    }
}

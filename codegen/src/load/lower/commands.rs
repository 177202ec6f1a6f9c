//! Lowering of `command = { kind, value }` and of `commands = [{ kind, value, name, doc }, ...]`,
//! a register that takes several command values (Kinco 2FF0h sub 1: 1 = store, 10 = initialise).
//! A register with named values gets a generated enum `<parameter>_command` as its value type
//! and those values as its only allowed ones, so `drive.store_data().write(StoreDataCommand::STORE)`
//! is typed and any other value is refused before it is sent.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::ir::{self, Number};
use crate::load::raw::RawCommand;

impl Lowering<'_> {
    /// The command of a parameter (`Some(None)`: none): `command`, or the first of `commands`
    /// with the others in `more`. `None` when malformed.
    pub(super) fn commands(
        &mut self,
        one: Option<&Spanned<RawCommand>>,
        several: Option<&Spanned<Vec<Spanned<RawCommand>>>>,
    ) -> Option<Option<ir::Command>> {
        let list = match (one, several) {
            (None, None) => return Some(None),
            (Some(c), None) => return self.command(c.get_ref()).map(Some),
            (Some(c), Some(_)) => {
                let span = self.span(c);
                self.error(
                    VALUE_RULE,
                    span,
                    "give either `command` or `commands`, not both",
                );
                return None;
            }
            (None, Some(list)) => list,
        };
        let mut values = Vec::new();
        for c in list.get_ref() {
            if c.get_ref().value.is_none() || c.get_ref().name.is_none() {
                let span = self.span(c);
                self.error_help(
                    VALUE_RULE,
                    span,
                    "each of `commands` needs `value` and `name`",
                    "write `{ kind, value, name, doc }` for every value",
                );
                return None;
            }
            values.push(self.command(c.get_ref())?);
        }
        let mut values = values.into_iter();
        let Some(mut first) = values.next() else {
            let span = self.span(list);
            self.error(VALUE_RULE, span, "`commands` needs at least one value");
            return None;
        };
        first.more = values.collect();
        Some(Some(first))
    }

    /// Gives every parameter whose command register takes several values its command enum.
    pub(super) fn command_enums(&mut self, device: &mut ir::Device) {
        let mut enums = Vec::new();
        for p in &mut device.parameters {
            let Some(command) = p.command.as_ref().filter(|c| c.name.is_some()) else {
                continue;
            };
            if p.enumeration.is_some() || p.flags.is_some() || !p.data_type.is_integer() {
                self.diagnostics.push(
                    crate::diagnostic::Diagnostic::error(
                        VALUE_RULE,
                        p.spans.name.clone(),
                        format!(
                            "`{}` has several command values, which make its value type: it cannot also have an enum, flags or a non-integer type",
                            p.name
                        ),
                    )
                    .help("drop `enum` / `flags`; the command values become the enum"),
                );
                continue;
            }
            let name = format!("{}_command", p.name);
            let values = command
                .values()
                .map(|c| ir::EnumValue {
                    name: c.name.clone().unwrap_or_default(),
                    value: c.value.unwrap_or_default(),
                    doc: c.doc.clone(),
                    class: None,
                    led: None,
                    meaning: None,
                    span: p.spans.name.clone(),
                })
                .collect::<Vec<_>>();
            p.allowed = values.iter().map(|v| Number::Int(v.value)).collect();
            p.enumeration = Some(name.clone());
            enums.push(ir::Enum {
                name,
                data_type: p.data_type,
                doc: Some(format!("The command values of `{}`.", p.name)),
                values,
                source: p.source.clone(),
                erratum: None,
                span: p.spans.name.clone(),
            });
        }
        device.enums.extend(enums);
    }
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{device, messages};

    const STORE_DATA: &str = r#"
[[parameter]]
name = "store_data"
type = "u8"
commands = [
  { kind = "store", value = 1, name = "store", doc = "Store the control loop parameters." },
  { kind = "restore-factory", value = 10, name = "initialise", doc = "Initialise them." },
]
canopen = { index = 0x2FF0, subindex = 1, access = "rw" }
source = { doc = "m", section = "8.11", line = 2117 }
"#;

    #[test]
    fn several_command_values_become_the_value_enum() {
        let d = device(STORE_DATA);
        let p = d.parameter("store_data").unwrap();
        let command = p.command.as_ref().unwrap();
        assert_eq!(
            command.values().map(|c| c.value).collect::<Vec<_>>(),
            [Some(1), Some(10)]
        );
        assert_eq!(p.enumeration.as_deref(), Some("store_data_command"));
        assert_eq!(p.allowed.len(), 2);
        let e = d.enumeration("store_data_command").unwrap();
        let names: Vec<_> = e
            .values
            .iter()
            .map(|v| (v.name.as_str(), v.value))
            .collect();
        assert_eq!(names, [("store", 1), ("initialise", 10)]);
    }

    #[test]
    fn a_value_is_required_when_there_are_several() {
        let body = STORE_DATA.replace("value = 10, ", "");
        assert_eq!(
            messages("values_are_well_formed", &body),
            ["each of `commands` needs `value` and `name`"]
        );
    }
}

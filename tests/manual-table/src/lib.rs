//! A drive's manual as a table of properties, compared with its description.
//!
//! Each drive crate's coverage test keeps a table typed by hand from its manual, one row per
//! parameter:
//!
//! ```text
//! # name           key=value ...                                              line=N  # note
//! target_torque    canopen=6071.00:rw pdo=both modbus=holding:0x3200:rw type=i16 unit=% line=1472
//! ```
//!
//! [`compare`] renders every property of the described parameter in the same form ([`render`])
//! and fails on any difference: a key the row gives must equal the description's, and a key the
//! row leaves out must be one the description does not have either, so a default or range the
//! description carries that the manual does not give fails as surely as a wrong one. `line=` (the
//! manual line the row was typed from) is required and not compared. A value `-` states "none".
//!
//! The keys and their forms:
//!
//! | key | form |
//! |---|---|
//! | `type` | `u16`, `i32`, `string(8)`, ... |
//! | `unit` | the unit symbol |
//! | `scale` | `1/100`, `1/10+5` (factor, then offset), `runtime` for a run-time factor |
//! | `range` | `MIN..MAX`, raw |
//! | `default` | raw, or `$NODEID+N` |
//! | `allowed` | raw values, `,`-joined, ascending |
//! | `values` | the enumeration's raw values, `,`-joined, ascending |
//! | `bits` | the bit field's bits, then its fields as `LSB+WIDTH`, `,`-joined |
//! | `bounds` | `min:NAME`, `max:NAME`, `magnitude:NAME`, `,`-joined |
//! | `modbus` | `TABLE:0xADDR:ACCESS`, `xWORDS` when more than one, `@VARIANT` when limited to one |
//! | `canopen`, `rs232` | `IIII.SS:ACCESS`, `@VARIANT` when limited to one |
//! | `pdo` | the CANopen mappability: `none`, `rx`, `tx` or `both` |
//! | `variants` | the variants the parameter exists in, when not all |
//!
//! The table must be typed from the manual, never printed from the description: rendered from the
//! description it would agree with any mistake. [`render`] only shows the forms.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use drivegen::ir::{Access, Device, ModbusAddress, ObjectAddress, Parameter, Pdo, Scale};

pub mod notation;

/// One row of a manual table: a parameter's name and the properties the manual gives it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Row {
    /// The description's name of the parameter.
    pub name: String,
    /// The manual line the row was typed from.
    pub line: u32,
    /// The properties, by key.
    pub properties: BTreeMap<String, String>,
}

/// Reads a table: one row per line, `#` starts a comment. Numbers may be written as the manual
/// prints them (`0x` hex, fractions not in lowest terms, values in any order): [`notation`]
/// brings them to the forms [`render`] prints. Panics, naming the line, on a row it cannot read
/// (a test-support crate: the panic is the test failure).
pub fn parse(text: &str) -> Vec<Row> {
    text.lines()
        .enumerate()
        .filter_map(|(n, line)| {
            let content = line.split('#').next().unwrap_or("").trim();
            (!content.is_empty()).then(|| parse_row(content, n + 1))
        })
        .collect()
}

fn parse_row(content: &str, table_line: usize) -> Row {
    let mut tokens = content.split_whitespace();
    let name = tokens.next().unwrap_or_default().to_owned();
    let mut properties = BTreeMap::new();
    let mut line = None;
    for token in tokens {
        let Some((key, value)) = token.split_once('=') else {
            panic!("table line {table_line}: `{token}` is not key=value");
        };
        if key == "line" {
            line = Some(value.parse().unwrap_or_else(|_| {
                panic!("table line {table_line}: line={value} is not a number")
            }));
        } else if !KEYS.contains(&key) {
            panic!("table line {table_line}: unknown key `{key}` (known: {KEYS:?})");
        } else if properties
            .insert(key.to_owned(), notation::normalised(key, value))
            .is_some()
        {
            panic!("table line {table_line}: `{key}` given twice");
        }
    }
    let line = line.unwrap_or_else(|| panic!("table line {table_line}: `{name}` has no line="));
    Row {
        name,
        line,
        properties,
    }
}

/// Every key a row may give, in the order [`render`] prints them.
pub const KEYS: [&str; 14] = [
    "modbus", "canopen", "rs232", "pdo", "type", "unit", "scale", "range", "default", "allowed",
    "values", "bits", "bounds", "variants",
];

/// Every property the description gives `parameter`, in table form; properties it does not have
/// are left out.
pub fn properties(device: &Device, parameter: &Parameter) -> BTreeMap<String, String> {
    let p = parameter;
    let candidates: [(&str, Option<String>); 14] = [
        ("modbus", joined(p.modbus.iter().map(modbus))),
        ("canopen", joined(p.canopen.iter().map(object))),
        ("rs232", joined(p.rs232.iter().map(object))),
        ("pdo", pdo(&p.canopen)),
        ("type", Some(p.data_type.to_string())),
        ("unit", p.unit.clone()),
        ("scale", p.scale.as_ref().and_then(scale)),
        (
            "range",
            p.range.as_ref().map(|r| format!("{}..{}", r.min, r.max)),
        ),
        ("default", default(p)),
        ("allowed", allowed(p)),
        ("values", enum_values(device, p)),
        ("bits", bits(device, p)),
        ("bounds", bounds(p)),
        ("variants", joined(p.variants.iter().cloned())),
    ];
    candidates
        .into_iter()
        .filter_map(|(key, value)| Some((key.to_owned(), value?)))
        .collect()
}

/// The row the description would need for `parameter`: shows the forms of [`KEYS`]. Never paste
/// it into a table (see the crate docs).
pub fn render(device: &Device, parameter: &Parameter) -> String {
    let properties = properties(device, parameter);
    let mut row = parameter.name.clone();
    for key in KEYS {
        if let Some(value) = properties.get(key) {
            let _ = write!(row, " {key}={value}");
        }
    }
    row
}

/// Every difference between the table and the description, one message each (empty: they
/// agree). A row naming no described parameter is a difference too.
pub fn compare(device: &Device, rows: &[Row]) -> Vec<String> {
    rows.iter()
        .flat_map(|row| match device.parameter(&row.name) {
            None => vec![format!(
                "`{}` (manual line {}) is not described",
                row.name, row.line
            )],
            Some(parameter) => differences(row, &properties(device, parameter)),
        })
        .collect()
}

fn differences(row: &Row, described: &BTreeMap<String, String>) -> Vec<String> {
    KEYS.iter()
        .filter_map(|key| {
            let manual = row
                .properties
                .get(*key)
                .map(String::as_str)
                .filter(|v| *v != "-");
            let description = described.get(*key).map(String::as_str);
            (manual != description).then(|| {
                format!(
                    "`{}` {key}: the manual (line {}) gives {}, the description {}",
                    row.name,
                    row.line,
                    manual.unwrap_or("none"),
                    description.unwrap_or("none"),
                )
            })
        })
        .collect()
}

fn joined(items: impl Iterator<Item = String>) -> Option<String> {
    let mut items: Vec<String> = items.collect();
    items.sort();
    (!items.is_empty()).then(|| items.join(","))
}

/// The allowed raw values in ascending numeric order (`2` before `10`).
fn allowed(p: &Parameter) -> Option<String> {
    let mut values: Vec<(f64, String)> = p
        .allowed
        .iter()
        .map(|n| {
            let text = n.to_string();
            (text.parse().unwrap_or(f64::NAN), text)
        })
        .collect();
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    let texts: Vec<String> = values.into_iter().map(|(_, text)| text).collect();
    (!texts.is_empty()).then(|| texts.join(","))
}

fn access(access: Access) -> &'static str {
    match (access.read, access.write) {
        (true, true) => "rw",
        (true, false) => "r",
        (false, true) => "w",
        (false, false) => "none",
    }
}

fn variant(variant: &Option<String>) -> String {
    variant
        .as_ref()
        .map_or_else(String::new, |v| format!("@{v}"))
}

fn modbus(address: &ModbusAddress) -> String {
    let words = match address.words {
        1 => String::new(),
        n => format!("x{n}"),
    };
    format!(
        "{}:{:#06x}:{}{words}{}",
        format!("{:?}", address.table).to_lowercase(),
        address.address,
        access(address.access),
        variant(&address.variant),
    )
}

fn object(address: &ObjectAddress) -> String {
    format!(
        "{:04X}.{:02X}:{}{}",
        address.index,
        address.subindex,
        access(address.access),
        variant(&address.variant),
    )
}

fn pdo(addresses: &[ObjectAddress]) -> Option<String> {
    let kinds: std::collections::BTreeSet<&str> = addresses
        .iter()
        .map(|a| match a.pdo {
            Pdo::None => "none",
            Pdo::Rx => "rx",
            Pdo::Tx => "tx",
            Pdo::Both => "both",
        })
        .collect();
    joined(kinds.into_iter().map(str::to_owned))
}

fn scale(scale: &Scale) -> Option<String> {
    match scale {
        Scale::Runtime { .. } => Some("runtime".into()),
        Scale::Fixed(fixed) => {
            let ratio = |r: drivebus::Ratio| match r.denominator() {
                1 => r.numerator().to_string(),
                d => format!("{}/{d}", r.numerator()),
            };
            let offset = fixed.offset;
            let factor = ratio(fixed.factor);
            match (factor.as_str(), offset.numerator()) {
                ("1", 0) => None,
                (_, 0) => Some(factor),
                (_, n) if n > 0 => Some(format!("{factor}+{}", ratio(offset))),
                _ => Some(format!("{factor}{}", ratio(offset))),
            }
        }
    }
}

fn default(p: &Parameter) -> Option<String> {
    let value = p.default.as_ref()?;
    Some(if p.default_plus_node_id {
        format!("$NODEID+{value}")
    } else {
        value.to_string()
    })
}

fn enum_values(device: &Device, p: &Parameter) -> Option<String> {
    let e = device.enumeration(p.enumeration.as_deref()?)?;
    let mut values: Vec<i64> = e.values.iter().map(|v| v.value).collect();
    values.sort_unstable();
    Some(
        values
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(","),
    )
}

fn bits(device: &Device, p: &Parameter) -> Option<String> {
    let f = device.flags_type(p.flags.as_deref()?)?;
    let mut bits: Vec<u32> = f.bits.iter().map(|b| b.bit).collect();
    bits.sort_unstable();
    let singles = bits.iter().map(ToString::to_string);
    let fields = f
        .fields
        .iter()
        .map(|field| format!("{}+{}", field.lsb, field.width));
    Some(singles.chain(fields).collect::<Vec<_>>().join(","))
}

fn bounds(p: &Parameter) -> Option<String> {
    let b = p.bounds.as_ref()?;
    joined(
        [
            ("min", &b.min),
            ("max", &b.max),
            ("magnitude", &b.magnitude),
        ]
        .into_iter()
        .filter_map(|(kind, name)| Some(format!("{kind}:{}", name.as_ref()?))),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const DESCRIPTION: &str = r#"format = 1
[device]
name = "Table test"
handle = "TableTest"
[[source]]
id = "m"
file = "manual.txt"
title = "Manual"

[[enum]]
name = "mode"
type = "u16"
values = [ { name = "off", value = 0 }, { name = "on", value = 1 } ]
source = { doc = "m", line = 1 }

[[parameter]]
name = "speed"
type = "i16"
unit = "rpm"
scale = "1/10"
range = [-100, 100]
default = 5
modbus = { table = "holding", address = 0x42, access = "rw" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "mode"
type = "u16"
enum = "mode"
modbus = { table = "holding", address = 0x43, access = "rw" }
source = { doc = "m", line = 3 }
"#;

    fn device() -> Device {
        let checked = drivegen::check_text(
            std::path::Path::new("table-test/device.toml"),
            DESCRIPTION.into(),
        );
        let report = checked.render();
        checked.device.unwrap_or_else(|| panic!("{report}"))
    }

    #[test]
    fn a_row_that_gives_every_property_agrees() {
        let rows = parse(
            "speed modbus=holding:0x0042:rw type=i16 unit=rpm scale=1/10 range=-100..100 default=5 line=2\n\
             mode modbus=holding:0x0043:rw type=u16 values=0,1 line=3 # a note",
        );
        assert_eq!(compare(&device(), &rows), Vec::<String>::new());
    }

    #[test]
    fn a_wrong_default_fails() {
        let rows = parse("speed modbus=holding:0x0042:rw type=i16 unit=rpm scale=1/10 range=-100..100 default=6 line=2");
        assert_eq!(
            compare(&device(), &rows),
            ["`speed` default: the manual (line 2) gives 6, the description 5"]
        );
    }

    #[test]
    fn a_property_the_row_leaves_out_must_be_absent() {
        let rows = parse(
            "speed modbus=holding:0x0042:rw type=i16 unit=rpm scale=1/10 range=-100..100 line=2",
        );
        assert_eq!(
            compare(&device(), &rows),
            ["`speed` default: the manual (line 2) gives none, the description 5"]
        );
    }

    #[test]
    fn dash_states_none_and_unknown_names_are_reported() {
        let rows = parse(
            "mode modbus=holding:0x0043:rw type=u16 values=0,1 unit=- line=3\nmissing line=9",
        );
        assert_eq!(
            compare(&device(), &rows),
            ["`missing` (manual line 9) is not described"]
        );
    }

    #[test]
    fn render_shows_the_forms() {
        let d = device();
        assert_eq!(
            render(&d, d.parameter("speed").unwrap()),
            "speed modbus=holding:0x0042:rw type=i16 unit=rpm scale=1/10 range=-100..100 default=5"
        );
    }

    #[test]
    #[should_panic(expected = "unknown key `colour`")]
    fn unknown_keys_are_refused() {
        parse("speed colour=red line=1");
    }
}

//! Changes to parameters: presence, value and raw types, capabilities per protocol and direction,
//! and the addresses, scales, limits and defaults behind them.

use super::{match_by_name, Change, Impact};
use crate::ir::{Effect, ModbusAddress, Number, ObjectAddress, Parameter, Scale, WordOrder};

/// Compares the parameter lists of two descriptions.
pub(super) fn compare(old: &[Parameter], new: &[Parameter], out: &mut Vec<Change>) {
    let matched = match_by_name(old, new, |p| &p.name);
    for p in matched.removed {
        out.push(Change::new(Impact::Breaking, subject(p), "removed"));
    }
    for p in matched.added {
        out.push(Change::new(Impact::Compatible, subject(p), "added"));
    }
    for (o, n) in matched.both {
        types(o, n, out);
        capabilities(o, n, out);
        behaviour(o, n, out);
    }
}

fn subject(p: &Parameter) -> String {
    format!("parameter `{}`", p.name)
}

/// The value type users handle and the raw type of `read_raw` / `write_raw`.
fn types(o: &Parameter, n: &Parameter, out: &mut Vec<Change>) {
    if o.value_type() != n.value_type() {
        out.push(Change::new(
            Impact::Breaking,
            subject(o),
            format!("value type {} → {}", o.value_type(), n.value_type()),
        ));
    }
    super::types::raw_type(&subject(o), o.data_type, n.data_type, out);
}

/// Read or write.
#[derive(Clone, Copy)]
enum Direction {
    Read,
    Write,
}

impl Direction {
    fn word(self) -> &'static str {
        match self {
            Direction::Read => "readable",
            Direction::Write => "writable",
        }
    }
}

/// The addresses a parameter is read or written at over one protocol, described in words.
type Addresses = fn(&Parameter, Direction) -> Vec<String>;

/// A lost capability removes a trait impl (breaking); a gained one adds one; a moved address
/// changes where the value travels.
fn capabilities(o: &Parameter, n: &Parameter, out: &mut Vec<Change>) {
    let protocols: [(&str, Addresses); 2] = [("Modbus", modbus), ("CANopen", canopen)];
    for (protocol, addresses) in protocols {
        for direction in [Direction::Read, Direction::Write] {
            let (before, after) = (addresses(o, direction), addresses(n, direction));
            let what = format!("{} over {protocol}", direction.word());
            let change = match (before.is_empty(), after.is_empty()) {
                (false, true) => {
                    Change::new(Impact::Breaking, subject(o), format!("no longer {what}"))
                }
                (true, false) => Change::new(Impact::Compatible, subject(o), format!("now {what}")),
                _ if before != after => Change::new(
                    Impact::Behaviour,
                    subject(o),
                    format!("{what} at {} → {}", before.join(", "), after.join(", ")),
                ),
                _ => continue,
            };
            out.push(change);
        }
    }
}

fn allows(direction: Direction, read: bool, write: bool) -> bool {
    match direction {
        Direction::Read => read,
        Direction::Write => write,
    }
}

fn modbus(p: &Parameter, direction: Direction) -> Vec<String> {
    p.modbus
        .iter()
        .filter(|a| allows(direction, a.access.read, a.access.write))
        .map(describe_modbus)
        .collect()
}

fn canopen(p: &Parameter, direction: Direction) -> Vec<String> {
    p.canopen
        .iter()
        .filter(|a| allows(direction, a.access.read, a.access.write))
        .map(describe_object)
        .collect()
}

fn describe_modbus(a: &ModbusAddress) -> String {
    let mut text = format!("{} 0x{:04X}", a.table.name(), a.address);
    if a.words > 1 {
        let order = match a.word_order {
            WordOrder::HighFirst => "high first",
            WordOrder::LowFirst => "low first",
            WordOrder::Text => "text, high byte first",
        };
        text += &format!(" ({} words, {order})", a.words);
    }
    text + &in_variant(&a.variant)
}

fn describe_object(a: &ObjectAddress) -> String {
    format!("0x{:04X}:{:02X}", a.index, a.subindex) + &in_variant(&a.variant)
}

fn in_variant(variant: &Option<String>) -> String {
    variant
        .as_ref()
        .map(|v| format!(" in {v}"))
        .unwrap_or_default()
}

/// One fact about a parameter, in words, for comparison.
type Describe = fn(&Parameter) -> String;

/// Scale, limits, default, variants and when a write takes effect: the code still compiles, but
/// the same call reads, writes or is refused differently.
const FACTS: [(&str, Describe); 6] = [
    ("scale", |p| scale(&p.scale)),
    ("range", range),
    ("allowed values", |p| list(&p.allowed)),
    ("default", |p| {
        p.default.map_or_else(|| "none".into(), |n| n.to_string())
    }),
    ("variants", variants),
    ("takes effect", |p| effect(p.effect).into()),
];

fn behaviour(o: &Parameter, n: &Parameter, out: &mut Vec<Change>) {
    for (fact, describe) in FACTS {
        let (before, after) = (describe(o), describe(n));
        if before != after {
            out.push(Change::new(
                Impact::Behaviour,
                subject(o),
                format!("{fact} {before} → {after}"),
            ));
        }
    }
}

fn range(p: &Parameter) -> String {
    p.range
        .as_ref()
        .map_or_else(|| "none".into(), |r| format!("{}..={}", r.min, r.max))
}

fn variants(p: &Parameter) -> String {
    if p.variants.is_empty() {
        "all".into()
    } else {
        p.variants.join(", ")
    }
}

fn scale(scale: &Option<Scale>) -> String {
    match scale {
        None => "none".into(),
        Some(Scale::Fixed(scale)) if scale.offset == drivebus_model::Ratio::ZERO => {
            ratio(scale.factor)
        }
        Some(Scale::Fixed(scale)) => format!("{} + {}", ratio(scale.factor), ratio(scale.offset)),
        Some(Scale::Runtime { expr, .. }) => format!("`{expr}`"),
    }
}

fn ratio(ratio: drivebus_model::Ratio) -> String {
    match (ratio.numerator(), ratio.denominator()) {
        (numerator, 1) => numerator.to_string(),
        (numerator, denominator) => format!("{numerator}/{denominator}"),
    }
}

fn list(values: &[Number]) -> String {
    if values.is_empty() {
        return "any".into();
    }
    values
        .iter()
        .map(|n| n.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

fn effect(effect: Effect) -> &'static str {
    match effect {
        Effect::Immediate => "at once",
        Effect::AfterReset => "after a reset",
        Effect::AfterStoreReset => "after store and reset",
    }
}

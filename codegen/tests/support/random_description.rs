//! Random TOML descriptions for property tests: every type, units, fixed and run-time scales,
//! ranges, defaults, allowed values, enums, flags, records, variants, commands, effects, PDO
//! mappings, Modbus, CANopen and RS-232 addresses and awkward names. About four in five are valid
//! (the rest have, for instance, a run-time scale over an input it cannot read, or two enum values
//! that name the same Rust identifier).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;

const TYPES: &[&str] = &[
    "bool", "u8", "u16", "u32", "u64", "i8", "i16", "i32", "i64", "u24", "u40", "u48", "u56",
    "i24", "i40", "i48", "i56", "f32", "f64", "string", "octets",
];

const UNITS: &[&str] = &[
    "V", "mV", "A", "rpm", "rpm/s", "°C", "%", "‰", "s", "ms", "µs", "Hz", "W", "Nm", "Ω",
    "kg·cm²", "bit/s",
];

const INTEGER_TYPES: &[&str] = &["u8", "u16", "u32", "i8", "i16", "i32"];

/// Types 1, 2 or 4 bytes wide: the ones a Kinco RS-232 telegram carries.
const RS232_TYPES: &[&str] = &["bool", "u8", "u16", "u32", "i8", "i16", "i32", "f32"];

/// Names that are awkward as Rust identifiers, or plain ones.
fn name() -> impl Strategy<Value = String> {
    prop_oneof![
        "[a-z][a-z0-9_]{0,12}",
        proptest::sample::select(
            &[
                "type", "self", "crate", "super", "r", "new", "read", "write", "value", "raw",
                "default", "range", "unknown", "bits", "all", "empty", "from_raw", "to_raw",
            ][..]
        )
        .prop_map(str::to_owned),
    ]
}

/// A value in `0..=100` as written for `ty`: a float for float types, 0/1 for `bool`.
fn raw(ty: &str, n: u8) -> String {
    match ty {
        "bool" => (n % 2).to_string(),
        "f32" | "f64" => format!("{n}.5"),
        _ => n.to_string(),
    }
}

/// An `[[enum]]` over an integer type with one to four values.
fn enumeration(index: usize) -> impl Strategy<Value = (String, String)> {
    let values = proptest::collection::btree_map(name(), 0u8..=100, 1..=4);
    (proptest::sample::select(INTEGER_TYPES), name(), values).prop_map(move |(ty, name, values)| {
        let name = format!("{name}_e{index}");
        let values: Vec<String> = values
            .into_iter()
            .map(|(n, v)| format!("{{ name = \"{n}\", value = {v}, doc = \"Value {v}.\" }}"))
            .collect();
        let toml = format!(
            "[[enum]]\nname = \"{name}\"\ntype = \"{ty}\"\ndoc = \"An enum.\"\nsource = {{ doc = \"m\", line = 1 }}\nvalues = [{}]\n\n",
            values.join(", ")
        );
        (ty.to_owned(), toml)
    })
}

/// A `[[flags]]` over an unsigned type with named bits and maybe a two-bit field.
fn flags(index: usize) -> impl Strategy<Value = (String, String)> {
    let bits = proptest::collection::btree_map(0u8..8, name(), 1..=4);
    (
        proptest::sample::select(&["u8", "u16", "u32"][..]),
        name(),
        bits,
        any::<bool>(),
    )
        .prop_map(move |(ty, name, bits, field)| {
            let name = format!("{name}_f{index}");
            let bits: Vec<String> = bits
                .into_iter()
                .map(|(bit, n)| format!("{{ name = \"{n}_{bit}\", bit = {bit}, doc = \"Bit.\" }}"))
                .collect();
            let fields = if field {
                "fields = [{ name = \"two_bits\", lsb = 8, width = 2, doc = \"A field.\" }]\n"
            } else {
                ""
            };
            let ty = if field && ty == "u8" { "u16" } else { ty };
            let toml = format!(
                "[[flags]]\nname = \"{name}\"\ntype = \"{ty}\"\ndoc = \"Flags.\"\nsource = {{ doc = \"m\", line = 1 }}\nbits = [{}]\n{fields}\n",
                bits.join(", ")
            );
            (ty.to_owned(), toml)
        })
}

/// What a parameter may say besides its name, type and addresses.
#[derive(Debug, Clone)]
struct Extras {
    unit: Option<&'static str>,
    scale: Option<&'static str>,
    range: Option<(u8, u8)>,
    default: Option<u8>,
    allowed: Option<Vec<u8>>,
    typed_by: u8,
    effect: &'static str,
    command: bool,
    variant: Option<u8>,
    access: &'static str,
    /// A scale computed at run time from the first parameter, instead of a fixed one.
    runtime_scale: bool,
    /// A member of record `members` (CANopen 0x3000) instead of an object of its own.
    member: bool,
    /// Also a Kinco RS-232 address.
    rs232: bool,
    /// PDO-mappable in the directions its access allows (and then maybe mapped).
    pdo: bool,
}

fn extras() -> impl Strategy<Value = Extras> {
    (
        (
            proptest::option::of(proptest::sample::select(UNITS)),
            proptest::option::of(proptest::sample::select(
                &[
                    "\"1/100\"",
                    "\"0.1\"",
                    "10",
                    "{ factor = \"1/10\", offset = \"-40\" }",
                ][..],
            )),
            proptest::option::of((0u8..=50, 50u8..=100)),
            proptest::option::of(0u8..=100),
            proptest::option::of(proptest::collection::vec(0u8..=100, 1..=3)),
        ),
        (
            0u8..4,
            proptest::sample::select(&["immediate", "after-reset", "after-store-reset"][..]),
            proptest::bool::weighted(0.1),
            proptest::option::of(0u8..2),
            proptest::sample::select(&["r", "w", "rw"][..]),
        ),
        (
            proptest::bool::weighted(0.2),
            proptest::bool::weighted(0.25),
            proptest::bool::weighted(0.2),
            proptest::bool::weighted(0.4),
        ),
    )
        .prop_map(
            |(
                (unit, scale, range, default, allowed),
                (typed_by, effect, command, variant, access),
                (runtime_scale, member, rs232, pdo),
            )| {
                Extras {
                    runtime_scale,
                    member,
                    rs232,
                    pdo,
                    unit,
                    scale,
                    range,
                    default,
                    allowed,
                    typed_by,
                    effect,
                    command,
                    variant,
                    access,
                }
            },
        )
}

/// Words a type takes in Modbus registers.
fn words(ty: &str) -> u16 {
    match ty {
        "bool" | "u8" | "i8" | "u16" | "i16" => 1,
        "u24" | "i24" | "u32" | "i32" | "f32" => 2,
        "string" | "octets" => 4,
        "u40" | "i40" | "u48" | "i48" => 3,
        _ => 4,
    }
}

/// What parameters may refer to: the description's enums and flags (type, TOML), and the name of
/// its first parameter (the input of run-time scales).
struct Context<'a> {
    enums: &'a [(String, String)],
    flags: &'a [(String, String)],
    first: String,
}

/// The enum or flags type parameter `index` takes, if any: key (`enum` / `flags`), its integer
/// type and its name.
fn typing<'c>(
    index: usize,
    x: &Extras,
    cx: &'c Context,
) -> Option<(&'static str, &'c str, &'c str)> {
    let (key, types) = match x.typed_by {
        1 => ("enum", cx.enums),
        2 => ("flags", cx.flags),
        _ => return None,
    };
    let (ty, toml) = types.get(index % types.len().max(1))?;
    Some((key, ty, toml.split('"').nth(1).unwrap_or_default()))
}

/// The type parameter `index` ends up with: its own, or its enum's or flags'.
fn effective_type<'a>(index: usize, ty: &'a str, x: &Extras, cx: &'a Context) -> &'a str {
    typing(index, x, cx).map_or(ty, |(_, ty, _)| ty)
}

/// Bits a value of `ty` takes in a PDO; `None` for strings.
fn pdo_bits(ty: &str) -> Option<u32> {
    match ty {
        "bool" => Some(1),
        "string" | "octets" => None,
        "f32" => Some(32),
        "f64" => Some(64),
        _ => ty[1..].parse().ok(),
    }
}

/// One `[[parameter]]` at Modbus register `address` and CANopen index `0x2000 + index` (or
/// sub-index `index + 1` of record `members`).
fn parameter(index: usize, address: u16, name: &str, ty: &str, x: &Extras, cx: &Context) -> String {
    let mut toml =
        format!("[[parameter]]\nname = \"{name}_{index}\"\ndoc = \"Parameter {index}.\"\n");
    // An enum or flags type gives the parameter its own type.
    let typed = typing(index, x, cx);
    if let Some((key, _, type_name)) = typed {
        let _ = writeln!(toml, "{key} = \"{type_name}\"");
    }
    let ty = effective_type(index, ty, x, cx);
    let _ = writeln!(toml, "type = \"{ty}\"");
    let numeric = !matches!(ty, "string" | "octets");
    if !numeric {
        toml += "length = 8\n";
    }
    if typed.is_none() && numeric && ty != "bool" {
        if let Some(unit) = x.unit {
            let _ = writeln!(toml, "unit = \"{unit}\"");
        }
        match x.scale {
            Some(_) if x.runtime_scale && index > 0 => {
                let _ = writeln!(toml, "scale = {{ expr = \"2 * {}\" }}", cx.first);
            }
            Some(scale) => {
                let _ = writeln!(toml, "scale = {scale}");
            }
            None => {}
        }
    }
    if typed.is_none() && numeric {
        if let Some((lo, hi)) = x.range {
            let _ = writeln!(toml, "range = [{}, {}]", raw(ty, lo), raw(ty, hi));
        }
        // Allowed values and defaults inside the range: most descriptions then check valid.
        let (lo, hi) = x.range.unwrap_or((0, 100));
        if let Some(allowed) = &x.allowed {
            let values: Vec<String> = allowed.iter().map(|&v| raw(ty, v.clamp(lo, hi))).collect();
            let _ = writeln!(toml, "allowed = [{}]", values.join(", "));
        }
        if let Some(default) = x.default {
            let default = x.allowed.as_ref().map_or(default, |a| a[0]).clamp(lo, hi);
            let _ = writeln!(toml, "default = {}", raw(ty, default));
        }
    }
    if x.command && INTEGER_TYPES.contains(&ty) {
        toml += "command = { kind = \"store\", value = 1 }\n";
    }
    let _ = writeln!(toml, "effect = \"{}\"", x.effect);
    if let Some(v) = x.variant {
        let _ = writeln!(toml, "variants = [\"v{v}\"]");
    }
    let table = if x.access == "r" { "input" } else { "holding" };
    let _ = writeln!(
        toml,
        "modbus = {{ table = \"{table}\", address = {address}, words = {}, access = \"{}\" }}",
        words(ty),
        x.access
    );
    let (object, subindex) = match x.member {
        true => (0x3000, index + 1),
        false => (0x2000 + index, 0),
    };
    if x.member {
        toml += "record = \"members\"\n";
    }
    let pdo = match (x.pdo, x.access) {
        (false, _) => "false",
        (true, "r") => "\"tx\"",
        (true, "w") => "\"rx\"",
        (true, _) => "\"both\"",
    };
    let _ = writeln!(
        toml,
        "canopen = {{ index = 0x{object:04X}, subindex = {subindex}, access = \"{}\", pdo = {pdo} }}",
        x.access
    );
    // An RS-232 telegram carries 1, 2 or 4 bytes (rule `rs232_values_fit_a_telegram`).
    if x.rs232 && RS232_TYPES.contains(&ty) {
        let _ = writeln!(
            toml,
            "rs232 = {{ index = 0x{object:04X}, subindex = {subindex}, access = \"{}\" }}",
            x.access
        );
    }
    toml + "source = { doc = \"m\", section = \"1\", line = 1 }\n\n"
}

/// A `[[pdo]]` in `direction` mapping the first parameters whose access has `access` and whose
/// address is mappable, within 64 bits; nothing without such parameters.
fn pdo(
    number: u16,
    direction: &str,
    cob_id: u16,
    access: char,
    parameters: &[(String, &str, Extras)],
    cx: &Context,
) -> String {
    let mut bits = 0;
    let mut entries = Vec::new();
    for (i, (name, ty, x)) in parameters.iter().enumerate() {
        let Some(size) = pdo_bits(effective_type(i, ty, x, cx)) else {
            continue;
        };
        if x.pdo && x.access.contains(access) && bits + size <= 64 && entries.len() < 4 {
            bits += size;
            entries.push(format!("\"{name}_{i}\""));
        }
    }
    if entries.is_empty() {
        return String::new();
    }
    format!(
        "[[pdo]]\nname = \"{direction}pdo{number}\"\ndirection = \"{direction}\"\nnumber = {number}\ncob_id = \"$NODEID+0x{cob_id:X}\"\ntransmission_type = 1\nentries = [{}]\nsource = {{ doc = \"m\", line = 1 }}\n\n",
        entries.join(", ")
    )
}

/// Parameters of the shipped CiA 402 profile a description may include.
pub const CIA402: &[&str] = &[
    "controlword",
    "statusword",
    "modes_of_operation",
    "modes_of_operation_display",
];

/// The `include` line of the CiA 402 profile restricted to `only`; nothing without.
fn include(only: Option<&[&str]>) -> String {
    let Some(only) = only else {
        return String::new();
    };
    // Every crate including this module has its manifest one level below the workspace root.
    let profile = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/profiles/cia402.toml"
    );
    let only: Vec<String> = only.iter().map(|n| format!("{n:?}")).collect();
    format!(
        "include = [{{ path = {profile:?}, only = [{}] }}]\n",
        only.join(", ")
    )
}

/// A whole description: device, Modbus and CANopen capabilities, two variants, enums, flags,
/// one to eight parameters, and maybe some CiA 402 profile parameters.
pub fn description() -> impl Strategy<Value = String> {
    let enums = (0usize..3).prop_flat_map(|n| (0..n).map(enumeration).collect::<Vec<_>>());
    let flags = (0usize..3).prop_flat_map(|n| (0..n).map(flags).collect::<Vec<_>>());
    let parameters =
        proptest::collection::vec((name(), proptest::sample::select(TYPES), extras()), 1..=8);
    let included = proptest::option::weighted(0.3, proptest::sample::subsequence(CIA402, 1..=4));
    (
        enums,
        flags,
        parameters,
        proptest::sample::select(&["high-first", "low-first"][..]),
        any::<bool>(),
        included,
    )
        .prop_map(|(enums, flags, parameters, word_order, read_gaps, included)| {
            let mut toml = format!("format = 1\n{}", include(included.as_deref()));
            let _ = write!(
                toml,
                "\n[device]\nname = \"Random\"\nhandle = \"Random\"\nvendor = \"ACME\"\nsource = {{ doc = \"m\", line = 1 }}\n\n\
                 [[source]]\nid = \"m\"\nfile = \"m.txt\"\ntitle = \"Manual\"\n\n\
                 [modbus]\nword_order = \"{word_order}\"\nread_gaps = {read_gaps}\nsource = {{ doc = \"m\", line = 1 }}\n\n\
                 [canopen]\ndefault_node_id = 5\nsource = {{ doc = \"m\", line = 1 }}\n\n"
            );
            toml += MANDATORY_OBJECTS;
            for v in 0..2 {
                let _ = write!(
                    toml,
                    "[[variant]]\nname = \"v{v}\"\ndoc = \"Variant {v}.\"\nsource = {{ doc = \"m\", line = 1 }}\n\n"
                );
            }
            for (_, t) in enums.iter().chain(&flags) {
                toml += t;
            }
            if parameters.iter().any(|(_, _, x)| x.member) {
                toml += "[[record]]\nname = \"members\"\nkind = \"record\"\nindex = 0x3000\ndoc = \"A record.\"\nsource = { doc = \"m\", line = 1 }\n\n";
            }
            let cx = Context {
                enums: &enums,
                flags: &flags,
                first: format!("{}_0", parameters[0].0),
            };
            let mut address = 0;
            for (i, (name, ty, x)) in parameters.iter().enumerate() {
                toml += &parameter(i, address, name, ty, x, &cx);
                address += 8;
            }
            for (number, direction, cob_id, access) in [(1, "tx", 0x180, 'r'), (1, "rx", 0x200, 'w')] {
                toml += &pdo(number, direction, cob_id, access, &parameters, &cx);
            }
            toml
        })
}

/// The CiA 301 objects every CANopen description must have (rule `canopen_has_mandatory_objects`).
const MANDATORY_OBJECTS: &str = "\
[[parameter]]\nname = \"device_type\"\ndoc = \"Device type.\"\ntype = \"u32\"\ncanopen = { index = 0x1000, subindex = 0, access = \"ro\" }\nsource = { doc = \"m\", line = 1 }\n\n\
[[parameter]]\nname = \"error_register\"\ndoc = \"Error register.\"\ntype = \"u8\"\ncanopen = { index = 0x1001, subindex = 0, access = \"ro\" }\nsource = { doc = \"m\", line = 1 }\n\n\
[[parameter]]\nname = \"identity_count\"\ndoc = \"Identity entries.\"\ntype = \"u8\"\ncanopen = { index = 0x1018, subindex = 0, access = \"ro\" }\nsource = { doc = \"m\", line = 1 }\n\n\
[[parameter]]\nname = \"vendor_id\"\ndoc = \"Vendor-ID.\"\ntype = \"u32\"\ncanopen = { index = 0x1018, subindex = 1, access = \"ro\" }\nsource = { doc = \"m\", line = 1 }\n\n";

/// `count` valid random descriptions written into `dir` as `random_N.toml`, the same on every run.
pub fn valid_descriptions(count: usize, dir: &Path) -> Vec<PathBuf> {
    let mut runner = TestRunner::deterministic();
    let strategy = description();
    let mut paths = Vec::new();
    while paths.len() < count {
        let text = strategy.new_tree(&mut runner).unwrap().current();
        let path = dir.join(format!("random_{}.toml", paths.len()));
        std::fs::write(&path, text).unwrap();
        if drivegen::check(&path).device.is_some() {
            paths.push(path);
        }
    }
    paths
}

/// A raw integer that exercises `p`'s whole width and still passes its checks: its last allowed
/// value, the top of its range, `true`, or else near the type's edge (high bits set; negative for
/// signed types). `None` for non-integer types.
pub fn telling_integer(p: &drivegen::ir::Parameter) -> Option<i128> {
    if let Some(last) = p.allowed.last() {
        return last.as_int().map(i128::from);
    }
    if let Some(range) = &p.range {
        return range.max.as_int().map(i128::from);
    }
    let (lo, hi) = p.data_type.integer_bounds()?;
    Some(match p.data_type {
        drivegen::ir::DataType::Bool => 1,
        _ if lo < 0 => lo + 5,
        _ => hi - 5,
    })
}

/// Whether `p` is an integer (or boolean) parameter of the default variant `v0` on Modbus, not a
/// command: one whose value a test can write and read back.
pub fn modbus_integer(p: &drivegen::ir::Parameter) -> bool {
    let in_default_variant = p.variants.is_empty() || p.variants.iter().any(|v| v == "v0");
    let integer = p.data_type.integer_bounds().is_some();
    in_default_variant && integer && p.command.is_none() && !p.modbus.is_empty()
}

/// [`modbus_integer`], and valued by its raw number (no enum or flags type).
pub fn plain_modbus_integer(p: &drivegen::ir::Parameter) -> bool {
    modbus_integer(p) && p.enumeration.is_none() && p.flags.is_none()
}

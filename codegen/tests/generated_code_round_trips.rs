//! The generated crates of random valid descriptions against their own simulators: through the
//! generated typed API over Modbus TCP (`write` / `read` in engineering units where a parameter
//! has a unit or a fixed scale, `write_raw` / `read_raw` otherwise, with its marker type), every
//! plain integer or boolean parameter of the default variant takes a value filling its type,
//! which the simulator holds and the generated code reads back unchanged — every width, odd
//! width, word count, word order and table. Each generated PDO struct of integer entries encodes
//! to the payload packed independently here, and decodes back. The generated code and the simulator decode registers
//! independently (drivebus's `parameter!` codecs against drivesim's IR-driven store).

mod support;

use std::fmt::Write as _;
use std::path::Path;

use drivegen::ir::{pdo_bits, DataType, Device, Parameter, Scale, ValueType};
use drivegen::names;
use support::crate_build::{build_and_test, generated, no_std_lib};
use support::random_description::{modbus_integer, telling_integer, valid_descriptions};
use support::{short_name, Scratch};

/// The Rust literal of raw value `value` of `data_type`.
fn literal(data_type: DataType, value: i128) -> String {
    match data_type {
        DataType::Bool => (value != 0).to_string(),
        _ => value.to_string(),
    }
}

/// The Rust expression of the engineering value `raw` stands for, where `p`'s value is a unit
/// newtype or a bare scaled `f64` with a fixed scale; `None` otherwise.
fn engineering(p: &Parameter, raw: i128) -> Option<String> {
    let unit = match p.value_type() {
        ValueType::Unit(unit) => Some(unit),
        ValueType::Scaled => None,
        _ => return None,
    };
    let scale = match &p.scale {
        None => drivebus::Scale::IDENTITY,
        Some(Scale::Fixed(scale)) => *scale,
        Some(Scale::Runtime { .. }) => return None,
    };
    let value = scale.to_engineering(i64::try_from(raw).ok()?);
    Some(match unit {
        Some(unit) => format!("::drivebus::units::{unit}({value:?})"),
        None => format!("{value:?}f64"),
    })
}

/// The raw value the test gives `p`, and the Rust expression of its engineering value where it
/// has one: an enum's last value, a flags type's first bit, a unit newtype or scaled `f64` (within
/// ±10^6 raw steps, so that the engineering value is exact); `None` for raw-valued parameters.
fn typed_value(module: &str, device: &Device, p: &Parameter) -> Option<(i128, Option<String>)> {
    let types = format!("random_round_trips::{module}::types");
    if let Some(e) = p.enumeration.as_deref().and_then(|e| device.enumeration(e)) {
        let last = e.values.last()?;
        let constant = names::constant(&last.name);
        let typed = format!("{types}::{}::{constant}", names::camel(&e.name));
        return Some((i128::from(last.value), Some(typed)));
    }
    if let Some(f) = p.flags.as_deref().and_then(|f| device.flags_type(f)) {
        let first = f.bits.first()?;
        let constant = names::constant(&first.name);
        let typed = format!("{types}::{}::{constant}", names::camel(&f.name));
        return Some((1 << first.bit, Some(typed)));
    }
    let telling = telling_integer(p)?;
    let steps = telling.clamp(-1_000_000, 1_000_000);
    Some(match engineering(p, steps) {
        Some(typed) => (steps, Some(typed)),
        None => (telling, None),
    })
}

/// One `#[test]` writing and reading back every plain integer parameter of `device`, whose
/// generated code is module `module` of crate `random_round_trips`. Returns the test and how many
/// values it reads back.
fn round_trip_test(module: &str, path: &Path, device: &Device) -> (String, usize) {
    let mut test = format!(
        "#[test]\nfn {module}() {{\n    let sim = drivesim::Simulator::load({path:?}).unwrap();\n    \
         let server = sim.serve_modbus_tcp(\"127.0.0.1:0\", UnitId(1)).unwrap();\n    \
         let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();\n    \
         let mut drive = random_round_trips::{module}::Random::modbus(bus, UnitId(1));\n    \
         let device = drive.device();\n"
    );
    let mut read_back = 0;
    // A run-time scaled parameter is on Modbus only where its inputs can be read there
    // (`scale_inputs_exist`): left out here.
    let fixed_scale = |p: &&Parameter| !matches!(p.scale, Some(Scale::Runtime { .. }));
    let tested = device.parameters.iter().filter(|p| modbus_integer(p));
    for p in tested.filter(fixed_scale) {
        let name = &p.name;
        let marker = format!(
            "random_round_trips::{module}::params::{}",
            names::camel(name)
        );
        let Some((value, typed)) = typed_value(module, device, p) else {
            continue;
        };
        let (write, read) = match typed {
            Some(typed) => (
                format!("write::<{marker}>({typed})"),
                format!("read::<{marker}>().unwrap(), {typed}"),
            ),
            None => {
                let raw = literal(p.data_type, value);
                (
                    format!("write_raw::<{marker}>({raw})"),
                    format!("read_raw::<{marker}>().unwrap(), {raw}"),
                )
            }
        };
        let address = &p.modbus[0];
        if address.access.write {
            let _ = writeln!(test, "    device.{write}.unwrap();");
        } else {
            let _ = writeln!(test, "    sim.preset({name:?}, {value}).unwrap();");
        }
        let _ = writeln!(
            test,
            "    assert_eq!(held(&sim, {name:?}), {value}, \"{name} held by the simulator\");"
        );
        if address.access.read {
            let _ = writeln!(test, "    assert_eq!(device.{read}, \"{name} read back\");");
            read_back += 1;
        }
    }
    test += "}\n\n";
    (test, read_back)
}

/// One `#[test]` per description with PDO mappings of integer entries: each generated PDO struct,
/// filled with the values the register tests use, encodes to the payload packed here from the
/// raw values (little-endian, from bit 0, in entry order) and decodes back to itself.
fn pdo_test(module: &str, device: &Device) -> Option<(String, usize)> {
    let mut test = format!("#[test]\nfn {module}_pdos() {{\n");
    let mut checked = 0;
    for (pdo, _) in device.pdos() {
        let Some(fields) = pdo_fields(module, device, &pdo.entries) else {
            continue;
        };
        let (mut packed, mut bits) = (0u64, 0);
        let mut init = String::new();
        for (field, raw, typed, width) in fields {
            packed |= (raw as u64 & (u64::MAX >> (64 - width))) << bits;
            bits += width;
            let _ = write!(init, "{field}: {typed}, ");
        }
        let bytes = &packed.to_le_bytes()[..(bits as usize).div_ceil(8)];
        let ty = format!(
            "random_round_trips::{module}::pdo::{}",
            names::camel(&pdo.name)
        );
        let _ = write!(
            test,
            "    let pdo = {ty} {{ {init}}};\n    let payload = pdo.encode().unwrap();\n    \
             assert_eq!(payload.as_bytes(), &{bytes:?}, \"{name} payload\");\n    \
             assert_eq!({ty}::decode(payload.as_bytes()).unwrap(), pdo, \"{name} decoded\");\n",
            name = pdo.name
        );
        checked += 1;
    }
    (checked > 0).then(|| (test + "}\n\n", checked))
}

/// The fields of a PDO struct mapping `entries`: field name, raw value, value expression and
/// bits; `None` if some entry has no integer value to give.
fn pdo_fields(
    module: &str,
    device: &Device,
    entries: &[String],
) -> Option<Vec<(String, i128, String, u32)>> {
    entries
        .iter()
        .map(|entry| {
            let p = device.parameter(entry)?;
            let (raw, typed) = typed_value(module, device, p)?;
            let typed = typed.unwrap_or_else(|| literal(p.data_type, raw));
            Some((names::snake(entry), raw, typed, pdo_bits(p.data_type)))
        })
        .collect()
}

const TEST_PRELUDE: &str = "//! Generated round trips.\n\
#![allow(unused_variables)] // A description may have no parameter to test.\n\
use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};\n\
use drivebus::modbus::UnitId;\n\n\
/// The raw integer the simulator holds for `name`.\n\
fn held(sim: &drivesim::Simulator, name: &str) -> i128 {\n    \
    sim.with(|drive| drive.store().int(drive.store().id(name).unwrap()).unwrap())\n}\n\n";

#[test]
fn generated_code_round_trips_values_through_the_simulator() {
    let scratch = Scratch::new("generated-round-trips");
    let mut modules = String::new();
    let mut tests = String::from(TEST_PRELUDE);
    let (mut read_back, mut pdos) = (0, 0);
    for path in valid_descriptions(32, &scratch.0) {
        let module = short_name(&path);
        let device = drivegen::check(&path).device.unwrap();
        let _ = write!(
            modules,
            "/// Generated from {module}.\npub mod {module} {{\n{}\n}}\n",
            generated(&path)
        );
        let (test, count) = round_trip_test(&module, &path, &device);
        tests += &test;
        read_back += count;
        if let Some((test, count)) = pdo_test(&module, &device) {
            tests += &test;
            pdos += count;
        }
    }
    assert!(read_back >= 10, "only {read_back} values are read back");
    assert!(pdos >= 5, "only {pdos} PDO mappings are encoded");
    let built = build_and_test("random_round_trips", &no_std_lib(&modules), &tests);
    assert!(
        built.success,
        "the generated round trips fail (set DRIVEGEN_KEEP_SCRATCH to keep the descriptions):\n{}\n{}",
        built.stdout,
        built.stderr
    );
}

//! The generated crates of random valid descriptions against their own simulators: through the
//! generated typed API (`write_raw` / `read_raw` with each parameter's marker type) over Modbus
//! TCP, every plain integer or boolean parameter of the default variant takes a value filling its
//! type, which the simulator holds and the generated code reads back unchanged — every width, odd
//! width, word count, word order and table. The generated code and the simulator decode registers
//! independently (drivebus's `parameter!` codecs against drivesim's IR-driven store).

mod support;

use std::fmt::Write as _;
use std::path::Path;

use drivegen::emit::ident;
use drivegen::ir::{DataType, Device};
use support::crate_build::{build_and_test, generated, no_std_lib};
use support::random_description::{plain_modbus_integer, telling_integer, valid_descriptions};
use support::{short_name, Scratch};

/// The Rust literal of raw value `value` of `data_type`.
fn literal(data_type: DataType, value: i128) -> String {
    match data_type {
        DataType::Bool => (value != 0).to_string(),
        _ => value.to_string(),
    }
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
    for p in device.parameters.iter().filter(|p| plain_modbus_integer(p)) {
        let Some(value) = telling_integer(p) else {
            continue;
        };
        let name = &p.name;
        let marker = format!(
            "random_round_trips::{module}::params::{}",
            ident::camel(name)
        );
        let raw = literal(p.data_type, value);
        let address = &p.modbus[0];
        if address.access.write {
            let _ = writeln!(test, "    device.write_raw::<{marker}>({raw}).unwrap();");
        } else {
            let _ = writeln!(test, "    sim.preset({name:?}, {value}).unwrap();");
        }
        let _ = writeln!(
            test,
            "    assert_eq!(held(&sim, {name:?}), {value}, \"{name} held by the simulator\");"
        );
        if address.access.read {
            let _ = writeln!(
                test,
                "    assert_eq!(device.read_raw::<{marker}>().unwrap(), {raw}, \"{name} read back\");"
            );
            read_back += 1;
        }
    }
    test += "}\n\n";
    (test, read_back)
}

const TEST_PRELUDE: &str = "//! Generated round trips.\n\
#![allow(unused_variables)] // A description may have no parameter to test.\n\
use drivebus::modbus::transport::{ModbusTcpClient, TcpConfig};\n\
use drivebus::modbus::UnitId;\n\n\
/// The raw integer the simulator holds for `name`.\n\
fn held(sim: &drivesim::Simulator, name: &str) -> i128 {\n    \
    sim.with(|drive| drive.store().int(drive.store().id(name).unwrap()).unwrap())\n}\n\n";

#[test]
fn generated_code_round_trips_values_through_the_simulator() {
    let scratch = Scratch::new("generated-round-trips");
    let mut modules = String::new();
    let mut tests = String::from(TEST_PRELUDE);
    let mut read_back = 0;
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
    }
    assert!(read_back >= 10, "only {read_back} values are read back");
    let built = build_and_test("random_round_trips", &no_std_lib(&modules), &tests);
    assert!(
        built.success,
        "the generated round trips fail (set DRIVEGEN_KEEP_SCRATCH to keep the descriptions):\n{}\n{}",
        built.stdout,
        built.stderr
    );
}

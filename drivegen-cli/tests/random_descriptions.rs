//! Random valid descriptions against their own simulator, through the `drivegen` binary: every
//! integer or boolean parameter the default variant has on Modbus takes a value that fills its
//! type (high bits set, negative for signed types, the edge of its range or its last allowed
//! value) and gives it back unchanged — whatever its width, odd width, word count and word order.

#[allow(dead_code)] // Shared with codegen's tests; each uses part of it.
#[path = "../../codegen/tests/support/random_description.rs"]
mod random_description;

use random_description::{plain_modbus_integer, telling_integer};

use std::path::Path;
use std::process::Command;

use drivebus::modbus::UnitId;
use drivegen::ir::Table;
use drivesim::Simulator;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn run(args: &[&str]) -> String {
    let output = Command::new(BIN).args(args).output().unwrap();
    assert!(
        output.status.success(),
        "drivegen {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The raw values `drivegen read --json` reports for `names`.
fn read_raw(description: &str, names: &[&str], addr: &str) -> Vec<i128> {
    let mut args = vec!["read", description];
    args.extend(names);
    args.extend(["--modbus-tcp", addr, "--json"]);
    let json: serde_json::Value = serde_json::from_str(&run(&args)).unwrap();
    let raw = |v: &serde_json::Value| {
        let raw = &v["raw"];
        raw.as_i64()
            .map(i128::from)
            .or(raw.as_u64().map(i128::from))
            .unwrap_or_else(|| panic!("no integer raw value in {v}"))
    };
    json.as_array().unwrap().iter().map(raw).collect()
}

fn stored(sim: &Simulator, name: &str) -> i128 {
    sim.with(|drive| drive.store().int(drive.store().id(name).unwrap()).unwrap())
}

#[test]
fn every_integer_parameter_round_trips_through_the_simulator() {
    let dir = std::env::temp_dir().join(format!("drivegen-random-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut checked = 0;
    for path in random_description::valid_descriptions(32, &dir) {
        let device = drivegen::check(&path).device.unwrap();
        let sim = Simulator::load(&path).unwrap();
        let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
        let addr = server.local_addr().to_string();
        let description = path.to_str().unwrap();
        let mut expected = Vec::new();
        for p in device.parameters.iter().filter(|p| plain_modbus_integer(p)) {
            let Some(value) = telling_integer(p) else {
                continue;
            };
            let address = &p.modbus[0];
            if address.access.write {
                run(&[
                    "write",
                    description,
                    &p.name,
                    &format!("raw:{value}"),
                    "--modbus-tcp",
                    &addr,
                ]);
            } else {
                sim.preset(&p.name, value).unwrap();
            }
            assert_eq!(
                stored(&sim, &p.name),
                value,
                "{description}: {} in the simulator",
                p.name
            );
            if address.access.read || address.table == Table::Input {
                expected.push((p.name.as_str(), value));
            }
        }
        let names: Vec<&str> = expected.iter().map(|(name, _)| *name).collect();
        if !names.is_empty() {
            let values: Vec<i128> = expected.iter().map(|(_, value)| *value).collect();
            assert_eq!(
                read_raw(description, &names, &addr),
                values,
                "{description}: {names:?}"
            );
        }
        checked += expected.len();
    }
    assert!(checked >= 15, "only {checked} parameters were read back");
    let _ = std::fs::remove_dir_all(Path::new(&dir));
}

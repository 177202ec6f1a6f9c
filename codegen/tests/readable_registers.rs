//! `Device::readable_register_runs`: what a request planner may read past on a device that
//! refuses reads over unlisted addresses.

use drivebus::modbus::RegisterSpan;
use drivegen::ir::Table;

const DESCRIPTION: &str = r#"
format = 1
[device]
name = "Test"
handle = "Test"
[[source]]
id = "m"
file = "manual.txt"
title = "Manual"
[modbus]
functions = [0x03, 0x04, 0x06]
read_gaps = false
[[variant]]
name = "a"
[[variant]]
name = "b"

[[parameter]]
name = "status"
type = "u16"
modbus = { table = "input", address = 0x10, access = "r" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "position"
type = "i32"
modbus = { table = "input", address = 0x11, words = 2, access = "r" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "setpoint"
type = "u16"
modbus = [ { table = "holding", address = 0x13, access = "w" },
           { table = "input", address = 0x14, access = "r" } ]
source = { doc = "m", line = 3 }

[[parameter]]
name = "tuning"
type = "u16"
modbus = [ { table = "holding", address = 0x20, access = "rw", variant = "a" },
           { table = "holding", address = 0x30, access = "rw", variant = "b" } ]
source = { doc = "m", line = 4 }

[[parameter]]
name = "option"
type = "u16"
variants = ["b"]
modbus = { table = "holding", address = 0x40, access = "rw" }
source = { doc = "m", line = 5 }

[[parameter]]
name = "mode"
type = "u16"
modbus = { table = "holding", address = 0x05, access = "rw" }
source = { doc = "m", line = 6 }
"#;

#[test]
fn runs_merge_neighbours_and_leave_out_write_only_and_variant_bound_registers() {
    let dir = std::env::temp_dir().join(format!("drivegen-readable-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("device.toml");
    std::fs::write(&path, DESCRIPTION).unwrap();
    let checked = drivegen::check(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    let rendered = checked.render();
    let device = checked.device.unwrap_or_else(|| panic!("{rendered}"));
    let run = |table, start, count| RegisterSpan {
        table,
        start,
        count,
    };
    // read_gaps = false: the planner reads past exactly these.
    assert_eq!(
        device.registers_to_read_past(),
        device.readable_register_runs()
    );
    assert_eq!(
        device.readable_register_runs(),
        [
            run(Table::Input, 0x10, 3),
            run(Table::Input, 0x14, 1),
            run(Table::Holding, 0x05, 1)
        ],
        "input 0x10 and 0x11..=0x12 merged, 0x13 unlisted; holding 0x13 is write-only; \
         0x20, 0x30 and 0x40 exist in one variant only"
    );
}

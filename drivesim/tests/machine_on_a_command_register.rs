//! A made-up drive whose commands are bits of one register (as the Lenze smd's #1) and whose
//! status shows the motor's speed phase: the simulator runs it from the description alone. A
//! `[state_machine]` `command` that is one of the register's commands takes any of them; status
//! patterns with `speed` follow the motor; `ramp-stop` ramps to zero; `commanded` shows the target;
//! `[modbus] combined_commands` decides a write of several bits.

use std::time::Duration;

use drivesim::modbus::ModbusServer;
use drivesim::{Drive, Simulator};

const PUMP: &str = r#"
format = 1
[device]
name = "Pump"
handle = "Pump"
source = { doc = "m", line = 1 }
[[source]]
id = "m"
file = "made-up.txt"
title = "A made-up manual"

[modbus]
combined_commands = { address = 1, obeys = "halt", refusal = 0x04, source = { doc = "m", line = 2 } }

[[parameter]]
name = "state"
type = "u16"
modbus = { table = "holding", address = 0, access = "r" }
source = { doc = "m", line = 3 }
[[parameter]]
name = "pump"
type = "u16"
command = { kind = "action", value = 0x01 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 4 }
[[parameter]]
name = "halt"
type = "u16"
command = { kind = "action", value = 0x02 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 5 }
[[parameter]]
name = "flow"
type = "u16"
modbus = { table = "holding", address = 4 }
source = { doc = "m", line = 6 }
[[parameter]]
name = "flow_now"
type = "u16"
modbus = { table = "holding", address = 5, access = "r" }
source = { doc = "m", line = 7 }
[[parameter]]
name = "flow_wanted"
type = "u16"
modbus = { table = "holding", address = 6, access = "r" }
source = { doc = "m", line = 8 }
[[parameter]]
name = "rise"
type = "u16"
default = 100
modbus = { table = "holding", address = 7 }
source = { doc = "m", line = 9 }
[[parameter]]
name = "fall"
type = "u16"
default = 50
modbus = { table = "holding", address = 8 }
source = { doc = "m", line = 10 }

[[ramp]]
setpoint = "flow"
up = { rate = "rise" }
down = { rate = "fall" }
source = { doc = "m", line = 11 }

[state_machine]
name = "pumping"
status = "state"
command = "pump"
setpoint = "flow"
actual = "flow_now"
commanded = "flow_wanted"
source = { doc = "m", line = 12 }
[[state]]
name = "idle"
status = { mask = 0xFF, value = 1 }
source = { doc = "m", line = 13 }
[[state]]
name = "pumping"
status = [
  { mask = 0xFF, value = 2, speed = "rising" },
  { mask = 0xFF, value = 3, speed = "falling" },
  { mask = 0xFF, value = 4, speed = "zero" },
  { mask = 0xFF, value = 5 },
]
motion = "follow"
source = { doc = "m", line = 14 }
[[state]]
name = "draining"
status = [{ mask = 0xFF, value = 3, speed = "falling" }, { mask = 0xFF, value = 1 }]
motion = "ramp-stop"
source = { doc = "m", line = 15 }
[[transition]]
name = "pump"
from = ["idle", "draining"]
to = "pumping"
command = 0x01
source = { doc = "m", line = 16 }
[[transition]]
name = "halt"
from = "pumping"
to = "draining"
command = 0x02
source = { doc = "m", line = 17 }
"#;

/// The pump, loaded from a file of its own.
fn pump() -> Drive {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("drivesim-pump-{}-{n}.toml", std::process::id()));
    std::fs::write(&path, PUMP).unwrap();
    let checked = drivegen::check(&path);
    std::fs::remove_file(&path).unwrap();
    let report = checked.render();
    Drive::new(checked.device.unwrap_or_else(|| panic!("{report}")))
}

fn value(drive: &Drive, name: &str) -> i128 {
    let store = drive.store();
    store.int(store.id(name).unwrap()).unwrap()
}

/// Writes register `address` with FC 06 through the Modbus server; the answer PDU.
fn write(drive: &mut Drive, address: u8, word: u16) -> Vec<u8> {
    let server = ModbusServer::new(drive.store().device(), None);
    let [hi, lo] = word.to_be_bytes();
    let mut out = [0u8; 256];
    let len = server.handle(drive, &[0x06, 0x00, address, hi, lo], &mut out);
    out[..len].to_vec()
}

fn tick(drive: &mut Drive, ms: u64) {
    drive.tick(Duration::from_millis(ms));
}

#[test]
fn any_command_of_the_register_drives_the_machine_and_the_status_follows_the_speed() {
    let mut drive = pump();
    assert_eq!(value(&drive, "state"), 1, "idle");
    write(&mut drive, 4, 200);
    write(&mut drive, 1, 0x01);
    assert_eq!(value(&drive, "state"), 2, "rising at once");
    assert_eq!(value(&drive, "flow_wanted"), 200);
    tick(&mut drive, 1000);
    assert_eq!(
        (value(&drive, "flow_now"), value(&drive, "state")),
        (100, 2)
    );
    tick(&mut drive, 1000);
    assert_eq!(
        (value(&drive, "flow_now"), value(&drive, "state")),
        (200, 5)
    );
    write(&mut drive, 4, 150);
    assert_eq!(value(&drive, "state"), 3, "falling to a lower target");
    tick(&mut drive, 1000);
    assert_eq!(
        (value(&drive, "flow_now"), value(&drive, "state")),
        (150, 5)
    );
    write(&mut drive, 4, 0);
    tick(&mut drive, 3000);
    assert_eq!(
        (value(&drive, "flow_now"), value(&drive, "state")),
        (0, 4),
        "at zero"
    );
}

#[test]
fn ramp_stop_ramps_to_zero_along_the_fall_rate() {
    let mut drive = pump();
    write(&mut drive, 4, 100);
    write(&mut drive, 1, 0x01);
    tick(&mut drive, 1000);
    write(&mut drive, 1, 0x02); // the `halt` command of the same register
    assert_eq!(value(&drive, "state"), 3, "draining, falling");
    assert_eq!(value(&drive, "flow_wanted"), 0);
    tick(&mut drive, 1000);
    assert_eq!(value(&drive, "flow_now"), 50);
    tick(&mut drive, 1000);
    assert_eq!((value(&drive, "flow_now"), value(&drive, "state")), (0, 1));
}

#[test]
fn several_bits_obey_the_named_command_or_are_refused() {
    let mut drive = pump();
    write(&mut drive, 4, 100);
    // Bits 0 and 2: no `halt` among them → the rule's exception.
    assert_eq!(write(&mut drive, 1, 0x05), [0x86, 0x04]);
    assert_eq!(value(&drive, "state"), 1, "nothing done");
    write(&mut drive, 1, 0x01);
    // Bits 0 and 1: `halt` alone.
    assert_eq!(write(&mut drive, 1, 0x03), [0x06, 0x00, 0x01, 0x00, 0x03]);
    assert_eq!(
        value(&drive, "state"),
        1,
        "halted at 0: idle pattern of draining"
    );
    // A single bit that is no command stays data out of range.
    assert_eq!(write(&mut drive, 1, 0x04), [0x86, 0x03]);
}

#[test]
fn without_the_rule_several_bits_are_out_of_range() {
    let text = PUMP.replace(
        "combined_commands = { address = 1, obeys = \"halt\", refusal = 0x04, source = { doc = \"m\", line = 2 } }",
        "",
    );
    let path =
        std::env::temp_dir().join(format!("drivesim-pump-plain-{}.toml", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let sim = Simulator::load(&path);
    std::fs::remove_file(&path).unwrap();
    let sim = sim.unwrap();
    let server = sim.modbus_server();
    let mut out = [0u8; 16];
    let len = sim.with(|d| server.handle(d, &[0x06, 0x00, 0x01, 0x00, 0x03], &mut out));
    assert_eq!(out[..len], [0x86, 0x03]);
}

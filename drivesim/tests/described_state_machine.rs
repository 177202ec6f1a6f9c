//! A drive whose only behaviour is a `[state_machine]` table gets a working simulated machine:
//! no simulator code names its states, registers or commands.

use drivesim::{Drive, Simulator};

/// A made-up conveyor drive: boots through `init`, runs on 0x10 following `belt_speed`, brakes on
/// 0x20, shows `jogging` instead of `running` while its mode register holds 7, and shows the
/// belt's speed in `measured_speed` (its `velocity_average` is some other value).
const CONVEYOR: &str = r#"
format = 1
[device]
name = "Conveyor"
handle = "Conveyor"
source = { doc = "m", line = 1 }
[[source]]
id = "m"
file = "made-up.txt"
title = "A made-up manual"

[[parameter]]
name = "state"
type = "u16"
modbus = { table = "input", address = 0, access = "r" }
source = { doc = "m", line = 2 }
[[parameter]]
name = "order"
type = "u16"
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 3 }
[[parameter]]
name = "mode"
type = "u16"
modbus = { table = "holding", address = 2 }
source = { doc = "m", line = 4 }
[[parameter]]
name = "fault_number"
type = "u16"
modbus = { table = "input", address = 3, access = "r" }
source = { doc = "m", line = 5 }
[[parameter]]
name = "belt_speed"
type = "i16"
modbus = { table = "holding", address = 4 }
source = { doc = "m", line = 16 }
[[parameter]]
name = "measured_speed"
type = "i16"
modbus = { table = "input", address = 5, access = "r" }
source = { doc = "m", line = 17 }
[[parameter]]
name = "velocity_average"
type = "i16"
modbus = { table = "input", address = 6, access = "r" }
source = { doc = "m", line = 18 }

[state_machine]
name = "belt"
status = "state"
command = "order"
fault = "tripped"
fault_code = "fault_number"
setpoint = "belt_speed"
actual = "measured_speed"
source = { doc = "m", line = 6 }
[[state]]
name = "init"
status = { mask = 0x0F, value = 0x01 }
source = { doc = "m", line = 7 }
[[state]]
name = "idle"
status = { mask = 0x0F, value = 0x02 }
source = { doc = "m", line = 8 }
[[state]]
name = "running"
status = [{ mask = 0x0F, value = 0x04 }, { mask = 0x0F, value = 0x0C, when = { parameter = "mode", value = 7 } }]
motion = "follow"
source = { doc = "m", line = 9 }
[[state]]
name = "braking"
status = { mask = 0x0F, value = 0x08 }
motion = "quick-stop"
source = { doc = "m", line = 10 }
[[state]]
name = "tripped"
status = { mask = 0xF0, value = 0x80 }
source = { doc = "m", line = 11 }
[[transition]]
name = "boot"
from = "init"
to = "idle"
kind = "automatic"
source = { doc = "m", line = 12 }
[[transition]]
name = "go"
from = ["idle", "braking"]
to = "running"
command = 0x10
source = { doc = "m", line = 13 }
[[transition]]
name = "brake"
from = "running"
to = "braking"
command = 0x20
source = { doc = "m", line = 14 }
[[transition]]
name = "trip"
from = ["idle", "running", "braking"]
to = "tripped"
kind = "external"
source = { doc = "m", line = 15 }
"#;

/// The conveyor, loaded from a file of its own (read once, at load).
fn conveyor() -> Simulator {
    // Tests run in parallel: one file each.
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let name = format!("drivesim-conveyor-{}-{n}.toml", std::process::id());
    let path = std::env::temp_dir().join(name);
    std::fs::write(&path, CONVEYOR).unwrap();
    let sim = Simulator::load(&path);
    std::fs::remove_file(&path).unwrap();
    sim.unwrap()
}

fn value(drive: &Drive, name: &str) -> i128 {
    let store = drive.store();
    store.int(store.id(name).unwrap()).unwrap()
}

fn write(drive: &mut Drive, name: &str, raw: i128) {
    let id = drive.store().id(name).unwrap();
    let data_type = drive.store().parameter(id).data_type;
    drive
        .write(id, &drivesim::raw::from_int(data_type, raw))
        .unwrap();
}

fn order(drive: &mut Drive, raw: i128) {
    write(drive, "order", raw);
}

#[test]
fn boots_through_automatic_transitions_and_follows_commands() {
    let sim = conveyor();
    sim.with(|drive| {
        assert_eq!(value(drive, "state"), 0x02, "init → idle by itself");
        order(drive, 0x20);
        assert_eq!(
            value(drive, "state"),
            0x02,
            "no brake transition leaves idle"
        );
        order(drive, 0x10);
        assert_eq!(value(drive, "state"), 0x04);
        order(drive, 0x20);
        assert_eq!(value(drive, "state"), 0x08);
        order(drive, 0x10);
        assert_eq!(value(drive, "state"), 0x04, "braking → running");
    });
}

#[test]
fn a_pattern_with_a_condition_shows_while_it_holds() {
    let sim = conveyor();
    sim.preset("mode", 7).unwrap();
    sim.with(|drive| {
        order(drive, 0x10);
        assert_eq!(value(drive, "state"), 0x0C);
    });
}

#[test]
fn a_fault_enters_the_fault_state_and_a_reset_boots_again() {
    let sim = conveyor();
    sim.with(|drive| {
        order(drive, 0x10);
        drive.inject_fault(0x42);
        assert_eq!(value(drive, "state"), 0x80);
        assert_eq!(value(drive, "fault_number"), 0x42);
        order(drive, 0x10);
        assert_eq!(value(drive, "state"), 0x80, "no command leaves the fault");
        drive.reboot();
        assert_eq!(value(drive, "state"), 0x02);
    });
}

#[test]
fn the_motor_shows_its_speed_in_the_machines_actual() {
    let sim = conveyor();
    sim.with(|drive| {
        write(drive, "belt_speed", -300);
        order(drive, 0x10);
        drive.tick(std::time::Duration::from_millis(10));
        assert_eq!(
            value(drive, "measured_speed"),
            -300,
            "no ramp: the speed jumps"
        );
        assert_eq!(
            value(drive, "velocity_average"),
            0,
            "a parameter's name does not make it the actual speed"
        );
        order(drive, 0x20);
        drive.tick(std::time::Duration::from_millis(10));
        assert_eq!(value(drive, "measured_speed"), 0, "braking stops at once");
    });
}

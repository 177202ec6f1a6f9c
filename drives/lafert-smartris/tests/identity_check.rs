//! The identity check on connect: `[identity]` covers FW RELEASE CUSTOMER (0x01FF) = 242, the
//! guide's FW 2.4.2 (guide line 180; digits packed in decimal, Modbus manual line 1022).

use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;
use drivebus::{Error, WriteRefusal};
use lafert_smartris::Smartris;

fn drive_with_firmware(release: u16) -> Smartris<ModbusLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 0x01FF, release);
    bus.set_register(Table::Holding, 0x0042, 0);
    bus.set_register(Table::Input, 0x0042, 0);
    // FULL SCALE VELOCITY (L motor): the bound each speed setpoint write reads first.
    bus.set_register(Table::Holding, 0x0003, 3000);
    Smartris::modbus(bus, UnitId(1))
}

#[test]
fn the_covered_firmware_verifies_and_writes() {
    let mut drive = drive_with_firmware(242);
    assert_eq!(drive.verify_identity(), Ok(()));
    assert_eq!(drive.speed_setpoint().write(Rpm(1500.0)), Ok(()));
}

#[test]
fn another_firmware_is_named_and_refuses_writes_until_trusted() {
    let mut drive = drive_with_firmware(226);
    let mismatch = WriteRefusal::IdentityMismatch {
        parameter: "fw_release",
        expected: &[242],
        found: 226,
    };
    assert_eq!(
        drive.verify_identity(),
        Err(Error::WritesRefused {
            parameter: "fw_release",
            reason: mismatch
        })
    );
    assert_eq!(
        drive.speed_setpoint().write(Rpm(1500.0)),
        Err(Error::WritesRefused {
            parameter: "speed_setpoint",
            reason: mismatch
        })
    );
    assert_eq!(drive.speed_setpoint().read(), Ok(Rpm(0.0)), "reads go on");
    drive.trust_unverified();
    assert_eq!(drive.speed_setpoint().write(Rpm(1500.0)), Ok(()));
}

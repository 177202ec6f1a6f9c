//! The CiA 402 controlword's stopping commands (profile `stops`: disable voltage, quick stop,
//! anything without enable operation, halt) go out while the handle refuses writes; enabling
//! operation does not. Kinco's own words (line 1935): 0x06 power off, 0x0B quick stop, 0x0F
//! power on.

use drivebus::modbus::{Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::{Error, WriteRefusal};
use kinco_fd::KincoFd;

#[test]
fn power_off_quick_stop_and_halt_go_out_power_on_does_not() {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 0x3100, 0);
    let mut drive = KincoFd::modbus(bus, UnitId(1));
    // What the client believes (an identity it could not confirm, say): every write refused.
    let belief = WriteRefusal::IdentityMismatch {
        parameter: "vendor_id",
        expected: &[0x0000_0300],
        found: 0,
    };
    drive.device().refuse_writes(belief);
    assert_eq!(
        drive.controlword().write_raw(0x000F),
        Err(Error::WritesRefused {
            parameter: "controlword",
            reason: belief
        })
    );
    for stop in [0x0006, 0x000B, 0x0000, 0x010F] {
        assert_eq!(drive.controlword().write_raw(stop), Ok(()), "{stop:#06x}");
    }
    let log = drive.device().link_mut().bus_mut().log();
    let written: Vec<u16> = log
        .iter()
        .filter_map(|r| match r {
            Request::Write {
                start: 0x3100,
                values,
            } => values.first().copied(),
            _ => None,
        })
        .collect();
    assert_eq!(written, [0x0006, 0x000B, 0x0000, 0x010F]);
}

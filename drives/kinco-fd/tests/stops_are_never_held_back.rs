//! The CiA 402 controlword's stopping commands (profile `stops`: disable voltage, quick stop,
//! anything without enable operation, halt) go out while the handle refuses writes; enabling
//! operation does not. Kinco's own words (line 1935): 0x06 power off, 0x0B quick stop, 0x0F
//! power on. A quick stop by option code goes out even when the code (605Ah) cannot be read.

use std::time::{Duration, Instant};

use drivebus::control::ControlError;
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
    let written = controlwords(&mut drive);
    assert_eq!(written, [0x0006, 0x000B, 0x0000, 0x010F]);
}

/// The controlword values written to holding 0x3100, in order.
fn controlwords(drive: &mut KincoFd<drivebus::modbus::ModbusLink<MemoryBus>>) -> Vec<u16> {
    let log = drive.device().link_mut().bus_mut().log();
    log.iter()
        .filter_map(|r| match r {
            Request::Write {
                start: 0x3100,
                values,
            } => values.first().copied(),
            _ => None,
        })
        .collect()
}

#[test]
fn a_quick_stop_by_option_code_goes_out_when_the_code_cannot_be_read() {
    let mut bus = MemoryBus::new();
    // Operation enabled; no register 0x3400 (605Ah): its read is refused.
    bus.set_register(Table::Holding, 0x3100, 0x000F);
    bus.set_register(Table::Holding, 0x3200, 0x0027);
    let mut drive = KincoFd::modbus(bus, UnitId(1));
    assert!(drive.quick_stop_mode().read().is_err());
    let outcome = drive.quick_stop_by_option_code(Instant::now() + Duration::from_millis(50));
    // The memory never leaves operation enabled, so the walk ends stuck; the command went out.
    assert!(
        matches!(outcome, Err(ControlError::Stuck { .. })),
        "{outcome:?}"
    );
    // The quick stop command (CiA 402: bit 1 set, bits 2 and 7 clear; Kinco's 0x0B is one).
    let first = controlwords(&mut drive).first().copied();
    assert_eq!(first.map(|c| c & 0x0086), Some(0x0002), "{first:x?}");
}

//! Stop (control word 0x0001, line 1215) and standby (0x0002, line 1219) are sent while the
//! handle refuses writes to a drive whose firmware its description does not cover; run (0x0003)
//! is not (`stops` on `control_word`, drivebus::stop).

use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::{Error, WriteRefusal};
use lafert_smartris::Smartris;

fn writes(drive: &mut Smartris<ModbusLink<MemoryBus>>) -> Vec<Request> {
    let log = drive.device().link_mut().bus_mut().log();
    log.iter()
        .filter(|r| matches!(r, Request::Write { .. }))
        .cloned()
        .collect()
}

#[test]
fn stop_and_standby_go_out_to_an_uncovered_firmware_run_does_not() {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 0x01FF, 226) // FW 2.2.6: not the covered 242
        .set_register(Table::Holding, 0x0001, 0x0003);
    let mut drive = Smartris::modbus(bus, UnitId(1));
    assert!(drive.verify_identity().is_err());
    let refused = drive.control_word().write_raw(0x0003).unwrap_err();
    assert!(
        matches!(
            refused,
            Error::WritesRefused {
                reason: WriteRefusal::IdentityMismatch { found: 226, .. },
                ..
            }
        ),
        "{refused:?}"
    );
    assert_eq!(drive.control_word().write_raw(0x0001), Ok(()));
    assert_eq!(drive.control_word().write_raw(0x0002), Ok(()));
    let sent = |value| Request::Write {
        start: 0x0001,
        values: vec![value],
    };
    assert_eq!(writes(&mut drive), [sent(0x0001), sent(0x0002)]);
}

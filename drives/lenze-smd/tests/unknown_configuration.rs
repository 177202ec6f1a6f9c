//! A drive reporting a configuration no variant covers (#50 neither 400 nor 507, line 314): the
//! handle guesses no address. A register that moves between PC400 and PC507 (c25: #95 / #103,
//! lines 348, 944) is not read, a register at one address in both still is, and nothing is
//! written but a stop.

#[path = "support/smd_double.rs"]
mod smd_double;

use drivebus::modbus::{Table, UnitId};
use lenze_smd::{LenzeSmd, SmdError, VariantSelection};
use smd_double::*;

#[test]
fn a_moved_register_is_not_read_and_only_a_stop_is_written() {
    let mut double = SmdDouble::pc507(11, 0);
    double
        .memory
        .set_register(Table::Holding, CONFIGURATION, 401)
        .set_register(Table::Holding, 95, 0x534D)
        .set_register(Table::Holding, 103, 0)
        .set_register(Table::Holding, 19, 69);
    double.controls_unlocked = true;
    let mut d = LenzeSmd::modbus(double, UnitId(10));
    assert_eq!(d.detect_variant(), Ok(VariantSelection::Unknown(401)));
    assert_eq!(
        SmdError::from(d.serial_baud_rate().read().unwrap_err()),
        SmdError::UnknownConfiguration { value: 401 }
    );
    assert_eq!(
        d.drive_family().read(),
        Ok(lenze_smd::types::DriveFamily::SMD)
    );
    assert_eq!(d.stop().write_raw(0x0004), Ok(()));
    let accepted = &d.device().link_mut().bus_mut().accepted;
    assert_eq!(accepted, &[(DRIVE_CONTROL, 0x0004)]);
}

//! A stop is sent whatever the handle believes about the drive's lock (`stops = true` on `stop`
//! and `lock_security`, drivebus::stop). Review finding E18: if the drive follows line 792 (#40
//! only after parameter writes are enabled), it refuses #40 after `#48 = 0` with exception 01 and
//! the handle's account closes the controls; the stop must still go out, since #1 stays open
//! (line 409) and the drive obeys a stop bit (line 570).

#[path = "support/smd_double.rs"]
mod smd_double;

use drivebus::modbus::{ModbusLink, UnitId};
use drivebus::{Error, WriteRefusal};
use lenze_smd::params::{SerialSpeedCommand, Start, UnlockCommands};
use lenze_smd::LenzeSmd;
use smd_double::*;

type Drive = LenzeSmd<ModbusLink<SmdDouble>>;

fn double(drive: &mut Drive) -> &mut SmdDouble {
    drive.device().link_mut().bus_mut()
}

#[test]
fn a_stop_goes_out_while_the_handle_believes_the_drive_locked() {
    // The drive was unlocked before this handle opened (another process, a reconnect): the
    // handle opens locked in its own account.
    let mut d = LenzeSmd::modbus(SmdDouble::pc507(11, 0), UnitId(10));
    double(&mut d).controls_unlocked = true;
    let refused = d.device().write_raw::<Start>(0x0008).unwrap_err();
    assert!(
        matches!(
            refused,
            Error::WritesRefused {
                reason: WriteRefusal::Locked { .. },
                ..
            }
        ),
        "{refused:?}"
    );
    assert_eq!(d.stop().write_raw(0x0004), Ok(()));
    assert_eq!(double(&mut d).accepted, [(DRIVE_CONTROL, 0x0004)]);
}

#[test]
fn a_stop_goes_out_after_the_drive_refused_serial_speed_e18() {
    let mut d = LenzeSmd::modbus(SmdDouble::pc507(11, 0), UnitId(10));
    d.device().write_raw::<UnlockCommands>(0).unwrap();
    // The drive refuses #40 as line 792 reads (01), while #1 stays open (line 409).
    double(&mut d).controls_unlocked = false;
    assert!(d.device().write_raw::<SerialSpeedCommand>(412).is_err());
    double(&mut d).controls_unlocked = true;
    assert_eq!(
        d.stop().write_raw(0x0004),
        Ok(()),
        "the stop is not held back"
    );
    assert!(
        d.device().write_raw::<Start>(0x0008).is_err(),
        "the account still refuses a start"
    );
    let accepted = &double(&mut d).accepted;
    assert_eq!(accepted.last(), Some(&(DRIVE_CONTROL, 0x0004)));
}

#[test]
fn the_drive_answer_to_a_stop_is_reported() {
    // Locked for real: the stop is sent, and the drive's exception 01 comes back.
    let mut d = LenzeSmd::modbus(SmdDouble::pc507(11, 0), UnitId(10));
    let answer = d.stop().write_raw(0x0004).unwrap_err();
    assert!(
        matches!(
            answer,
            Error::Bus {
                parameter: "stop",
                ..
            }
        ),
        "{answer:?}"
    );
    assert!(double(&mut d).accepted.is_empty());
}

//! Bounds set by other parameters (`Writable::BOUNDS`, the `[bounds: ..]` clause of
//! `drivebus::parameter!`): every write reads the bounding parameters over the same link and
//! refuses a value beyond one before sending; a write that stops the drive is never refused.
#![cfg(feature = "modbus")]

use drivebus::modbus::{ModbusLimits, ModbusLink, Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::units::Rpm;
use drivebus::{Device, Error, OutsideBound, VariantId};

/// The full scale, an unsigned bound of a signed setpoint.
pub struct FullScale;
drivebus::parameter!(FullScale = "full_scale": u16 => Rpm, InUnit; read modbus (holding 0x0003));

/// Within ± the full scale.
pub struct Setpoint;
drivebus::parameter!(Setpoint = "setpoint": i16 => Rpm, InUnit;
    read modbus (input 0x0042);
    write modbus (holding 0x0042) [bounds: magnitude = FullScale]);

/// The least and the greatest frequency.
pub struct Least;
drivebus::parameter!(Least = "least": u16 => u16, Plain; read modbus (holding 0x0010));
/// See [`Least`].
pub struct Greatest;
drivebus::parameter!(Greatest = "greatest": u16 => u16, Plain; read modbus (holding 0x0011));

/// Within `least ..= greatest`; 0 stops the drive.
pub struct Frequency;
drivebus::parameter!(Frequency = "frequency": u16 => u16, Plain, stops(0xFFFF => 0x0000);
    write modbus (holding 0x0012) [bounds: min = Least, max = Greatest]);

type Drive = Device<ModbusLink<MemoryBus>>;

/// The full scale 3000, the setpoint 0 and the frequency 100 within 100 ..= 500.
const REGISTERS: [(Table, u16, u16); 6] = [
    (Table::Holding, 0x03, 3000),
    (Table::Input, 0x42, 0),
    (Table::Holding, 0x42, 0),
    (Table::Holding, 0x10, 100),
    (Table::Holding, 0x11, 500),
    (Table::Holding, 0x12, 100),
];

fn drive() -> Drive {
    let mut bus = MemoryBus::new();
    for (table, address, value) in REGISTERS {
        bus.set_register(table, address, value);
    }
    Device::new(
        ModbusLink::new(bus, UnitId(1), ModbusLimits::SPEC),
        VariantId(0),
    )
}

fn writes(drive: &mut Drive) -> Vec<Request> {
    let log = drive.link_mut().bus_mut().log().to_vec();
    log.into_iter()
        .filter(|r| matches!(r, Request::Write { .. }))
        .collect()
}

#[test]
fn a_value_beyond_the_magnitude_is_refused_after_reading_the_bound_and_nothing_is_written() {
    let mut drive = drive();
    for beyond in [3001.0, -3001.0] {
        assert_eq!(
            drive.parameter::<Setpoint>().write(Rpm(beyond)),
            Err(Error::OutsideBound(OutsideBound {
                parameter: "setpoint",
                bound: "full_scale",
                raw: beyond as i128,
                limit: 3000,
            }))
        );
    }
    assert_eq!(writes(&mut drive), []);
    let bound_read = Request::Read {
        table: Table::Holding,
        start: 0x03,
        count: 1,
    };
    assert_eq!(
        drive.link_mut().bus_mut().log(),
        [bound_read.clone(), bound_read],
        "the bound is read through the same link, each time"
    );
    drive.parameter::<Setpoint>().write(Rpm(-3000.0)).unwrap();
    assert_eq!(
        writes(&mut drive),
        [Request::Write {
            start: 0x42,
            values: vec![(-3000i16) as u16]
        }]
    );
}

#[test]
fn write_raw_is_bounded_too() {
    let mut drive = drive();
    assert!(matches!(
        drive.write_raw::<Frequency>(501),
        Err(Error::OutsideBound(OutsideBound {
            bound: "greatest",
            ..
        }))
    ));
    assert!(matches!(
        drive.parameter::<Frequency>().write_raw(99),
        Err(Error::OutsideBound(OutsideBound { bound: "least", .. }))
    ));
    assert_eq!(writes(&mut drive), []);
    drive.parameter::<Frequency>().write(500).unwrap();
    assert_eq!(
        drive.link_mut().bus_mut().register(Table::Holding, 0x12),
        Some(500)
    );
}

#[test]
fn a_stop_is_never_refused_by_a_bound_and_reads_none() {
    let mut drive = drive();
    // 0 lies below `least` (100), but it stops the drive.
    drive.parameter::<Frequency>().write(0).unwrap();
    assert_eq!(
        drive.link_mut().bus_mut().log(),
        [Request::Write {
            start: 0x12,
            values: vec![0]
        }]
    );
}

#[test]
fn a_bound_that_cannot_be_read_fails_the_write_naming_the_bound() {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 0x42, 0);
    let mut drive = Device::new(
        ModbusLink::new(bus, UnitId(1), ModbusLimits::SPEC),
        VariantId(0),
    );
    let error = drive.parameter::<Setpoint>().write(Rpm(1.0)).unwrap_err();
    assert!(
        matches!(
            error,
            Error::Bus {
                parameter: "full_scale",
                ..
            }
        ),
        "{error:?}"
    );
    assert_eq!(writes(&mut drive), []);
}

//! `drivebus::parameter!` as generated crates use it: per-variant placements, scales, ranges and
//! allowed values, over the in-memory Modbus bus.
#![cfg(feature = "modbus")]

use drivebus::modbus::{ModbusLimits, ModbusLink, Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::units::{Celsius, Hertz};
use drivebus::{Device, Error, ValueError, VariantId};

/// At holding 0x004E in variant 0, 0x004F in variant 1, absent in variant 2; 0.1 Hz steps.
pub struct Setpoint;
drivebus::parameter!(Setpoint = "setpoint": u16 => Hertz, InUnit, scale = 1 / 10, range(0, 2400);
    read modbus [(holding 0x004E), (holding 0x004F), _];
    write modbus [(holding 0x004E), (holding 0x004F), _]);

/// A raw code that only takes the listed values.
pub struct Code;
drivebus::parameter!(Code = "code": u16 => u16, Plain, one_of[1, 2, 4];
    read modbus (input 0x0010); write modbus (holding 0x0010));
/// Tenths of a degree from -40 °C, two registers low word first.
pub struct Temperature;
drivebus::parameter!(Temperature = "temperature": u32 => Celsius, InUnit,
    scale = 1 / 10, offset = -40 / 1;
    read modbus (input 0x0020, 2 words, LowFirst));

fn device(variant: u16) -> Device<ModbusLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 0x4E, 500)
        .set_register(Table::Holding, 0x4F, 600)
        .set_register(Table::Input, 0x10, 2)
        .set_register(Table::Input, 0x20, 653)
        .set_register(Table::Input, 0x21, 0)
        .set_register(Table::Holding, 0x10, 0);
    let link = ModbusLink::new(bus, UnitId(1), ModbusLimits::SPEC);
    Device::new(link, VariantId(variant))
}

fn holding(device: &mut Device<ModbusLink<MemoryBus>>, address: u16) -> Option<u16> {
    device
        .link_mut()
        .bus_mut()
        .register(Table::Holding, address)
}

#[test]
fn each_variant_reads_and_writes_its_own_register() {
    let mut first = device(0);
    assert_eq!(first.read::<Setpoint>().unwrap(), Hertz(50.0));
    first.write::<Setpoint>(Hertz(12.5)).unwrap();
    assert_eq!(holding(&mut first, 0x4E), Some(125));
    assert_eq!(holding(&mut first, 0x4F), Some(600));

    let mut second = device(1);
    assert_eq!(second.read::<Setpoint>().unwrap(), Hertz(60.0));
    second.write::<Setpoint>(Hertz(12.5)).unwrap();
    assert_eq!(holding(&mut second, 0x4F), Some(125));
    assert_eq!(holding(&mut second, 0x4E), Some(500));
}

#[test]
fn a_variant_without_the_parameter_and_an_unknown_variant_refuse_it() {
    for variant in [2, 7] {
        let err = device(variant).read::<Setpoint>().unwrap_err();
        assert!(
            matches!(
                err,
                Error::NotInVariant {
                    parameter: "setpoint"
                }
            ),
            "{err:?}"
        );
    }
}

#[test]
fn range_and_allowed_values_are_checked_before_sending() {
    let mut drive = device(0);
    let err = drive.write::<Setpoint>(Hertz(240.1)).unwrap_err();
    assert!(
        matches!(err, Error::Value(ValueError::OutOfRange { .. })),
        "{err:?}"
    );
    assert_eq!(holding(&mut drive, 0x4E), Some(500), "nothing was written");

    assert!(drive.write::<Code>(3).is_err());
    drive.write::<Code>(4).unwrap();
    assert_eq!(holding(&mut drive, 0x10), Some(4));
    assert_eq!(
        drive.read::<Code>().unwrap(),
        2,
        "read from the input register"
    );
}

#[test]
fn named_scale_offset_and_word_order_clauses() {
    // 653 tenths from -40 °C is 25.3 °C; the low word comes first.
    assert_eq!(device(0).read::<Temperature>().unwrap(), Celsius(25.3));
}

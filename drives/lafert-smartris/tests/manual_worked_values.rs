//! The Modbus manual's own worked values (001_ad8624675505a5b5.txt §2.2), decoded through the
//! generated API over an in-memory register map.

use drivebus::memory::{MemoryBus, Request};
use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::units::{AmperesRms, Celsius, Rpm, Volts};
use drivebus::{BusError, Error, ValueError};
use lafert_smartris::{params, types::DriveStatus, Smartris};

fn drive_with(registers: &[(Table, u16, u16)]) -> Smartris<ModbusLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    for &(table, address, value) in registers {
        bus.set_register(table, address, value);
    }
    Smartris::modbus(bus, UnitId(1))
}

#[test]
fn bus_dc_link_0x1356_is_49_50_volts() {
    // Manual line 432: "0x0064 = 0x1356 (4950) → Bus Dc Link = 49.5 Vdc".
    let mut drive = drive_with(&[(Table::Input, 0x0064, 0x1356)]);
    assert_eq!(drive.bus_dc_link().read(), Ok(Volts(49.5)));
    assert_eq!(drive.bus_dc_link().read_raw(), Ok(4950));
}

#[test]
fn speed_setpoint_0xf448_is_minus_3000_rpm() {
    // Manual §2.2: "0x0042 = 0xF448 (62536 = -3000) → Speed Motor = -3000 rpm".
    let mut drive = drive_with(&[(Table::Input, 0x0042, 0xF448)]);
    assert_eq!(drive.speed_setpoint().read(), Ok(Rpm(-3000.0)));
}

#[test]
fn temperatures_0x0163_are_35_5_celsius() {
    // Manual §2.2: "0x0065 = 0x0163 (355) → Motor temperature = 35.5 °C", same for 0x0066/0x0067.
    let mut drive = drive_with(&[
        (Table::Input, 0x0065, 0x0163),
        (Table::Input, 0x0066, 0x0163),
        (Table::Input, 0x0067, 0x0163),
    ]);
    assert_eq!(drive.motor_temperature().read(), Ok(Celsius(35.5)));
    assert_eq!(drive.heat_sink_temperature().read(), Ok(Celsius(35.5)));
    assert_eq!(drive.board_temperature().read(), Ok(Celsius(35.5)));
}

#[test]
fn torque_setpoint_0xff38_is_minus_2_arms() {
    // Manual §2.2: "0x0047 = 0xFF38 (65336 = -200) → - 2 Arms".
    let mut drive = drive_with(&[(Table::Input, 0x0047, 0xFF38)]);
    assert_eq!(drive.torque_setpoint().read(), Ok(AmperesRms(-2.0)));
}

#[test]
fn velocity_average_0xfc18_is_minus_1000_rpm() {
    let mut drive = drive_with(&[(Table::Input, 0x0068, 0xFC18)]);
    assert_eq!(drive.velocity_average().read(), Ok(Rpm(-1000.0)));
}

#[test]
fn drive_status_word_decodes_into_flags_and_keeps_unknown_bits() {
    // Alarm (0x0010) + stop (0x0004) + an undocumented bit 12.
    let mut drive = drive_with(&[(Table::Input, 0x0060, 0x1014)]);
    let status = drive.drive_status().read().unwrap();
    assert!(status.contains(DriveStatus::ALARM | DriveStatus::STOP));
    assert!(!status.contains(DriveStatus::RUN_VELOCITY));
    assert_eq!(status.bits(), 0x1014, "unknown bits survive the read");
}

#[test]
fn setpoint_write_goes_to_the_holding_register_and_reads_back_from_input() {
    let mut drive = drive_with(&[(Table::Holding, 0x0042, 0), (Table::Input, 0x0042, 0)]);
    drive.speed_setpoint().write(Rpm(1500.0)).unwrap();
    let bus = drive.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 0x0042), Some(1500));
    assert_eq!(
        bus.log(),
        [Request::Write {
            start: 0x0042,
            values: vec![1500]
        }]
    );
}

#[test]
fn out_of_range_write_is_refused_before_anything_is_sent() {
    let mut drive = drive_with(&[(Table::Holding, 0x0042, 0)]);
    let too_fast = drive.speed_setpoint().write(Rpm(40_000.0));
    assert!(matches!(
        too_fast,
        Err(Error::Value(ValueError::Overflow {
            parameter: "speed_setpoint"
        }))
    ));
    let between_steps = drive.speed_setpoint().write(Rpm(1500.5));
    assert!(matches!(
        between_steps,
        Err(Error::Value(ValueError::NotRepresentable { .. }))
    ));
    assert!(drive.into_link().into_bus().log().is_empty());
}

#[test]
fn unknown_register_surfaces_the_exception() {
    let mut drive = drive_with(&[]);
    let error = drive.bus_dc_link().read().unwrap_err();
    assert_eq!(
        error.bus(),
        Some(&BusError::ModbusException {
            function: 0x04,
            code: 0x02
        })
    );
}

#[test]
fn read_many_returns_typed_values_in_order() {
    let mut drive = drive_with(&[
        (Table::Input, 0x0064, 0x1356),
        (Table::Input, 0x0065, 0x0163),
        (Table::Input, 0x0060, 0x0002),
    ]);
    let (volts, temperature, status) = drive
        .read_many((
            params::BusDcLink,
            params::MotorTemperature,
            params::DriveStatus,
        ))
        .unwrap();
    assert_eq!((volts, temperature), (Volts(49.5), Celsius(35.5)));
    assert!(status.contains(DriveStatus::STANDBY));
}

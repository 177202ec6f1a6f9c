//! Quickstart: drive a Lafert Smartris through its generated, typed API.
//!
//! Until the simulator lands, the drive is an in-memory register map preloaded with the values of
//! the Modbus manual's worked examples; the code is the same against a real drive, only the bus
//! differs.

use drivebus::memory::MemoryBus;
use drivebus::modbus::{Table, UnitId};
use drivebus::units::Rpm;
use lafert_smartris::{params, Smartris};

fn main() -> Result<(), drivebus::Error> {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Input, 0x0060, 0x0002) // drive status: standby
        .set_register(Table::Input, 0x0064, 0x1356) // DC link: 49.50 V
        .set_register(Table::Input, 0x0065, 0x0163) // motor: 35.5 °C
        .set_register(Table::Input, 0x0066, 0x0163) // heat sink: 35.5 °C
        .set_register(Table::Input, 0x0068, 0x0000) // velocity (average)
        .set_register(Table::Holding, 0x0042, 0x0000) // speed setpoint (written)
        .set_register(Table::Input, 0x0042, 0x0000); // speed setpoint (read back)
    let mut drive = Smartris::modbus(bus, UnitId(1));

    let status = drive.drive_status().read()?;
    println!("drive status      {status:?}");

    println!("set speed         1500 rpm");
    drive.speed_setpoint().write(Rpm(1500.0))?;

    let (dc_link, motor, heat_sink) = drive.read_many((
        params::BusDcLink,
        params::MotorTemperature,
        params::HeatSinkTemperature,
    ))?;
    println!("DC link           {dc_link:.2}");
    println!("motor temperature {motor:.1}");
    println!("heat sink         {heat_sink:.1}");

    let written = drive
        .into_link()
        .into_bus()
        .register(Table::Holding, 0x0042);
    println!("holding 0x0042    {written:?} (raw, as sent on the wire)");
    Ok(())
}

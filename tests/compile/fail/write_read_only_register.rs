use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Volts;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    // The DC link voltage is an input register: read-only.
    let _ = drive.bus_dc_link().write(Volts(48.0));
}

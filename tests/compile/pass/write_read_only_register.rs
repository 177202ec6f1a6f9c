use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Volts;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    let _: Result<Volts, _> = drive.bus_dc_link().read();
}

use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Seconds;

fn main() {
    let mut drive = lenze_smd::LenzeSmd::modbus(MemoryBus::new(), UnitId(10));
    let _ = drive.acceleration_time().read();
    // Written through the guard of an unlock that opens the `parameters` scope.
    if let Ok(mut unlocked) = drive.unlock_parameter_writing(0) {
        let _ = unlocked.acceleration_time().write(Seconds(10.0));
        let _ = unlocked.lock();
    };
}

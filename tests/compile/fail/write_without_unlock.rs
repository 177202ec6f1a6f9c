use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Seconds;

fn main() {
    let mut drive = lenze_smd::LenzeSmd::modbus(MemoryBus::new(), UnitId(10));
    // C12 (acceleration time) needs an unlock (#48 or #49 = C94, smd manual lines 412, 421): the
    // handle reads it but has no setter; the write goes through the guard of an unlock.
    let _ = drive.acceleration_time().write(Seconds(10.0));
    let _ = drive.acceleration_time().write_raw(100);
}

use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lenze_smd::Trigger;

fn main() {
    let mut drive = lenze_smd::LenzeSmd::modbus(MemoryBus::new(), UnitId(10));
    // #48 = 0 unlocks the controls (line 409): its guard commands the drive.
    if let Ok(mut unlocked) = drive.unlock_controls() {
        let _ = unlocked.start().trigger();
    };
}

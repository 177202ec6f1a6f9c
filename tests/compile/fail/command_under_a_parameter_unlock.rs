use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lenze_smd::Trigger;

fn main() {
    let mut drive = lenze_smd::LenzeSmd::modbus(MemoryBus::new(), UnitId(10));
    // #49 = C94 unlocks every writable register except #1 (smd manual line 421): the guard of
    // `unlock_parameter_writing` has no `start`, and the handle has no command setters at all.
    if let Ok(mut unlocked) = drive.unlock_parameter_writing(0) {
        let _ = unlocked.start().trigger();
    }
    let _ = drive.start().trigger();
}

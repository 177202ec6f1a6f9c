//! The simulator serves the PDO objects a description's `[[pdo]]` tables imply (as the exported
//! EDS lists them), and follows a vl target velocity (6042h) along the vl ramps 6048h / 6049h.

use std::time::Duration;

use drivebus::canopen::sdo::server::ObjectDictionary;
use drivesim::canopen::Dictionary;
use drivesim::Simulator;

const SWD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/ezwheel-swd");

fn dictionary(sim: &Simulator) -> Dictionary {
    let device = sim.with(|drive| drive.store().device().clone());
    Dictionary::new(sim.clone(), &device, sim.variant())
}

#[test]
fn a_pdo_disabled_by_default_is_served_with_cob_id_bit_31() {
    let sim = Simulator::load(SWD).unwrap();
    let mut od = dictionary(&sim);
    // TPDO 2: mapped (statusword), not valid, no identifier given (SWD manual line 1325).
    assert_eq!(od.read(0x1801, 1).unwrap(), 0x8000_0000u32.to_le_bytes());
    assert_eq!(od.read(0x1A01, 1).unwrap(), 0x6041_0010u32.to_le_bytes());
    // Objects the description describes itself are served once, with its own values.
    assert_eq!(od.read(0x1800, 1).unwrap(), 0x4000_0190u32.to_le_bytes());
}

#[test]
fn the_vl_setpoint_is_followed_along_the_vl_ramp() {
    let sim = Simulator::load(SWD).unwrap();
    let mut od = dictionary(&sim);
    for word in [0x06u16, 0x07, 0x0F] {
        od.write(0x6040, 0, &word.to_le_bytes()).unwrap();
    }
    od.write(0x6042, 0, &500i16.to_le_bytes()).unwrap();
    // 500 rpm per 1 s (6048h defaults): after 0.2 s the motor is near 100 rpm, not at 500.
    sim.with(|drive| drive.tick(Duration::from_millis(200)));
    let speed = i32::from_le_bytes(od.read(0x606C, 0).unwrap().try_into().unwrap());
    assert!((90..=110).contains(&speed), "{speed}");
    sim.with(|drive| drive.tick(Duration::from_secs(2)));
    let speed = i32::from_le_bytes(od.read(0x606C, 0).unwrap().try_into().unwrap());
    assert_eq!(speed, 500);
}

//! The run-time scales: speed and acceleration from the encoder resolution (read over CANopen,
//! given over Modbus), currents from the model's peak current (appendix 2, lines 3401-3403).

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::modbus::{Table, UnitId};
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;
use drivebus::{Error, ValueError};
use kinco_fd::{KincoFd, Model};

fn modbus_memory() -> MemoryBus {
    let mut memory = MemoryBus::new();
    for address in [0x6F00, 0x6F01, 0x3D00] {
        memory.set_register(Table::Holding, address, 0);
    }
    memory
}

#[test]
fn over_modbus_the_encoder_resolution_is_given() {
    let mut drive = KincoFd::modbus(modbus_memory(), UnitId(1));
    assert_eq!(
        drive.target_velocity().write(Rpm(150.0)),
        Err(Error::Value(ValueError::BadScale {
            parameter: "target_velocity"
        })),
        "no resolution given: refused, nothing unscaled"
    );
    let mut drive = drive.give_encoder_resolution(10_000);
    drive.target_velocity().write(Rpm(150.0)).unwrap();
    // 150 rpm = 409600 DEC = 0x00064000, low word first (RS-232 example, line 2364).
    let bus = drive.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 0x6F00), Some(0x4000));
    assert_eq!(bus.register(Table::Holding, 0x6F01), Some(0x0006));
}

#[test]
fn a_speed_that_is_no_whole_dec_is_refused_before_sending() {
    let mut drive = KincoFd::modbus(modbus_memory(), UnitId(1)).give_encoder_resolution(10_000);
    // 200 rpm = 546133.33 DEC (the manual sends the rounded 546133, line 2474).
    let refused = drive.target_velocity().write(Rpm(200.0));
    assert!(
        matches!(
            refused,
            Err(Error::Value(ValueError::NotRepresentable { .. }))
        ),
        "{refused:?}"
    );
    assert_eq!(drive.into_link().into_bus().log().len(), 0, "nothing sent");
}

#[test]
fn over_canopen_the_encoder_resolution_is_read() {
    let mut memory = MemoryBus::new();
    memory
        .set_object(0x6410, 3, &10_000u32.to_le_bytes())
        .set_object(0x606C, 0, &409_600i32.to_le_bytes());
    let node = NodeId::new(1).unwrap();
    let mut drive = KincoFd::<CanOpenLink<MemoryBus>>::canopen(memory, node);
    assert_eq!(drive.velocity_actual_value().read().unwrap(), Rpm(150.0));
}

#[test]
fn currents_follow_the_model() {
    // 1 Arms = 2048 / I_peak / 1.414 DEC (line 1990). FD123 (45 A peak, line 227): 2048 DEC is
    // 45 * 1.414 = 63.63 Arms; FD114S (8 A peak, line 252): 11.312 Arms.
    let mut memory = modbus_memory();
    memory.set_register(Table::Holding, 0x3D00, 2048);
    let mut drive = KincoFd::modbus(memory, UnitId(1));
    assert_eq!(
        drive.max_current().read(),
        Err(Error::Value(ValueError::BadScale {
            parameter: "max_current"
        })),
        "no model: refused"
    );
    let mut drive = drive.with_model(Model::Fd123);
    assert!((drive.max_current().read().unwrap().0 - 63.63).abs() < 1e-9);
    drive.set_model(Model::Fd114s);
    assert!((drive.max_current().read().unwrap().0 - 11.312).abs() < 1e-9);
    assert_eq!(Model::Fd144s.name(), "fd144s");
}

#[test]
fn accelerations_are_in_rps_per_second() {
    // 100000 DEC at resolution 10000 is 610.352 rps/s (line 1966): DEC · 4000000 / (65536 · 10000).
    let mut memory = MemoryBus::new();
    memory
        .set_object(0x6410, 3, &10_000u32.to_le_bytes())
        .set_object(0x6083, 0, &100_000u32.to_le_bytes());
    let node = NodeId::new(1).unwrap();
    let mut drive = KincoFd::<CanOpenLink<MemoryBus>>::canopen(memory, node);
    let acceleration = drive.profile_acceleration().read().unwrap();
    assert!(
        (acceleration.0 - 610.3515625).abs() < 1e-9,
        "{acceleration:?}"
    );
    // 1 rps/s is 16.384 DEC here: not a whole DEC, refused rather than rounded.
    assert!(drive
        .profile_acceleration()
        .write(drivebus::units::RpsPerSecond(1.0))
        .is_err());
    drive
        .profile_acceleration()
        .write(drivebus::units::RpsPerSecond(610.3515625))
        .unwrap();
}

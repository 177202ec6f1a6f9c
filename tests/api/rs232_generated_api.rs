//! The generated API of the RS-232 fixture over the in-memory bus: values travel as the data
//! protocol carries them, run-time scales are read over RS-232, failures name the parameter and
//! the object, and values outside the description are refused before anything is sent.

use drivebus::rs232::{Rs232Error, StationId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::units::Rpm;
use drivebus::{BusError, Error, ValueError};
use drivegen_tests::kinco_rs232::KincoRs232;

fn drive(bus: MemoryBus) -> KincoRs232<drivebus::rs232::Rs232Link<MemoryBus>> {
    KincoRs232::rs232(bus, StationId(1))
}

#[test]
fn a_run_time_scaled_speed_reads_its_factor_over_rs232() {
    let mut bus = MemoryBus::new();
    bus.set_object(0x6410, 3, &10_000u32.to_le_bytes())
        .set_object(0x60FF, 0, &0x0006_4000i32.to_le_bytes());
    let mut drive = drive(bus);
    // 409600 DEC = 150 rpm at resolution 10000 (manual line 2364).
    assert_eq!(drive.target_speed().read().unwrap(), Rpm(150.0));
    drive.target_speed().write(Rpm(200.0)).unwrap_err(); // 546133.33 DEC: not representable
    drive.target_speed().write(Rpm(-150.0)).unwrap();
    let bus = drive.into_link().into_bus();
    assert_eq!(
        bus.object(0x60FF, 0),
        Some(&(-409_600i32).to_le_bytes()[..])
    );
}

#[test]
fn writes_go_out_in_the_objects_width() {
    let mut bus = MemoryBus::new();
    bus.set_object(0x6060, 0, &[0])
        .set_object(0x607A, 0, &[0; 4]);
    let mut drive = drive(bus);
    drive.operation_mode().write(6i8).unwrap();
    drive.target_position().write(50_000i32).unwrap();
    let log = drive.into_link().into_bus().log().to_vec();
    assert_eq!(
        log,
        [
            Request::Download(0x6060, 0, vec![6]),
            Request::Download(0x607A, 0, vec![0x50, 0xC3, 0, 0]),
        ]
    );
}

#[test]
fn an_error_answer_names_the_parameter_and_the_object() {
    let mut drive = drive(MemoryBus::new());
    let error = drive.statusword().read().unwrap_err();
    assert_eq!(
        error,
        Error::Bus {
            parameter: "statusword",
            cause: BusError::Rs232Exchange {
                index: 0x6041,
                subindex: 0,
                error: Rs232Error::Refused { cause: 0x0602_0000 },
            },
        }
    );
    assert_eq!(
        error.to_string(),
        "statusword: RS-232 request about 0x6041:0: error answer, cause 0x06020000 (object does not exist in the object dictionary)"
    );
}

#[test]
fn a_value_the_description_does_not_allow_is_refused_before_sending() {
    let mut bus = MemoryBus::new();
    bus.set_object(0x6060, 0, &[0]);
    let mut drive = drive(bus);
    let error = drive.operation_mode().write_raw(5).unwrap_err();
    assert!(matches!(
        error,
        Error::Value(ValueError::NotAllowed {
            raw: drivebus::interpret::RawValue::Int(5),
            ..
        })
    ));
    assert!(drive.into_link().into_bus().log().is_empty());
}

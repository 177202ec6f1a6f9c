//! The manual's worked values and rules, through the generated API on an in-memory register map:
//! internal units (Table 3), ranges refused before sending, the two configurations' registers,
//! PC507-only parameters, and the fault table. Values are written through the raw device
//! (`drive.device().write::<P>()`); the typed setters need an unlock guard
//! (`tests/unlock_session.rs`). The map has no lock, but the handle follows the drive's: it opens
//! locked, as the drive powers up (line 1055), so each drive first gets the grant #49 = 0, the
//! factory password (lines 423-424), through the raw device too.

use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::units::{Hertz, Milliseconds, Seconds};
use drivebus::{Error, ValueError};
use lenze_smd::types::{FaultAndCommandedDirection, FaultCode, SerialBaudRate};
use lenze_smd::{params, LenzeSmd, Variant};

type Drive = LenzeSmd<ModbusLink<MemoryBus>>;

/// #49, Unlock Parameters (line 507).
const UNLOCK_PARAMETERS: u16 = 49;

/// The grant each drive gets: the factory password 0 to #49.
fn grant() -> Request {
    Request::Write {
        start: UNLOCK_PARAMETERS,
        values: vec![0],
    }
}

/// A drive whose map holds `registers` (all zero), its parameters unlocked by the grant.
fn drive(variant: Variant, registers: impl IntoIterator<Item = u16>) -> Drive {
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, UNLOCK_PARAMETERS, 0);
    for r in registers {
        bus.set_register(Table::Holding, r, 0);
    }
    let mut drive = LenzeSmd::modbus(bus, UnitId(1));
    drive.set_variant(variant);
    drive
        .device()
        .write_raw::<params::UnlockParameters>(0)
        .unwrap();
    drive
}

fn register(drive: Drive, address: u16) -> Option<u16> {
    drive
        .into_link()
        .into_bus()
        .register(Table::Holding, address)
}

/// The requests sent, but for the grants.
fn requests(drive: Drive) -> Vec<Request> {
    let bus = drive.into_link().into_bus();
    bus.log()
        .iter()
        .filter(|r| **r != grant())
        .cloned()
        .collect()
}

#[test]
fn speeds_and_times_travel_in_internal_units() {
    // Table 3 (lines 303-304): 100 Hz = 1000, 30.0 s = 300. c40 is #97 in PC400 (line 946),
    // C12 #61 in both (line 890).
    let mut d = drive(Variant::Pc400, [97, 61]);
    d.device()
        .write::<params::FrequencySetpointCommand>(Hertz(100.0))
        .unwrap();
    d.device()
        .write::<params::AccelerationTime>(Seconds(30.0))
        .unwrap();
    let bus = d.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 97), Some(1000));
    assert_eq!(bus.register(Table::Holding, 61), Some(300));
}

#[test]
fn watchdog_time_is_in_milliseconds_from_50() {
    // n23, line 387 and 966: 50-65535 ms; #115 in PC400, #133 in PC507.
    let mut d = drive(Variant::Pc507, [133]);
    d.device()
        .write::<params::SerialFaultTime>(Milliseconds(200.0))
        .unwrap();
    assert_eq!(register(d, 133), Some(200));
    let mut d = drive(Variant::Pc400, [115]);
    let refused = d
        .device()
        .write::<params::SerialFaultTime>(Milliseconds(49.0))
        .unwrap_err();
    assert!(matches!(
        refused,
        Error::Value(ValueError::OutOfRange {
            parameter: "serial_fault_time",
            ..
        })
    ));
    assert!(requests(d).is_empty(), "nothing may be sent");
}

#[test]
fn values_outside_the_printed_ranges_are_refused_before_sending() {
    // C11 maximum output frequency 7.5-240 Hz (line 889); C22 current limit 30-150 % (line 898);
    // C94 password 0-999 (line 925); #48 0-999 (line 505).
    let mut d = drive(Variant::Pc400, [60, 69, 88, 48]);
    assert!(d
        .device()
        .write::<params::MaximumOutputFrequency>(Hertz(7.4))
        .is_err());
    assert!(d
        .device()
        .write::<params::MaximumOutputFrequency>(Hertz(240.1))
        .is_err());
    assert!(d
        .device()
        .write::<params::CurrentLimit>(drivebus::units::Percent(29.0))
        .is_err());
    assert!(d.device().write::<params::UserPassword>(1000).is_err());
    assert!(d.unlock_commands().write(1000).is_err());
    assert!(requests(d).is_empty());
}

#[test]
fn register_95_is_c25_in_pc400_and_c99_in_pc507() {
    // Issue example and lines 926 / 944: c25 at #95 (PC400) and #103 (PC507).
    let mut d = drive(Variant::Pc400, [95]);
    d.device()
        .write::<params::SerialBaudRate>(SerialBaudRate::E81_9600)
        .unwrap();
    assert_eq!(register(d, 95), Some(2));
    let mut d = drive(Variant::Pc507, [95, 103]);
    d.device()
        .write::<params::SerialBaudRate>(SerialBaudRate::O81_9600)
        .unwrap();
    let bus = d.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 103), Some(3));
    assert_eq!(bus.register(Table::Holding, 95), Some(0), "C99 untouched");
}

#[test]
fn pc507_only_parameters_are_absent_in_pc400() {
    // d38 PI enable exists only in PC507, #124 (line 961).
    let mut d = drive(Variant::Pc400, [124]);
    assert_eq!(
        d.pi_enable().read().unwrap_err(),
        Error::NotInVariant {
            parameter: "pi_enable"
        }
    );
    assert!(requests(d).is_empty());
    let mut d = drive(Variant::Pc507, [124]);
    assert!(d.pi_enable().read().unwrap().is_known());
}

#[test]
fn every_moved_parameter_follows_the_configuration() {
    // c61 present fault: #100 in PC400, #110 in PC507 (line 949).
    for (variant, address) in [(Variant::Pc400, 100), (Variant::Pc507, 110)] {
        let mut bus = MemoryBus::new();
        bus.set_register(Table::Holding, address, 24);
        let mut d: Drive = LenzeSmd::modbus(bus, UnitId(1));
        d.set_variant(variant);
        assert_eq!(
            d.present_fault().read().unwrap(),
            FaultCode::COMMUNICATION_FAULT
        );
    }
}

#[test]
fn fault_codes_0_to_26_have_their_meaning() {
    // Table 18 (lines 983-1009), the same as Table 16 (lines 752-765).
    let meaning = |code: u16| {
        FaultAndCommandedDirection::from_bits_retain(code << 8)
            .present_fault()
            .meaning()
    };
    assert_eq!(meaning(0), Some("NO FAULT"));
    assert_eq!(meaning(1), Some("OUTPUT (TRANSISTOR) FAULT"));
    assert_eq!(meaning(19), Some("INTERNAL FAULT o"));
    assert_eq!(meaning(26), Some("CONFIGURATION FAULT"));
    assert!((0..=26).all(|code| meaning(code).is_some()));
    assert_eq!(meaning(27), None, "an unlisted code survives as unknown");
}

#[test]
fn the_pi_setpoint_lies_within_c86_and_c87() {
    // c81 (#117 in PC507) within c86 ... c87 (#119, #120; line 956), checked at run time by
    // the bounded write of the parameter unlock's guard (#49, then #1 = lock).
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 117, 0)
        .set_register(Table::Holding, 1, 0)
        .set_register(Table::Holding, 49, 0)
        .set_register(Table::Holding, 119, 100) // c86 = 10.0
        .set_register(Table::Holding, 120, 500); // c87 = 50.0
    let mut d: Drive = LenzeSmd::modbus(bus, UnitId(1));
    d.set_variant(Variant::Pc507);
    let mut unlocked = d.unlock_parameter_writing(0).unwrap();
    assert_eq!(
        unlocked.pi_setpoint().write(50.1).unwrap_err(),
        drivebus::Error::OutsideBound(drivebus::OutsideBound {
            parameter: "pi_setpoint",
            bound: "pi_max_feedback",
            raw: 501,
            limit: 500
        })
    );
    assert!(matches!(
        unlocked.pi_setpoint().write(9.9).unwrap_err(),
        drivebus::Error::OutsideBound(drivebus::OutsideBound {
            bound: "pi_min_feedback",
            ..
        })
    ));
    unlocked.pi_setpoint().write(25.0).unwrap();
    drop(unlocked);
    let writes: Vec<Request> = requests(d)
        .into_iter()
        .filter(|r| matches!(r, Request::Write { start: 117, .. }))
        .collect();
    assert_eq!(
        writes.len(),
        1,
        "only the value within the bounds is written: {writes:?}"
    );
}

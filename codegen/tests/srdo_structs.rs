//! `[[srdo]]` end to end: the fixture of the SWD's default SRDO1, SRDO2 (16 entries) and SRDO10
//! (128 bits) lowers to the IR, and its generated structs compile `no_std`, sign their default
//! configurations with the manual's 13FFh values (lines 3588, 3589, 3594) and carry typed values
//! through a producer / consumer pair.

mod support;

use std::path::Path;

use drivegen::ir::Direction;
use support::crate_build::{build_and_test, generated, no_std_lib};

const FIXTURE: &str = "tests/fixtures/srdo";

#[test]
fn the_fixture_lowers_to_three_srdos() {
    let checked = drivegen::check(Path::new(FIXTURE));
    let device = checked.device.expect("the SRDO fixture is valid");
    let srdos: Vec<_> = device.srdos().collect();
    let (srdo1, defaults1) = srdos[0];
    assert_eq!((defaults1.number, srdo1.direction), (1, Direction::Rx));
    assert_eq!(srdo1.information_direction(), 2);
    assert_eq!(defaults1.cob_ids[0].resolve(Some(0x10)), Some(0x11F)); // line 4111
    assert_eq!(defaults1.cob_ids[1].resolve(None), None);
    let (srdo2, defaults2) = srdos[1];
    assert_eq!(srdo2.entries.len(), 16);
    assert_eq!(defaults2.cob_ids[0].resolve(None), Some(0x103));
    let (srdo10, _) = srdos[2];
    assert_eq!(srdo10.information_direction(), 0);
    let objects = srdo10.mapped_objects(&device).unwrap();
    assert_eq!(drivebus::canopen::pdo::mapping_bits(&objects), 128);
}

const TEST: &str = r#"
use drivebus::canopen::srdo::{signature, SrdoError};
use drivebus::canopen::NodeId;
use srdo_structs::srdo::{SafeActualValues, SafetyControl, SafetyStatus};

const NODE: NodeId = NodeId(0x10);

#[test]
fn default_configurations_sign_as_the_manual_says() {
    assert_eq!(signature(&SafetyControl::config(NODE)), Ok(0x70AB));
    assert_eq!(signature(&SafetyStatus::config(NODE)), Ok(0x8C5F));
    assert_eq!(signature(&SafeActualValues::config(NODE)), Ok(0x2274));
}

#[test]
fn srdo1_uses_the_quick_start_cob_ids() {
    let ids = SafetyControl::communication(NODE).cob_ids().unwrap();
    assert_eq!((ids.normal(), ids.inverted()), (0x11F, 0x120));
}

#[test]
fn typed_values_cross_a_producer_and_a_consumer() {
    let status = SafetyStatus {
        safety_statusword_1: 0x01,
        safety_statusword_2: 0x02,
        safety_statusword_3: 0x04,
        safety_statusword_4: 0x08,
        safety_statusword_5: 0x10,
        safety_statusword_6: 0x20,
        safety_statusword_7: 0x40,
        safety_statusword_8: 0x80,
    };
    let payload = status.encode().unwrap();
    let producer = SafetyStatus::producer(NODE).unwrap();
    let mut consumer = SafetyStatus::consumer(NODE).unwrap();
    let [normal, inverted] = producer.pair(payload.as_bytes()).unwrap();
    let ms = core::time::Duration::from_millis;
    assert_eq!(consumer.handle(&normal, ms(0)), Some(Ok(None)));
    let released = consumer.handle(&inverted, ms(1)).unwrap().unwrap().unwrap();
    assert_eq!(SafetyStatus::decode(released.as_bytes()), Ok(status));
}

#[test]
fn a_128_bit_srdo_carries_two_i32() {
    let values = SafeActualValues {
        safe_position_actual_value: -123_456,
        safe_velocity_actual_value: 7_890,
    };
    let payload = values.encode().unwrap();
    assert_eq!(payload.as_bytes().len(), 8);
    let producer = SafeActualValues::producer(NODE).unwrap();
    let mut consumer = SafeActualValues::consumer(NODE).unwrap();
    let [normal, mut inverted] = producer.pair(payload.as_bytes()).unwrap();
    let ms = core::time::Duration::from_millis;
    consumer.handle(&normal, ms(0));
    let mut data = inverted.padded();
    data[7] ^= 0x01;
    inverted = drivebus::canopen::CanFrame::new(inverted.id(), &data).unwrap();
    assert_eq!(consumer.handle(&inverted, ms(1)), Some(Err(SrdoError::Inconsistent)));
}
"#;

#[test]
fn generated_srdo_structs_compile_and_work() {
    let lib = no_std_lib(&generated(Path::new(FIXTURE)));
    let built = build_and_test("srdo_structs", &lib, TEST);
    assert!(
        built.success,
        "generated SRDO code failed:\n{}\n{}",
        built.stdout, built.stderr
    );
}

//! The default PDO mappings of the user guide (§6.5.1) as typed structs: payloads decode into the
//! parameters' own types, encodes are range- and step-checked, and `config(node).apply` writes the
//! CiA 301 sequence (disable, zero the count, entries, count, enable).

use drivebus::canopen::pdo::COB_ID_INVALID;
use drivebus::canopen::NodeId;
use drivebus::testing::{MemoryBus, Request};
use drivebus::units::PerMille;
use drivebus::ValueError;
use lafert_smartris::pdo::{Rpdo4, Tpdo2, Tpdo4};
use lafert_smartris::types::{Controlword, Statusword};

/// Operation enabled (0x0237) and a position of 10,000 increments, little-endian.
const TPDO2_PAYLOAD: [u8; 6] = [0x37, 0x02, 0x10, 0x27, 0x00, 0x00];

#[test]
fn a_transmit_pdo_decodes_into_flags_and_values() {
    let tpdo = Tpdo2::decode(&TPDO2_PAYLOAD).unwrap();
    assert!(tpdo.statusword.contains(Statusword::OPERATION_ENABLED));
    assert!(!tpdo.statusword.contains(Statusword::FAULT));
    assert_eq!(tpdo.statusword.bits(), 0x0237);
    assert_eq!(tpdo.position_actual_value, 10_000);

    let torque = Tpdo4::decode(&[0x37, 0x02, 0x0C, 0xFE]).unwrap();
    assert_eq!(torque.torque_actual_value, PerMille(-500.0));
}

#[test]
fn a_short_payload_is_an_error_not_a_guess() {
    let err = Tpdo2::decode(&TPDO2_PAYLOAD[..5]).unwrap_err();
    assert_eq!(
        err,
        ValueError::WrongLength {
            expected: 6,
            actual: 5
        }
    );
}

#[test]
fn a_receive_pdo_encodes_its_values_and_refuses_what_does_not_fit() {
    let rpdo = Rpdo4 {
        controlword: Controlword::SWITCH_ON
            | Controlword::ENABLE_VOLTAGE
            | Controlword::QUICK_STOP
            | Controlword::ENABLE_OPERATION,
        target_torque: PerMille(-250.0),
    };
    assert_eq!(rpdo.encode().unwrap().as_bytes(), [0x0F, 0x00, 0x06, 0xFF]);
    let round_trip = Rpdo4::decode(rpdo.encode().unwrap().as_bytes()).unwrap();
    assert_eq!(round_trip, rpdo);

    let between_steps = Rpdo4 {
        target_torque: PerMille(12.5),
        ..rpdo
    };
    assert!(
        between_steps.encode().is_err(),
        "12.5 ‰ is not a whole step"
    );
    let too_big = Rpdo4 {
        target_torque: PerMille(40_000.0),
        ..rpdo
    };
    assert!(too_big.encode().is_err(), "40,000 ‰ does not fit an i16");
}

#[test]
fn the_cob_id_follows_the_node_id() {
    assert_eq!(Tpdo2::cob_id(NodeId(5)), 0x285);
    assert_eq!(Rpdo4::cob_id(NodeId(127)), 0x57F);
}

/// The RPDO4 objects of node 3, to configure.
fn rpdo4_objects() -> MemoryBus {
    let mut bus = MemoryBus::new();
    bus.set_object(0x1403, 1, &[0; 4])
        .set_object(0x1603, 0, &[0])
        .set_object(0x1603, 1, &[0; 4])
        .set_object(0x1603, 2, &[0; 4]);
    bus
}

#[test]
fn config_applied_over_an_async_sdo_client_writes_the_same_sequence() {
    use drivebus::testing::{now, Immediate};
    let node = NodeId(3);
    let mut blocking = rpdo4_objects();
    Rpdo4::config(node).apply(&mut blocking, node).unwrap();
    let mut awaited = Immediate(rpdo4_objects());
    let outcome = now(Rpdo4::config(node).apply_async(&mut awaited, node));
    assert_eq!(outcome, Some(Ok(())));
    assert_eq!(awaited.0.log(), blocking.log());
}

#[test]
fn config_writes_the_cia301_mapping_sequence() {
    let node = NodeId(3);
    let mut bus = rpdo4_objects();
    Rpdo4::config(node).apply(&mut bus, node).unwrap();

    let cob_id = 0x503u32;
    let expected = [
        Request::Download(0x1403, 1, (cob_id | COB_ID_INVALID).to_le_bytes().to_vec()),
        Request::Download(0x1603, 0, vec![0]),
        Request::Download(0x1603, 1, 0x6040_0010u32.to_le_bytes().to_vec()),
        Request::Download(0x1603, 2, 0x6071_0010u32.to_le_bytes().to_vec()),
        Request::Download(0x1603, 0, vec![2]),
        Request::Download(0x1403, 1, cob_id.to_le_bytes().to_vec()),
    ];
    assert_eq!(bus.log(), expected);
}

#[test]
fn pdo_3_carries_the_velocity_mode_values() {
    // Guide 4366/4376 and 4403/4414: RPDO3 = controlword + target velocity (400h + node),
    // TPDO3 = statusword + actual velocity (380h + node); 6 bytes each.
    use lafert_smartris::pdo::{Rpdo3, Tpdo3};
    assert_eq!(Rpdo3::cob_id(NodeId(1)), 0x401);
    assert_eq!(Tpdo3::cob_id(NodeId(1)), 0x381);
    let rpdo = Rpdo3 {
        controlword: Controlword::SWITCH_ON
            | Controlword::ENABLE_VOLTAGE
            | Controlword::QUICK_STOP
            | Controlword::ENABLE_OPERATION,
        // 3000 rpm with the default factor 1/1 and a 16384-increment feedback: 819200 inc/s
        // (guide 7515, ERRATA C5).
        target_velocity: 819_200,
    };
    assert_eq!(
        rpdo.encode().unwrap().as_bytes(),
        [0x0F, 0x00, 0x00, 0x80, 0x0C, 0x00]
    );
    let tpdo = Tpdo3::decode(&[0x27, 0x02, 0x00, 0x80, 0x0C, 0x00]).unwrap();
    assert!(tpdo.statusword.contains(Statusword::OPERATION_ENABLED));
    assert_eq!(tpdo.velocity_actual_value, 819_200);
}

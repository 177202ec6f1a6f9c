//! The default PDOs of the manual (section 9.7, lines 1309-1439) as typed structs: payloads
//! decode into the parameters' types, COB-IDs are the printed fixed values (a node-id change
//! does not move them, lines 1082-1084), TPDO 2 and 5-8 are mapped but not valid by default
//! (lines 1322-1331), and a configuration applies to the simulated SWD.

mod support;

use core::time::Duration;

use drivebus::canopen::pdo::COB_ID_INVALID;
use drivebus::canopen::sdo::client::SdoClient;
use drivebus::canopen::sdo::Transfer;
use drivebus::canopen::{NodeId, SdoBus};
use drivebus::units::Increments;
use ezwheel_swd::pdo::{Rpdo1, Rpdo4, Tpdo1, Tpdo2, Tpdo3, Tpdo4, Tpdo8};
use ezwheel_swd::types::{Controlword, Statusword};
use support::simulated_swd::{start, NODE};

#[test]
fn transmit_pdos_decode_the_statusword_and_actual_values() {
    // Operation enabled, statusword 0027h (quick start, line 4162).
    let tpdo1 = Tpdo1::decode(&[0x27, 0x00]).unwrap();
    assert!(tpdo1.statusword.contains(Statusword::OPERATION_ENABLED));
    let tpdo3 = Tpdo3::decode(&[0x27, 0x00, 0x1E, 0x00, 0x00, 0x00]).unwrap();
    assert_eq!(
        tpdo3.position_actual_value,
        Increments(30.0),
        "one motor revolution = 30 increments, in the unit the row gives (lines 2504, 2508)"
    );
    let tpdo4 = Tpdo4::decode(&[0x27, 0x00, 0xD6, 0xFE, 0xFF, 0xFF]).unwrap();
    assert_eq!(tpdo4.velocity_actual_value, -298);
    assert!(Tpdo4::decode(&[0x27, 0x00, 0xD6]).is_err());
}

#[test]
fn rpdo4_carries_the_controlword_and_the_raw_vl_target_velocity() {
    let rpdo = Rpdo4 {
        controlword: Controlword::from_bits_retain(0x007F),
        // Run-time scale (vl dimension factor): the field is the raw value.
        vl_target_velocity: 298,
    };
    // 298 rpm = 012Ah, the quick start's setpoint (line 4192).
    assert_eq!(rpdo.encode().unwrap().as_bytes(), [0x7F, 0x00, 0x2A, 0x01]);
    assert_eq!(
        Rpdo4::decode(&[0x7F, 0x00, 0x88, 0xFA])
            .unwrap()
            .vl_target_velocity,
        -1400
    );
}

#[test]
fn default_cob_ids_are_fixed_and_do_not_follow_the_node_id() {
    for node in [1, NODE, 0x7F] {
        let node = NodeId(node);
        assert_eq!(Rpdo1::cob_id(node), 0x210, "line 1339");
        assert_eq!(Rpdo4::cob_id(node), 0x510, "line 1363");
        assert_eq!(Tpdo1::cob_id(node), 0x4000_0190, "line 1387");
        assert_eq!(Tpdo3::cob_id(node), 0x4000_0390, "line 1406");
        assert_eq!(Tpdo4::cob_id(node), 0x4000_0490, "line 1428");
    }
}

#[test]
fn communication_defaults_are_constants() {
    let enabled = [
        Rpdo1::ENABLED_BY_DEFAULT,
        Tpdo4::ENABLED_BY_DEFAULT,
        Tpdo2::ENABLED_BY_DEFAULT,
        Tpdo8::ENABLED_BY_DEFAULT,
    ];
    assert_eq!(enabled, [true, true, false, false]);
    assert_eq!(
        Tpdo1::TRANSMISSION_TYPE,
        Some(1),
        "cyclic synchronous, line 1388"
    );
    assert_eq!(Rpdo1::INHIBIT_TIME, Some(0), "line 1341");
    assert_eq!(Rpdo1::EVENT_TIMER, Some(0), "line 1345");
    assert_eq!(Tpdo1::EVENT_TIMER, None, "the TPDO tables have no sub 5");
    assert_eq!(Tpdo2::TRANSMISSION_TYPE, None);
    // A PDO whose COB-ID the manual does not give is configured with one the user picks.
    let config = Tpdo2::config_with_cob_id(0x4000_0290);
    assert_eq!(config.number, 2);
    assert_eq!(config.entries.len(), 1);
}

#[test]
fn a_configuration_applies_to_the_simulated_drive_and_enables_the_pdo() {
    let (mut drive, _node) = start();
    // Disable RPDO 4 first, as a master reconfiguring it would find it.
    drive.rpdo4_cob_id().write(0x510 | COB_ID_INVALID).unwrap();
    Rpdo4::config(NodeId(NODE))
        .apply(drive.device().link_mut().bus_mut(), NodeId(NODE))
        .unwrap();
    assert_eq!(drive.rpdo4_cob_id().read().unwrap(), 0x510);
    assert_eq!(drive.rpdo4_mapping_count().read().unwrap(), 2);
    assert_eq!(drive.rpdo4_mapping_entry_2().read().unwrap(), 0x6042_0010);
    let mut count = [0u8; 1];
    let bus = drive.device().link_mut().bus_mut();
    bus.upload(NodeId(NODE), 0x1603, 0, &mut count).unwrap();
    assert_eq!(count, [2]);
}

/// The first SDO frame (COB-ID, data) of each write of `plan`, for node 10h.
fn sdo_frames(plan: drivebus::canopen::pdo::PdoPlan<'_>) -> Vec<(u16, Vec<u8>)> {
    plan.map(|write| {
        let client = SdoClient::new(NodeId(NODE), Duration::from_secs(1));
        let mut transfer =
            client.download(write.index, write.subindex, write.data(), Duration::ZERO);
        let frame = transfer
            .poll_transmit()
            .expect("a download starts with a frame");
        (frame.id(), frame.data().to_vec())
    })
    .collect()
}

#[test]
fn a_configuration_writes_the_inhibit_time_and_event_timer_it_gives() {
    // RPDO 1 (lines 1338-1345): transmission type 1 and event timer 0 (sub 5, a 2-byte
    // expedited download, 2Bh) written while the PDO is invalid. The inhibit time (sub 3) is
    // read-only on the SWD (line 1341), so the configuration does not write it.
    let frames = sdo_frames(Rpdo1::config(NodeId(NODE)).plan().unwrap());
    assert_eq!(
        frames,
        [
            (0x610, vec![0x23, 0x00, 0x14, 0x01, 0x10, 0x02, 0x00, 0x80]),
            (0x610, vec![0x2F, 0x00, 0x14, 0x02, 0x01, 0x00, 0x00, 0x00]),
            (0x610, vec![0x2B, 0x00, 0x14, 0x05, 0x00, 0x00, 0x00, 0x00]),
            (0x610, vec![0x2F, 0x00, 0x16, 0x00, 0x00, 0x00, 0x00, 0x00]),
            (0x610, vec![0x23, 0x00, 0x16, 0x01, 0x10, 0x00, 0x40, 0x60]),
            (0x610, vec![0x2F, 0x00, 0x16, 0x00, 0x01, 0x00, 0x00, 0x00]),
            (0x610, vec![0x23, 0x00, 0x14, 0x01, 0x10, 0x02, 0x00, 0x00]),
        ]
    );
    assert_eq!(Rpdo1::INHIBIT_TIME, Some(0));
    // A TPDO table without sub 5 (lines 1387-1390) writes no event timer.
    let tpdo1: Vec<u8> = Tpdo1::config(NodeId(NODE))
        .plan()
        .unwrap()
        .filter(|w| w.index == 0x1800)
        .map(|w| w.subindex)
        .collect();
    assert!(!tpdo1.contains(&5));
}

//! The CAN bus logs of section 11.4.4 (manual 003_8cc8f7f4f05b8633.txt, lines 3135-3326) and the
//! PDO configuration of 11.4.2 / 11.4.3, decoded and rebuilt through drivebus' sans-I/O CANopen
//! cores and the generated crate: heartbeats, NMT commands, the SDO read and write of 1017h, the
//! SYNC COB-ID, the PDO log, and TPDO1 / RPDO1 / RPDO2 as configured.
//!
//! The logs print a few identifiers wrongly (ERRATA.md #45): the SDO answers at lines 3217 and
//! 3236 are printed with ID 0706 and 0566 where node 6 answers on 0x586, and line 3184 shows a
//! heartbeat byte under ID 0000, and the text reads the answer E8 03 as "0x03EB (1000ms)" (line
//! 3222). The data bytes are intact and are the vectors here.

use std::time::Duration;

use drivebus::canopen::nmt::{decode_heartbeat, NmtCommand, NmtState};
use drivebus::canopen::pdo::{decode_entry, MappedObject, PdoLayout};
use drivebus::canopen::sdo::client::SdoClient;
use drivebus::canopen::sdo::{Progress, Transfer};
use drivebus::canopen::{CanFrame, NodeId};
use drivebus::Parameter;
use kinco_fd::params::{
    ModesOfOperationDisplay, PositionActual, ProducerHeartbeatTime, TargetPosition,
};
use kinco_fd::pdo::{Rpdo1, Rpdo2, Tpdo1};

fn node(n: u8) -> NodeId {
    NodeId::new(n).unwrap()
}

fn frame(id: u16, printed: &str) -> CanFrame {
    let data: Vec<u8> = printed
        .split_whitespace()
        .map(|pair| u8::from_str_radix(pair, 16).unwrap())
        .collect();
    CanFrame::new(id, &data).unwrap()
}

#[test]
fn heartbeats_of_node_6_decode_as_the_manual_reads_them() {
    // 0706 7F pre-operational (line 3161), 05 operational (3172), 04 stopped (3188), 00 the
    // boot-up after a reset (3201, line 3207).
    for (printed, state, line) in [
        ("7F", NmtState::PreOperational, 3142),
        ("05", NmtState::Operational, 3172),
        ("04", NmtState::Stopped, 3188),
        ("00", NmtState::Initializing, 3201),
    ] {
        assert_eq!(
            decode_heartbeat(&frame(0x706, printed)),
            Some((node(6), state)),
            "line {line}"
        );
    }
}

#[test]
fn nmt_commands_are_the_printed_frames() {
    // Start node 6 (line 3170), stop (3186), reset (3199); start node 2 (lines 2976-2977).
    for (command, target, printed, line) in [
        (NmtCommand::Start, 6, "01 06", 3170),
        (NmtCommand::Stop, 6, "02 06", 3186),
        (NmtCommand::ResetNode, 6, "81 06", 3199),
        (NmtCommand::Start, 2, "01 02", 2977),
    ] {
        let sent = command.frame(Some(node(target)));
        assert_eq!(sent, frame(0x000, printed), "line {line}");
        assert_eq!(
            NmtCommand::decode(&sent),
            Some((command, Some(node(target))))
        );
    }
}

#[test]
fn the_sdo_read_of_1017h_sends_and_decodes_the_printed_frames() {
    // 0606: 40 17 10 00 00 00 00 00 (line 3215); answer 4B 17 10 00 E8 03 00 00 (line 3217):
    // 2 bytes, 0x03E8 = 1000 ms of producer heartbeat time.
    let mut buf = [0u8; 4];
    let client = SdoClient::new(node(6), Duration::from_secs(1));
    let mut read = client.upload(0x1017, 0, &mut buf, Duration::ZERO);
    assert_eq!(
        read.poll_transmit(),
        Some(frame(0x606, "40 17 10 00 00 00 00 00"))
    );
    let answer = frame(0x586, "4B 17 10 00 E8 03 00 00");
    assert_eq!(read.handle(&answer, Duration::ZERO), Progress::Done(2));
    let raw = u16::from_le_bytes([buf[0], buf[1]]);
    assert_eq!(
        ProducerHeartbeatTime::decode(raw, ProducerHeartbeatTime::SCALE).unwrap(),
        drivebus::units::Milliseconds(1000.0)
    );
}

#[test]
fn the_sdo_write_of_1017h_sends_the_printed_frame_and_takes_the_printed_answer() {
    // 0606: 2B 17 10 00 FF 01 00 00 (line 3234), 0x01FF = 511 ms; answer 60 17 10 00 (line 3236).
    let raw = ProducerHeartbeatTime::encode(
        drivebus::units::Milliseconds(511.0),
        ProducerHeartbeatTime::SCALE,
    )
    .unwrap();
    let data = raw.to_le_bytes();
    let client = SdoClient::new(node(6), Duration::from_secs(1));
    let mut write = client.download(0x1017, 0, &data, Duration::ZERO);
    assert_eq!(
        write.poll_transmit(),
        Some(frame(0x606, "2B 17 10 00 FF 01 00 00"))
    );
    let answer = frame(0x586, "60 17 10 00 00 00 00 00");
    assert_eq!(write.handle(&answer, Duration::ZERO), Progress::Done(2));
}

#[test]
fn the_sync_cob_id_is_0x80() {
    // Sync_ID default 80 (line 2912); the SYNC of the differential complement mode is COB-ID
    // 0x80 with no data (lines 3097-3100).
    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/kinco-fd"
    ))
    .unwrap();
    let sync_id = sim.with(|drive| drive.store().int(drive.store().id("sync_id").unwrap()));
    assert_eq!(
        sync_id,
        Some(i128::from(drivebus::canopen::frame::cob::SYNC))
    );
    assert_eq!(drivebus::canopen::frame::cob::SYNC, 0x80);
}

#[test]
fn the_pdo_log_decodes_the_actual_position_0xfae84270() {
    // The TPDO1 of lines 3294-3297 maps 60630020, 60780010, 60610008 (7 bytes); the logged
    // frame 0186 7 70 42 E8 FA 00 00 00 (line 3312) is "actual position 0xFaE84270" (line 3310).
    let layout = PdoLayout::new([
        MappedObject::from_entry(0x6063_0020),
        MappedObject::from_entry(0x6078_0010),
        MappedObject::from_entry(0x6061_0008),
    ]);
    let logged = frame(0x186, "70 42 E8 FA 00 00 00");
    assert_eq!(layout.len(), usize::from(logged.dlc()));
    let position = decode_entry::<PositionActual, 3>(&layout, logged.data(), 0).unwrap();
    assert_eq!(position.0, f64::from(0xFAE8_4270u32 as i32));
    assert_eq!(layout.get_raw(logged.data(), 0).unwrap(), 0xFAE8_4270);
    let mode = decode_entry::<ModesOfOperationDisplay, 3>(&layout, logged.data(), 2).unwrap();
    assert_eq!(mode.raw(), 0);
}

#[test]
fn tpdo1_is_configured_as_section_11_4_3_prints_it() {
    // 1A00h: 2 entries, 60630020, 60410010; 1800h: COB-ID 0x181, type 254, inhibit time 10,
    // event timer 0 (lines 2986-2998).
    let writes: Vec<(u16, u8, Vec<u8>)> = Tpdo1::config(node(1))
        .plan()
        .unwrap()
        .map(|w| (w.index, w.subindex, w.data().to_vec()))
        .collect();
    let expect = [
        (0x1800, 1, 0x8000_0181u32.to_le_bytes().to_vec()),
        (0x1800, 2, vec![254]),
        (0x1800, 3, 10u16.to_le_bytes().to_vec()),
        (0x1800, 5, 0u16.to_le_bytes().to_vec()),
        (0x1A00, 0, vec![0]),
        (0x1A00, 1, 0x6063_0020u32.to_le_bytes().to_vec()),
        (0x1A00, 2, 0x6041_0010u32.to_le_bytes().to_vec()),
        (0x1A00, 0, vec![2]),
        (0x1800, 1, 0x0000_0181u32.to_le_bytes().to_vec()),
    ];
    assert_eq!(writes, expect);
}

#[test]
fn the_rpdos_carry_what_section_11_4_2_lists() {
    // RPDO1: target position + operation mode + controlword; RPDO2: target speed + profile
    // speed (lines 2964-2966); COB-IDs 0x200 / 0x300 + node (lines 2737-2738).
    assert_eq!(Rpdo1::cob_id(node(1)), 0x201);
    assert_eq!(Rpdo2::cob_id(node(1)), 0x301);
    let entries = |e: &[MappedObject]| e.iter().map(|m| m.entry()).collect::<Vec<_>>();
    assert_eq!(
        entries(Rpdo1::LAYOUT.entries()),
        [0x607A_0020, 0x6060_0008, 0x6040_0010]
    );
    assert_eq!(entries(Rpdo2::LAYOUT.entries()), [0x60FF_0020, 0x6081_0020]);
    assert_eq!(Rpdo1::LAYOUT.len(), 7, "4 + 1 + 2 bytes");
    assert_eq!(Rpdo2::LAYOUT.len(), 8, "not more than 8 bytes (line 2970)");
    // The target position of the position example, 50000 inc (line 3266), in RPDO1's first 4 bytes.
    let mut payload = [0u8; 8];
    drivebus::canopen::pdo::encode_entry::<TargetPosition, 3>(
        &Rpdo1::LAYOUT,
        &mut payload,
        0,
        drivebus::units::Increments(50_000.0),
    )
    .unwrap();
    assert_eq!(payload[..4], [0x50, 0xC3, 0x00, 0x00]);
}

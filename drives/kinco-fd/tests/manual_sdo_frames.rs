//! The SDO requests of section 11.5 (manual lines 3254-3283, node 1: COB-ID 0x601) whose digits
//! are intact, built through the generated API and drivebus' sans-I/O SDO client. The manual
//! prints expedited downloads without the unused trailing bytes (`2B 40 60 00 0F 00` for an
//! 8-byte frame): the printed bytes must be a prefix of the frame, the rest zero. The position
//! section's controlword and mode lines (3264-3265) drop a digit and are left out; its other
//! lines are intact.

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::memory::SdoRecorder;
use drivebus::units::{Increments, Rpm};
use kinco_fd::types::ModesOfOperation;
use kinco_fd::KincoFd;

fn drive() -> KincoFd<CanOpenLink<SdoRecorder>> {
    let mut recorder = SdoRecorder::default();
    recorder
        .memory
        .set_object(0x6410, 3, &10_000u32.to_le_bytes())
        .set_object(0x6040, 0, &[0, 0])
        .set_object(0x6041, 0, &[0x37, 0xC0])
        .set_object(0x6060, 0, &[0])
        .set_object(0x6098, 0, &[0])
        .set_object(0x6099, 1, &[0; 4])
        .set_object(0x6099, 2, &[0; 4])
        .set_object(0x607A, 0, &[0; 4])
        .set_object(0x6081, 0, &[0; 4])
        .set_object(0x60FF, 0, &[0; 4]);
    KincoFd::canopen(recorder, NodeId::new(1).unwrap())
}

/// The request frames (COB-ID, data) sent, leaving out the reads of the encoder resolution the
/// speed scale makes.
fn requests(mut drive: KincoFd<CanOpenLink<SdoRecorder>>) -> Vec<(u16, Vec<u8>)> {
    drive
        .device()
        .link_mut()
        .bus_mut()
        .frames
        .iter()
        .map(|f| (f.id(), f.data().to_vec()))
        .filter(|(_, data)| data[1..4] != [0x10, 0x64, 0x03])
        .collect()
}

/// A printed request: `601` then its data bytes.
fn printed(hex: &str) -> (u16, Vec<u8>) {
    let bytes: Vec<u8> = hex
        .split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect();
    (0x601, bytes)
}

fn assert_sent(sent: &[(u16, Vec<u8>)], manual: &[&str]) {
    assert_eq!(sent.len(), manual.len(), "{sent:02X?}");
    for ((id, data), hex) in sent.iter().zip(manual) {
        let (cob_id, bytes) = printed(hex);
        assert_eq!(*id, cob_id);
        assert_eq!(data.len(), 8);
        assert_eq!(data[..bytes.len()], bytes[..], "{hex}");
        assert!(
            data[bytes.len()..].iter().all(|&b| b == 0),
            "{hex}: {data:02X?}"
        );
    }
}

/// 0x00085555, the manual's "200 rpm": 199.99988 rpm at resolution 10000.
fn rpm_200_as_printed() -> Rpm {
    Rpm(f64::from(0x0008_5555u32) * 1875.0 / 5_120_000.0)
}

#[test]
fn homing_lines_3254_3260() {
    let mut drive = drive();
    drive.controlword().write_raw(0x0F).unwrap();
    drive
        .modes_of_operation()
        .write(ModesOfOperation::HOMING)
        .unwrap();
    drive
        .homing_method()
        .write(kinco_fd::types::HomingMethod::METHOD33)
        .unwrap();
    drive
        .homing_speed_switch()
        .write(rpm_200_as_printed())
        .unwrap();
    drive.homing_speed_zero().write(Rpm(150.0)).unwrap();
    drive.controlword().write_raw(0x1F).unwrap();
    let status = drive.statusword().read_raw().unwrap();
    assert_eq!(status, 0xC037, "home found (line 3260)");
    assert_sent(
        &requests(drive),
        &[
            "2B 40 60 00 0F 00",
            "2F 60 60 00 06 00",
            "2F 98 60 00 21 00",
            "23 99 60 01 55 55 08 00",
            "23 99 60 02 00 40 06 00",
            "2B 40 60 00 1F 00",
            "40 41 60 00 00 00 00 00",
        ],
    );
}

#[test]
fn position_lines_3266_3273() {
    let mut drive = drive();
    drive.target_position().write(Increments(50_000.0)).unwrap();
    drive.profile_speed().write(rpm_200_as_printed()).unwrap();
    for command in [0x2F, 0x3F, 0x4F, 0x5F] {
        drive.controlword().write_raw(command).unwrap();
    }
    assert_sent(
        &requests(drive),
        &[
            "23 7A 60 00 50 C3 00 00",
            "23 81 60 00 55 55 08 00",
            "2B 40 60 00 2F 00",
            "2B 40 60 00 3F 00",
            "2B 40 60 00 4F 00",
            "2B 40 60 00 5F 00",
        ],
    );
}

#[test]
fn speed_lines_3278_3281() {
    let mut drive = drive();
    drive
        .modes_of_operation()
        .write(ModesOfOperation::VELOCITY)
        .unwrap();
    drive.target_velocity().write(Rpm(150.0)).unwrap();
    drive.controlword().write_raw(0x0F).unwrap();
    assert_sent(
        &requests(drive),
        &[
            "2F 60 60 00 03 00",
            "23 FF 60 00 00 40 06 00",
            "2B 40 60 00 0F 00",
        ],
    );
}

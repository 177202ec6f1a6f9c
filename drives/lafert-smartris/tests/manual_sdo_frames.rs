//! The SDO frames of the user guide's CANopen run sequence (11.1.2, 000_ac225e0ba9cf582c.txt lines
//! 7507-7568), built through the generated API and drivebus' sans-I/O SDO client, compared with
//! the printed bytes (node 1: request COB-ID 0x601).

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::testing::SdoRecorder;
use lafert_smartris::Smartris;

fn drive() -> Smartris<CanOpenLink<SdoRecorder>> {
    let mut recorder = SdoRecorder::default();
    recorder
        .memory
        .set_object(0x6040, 0, &[0, 0])
        .set_object(0x6041, 0, &[0x27, 0])
        .set_object(0x60FF, 0, &[0; 4])
        .set_object(0x606C, 0, &[0; 4]);
    Smartris::canopen(recorder, NodeId::new(1).unwrap())
}

fn sent(mut drive: Smartris<CanOpenLink<SdoRecorder>>) -> Vec<(u16, Vec<u8>)> {
    drive
        .device()
        .link_mut()
        .bus_mut()
        .frames
        .iter()
        .map(|f| (f.id(), f.data().to_vec()))
        .collect()
}

#[test]
fn controlword_sequence_shutdown_switch_on_enable() {
    // Lines 7507-7513: 6040h = 0x00, 0x06, 0x07, 0x0F, each "ID (601) ... 2B 40 60 00 xx 00 00 00".
    let mut drive = drive();
    for word in [0x00, 0x06, 0x07, 0x0F] {
        drive.controlword().write_raw(word).unwrap();
    }
    let expected: Vec<(u16, Vec<u8>)> = [0x00, 0x06, 0x07, 0x0F]
        .into_iter()
        .map(|word| (0x601, vec![0x2B, 0x40, 0x60, 0x00, word, 0x00, 0x00, 0x00]))
        .collect();
    assert_eq!(sent(drive), expected);
}

#[test]
fn target_velocity_frames() {
    // Lines 7515-7519 and 7568: 60FFh in user units (inc/s by default; ERRATA.md C5).
    let printed: [(i32, [u8; 4]); 4] = [
        (0x000C_8000, [0x00, 0x80, 0x0C, 0x00]), // "3000 rpm" = 3000 * 16384 / 60
        (0x0006_8000, [0x00, 0x80, 0x06, 0x00]), // "1550 rpm" (approximate, C5)
        (0x0000_7000, [0x00, 0x70, 0x00, 0x00]), // "100 rpm" (approximate, C5)
        (0x0012_BED4, [0xD4, 0xBE, 0x12, 0x00]), // "4500 rpm" (approximate, C5)
    ];
    assert_eq!(
        printed[0].0,
        3000 * 16384 / 60,
        "the 3000 rpm frame is exact"
    );
    let mut drive = drive();
    for (raw, _) in printed {
        drive.target_velocity().write_raw(raw).unwrap();
    }
    let expected: Vec<(u16, Vec<u8>)> = printed
        .iter()
        .map(|(_, bytes)| {
            let mut data = vec![0x23, 0xFF, 0x60, 0x00];
            data.extend_from_slice(bytes);
            (0x601, data)
        })
        .collect();
    assert_eq!(sent(drive), expected);
}

#[test]
fn reads_are_uploads_and_the_enabled_statusword_is_0x27() {
    // Lines 7521/7523 print "4B 6C 60 00" and "23 41 60 00"; a read is an upload request, 0x40
    // (ERRATA.md C8). Line 7548: enabled → statusword 0x27.
    let mut drive = drive();
    drive.velocity_actual_value().read_raw().unwrap();
    assert_eq!(drive.statusword().read_raw(), Ok(0x27));
    assert_eq!(
        sent(drive),
        [
            (0x601, vec![0x40, 0x6C, 0x60, 0x00, 0, 0, 0, 0]),
            (0x601, vec![0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]),
        ]
    );
}

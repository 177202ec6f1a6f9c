//! The quick start's frames (appendix "SWD - Quick start", lines 4072-4181; node 10h: SDO
//! request COB-ID 610h) built through the generated API and drivebus' sans-I/O SDO client, NMT
//! and frame codecs, compared with the printed bytes.

use drivebus::canopen::nmt::{NmtCommand, NmtState};
use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{
    self, write_safety_configuration, MappingWrite, SrdoCommunication, SrdoConfig,
};
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::testing::SdoRecorder;
use drivebus::units::Rpm;
use ezwheel_swd::Swd;

const NODE: NodeId = NodeId(0x10);

fn drive() -> Swd<CanOpenLink<SdoRecorder>> {
    let mut recorder = SdoRecorder::default();
    recorder
        .memory
        .set_object(0x6040, 0, &[0, 0])
        .set_object(0x6041, 0, &[0x27, 0])
        .set_object(0x6042, 0, &[0, 0])
        .set_object(0x604C, 1, &1i32.to_le_bytes())
        .set_object(0x604C, 2, &1i32.to_le_bytes())
        .set_object(0x1010, 1, &[0; 4])
        .set_object(0x1301, 1, &[2])
        .set_object(0x1301, 2, &50u16.to_le_bytes())
        .set_object(0x1301, 3, &20u16.to_le_bytes())
        .set_object(0x1301, 5, &0x11Fu32.to_le_bytes())
        .set_object(0x1301, 6, &0x120u32.to_le_bytes())
        .set_object(0x13FF, 1, &[0; 2])
        .set_object(0x13FE, 0, &[0]);
    Swd::canopen(recorder, NODE)
}

fn sent(drive: &mut Swd<CanOpenLink<SdoRecorder>>) -> Vec<(u16, Vec<u8>)> {
    let frames = std::mem::take(&mut drive.device().link_mut().bus_mut().frames);
    frames.iter().map(|f| (f.id(), f.data().to_vec())).collect()
}

fn frame(bytes: [u8; 8]) -> Vec<(u16, Vec<u8>)> {
    vec![(0x610, bytes.to_vec())]
}

#[test]
fn controlword_commands_of_the_quick_start() {
    // Lines 4180-4183: reset fault 80h, ready to switch on 06h, switched on 07h, enabled 0Fh.
    let mut drive = drive();
    for word in [0x80, 0x06, 0x07, 0x0F] {
        drive.controlword().write_raw(word).unwrap();
        assert_eq!(
            sent(&mut drive),
            frame([0x2B, 0x40, 0x60, 0x00, word as u8, 0, 0, 0])
        );
    }
}

#[test]
fn statusword_read_is_an_upload_request() {
    // Lines 4171-4172: request 40 41 60 00, response 4B 41 60 00 XX (2 bytes).
    let mut drive = drive();
    let status = drive.statusword().read().unwrap();
    assert_eq!(
        sent(&mut drive),
        frame([0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0])
    );
    assert_eq!(status.bits(), 0x0027);
}

#[test]
fn velocity_setpoints_are_two_byte_downloads() {
    // Lines 4192-4195. The command byte 2Bh is a 2-byte expedited download (6042h is INTEGER16):
    // the printed FF FF after a negative value is padding; the frames agree on bytes 0-5.
    let mut drive = drive();
    for (rpm, printed) in [
        (298.0, [0x2B, 0x42, 0x60, 0x00, 0x2A, 0x01, 0x00, 0x00]),
        (-298.0, [0x2B, 0x42, 0x60, 0x00, 0xD6, 0xFE, 0xFF, 0xFF]),
        (1400.0, [0x2B, 0x42, 0x60, 0x00, 0x78, 0x05, 0x00, 0x00]),
        // "FA88h = 1400d" (line 4195) is -1400 (ERRATA.md).
        (-1400.0, [0x2B, 0x42, 0x60, 0x00, 0x88, 0xFA, 0xFF, 0xFF]),
    ] {
        drive.set_motor_speed(Rpm(rpm)).unwrap();
        let frames = sent(&mut drive);
        // The dimension factor 604Ch is read (two uploads) before the setpoint is written.
        let (id, data) = frames.last().unwrap();
        assert_eq!(*id, 0x610);
        assert_eq!(data[..6], printed[..6], "{rpm} rpm");
    }
}

#[test]
fn save_all_parameters_writes_save() {
    // Line 4127: 23 10 10 01 73 61 76 65 ("save" = 65766173h, line 1946).
    let mut drive = drive();
    drive.store_all_parameters().write_raw(0x6576_6173).unwrap();
    assert_eq!(
        sent(&mut drive),
        frame([0x23, 0x10, 0x10, 0x01, 0x73, 0x61, 0x76, 0x65])
    );
}

#[test]
fn srdo1_configuration_frames_of_step_4() {
    // Lines 4107-4111: disable SRDO 1 reception (1301:01 = 0), signature 13FF:01 = BABDh,
    // configuration valid 13FE:00 = A5h. Safety objects have no plain setters: the frames come
    // from the deliberate safety write, which also rewrites SCT, SRVT and the COB-IDs.
    let mut drive = drive();
    let mapping = [
        MappedObject::from_entry(0x6620_0108),
        MappedObject::from_entry(0x6622_0108),
    ];
    let srdo1 = SrdoConfig {
        number: 1,
        communication: SrdoCommunication {
            direction: srdo::SrdoDirection::Invalid,
            sct_ms: 50,
            srvt_ms: 20,
            transmission_type: 0xFE,
            cob_id_normal: 0x11F,
            cob_id_inverted: 0x120,
        },
        mapping: &mapping,
    };
    let bus = drive.device().link_mut().bus_mut();
    let signature = write_safety_configuration(
        bus,
        NODE,
        NmtState::PreOperational,
        srdo1,
        MappingWrite::Keep,
    );
    assert_eq!(signature, Ok(0xBABD));
    let printed: Vec<(u16, Vec<u8>)> = [
        [0x2F, 0x01, 0x13, 0x01, 0x00, 0, 0, 0],
        [0x2B, 0xFF, 0x13, 0x01, 0xBD, 0xBA, 0, 0],
        [0x2F, 0xFE, 0x13, 0x00, 0xA5, 0, 0, 0],
    ]
    .into_iter()
    .flat_map(frame)
    .collect();
    let sent = sent(&mut drive);
    let positions: Vec<usize> = printed
        .iter()
        .map(|p| {
            sent.iter()
                .position(|s| s == p)
                .expect("printed frame sent")
        })
        .collect();
    assert!(positions.windows(2).all(|w| w[0] < w[1]), "{positions:?}");
    assert_eq!(sent.last(), printed.last(), "validity is written last");
}

#[test]
fn nmt_start_of_step_6a() {
    // Line 4143: 000h 01 10 (node 10h), or 01 00 to all nodes.
    let to_node = NmtCommand::Start.frame(Some(NODE));
    assert_eq!((to_node.id(), to_node.data()), (0x000, &[0x01, 0x10][..]));
    let broadcast = NmtCommand::Start.frame(None);
    assert_eq!(broadcast.data(), &[0x01, 0x00]);
}

#[test]
fn srdo1_cob_ids_are_the_quick_starts() {
    // Line 4112: SRDO 1 is sent on 11Fh (FFh) and 120h (00h, the inverse): 0FFh + 2 x 10h.
    use drivegen::ir::Number;
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/ezwheel-swd"
    );
    let device = drivegen::check(std::path::Path::new(path)).device.unwrap();
    let default = |name: &str| device.parameter(name).unwrap().default;
    assert_eq!(default("srdo1_cob_id_1"), Some(Number::Int(0x11F)));
    assert_eq!(default("srdo1_cob_id_2"), Some(Number::Int(0x120)));
}

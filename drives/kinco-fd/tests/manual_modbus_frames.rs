//! Every Modbus frame of sections 10.4 and 10.5 (manual 003_8cc8f7f4f05b8633.txt, lines
//! 2466-2522), with its printed CRC, built through the generated API and `drivebus::modbus::rtu`,
//! and checked against a CRC-16/MODBUS computed here bit by bit. Station 1; the encoder
//! resolution is the manual's 10000.

mod manual;

use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::testing::RtuRecorder;
use kinco_fd::types::ModesOfOperation;
use kinco_fd::KincoFd;
use manual::{hex, rpm_200_as_printed};
use peer_support::modbus_crc::crc16_modbus;

/// A manual frame written as hex pairs; its last two bytes must be its CRC, low byte first.
fn frame(printed: &str) -> Vec<u8> {
    let bytes = hex(printed);
    let (body, crc) = bytes.split_at(bytes.len() - 2);
    assert_eq!(
        crc,
        crc16_modbus(body).to_le_bytes(),
        "printed CRC of {printed}"
    );
    bytes
}

fn drive() -> KincoFd<ModbusLink<RtuRecorder>> {
    let mut recorder = RtuRecorder::default();
    for address in [0x3100, 0x3200, 0x3201, 0x3500, 0x4D00] {
        recorder.memory.set_register(Table::Holding, address, 0);
    }
    for start in [0x4000, 0x4A00, 0x5010, 0x5020, 0x6F00] {
        recorder.memory.set_register(Table::Holding, start, 0);
        recorder.memory.set_register(Table::Holding, start + 1, 0);
    }
    KincoFd::modbus(recorder, UnitId(1)).give_encoder_resolution(10_000)
}

fn frames(drive: KincoFd<ModbusLink<RtuRecorder>>) -> Vec<Vec<u8>> {
    drive.into_link().into_bus().frames
}

const MODE_3: &str = "01 06 35 00 00 03 C6 07";
const SPEED_200_RPM: &str = "01 10 6F 00 00 02 04 55 55 00 08 1A 47";
const ENABLE: &str = "01 06 31 00 00 0F C7 32";

#[test]
fn write_multiple_example_10_4() {
    // Line 2466: target velocity 0x00085555 = 546133 DEC = 200 rpm (erratum: not "150 RPM").
    let mut drive = drive();
    drive.target_velocity().write(rpm_200_as_printed()).unwrap();
    assert_eq!(frames(drive), [frame(SPEED_200_RPM)]);
}

#[test]
fn speed_mode_10_5() {
    // Lines 2485-2487 and 2518-2520: mode 3, target speed, enable.
    let mut drive = drive();
    manual::speed_mode!(drive, rpm_200_as_printed());
    assert_eq!(
        frames(drive),
        [frame(MODE_3), frame(SPEED_200_RPM), frame(ENABLE)]
    );
}

#[test]
fn homing_10_5() {
    let mut drive = drive();
    manual::homing!(drive);
    let expected = [
        ENABLE,
        "01 06 35 00 00 06 06 04",
        "01 06 4D 00 00 21 5E BE",
        "01 10 50 10 00 02 04 55 55 00 08 0E BA",
        "01 10 50 20 00 02 04 40 00 00 06 98 76",
        "01 06 31 00 00 1F C6 FE",
    ];
    assert_eq!(frames(drive), expected.map(frame));
}

#[test]
fn position_mode_10_5() {
    // Lines 2502-2512: enable, mode 1, 50000 inc, profile speed 200 rpm, then 2F/3F/4F/5F.
    let mut drive = drive();
    drive.controlword().write_raw(0x0F).unwrap();
    drive
        .modes_of_operation()
        .write(ModesOfOperation::POSITION)
        .unwrap();
    manual::position_move!(drive);
    let expected = [
        ENABLE,
        "01 06 35 00 00 01 47 C6",
        "01 10 40 00 00 02 04 C3 50 00 00 FE 39",
        "01 10 4A 00 00 02 04 55 55 00 08 BC D6",
        "01 06 31 00 00 2F C6 EA",
        "01 06 31 00 00 3F C7 26",
        "01 06 31 00 00 4F C6 C2",
        "01 06 31 00 00 5F C7 0E",
    ];
    assert_eq!(frames(drive), expected.map(frame));
}

#[test]
fn status_read_10_5() {
    // Line 2488: the manual reads two registers at 0x3200 for the 16-bit statusword (erratum):
    // the frame is intact, and the generated API reads the one register the word occupies.
    let printed = frame("01 03 32 00 00 02 CA B3");
    let mut drive = drive();
    drive.statusword().read().unwrap();
    let sent = frames(drive);
    assert_eq!(sent[0][..5], printed[..5]);
    assert_eq!(sent[0][5], 1, "one register");
}

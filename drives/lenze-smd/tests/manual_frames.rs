//! Every frame the smd manual prints (004_e90b7fce7c8d5710.txt): the request and response rows of
//! Table 6 (lines 475-510), the message structures of section 6.1 (lines 828-843) and the
//! commands of sections 4.8 and 7.2-7.4 (lines 441-446, 1057-1079), instantiated at slave
//! address SA = 0x0A with the data the text gives, built and decoded through the generated crate
//! and `drivebus`'s RTU client, and compared with the manual's bytes plus a CRC-16/MODBUS
//! computed here bit by bit. The manual prints "CRCH CRCL"; the frames carry the CRC low byte
//! first (ERRATA.md E4), and the printed order is shown to be no valid frame.

#[path = "support/scripted_line.rs"]
mod scripted_line;

use drivebus::modbus::client::Client;
use drivebus::modbus::rtu::{open_frame, RtuFraming};
use drivebus::modbus::{ModbusLink, UnitId};
use drivebus::units::{Hertz, Percent};
use drivebus::BusError;
use lenze_smd::types::{
    ControlSource, Direction, FaultCode, HardwareConfiguration, OperationalStatus,
    ParameterConfiguration, SpeedCommandSource, SpeedReference,
};
use lenze_smd::{Command, LenzeSmd, SmdError, Trigger, UnlockError, Variant, VariantSelection};
use peer_support::modbus_crc::{with_crc, with_crc_as_printed};
use scripted_line::{client, ScriptedLine};

const SA: u8 = 0x0A;

type Drive = LenzeSmd<ModbusLink<Client<ScriptedLine, RtuFraming>>>;

/// A drive whose answers are the given manual frames (without CRC).
fn drive(answers: &[&[u8]]) -> Drive {
    let line = ScriptedLine::answering(answers.iter().map(|a| with_crc(a)));
    LenzeSmd::modbus(client(line), UnitId(SA))
}

fn sent(drive: Drive) -> Vec<Vec<u8>> {
    drive.into_link().into_bus().into_stream().sent
}

/// Reading C01 (#51, PC507 and PC400 alike) before unlocking the controls, and its answer 11.
const READ_C01: [u8; 6] = [SA, 0x03, 0x00, 0x33, 0x00, 0x01];
const C01_IS_11: [u8; 5] = [SA, 0x03, 0x02, 0x00, 0x0B];
/// #48 = 0: unlock the controls (4.8 step 4, line 441), echoed.
const UNLOCK_CONTROLS: [u8; 6] = [SA, 0x06, 0x00, 0x30, 0x00, 0x00];
/// #1 = 0x0002: lock (4.8 step 9, line 446), echoed.
const LOCK: [u8; 6] = [SA, 0x06, 0x00, 0x01, 0x00, 0x02];

/// The request frames (without CRC) as the manual prints them.
fn frames(requests: &[&[u8]]) -> Vec<Vec<u8>> {
    requests.iter().map(|r| with_crc(r)).collect()
}

#[test]
fn the_crc_goes_low_byte_first_not_as_printed() {
    // Line 477: read #19. Sent through the crate, the CRC comes low byte first.
    let request = [SA, 0x03, 0x00, 0x13, 0x00, 0x01];
    let mut d = drive(&[&[SA, 0x03, 0x02, 0x00, 0x45]]);
    d.drive_family().read().unwrap();
    let sent = sent(d);
    assert_eq!(sent, frames(&[&request]));
    let printed = with_crc_as_printed(&request);
    assert_ne!(
        sent[0], printed,
        "this CRC is symmetric; pick another frame"
    );
    // The manual's "CRCH CRCL" order is no valid RTU frame.
    assert!(open_frame(UnitId(SA), &sent[0]).is_ok());
    assert!(open_frame(UnitId(SA), &printed).is_err());
}

#[test]
fn a_response_with_the_crc_as_printed_is_refused() {
    let line = ScriptedLine::answering([with_crc_as_printed(&[SA, 0x03, 0x02, 0x00, 0x45])]);
    let mut d: Drive = LenzeSmd::modbus(client(line), UnitId(SA));
    assert!(d.drive_family().read().is_err());
}

#[test]
fn drive_control_register_1_writes() {
    // Line 475 (W / RS echo); the commands of 7.2-7.3 (lines 1063-1072) and the lock of 4.8
    // step 9 (line 446), each a separate write of one bit.
    let words: [(Command, u16); 5] = [
        (Command::SerialSpeedReference, 0x0100),
        (Command::Stop, 0x0004),
        (Command::Start, 0x0008),
        (Command::Reverse, 0x0040),
        (Command::Forward, 0x0080),
    ];
    for (command, word) in words {
        let frame = [SA, 0x06, 0x00, 0x01, (word >> 8) as u8, word as u8];
        let mut d = drive(&[&C01_IS_11, &UNLOCK_CONTROLS, &frame, &LOCK]);
        let mut unlocked = d.unlock_controls().unwrap();
        unlocked.command(command).unwrap();
        unlocked.lock().unwrap();
        assert_eq!(command.word(), word);
        assert_eq!(
            sent(d),
            frames(&[&READ_C01, &UNLOCK_CONTROLS, &frame, &LOCK]),
            "{command:?}"
        );
    }
}

#[test]
fn drive_family_19_and_drive_size_21() {
    // Lines 477-480: the smd answers 0x45 (69) and always 0 for the size.
    let mut d = drive(&[&[SA, 0x03, 0x02, 0x00, 0x45], &[SA, 0x03, 0x02, 0x00, 0x00]]);
    let family = d.drive_family().read().unwrap();
    assert_eq!(
        (family, family.raw()),
        (lenze_smd::types::DriveFamily::SMD, 69)
    );
    assert_eq!(d.drive_size().read().unwrap(), 0);
    assert_eq!(
        sent(d),
        frames(&[
            &[SA, 0x03, 0x00, 0x13, 0x00, 0x01],
            &[SA, 0x03, 0x00, 0x15, 0x00, 0x01]
        ])
    );
}

#[test]
fn hardware_configuration_22() {
    // Lines 481-482 with DL = 0x04: bit 2, OEM defaults present (Table 9, line 604).
    let mut d = drive(&[&[SA, 0x03, 0x02, 0x00, 0x04]]);
    let flags = d.hardware_configuration().read().unwrap();
    assert_eq!(flags, HardwareConfiguration::OEM_DEFAULTS_PRESENT);
    assert_eq!(sent(d), frames(&[&[SA, 0x03, 0x00, 0x16, 0x00, 0x01]]));
}

#[test]
fn status_block_24_six_words() {
    // Lines 483-486 and Table 10: D1 = 02 01 (51.3 Hz, Note 4a line 640), D2 = 01 F4 (50.0 Hz),
    // D3 = 64 06 (100 % load, line 654; RUN), D4 = 01 0B (reverse; C40 / Modbus / Modbus),
    // D5 = 06 00 (serial speed; serial reference), D6 = 18 01 (FC3 communication fault; reverse).
    let answer = [
        SA, 0x03, 0x0C, 0x02, 0x01, 0x01, 0xF4, 0x64, 0x06, 0x01, 0x0B, 0x06, 0x00, 0x18, 0x01,
    ];
    let mut d = drive(&[&answer]);
    let status = d.status().unwrap();
    assert_eq!(sent(d), frames(&[&[SA, 0x03, 0x00, 0x18, 0x00, 0x06]]));
    assert!((status.command_speed.0 - 51.3).abs() < 1e-9);
    assert!((status.actual_speed.0 - 50.0).abs() < 1e-9);
    assert_eq!(status.load_and_status.load(), 100);
    assert_eq!(
        status.load_and_status.operational_status(),
        OperationalStatus::RUN
    );
    let mode = status.direction_and_control_mode;
    assert_eq!(mode.actual_direction(), Direction::REVERSE);
    assert_eq!(mode.control_mode(), ControlSource::C40_MODBUS);
    let source = status.speed_source_and_reference;
    assert_eq!(source.speed_command_source(), SpeedCommandSource::SERIAL);
    assert_eq!(source.speed_reference(), SpeedReference::SERIAL);
    let fault = status.fault_and_commanded_direction;
    assert_eq!(fault.present_fault(), FaultCode::COMMUNICATION_FAULT);
    assert_eq!(fault.present_fault().meaning(), Some("COMMUNICATION FAULT"));
    assert_eq!(fault.commanded_direction(), Direction::REVERSE);
}

#[test]
fn status_registers_24_to_30_one_word_each() {
    // Lines 487-500, one request each; #26 is also the read of section 7.4 (40027, line 1079).
    let mut d = drive(&[
        &[SA, 0x03, 0x02, 0x02, 0x01],
        &[SA, 0x03, 0x02, 0x01, 0xF4],
        &[SA, 0x03, 0x02, 0x64, 0x07],
        &[SA, 0x03, 0x02, 0x00, 0x0A],
        &[SA, 0x03, 0x02, 0x01, 0x01],
        &[SA, 0x03, 0x02, 0x02, 0x00],
        &[SA, 0x03, 0x02, 0x00, 0xFA],
    ]);
    assert!((d.command_speed().read().unwrap().0 - 51.3).abs() < 1e-9);
    assert!((d.actual_speed().read().unwrap().0 - 50.0).abs() < 1e-9);
    let load = d.load_and_status().read().unwrap();
    assert_eq!(
        (load.load(), load.operational_status()),
        (100, OperationalStatus::ACCEL)
    );
    let mode = d.direction_and_control_mode().read().unwrap();
    assert_eq!(mode.control_mode(), ControlSource::ANALOG_MODBUS);
    assert_eq!(mode.actual_direction(), Direction::FORWARD);
    let source = d.speed_source_and_reference().read().unwrap();
    assert_eq!(
        source.speed_command_source(),
        SpeedCommandSource::PRESET_C40
    );
    assert_eq!(source.speed_reference(), SpeedReference::LOCAL);
    let fault = d.fault_and_commanded_direction().read().unwrap();
    assert_eq!(fault.present_fault(), FaultCode::HIGH_DRIVE_TEMPERATURE);
    assert_eq!(d.motor_voltage().read().unwrap(), Percent(250.0));
    let requests: Vec<Vec<u8>> = (0x18..=0x1E)
        .map(|r| with_crc(&[SA, 0x03, 0x00, r, 0x00, 0x01]))
        .collect();
    assert_eq!(sent(d), requests);
}

#[test]
fn serial_speed_command_40_read_and_write() {
    // Lines 501-504; 412 → 41.2 Hz (section 7.3, line 1073). The write reads its bounds C10
    // (#59, 0.0 Hz) and C11 (#60, 50.0 Hz) first (line 501, `bounds`).
    let write = [SA, 0x06, 0x00, 0x28, 0x01, 0x9C];
    let mut d = drive(&[
        &[SA, 0x03, 0x02, 0x01, 0x9C],
        &C01_IS_11,
        &UNLOCK_CONTROLS,
        &[SA, 0x03, 0x02, 0x00, 0x00],
        &[SA, 0x03, 0x02, 0x01, 0xF4],
        &write,
        &LOCK,
    ]);
    assert!((d.serial_speed_command().read().unwrap().0 - 41.2).abs() < 1e-9);
    let mut unlocked = d.unlock_controls().unwrap();
    unlocked.serial_speed_command().write(Hertz(41.2)).unwrap();
    drop(unlocked); // locks
    assert_eq!(
        sent(d),
        frames(&[
            &[SA, 0x03, 0x00, 0x28, 0x00, 0x01],
            &READ_C01,
            &UNLOCK_CONTROLS,
            &[SA, 0x03, 0x00, 0x3B, 0x00, 0x01],
            &[SA, 0x03, 0x00, 0x3C, 0x00, 0x01],
            &write,
            &LOCK
        ])
    );
}

#[test]
fn unlock_registers_48_and_49() {
    // Lines 505-508: unlock controls with 0 (4.8 step 4, line 441) and parameters with the
    // factory password 0 (line 424); section 7.2 writes the password to 40049 = #48 (line 1057).
    let controls = [SA, 0x06, 0x00, 0x30, 0x00, 0x00];
    let parameters = [SA, 0x06, 0x00, 0x31, 0x00, 0x00];
    let mut d = drive(&[&controls, &parameters]);
    d.unlock_commands().write(0).unwrap();
    d.unlock_parameters().write(0).unwrap();
    assert_eq!(sent(d), frames(&[&controls, &parameters]));
}

#[test]
fn parameter_configuration_50_selects_the_variant() {
    // Lines 509-510: 0x0190 = 400, 0x01FB = 507, anything else unknown (line 314).
    for (word, expected) in [
        (400u16, VariantSelection::Known(Variant::Pc400)),
        (507, VariantSelection::Known(Variant::Pc507)),
        (401, VariantSelection::Unknown(401)),
    ] {
        let answer = [SA, 0x03, 0x02, (word >> 8) as u8, word as u8];
        let mut d = drive(&[&answer]);
        assert_eq!(d.detect_variant().unwrap(), expected);
        assert_eq!(sent(d), frames(&[&[SA, 0x03, 0x00, 0x32, 0x00, 0x01]]));
    }
    assert_eq!(
        Variant::selected_by(ParameterConfiguration::PC507.raw()),
        Some(Variant::Pc507)
    );
}

#[test]
fn one_word_parameter_read_and_write_6_1() {
    // Section 6.1 (lines 830-843) with C12, acceleration time, #61 (4.9 step 8, line 459):
    // read 50 (5.0 s, the default), write 100 (10.0 s).
    // Parameters are unlocked with #49 = the password C94, factory default 0 (line 424).
    let write = [SA, 0x06, 0x00, 0x3D, 0x00, 0x64];
    let unlock = [SA, 0x06, 0x00, 0x31, 0x00, 0x00];
    let mut d = drive(&[&[SA, 0x03, 0x02, 0x00, 0x32], &unlock, &write, &LOCK]);
    assert_eq!(d.acceleration_time().read().unwrap().0, 5.0);
    let mut unlocked = d.unlock_parameter_writing(0).unwrap();
    unlocked
        .acceleration_time()
        .write(drivebus::units::Seconds(10.0))
        .unwrap();
    unlocked.lock().unwrap();
    assert_eq!(
        sent(d),
        frames(&[&[SA, 0x03, 0x00, 0x3D, 0x00, 0x01], &unlock, &write, &LOCK])
    );
}

#[test]
fn software_version_c99_four_words_6_1() {
    // Section 6.1 (lines 833-836): "SA 03 00 RA 00 04", answer 8 bytes, text as on line 926,
    // through the generated accessor: the planner reads the 4-word value alone although the
    // drive reads one register at a time, and its text runs in address order, each register
    // high byte first (Note 4a, line 639).
    for (variant, register) in [(Variant::Pc400, 0x59u8), (Variant::Pc507, 0x5F)] {
        let mut answer = vec![SA, 0x03, 0x08];
        answer.extend_from_slice(b"SMD 1.51");
        let mut d = drive(&[&answer]);
        d.set_variant(variant);
        let version = d.software_version().read().unwrap();
        assert_eq!(version.as_str(), Some("SMD 1.51"));
        assert_eq!(sent(d), frames(&[&[SA, 0x03, 0x00, register, 0x00, 0x04]]));
    }
}

#[test]
fn a_locked_drive_answers_writes_with_exception_01() {
    // Section 4.5, line 416: exception 01 after a write while locked → typed `Locked`.
    // The unlock ended on the drive's side (a serial timeout, line 414) before `start`.
    let mut d = drive(&[&C01_IS_11, &UNLOCK_CONTROLS, &[SA, 0x86, 0x01]]);
    let mut unlocked = d.unlock_controls().unwrap();
    let error = unlocked.start().trigger().unwrap_err();
    assert_eq!(
        error.bus(),
        Some(&BusError::ModbusException {
            function: 0x06,
            code: drivebus::modbus::ExceptionCode::IllegalFunction
        })
    );
    assert_eq!(
        UnlockError::from(error.clone()),
        UnlockError::Locked { parameter: "start" }
    );
    assert_eq!(
        SmdError::from(error),
        SmdError::Locked { parameter: "start" }
    );
}

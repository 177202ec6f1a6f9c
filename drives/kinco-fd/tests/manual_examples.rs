//! The manual's worked calculations and decodes (003_8cc8f7f4f05b8633.txt) through the generated
//! crate: appendix 2's 10 rpm = 27300 DEC = 0x6AA4, the statuswords 0xC037 and 0xD437, the notch
//! and speed feedback filter bandwidths, the target torque in %, the velocity feedforward range,
//! the analog deadband in 0.01 V and the DIN speed mode default.

use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::modbus::{Table, UnitId};
use drivebus::testing::{MemoryBus, SdoRecorder};
use drivebus::units::{Hertz, Percent, Rpm, Volts};
use drivebus::{Error, ValueError};
use kinco_fd::types::{NotchSwitch, Statusword};
use kinco_fd::KincoFd;

fn modbus(registers: &[(u16, u16)]) -> KincoFd<drivebus::modbus::ModbusLink<MemoryBus>> {
    let mut memory = MemoryBus::new();
    for &(address, value) in registers {
        memory.set_register(Table::Holding, address, value);
    }
    KincoFd::modbus(memory, UnitId(1))
}

fn canopen(objects: &[(u16, u8, &[u8])]) -> KincoFd<CanOpenLink<SdoRecorder>> {
    let mut recorder = SdoRecorder::default();
    for &(index, subindex, value) in objects {
        recorder.memory.set_object(index, subindex, value);
    }
    KincoFd::canopen(recorder, NodeId::new(1).unwrap())
}

/// The data bytes of the SDO requests sent.
fn sent(drive: &mut KincoFd<CanOpenLink<SdoRecorder>>) -> Vec<Vec<u8>> {
    let frames = &drive.device().link_mut().bus_mut().frames;
    frames.iter().map(|f| f.data().to_vec()).collect()
}

#[test]
fn appendix_2_ten_rpm_is_27300_dec_0x6aa4_rounded_from_the_formula() {
    // "1 rpm = 2730 DEC ... 10 rpm = 27300 DEC = 0x6AA4" at resolution 10000 (lines 3405-3407).
    assert_eq!(27_300, 0x6AA4);
    let mut drive = modbus(&[(0x6F00, 0x6AA4), (0x6F01, 0)]).give_encoder_resolution(10_000);
    // Read back, the printed 27300 DEC is 9.9976 rpm: the formula (line 3401) gives 27306.67 DEC
    // for 10 rpm, which the example rounds per rpm (ERRATA.md #8).
    let read = drive.target_velocity().read().unwrap();
    assert_eq!(drive.target_velocity().read_raw().unwrap(), 27_300);
    assert!(
        (read.0 - 27_300.0 * 1875.0 / 5_120_000.0).abs() < 1e-9,
        "{read:?}"
    );
    assert!(
        (read.0 - 10.0).abs() < 0.003,
        "within the rounding of the example"
    );
    // 10 rpm itself is no whole DEC: refused, never rounded to the example's value.
    let refused = drive.target_velocity().write(Rpm(10.0));
    assert!(
        matches!(
            refused,
            Err(Error::Value(ValueError::NotRepresentable { .. }))
        ),
        "{refused:?}"
    );
}

#[test]
fn statusword_0xc037_is_home_found_and_0xd437_position_reached() {
    // C037 "means home found" (lines 2498, 3260); D437 "means position found" (lines 2513, 3274).
    // Kinco's bits (line 1936): 0 ready on, 1 switch on, 2 operation enable, 4 voltage enable,
    // 5 quick stop, 10 target reached, 12 setpoint ack, 14 communication found, 15 reference found.
    let mut drive = modbus(&[(0x3200, 0xC037)]);
    let home = drive.statusword().read().unwrap();
    let enabled = Statusword::READY_TO_SWITCH_ON
        | Statusword::SWITCHED_ON
        | Statusword::OPERATION_ENABLED
        | Statusword::VOLTAGE_ENABLED
        | Statusword::QUICK_STOP;
    assert!(home.contains(enabled));
    assert_eq!(
        home.manufacturer_specific(),
        0b11,
        "communication and reference found"
    );
    assert!(!home.contains(Statusword::TARGET_REACHED));
    assert!(!home.contains(Statusword::FAULT));

    let mut drive = modbus(&[(0x3200, 0xD437)]);
    let reached = drive.statusword().read().unwrap();
    assert!(reached.contains(enabled | Statusword::TARGET_REACHED));
    assert!(
        reached.contains(Statusword::OPERATION_MODE_SPECIFIC_12),
        "setpoint ack"
    );
    assert_eq!(reached.manufacturer_specific(), 0b11);
    assert_eq!(
        reached.bits() ^ home.bits(),
        0x1400,
        "bits 10 and 12 differ"
    );
}

#[test]
fn a_500_hz_resonance_is_notch_n_40() {
    // F = Notch_N * 10 + 100; "if mechanical resonance frequency F = 500 Hz, the parameter
    // setting should be 40" (line 1815). Default 45 = 550 Hz.
    let mut drive = canopen(&[(0x60F9, 0x03, &[45]), (0x60F9, 0x04, &[0])]);
    assert_eq!(drive.notch_frequency().read().unwrap(), Hertz(550.0));
    drive.notch_frequency().write(Hertz(500.0)).unwrap();
    drive.notch_on().write(NotchSwitch::ON).unwrap();
    let frames = sent(&mut drive);
    assert_eq!(frames[1][..5], [0x2F, 0xF9, 0x60, 0x03, 40]);
    // Notch_On 1 turns the filter on (line 1806, ERRATA.md #34).
    assert_eq!(frames[2][..5], [0x2F, 0xF9, 0x60, 0x04, 1]);
    // Outside 0~90 (100-1000 Hz) is refused before sending.
    assert!(drive.notch_frequency().write(Hertz(1010.0)).is_err());
    assert_eq!(sent(&mut drive).len(), 3);
}

#[test]
fn speed_fb_n_default_7_is_a_240_hz_bandwidth() {
    // BW = Speed_Fb_N * 20 + 100 Hz, default 7, range 0~45 (lines 1690, 1705, 2041).
    let mut drive = modbus(&[(0x6350, 7)]);
    assert_eq!(drive.speed_feedback_filter().read().unwrap(), Hertz(240.0));
    drive.speed_feedback_filter().write(Hertz(1000.0)).unwrap();
    assert_eq!(drive.speed_feedback_filter().read_raw().unwrap(), 45);
    assert!(drive.speed_feedback_filter().write(Hertz(1020.0)).is_err());
    assert!(
        drive.speed_feedback_filter().write(Hertz(110.0)).is_err(),
        "no whole N"
    );
}

#[test]
fn target_torque_is_a_percentage_of_rated_torque_without_a_model() {
    // "target_torque/rated_torque*100 (unit:%)" (line 1968, ERRATA.md #10): 32 % is raw 32, with
    // no peak current needed (the current conversion of 6073h needs the model).
    let mut drive = modbus(&[(0x3C00, 0), (0x3D00, 0)]);
    drive.target_torque().write(Percent(32.0)).unwrap();
    assert_eq!(drive.target_torque().read_raw().unwrap(), 32);
    assert!(matches!(
        drive.max_current().write(drivebus::units::AmperesRms(1.0)),
        Err(Error::Value(ValueError::BadScale { .. }))
    ));
}

#[test]
fn k_velocity_ff_1000_is_refused_100_is_full_feedforward() {
    // Range 0 ~ 100, default 100, in % (line 1751; "1000 means 100%" is the erratum, #33).
    let mut drive = modbus(&[(0x6820, 100)]);
    assert_eq!(drive.k_velocity_ff().read().unwrap(), Percent(100.0));
    let refused = drive.k_velocity_ff().write(Percent(1000.0));
    assert!(matches!(refused, Err(Error::Value(_))), "{refused:?}");
    drive.k_velocity_ff().write(Percent(50.0)).unwrap();
    assert_eq!(drive.k_velocity_ff().read_raw().unwrap(), 50);
}

#[test]
fn the_analog_speed_example_deadband_1_v_and_offset_2_v_are_in_0_01_v() {
    // Example of 5.1.1 (lines 1399-1413): deadband 1 V, offset 2 V; unit 0.01 V (lines 1492-1493).
    let mut drive = canopen(&[(0x2502, 0x02, &[0, 0]), (0x2502, 0x03, &[0, 0])]);
    drive.analog1_deadband().write(Volts(1.0)).unwrap();
    drive.analog1_offset().write(Volts(2.0)).unwrap();
    let frames = sent(&mut drive);
    assert_eq!(frames[0][..6], [0x2B, 0x02, 0x25, 0x02, 100, 0]);
    assert_eq!(frames[1][..6], [0x2B, 0x02, 0x25, 0x03, 200, 0]);
}

#[test]
fn the_din_speed_example_starts_from_din_mode1_minus_3() {
    // Din_Mode1 (2020.0E) "default value = -3" (lines 1187, 1459): the simulated drive starts so.
    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/kinco-fd"
    ))
    .unwrap();
    let read = |name: &str| sim.with(|d| d.store().int(d.store().id(name).unwrap()));
    assert_eq!(read("din_mode1"), Some(-3));
    assert_eq!(read("absolute_relative_select"), Some(0x2F), "line 1206");
    assert_eq!(read("max_speed"), Some(5000), "line 1965");
    assert_eq!(read("k_velocity_ff"), Some(100), "line 1751");
    assert_eq!(read("notch_on"), Some(0), "off, line 1816");
}

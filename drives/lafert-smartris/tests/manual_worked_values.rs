//! The Modbus manual's own worked values (001_ad8624675505a5b5.txt, every "i.e." example of §2-4),
//! decoded or encoded through the generated API over an in-memory register map.

use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::units::{AmperesRms, Celsius, Rpm, Volts};
use drivebus::{BusError, Error, ValueError};
use lafert_smartris::types::{
    AnalogOutputConfig, BaudRate, BrakeMode, BrakeType, DigitalInputs, DigitalOutputs, EncoderType,
    FeedbackType, MotorTempSensor, MotorType, StoCheck, StoppingMode,
};
use lafert_smartris::{params, types::DriveStatus, Smartris};

fn drive_with(registers: &[(Table, u16, u16)]) -> Smartris<ModbusLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    for &(table, address, value) in registers {
        bus.set_register(table, address, value);
    }
    Smartris::modbus(bus, UnitId(1))
}

#[test]
fn bus_dc_link_0x1356_is_49_50_volts() {
    // Manual line 485: "0x0064 = 0x1356 (4950) → Bus Dc Link = 49.5 Vdc".
    let mut drive = drive_with(&[(Table::Input, 0x0064, 0x1356)]);
    assert_eq!(drive.bus_dc_link().read(), Ok(Volts(49.5)));
    assert_eq!(drive.bus_dc_link().read_raw(), Ok(4950));
}

#[test]
fn speed_setpoint_0xf448_is_minus_3000_rpm() {
    // Manual §2.2: "0x0042 = 0xF448 (62536 = -3000) → Speed Motor = -3000 rpm".
    let mut drive = drive_with(&[(Table::Input, 0x0042, 0xF448)]);
    assert_eq!(drive.speed_setpoint().read(), Ok(Rpm(-3000.0)));
}

#[test]
fn temperatures_0x0163_are_35_5_celsius() {
    // Manual §2.2: "0x0065 = 0x0163 (355) → Motor temperature = 35.5 °C", same for 0x0066/0x0067.
    let mut drive = drive_with(&[
        (Table::Input, 0x0065, 0x0163),
        (Table::Input, 0x0066, 0x0163),
        (Table::Input, 0x0067, 0x0163),
    ]);
    assert_eq!(drive.motor_temperature().read(), Ok(Celsius(35.5)));
    assert_eq!(drive.heat_sink_temperature().read(), Ok(Celsius(35.5)));
    assert_eq!(drive.board_temperature().read(), Ok(Celsius(35.5)));
}

#[test]
fn torque_setpoint_0xff38_is_minus_2_arms() {
    // Manual §2.2: "0x0047 = 0xFF38 (65336 = -200) → - 2 Arms".
    let mut drive = drive_with(&[(Table::Input, 0x0047, 0xFF38)]);
    assert_eq!(drive.torque_setpoint().read(), Ok(AmperesRms(-2.0)));
}

#[test]
fn velocity_average_0xfc18_is_minus_1000_rpm() {
    let mut drive = drive_with(&[(Table::Input, 0x0068, 0xFC18)]);
    assert_eq!(drive.velocity_average().read(), Ok(Rpm(-1000.0)));
}

#[test]
fn drive_status_word_decodes_into_flags_and_keeps_unknown_bits() {
    // Alarm (0x0010) + stop (0x0004) + an undocumented bit 12.
    let mut drive = drive_with(&[(Table::Input, 0x0060, 0x1014)]);
    let status = drive.drive_status().read().unwrap();
    assert!(status.contains(DriveStatus::ALARM | DriveStatus::STOP));
    assert!(!status.contains(DriveStatus::RUN_VELOCITY));
    assert_eq!(status.bits(), 0x1014, "unknown bits survive the read");
}

#[test]
fn setpoint_write_goes_to_the_holding_register_and_reads_back_from_input() {
    let mut drive = drive_with(&[
        (Table::Holding, 0x0003, 0x1194),
        (Table::Holding, 0x0042, 0),
        (Table::Input, 0x0042, 0),
    ]);
    drive.speed_setpoint().write(Rpm(1500.0)).unwrap();
    let bus = drive.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 0x0042), Some(1500));
    assert_eq!(
        bus.log(),
        [
            // The bound, FULL SCALE VELOCITY (line 1333), is read before every write.
            Request::Read {
                table: Table::Holding,
                start: 0x0003,
                count: 1
            },
            Request::Write {
                start: 0x0042,
                values: vec![1500]
            }
        ]
    );
}

#[test]
fn out_of_range_write_is_refused_before_anything_is_sent() {
    let mut drive = drive_with(&[(Table::Holding, 0x0042, 0)]);
    let too_fast = drive.speed_setpoint().write(Rpm(40_000.0));
    assert!(matches!(
        too_fast,
        Err(Error::Value(ValueError::Overflow {
            parameter: "speed_setpoint"
        }))
    ));
    let between_steps = drive.speed_setpoint().write(Rpm(1500.5));
    assert!(matches!(
        between_steps,
        Err(Error::Value(ValueError::NotRepresentable { .. }))
    ));
    assert!(drive.into_link().into_bus().log().is_empty());
}

#[test]
fn unknown_register_surfaces_the_exception() {
    let mut drive = drive_with(&[]);
    let error = drive.bus_dc_link().read().unwrap_err();
    assert_eq!(
        error.bus(),
        Some(&BusError::ModbusException {
            function: 0x04,
            code: drivebus::modbus::ExceptionCode::IllegalDataAddress
        })
    );
}

#[test]
fn read_many_returns_typed_values_in_order() {
    let mut drive = drive_with(&[
        (Table::Input, 0x0064, 0x1356),
        (Table::Input, 0x0065, 0x0163),
        (Table::Input, 0x0060, 0x0002),
        // Listed by the manual, so the planner reads past them (the drive answers them).
        (Table::Input, 0x0061, 0),
        (Table::Input, 0x0062, 0),
        (Table::Input, 0x0063, 0),
    ]);
    let (volts, temperature, status) = drive
        .read_many((
            params::BusDcLink,
            params::MotorTemperature,
            params::DriveStatus,
        ))
        .unwrap();
    assert_eq!((volts, temperature), (Volts(49.5), Celsius(35.5)));
    assert!(status.contains(DriveStatus::STANDBY));
    let read = Request::Read {
        table: Table::Input,
        start: 0x0060,
        count: 6,
    };
    assert_eq!(drive.into_link().into_bus().log(), [read], "one request");
}

// ---------------------------------------------------------------------------------------------
// The remaining "i.e." examples of the Modbus manual (001_ad8624675505a5b5.txt), one assertion
// each, with the manual line. Frames are in manual_frames.rs, the run sequence examples in
// run_sequence.rs.
// ---------------------------------------------------------------------------------------------

#[test]
fn input_register_examples_of_section_2_2() {
    let mut drive = drive_with(&[
        (Table::Input, 0x0042, 0x0064),
        (Table::Input, 0x0047, 0x00C8),
        (Table::Input, 0x005E, 0x000F),
        (Table::Input, 0x005F, 0x0001),
        (Table::Input, 0x0068, 0x01F4),
        (Table::Input, 0x0069, 0x01F4),
        (Table::Input, 0x006A, 0x0032),
        (Table::Input, 0x006B, 0x4240),
        (Table::Input, 0x006C, 0x000F),
        (Table::Input, 0x006D, 0x1000),
        (Table::Input, 0x006E, 0x03E8),
    ]);
    // Line 309: 0x0042 = 0x64 (100) → 100 rpm.
    assert_eq!(drive.speed_setpoint().read(), Ok(Rpm(100.0)));
    // Line 316: 0x0047 = 0xC8 (200) → 2 Arms.
    assert_eq!(drive.torque_setpoint().read(), Ok(AmperesRms(2.0)));
    // Line 329 table: 0x005E = 0x000F → all four inputs on.
    assert_eq!(
        drive.digital_inputs().read(),
        Ok(DigitalInputs::DIGIN1
            | DigitalInputs::DIGIN2
            | DigitalInputs::DIGIN3
            | DigitalInputs::DIGIN4)
    );
    // Line 359: 0x005F = 0x0001 → Drive OK on, no alarm.
    assert_eq!(drive.digital_outputs().read(), Ok(DigitalOutputs::DRIVE_OK));
    // Line 514: 0x0068 = 0x01F4 (500) → 500 rpm.
    assert_eq!(drive.velocity_average().read(), Ok(Rpm(500.0)));
    // Line 521: 0x0069 = 0x01F4 (500) → 5 Arms (ERRATA.md U1: 1/100 Arms).
    assert_eq!(drive.torque_current().read(), Ok(AmperesRms(5.0)));
    // Line 527: 0x006A = 0x0032 (50) → 50 % of rated current.
    assert_eq!(drive.i2t_energy().read().map(|v| v.0), Ok(50.0));
    // Lines 534-541: axis position 1000000 = 0x000F4240, 0x006B = 0x4240 (low), 0x006C = 0x000F.
    assert_eq!(drive.axis_position().read_raw(), Ok(1_000_000));
    // Line 556: 0x006D = 0x1000 → 4096 of 16384 pulses (90°).
    assert_eq!(drive.impulses().read_raw(), Ok(4096));
    // Line 564: 0x006E = 0x03E8 → 1000 rpm.
    assert_eq!(drive.actual_velocity_user().read(), Ok(Rpm(1000.0)));
}

#[test]
fn feedback_examples_of_section_2_2() {
    let mut drive = drive_with(&[
        (Table::Input, 0x0101, 0x4000),
        (Table::Input, 0x0102, 0x7421),
        (Table::Input, 0x0103, 0x0029),
        (Table::Input, 0x0104, 0x7421),
        (Table::Input, 0x0105, 0x0029),
        (Table::Input, 0x0106, 0x0037),
    ]);
    // Line 585: 0x0101 = 4000h → 16384 per revolution.
    assert_eq!(drive.feedback_resolution().read(), Ok(16384));
    // Lines 591-615: pos = 0x297421, low word 0x7421, high word 0x0029 (ERRATA.md M8).
    assert_eq!(drive.feedback_init_position().read_raw(), Ok(0x0029_7421));
    assert_eq!(drive.feedback_actual_position().read_raw(), Ok(0x0029_7421));
    // Line 621: 0x0106 = 0x37 → SinCos multi-turn.
    assert_eq!(drive.encoder_type().read(), Ok(EncoderType::MULTITURN));
}

#[test]
fn holding_register_examples_of_sections_3_2_and_4_2() {
    let mut drive = drive_with(&[
        (Table::Holding, 0x0028, 1),
        (Table::Holding, 0x0035, 0x00C0),
        (Table::Holding, 0x0036, 1000),
        (Table::Holding, 0x003F, 1),
        (Table::Holding, 0x0040, 0x03E8),
        (Table::Holding, 0x0041, 0x03E8),
        (Table::Holding, 0x0044, 0x0032),
        (Table::Holding, 0x0045, 0x0032),
        (Table::Holding, 0x0046, 0x01F4),
        (Table::Holding, 0x004E, 1),
        (Table::Holding, 0x004F, 1),
        (Table::Holding, 0x0050, 1),
        (Table::Holding, 0x0051, 1),
        (Table::Holding, 0x0053, 1),
        (Table::Holding, 0x0054, 4095),
    ]);
    // Lines 791 / 1246: 0x0028 = 1 → Modbus address 1.
    assert_eq!(drive.modbus_address().read(), Ok(1));
    // Lines 804 / 1269: 0x0035 = 0x00C0 (192) → 19200 baud.
    assert_eq!(drive.baud_rate().read(), Ok(BaudRate::B19200));
    // Line 1277: 0x0036 = 1000 → loss time 1000 ms (ERRATA.md M4: the hex 0x03B8 is wrong).
    assert_eq!(
        drive.communication_loss_time().read().map(|v| v.0),
        Ok(1000.0)
    );
    // Lines 837 / 1308: 0x003F = 1 → ramp enabled.
    assert_eq!(drive.ramp_enable().read(), Ok(1));
    // Lines 845 / 1317 and 1324 (ERRATA.md M5): ramps of 0x03E8 = 1000 ms = 1 s.
    assert_eq!(drive.speed_ramp_up().read().map(|v| v.0), Ok(1000.0));
    assert_eq!(drive.speed_ramp_down().read().map(|v| v.0), Ok(1000.0));
    // Lines 869-878 / 1357-1365: 0x0044 = 0x0045 = 0x0032 (50) → 50 % of rated current.
    assert_eq!(drive.limit_torque_positive().read().map(|v| v.0), Ok(50.0));
    assert_eq!(drive.limit_torque_negative().read().map(|v| v.0), Ok(50.0));
    // Line 1373: 0x0046 = 0x01F4 (500) → rated current reached in 1000 / 500 = 2 s.
    assert_eq!(drive.slope_ramp_torque().read(), Ok(500));
    // Lines 891, 901, 908, 916: brake managed, manual brake mode, magnetic brake, standby CW.
    assert_eq!(drive.brake_managed().read(), Ok(1));
    assert_eq!(drive.brake_mode().read(), Ok(BrakeMode::MANUAL));
    assert_eq!(drive.brake_type().read(), Ok(BrakeType::MAGNETIC));
    assert_eq!(
        drive.move_to_standby_cw().read(),
        Ok(StoppingMode::DYNAMIC_RAMP)
    );
    // Lines 928 / 1424: 0x0053 = 1 → general purpose; lines 934 / 1430: 0x0054 = 4095 → 10 V.
    assert_eq!(
        drive.analog_output_config().read(),
        Ok(AnalogOutputConfig::GENERAL_PURPOSE)
    );
    assert_eq!(drive.analog_output_value().read(), Ok(Volts(10.0)));
}

#[test]
fn identity_examples_of_section_3_2() {
    let mut drive = drive_with(&[
        (Table::Holding, 0x01FF, 226),
        (Table::Holding, 0x0201, 0x000B),
        (Table::Holding, 0x0202, 0x0136),
        (Table::Holding, 0x0203, 1),
        (Table::Holding, 0x0204, 1),
        (Table::Holding, 0x0208, 4),
        (Table::Holding, 0x020A, 4500),
    ]);
    // Line 1023: firmware 226 → 2.2.6, decimal digits (ERRATA.md M6: the hex 0x00E1 is 225).
    assert_eq!(drive.fw_release().read(), Ok(226));
    // Line 1029: 0x000B (11) → hardware 1.1 (ERRATA.md M7); line 1035: 0x0136 (310) → 3.1.0.
    assert_eq!(drive.hw_release().read(), Ok(11));
    assert_eq!(drive.parameter_release().read(), Ok(310));
    // Line 1045: 0x0203 = 1; the list says B40, the example "S" (ERRATA.md M9).
    assert_eq!(drive.motor_type().read(), Ok(MotorType::B40));
    // Line 1051: 0x0204 = 1 → STO present.
    assert_eq!(drive.sto_check().read(), Ok(StoCheck::STO_PRESENT));
    // Line 1076: 4 pole pairs; line 1091: 0x020A = 4500 → cannot run over 4500 rpm.
    assert_eq!(drive.motor_pole_pairs().read(), Ok(4));
    assert_eq!(drive.max_motor_speed().read(), Ok(Rpm(4500.0)));
}

#[test]
fn setpoint_write_examples_of_section_4_2() {
    let mut drive = drive_with(&[
        (Table::Holding, 0x0003, 0x1194),
        (Table::Holding, 0x0042, 0),
        (Table::Holding, 0x0047, 0),
        (Table::Holding, 0x0052, 0),
    ]);
    // Line 1337: 0x0042 = 0x0BB8 → 3000 rpm; line 1382: 0x0047 = 0xFF38 → -2 Arms.
    drive.speed_setpoint().write(Rpm(3000.0)).unwrap();
    drive.torque_setpoint().write(AmperesRms(-2.0)).unwrap();
    // Line 1414: 0x0052 = 1 → update of READ ENCODER STATUS.
    drive
        .set_cmd_req_feedback()
        .write(lafert_smartris::types::SincosCommand::READ_ENCODER_STATUS)
        .unwrap();
    let bus = drive.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 0x0042), Some(0x0BB8));
    assert_eq!(bus.register(Table::Holding, 0x0047), Some(0xFF38));
    assert_eq!(bus.register(Table::Holding, 0x0052), Some(1));
}

#[test]
fn error_codes_carry_the_table_2_class_led_code_and_meaning() {
    use drivebus::ErrorClass;
    use lafert_smartris::types::ErrorCode;
    let mut drive = drive_with(&[(Table::Input, 0x0063, 0x7521)]);
    // Line 458: 0x7521 Modbus communication lost, F, LED 9,1.
    let code = drive.error_code().read().unwrap();
    assert_eq!(code, ErrorCode::MODBUS_COMMUNICATION_LOST);
    assert_eq!(code.class(), Some(ErrorClass::Fault));
    assert_eq!(code.led_code(), Some((9, 1)));
    assert!(code.meaning().unwrap().contains("Communication Loss Timer"));
    // Line 406: 0x4301 warning, no LED code; line 395: no error has neither.
    assert_eq!(
        ErrorCode::WARNING_TEMPERATURE_DRIVE.class(),
        Some(ErrorClass::Warning)
    );
    assert_eq!(ErrorCode::WARNING_TEMPERATURE_DRIVE.led_code(), None);
    assert_eq!(ErrorCode::NO_ERROR.class(), None);
    // Line 447: 0x7374 has no class in the table (ERRATA.md R17).
    assert_eq!(ErrorCode::RESOLVER_INITIALIZATION.class(), None);
    assert_eq!(ErrorCode::RESOLVER_INITIALIZATION.led_code(), Some((2, 4)));
    // A code between the documented range end points stays readable, without attributes.
    let inside_range = drive_with(&[(Table::Input, 0x0063, 0x5540)])
        .error_code()
        .read()
        .unwrap();
    assert!(!inside_range.is_known());
    assert_eq!((inside_range.raw(), inside_range.class()), (0x5540, None));
}

#[test]
fn the_speed_setpoint_lies_within_the_full_scale_velocity() {
    // Line 1333: "range [-Full scale velocity: Full scale velocity]"; line 783: holding 0x0003
    // = 0x1194 (4500) → 4500 rpm.
    let mut drive = drive_with(&[
        (Table::Holding, 0x0003, 0x1194),
        (Table::Holding, 0x0042, 0),
    ]);
    let beyond = |raw, limit| {
        drivebus::Error::OutsideBound(drivebus::OutsideBound {
            parameter: "speed_setpoint",
            bound: "full_scale_velocity",
            raw,
            limit,
        })
    };
    assert_eq!(
        drive.speed_setpoint().write(Rpm(4501.0)),
        Err(beyond(4501, 4500))
    );
    assert_eq!(
        drive.speed_setpoint().write(Rpm(-4501.0)),
        Err(beyond(-4501, 4500))
    );
    assert_eq!(
        drive.device().write_raw::<params::SpeedSetpoint>(4501),
        Err(beyond(4501, 4500)),
        "the device's raw write is bounded too"
    );
    drive.speed_setpoint().write(Rpm(-4500.0)).unwrap();
    // Line 1333's example: 0xF448 is -3000 rpm, so -4500 is 0xEE6C.
    let bus = drive.into_link().into_bus();
    assert_eq!(bus.register(Table::Holding, 0x0042), Some(0xEE6C));
    let writes: Vec<&Request> = bus
        .log()
        .iter()
        .filter(|r| matches!(r, Request::Write { .. }))
        .collect();
    assert_eq!(
        writes.len(),
        1,
        "nothing written beyond the bound: {writes:?}"
    );
}

#[test]
fn the_remaining_value_examples_of_sections_2_2_and_3_2() {
    let mut drive = drive_with(&[
        (Table::Input, 0x005E, 0x0001),
        (Table::Input, 0x006A, 0x0096),
        (Table::Input, 0x010D, 4095),
        (Table::Holding, 0x004E, 0),
        (Table::Holding, 0x004F, 0),
        (Table::Holding, 0x0050, 2),
        (Table::Holding, 0x0051, 0),
        (Table::Holding, 0x0204, 2),
        (Table::Holding, 0x0205, 2),
        (Table::Holding, 0x0209, 4),
    ]);
    // Line 330: 0x005E = 0x0001 → DIG IN 1 only.
    assert_eq!(drive.digital_inputs().read(), Ok(DigitalInputs::DIGIN1));
    // Line 528: 0x006A = 0x0096 (150) → 150 % of rated current.
    assert_eq!(drive.i2t_energy().read().map(|v| v.0), Ok(150.0));
    // Line 641: 0x010D [0 … 4095] → [0 … 10] V.
    assert_eq!(drive.analog_output_dac().read(), Ok(Volts(10.0)));
    // Lines 890-891 (0/1 admitted), 902, 909: brake not managed, automatic, spring brake.
    assert_eq!(drive.brake_managed().read(), Ok(0));
    assert_eq!(drive.brake_mode().read(), Ok(BrakeMode::AUTOMATIC));
    assert_eq!(drive.brake_type().read(), Ok(BrakeType::SPRING));
    // Line 917 (0x0051 = 0 → no dynamic stop), guide line 2738: the motor stops by inertia.
    assert_eq!(drive.move_to_standby_cw().read(), Ok(StoppingMode::COAST));
    // Lines 1052, 1062, 1085: no STO, SinCos encoder, PTC on/off.
    assert_eq!(drive.sto_check().read(), Ok(StoCheck::NO_STO));
    assert_eq!(drive.feedback_type().read(), Ok(FeedbackType::SINCOS));
    assert_eq!(
        drive.motor_temp_sensor().read(),
        Ok(MotorTempSensor::PTC_ON_OFF)
    );
}

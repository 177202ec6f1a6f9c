//! The IR as the run-time interpreter's model: values typed by people become the raw bytes of a
//! described parameter and raw bytes become shown values, through `drivebus::interpret` (the path
//! the CLI and simulator use), with the Lafert description as the model.

use drivebus::interpret::{parse, show, Engineering, InputError, Raw, RawValue};
use drivegen::ir::{DataType, Device, Parameter, Scale};

fn lafert() -> Device {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/lafert-smartris"
    );
    drivegen::check(std::path::Path::new(path)).device.unwrap()
}

fn parsed(name: &str, text: &str) -> Result<Vec<u8>, InputError> {
    let device = lafert();
    let parameter = device.parameter(name).unwrap().clone();
    parse(&device, &parameter, text)
}

#[test]
fn engineering_values_become_raw_bytes() {
    assert_eq!(
        parsed("speed_setpoint", "1500rpm"),
        Ok(1500i16.to_le_bytes().to_vec())
    );
    assert_eq!(
        parsed("speed_setpoint", "-3000 rpm"),
        Ok((-3000i16).to_le_bytes().to_vec())
    );
    assert_eq!(
        parsed("torque_setpoint", "2Arms"),
        Ok(200i16.to_le_bytes().to_vec())
    );
    assert_eq!(
        parsed("speed_setpoint", "raw:1000"),
        Ok(1000i16.to_le_bytes().to_vec())
    );
}

#[test]
fn names_become_raw_values() {
    assert_eq!(
        parsed("operation_mode", "velocity"),
        Ok(2u16.to_le_bytes().to_vec())
    );
    assert_eq!(
        parsed("control_word", "run|stop_disabled"),
        Ok(3u16.to_le_bytes().to_vec())
    );
}

#[test]
fn wrong_units_and_ranges_are_refused() {
    assert!(matches!(
        parsed("speed_setpoint", "1500V"),
        Err(InputError::WrongUnit { .. })
    ));
    assert!(matches!(
        parsed("control_word", "8"),
        Err(InputError::OutOfRange(_))
    ));
    assert!(matches!(
        parsed("speed_setpoint", "40000rpm"),
        Err(InputError::OutOfRange(_))
    ));
    assert!(matches!(
        parsed("operation_mode", "none"),
        Err(InputError::NotAllowed(_))
    ));
    assert!(matches!(
        parsed("torque_setpoint", "2.005Arms"),
        Err(InputError::NotRepresentable(_))
    ));
    assert!(matches!(
        parsed("operation_mode", "fast"),
        Err(InputError::Unparsable(_))
    ));
}

/// A description of one unscaled and one scaled `u64`: values beyond 2^53 must not pass
/// through a float.
fn wide() -> Device {
    let mut device = lafert();
    let template = device.parameter("speed_setpoint").unwrap().clone();
    device.parameters = ["plain", "scaled"]
        .into_iter()
        .map(|name| Parameter {
            name: name.into(),
            data_type: DataType::Unsigned(8),
            range: None,
            allowed: Vec::new(),
            unit: None,
            scale: (name == "scaled").then_some(Scale::Fixed(drivebus::Scale::fixed(1, 10, 0, 1))),
            ..template.clone()
        })
        .collect();
    device
}

#[test]
fn floats_beyond_their_width_are_refused_not_sent_as_infinity() {
    let device = lafert();
    let mut gain = device.parameter("speed_setpoint").unwrap().clone();
    (gain.data_type, gain.range, gain.unit) = (DataType::F32, None, None);
    let huge = format!("1{}", "0".repeat(40));
    assert!(matches!(
        parse(&device, &gain, &huge),
        Err(InputError::OutOfRange(_))
    ));
    assert_eq!(
        parse(&device, &gain, "1.5"),
        Ok(1.5f32.to_le_bytes().to_vec())
    );
}

#[test]
fn wide_enum_values_are_named_exactly() {
    let mut device = lafert();
    let e = device
        .enums
        .iter_mut()
        .find(|e| e.name == "operation_mode")
        .unwrap();
    e.data_type = DataType::Signed(8);
    e.values.truncate(2);
    (e.values[0].name, e.values[0].value) = ("near".into(), i64::MAX - 1);
    (e.values[1].name, e.values[1].value) = ("top".into(), i64::MAX);
    let mut mode = device.parameter("operation_mode").unwrap().clone();
    mode.data_type = DataType::Signed(8);
    mode.allowed.clear();
    // As floats both values are 2^63: only an exact comparison tells them apart.
    let shown = show(&device, &mode, &i64::MAX.to_le_bytes());
    assert_eq!(shown.text, "top");
    assert_eq!(
        parse(&device, &mode, "top"),
        Ok(i64::MAX.to_le_bytes().to_vec())
    );
}

#[test]
fn wide_integers_stay_exact() {
    let device = wide();
    let plain = device.parameter("plain").unwrap();
    for text in [
        "raw:18446744073709551610",
        "18446744073709551610",
        "0xFFFFFFFFFFFFFFFA",
    ] {
        let bytes = parse(&device, plain, text).unwrap();
        assert_eq!(bytes, (u64::MAX - 5).to_le_bytes(), "{text}");
        let shown = show(&device, plain, &bytes);
        assert_eq!(shown.text, "18446744073709551610");
        assert_eq!(shown.raw, Raw::Number(RawValue::Int((u64::MAX - 5).into())));
        assert_eq!(shown.value, Engineering::Int((u64::MAX - 5).into()));
    }
    assert!(matches!(
        parse(&device, plain, "raw:18446744073709551616"),
        Err(InputError::OutOfRange(_))
    ));
    assert!(matches!(
        parse(&device, plain, "raw:-1"),
        Err(InputError::OutOfRange(_))
    ));
    let scaled = device.parameter("scaled").unwrap();
    assert_eq!(
        parse(&device, scaled, "raw:18446744073709551610").unwrap(),
        (u64::MAX - 5).to_le_bytes()
    );
    // Scaled input beyond 2^53 raw steps cannot be converted exactly: refused, not rounded.
    assert!(matches!(
        parse(&device, scaled, "1844674407370955161"),
        Err(InputError::NotRepresentable(_))
    ));
    assert_eq!(parse(&device, scaled, "1.5").unwrap(), 15u64.to_le_bytes());
}

#[test]
fn decimal_steps_show_as_written() {
    let device = lafert();
    let torque = device.parameter("torque_setpoint").unwrap();
    // 1/100 Arms: raw 35 is 0.35 Arms (35 × 0.01 would be 0.35000000000000003).
    let shown = show(&device, torque, &35i16.to_le_bytes());
    assert_eq!(shown.value, Engineering::Float(0.35));
    assert_eq!(shown.text, "0.35 Arms");
}

#[test]
fn raw_bytes_show_with_units_and_names() {
    let device = lafert();
    let dc = device.parameter("bus_dc_link").unwrap();
    assert_eq!(show(&device, dc, &4950u16.to_le_bytes()).text, "49.50 V");
    let status = device.parameter("drive_status").unwrap();
    assert_eq!(
        show(&device, status, &0x11u16.to_le_bytes()).text,
        "run_velocity|alarm"
    );
    let mode = device.parameter("operation_mode").unwrap();
    assert_eq!(show(&device, mode, &2u16.to_le_bytes()).text, "velocity");
    assert_eq!(show(&device, mode, &9u16.to_le_bytes()).text, "unknown (9)");
}

/// The manual's own register values (modbus.txt line 1333: 0xF448 is −3000 rpm; line 484:
/// 0x1356 is 49.5 V), read and written by name over the Modbus link generated code uses.
#[test]
fn parameters_are_read_and_written_by_name_over_a_link() {
    use drivebus::interpret::{read, write, InterpretError, Variant};
    use drivebus::modbus::{ModbusLimits, ModbusLink, Table, UnitId};
    use drivebus::testing::MemoryBus;

    let device = lafert();
    let mut bus = MemoryBus::new();
    // Line 783: full scale velocity 0x0003 = 0x1194 (4500) bounds the setpoint (line 1333).
    bus.set_register(Table::Input, 0x0064, 0x1356)
        .set_register(Table::Input, 0x0042, 0xF448)
        .set_register(Table::Holding, 0x0042, 0)
        .set_register(Table::Holding, 0x0003, 0x1194);
    let mut link = ModbusLink::new(&mut bus, UnitId(1), ModbusLimits::SPEC);
    assert_eq!(
        read(&device, &mut link, &Variant::Single, "bus_dc_link")
            .unwrap()
            .text,
        "49.50 V"
    );
    assert_eq!(
        read(&device, &mut link, &Variant::Single, "speed_setpoint")
            .unwrap()
            .text,
        "-3000 rpm"
    );
    write(
        &device,
        &mut link,
        &Variant::Single,
        "speed_setpoint",
        "-3000rpm",
    )
    .unwrap();
    assert_eq!(bus.register(Table::Holding, 0x0042), Some(0xF448));

    let mut link = ModbusLink::new(&mut bus, UnitId(1), ModbusLimits::SPEC);
    assert!(matches!(
        write(
            &device,
            &mut link,
            &Variant::Single,
            "speed_setpoint",
            "40000rpm"
        ),
        Err(InterpretError::Input {
            cause: InputError::OutOfRange(_),
            ..
        })
    ));
    assert_eq!(
        write(
            &device,
            &mut link,
            &Variant::Single,
            "speed_setpoint",
            "-4501rpm"
        ),
        Err(InterpretError::OutsideBound(drivebus::OutsideBound {
            parameter: "speed_setpoint".into(),
            bound: "full_scale_velocity".into(),
            raw: -4501,
            limit: 4500
        }))
    );
    assert!(matches!(
        write(&device, &mut link, &Variant::Single, "bus_dc_link", "48V"),
        Err(InterpretError::NoAccess { .. })
    ));
    assert_eq!(
        read(&device, &mut link, &Variant::Single, "no_such_thing"),
        Err(InterpretError::UnknownParameter("no_such_thing".into()))
    );
    // Nothing refused was sent.
    assert_eq!(bus.register(Table::Holding, 0x0042), Some(0xF448));
}

/// The Lenze smd moves c25 (`serial_baud_rate`) from #95 in PC400 to #103 in PC507, where #95
/// is part of C99 (smd manual lines 348, 926, 944): the interpreter reads and writes the
/// configuration's own register, and with the configuration unknown it guesses neither.
#[test]
fn the_variant_decides_the_register_and_an_unknown_one_reaches_none() {
    use drivebus::interpret::{read, write, InterpretError, Variant};
    use drivebus::modbus::{ModbusLimits, ModbusLink, Table, UnitId};
    use drivebus::testing::MemoryBus;

    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/lenze-smd");
    let device = drivegen::check(std::path::Path::new(path)).device.unwrap();
    let mut bus = MemoryBus::new();
    bus.set_register(Table::Holding, 95, 2)
        .set_register(Table::Holding, 103, 3)
        .set_register(Table::Holding, 19, 69)
        .set_register(Table::Holding, 1, 0);
    let mut link = ModbusLink::new(&mut bus, UnitId(1), ModbusLimits::SPEC);
    let pc507 = Variant::Selected("pc507".into());
    let pc400 = Variant::Selected("pc400".into());
    let c25 = device.parameter("serial_baud_rate").unwrap();
    let shown = |raw: u16| drivebus::interpret::show(&device, c25, &raw.to_le_bytes()).text;
    let read_c25 = |link: &mut ModbusLink<&mut MemoryBus>, variant| {
        read(&device, link, variant, "serial_baud_rate")
            .unwrap()
            .text
    };
    assert_eq!(read_c25(&mut link, &pc507), shown(3));
    assert_eq!(read_c25(&mut link, &pc400), shown(2));
    write(&device, &mut link, &pc507, "serial_baud_rate", "raw:1").unwrap();
    assert_eq!(bus.register(Table::Holding, 103), Some(1));
    assert_eq!(
        bus.register(Table::Holding, 95),
        Some(2),
        "#95 untouched under PC507"
    );

    let unknown = Variant::Unknown {
        selector: "parameter_configuration".into(),
        found: Some(401),
    };
    let mut link = ModbusLink::new(&mut bus, UnitId(1), ModbusLimits::SPEC);
    let refused = read(&device, &mut link, &unknown, "serial_baud_rate").unwrap_err();
    assert!(
        matches!(
            &refused,
            InterpretError::VariantUnknown {
                found: Some(401),
                ..
            }
        ),
        "{refused:?}"
    );
    assert!(
        refused
            .to_string()
            .contains("parameter_configuration = 401"),
        "{refused}"
    );
    // A register every configuration has is still read; no write but a stop goes out.
    assert!(read(&device, &mut link, &unknown, "drive_family").is_ok());
    assert!(matches!(
        write(
            &device,
            &mut link,
            &unknown,
            "serial_speed_command",
            "raw:100"
        ),
        Err(InterpretError::VariantUnknown { .. })
    ));
    write(&device, &mut link, &unknown, "stop", "raw:4").unwrap();
    let writes: Vec<_> = bus
        .log()
        .iter()
        .filter(|r| matches!(r, drivebus::testing::Request::Write { .. }))
        .collect();
    let expected = [
        drivebus::testing::Request::Write {
            start: 103,
            values: vec![1],
        },
        drivebus::testing::Request::Write {
            start: 1,
            values: vec![4],
        },
    ];
    assert_eq!(
        writes,
        expected.iter().collect::<Vec<_>>(),
        "c25 under PC507, then the stop"
    );
}

//! Quickstart: the Lafert Smartris run sequence (RTU Modbus manual §4.2.1) through the generated,
//! typed `lafert-smartris` crate.
//!
//! ```sh
//! cargo run --example quickstart                           # a simulated drive on 127.0.0.1
//! cargo run --example quickstart -- --serial /dev/ttyUSB0  # a real drive (19200 baud, 8N2, unit 1)
//! ```

use std::error::Error;
use std::thread::sleep;
use std::time::Duration;

use drivebus::prelude::*;
use lafert_smartris::types::{ControlWord, OperationMode};
use lafert_smartris::{params, Smartris};

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [] => {
            let sim = simulated_drive()?;
            let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1))?;
            println!("simulated Lafert Smartris on {}", server.local_addr());
            let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default())?;
            run(Smartris::modbus(bus, UnitId(1)))
        }
        [flag, path] if flag == "--serial" => {
            // Factory line settings: 19200 baud, no parity, 2 stop bits (manual §1.1).
            let line = SerialConfig {
                parity: Parity::None,
                stop_bits: StopBits::Two,
                ..SerialConfig::new(19_200)
            };
            run(Smartris::modbus(
                SerialRtuClient::open(path, &line)?,
                UnitId(1),
            ))
        }
        _ => Err("usage: quickstart [--serial /dev/ttyUSB0]".into()),
    }
}

/// The run sequence: check the mode, enable, 1500 rpm, watch the ramp, stop, standby.
fn run<B: RegisterBus>(mut drive: Smartris<ModbusLink<B>>) -> Result<(), Box<dyn Error>> {
    let mode = drive.operation_mode().read()?;
    println!("operation mode     {mode:?}");
    if mode != OperationMode::VELOCITY {
        return Err("the drive is not in velocity mode (holding 0x0207 = 2, store, reset)".into());
    }
    println!("status             {:?}", drive.drive_status().read()?);

    drive
        .control_word()
        .write(ControlWord::RUN | ControlWord::STOP_DISABLED)?; // T2: run
    drive.speed_setpoint().write(Rpm(1500.0))?;
    println!("speed setpoint     {}", drive.speed_setpoint().read()?);

    println!("  speed        DC link   motor     heat sink  status");
    for _ in 0..6 {
        sleep(Duration::from_millis(400));
        let (status, dc_link, motor, heat_sink, speed) = drive.read_many((
            params::DriveStatus,
            params::BusDcLink,
            params::MotorTemperature,
            params::HeatSinkTemperature,
            params::VelocityAverage,
        ))?;
        let columns = [
            format!("{speed:.0}"),
            format!("{dc_link:.2}"),
            format!("{motor:.1}"),
            format!("{heat_sink:.1}"),
        ];
        println!(
            "  {:<12} {:<9} {:<9} {:<10} {status:?}",
            columns[0], columns[1], columns[2], columns[3]
        );
    }

    drive.control_word().write(ControlWord::RUN)?; // T4: stop with maximum torque
    println!(
        "stop               {:?}, {}",
        drive.drive_status().read()?,
        drive.velocity_average().read()?
    );
    drive.control_word().write(ControlWord::STOP_DISABLED)?; // T6: standby
    println!("standby            {:?}", drive.drive_status().read()?);
    Ok(())
}

/// A simulated Smartris with the measured values of the manual's worked examples (§2.2) and the
/// factory configuration for velocity mode.
fn simulated_drive() -> Result<drivesim::Simulator, drivesim::SimError> {
    let description = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/lafert-smartris"
    );
    let sim = drivesim::Simulator::load(description)?;
    sim.preset("operation_mode", 2)? // velocity mode
        .preset("full_scale_velocity", 3000)? // an L motor
        .preset("bus_dc_link", 4950)? // 49.50 V
        .preset("motor_temperature", 355)? // 35.5 °C
        .preset("heat_sink_temperature", 355)?; // 35.5 °C
    Ok(sim)
}

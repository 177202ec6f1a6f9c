//! The Lenze smd's normal control sequence (manual section 4.9) through the generated, typed
//! `lenze-smd` crate: detect the parameter configuration (#50), unlock controls (the guard the
//! description's `[[unlock]]` generates), take the speed from the serial link, start at 41.2 Hz,
//! watch the 6-word status block, stop, lock. Outside the guard the commands and #40 have no
//! setter; the simulator answers such writes with exception 01 as the drive does.
//!
//! ```sh
//! cargo run --example lenze_smd                           # a simulated PC507 drive on 127.0.0.1
//! cargo run --example lenze_smd -- --serial /dev/ttyUSB0  # a real drive (9600 baud, 8N2, unit 10)
//! ```
//! A real drive needs C01 = 10 or 11 and terminal 28 closed (section 4.9 steps 2-3).

use std::error::Error;
use std::thread::sleep;
use std::time::Duration;

use drivebus::modbus::client::{ModbusTcpClient, SerialConfig, SerialRtuClient, TcpConfig};
use drivebus::modbus::rtu::{Parity, StopBits};
use drivebus::modbus::{ModbusLink, RegisterBus, UnitId};
use drivebus::units::Hertz;
use lenze_smd::{Command, LenzeSmd, SmdError};

/// The unit: the manual advises against address 1 (section 4.2, line 344).
const UNIT: UnitId = UnitId(10);

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [] => {
            let sim = simulated_drive()?;
            let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT)?;
            println!("simulated Lenze smd on {}", server.local_addr());
            run(ModbusTcpClient::connect(
                server.local_addr(),
                &TcpConfig::default(),
            )?)
        }
        [flag, path] if flag == "--serial" => {
            // 9600 baud, no parity, two stop bits: the default (section 2.3 A, line 210).
            let line = SerialConfig {
                parity: Parity::None,
                stop_bits: StopBits::Two,
                ..SerialConfig::new(9_600)
            };
            run(SerialRtuClient::open(path, &line)?)
        }
        _ => Err("usage: lenze_smd [--serial /dev/ttyUSB0]".into()),
    }
}

/// Section 4.9: unlock, serial speed reference, speed, start, watch, stop, lock.
fn run<B: RegisterBus>(bus: B) -> Result<(), Box<dyn Error>> {
    let (mut drive, selection) = LenzeSmd::<ModbusLink<B>>::open(bus, UNIT)?;
    println!("configuration      {selection:?}");
    println!("drive family       {:?}", drive.drive_family().read()?);
    println!("control source     {:?}", drive.control_source().read()?);

    let mut unlocked = drive.unlock_controls()?; // reads C01 (10 or 11), then #48 = 0
    unlocked.command(Command::SerialSpeedReference)?; // #1 = 0x0100
    unlocked
        .serial_speed_command()
        .write(Hertz(41.2)) // #40 = 412, within C10 ... C11
        .map_err(SmdError::from)?;
    if let Err(refused) = unlocked.serial_speed_command().write(Hertz(75.0)) {
        println!("refused            {}", SmdError::from(refused));
    }
    unlocked.command(Command::Start)?; // #1 = 0x0008
    println!("  command   actual   load  status   fault");
    let show = |drive: &mut LenzeSmd<ModbusLink<B>>| -> Result<(), Box<dyn Error>> {
        // #24-#29 in one request: the frequency ramps up with C12 (5.0 s from 0 to C11 = 50 Hz).
        let status = drive.status()?;
        let fault = status.fault_and_commanded_direction.present_fault();
        println!(
            "  {:<9} {:<8} {:<5} {:<8} {}",
            format!("{:.1} Hz", status.command_speed.0),
            format!("{:.1} Hz", status.actual_speed.0),
            format!("{} %", status.load_and_status.load()),
            format!("{:?}", status.load_and_status.operational_status()),
            fault.meaning().unwrap_or("unknown code"),
        );
        Ok(())
    };
    for _ in 0..10 {
        sleep(Duration::from_millis(500));
        show(unlocked.drive())?;
    }
    unlocked.command(Command::Stop)?; // #1 = 0x0004: coast to stop, the output ends at once
    show(unlocked.drive())?;
    unlocked.lock()?; // #1 = 0x0002
    println!(
        "locked             serial speed {}",
        drive.serial_speed_command().read()?
    );
    // Past the lock only the raw device could still write #1; the handle, which sent the lock,
    // refuses it before sending (the drive would answer exception 0x01).
    let refused = drive
        .device()
        .write_raw::<lenze_smd::params::Start>(lenze_smd::params::Start::TRIGGER)
        .map_err(SmdError::from);
    println!(
        "start after lock   {}",
        refused.err().map_or("accepted".into(), |e| e.to_string())
    );
    Ok(())
}

/// A simulated PC507 drive under Modbus control (C01 = 11, section 7.1 step 1).
fn simulated_drive() -> Result<drivesim::Simulator, drivesim::SimError> {
    let description = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/lenze-smd");
    let sim = drivesim::Simulator::load(description)?;
    sim.preset("parameter_configuration", 507)?
        .preset("control_source", 11)?;
    Ok(sim)
}

//! The Lafert Smartris on Modbus TCP: run (control word T2), 1500 rpm; stopped with the control
//! word's stop (T4) and standby (T6).

use drivebus::modbus::async_client::{AsyncClientConfig, AsyncTcpClient};
use drivebus::modbus::UnitId;
use drivebus::units::Rpm;
use drivesim::Simulator;
use lafert_smartris::types::ControlWord;
use lafert_smartris::{params, Smartris};
use tokio::sync::watch;

use super::{description, pause, publish, stop_asked, Live, Outcome};

const COLUMN: usize = 0;

/// Starts the simulated drive, runs it until the stop is asked, then stops it.
pub async fn run(live: Live, mut stopping: watch::Receiver<bool>) -> Outcome {
    let sim = Simulator::load(description("lafert-smartris"))?;
    sim.preset("operation_mode", 2)? // velocity mode
        .preset("full_scale_velocity", 3000)?; // an L motor
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1))?;
    let client = AsyncTcpClient::connect(server.local_addr(), AsyncClientConfig::default()).await?;
    let mut drive = Smartris::modbus_async(client, UnitId(1));
    drive
        .control_word()
        .write(ControlWord::RUN | ControlWord::STOP_DISABLED)
        .await?;
    drive.speed_setpoint().write(Rpm(1500.0)).await?;
    while !stop_asked(&stopping) {
        let (speed, setpoint) = drive
            .read_many_async((params::VelocityAverage, params::SpeedSetpoint))
            .await?;
        publish(&live, COLUMN, format!("{speed:.0} (set {setpoint:.0})"));
        pause(&mut stopping).await;
    }
    drive.speed_setpoint().write(Rpm(0.0)).await?;
    drive.control_word().write(ControlWord::RUN).await?; // T4: stop
    drive
        .control_word()
        .write(ControlWord::STOP_DISABLED)
        .await?; // T6: standby
    let status = drive.drive_status().read().await?;
    Ok(format!(
        "setpoint {}, {status:?}",
        drive.speed_setpoint().read().await?
    ))
}

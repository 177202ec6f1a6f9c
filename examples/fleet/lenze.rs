//! The Lenze smd on Modbus RTU over TCP: controls unlocked (#48 = 0), serial speed reference,
//! 20 Hz, start; stopped with Stop (coast) and the lock.

use std::time::Duration;

use drivebus::modbus::async_client::{AsyncClientConfig, AsyncRtuClient};
use drivebus::modbus::UnitId;
use drivebus::units::Hertz;
use drivesim::Simulator;
use lenze_smd::{params, LenzeSmd, Variant};
use tokio::sync::watch;

use super::{description, pause, publish, stop_asked, Live, Outcome};

const COLUMN: usize = 1;
const UNIT: UnitId = UnitId(1);

/// Starts the simulated drive, runs it until the stop is asked, then stops it.
pub async fn run(live: Live, mut stopping: watch::Receiver<bool>) -> Outcome {
    let sim = Simulator::load(description("lenze-smd"))?;
    sim.preset("parameter_configuration", 507)? // smd software 2.0x
        .preset("control_source", 11)?; // C01: Modbus control
    let address = drivesim::modbus::rtu_over_tcp::serve(&sim, "127.0.0.1:0", UNIT)?;
    let config = AsyncClientConfig {
        timeout: Duration::from_secs(1),
        ..AsyncClientConfig::default()
    };
    let client = AsyncRtuClient::connect(address, config).await?;
    let mut drive = LenzeSmd::modbus_async(client, UNIT);
    let configuration = drive.parameter_configuration().read_raw().await?;
    drive.set_variant(Variant::selected_by(configuration).ok_or("unknown smd configuration")?);
    drive.unlock_commands().write_raw(0).await?; // #48 = 0: the controls
    let device = drive.device();
    device
        .write_raw::<params::SerialSpeedReference>(params::SerialSpeedReference::TRIGGER)
        .await?;
    device
        .write::<params::SerialSpeedCommand>(Hertz(20.0))
        .await?;
    device
        .write_raw::<params::Start>(params::Start::TRIGGER)
        .await?;
    while !stop_asked(&stopping) {
        let (frequency, setpoint) = drive
            .read_many_async((params::ActualSpeed, params::SerialSpeedCommand))
            .await?;
        publish(&live, COLUMN, format!("{frequency:.1} (set {setpoint:.1})"));
        pause(&mut stopping).await;
    }
    let device = drive.device();
    // A stop is never refused client-side: no unlock needed, whatever the handle believes.
    device
        .write_raw::<params::Stop>(params::Stop::TRIGGER)
        .await?;
    device
        .write::<params::SerialSpeedCommand>(Hertz(0.0))
        .await?;
    device
        .write_raw::<params::LockSecurity>(params::LockSecurity::TRIGGER)
        .await?;
    let frequency = drive.actual_speed().read().await?;
    Ok(format!("actual {frequency:.1}, locked"))
}

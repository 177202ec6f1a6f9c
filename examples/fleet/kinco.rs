//! The Kinco FD on its RS-232 protocol, an in-memory serial line to the simulated drive's
//! RS-232 server: speed mode, 150 rpm, CiA 402 to operation enabled; stopped with the setpoint 0
//! and the state machine back to switched on.

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::rs232::async_client::AsyncRs232Client;
use drivebus::rs232::{LoopMode, StationId};
use drivebus::units::Rpm;
use drivesim::rs232::Rs232Server;
use drivesim::Simulator;
use kinco_fd::types::ModesOfOperation;
use kinco_fd::{params, KincoFd};
use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream};
use tokio::sync::watch;

use super::{description, pause, publish, stop_asked, Live, Outcome};

const COLUMN: usize = 3;
const STATION: StationId = StationId(1);
/// One telegram: station, 8 data bytes, checksum.
const TELEGRAM_LEN: usize = 10;
/// Controlword: shutdown, switch on, enable operation (CiA 402 transitions 2, 3, 4).
const SHUTDOWN: u16 = 0x06;
const SWITCH_ON: u16 = 0x07;
const ENABLE_OPERATION: u16 = 0x0F;

/// The drive's RS-232 server on the far end of an in-memory line, in a task that ends when the
/// host hangs up; returns the near end.
fn serve(sim: &Simulator) -> DuplexStream {
    let (near, mut far) = tokio::io::duplex(256);
    let mut server = Rs232Server::new(sim, STATION, LoopMode::PointToPoint);
    tokio::spawn(async move {
        let mut telegram = [0u8; TELEGRAM_LEN];
        while far.read_exact(&mut telegram).await.is_ok() {
            if far.write_all(&server.handle(&telegram)).await.is_err() {
                return;
            }
        }
    });
    near
}

/// Starts the simulated drive, runs it until the stop is asked, then stops it.
pub async fn run(live: Live, mut stopping: watch::Receiver<bool>) -> Outcome {
    let sim = Simulator::load(description("kinco-fd"))?;
    // The simulated motor's encoder: the manual's examples assume 10000 increments.
    sim.preset("encoder_resolution", 10_000)?;
    let line = TokioIo::new(serve(&sim));
    let host = AsyncRs232Client::new(line, TokioTimer, LoopMode::PointToPoint)
        .with_timeout(Duration::from_millis(500));
    let mut drive = KincoFd::rs232_async(host, STATION);
    drive
        .modes_of_operation()
        .write(ModesOfOperation::VELOCITY)
        .await?;
    drive.target_velocity().write(Rpm(150.0)).await?;
    for step in [SHUTDOWN, SWITCH_ON, ENABLE_OPERATION] {
        drive.controlword().write_raw(step).await?;
    }
    while !stop_asked(&stopping) {
        let (speed, setpoint) = drive
            .read_many_async((params::VelocityActualValue, params::TargetVelocity))
            .await?;
        publish(&live, COLUMN, format!("{speed:.0} (set {setpoint:.0})"));
        pause(&mut stopping).await;
    }
    drive.target_velocity().write(Rpm(0.0)).await?;
    drive.controlword().write_raw(SWITCH_ON).await?; // disable operation
    let speed = drive.target_velocity().read().await?;
    Ok(format!("setpoint {speed:.0}, operation disabled"))
}

//! The ez-Wheel SWD on CANopen, SLCAN over a TCP connection to the simulated node: velocity
//! mode, CiA 402 to operation enabled with the vl ramp open, 298 rpm at the motor; stopped with
//! the setpoint 0 and the state machine back to switched on.

use std::net::TcpListener;
use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::async_client::AsyncSdo;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::slcan::SlcanBus;
use drivebus::canopen::NodeId;
use drivebus::units::Rpm;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use ezwheel_swd::types::OperatingMode;
use ezwheel_swd::{params, Swd, VL_OPERATION_ENABLED};
use tokio::sync::watch;

use super::{description, pause, publish, stop_asked, Live, Outcome};

const COLUMN: usize = 2;
/// Factory node id (manual section 9.3).
const NODE: NodeId = NodeId(0x10);
/// Controlword: shutdown, switch on (CiA 402 transitions 2 and 3).
const SHUTDOWN: u16 = 0x06;
const SWITCH_ON: u16 = 0x07;

/// The simulated node on SLCAN over a loopback port, in a thread that ends when the client
/// hangs up.
fn serve(sim: Simulator) -> std::io::Result<std::net::SocketAddr> {
    let listener = TcpListener::bind("127.0.0.1:0")?;
    let address = listener.local_addr()?;
    std::thread::spawn(move || -> Result<(), drivebus::BusError> {
        let (stream, _) = listener
            .accept()
            .map_err(|e| drivebus::BusError::Io(e.kind()))?;
        let mut bus = SlcanBus::tcp(stream)?;
        let config = NodeConfig {
            node: NODE,
            heartbeat: None,
        };
        Node::new(sim.clone(), config, sim.variant()).run(&mut bus)
    });
    Ok(address)
}

/// Starts the simulated drive, runs it until the stop is asked, then stops it.
pub async fn run(live: Live, mut stopping: watch::Receiver<bool>) -> Outcome {
    let address = serve(Simulator::load(description("ezwheel-swd"))?)?;
    let bus = AsyncSlcanBus::connect(address).await?;
    let sdo = AsyncSdo::new(bus, TokioTimer).with_timeout(Duration::from_millis(500));
    let mut drive = Swd::canopen_async(sdo, NODE);
    drive
        .modes_of_operation()
        .write(OperatingMode::VELOCITY)
        .await?;
    for step in [SHUTDOWN, SWITCH_ON, VL_OPERATION_ENABLED] {
        drive.controlword().write_raw(step).await?;
    }
    drive.vl_target_velocity().write(Rpm(298.0)).await?;
    while !stop_asked(&stopping) {
        let (speed, setpoint) = drive
            .read_many_async((params::VlVelocityActualValue, params::VlTargetVelocity))
            .await?;
        publish(&live, COLUMN, format!("{speed:.0} (set {setpoint:.0})"));
        pause(&mut stopping).await;
    }
    drive.vl_target_velocity().write(Rpm(0.0)).await?;
    drive.controlword().write_raw(SWITCH_ON).await?; // disable operation
    let speed = drive.vl_target_velocity().read().await?;
    Ok(format!("setpoint {speed:.0}, operation disabled"))
}

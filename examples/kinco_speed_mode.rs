//! The Kinco FD speed-mode sequence of the manual (sections 9.4 / 10.5 / 11.5: mode 3, target
//! speed 150 rpm, controlword 0x0F) through the generated `kinco-fd` crate, against the simulated
//! drive built from the same description — over Modbus TCP, over CANopen (an in-process CAN bus)
//! and over the Kinco RS-232 protocol (the sans-I/O telegram exchange of `drivebus::rs232`
//! against the simulator's RS-232 server, in process; `drivegen sim --kinco-rs232 PTY` serves a
//! real serial line).
//!
//! ```sh
//! cargo run --example kinco_speed_mode
//! ```

use std::error::Error;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::NodeId;
use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::UnitId;
use drivebus::rs232::{LoopMode, StationId};
use drivebus::units::Rpm;
use drivebus::{Link, Readable, Writable};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::rs232::{InProcessLine, Rs232Server};
use kinco_fd::params::{
    Controlword, ModesOfOperation, Statusword, TargetVelocity, VelocityActualValue,
};
use kinco_fd::{types, KincoFd};

const DESCRIPTION: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");

fn main() -> Result<(), Box<dyn Error>> {
    let sim = drivesim::Simulator::load(DESCRIPTION)?;
    // The simulated motor's encoder: the manual's examples assume 10000 increments.
    sim.preset("encoder_resolution", 10_000)?;

    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1))?;
    println!("Modbus TCP, simulated Kinco FD on {}", server.local_addr());
    let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default())?;
    // Modbus cannot read the encoder resolution (6410h.03 has no register): give it.
    speed_mode(KincoFd::modbus(bus, UnitId(1)).give_encoder_resolution(10_000))?;

    println!("CANopen, simulated Kinco FD as node 1 on an in-process bus");
    let can = InProcessBus::new();
    let mut endpoint = can.endpoint();
    let stop = Arc::new(AtomicBool::new(false));
    let running = Arc::clone(&stop);
    let node_sim = drivesim::Simulator::load(DESCRIPTION)?;
    node_sim.preset("encoder_resolution", 10_000)?;
    let node = std::thread::spawn(move || {
        let config = NodeConfig {
            node: NodeId(1),
            heartbeat: None,
        };
        let mut node = Node::new(node_sim.clone(), config, node_sim.variant());
        node.run_while(&mut endpoint, || !running.load(Ordering::Relaxed))
    });
    let sdo = BlockingSdo::new(can.endpoint()).with_timeout(Duration::from_millis(500));
    // Over CANopen the encoder resolution is read from the drive.
    let result = speed_mode(KincoFd::canopen(sdo, NodeId(1)));
    stop.store(true, Ordering::Relaxed);
    node.join()
        .map_err(|_| "the CANopen node thread panicked")??;
    result?;

    println!("Kinco RS-232, simulated Kinco FD as station 1, telegrams exchanged in process");
    let rs232_sim = drivesim::Simulator::load(DESCRIPTION)?;
    rs232_sim.preset("encoder_resolution", 10_000)?;
    let server = Rs232Server::new(&rs232_sim, StationId(1), LoopMode::PointToPoint);
    // Over RS-232 the encoder resolution (6410h.03) is read from the drive, as over CANopen.
    speed_mode(KincoFd::rs232(InProcessLine::new(server), StationId(1)))
}

/// Mode 3, 150 rpm, power on; then the drive's own view of it.
fn speed_mode<L: Link>(mut drive: KincoFd<L>) -> Result<(), Box<dyn Error>>
where
    ModesOfOperation: Writable<L::Protocol> + Readable<L::Protocol>,
    TargetVelocity: Writable<L::Protocol> + Readable<L::Protocol>,
    Controlword: Writable<L::Protocol> + Readable<L::Protocol>,
    Statusword: Readable<L::Protocol>,
    VelocityActualValue: Readable<L::Protocol>,
{
    drive
        .modes_of_operation()
        .write(types::ModesOfOperation::VELOCITY)?;
    drive.target_velocity().write(Rpm(150.0))?;
    drive.controlword().write_raw(0x0F)?; // "0x0F: Power on motor" (line 1935)
    println!("  after 0x0F     {:?}", drive.statusword().read()?);
    // A drive that follows CiA 402 strictly (the simulator does) needs 0x06 and 0x07 first.
    drive.enable_operation(Instant::now() + Duration::from_secs(2))?;
    std::thread::sleep(Duration::from_millis(300));
    println!("  mode           {:?}", drive.modes_of_operation().read()?);
    println!(
        "  target speed   {} ({} DEC)",
        drive.target_velocity().read()?,
        drive.target_velocity().read_raw()?
    );
    println!("  statusword     {:?}", drive.statusword().read()?);
    println!("  actual speed   {}", drive.velocity_actual_value().read()?);
    Ok(())
}

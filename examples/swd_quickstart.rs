//! The ez-Wheel SWD quick start (user manual v2.0.3, appendix "SWD - Quick start", method A)
//! through the generated `ezwheel-swd` crate, against the simulated SWD on an in-process CAN bus:
//! the safety frames of step 4, NMT start (step 6a, heartbeat 710h = 05h), velocity mode and the
//! CiA 402 state machine (step 7a), a motor speed and the resulting wheel speed (step 8a).
//!
//! ```sh
//! cargo run --example swd_quickstart
//! ```
//!
//! Against a real SWD, open a `drivebus::canopen::can::socketcan::SocketCanBus` (feature
//! `socketcan`) instead of the in-process bus; the rest is the same.

use std::error::Error;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::nmt::{decode_heartbeat, NmtCommand, NmtState};
use drivebus::canopen::{CanBus, CanOpenLink, NodeId, SdoBus};
use drivebus::units::{Milliseconds, Rpm};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use ezwheel_swd::{Model, Swd};

/// Factory node id (manual section 9.3).
const NODE: NodeId = NodeId(0x10);

/// The product: the standard SWD 150 (ezSWD150IH.14x/Cx), gear ratio (63/17)², manual line 465.
const MODEL: Model = Model::Swd15014x;

fn main() -> Result<(), Box<dyn Error>> {
    let description = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/ezwheel-swd");
    let bus = InProcessBus::new();
    let (mut monitor, client, mut endpoint) = (bus.endpoint(), bus.endpoint(), bus.endpoint());
    let sim = Simulator::load(description)?;
    let stop = Arc::new(AtomicBool::new(false));
    let running = Arc::clone(&stop);
    let node = thread::spawn(move || {
        let config = NodeConfig {
            node: NODE,
            heartbeat: None,
        };
        let mut node = Node::new(sim.clone(), config, sim.variant());
        node.run_while(&mut endpoint, || !running.load(Ordering::Relaxed))
    });
    println!("simulated ez-Wheel SWD, node {:#04x}", NODE.0);
    let sdo = BlockingSdo::new(client).with_timeout(Duration::from_millis(500));
    let result = run(Swd::canopen(sdo, NODE).with_model(MODEL), &mut monitor);
    stop.store(true, Ordering::Relaxed);
    node.join().map_err(|_| "the simulated node panicked")??;
    result
}

fn run(
    mut drive: Swd<CanOpenLink<BlockingSdo<InProcessEndpoint>>>,
    monitor: &mut InProcessEndpoint,
) -> Result<(), Box<dyn Error>> {
    // Step 4: disable SRDO 1 reception, its signature, configuration valid (frames as printed).
    let sdo = drive.device().link_mut().bus_mut();
    sdo.download(NODE, 0x1301, 1, &[0x00])?;
    sdo.download(NODE, 0x13FF, 1, &[0xBD, 0xBA])?;
    sdo.download(NODE, 0x13FE, 0, &[0xA5])?;
    println!(
        "safety             SRDO 1 {:?}, signature {:#06x}, {:?}",
        drive.srdo1_direction().read()?,
        drive.srdo1_signature().read()?,
        drive.srdo_configuration_valid().read()?
    );

    // Step 6a: NMT start; the heartbeat (710h) then shows 05h, operational. The manual gives no
    // default for 1017h: the example sets 100 ms.
    drive.producer_heartbeat_time().write(Milliseconds(100.0))?;
    let sdo = drive.device().link_mut().bus_mut();
    sdo.bus_mut().send(&NmtCommand::Start.frame(Some(NODE)))?;
    println!("heartbeat          {:?}", operational(monitor)?);

    // Step 7a: velocity mode, operation enabled, vl ramp open.
    drive.start_velocity_mode(Instant::now() + Duration::from_secs(3))?;
    println!("state              {:?}", drive.cia402_state()?);
    println!(
        "mode               {:?}",
        drive.modes_of_operation_display().read()?
    );

    // Step 8a: 298 rpm at the motor shaft.
    drive.set_motor_speed(Rpm(298.0))?;
    let until = Instant::now() + Duration::from_secs(3);
    let mut motor = 0;
    while motor != 298 && Instant::now() < until {
        thread::sleep(Duration::from_millis(100));
        motor = drive.velocity_actual_value().read()?;
        println!("motor speed        {motor} rpm");
    }
    let ratio = drive.gear_ratio()?;
    // 6044h (rpm at the motor) through the model's gear ratio.
    let wheel = drive.wheel_speed_actual()?;
    println!(
        "wheel speed        {:.1} rpm (SWD 150, ratio {:.3})",
        wheel.0,
        ratio.to_f64()
    );

    drive.set_motor_speed(Rpm(0.0))?;
    drive.disable(Instant::now() + Duration::from_secs(3))?;
    println!("state              {:?}", drive.cia402_state()?);
    Ok(())
}

/// The node's state from its next heartbeat that shows operational (or the last one seen).
fn operational(monitor: &mut InProcessEndpoint) -> Result<NmtState, Box<dyn Error>> {
    let until = Instant::now() + Duration::from_secs(2);
    let mut last = None;
    while Instant::now() < until {
        let Some(frame) = monitor.recv(Duration::from_millis(50))? else {
            continue;
        };
        if let Some((_, state)) = decode_heartbeat(&frame).filter(|(n, _)| *n == NODE) {
            last = Some(state);
            if state == NmtState::Operational {
                break;
            }
        }
    }
    last.ok_or_else(|| "no heartbeat".into())
}

//! Two simulated axes following one trajectory in cyclic synchronous position mode (CSP, issue
//! 32): the network manager produces SYNC every 4 ms, each axis answers with a TPDO (statusword,
//! position), and the master answers each with the next set point in an RPDO, taken at the next
//! SYNC. The axes are the example CiA 402 axis (`examples/csp_axis`, objects from the profile:
//! none of the four manuals documents CSP over CANopen) on one in-process CAN bus.
//!
//! ```sh
//! cargo run --example csp_two_axes            # a 2 s move
//! cargo run --example csp_two_axes -- 0.5     # a 0.5 s move
//! ```
//!
//! The trajectory is a smooth (cosine) move from 0 to 20 000 increments; the example prints both
//! positions every 100 ms, then each axis's error from the end once it holds there.

use std::error::Error;
use std::f64::consts::PI;
use std::time::Duration;

use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::network::Network;
use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::NodeId;
use drivebus::control::cyclic::CyclicMode;
use drivebus::control::cyclic_driver::{AxisLink, CyclicConfig, CyclicRun};
use drivebus::control::Quirks;
use drivesim::canopen::{InProcessNode, NodeConfig};

const AXIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/csp_axis");
const PERIOD: Duration = Duration::from_millis(4);
const DISTANCE: f64 = 20_000.0;
/// Cycles between two printed lines (100 ms).
const PRINT_EVERY: u64 = 25;

/// The trajectory's position at `t` seconds of a move lasting `duration` seconds.
fn trajectory(t: f64, duration: f64) -> i32 {
    let s = (t / duration).clamp(0.0, 1.0);
    (DISTANCE * (1.0 - (PI * s).cos()) / 2.0).round() as i32
}

fn main() -> Result<(), Box<dyn Error>> {
    let duration: f64 = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(2.0);
    let bus = InProcessBus::new();
    let nodes = [NodeId(1), NodeId(2)];
    let mut sims = Vec::new();
    for node in nodes {
        let sim = drivesim::Simulator::load(AXIS)?;
        sims.push((
            sim,
            NodeConfig {
                node,
                heartbeat: None,
            },
        ));
    }
    let _drives = InProcessNode::serve(&bus, sims);
    let network = Network::new(bus.endpoint());
    network.nmt(NmtCommand::Start, None)?;
    println!("two simulated CiA 402 axes (nodes 1, 2), CSP at a 4 ms SYNC");

    let links = nodes.map(|node| AxisLink {
        node,
        rpdo_cob_id: 0x200 + u16::from(node.0),
        tpdo: 1,
    });
    let config = CyclicConfig {
        mode: CyclicMode::Position,
        period: PERIOD,
        quirks: Quirks::STANDARD,
        enable_within: Duration::from_secs(1),
        // Generous: on a loaded machine (CI, a debug build) a thread may wait tens of
        // milliseconds for a core; late SYNCs are counted as missed cycles meanwhile.
        feedback_within: Duration::from_secs(1),
    };
    let mut run = CyclicRun::start(&network, &links, config)?;
    let cycles = (duration / PERIOD.as_secs_f64()).ceil() as u64;
    let mut done = 0;
    while done <= cycles {
        let first = done;
        run.run(PRINT_EVERY, |cycle, _axis| {
            trajectory((first + cycle + 1) as f64 * PERIOD.as_secs_f64(), duration)
        })?;
        done += PRINT_EVERY;
        let [a, b] = [run.feedback()[0].actual, run.feedback()[1].actual];
        let t = done as f64 * PERIOD.as_secs_f64();
        println!("t = {t:5.2} s: axis 1 at {a:>6} inc, axis 2 at {b:>6} inc");
    }
    // Hold the end for a few cycles so both stand on it, then report the error from it.
    let end = trajectory(duration, duration);
    let stats = run.run(PRINT_EVERY, |_, _| end)?;
    for (node, feedback) in nodes.iter().zip(run.feedback()) {
        let error = feedback.actual - end;
        println!(
            "axis {} holds {} inc: error {error} inc (window 2000)",
            node.0, feedback.actual
        );
    }
    println!(
        "last {} cycles: jitter p50 {:?}, max {:?}, missed {}",
        stats.cycles(),
        stats.jitter(0.5),
        stats.jitter(1.0),
        stats.missed()
    );
    run.stop();
    Ok(())
}

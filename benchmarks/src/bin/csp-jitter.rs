//! Cyclic synchronous position with two axes at a 1 ms SYNC, in process (issue 32,
//! "Performance"): the cycle jitter the master sees (the time between the TPDO feedback of two
//! successive SYNCs, minus the period) at p50, p99 and max, and the missed cycles.
//!
//! `cargo run --release -p benchmarks --bin csp-jitter -- [--seconds 20] [--period-us 1000]`
//!
//! The axes are two simulated example axes (`examples/csp_axis`) on one in-process CAN bus,
//! served from one thread; the master is the network manager (SYNC producer on its router
//! thread) and `drivebus::control::cyclic_driver` on the main thread. The trajectory is a
//! back-and-forth cosine of 10 000 increments every 2 s. Debug builds are not meaningful.
//! Prints Markdown.

use std::error::Error;
use std::f64::consts::PI;
use std::time::Duration;

use benchmarks::flags::Flags;
use benchmarks::process::load_average;
use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::network::Network;
use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::NodeId;
use drivebus::control::cyclic::CyclicMode;
use drivebus::control::cyclic_driver::{AxisLink, CyclicConfig, CyclicRun};
use drivebus::control::Quirks;
use drivesim::canopen::{InProcessNode, NodeConfig};

const AXIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/csp_axis");

fn main() -> Result<(), Box<dyn Error>> {
    let mut flags = Flags::from_env()?;
    let seconds = flags.number("--seconds", 20)?;
    let period = Duration::from_micros(flags.number("--period-us", 1_000)?);
    flags.finish()?;
    let bus = InProcessBus::new();
    let links = [NodeId(1), NodeId(2)].map(|node| AxisLink {
        node,
        rpdo_cob_id: 0x200 + u16::from(node.0),
        tpdo: 1,
    });
    let mut drives = Vec::new();
    for link in &links {
        let config = NodeConfig {
            node: link.node,
            heartbeat: None,
        };
        drives.push((drivesim::Simulator::load(AXIS)?, config));
    }
    let _drives = InProcessNode::serve(&bus, drives);
    let network = Network::new(bus.endpoint());
    network.nmt(NmtCommand::Start, None)?;
    let config = CyclicConfig {
        mode: CyclicMode::Position,
        period,
        quirks: Quirks::STANDARD,
        enable_within: Duration::from_secs(2),
        feedback_within: Duration::from_millis(100),
    };
    let mut run = CyclicRun::start(&network, &links, config)?;
    let cycles = seconds * 1_000_000 / period.as_micros() as u64;
    let dt = period.as_secs_f64();
    let stats = run.run(cycles, |cycle, _| {
        let t = cycle as f64 * dt;
        (5_000.0 * (1.0 - (PI * t).cos())).round() as i32
    })?;
    run.stop();
    let us = |d: Duration| d.as_secs_f64() * 1e6;
    println!("| SYNC period | cycles | jitter p50 | p99 | max | missed | load average |");
    println!("|---|---|---|---|---|---|---|");
    println!(
        "| {} µs | {} | {:.0} µs | {:.0} µs | {:.0} µs | {} | {} |",
        period.as_micros(),
        stats.cycles(),
        us(stats.jitter(0.5)),
        us(stats.jitter(0.99)),
        us(stats.jitter(1.0)),
        stats.missed(),
        load_average()
    );
    Ok(())
}

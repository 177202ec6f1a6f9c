//! Cyclic synchronous position with two axes at a 1 ms SYNC (issue 32, "Performance"), in
//! process or on a kernel CAN interface: the cycle jitter the master sees (the time between the
//! TPDO feedback of two successive SYNCs, minus the period) at p50, p99 and max, and the missed
//! cycles.
//!
//! `cargo run --release -p benchmarks --bin csp-jitter -- [--seconds 20] [--period-us 1000]
//! [--feedback-ms 100] [--can socketcan:IFACE] [--axis DIR]`
//!
//! The axes are two simulated example axes (`examples/csp_axis`, or the description folder
//! `--axis`) served from one thread; the master is the network manager (SYNC producer on its
//! router thread) and `drivebus::control::cyclic_driver` on the main thread. In process, both
//! sit on one in-process CAN bus; with `--can socketcan:IFACE` (Linux), each has its own socket
//! on the interface (`vcan0` in the VM of `scripts/vm-can-test`, `VM_JITTER=1`), so every frame
//! goes through the kernel. The trajectory is a back-and-forth cosine of 10 000 increments every
//! 2 s. Debug builds are not meaningful. Prints Markdown.

use std::error::Error;
use std::f64::consts::PI;
use std::time::Duration;

use benchmarks::flags::Flags;
use benchmarks::process::load_average;
use drivebus::canopen::can::in_process::InProcessBus;
use drivebus::canopen::network::Network;
use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::{CanBus, NodeId};
use drivebus::control::cycle_stats::CycleStats;
use drivebus::control::cyclic::CyclicMode;
use drivebus::control::cyclic_driver::{AxisLink, CyclicConfig, CyclicRun};
use drivebus::control::Quirks;
use drivesim::canopen::{InProcessNode, NodeConfig};

const AXIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/csp_axis");

/// What one run measures.
struct Run {
    seconds: u64,
    period: Duration,
    feedback_within: Duration,
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut flags = Flags::from_env()?;
    let run = Run {
        seconds: flags.number("--seconds", 20)?,
        period: Duration::from_micros(flags.number("--period-us", 1_000)?),
        feedback_within: Duration::from_millis(flags.number("--feedback-ms", 100)?),
    };
    let can = flags.text("--can");
    let axis = flags.text("--axis").unwrap_or_else(|| AXIS.to_owned());
    flags.finish()?;
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
        drives.push((drivesim::Simulator::load(&axis)?, config));
    }
    let (stats, bus) = match can.as_deref() {
        None => {
            let bus = InProcessBus::new();
            let _drives = InProcessNode::serve(&bus, drives);
            (measure(bus.endpoint(), &links, &run)?, "in process")
        }
        Some(can) => (kernel::measure(can, drives, &links, &run)?, can),
    };
    let us = |d: Duration| d.as_secs_f64() * 1e6;
    println!("| bus | SYNC period | cycles | jitter p50 | p99 | max | missed | load average |");
    println!("|---|---|---|---|---|---|---|---|");
    println!(
        "| {bus} | {} µs | {} | {:.0} µs | {:.0} µs | {:.0} µs | {} | {} |",
        run.period.as_micros(),
        stats.cycles(),
        us(stats.jitter(0.5)),
        us(stats.jitter(0.99)),
        us(stats.jitter(1.0)),
        stats.missed(),
        load_average()
    );
    Ok(())
}

/// Starts the axes' PDOs through the master on `bus`, runs the trajectory and returns the
/// cycle timing.
fn measure<B: CanBus + Send + 'static>(
    bus: B,
    links: &[AxisLink],
    run: &Run,
) -> Result<CycleStats, Box<dyn Error>> {
    let network = Network::new(bus);
    network.nmt(NmtCommand::Start, None)?;
    let config = CyclicConfig {
        mode: CyclicMode::Position,
        period: run.period,
        quirks: Quirks::STANDARD,
        enable_within: Duration::from_secs(2),
        feedback_within: run.feedback_within,
    };
    let mut cyclic = CyclicRun::start(&network, links, config)?;
    let cycles = run.seconds * 1_000_000 / run.period.as_micros().max(1) as u64;
    let dt = run.period.as_secs_f64();
    let stats = cyclic.run(cycles, |cycle, _| {
        let t = cycle as f64 * dt;
        (5_000.0 * (1.0 - (PI * t).cos())).round() as i32
    })?;
    cyclic.stop();
    Ok(stats)
}

/// The run on a kernel CAN interface: the simulated axes on one socket, the master on another.
#[cfg(target_os = "linux")]
mod kernel {
    use std::error::Error;

    use drivebus::canopen::can::socketcan::SocketCanBus;
    use drivebus::control::cycle_stats::CycleStats;
    use drivebus::control::cyclic_driver::AxisLink;
    use drivesim::canopen::{NodeConfig, ServedNodes};
    use drivesim::Simulator;

    use super::Run;

    /// `can` is `socketcan:IFACE`.
    pub fn measure(
        can: &str,
        drives: Vec<(Simulator, NodeConfig)>,
        links: &[AxisLink],
        run: &Run,
    ) -> Result<CycleStats, Box<dyn Error>> {
        let iface = can
            .strip_prefix("socketcan:")
            .ok_or_else(|| format!("--can takes socketcan:IFACE, not {can:?}"))?;
        // Both sockets open before the axes boot, so the master sees their boot-up.
        let axes_bus = SocketCanBus::open(iface)?;
        let master_bus = SocketCanBus::open(iface)?;
        let axes = ServedNodes::serve_on(axes_bus, drives);
        let stats = super::measure(master_bus, links, run);
        axes.stop()?;
        stats
    }
}

/// Without Linux there is no kernel CAN to run on.
#[cfg(not(target_os = "linux"))]
mod kernel {
    use std::error::Error;

    use drivebus::control::cycle_stats::CycleStats;
    use drivebus::control::cyclic_driver::AxisLink;
    use drivesim::canopen::NodeConfig;
    use drivesim::Simulator;

    use super::Run;

    pub fn measure(
        can: &str,
        _: Vec<(Simulator, NodeConfig)>,
        _: &[AxisLink],
        _: &Run,
    ) -> Result<CycleStats, Box<dyn Error>> {
        Err(format!("--can {can}: kernel CAN exists on Linux only").into())
    }
}

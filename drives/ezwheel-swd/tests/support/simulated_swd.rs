//! The simulated SWD (drivesim, built from the same description) as a CANopen node on an
//! in-process bus, reached through the generated `Swd` handle. The node thread stops on drop.

// Each test binary uses a part of the double.
#![allow(dead_code)]

use std::net::TcpListener;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

use drivebus::asynch::{Async, TokioTimer};
use drivebus::canopen::async_client::AsyncSdo;
use drivebus::canopen::can::async_slcan::AsyncSlcanBus;
use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};
use drivebus::canopen::can::slcan::SlcanBus;
use drivebus::canopen::can::tokio_adapters::TokioIo;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;
use ezwheel_swd::Swd;

/// The factory node id (manual section 9.3, line 1063).
pub const NODE: u8 = 0x10;

pub const DESCRIPTION: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../descriptions/ezwheel-swd"
);

/// The generated handle on the simulated drive.
pub type SimulatedSwd = Swd<CanOpenLink<BlockingSdo<InProcessEndpoint>>>;

/// A node running in a thread; stopped and joined on drop.
pub struct Running {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
    /// The simulator behind the node, for presets and inspection.
    pub sim: Simulator,
}

impl Drop for Running {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            t.join().unwrap();
        }
    }
}

/// Starts the simulated SWD at the factory node id.
pub fn start() -> (SimulatedSwd, Running) {
    let sim = Simulator::load(DESCRIPTION).unwrap();
    let bus = InProcessBus::new();
    let client = bus.endpoint();
    let mut endpoint = bus.endpoint();
    let config = NodeConfig {
        node: NodeId(NODE),
        heartbeat: None,
    };
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let node_sim = sim.clone();
    let thread = std::thread::spawn(move || {
        let mut node = Node::new(node_sim.clone(), config, node_sim.variant());
        node.run_while(&mut endpoint, || !flag.load(Ordering::Relaxed))
            .unwrap();
    });
    let sdo = BlockingSdo::new(client).with_timeout(Duration::from_millis(500));
    let drive = Swd::canopen(sdo, NodeId(NODE));
    (
        drive,
        Running {
            stop,
            thread: Some(thread),
            sim,
        },
    )
}

/// The generated handle over the async SDO client on SLCAN over TCP.
pub type AsyncSwd =
    Swd<Async<CanOpenLink<AsyncSdo<AsyncSlcanBus<TokioIo<tokio::net::TcpStream>>, TokioTimer>>>>;

/// Serves `sim` as a CANopen node on SLCAN over a loopback port, in a thread that ends when the
/// client hangs up; returns the async handle connected to it.
pub async fn async_swd(sim: &Simulator) -> AsyncSwd {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap();
    let sim = sim.clone();
    std::thread::spawn(move || {
        let (stream, _) = listener.accept().unwrap();
        let mut bus = SlcanBus::tcp(stream).unwrap();
        let config = NodeConfig {
            node: NodeId(NODE),
            heartbeat: None,
        };
        let mut node = Node::new(sim.clone(), config, sim.variant());
        // Ends with an error once the client hung up; that is how a test ends.
        let _ = node.run(&mut bus);
    });
    let bus = AsyncSlcanBus::connect(address).await.unwrap();
    let sdo = AsyncSdo::new(bus, TokioTimer).with_timeout(Duration::from_millis(500));
    Swd::canopen_async(sdo, NodeId(NODE))
}

//! A simulated node served on an in-process CAN bus from its own thread: the CANopen test double
//! and example drive of applications, which talk to it through the endpoint it hands back.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;

use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};

use super::{Node, NodeConfig};
use crate::Simulator;

/// The running node; stopped and joined when dropped.
#[derive(Debug)]
pub struct InProcessNode {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl InProcessNode {
    /// Serves `sim` as the node `config` says on a new in-process bus; returns the bus endpoint
    /// a master uses and the running node.
    pub fn start(sim: Simulator, config: NodeConfig) -> (InProcessEndpoint, InProcessNode) {
        let bus = InProcessBus::new();
        let client = bus.endpoint();
        let running = Self::serve(&bus, vec![(sim, config)]);
        (client, running)
    }

    /// Serves several simulated nodes on `bus` from one thread, as drives share a real bus:
    /// each answers for its own node id and sees the others' frames. A master takes its own
    /// endpoint of `bus`.
    pub fn serve(bus: &InProcessBus, nodes: Vec<(Simulator, NodeConfig)>) -> InProcessNode {
        let mut endpoint = bus.endpoint();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || {
            let mut nodes: Vec<Node> = nodes
                .into_iter()
                .map(|(sim, config)| Node::new(sim.clone(), config, sim.variant()))
                .collect();
            // An in-process bus does not fail; the loop ends when the node is dropped.
            let _ = super::nodes::run_while(&mut nodes, &mut endpoint, || {
                !flag.load(Ordering::Relaxed)
            });
        });
        InProcessNode {
            stop,
            thread: Some(thread),
        }
    }
}

impl Drop for InProcessNode {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

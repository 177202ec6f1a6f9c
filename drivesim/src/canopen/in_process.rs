//! A simulated node served on an in-process CAN bus from its own thread: the CANopen test double
//! and example drive of applications, which talk to it through the endpoint it hands back.

use drivebus::canopen::can::in_process::{InProcessBus, InProcessEndpoint};

use super::served::ServedNodes;
use super::NodeConfig;
use crate::Simulator;

/// The running node; stopped and joined when dropped.
#[derive(Debug)]
pub struct InProcessNode {
    /// Held only to be dropped: that stops the node.
    _served: ServedNodes,
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
        // An in-process bus does not fail; the serving ends when the node is dropped.
        InProcessNode {
            _served: ServedNodes::serve_on(bus.endpoint(), nodes),
        }
    }
}

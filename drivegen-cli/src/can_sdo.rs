//! How a CANopen session reaches its node: alone on the bus through one SDO client, or, when
//! `read` or `watch` name several nodes, through the network manager
//! (`drivebus::canopen::network`), which has transfers to different nodes in flight at once.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::network::{Network, NodeSdo};
use drivebus::canopen::{NodeId, SdoBus};

use crate::connect::DynCan;

/// A session's SDO client.
#[derive(Clone)]
pub enum CanSdo {
    /// The only node on this connection: one client (sessions to the same bus share it).
    Alone(Arc<Mutex<BlockingSdo<DynCan>>>),
    /// One of several nodes: the node's handle on the network manager that owns the bus.
    Network {
        /// The manager, kept running while a session holds it.
        network: Arc<Network<DynCan>>,
        /// This node's handle.
        sdo: NodeSdo,
        /// Each request's timeout (given to the handles of other nodes too).
        timeout: Duration,
    },
}

impl CanSdo {
    /// A client on `bus`: alone, or through a network manager when `several` nodes share it.
    pub fn open(bus: DynCan, node: NodeId, timeout: Duration, several: bool) -> Self {
        if !several {
            let sdo = BlockingSdo::new(bus).with_timeout(timeout);
            return Self::Alone(Arc::new(Mutex::new(sdo)));
        }
        let network = Arc::new(Network::new(bus));
        Self::Network {
            sdo: network.node(node).with_timeout(timeout),
            network,
            timeout,
        }
    }

    /// A client for `node` on the same bus.
    pub fn to(&self, node: NodeId) -> Self {
        match self {
            Self::Alone(sdo) => Self::Alone(Arc::clone(sdo)),
            Self::Network {
                network, timeout, ..
            } => Self::Network {
                sdo: network.node(node).with_timeout(*timeout),
                network: Arc::clone(network),
                timeout: *timeout,
            },
        }
    }

    /// Whether transfers of this session may run beside other nodes' transfers.
    pub fn concurrent(&self) -> bool {
        matches!(self, Self::Network { .. })
    }

    /// Runs `exchange` on the client (an alone client held for the whole of it).
    pub fn with<R>(&mut self, exchange: impl FnOnce(&mut dyn SdoBus) -> R) -> R {
        match self {
            Self::Alone(sdo) => {
                let mut held = sdo
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner);
                exchange(&mut *held)
            }
            Self::Network { sdo, .. } => exchange(sdo),
        }
    }
}

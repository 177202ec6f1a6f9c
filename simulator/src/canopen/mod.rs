//! The CANopen side of the simulator: the object dictionary view of the drive, and a node with
//! NMT, heartbeat and an SDO server, run over any [`CanBus`](drivebus::canopen::CanBus).

pub mod dictionary;
pub mod node;

pub use dictionary::Dictionary;
pub use node::{Node, NodeConfig};

//! The CANopen side of the simulator: the object dictionary view of the drive, and a node with
//! NMT, heartbeat, an SDO server and SRDOs, run over any [`CanBus`](drivebus::canopen::CanBus).

pub mod dictionary;
pub mod node;
pub mod nodes;
pub mod srdo;

pub use dictionary::Dictionary;
pub use node::{Node, NodeConfig};
pub use srdo::Srdos;

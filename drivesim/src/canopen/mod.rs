//! The CANopen side of the simulator: the object dictionary view of the drive, and a node with
//! NMT, heartbeat, an SDO server, SRDOs and (for LSS slaves) LSS, run over any [`CanBus`](drivebus::canopen::CanBus).

pub mod dictionary;
pub mod in_process;
pub mod lss;
pub mod node;
pub mod nodes;
pub mod pdo;
pub mod served;
pub mod srdo;

pub use dictionary::Dictionary;
pub use in_process::InProcessNode;
pub use node::{Node, NodeConfig};
pub use pdo::Pdos;
pub use served::ServedNodes;
pub use srdo::Srdos;

//! The CANopen network manager: one CAN bus shared by the drives of many nodes.
//!
//! A [`Network`] owns the bus. [`Network::node`] gives an SDO client per node ([`NodeSdo`], an
//! [`SdoBus`](crate::canopen::SdoBus)), so generated drive handles run on it unchanged, each on
//! its own thread if need be; transfers to different nodes are in flight at once, one per node
//! as CANopen requires. PDOs, EMCYs, boot-ups, state changes and heartbeat losses of a node go
//! to its [`Subscription`] (a bounded queue: when full, the oldest event is dropped and counted;
//! the router never waits for a subscriber). The manager also produces SYNC at a set period,
//! watches heartbeats ([`NetworkEvent::Lost`], [`NetworkEvent::Back`]) and sends NMT commands
//! to one node or all.
//!
//! One design, two shells: [`NetworkCore`] is sans-I/O (it routes frames, tracks nodes and
//! queues frames to send, given the time); the blocking [`Network`] runs it on a router
//! thread, the async `AsyncNetwork` (feature `async`) in a router future driven by any
//! executor, with an `AsyncCanBus` and a `Timer`.
//!
//! ```no_run
//! # fn main() -> Result<(), drivebus::BusError> {
//! use std::time::Duration;
//! use drivebus::canopen::can::in_process::InProcessBus;
//! use drivebus::canopen::network::{Network, NetworkEvent};
//! use drivebus::canopen::nmt::NmtCommand;
//! use drivebus::canopen::{NodeId, SdoBus};
//!
//! let bus = InProcessBus::new();
//! let network = Network::new(bus.endpoint());
//! let events = network.subscribe(NodeId(2), 64);
//! network.monitor_heartbeat(NodeId(2), Duration::from_millis(300));
//! let readers: Vec<_> = (1..=8u8)
//!     .map(|id| {
//!         let mut sdo = network.node(NodeId(id));
//!         std::thread::spawn(move || {
//!             let mut out = [0u8; 4];
//!             sdo.upload(NodeId(id), 0x1000, 0, &mut out).map(|_| u32::from_le_bytes(out))
//!         })
//!     })
//!     .collect();
//! for reader in readers {
//!     println!("{:?}", reader.join());
//! }
//! network.nmt(NmtCommand::Start, None)?;
//! if let Some(NetworkEvent::Lost) = events.recv(Duration::from_secs(1))? {
//!     println!("node 2 lost");
//! }
//! # Ok(())
//! # }
//! ```

#[cfg(feature = "async")]
mod async_network;
mod blocking;
pub mod boot;
mod core;
mod event;
mod guarded;
mod manager_methods;
mod node_sdo;
mod own_node;
mod router;
mod shared;
mod subscription;

#[cfg(feature = "async")]
pub use async_network::{AsyncNetwork, AsyncNodeSdo, AsyncRouter, AsyncSubscription};
pub use blocking::{Network, DEFAULT_POLL_INTERVAL};
pub use core::{NetworkCore, NodeStatus, SubscriptionId, OUTBOX, SDO_INBOX};
pub use event::NetworkEvent;
pub use node_sdo::NodeSdo;
pub use router::BUSY_POLL_INTERVAL;
pub use subscription::Subscription;

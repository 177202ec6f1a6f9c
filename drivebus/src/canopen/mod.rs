//! CANopen (CiA 301, CiA 402): the side that configures and commands drives (SDO client, NMT
//! master, SYNC producer, heartbeat and EMCY consumer, PDOs both ways) and, with feature
//! `server`, an SDO server for simulators and test peers.
//!
//! The protocol cores are sans-I/O and `no_std`: each is a pure function of received frames and
//! the time the caller passes in ([`core::time::Duration`] since any fixed origin), returning the
//! frames to send and the events to act on. They never read a clock or touch a bus.
//!
//! * [`frame`] — the [`CanFrame`] type and the predefined connection set (COB-IDs).
//! * [`sdo`] — SDO client transfers (expedited, segmented, block), the abort codes and (feature
//!   `server`, with `canopen`) the SDO server.
//! * [`nmt`], [`heartbeat`], [`emcy`], [`sync`], [`pdo`] — the other CiA 301 services.
//! * `srdo` — (`srdo`, in `canopen`) CANopen Safety SRDOs: consumer, producer, signature, safety writes.
//! * [`lss`] — LSS (CiA 305) master: node ids and bit rates, Fastscan; with `server`, a slave.
//! * [`message`] — classifies any frame of the predefined connection set into typed values.
//! * [`can`] — the [`CanBus`] trait; with `canopen`: the CAN interfaces SocketCAN, SLCAN, candump
//!   streams and an in-process bus.
//! * `client` — (`canopen`) the blocking layer: `BlockingSdo`, an [`SdoBus`] over any
//!   [`CanBus`], so [`CanOpenLink`] runs on every interface; `client::scan`, the bus scan.
//! * `async_client` — (`async` with `canopen`) the async layer: `AsyncSdo`, an `AsyncSdoBus`
//!   over any `AsyncCanBus` driving the same transfers, so [`CanOpenLink`] is an `AsyncLink`.
//! * `network` — (`canopen`) the network manager: one bus shared by the drives of many nodes,
//!   SDO to several nodes at once, per-node PDO/EMCY/heartbeat subscribers, SYNC, NMT; blocking
//!   and (with `async`) async.
//!
//! # Opening a CAN interface
//!
//! | interface | how |
//! | --- | --- |
//! | SocketCAN (feature `socketcan`) | `can::socketcan::SocketCanBus::open("can0")` |
//! | SLCAN over TCP | `SlcanBus::connect("127.0.0.1:3333")?` then `.open(Bitrate::K500)` |
//! | SLCAN over a serial port | `SlcanBus::new(port)` with any `Read + Write` port that has a read timeout, then `.open(..)` |
//! | candump stdio / pipes | `CandumpBus::from_child(&mut child)` or `CandumpBus::new(reader, writer)` |
//! | candump file replay | `CandumpBus::new(File::open(path)?, std::io::sink())`; offline: `CandumpReader` |
//! | in-process (tests) | `let bus = InProcessBus::new(); let a = bus.endpoint();` |
//!
//! # An SDO read over a candump stdio relay
//!
//! ```no_run
//! # #[cfg(feature = "canopen")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use std::process::{Command, Stdio};
//! use std::time::Duration;
//! use drivebus::canopen::can::candump::CandumpBus;
//! use drivebus::canopen::client::BlockingSdo;
//! use drivebus::canopen::{NodeId, SdoBus};
//!
//! // Any process that speaks candump compact lines on stdio, e.g. tests/peers/canopen_relay.py.
//! let mut relay = Command::new("relay").stdin(Stdio::piped()).stdout(Stdio::piped()).spawn()?;
//! let mut sdo = BlockingSdo::new(CandumpBus::from_child(&mut relay)?)
//!     .with_timeout(Duration::from_millis(500));
//! let mut buf = [0u8; 4];
//! let len = sdo.upload(NodeId(5), 0x1000, 0, &mut buf)?; // device type
//! println!("0x1000 = {:#010x}", u32::from_le_bytes(buf));
//! # let _ = len;
//! relay.kill()?;
//! relay.wait()?;
//! # Ok(())
//! # }
//! # #[cfg(not(feature = "canopen"))]
//! # fn main() {}
//! ```

pub(crate) use drivebus_model::canopen as address;
#[cfg(all(feature = "async", feature = "canopen"))]
pub mod async_client;
#[cfg(feature = "canopen")]
mod bounded_queue;
pub mod can;
#[cfg(feature = "canopen")]
pub mod client;
pub mod emcy;
pub mod frame;
pub mod heartbeat;
mod link;
pub mod lss;
pub mod message;
#[cfg(feature = "canopen")]
pub mod network;
pub mod nmt;
pub mod pdo;
pub mod sdo;
#[cfg(feature = "srdo")]
pub mod srdo;
pub mod sync;

pub use address::{CanOpen, NodeId, ObjectAddress};
pub use can::CanBus;
pub use frame::CanFrame;
#[cfg(feature = "async")]
pub use link::AsyncSdoBus;
pub use link::{CanOpenLink, SdoBus};

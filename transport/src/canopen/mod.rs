//! CANopen (CiA 301 / CiA 402 master side).
//!
//! The protocol cores are sans-I/O and `no_std`: each is a pure function of received frames and
//! the time the caller passes in ([`core::time::Duration`] since any fixed origin), returning the
//! frames to send and the events to act on. They never read a clock or touch a bus.
//!
//! * [`frame`] — the [`CanFrame`] type and the predefined connection set (COB-IDs).
//! * [`sdo`] — SDO client transfers (expedited, segmented, block) and the abort codes.
//! * [`nmt`], [`heartbeat`], [`emcy`], [`sync`], [`pdo`] — the other CiA 301 services.
//! * [`message`] — classifies any frame of the predefined connection set into typed values.
//! * [`backend`] — the [`CanBus`] trait; with `canopen`: SocketCAN, SLCAN, candump streams and an
//!   in-process bus.
//! * [`blocking`] — (`canopen`) an [`SdoBus`] over any [`CanBus`], so [`CanOpenLink`] runs on every
//!   backend.

mod address;
pub mod backend;
#[cfg(feature = "canopen")]
pub mod blocking;
pub mod emcy;
pub mod frame;
pub mod heartbeat;
mod link;
pub mod message;
pub mod nmt;
pub mod pdo;
pub mod sdo;
pub mod sync;

pub use address::{CanOpen, NodeId, ObjectAddress};
pub use backend::CanBus;
pub use frame::CanFrame;
pub use link::{CanOpenLink, SdoBus};

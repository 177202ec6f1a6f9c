//! CAN backends behind one trait.
//!
//! * `in_process` — several endpoints in one process, frames broadcast to the others (tests).
//! * `slcan` — Lawicel ASCII adapters over any byte stream (serial port, TCP).
//! * `candump` — can-utils text lines over pipes and files (relays, replay, offline decoding).
//! * `socketcan` — Linux kernel CAN (feature `socketcan`).

use core::time::Duration;

use super::frame::CanFrame;
use crate::error::BusError;

#[cfg(feature = "canopen")]
pub mod candump;
#[cfg(feature = "canopen")]
pub mod in_process;
#[cfg(feature = "canopen")]
pub mod slcan;
#[cfg(feature = "socketcan")]
pub mod socketcan;

/// A CAN interface: send frames, receive frames with a timeout.
pub trait CanBus {
    /// Queues `frame` for transmission.
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError>;
    /// The next received frame, or `None` if none arrived within `timeout`.
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError>;
}

impl<B: CanBus + ?Sized> CanBus for &mut B {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        (**self).send(frame)
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        (**self).recv(timeout)
    }
}

//! [`AsyncCanBus`], the async twin of [`CanBus`](super::CanBus).

use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// A CAN interface, awaited: send frames, receive the next frame.
///
/// There is no timeout argument: the caller races [`recv`](AsyncCanBus::recv) against its
/// [`Timer`](crate::asynch::Timer) ([`within`](crate::asynch::within)), so an implementation must
/// be cancel-safe: a `recv` future dropped before it completed has consumed no frame, and a
/// `send` future dropped mid-frame has its frame finished (or never started) before the next
/// `send` goes out, so no torn frame reaches the bus.
///
/// An interface that was closed (the peer hung up, the stream ended, the adapter vanished)
/// answers every call with an error, never with a future that waits forever.
// Futures are not declared `Send`, as for `AsyncLink`: single-threaded executors need none.
#[allow(async_fn_in_trait)]
pub trait AsyncCanBus {
    /// Sends `frame` (queues it for transmission), waiting while the interface is busy.
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError>;

    /// Sends `frame` if that can be done without waiting: `Ok(true)` when it was sent,
    /// `Ok(false)` when it would have had to wait (nothing was sent). Used where no await is
    /// possible, such as the SDO abort of a transfer whose future was dropped. The default
    /// never sends: an interface over a byte stream cannot know without awaiting.
    fn try_send(&mut self, frame: &CanFrame) -> Result<bool, BusError> {
        let _ = frame;
        Ok(false)
    }

    /// The next received frame; waits until one arrives. Cancel-safe.
    async fn recv(&mut self) -> Result<CanFrame, BusError>;
}

impl<B: AsyncCanBus + ?Sized> AsyncCanBus for &mut B {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        (**self).send(frame).await
    }
    fn try_send(&mut self, frame: &CanFrame) -> Result<bool, BusError> {
        (**self).try_send(frame)
    }
    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        (**self).recv().await
    }
}

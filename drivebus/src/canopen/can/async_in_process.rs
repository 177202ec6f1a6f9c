//! An in-process async CAN bus: endpoints in one process, each frame delivered to every other
//! endpoint, woken through their wakers (no executor named; any runs it).

use core::task::{Poll, Waker};
use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard};
use std::vec::Vec;

use super::AsyncCanBus;
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// One endpoint's inbox.
#[derive(Debug, Default)]
struct Inbox {
    frames: VecDeque<CanFrame>,
    waker: Option<Waker>,
}

#[derive(Debug, Default)]
struct Shared {
    inboxes: Vec<(usize, Inbox)>,
    next_id: usize,
    closed: bool,
}

/// The bus itself; endpoints are attached with [`AsyncInProcessBus::endpoint`].
#[derive(Debug, Clone, Default)]
pub struct AsyncInProcessBus {
    shared: Arc<Mutex<Shared>>,
}

fn lock(shared: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    shared.lock().unwrap_or_else(|e| e.into_inner())
}

/// What every endpoint of a closed bus answers.
fn closed() -> BusError {
    BusError::Io(std::io::ErrorKind::BrokenPipe)
}

impl AsyncInProcessBus {
    /// An empty bus.
    pub fn new() -> Self {
        Self::default()
    }

    /// Attaches a new endpoint; it receives every frame other endpoints send from now on.
    pub fn endpoint(&self) -> AsyncInProcessEndpoint {
        let mut shared = lock(&self.shared);
        shared.next_id += 1;
        let id = shared.next_id;
        shared.inboxes.push((id, Inbox::default()));
        AsyncInProcessEndpoint {
            id,
            shared: Arc::clone(&self.shared),
        }
    }

    /// Closes the bus, as a pulled cable or a vanished adapter would: every pending and later
    /// call of every endpoint fails with [`BusError::Io`] (`BrokenPipe`).
    pub fn close(&self) {
        let mut shared = lock(&self.shared);
        shared.closed = true;
        for (_, inbox) in &mut shared.inboxes {
            if let Some(waker) = inbox.waker.take() {
                waker.wake();
            }
        }
    }
}

/// One node's attachment to an [`AsyncInProcessBus`].
#[derive(Debug)]
pub struct AsyncInProcessEndpoint {
    id: usize,
    shared: Arc<Mutex<Shared>>,
}

impl AsyncInProcessEndpoint {
    fn deliver(&self, frame: &CanFrame) -> Result<(), BusError> {
        let mut shared = lock(&self.shared);
        if shared.closed {
            return Err(closed());
        }
        for (_, inbox) in shared.inboxes.iter_mut().filter(|(id, _)| *id != self.id) {
            inbox.frames.push_back(*frame);
            if let Some(waker) = inbox.waker.take() {
                waker.wake();
            }
        }
        Ok(())
    }
}

impl AsyncCanBus for AsyncInProcessEndpoint {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.deliver(frame)
    }

    fn try_send(&mut self, frame: &CanFrame) -> Result<bool, BusError> {
        self.deliver(frame).map(|()| true)
    }

    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        core::future::poll_fn(|cx| {
            let mut shared = lock(&self.shared);
            if shared.closed {
                return Poll::Ready(Err(closed()));
            }
            let Some((_, inbox)) = shared.inboxes.iter_mut().find(|(id, _)| *id == self.id) else {
                return Poll::Ready(Err(closed()));
            };
            match inbox.frames.pop_front() {
                Some(frame) => Poll::Ready(Ok(frame)),
                None => {
                    inbox.waker = Some(cx.waker().clone());
                    Poll::Pending
                }
            }
        })
        .await
    }
}

impl Drop for AsyncInProcessEndpoint {
    fn drop(&mut self) {
        lock(&self.shared).inboxes.retain(|(id, _)| *id != self.id);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::future::Future;
    use core::pin::pin;
    use core::task::Context;

    fn poll_once<F: Future>(future: F) -> Poll<F::Output> {
        let mut cx = Context::from_waker(Waker::noop());
        pin!(future).poll(&mut cx)
    }

    #[test]
    fn frames_reach_every_other_endpoint_but_not_the_sender() {
        let bus = AsyncInProcessBus::new();
        let (mut a, mut b, mut c) = (bus.endpoint(), bus.endpoint(), bus.endpoint());
        let frame = CanFrame::new(0x123, &[1, 2, 3]).unwrap();
        assert_eq!(poll_once(a.send(&frame)), Poll::Ready(Ok(())));
        assert_eq!(poll_once(b.recv()), Poll::Ready(Ok(frame)));
        assert_eq!(poll_once(c.recv()), Poll::Ready(Ok(frame)));
        assert_eq!(poll_once(a.recv()), Poll::Pending);
    }

    #[test]
    fn a_closed_bus_fails_every_call() {
        let bus = AsyncInProcessBus::new();
        let mut a = bus.endpoint();
        bus.close();
        assert_eq!(poll_once(a.recv()), Poll::Ready(Err(closed())));
        assert_eq!(a.try_send(&CanFrame::new(1, &[]).unwrap()), Err(closed()));
    }
}

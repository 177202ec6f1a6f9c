//! An in-process CAN bus: endpoints in one process, each frame delivered to every other endpoint.

use core::time::Duration;
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::vec::Vec;

use super::CanBus;
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

type Members = Arc<Mutex<Vec<(usize, Sender<CanFrame>)>>>;

/// The bus itself; endpoints are attached with [`InProcessBus::endpoint`].
#[derive(Debug, Clone, Default)]
pub struct InProcessBus {
    members: Members,
    next_id: Arc<Mutex<usize>>,
}

impl InProcessBus {
    /// An empty bus.
    pub fn new() -> Self {
        Self::default()
    }

    /// Attaches a new endpoint; it receives every frame other endpoints send from now on.
    pub fn endpoint(&self) -> InProcessEndpoint {
        let (tx, rx) = channel();
        let id = {
            let mut next = self.next_id.lock().unwrap_or_else(|e| e.into_inner());
            *next += 1;
            *next
        };
        self.members
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push((id, tx));
        InProcessEndpoint {
            id,
            members: Arc::clone(&self.members),
            rx,
        }
    }
}

/// One node's attachment to an [`InProcessBus`].
#[derive(Debug)]
pub struct InProcessEndpoint {
    id: usize,
    members: Members,
    rx: Receiver<CanFrame>,
}

impl CanBus for InProcessEndpoint {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        let mut members = self.members.lock().unwrap_or_else(|e| e.into_inner());
        // Endpoints that were dropped are detached here.
        members.retain(|(id, tx)| *id == self.id || tx.send(*frame).is_ok());
        Ok(())
    }

    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        match self.rx.recv_timeout(timeout) {
            Ok(frame) => Ok(Some(frame)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => {
                Err(BusError::Io(std::io::ErrorKind::BrokenPipe))
            }
        }
    }
}

impl Drop for InProcessEndpoint {
    fn drop(&mut self) {
        let mut members = self.members.lock().unwrap_or_else(|e| e.into_inner());
        members.retain(|(id, _)| *id != self.id);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_reach_every_other_endpoint_but_not_the_sender() {
        let bus = InProcessBus::new();
        let (mut a, mut b, mut c) = (bus.endpoint(), bus.endpoint(), bus.endpoint());
        let frame = CanFrame::new(0x123, &[1, 2, 3]).unwrap();
        a.send(&frame).unwrap();
        assert_eq!(b.recv(Duration::from_millis(100)).unwrap(), Some(frame));
        assert_eq!(c.recv(Duration::from_millis(100)).unwrap(), Some(frame));
        assert_eq!(a.recv(Duration::from_millis(1)).unwrap(), None);
    }

    #[test]
    fn dropped_endpoints_are_detached() {
        let bus = InProcessBus::new();
        let mut a = bus.endpoint();
        drop(bus.endpoint());
        a.send(&CanFrame::new(1, &[]).unwrap()).unwrap();
        assert_eq!(bus.members.lock().unwrap().len(), 1);
    }
}

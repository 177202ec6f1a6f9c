//! SocketCAN for the async API (features `socketcan` and `tokio`): the socket
//! [`SocketCanBus::open`] opens and checks, driven by tokio's reactor.
//!
//! The `socketcan` crate's own tokio socket opens its socket by name only; registering ours
//! keeps the typed [`OpenError`]s, the error-frame filter and the kernel timestamps of the
//! blocking backend.

use std::io;

use socketcan::{CanSocket, Socket};
use tokio::io::unix::AsyncFd;

use super::socketcan::{
    event_from_socketcan, io_error, reported_state, to_socketcan, SocketCanBus,
};
use super::{AsyncCanBus, BusState, CanEvent, OpenError, Timestamp};
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// An [`AsyncCanBus`] on a SocketCAN interface such as `can0` or `vcan0`.
#[derive(Debug)]
pub struct AsyncSocketCanBus {
    socket: AsyncFd<CanSocket>,
    state: BusState,
}

impl AsyncSocketCanBus {
    /// Opens interface `name` as [`SocketCanBus::open`] does (same checks, same errors).
    ///
    /// # Panics
    /// Outside a tokio runtime with I/O enabled (tokio's `AsyncFd::new` does).
    pub fn open(name: &str) -> Result<Self, OpenError> {
        let socket = SocketCanBus::open(name)?.into_socket();
        // SAFETY: the socket owns its descriptor until it is dropped, which only the `AsyncFd`
        // holding it does, and always answers `as_raw_fd` with that descriptor.
        let socket = unsafe { AsyncFd::register(socket) }
            .map_err(|e| OpenError::Io(e.into_parts().1.kind()))?;
        Ok(Self {
            socket,
            state: BusState::ErrorActive,
        })
    }

    /// The bus state the last error frame reported.
    pub fn bus_state(&self) -> BusState {
        self.state
    }

    /// The next frame or error report (extended frames are skipped). Cancel-safe.
    pub async fn recv_event(&mut self) -> Result<CanEvent, BusError> {
        loop {
            let mut ready = self.socket.readable().await.map_err(|e| io_error(&e))?;
            let read = ready.try_io(|socket| socket.get_ref().read_frame_with_timestamp());
            let (frame, time) = match read {
                Ok(Ok(received)) => received,
                Ok(Err(e)) if e.kind() == io::ErrorKind::Interrupted => continue,
                Ok(Err(e)) => return Err(io_error(&e)),
                Err(_would_block) => continue,
            };
            let Some(event) = event_from_socketcan(&frame, Some(Timestamp::Kernel(time))) else {
                continue;
            };
            self.state = reported_state(&event).unwrap_or(self.state);
            return Ok(event);
        }
    }
}

impl AsyncCanBus for AsyncSocketCanBus {
    /// Sends `frame`, waiting while the socket is not writable. A transmit queue that is full
    /// (`ENOBUFS`, which the reactor does not signal) fails at once with
    /// [`BusError::CanQueueFull`]: the caller retries with its own timer.
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        let frame = to_socketcan(frame)?;
        loop {
            let mut ready = self.socket.writable().await.map_err(|e| io_error(&e))?;
            match ready.try_io(|socket| socket.get_ref().write_frame(&frame)) {
                Ok(result) => return result.map_err(|e| io_error(&e)),
                Err(_would_block) => continue,
            }
        }
    }

    fn try_send(&mut self, frame: &CanFrame) -> Result<bool, BusError> {
        let frame = to_socketcan(frame)?;
        match self.socket.get_ref().write_frame(&frame) {
            Ok(()) => Ok(true),
            Err(e) if e.kind() == io::ErrorKind::WouldBlock => Ok(false),
            Err(e) => match io_error(&e) {
                BusError::CanQueueFull => Ok(false),
                error => Err(error),
            },
        }
    }

    /// The next standard frame; error frames are skipped (their bus state is kept), except a
    /// bus-off, which fails with [`BusError::CanBusOff`], as the blocking backend does.
    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        loop {
            match self.recv_event().await? {
                CanEvent::Frame { frame, .. } => return Ok(frame),
                CanEvent::Error { report, .. } if report.state == Some(BusState::BusOff) => {
                    return Err(BusError::CanBusOff)
                }
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_interface_is_the_blocking_backends_typed_error() {
        assert_eq!(
            AsyncSocketCanBus::open("drivegen-none0").map(drop),
            Err(OpenError::NoInterface {
                name: "drivegen-none0".into()
            })
        );
    }

    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn frames_travel_between_two_async_sockets_on_vcan0() {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap();
        runtime.block_on(async {
            let mut a = AsyncSocketCanBus::open("vcan0").expect("vcan0 for socketcan-tests");
            let mut b = AsyncSocketCanBus::open("vcan0").unwrap();
            let frame = CanFrame::new(0x605, &[0x40, 0x00, 0x10, 0x00]).unwrap();
            a.send(&frame).await.unwrap();
            assert_eq!(b.recv().await, Ok(frame));
            assert_eq!(a.try_send(&frame), Ok(true));
            assert_eq!(b.recv().await, Ok(frame));
        });
    }
}

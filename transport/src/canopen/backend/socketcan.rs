//! Linux kernel CAN (SocketCAN) through the `socketcan` crate.
//!
//! Its run-time tests need a CAN interface (`vcan0`): they run with the `socketcan-tests`
//! feature only, since CI machines have no kernel CAN.

use core::time::Duration;
use std::io;
use std::time::Instant;

use socketcan::{CanSocket, EmbeddedFrame, Id, Socket, StandardId};

use super::CanBus;
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// A [`CanBus`] on a SocketCAN interface such as `can0` or `vcan0`.
#[derive(Debug)]
pub struct SocketCanBus {
    socket: CanSocket,
}

impl SocketCanBus {
    /// Opens interface `name`.
    pub fn open(name: &str) -> Result<Self, BusError> {
        let socket = CanSocket::open(name).map_err(|e| BusError::Io(e.kind()))?;
        Ok(Self { socket })
    }

    /// The socket, for filters and options.
    pub fn socket(&self) -> &CanSocket {
        &self.socket
    }
}

/// Converts to the `socketcan` frame type.
pub fn to_socketcan(frame: &CanFrame) -> Result<socketcan::CanFrame, BusError> {
    let id = StandardId::new(frame.id()).ok_or(BusError::Frame("CAN id exceeds 11 bits"))?;
    let built = if frame.is_remote() {
        socketcan::CanFrame::new_remote(id, frame.dlc() as usize)
    } else {
        socketcan::CanFrame::new(id, frame.data())
    };
    built.ok_or(BusError::Frame("frame not representable in SocketCAN"))
}

/// Converts from the `socketcan` frame type; `None` for extended-id and error frames, which a
/// CANopen bus does not use.
pub fn from_socketcan(frame: &socketcan::CanFrame) -> Option<CanFrame> {
    let Id::Standard(id) = frame.id() else {
        return None;
    };
    match frame {
        socketcan::CanFrame::Data(_) => CanFrame::new(id.as_raw(), frame.data()).ok(),
        socketcan::CanFrame::Remote(_) => CanFrame::remote(id.as_raw(), frame.dlc() as u8).ok(),
        socketcan::CanFrame::Error(_) => None,
    }
}

impl CanBus for SocketCanBus {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.socket
            .write_frame(&to_socketcan(frame)?)
            .map_err(|e| BusError::Io(e.kind()))
    }

    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.socket.read_frame_timeout(left) {
                Ok(frame) => {
                    if let Some(frame) = from_socketcan(&frame) {
                        return Ok(Some(frame));
                    }
                    // Extended and error frames are skipped until the deadline.
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock
                    ) =>
                {
                    return Ok(None)
                }
                Err(e) => return Err(BusError::Io(e.kind())),
            }
            if Instant::now() >= deadline {
                return Ok(None);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_convert_both_ways() {
        for frame in [
            CanFrame::new(0x605, &[0x40, 0, 0x10, 0, 0, 0, 0, 0]).unwrap(),
            CanFrame::new(0x80, &[]).unwrap(),
            CanFrame::remote(0x701, 1).unwrap(),
        ] {
            assert_eq!(from_socketcan(&to_socketcan(&frame).unwrap()), Some(frame));
        }
        let extended =
            socketcan::CanFrame::new(socketcan::ExtendedId::new(0x1234_5678).unwrap(), &[1])
                .unwrap();
        assert_eq!(from_socketcan(&extended), None);
    }

    /// Needs `ip link add dev vcan0 type vcan && ip link set up vcan0`.
    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn frames_travel_between_two_sockets_on_vcan0() {
        let mut a = SocketCanBus::open("vcan0").expect("vcan0 must exist for socketcan-tests");
        let mut b = SocketCanBus::open("vcan0").unwrap();
        let frame = CanFrame::new(0x123, &[1, 2, 3]).unwrap();
        a.send(&frame).unwrap();
        assert_eq!(b.recv(Duration::from_secs(1)).unwrap(), Some(frame));
        assert_eq!(b.recv(Duration::from_millis(10)).unwrap(), None);
    }
}

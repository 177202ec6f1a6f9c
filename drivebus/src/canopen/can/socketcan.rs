//! Linux kernel CAN (SocketCAN) through the `socketcan` crate.
//!
//! Frames come with the kernel's receive timestamp ([`CanBus::recv_event`]); error frames are
//! received (all error classes enabled) and reported as [`CanEvent::Error`] with the bus state
//! they put the controller in. [`CanBus::recv`] skips them but fails with
//! [`BusError::CanBusOff`] on a bus-off, so a transfer cut by it says so. A full transmit queue
//! (`ENOBUFS`) is retried with a bounded exponential back-off ([`Backoff`]).
//!
//! Its run-time tests need a CAN interface (`vcan0`): they run with the `socketcan-tests`
//! feature only, inside the VM of `scripts/vm-can-test`, since CI machines have no kernel CAN.

use core::time::Duration;
use std::io;
use std::string::String;
use std::time::Instant;

use socketcan::{CanSocket, EmbeddedFrame, Id, Socket, SocketOptions, StandardId};

use super::{BusState, CanBus, CanErrorReport, CanEvent, OpenError, Timestamp};
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// How a send retries while the kernel's transmit queue is full (`ENOBUFS`): it waits `first`,
/// doubling up to `longest`, and gives up with [`BusError::CanQueueFull`] once `budget` has been
/// spent waiting.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Backoff {
    /// The first wait.
    pub first: Duration,
    /// The longest single wait.
    pub longest: Duration,
    /// The total wait after which the send fails.
    pub budget: Duration,
}

impl Default for Backoff {
    /// 1 ms, doubling to 20 ms, at most 200 ms in all (a 1 Mbit/s bus sends about 1 500 frames in
    /// that time).
    fn default() -> Self {
        Self {
            first: Duration::from_millis(1),
            longest: Duration::from_millis(20),
            budget: Duration::from_millis(200),
        }
    }
}

impl Backoff {
    /// Runs `attempt` until it succeeds, fails otherwise than with `ENOBUFS`, or the budget is
    /// spent; `sleep` waits (a test passes a recorder). Returns how many times it waited.
    pub fn run(
        &self,
        mut attempt: impl FnMut() -> io::Result<()>,
        mut sleep: impl FnMut(Duration),
    ) -> Result<usize, BusError> {
        let mut waited = Duration::ZERO;
        let mut wait = self.first;
        let mut waits = 0;
        loop {
            match attempt() {
                Ok(()) => return Ok(waits),
                Err(e) if queue_full(&e) => {
                    if waited >= self.budget {
                        return Err(BusError::CanQueueFull);
                    }
                    let this = wait.min(self.budget - waited);
                    sleep(this);
                    waited += this;
                    waits += 1;
                    wait = (wait * 2).min(self.longest);
                }
                Err(e) => return Err(io_error(&e)),
            }
        }
    }
}

/// Linux `ENOBUFS`: the interface's transmit queue is full.
const ENOBUFS: i32 = 105;

/// The interface's queue (`ENOBUFS`) or the socket's send buffer (`EAGAIN` on the
/// non-blocking socket) is full.
fn queue_full(e: &io::Error) -> bool {
    e.raw_os_error() == Some(ENOBUFS) || e.kind() == io::ErrorKind::WouldBlock
}

/// Waits until `fd` is readable or `timeout` passed (rounded up to whole milliseconds);
/// `false` on timeout or a signal.
fn wait_readable(fd: std::os::fd::RawFd, timeout: Duration) -> io::Result<bool> {
    let millis = timeout.as_micros().div_ceil(1000).min(i32::MAX as u128) as i32;
    let mut pollfd = libc::pollfd {
        fd,
        events: libc::POLLIN,
        revents: 0,
    };
    // SAFETY: one valid pollfd, and its count 1.
    let ready = unsafe { libc::poll(&mut pollfd, 1, millis) };
    if ready < 0 {
        let error = io::Error::last_os_error();
        return match error.kind() {
            io::ErrorKind::Interrupted => Ok(false),
            _ => Err(error),
        };
    }
    Ok(ready > 0)
}

pub(super) fn io_error(e: &io::Error) -> BusError {
    if queue_full(e) {
        BusError::CanQueueFull
    } else {
        BusError::Io(e.kind())
    }
}

/// A [`CanBus`] on a SocketCAN interface such as `can0` or `vcan0`.
#[derive(Debug)]
pub struct SocketCanBus {
    socket: CanSocket,
    backoff: Backoff,
    state: BusState,
    queue_full_waits: usize,
}

/// Whether interface `name` exists (`Some`) and is up, from sysfs.
fn interface_up(name: &str) -> Option<bool> {
    if name.is_empty() || name.contains('/') || name.starts_with('.') {
        return None;
    }
    let flags = std::fs::read_to_string(std::format!("/sys/class/net/{name}/flags")).ok()?;
    let flags = u32::from_str_radix(flags.trim().trim_start_matches("0x"), 16).ok()?;
    Some(flags & 1 != 0)
}

impl SocketCanBus {
    /// Opens interface `name`, with kernel receive timestamps and every error class reported.
    /// A missing or down interface, a kernel without CAN and a refused permission are each
    /// their own [`OpenError`].
    pub fn open(name: &str) -> Result<Self, OpenError> {
        match interface_up(name) {
            None => return Err(OpenError::NoInterface { name: name.into() }),
            Some(false) => return Err(OpenError::InterfaceDown { name: name.into() }),
            Some(true) => {}
        }
        let socket = CanSocket::open(name).map_err(|e| open_error(name, &e))?;
        socket
            .set_recv_timestamp(true)
            .map_err(|e| open_error(name, &e))?;
        socket
            .set_error_filter_accept_all()
            .map_err(|e| open_error(name, &e))?;
        // Reads and writes never block: receive deadlines are kept with poll(2), whose
        // millisecond resolution is finer than SO_RCVTIMEO's jiffies (a zero timeout would
        // otherwise wait a whole jiffy); a full send buffer is retried with the back-off.
        socket
            .set_nonblocking(true)
            .map_err(|e| open_error(name, &e))?;
        Ok(Self {
            socket,
            backoff: Backoff::default(),
            state: BusState::ErrorActive,
            queue_full_waits: 0,
        })
    }

    /// Gives the opened, non-blocking socket up (to the async adapter, which registers it
    /// with its reactor).
    #[cfg(feature = "tokio")]
    pub(super) fn into_socket(self) -> CanSocket {
        self.socket
    }

    /// Replaces the `ENOBUFS` back-off.
    pub fn with_backoff(mut self, backoff: Backoff) -> Self {
        self.backoff = backoff;
        self
    }

    /// The socket, for filters and options.
    pub fn socket(&self) -> &CanSocket {
        &self.socket
    }

    /// The bus state the last error frame reported (error active until one does).
    pub fn bus_state(&self) -> BusState {
        self.state
    }

    /// How many times sends waited for a full transmit queue so far.
    pub fn queue_full_waits(&self) -> usize {
        self.queue_full_waits
    }
}

fn open_error(name: &str, e: &io::Error) -> OpenError {
    const ENODEV: i32 = 19;
    const ENETDOWN: i32 = 100;
    const EAFNOSUPPORT: i32 = 97;
    match e.raw_os_error() {
        Some(ENODEV) => OpenError::NoInterface { name: name.into() },
        Some(ENETDOWN) => OpenError::InterfaceDown { name: name.into() },
        Some(EAFNOSUPPORT) => OpenError::NoKernelCan,
        _ if e.kind() == io::ErrorKind::PermissionDenied => OpenError::PermissionDenied {
            what: String::from(name),
        },
        _ => OpenError::Io(e.kind()),
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
/// CANopen bus does not use ([`event_from_socketcan`] decodes error frames).
pub fn from_socketcan(frame: &socketcan::CanFrame) -> Option<CanFrame> {
    match frame {
        socketcan::CanFrame::Error(_) => None,
        _ => {
            let Id::Standard(id) = frame.id() else {
                return None;
            };
            if frame.is_remote_frame() {
                CanFrame::remote(id.as_raw(), frame.dlc() as u8).ok()
            } else {
                CanFrame::new(id.as_raw(), frame.data()).ok()
            }
        }
    }
}

/// The bus state an event reports, if it is an error report that names one.
pub(super) fn reported_state(event: &CanEvent) -> Option<BusState> {
    match event {
        CanEvent::Error { report, .. } => report.state,
        _ => None,
    }
}

/// The event a received `socketcan` frame is: a standard frame, or a decoded error frame;
/// `None` for extended-id frames.
pub fn event_from_socketcan(
    frame: &socketcan::CanFrame,
    timestamp: Option<Timestamp>,
) -> Option<CanEvent> {
    if let socketcan::CanFrame::Error(error) = frame {
        let mut data = [0u8; 8];
        let bytes = error.data();
        let n = bytes.len().min(8);
        data[..n].copy_from_slice(&bytes[..n]);
        return Some(CanEvent::Error {
            report: CanErrorReport::from_linux(error.error_bits(), data),
            timestamp,
        });
    }
    from_socketcan(frame).map(|frame| CanEvent::Frame { frame, timestamp })
}

impl CanBus for SocketCanBus {
    /// Sends `frame`; while the transmit queue is full it retries with the bounded back-off,
    /// then fails with [`BusError::CanQueueFull`].
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        let frame = to_socketcan(frame)?;
        let socket = &self.socket;
        let waits = self
            .backoff
            .run(|| socket.write_frame(&frame), std::thread::sleep)?;
        self.queue_full_waits += waits;
        Ok(())
    }

    /// The next standard frame; error frames are skipped (their bus state is kept, see
    /// [`SocketCanBus::bus_state`]), except a bus-off, which fails with
    /// [`BusError::CanBusOff`].
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.recv_event(left)? {
                None => return Ok(None),
                Some(CanEvent::Frame { frame, .. }) => return Ok(Some(frame)),
                Some(CanEvent::Error { report, .. }) if report.state == Some(BusState::BusOff) => {
                    return Err(BusError::CanBusOff)
                }
                Some(_) => {}
            }
        }
    }

    fn recv_event(&mut self, timeout: Duration) -> Result<Option<CanEvent>, BusError> {
        use std::os::fd::AsRawFd;
        let deadline = Instant::now() + timeout;
        loop {
            match self.socket.read_frame_with_timestamp() {
                Ok((frame, time)) => {
                    if let Some(event) = event_from_socketcan(&frame, Some(Timestamp::Kernel(time)))
                    {
                        self.state = reported_state(&event).unwrap_or(self.state);
                        return Ok(Some(event));
                    }
                    // Extended frames are skipped until the deadline.
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::TimedOut
                            | io::ErrorKind::WouldBlock
                            | io::ErrorKind::Interrupted
                    ) => {}
                Err(e) => return Err(io_error(&e)),
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(None);
            }
            wait_readable(self.socket.as_raw_fd(), left).map_err(|e| io_error(&e))?;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;
    use std::vec::Vec;

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
        assert_eq!(event_from_socketcan(&extended, None), None);
    }

    #[test]
    fn error_frames_are_events_with_their_bus_state() {
        let cases = [
            (0x040, [0u8; 8], Some(BusState::BusOff)),
            (0x100, [0; 8], Some(BusState::Restarted)),
            (
                0x004,
                [0, 0x20, 0, 0, 0, 0, 0, 0],
                Some(BusState::ErrorPassive),
            ),
            (
                0x004,
                [0, 0x04, 0, 0, 0, 0, 0, 0],
                Some(BusState::ErrorWarning),
            ),
            (
                0x004,
                [0, 0x40, 0, 0, 0, 0, 0, 0],
                Some(BusState::ErrorActive),
            ),
            (0x020, [0; 8], None),
        ];
        for (bits, data, state) in cases {
            let raw = socketcan::frame::CanErrorFrame::new_error(bits, &data).unwrap();
            let frame = socketcan::CanFrame::Error(raw);
            let Some(CanEvent::Error { report, .. }) = event_from_socketcan(&frame, None) else {
                panic!("{bits:#x}: not an error event");
            };
            assert_eq!(report.state, state, "{bits:#x} {data:?}");
            assert_eq!(report.classes.bits(), bits);
            assert_eq!(from_socketcan(&frame), None);
        }
        let counted = CanErrorReport::from_linux(0x204, [0, 0x10, 0, 0, 0, 0, 130, 7]);
        assert_eq!(counted.counters, Some((130, 7)));
        assert_eq!(counted.state, Some(BusState::ErrorPassive));
    }

    #[test]
    fn a_full_queue_is_retried_with_a_bounded_backoff() {
        let backoff = Backoff::default();
        // Full three times, then free.
        let mut full = 3;
        let mut sleeps = Vec::new();
        let waits = backoff
            .run(
                || {
                    if full > 0 {
                        full -= 1;
                        Err(io::Error::from_raw_os_error(ENOBUFS))
                    } else {
                        Ok(())
                    }
                },
                |d| sleeps.push(d),
            )
            .unwrap();
        assert_eq!(waits, 3);
        assert_eq!(sleeps, [1, 2, 4].map(Duration::from_millis));
        // Full for ever: a bounded number of waits, then CanQueueFull.
        let mut attempts = 0;
        let mut slept = Duration::ZERO;
        let result = backoff.run(
            || {
                attempts += 1;
                Err(io::Error::from_raw_os_error(ENOBUFS))
            },
            |d| slept += d,
        );
        assert_eq!(result, Err(BusError::CanQueueFull));
        assert_eq!(slept, backoff.budget);
        assert!(attempts < 20, "{attempts} attempts");
        // Another error is not retried.
        let result = backoff.run(|| Err(io::ErrorKind::BrokenPipe.into()), |_| unreachable!());
        assert_eq!(result, Err(BusError::Io(io::ErrorKind::BrokenPipe)));
    }

    #[test]
    fn a_missing_interface_is_named_with_the_command_that_brings_it_up() {
        let error = SocketCanBus::open("nocan7").unwrap_err();
        assert_eq!(
            error,
            OpenError::NoInterface {
                name: "nocan7".into()
            }
        );
        assert_eq!(
            error.to_string(),
            "no CAN interface nocan7; bring it up with `ip link set nocan7 up type can bitrate 500000`"
        );
        assert!(matches!(
            SocketCanBus::open("../lo"),
            Err(OpenError::NoInterface { .. })
        ));
    }

    /// Needs `ip link add dev vcan0 type vcan && ip link set up vcan0`.
    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn frames_travel_between_two_sockets_on_vcan0_with_kernel_timestamps() {
        let mut a = SocketCanBus::open("vcan0").expect("vcan0 must exist for socketcan-tests");
        let mut b = SocketCanBus::open("vcan0").unwrap();
        let frame = CanFrame::new(0x123, &[1, 2, 3]).unwrap();
        let before = std::time::SystemTime::now();
        a.send(&frame).unwrap();
        let event = b.recv_event(Duration::from_secs(1)).unwrap();
        let after = std::time::SystemTime::now();
        let Some(CanEvent::Frame {
            frame: got,
            timestamp: Some(Timestamp::Kernel(at)),
        }) = event
        else {
            panic!("no timestamped frame: {event:?}");
        };
        assert_eq!(got, frame);
        // The kernel stamped it between the send and the receive (1 ms slack for clocks).
        assert!(
            at + Duration::from_millis(1) >= before && at <= after,
            "{at:?}"
        );
        assert_eq!(b.recv(Duration::from_millis(10)).unwrap(), None);
    }

    /// Needs vcan0 up. Error frames are what a CAN controller driver sends; vcan passes any
    /// frame with the error flag on to the sockets that accept errors, as a driver's would be.
    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn error_frames_on_vcan0_are_reported_and_bus_off_cuts_recv() {
        let tx = CanSocket::open("vcan0").unwrap();
        let mut rx = SocketCanBus::open("vcan0").unwrap();
        let passive =
            socketcan::frame::CanErrorFrame::new_error(0x004, &[0, 0x20, 0, 0, 0, 0, 0, 0])
                .unwrap();
        tx.write_frame(&passive).unwrap();
        let event = rx.recv_event(Duration::from_secs(1)).unwrap();
        let Some(CanEvent::Error { report, timestamp }) = event else {
            panic!("error frame not reported: {event:?}");
        };
        assert_eq!(report.state, Some(BusState::ErrorPassive));
        assert!(matches!(timestamp, Some(Timestamp::Kernel(_))));
        assert_eq!(rx.bus_state(), BusState::ErrorPassive);
        // recv skips an error-passive report, returns the frame after it.
        tx.write_frame(&passive).unwrap();
        tx.write_frame(&to_socketcan(&CanFrame::new(0x581, &[1]).unwrap()).unwrap())
            .unwrap();
        assert_eq!(
            rx.recv(Duration::from_secs(1)).unwrap(),
            Some(CanFrame::new(0x581, &[1]).unwrap())
        );
        let bus_off = socketcan::frame::CanErrorFrame::new_error(0x040, &[0; 8]).unwrap();
        tx.write_frame(&bus_off).unwrap();
        assert_eq!(rx.recv(Duration::from_secs(1)), Err(BusError::CanBusOff));
        assert_eq!(rx.bus_state(), BusState::BusOff);
        let restarted = socketcan::frame::CanErrorFrame::new_error(0x100, &[0; 8]).unwrap();
        tx.write_frame(&restarted).unwrap();
        assert!(matches!(
            rx.recv_event(Duration::from_secs(1)).unwrap(),
            Some(CanEvent::Error { report, .. }) if report.state == Some(BusState::Restarted)
        ));
    }

    /// Needs vcan0 up: a bus-off while an SDO upload awaits its answer ends the upload with
    /// `CanBusOff`, not a timeout.
    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn a_bus_off_during_an_sdo_transfer_is_reported_as_such() {
        use crate::canopen::client::BlockingSdo;
        use crate::canopen::{NodeId, SdoBus};
        use socketcan::Frame;
        let peer = CanSocket::open("vcan0").unwrap();
        peer.set_read_timeout(Duration::from_secs(5)).unwrap();
        let watcher = std::thread::spawn(move || loop {
            let frame = peer.read_frame().unwrap();
            if frame.raw_id() == 0x605 {
                let bus_off = socketcan::frame::CanErrorFrame::new_error(0x040, &[0; 8]).unwrap();
                peer.write_frame(&bus_off).unwrap();
                return;
            }
        });
        let bus = SocketCanBus::open("vcan0").unwrap();
        let mut sdo = BlockingSdo::new(bus).with_timeout(Duration::from_secs(3));
        let started = Instant::now();
        let mut out = [0u8; 4];
        assert_eq!(
            sdo.upload(NodeId(5), 0x1000, 0, &mut out),
            Err(BusError::CanBusOff)
        );
        assert!(
            started.elapsed() < Duration::from_secs(2),
            "{:?}",
            started.elapsed()
        );
        watcher.join().unwrap();
    }

    /// Needs vcan0 up: a burst far longer than any queue is sent without an error storm.
    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn a_burst_of_frames_is_sent_whole() {
        let mut tx = SocketCanBus::open("vcan0").unwrap();
        let frame = CanFrame::new(0x7FF, &[0xAA; 8]).unwrap();
        for _ in 0..5000 {
            tx.send(&frame).unwrap();
        }
    }

    /// Needs vcan0 up and a down `vcan1`.
    #[cfg(feature = "socketcan-tests")]
    #[test]
    fn a_down_interface_is_named() {
        assert_eq!(
            SocketCanBus::open("vcan1").unwrap_err(),
            OpenError::InterfaceDown {
                name: "vcan1".into()
            }
        );
    }
}

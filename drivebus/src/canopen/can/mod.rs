//! CAN interfaces behind one trait, used by the client (`canopen::client`) and by simulated
//! devices alike.
//!
//! * `in_process` — several endpoints in one process, frames broadcast to the others (tests).
//! * `slcan` — Lawicel ASCII adapters over any byte stream (serial port, TCP).
//! * `candump` — can-utils text lines over pipes and files (relays, replay, offline decoding).
//! * `socketcan` — Linux kernel CAN (feature `socketcan`).
//!
//! With feature `async`: [`AsyncCanBus`], the async twin of [`CanBus`], and (with `canopen`)
//! `async_in_process`, `async_slcan` and `async_candump` over any `embedded-io-async` stream;
//! with `tokio`: `tokio_adapters` (SLCAN over TCP and serial, candump over a child's stdio)
//! and, with `socketcan`, `async_socketcan`.

use core::time::Duration;

use super::frame::CanFrame;
use crate::error::BusError;

#[cfg(feature = "async")]
mod async_bus;
#[cfg(all(feature = "async", feature = "canopen"))]
pub mod async_candump;
#[cfg(all(feature = "async", feature = "canopen"))]
pub mod async_in_process;
#[cfg(all(feature = "async", feature = "canopen"))]
mod async_line;
#[cfg(all(feature = "async", feature = "canopen"))]
pub mod async_slcan;
#[cfg(all(feature = "tokio", feature = "socketcan"))]
pub mod async_socketcan;
#[cfg(feature = "canopen")]
pub mod candump;
#[cfg(feature = "canopen")]
mod candump_fast;
#[cfg(feature = "canopen")]
pub mod in_process;
#[cfg(feature = "canopen")]
pub mod slcan;
#[cfg(feature = "canopen")]
mod slcan_decoder;
#[cfg(feature = "socketcan")]
pub mod socketcan;
#[cfg(all(feature = "tokio", feature = "canopen"))]
pub mod tokio_adapters;

#[cfg(feature = "async")]
pub use async_bus::AsyncCanBus;

/// Why a CAN interface or adapter could not be opened: each case says what to do about it.
#[cfg(feature = "canopen")]
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum OpenError {
    /// The kernel has no CAN interface of this name.
    NoInterface {
        /// The interface name (`can0`).
        name: std::string::String,
    },
    /// The interface exists but is down.
    InterfaceDown {
        /// The interface name.
        name: std::string::String,
    },
    /// The kernel has no CAN support at all (`socket(AF_CAN)` is refused).
    NoKernelCan,
    /// The operating system refused access to the interface or port.
    PermissionDenied {
        /// The interface or device path.
        what: std::string::String,
    },
    /// The device path does not exist.
    NoDevice {
        /// The device path.
        path: std::string::String,
    },
    /// The SLCAN adapter did not answer a command of its opening sequence in time.
    NoAnswer {
        /// The command (`S6`, `O`).
        command: &'static str,
    },
    /// The SLCAN adapter refused a command of its opening sequence (answered BEL).
    Refused {
        /// The command (`S6`, `O`).
        command: &'static str,
    },
    /// Another I/O failure.
    Io(std::io::ErrorKind),
}

#[cfg(feature = "canopen")]
impl core::fmt::Display for OpenError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoInterface { name } => write!(
                f,
                "no CAN interface {name}; bring it up with `{}`",
                bring_up(name, 500_000)
            ),
            Self::InterfaceDown { name } => write!(
                f,
                "CAN interface {name} is down; bring it up with `{}`",
                bring_up(name, 500_000)
            ),
            Self::NoKernelCan => write!(
                f,
                "this kernel has no CAN support (socket(AF_CAN) refused); load the can and can-raw modules"
            ),
            Self::PermissionDenied { what } => write!(
                f,
                "permission denied on {what}; run as a user with access to it (e.g. in the dialout group for serial adapters)"
            ),
            Self::NoDevice { path } => write!(f, "no such device {path}; is the adapter plugged in?"),
            Self::NoAnswer { command } => write!(
                f,
                "the SLCAN adapter did not answer its `{command}` command; is it an SLCAN (Lawicel) adapter, at the right serial speed?"
            ),
            Self::Refused { command } => write!(
                f,
                "the SLCAN adapter refused its `{command}` command (answered BEL)"
            ),
            Self::Io(kind) => write!(f, "I/O error: {kind}"),
        }
    }
}

#[cfg(feature = "canopen")]
impl std::error::Error for OpenError {}

/// The `ip` command that brings CAN interface `name` up at `bitrate` (a virtual `vcan` interface
/// is created instead, it has no bit rate).
#[cfg(feature = "canopen")]
pub fn bring_up(name: &str, bitrate: u32) -> std::string::String {
    if name.starts_with("vcan") {
        std::format!("ip link add dev {name} type vcan && ip link set {name} up")
    } else {
        std::format!("ip link set {name} up type can bitrate {bitrate}")
    }
}

/// When a frame or event was received.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg(feature = "std")]
pub enum Timestamp {
    /// The kernel's receive time (SocketCAN `SO_TIMESTAMP`), wall clock.
    Kernel(std::time::SystemTime),
    /// An SLCAN adapter's own millisecond counter (`Z1` mode), wrapping at 60 000 ms.
    AdapterMillis(u16),
}

/// The state of the CAN controller's error confinement, as CiA 301 / ISO 11898 name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BusState {
    /// Error active: the controller takes part normally (also: recovered from a worse state).
    ErrorActive,
    /// An error counter reached the warning level (96).
    ErrorWarning,
    /// An error counter reached 128: the controller only sends passive error flags.
    ErrorPassive,
    /// The transmit error counter passed 255: the controller left the bus.
    BusOff,
    /// The controller was restarted after bus-off.
    Restarted,
}

impl core::fmt::Display for BusState {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::ErrorActive => "error active",
            Self::ErrorWarning => "error warning",
            Self::ErrorPassive => "error passive",
            Self::BusOff => "bus-off",
            Self::Restarted => "restarted",
        })
    }
}

bitflags::bitflags! {
    /// The error classes an error frame reports (Linux `CAN_ERR_*` of the identifier).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub struct ErrorClasses: u32 {
        /// Transmission timeout (by the driver).
        const TX_TIMEOUT = 0x001;
        /// Arbitration lost.
        const LOST_ARBITRATION = 0x002;
        /// Controller problem (state change, overflow).
        const CONTROLLER = 0x004;
        /// Protocol violation (bit, form, stuff error).
        const PROTOCOL = 0x008;
        /// Transceiver status.
        const TRANSCEIVER = 0x010;
        /// No acknowledgement of a transmitted frame.
        const NO_ACK = 0x020;
        /// Bus-off.
        const BUS_OFF = 0x040;
        /// Bus error (may flood).
        const BUS_ERROR = 0x080;
        /// The controller restarted.
        const RESTARTED = 0x100;
        /// The error counters are valid.
        const COUNTERS = 0x200;
    }
}

/// A CAN error frame or adapter status report, decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CanErrorReport {
    /// The classes of error reported.
    pub classes: ErrorClasses,
    /// The bus state this report puts the controller in, if it says.
    pub state: Option<BusState>,
    /// Receive buffer overflow: frames were lost.
    pub rx_overflow: bool,
    /// Transmit and receive error counters, when reported.
    pub counters: Option<(u8, u8)>,
}

impl CanErrorReport {
    /// Decodes a Linux error frame: the error class bits of its identifier (without
    /// `CAN_ERR_FLAG`) and its 8 data bytes (`linux/can/error.h`).
    pub fn from_linux(class_bits: u32, data: [u8; 8]) -> Self {
        let classes = ErrorClasses::from_bits_truncate(class_bits);
        let controller = if classes.contains(ErrorClasses::CONTROLLER) {
            data[1]
        } else {
            0
        };
        let state = if classes.contains(ErrorClasses::BUS_OFF) {
            Some(BusState::BusOff)
        } else if classes.contains(ErrorClasses::RESTARTED) {
            Some(BusState::Restarted)
        } else if controller & 0x30 != 0 {
            Some(BusState::ErrorPassive)
        } else if controller & 0x0C != 0 {
            Some(BusState::ErrorWarning)
        } else if controller & 0x40 != 0 {
            Some(BusState::ErrorActive)
        } else {
            None
        };
        Self {
            classes,
            state,
            rx_overflow: controller & 0x01 != 0,
            counters: classes
                .contains(ErrorClasses::COUNTERS)
                .then_some((data[6], data[7])),
        }
    }

    /// Decodes the status flags of an SLCAN `F` answer (Lawicel: bit 2 error warning, bit 3
    /// data overrun, bit 5 error passive, bit 6 arbitration lost, bit 7 bus error).
    pub fn from_slcan_status(flags: u8) -> Self {
        let mut classes = ErrorClasses::empty();
        if flags & 0x2C != 0 {
            classes |= ErrorClasses::CONTROLLER;
        }
        if flags & 0x40 != 0 {
            classes |= ErrorClasses::LOST_ARBITRATION;
        }
        if flags & 0x80 != 0 {
            classes |= ErrorClasses::BUS_ERROR;
        }
        let state = if flags & 0x20 != 0 {
            Some(BusState::ErrorPassive)
        } else if flags & 0x04 != 0 {
            Some(BusState::ErrorWarning)
        } else {
            None
        };
        Self {
            classes,
            state,
            rx_overflow: flags & 0x0B != 0,
            counters: None,
        }
    }
}

/// What a CAN interface delivers: frames with their receive time, and what it reports about the
/// bus instead of dropping it.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg(feature = "std")]
pub enum CanEvent {
    /// A frame.
    Frame {
        /// The frame.
        frame: CanFrame,
        /// When it was received, if the interface says.
        timestamp: Option<Timestamp>,
    },
    /// An error frame or status report.
    Error {
        /// What it reports.
        report: CanErrorReport,
        /// When it was received, if the interface says.
        timestamp: Option<Timestamp>,
    },
    /// A line or datagram that is neither a frame nor a known report (line noise, a wrong
    /// serial speed); it was skipped.
    Garbage {
        /// Why it was not understood.
        why: &'static str,
    },
    /// The adapter refused a command or a frame (SLCAN BEL).
    Refused,
}

/// A CAN interface: send frames, receive frames with a timeout.
pub trait CanBus {
    /// Queues `frame` for transmission.
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError>;
    /// The next received frame, or `None` if none arrived within `timeout`.
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError>;
    /// The next received frame or report, with its receive time where the interface gives one;
    /// `None` if nothing arrived within `timeout`. The default wraps [`CanBus::recv`] (no
    /// timestamps, no reports); SocketCAN and SLCAN report more.
    #[cfg(feature = "std")]
    fn recv_event(&mut self, timeout: Duration) -> Result<Option<CanEvent>, BusError> {
        Ok(self.recv(timeout)?.map(|frame| CanEvent::Frame {
            frame,
            timestamp: None,
        }))
    }
}

impl<B: CanBus + ?Sized> CanBus for &mut B {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        (**self).send(frame)
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        (**self).recv(timeout)
    }
    #[cfg(feature = "std")]
    fn recv_event(&mut self, timeout: Duration) -> Result<Option<CanEvent>, BusError> {
        (**self).recv_event(timeout)
    }
}

//! The names an application driving a generated crate uses most, in one import:
//!
//! ```
//! use drivebus::prelude::*;
//! ```
//!
//! Values and errors are always here; each protocol's addressing, links and (with `std`)
//! blocking clients come with the feature that enables them.

pub use crate::error::{BusError, Error, ValueError};
pub use crate::link::Link;
pub use crate::parameter::{Readable, Writable};
pub use crate::units::*;

#[cfg(feature = "canopen")]
pub use crate::canopen::{can::in_process::InProcessBus, client::BlockingSdo};
pub use crate::canopen::{CanBus, CanFrame, CanOpenLink, NodeId};

#[cfg(feature = "modbus")]
pub use crate::modbus::client::{
    ModbusTcpClient, RtuOverTcpClient, SerialConfig, SerialRtuClient, TcpConfig,
};
#[cfg(feature = "modbus-core")]
pub use crate::modbus::rtu::{Parity, StopBits};
pub use crate::modbus::{ExceptionCode, ModbusLink, RegisterBus, UnitId};

#[cfg(feature = "rs232")]
pub use crate::rs232::client::{Rs232Client, Rs232Config};
pub use crate::rs232::{Rs232Link, StationId, TelegramBus};
